"""G005 and G006 (issue 30, items 3 and 4) beyond their corpus pairs: the triangle count is the mesh file's own, the
ground is found by the default pose, friction on any link of a rigid body counts, an arm on its base is not asked for
friction, and a file not written for Gazebo gets a note, not a warning."""

from __future__ import annotations

import trimesh
from check_helpers import CORPUS

from xacrokit.check import check


def _findings(tmp_path, text: str, rule: str) -> list[tuple[str, str]]:
    path = tmp_path / "robot.urdf"
    path.write_text(text, encoding="utf-8")
    return [(f.element, f.severity) for f in check(path, consumers=[]).findings if f.rule == rule]


def test_the_triangle_count_is_the_files(tmp_path):
    """An icosphere of 5,120 triangles (written here by trimesh) as visual and collision: the message says 5,120;
    scaled differently in the collision, it is another geometry and passes."""
    ball = trimesh.creation.icosphere(subdivisions=4, radius=0.05)
    ball.export(tmp_path / "ball.stl")
    text = (CORPUS / "G005_fail.urdf").read_text(encoding="utf-8").replace("meshes/ball_detailed.stl", "ball.stl")
    path = tmp_path / "robot.urdf"
    path.write_text(text, encoding="utf-8")
    (finding,) = [f for f in check(path, consumers=[]).findings if f.rule == "G005"]
    assert f"({len(ball.faces):,} triangles)" in finding.message and len(ball.faces) == 5120
    scaled = text.replace(
        '<collision><geometry><mesh filename="ball.stl"/>',
        '<collision><geometry><mesh filename="ball.stl" scale="0.9 0.9 0.9"/>',
    )
    assert _findings(tmp_path, scaled, "G005") == []


def test_the_ground_is_found_in_the_default_pose(tmp_path):
    """The corpus wheel lifted above the base's bottom is no longer lowest: the base touches the ground, and a robot
    whose lowest link is its base (an arm on its base) is not asked for friction."""
    text = (CORPUS / "G006_fail.urdf").read_text(encoding="utf-8")
    assert _findings(tmp_path, text, "G006") == [("wheel", "warning")]
    lifted = text.replace('<origin xyz="0 0 -0.05"/><axis xyz="0 1 0"/>', '<origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>')
    assert _findings(tmp_path, lifted, "G006") == []


def test_friction_on_a_link_fixed_to_the_contact_counts(tmp_path):
    """Gazebo lumps links joined by fixed joints: friction given to a foot frame fixed to the wheel counts for it."""
    text = (CORPUS / "G006_fail.urdf").read_text(encoding="utf-8")
    foot = (
        '<link name="tread"/><joint name="tread_joint" type="fixed"><parent link="wheel"/><child link="tread"/></joint>'
        '<gazebo reference="tread"><mu1>0.9</mu1><mu2>0.9</mu2></gazebo>\n</robot>'
    )
    assert _findings(tmp_path, text.replace("</robot>", foot), "G006") == []


def test_a_file_without_gazebo_blocks_gets_a_note(tmp_path):
    text = (CORPUS / "G006_fail.urdf").read_text(encoding="utf-8")
    bare = text.replace('<gazebo reference="base_link"><material>Gazebo/Grey</material></gazebo>', "")
    assert _findings(tmp_path, bare, "G006") == [("wheel", "info")]
    fixed = '<link name="world"/><joint name="fix" type="fixed"><parent link="world"/><child link="base_link"/></joint>'
    world = text.replace('<link name="base_link">', fixed + '\n  <link name="base_link">')
    assert _findings(tmp_path, world, "G006") == []  # (fixed to the world: nothing rolls)


def test_a_base_fixed_to_a_world_root_needs_no_mass_and_equal_limits_say_the_ways_out(tmp_path):
    """I007 (issue 30, item 6): a KUKA-style file fixes base_link to a geometry-less world root: its massless base is
    a fixed base, no warning; the same base as the root is warned. J013 names real limits, continuous and fixed."""
    text = (CORPUS / "I007_fail.urdf").read_text(encoding="utf-8")
    assert _findings(tmp_path, text, "I007") == [("base_link", "warning")]
    fixed = '<link name="world"/><joint name="world_joint" type="fixed"><parent link="world"/><child link="base_link"/>'
    kuka = text.replace('<link name="base_link">', fixed + '</joint>\n  <link name="base_link">')
    assert _findings(tmp_path, kuka, "I007") == []
    path = tmp_path / "robot.urdf"
    path.write_text((CORPUS / "J013_fail.urdf").read_text(encoding="utf-8"), encoding="utf-8")
    (finding,) = [f for f in check(path, consumers=[]).findings if f.rule == "J013"]
    assert all(words in finding.message for words in ("real limits", "continuous", "fixed if it never moves"))
