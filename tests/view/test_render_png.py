"""gen-robot render: a PNG of a robot without OpenGL. Every example and scene draws (and is the picture docs/view.md
shows, within a rendering tolerance), the same input gives the same bytes, moving a joint changes the picture, and a
missing mesh or an unknown joint is a clear error, never a picture with a hole."""

from __future__ import annotations

import io

import matplotlib.image
import numpy as np
import pytest

from conftest import REPO, ROBOT_EXAMPLES, SCENE_EXAMPLES, gen_robot
from xacrokit.errors import XacrokitError
from xacrokit.view.picture import render

UR5 = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"


def pixels(png: bytes) -> np.ndarray:
    return matplotlib.image.imread(io.BytesIO(png), format="png")


@pytest.mark.parametrize("example", [*ROBOT_EXAMPLES, *SCENE_EXAMPLES], ids=lambda p: p.stem)
def test_every_example_draws_as_docs_show_it(example):
    made = pixels(render(example, size=(480, 360)))
    shown = matplotlib.image.imread(REPO / "docs" / "images" / "examples" / f"{example.stem}.png")
    assert made.shape == shown.shape == (360, 480, 4)
    assert np.std(made[..., :3]) > 0.05  # (drawn, not blank)
    assert np.abs(made - shown).mean() < 0.01, (
        "regenerate: gen-robot render EXAMPLE -o docs/images/examples/NAME.png --size 480x360"
    )


def test_docs_view_shows_every_examples_picture():
    shown = (REPO / "docs" / "view.md").read_text(encoding="utf-8")
    missing = [p.stem for p in (*ROBOT_EXAMPLES, *SCENE_EXAMPLES) if f"(images/examples/{p.stem}.png)" not in shown]
    assert not missing, f"add to docs/view.md's table: {missing}"


def test_the_same_input_gives_the_same_bytes_and_a_joint_moves_the_picture():
    first, again = render(UR5), render(UR5)
    assert first == again
    moved = render(UR5, joints={"shoulder_lift_joint": -1.0, "elbow_joint": 1.0})
    assert np.abs(pixels(moved) - pixels(first)).mean() > 0.005


def test_a_missing_mesh_or_an_unknown_joint_is_an_error(tmp_path):
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        '<robot name="r"><link name="a"><visual><geometry><mesh filename="meshes/gone.stl"/></geometry></visual>'
        "</link></robot>",
        encoding="utf-8",
    )
    with pytest.raises(XacrokitError, match="'meshes/gone.stl' is not there"):
        render(urdf)
    result = gen_robot("render", UR5, "-o", tmp_path / "x.png", "--joint", "elbo_joint=1")
    assert result.returncode == 2 and "no moving joint 'elbo_joint'" in result.stderr
    assert not (tmp_path / "x.png").exists()
    bad = gen_robot("render", UR5, "-o", tmp_path / "x.png", "--size", "big")
    assert bad.returncode == 2 and "WIDTHxHEIGHT" in bad.stderr


def test_the_command_line_writes_the_png(tmp_path):
    out = tmp_path / "ur5.png"
    result = gen_robot("render", UR5, "-o", out, "--joint", "elbow_joint=90 deg", "--size", "320x240")
    assert result.returncode == 0, result.stderr
    assert matplotlib.image.imread(out).shape == (240, 320, 4)


@pytest.mark.parametrize("example", ["humanoid_upper_body", "rover"])
def test_the_placements_are_trimeshs_composed_once(example):
    """world_transforms (one walk down the scene graph) places every node where trimesh's own graph.get does (1e-12),
    at a joint configuration that is not zero; it replaced graph.get, cubic in a chain's length (issue 28)."""
    import yourdfpy

    from xacrokit.reader.read_robot import read_robot
    from xacrokit.view.picture import world_transforms

    read = read_robot(REPO / "examples" / "robots" / f"{example}.yaml")
    with read.mesh_packages() as packages:
        from xacrokit.shared.ros_packages import mesh_file

        robot = yourdfpy.URDF.load(
            io.StringIO(read.text),
            filename_handler=lambda fname: str(mesh_file(fname, REPO, packages)),
            build_scene_graph=True,
        )
        robot.update_cfg({name: 0.3 + 0.1 * k for k, name in enumerate(robot.actuated_joint_names)})
    placed = world_transforms(robot.scene.graph)
    nodes = [n for n in robot.scene.graph.nodes if n != robot.scene.graph.base_frame]
    assert len(nodes) > 10
    for node in nodes:
        assert np.abs(placed[node] - robot.scene.graph.get(node)[0]).max() < 1e-12, node


CHAIN = 600  # links: placing them as trimesh's graph.get did would take 40 minutes or more (see below)


def test_a_long_chain_draws():
    """A 2,000-link chain took hours in trimesh's graph.get (a sweep of hostile inputs, issue 28): the placement of
    each node multiplied its whole path with numpy's multi_dot, at least cubic in the path's length (all the nodes of
    a 100-link chain placed so: 6 s, of a 200-link one: 92 s, on a loaded machine). 600 links would take it 40 minutes
    or more, beyond any test run: the chain proves the placement composed once as 2,000 links did. What 2,000 links
    cost besides (about 9 of their 10 s) is yourdfpy's scene build, quadratic in the links, which MAX_LINKS bounds
    (the test below)."""
    box = '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
    links = "".join(f'<link name="l{k}">{box}</link>' for k in range(CHAIN))
    joints = "".join(
        f'<joint name="j{k}" type="revolute"><parent link="l{k - 1}"/><child link="l{k}"/><origin xyz="0 0 0.1"/>'
        '<axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        for k in range(1, CHAIN)
    )
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as folder:
        urdf = Path(folder, "chain.urdf")
        urdf.write_text(f'<robot name="c">{links}{joints}</robot>', encoding="utf-8")
        assert np.std(pixels(render(urdf, size=(64, 48)))[..., :3]) > 0.01


def test_a_robot_of_more_links_than_render_draws_is_refused_with_the_bound(tmp_path, monkeypatch):
    """yourdfpy builds its scene in time that grows with the square of the links (a 20,000-link chain ran past 120 s,
    issue 28): render draws at most MAX_LINKS and says so (the bound lowered here to keep the test small)."""
    import xacrokit.view.picture as picture

    monkeypatch.setattr(picture, "MAX_LINKS", 3)
    urdf = tmp_path / "four.urdf"
    links = "".join(f'<link name="l{k}"/>' for k in range(4))
    joints = "".join(
        f'<joint name="j{k}" type="fixed"><parent link="l{k - 1}"/><child link="l{k}"/></joint>' for k in range(1, 4)
    )
    urdf.write_text(f'<robot name="c">{links}{joints}</robot>', encoding="utf-8")
    with pytest.raises(XacrokitError, match="the robot has 4 links; render draws at most 3"):
        render(urdf, size=(64, 48))
