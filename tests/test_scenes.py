"""Multi-robot scenes: examples, third-party macros, collisions, fleets, and properties over random scenes."""

from __future__ import annotations

import ast
import subprocess
import sys

import numpy as np
import pinocchio as pin
import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lxml import etree

import xacrokit
from conftest import REPO, gen_robot, mesh_package_at
from xacrokit.check import check
from xacrokit.emit import urdf_differences
from xacrokit.errors import SpecErrors
from xacrokit.kinematics import origin_transform
from xacrokit.pipeline import expand_package
from xacrokit.render import render_package
from xacrokit.testing import valid_specs

SCENES = REPO / "examples" / "scenes"

THIRD_PARTY = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="acme_arm" params="prefix parent *origin length:=0.5">
    <joint name="${prefix}acme_mount" type="fixed">
      <parent link="${parent}"/><child link="${prefix}acme_base"/><xacro:insert_block name="origin"/>
    </joint>
    <link name="${prefix}acme_base">
      <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>
      <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    </link>
    <joint name="${prefix}acme_joint" type="revolute">
      <parent link="${prefix}acme_base"/><child link="${prefix}acme_link"/>
      <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
      <dynamics damping="0.1" friction="0"/>
    </joint>
    <link name="${prefix}acme_link">
      <visual><geometry><cylinder radius="0.02" length="${length}"/></geometry></visual>
      <inertial><mass value="0.5"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.001"/></inertial>
    </link>
  </xacro:macro>
</robot>
"""


def urdf_root(result) -> etree._Element:
    text = {f.path: f.content for f in result.files}[f"urdf/{result.scene.name}.urdf"]
    return etree.fromstring(text.encode())


@pytest.fixture(scope="module")
def cell(tmp_path_factory):
    return xacrokit.generate(SCENES / "bin_sorting_cell.yaml", tmp_path_factory.mktemp("cell") / "pkg")


def test_bin_sorting_cell_prefixes_every_name_and_mounts_as_specified(cell):
    scene, root = cell.scene, urdf_root(cell)
    links = [e.get("name") for e in root.findall("link")]
    joints = [e.get("name") for e in root.findall("joint")]
    assert sorted(links) == sorted(scene.link_names) and len(links) == len(set(links))
    assert sorted(joints) == sorted(scene.joint_names) and len(joints) == len(set(joints))
    by_name = {i.name: i for i in scene.instances}
    for instance in scene.instances:
        assert instance.links and all(n.startswith(instance.prefix) for n in (*instance.links, *instance.joints))
    mount = root.find("joint[@name='left_gripper_gripper_base_mount_joint']")
    assert mount.find("parent").get("link") == "left_tool0"
    assert by_name["arm"].parent == "table_top"
    mimic = root.find("joint[@name='left_gripper_right_finger_joint']/mimic")
    assert mimic.get("joint") == "left_gripper_left_finger_joint"  # the mimic reference is prefixed too
    control = {c.get("name"): [j.get("name") for j in c.findall("joint")] for c in root.findall("ros2_control")}
    assert control["left_ur5"][0] == "left_shoulder_pan_joint"
    assert control["left_gripper_parallel_gripper"] == ["left_gripper_left_finger_joint"]


def test_bin_sorting_cell_checks_clean_with_every_consumer():
    report = check(SCENES / "bin_sorting_cell.yaml")
    assert not report.findings, [str(f) for f in report.findings]
    assert report.consumers and all(c.status == "accepted" for c in report.consumers)


def test_scene_rviz_fixed_frame_is_the_unprefixed_world_link(cell):
    """A scene's names are fixed when it is generated (its launch file has no prefix argument), so the .rviz file's
    fixed frame, the scene's world link, is valid as written and rviz2 needs no -f."""
    files = {f.path: f.content for f in cell.files}
    launch = files["launch/display.launch.py"]
    declared = [
        node.args[0].value
        for node in ast.walk(ast.parse(launch))
        if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "DeclareLaunchArgument"
    ]
    assert "ros2_control" in declared and "prefix" not in declared
    root = urdf_root(cell)
    children = {j.find("child").get("link") for j in root.findall("joint")}
    (world,) = [e.get("name") for e in root.findall("link") if e.get("name") not in children]
    assert world == cell.scene.world
    rviz = yaml.safe_load(files[f"rviz/{cell.scene.name}.rviz"])
    assert rviz["Visualization Manager"]["Global Options"]["Fixed Frame"] == world


def test_per_instance_controller_configs_list_prefixed_joints(cell):
    config = yaml.safe_load({f.path: f.content for f in cell.files}["config/arm_controllers.yaml"])
    assert config["left_position_controller"]["ros__parameters"]["joints"][0] == "left_shoulder_pan_joint"
    assert "left_joint_state_broadcaster" in config["controller_manager"]["ros__parameters"]


def test_two_identical_arms_share_one_macro_and_materials(tmp_path):
    result = xacrokit.generate(SCENES / "two_arm_cell.yaml", tmp_path / "pkg")
    root = urdf_root(result)
    materials = [m.get("name") for m in root.findall("material")]
    assert len(materials) == len(set(materials))
    assert {"left_tool0", "right_tool0"} <= {e.get("name") for e in root.findall("link")}
    entry = (tmp_path / "pkg" / "urdf" / "two_arm_cell.urdf.xacro").read_text(encoding="utf-8")
    assert entry.count("ur5_macro.xacro") == 1
    assert not check(tmp_path / "pkg" / "urdf" / "two_arm_cell.urdf", consumers=[]).errors


class NoAliases(yaml.SafeDumper):
    """Specs reject YAML aliases; write shared values out in full."""

    def ignore_aliases(self, data):
        return True


def scene_file(folder, instances, name="s", extra=None):
    data = {"scene": name, "instances": instances, **(extra or {})}
    path = folder / f"{name}.yaml"
    path.write_text(yaml.dump(data, Dumper=NoAliases, sort_keys=False), encoding="utf-8")
    return path


def test_third_party_macro_twice_in_one_scene(tmp_path):
    (tmp_path / "acme.xacro").write_text(THIRD_PARTY, encoding="utf-8")
    macro = {"file": "acme.xacro", "macro": "acme_arm", "params": {"length": 0.3}}
    path = scene_file(
        tmp_path,
        {
            "one": {"xacro": dict(macro), "prefix": "a_", "parent": "world", "origin": {"xyz": [1, 0, 0]}},
            "two": {"xacro": dict(macro), "prefix": "b_", "parent": "one/acme_link"},
        },
    )
    result = xacrokit.generate(path, tmp_path / "pkg")
    root = urdf_root(result)
    assert {"a_acme_link", "b_acme_base"} <= {e.get("name") for e in root.findall("link")}
    assert root.find("joint[@name='b_acme_mount']/parent").get("link") == "a_acme_link"
    assert float(root.find("link[@name='a_acme_link']/visual/geometry/cylinder").get("length")) == 0.3
    by_name = {i.name: i for i in result.scene.instances}
    assert set(by_name["one"].links) == {"a_acme_base", "a_acme_link"}


def test_a_clash_names_both_instances_before_writing(tmp_path):
    (tmp_path / "acme.xacro").write_text(THIRD_PARTY, encoding="utf-8")
    macro = {"file": "acme.xacro", "macro": "acme_arm"}
    path = scene_file(
        tmp_path,
        {
            "one": {"xacro": dict(macro), "prefix": "x_", "parent": "world"},
            "two": {"xacro": dict(macro), "prefix": "x_", "parent": "world"},
        },
    )
    with pytest.raises(xacrokit.SpecErrors) as caught:
        xacrokit.generate(path, tmp_path / "pkg")
    (error,) = caught.value.errors
    assert "instances one and two would both have link x_acme_base" in error.message
    assert error.path == "$.instances.two" and error.line is not None
    assert not (tmp_path / "pkg").exists()


def test_a_clash_between_our_robots(tmp_path):
    arm = REPO / "examples" / "two_dof_arm.yaml"
    path = scene_file(
        tmp_path,
        {
            "a": {"spec": str(arm), "prefix": "r_", "parent": "world"},
            "b": {"spec": str(arm), "prefix": "r_", "parent": "world"},
        },
    )
    with pytest.raises(xacrokit.SpecErrors, match="instances a and b would both have link r_base_link"):
        xacrokit.generate(path, tmp_path / "pkg")


@pytest.mark.parametrize(
    ("instances", "path", "words"),
    [
        (
            {"a": {"spec": "ARM", "prefix": "a_", "parent": "b/base_link"}},
            "$.instances.a.parent",
            "instance 'b' is not",
        ),
        (
            {
                "a": {"spec": "ARM", "prefix": "a_", "parent": "world"},
                "b": {"spec": "ARM", "prefix": "b_", "parent": "a/nope"},
            },
            "$.instances.b.parent",
            "'nope' is not a link",
        ),
        (
            {
                "a": {"spec": "ARM", "prefix": "a_", "parent": "b/base_link"},
                "b": {"spec": "ARM", "prefix": "b_", "parent": "a/base_link"},
            },
            "$.instances.a.parent",
            "in a loop",
        ),
        ({"a": {"spec": "ARM", "prefix": "bad prefix", "parent": "world"}}, "$.instances.a.prefix", "not a valid name"),
        ({"a": {"spec": "missing.yaml", "prefix": "a_", "parent": "world"}}, "$.instances.a.spec", "no robot spec"),
        ({"a": {"spec": "ARM", "prefix": "a_", "parent": "moon"}}, "$.instances.a.parent", "must be 'world'"),
        ({"a": {"prefix": "a_", "parent": "world"}}, "$.instances.a", "exactly one of spec (a robot spec) or xacro"),
        (
            {"a": {"spec": "ARM", "xacro": {"file": "x.xacro", "macro": "m"}, "prefix": "a_", "parent": "world"}},
            "$.instances.a",
            "got both spec and xacro",
        ),
    ],
)
def test_scene_mistakes_are_located(tmp_path, instances, path, words):
    arm = str(REPO / "examples" / "two_dof_arm.yaml")
    for entry in instances.values():
        if entry.get("spec") == "ARM":
            entry["spec"] = arm
    with pytest.raises(xacrokit.SpecErrors) as caught:
        xacrokit.generate(scene_file(tmp_path, instances), tmp_path / "pkg")
    assert any(e.path == path and words in e.message for e in caught.value.errors), [
        str(e) for e in caught.value.errors
    ]


def test_errors_inside_an_instance_spec_point_into_that_spec(tmp_path):
    bad = tmp_path / "bad_robot.yaml"
    bad.write_text(
        (REPO / "examples" / "two_dof_arm.yaml").read_text(encoding="utf-8").replace("mass: 0.5", "mass: -1"),
        encoding="utf-8",
    )
    with pytest.raises(xacrokit.SpecErrors) as caught:
        xacrokit.generate(scene_file(tmp_path, {"a": {"spec": "bad_robot.yaml", "parent": "world"}}), tmp_path / "o")
    assert [e.file for e in caught.value.errors] == [str(bad)]


def test_fleet_of_ten_on_a_grid(tmp_path):
    diff_drive = REPO / "examples" / "diff_drive.yaml"
    result = gen_robot(
        "fleet", diff_drive, "--count", "10", "--grid", "2x5", "--spacing", "1.5", "-o", tmp_path / "fleet"
    )
    assert result.returncode == 0, result.stderr
    root = etree.parse(str(tmp_path / "fleet" / "urdf" / "diff_drive_fleet.urdf")).getroot()
    for index in range(10):
        mount = root.find(f"joint[@name='r{index}_base_footprint_mount_joint']")
        row, column = divmod(index, 5)
        assert [float(v) for v in mount.find("origin").get("xyz").split()] == [column * 1.5, row * 1.5, 0.0]
    assert len(root.findall("link")) == 1 + 10 * 8
    assert not check(tmp_path / "fleet" / "urdf" / "diff_drive_fleet.urdf", consumers=["check_urdf"]).errors
    bad = gen_robot("fleet", diff_drive, "--count", "10", "--grid", "2x4")
    assert bad.returncode == 2 and "has 8 places for 10 robots" in bad.stderr


# --------------------------------------------------------------------------------------------- random scenes
@st.composite
def random_scenes(draw):
    robots = [draw(valid_specs(max_links=3)) for _ in range(draw(st.integers(1, 2)))]
    for index, robot in enumerate(robots):
        robot["robot"] = f"robot_{index}"
    instances = {}
    for index in range(draw(st.integers(1, 3))):
        which = draw(st.integers(0, len(robots) - 1))
        parent = "world"
        if instances and draw(st.booleans()):
            other = draw(st.sampled_from(sorted(instances)))
            parent = f"{other}/{draw(st.sampled_from(sorted(robots[instances[other]['robot']]['links'])))}"
        origin = {"xyz": [draw(st.floats(-2, 2)) for _ in range(3)], "rpy": [draw(st.floats(-3, 3)) for _ in range(3)]}
        instances[f"i{index}"] = {"robot": which, "prefix": f"p{index}_", "parent": parent, "origin": origin}
    return robots, instances


@settings(max_examples=8, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(case=random_scenes(), seed=st.integers(0, 2**16))
def test_random_scenes_prefix_disjoint_fk_and_check(tmp_path_factory, case, seed):
    robots, instances = case
    folder = tmp_path_factory.mktemp("scene")
    for index, robot in enumerate(robots):
        (folder / f"robot_{index}.yaml").write_text(yaml.safe_dump(robot, sort_keys=False), encoding="utf-8")
    entries = {
        name: {"spec": f"robot_{i['robot']}.yaml", "prefix": i["prefix"], "parent": i["parent"], "origin": i["origin"]}
        for name, i in instances.items()
    }
    path = scene_file(folder, entries)
    result = xacrokit.generate(path, folder / "pkg")
    scene, root = result.scene, urdf_root(result)

    # every name of an instance carries its prefix; the scene's names are the disjoint union of the instances'
    all_links = [scene.world]
    for instance in scene.instances:
        names = [*instance.links, *instance.joints]
        assert all(n.startswith(instance.prefix) for n in names)
        all_links += instance.links
    assert sorted(e.get("name") for e in root.findall("link")) == sorted(all_links)
    assert len(all_links) == len(set(all_links))
    for element in (*root.findall("gazebo"), *root.findall("ros2_control/joint")):
        name = element.get("reference") or element.get("name")
        assert any(name.startswith(i.prefix) and name in (*i.links, *i.joints) for i in scene.instances), name

    # each instance's FK from the world is its mount pose composed with the single robot's own FK
    model = pin.buildModelFromXML(etree.tostring(root, encoding="unicode"))
    data = model.createData()
    rng = np.random.default_rng(seed)
    q = pin.neutral(model)
    values = {}
    for j in range(1, model.njoints):
        if model.nqs[j] == 1:
            q[model.idx_qs[j]] = values[model.names[j]] = float(rng.uniform(-1, 1))
    pin.framesForwardKinematics(model, data, q)
    for instance in scene.instances:
        robot = instance.robot
        alone = pin.buildModelFromXML(expand_package(robot, render_package(robot)).content)
        alone_data = alone.createData()
        q_alone = pin.neutral(alone)
        for j in range(1, alone.njoints):
            if alone.nqs[j] == 1:
                q_alone[alone.idx_qs[j]] = values[instance.prefix + alone.names[j]]
        pin.framesForwardKinematics(alone, alone_data, q_alone)
        mount = data.oMf[model.getFrameId(instance.parent)].homogeneous @ origin_transform(instance.origin)
        root_alone = alone_data.oMf[alone.getFrameId(robot.root)].homogeneous
        for link in robot.link_names:
            want = mount @ np.linalg.inv(root_alone) @ alone_data.oMf[alone.getFrameId(link)].homogeneous
            got = data.oMf[model.getFrameId(instance.prefix + link)].homogeneous
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-9)

    report = check(path, consumers=["check_urdf", "pinocchio"], package_paths={"some_pkg": mesh_package_at(folder)})
    assert not report.errors, [str(f) for f in report.errors]
    assert all(c.status == "accepted" for c in report.consumers)


@pytest.mark.parametrize(
    "scene", sorted(p for p in SCENES.glob("*.yaml") if "scene:" in p.read_text("utf-8")), ids=lambda p: p.stem
)
def test_every_scene_example_generates_and_checks_clean(tmp_path, scene):
    result = xacrokit.generate(scene, tmp_path / "pkg")
    assert result.scene is not None and len(result.scene.instances) >= 2
    report = check(tmp_path / "pkg" / "urdf" / f"{result.scene.name}.urdf")
    assert not report.findings, [str(f) for f in report.findings]
    assert report.consumers and all(c.status == "accepted" for c in report.consumers)
    again = xacrokit.generate(scene, tmp_path / "pkg")
    assert {a.action for a in again.actions} == {"identical"}


def test_fleet_command_and_the_fleet_scene_example_agree(tmp_path):
    diff_drive = REPO / "examples" / "diff_drive.yaml"
    assert (
        gen_robot(
            "fleet", diff_drive, "--count", "10", "--grid", "2x5", "--spacing", "1.5", "-o", tmp_path / "cli"
        ).returncode
        == 0
    )
    xacrokit.generate(SCENES / "diff_drive_fleet.yaml", tmp_path / "file")
    urdf = "urdf/diff_drive_fleet.urdf"
    assert (tmp_path / "cli" / urdf).read_text(encoding="utf-8") == (tmp_path / "file" / urdf).read_text(
        encoding="utf-8"
    )


@pytest.mark.parametrize("mode", ["copy", "find"])
def test_fleets_take_the_macro_mode_and_describe_the_same_robots(tmp_path, mode):
    diff_drive = REPO / "examples" / "diff_drive.yaml"
    for name, extra in (("default", ()), (mode, ("--macros", mode, "--via-xacro"))):
        result = gen_robot("fleet", diff_drive, "--count", "3", "-o", tmp_path / name, *extra)
        assert result.returncode == 0, result.stderr
    urdf = "urdf/diff_drive_fleet.urdf"
    texts = [(tmp_path / name / urdf).read_text(encoding="utf-8") for name in ("default", mode)]
    assert urdf_differences(*texts, rel=0.0) == []
    macro = (tmp_path / mode / "robots" / "diff_drive_description" / "urdf" / "diff_drive_macro.xacro").read_text(
        encoding="utf-8"
    )
    assert "<xacro:wheel" in macro
    assert (tmp_path / mode / "robots" / "diff_drive_description" / "urdf" / "xacrokit").is_dir() == (mode == "copy")
    depends = "<exec_depend>xacrokit</exec_depend>" in (tmp_path / mode / "package.xml").read_text(encoding="utf-8")
    assert depends == (mode == "find")


def run_with_tty_stderr(*args) -> tuple[int, str, str]:
    """Run gen-robot with stderr on a pseudo-terminal; return (exit code, stdout, what the terminal received)."""
    import os
    import pty

    leader, follower = pty.openpty()
    process = subprocess.Popen(
        [sys.executable, "-m", "xacrokit.cli", *map(str, args)], stdout=subprocess.PIPE, stderr=follower, text=True
    )
    os.close(follower)
    received = b""
    while True:
        try:
            chunk = os.read(leader, 4096)
        except OSError:  # the terminal closed: the command has ended
            break
        if not chunk:
            break
        received += chunk
    stdout = process.stdout.read()
    code = process.wait(timeout=300)
    os.close(leader)
    return code, stdout, received.decode("utf-8", errors="replace")


def test_progress_shows_on_a_terminal_only(tmp_path):
    diff_drive = REPO / "examples" / "diff_drive.yaml"
    code, stdout, terminal = run_with_tty_stderr("fleet", diff_drive, "--count", "4", "-o", tmp_path / "fleet")
    assert code == 0 and "4 robots r0_ .. r3_" in stdout
    for step in (
        "checking 4 copies of diff_drive.yaml",
        "rendering 4 instances of 1 robot(s)",
        "emitting the URDF",
        "writing",
    ):
        assert step in terminal, terminal
    assert terminal.endswith("\r\x1b[K")  # the line is cleared when the work is done
    code, stdout, terminal = run_with_tty_stderr("check", diff_drive, "--consumers", "check_urdf")
    assert code == 0 and "running check_urdf" in terminal and "OK: 0 error(s)" in stdout
    quiet = gen_robot("fleet", diff_drive, "--count", "2", "-o", tmp_path / "quiet")
    assert quiet.returncode == 0 and quiet.stderr == ""  # not a terminal: nothing on stderr


def test_a_scene_passes_on_its_robots_warnings(tmp_path):
    robot = tmp_path / "heavy.yaml"
    robot.write_text(
        "robot: heavy\nlinks:\n  base_link: {shape: {box: {size: [0.1, 0.1, 0.1]}}, mass: 500}\n", encoding="utf-8"
    )
    scene = tmp_path / "cell.yaml"
    scene.write_text(
        "scene: cell\ninstances:\n  a: {spec: heavy.yaml, prefix: a_, parent: world, origin: {rpy: [0, 0, 45]}}\n"
        "  b: {spec: heavy.yaml, prefix: b_, parent: world}\n",
        encoding="utf-8",
    )
    result = xacrokit.generate(scene, tmp_path / "out")
    assert [(w.file, w.path) for w in result.warnings] == [
        (str(scene), "$.instances.a.origin.rpy[2]"),  # 45 rad: degrees without their unit
        (str(robot), "$.links.base_link.mass"),  # 500 kg in a litre: once, however many instances use it
    ]
    notes = [f for f in check(scene, consumers=[]).findings if f.rule == "V001"]
    assert sorted(f.element for f in notes) == ["$.instances.a.origin.rpy[2]", "$.links.base_link.mass"]
    fleet = gen_robot("fleet", robot, "--count", 2, "-o", tmp_path / "fleet")
    assert fleet.returncode == 0 and fleet.stderr.count("gen-robot: warning:") == 1, fleet.stderr


def test_a_missing_robot_spec_is_reported_once_where_the_scene_names_it(tmp_path):
    scene = tmp_path / "cell.yaml"
    scene.write_text("scene: cell\ninstances:\n  a: {spec: griper.yaml, prefix: a_, parent: world}\n")
    with pytest.raises(SpecErrors) as caught:
        xacrokit.generate(scene, tmp_path / "out")
    (error,) = caught.value.errors
    assert (error.file, error.path, error.line) == (str(scene), "$.instances.a.spec", 3)
    assert "no robot spec at" in error.message and "No such file or directory" in error.message


def test_a_scene_refuses_gazebo_by_name(tmp_path):
    xacrokit.generate(SCENES / "two_arm_cell.yaml", tmp_path / "pkg")
    result = gen_robot("expand", tmp_path / "pkg" / "urdf" / "two_arm_cell.urdf.xacro", "ros2_control:=gazebo")
    assert result.returncode == 2
    assert "ros2_control must be mock or none in a scene, got 'gazebo'" in result.stderr


def test_a_fleet_readme_says_how_to_make_it_again(tmp_path):
    spec = REPO / "examples" / "diff_drive.yaml"
    result = gen_robot("fleet", spec, "--count", 3, "--grid", "1x3", "--spacing", "150 cm", "-o", tmp_path / "f")
    assert result.returncode == 0, result.stderr
    readme = (tmp_path / "f" / "README.md").read_text(encoding="utf-8")
    assert "run `gen-robot fleet diff_drive.yaml --count 3 --grid 1x3 --spacing 1.5` again" in readme


THIRD_PARTY_FAULTS = {
    "makes_world": '<link name="world"/><link name="${prefix}base"/>'
    '<joint name="${prefix}j" type="fixed"><parent link="world"/><child link="${prefix}base"/></joint>',
    "ignores_prefix": '<link name="plate"/>'
    '<joint name="plate_joint" type="fixed"><parent link="${parent}"/><child link="plate"/></joint>',
    "ignores_parent": '<link name="${prefix}base"/>',
    "prefix_inside": '<link name="${prefix}base"/>'  # valid: the prefix is inside the joint's name
    '<joint name="${parent}_to_${prefix}base" type="fixed"><parent link="${parent}"/><child link="${prefix}base"/>'
    "</joint>",
}


@pytest.mark.parametrize(
    ("macro", "words"),
    [
        ("makes_world", "it makes a link 'world' itself"),
        ("ignores_prefix", "its names plate, plate_joint do not hold the prefix 'p_'"),
        ("ignores_parent", "no joint of it hangs from the link it is mounted on, 'world'"),
    ],
)
def test_a_third_party_macro_that_breaks_the_scene_is_refused_before_writing(tmp_path, macro, words):
    (tmp_path / "parts.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        + "".join(
            f'<xacro:macro name="{name}" params="prefix parent *origin">{body}</xacro:macro>'
            for name, body in THIRD_PARTY_FAULTS.items()
        )
        + "</robot>",
        encoding="utf-8",
    )
    scene = tmp_path / "cell.yaml"
    scene.write_text(
        f"scene: cell\ninstances:\n  p: {{xacro: {{file: parts.xacro, macro: {macro}}}, prefix: p_, parent: world}}\n",
        encoding="utf-8",
    )
    with pytest.raises(SpecErrors) as caught:
        xacrokit.generate(scene, tmp_path / "out")
    (error,) = caught.value.errors
    assert error.path == "$.instances.p.xacro" and words in error.message, error.message
    assert not (tmp_path / "out").exists()


def test_a_name_taken_by_the_world_link_is_said_so(tmp_path):
    robot = tmp_path / "r.yaml"
    robot.write_text("robot: r\nlinks:\n  world: {}\n", encoding="utf-8")
    scene = tmp_path / "cell.yaml"
    scene.write_text("scene: cell\ninstances:\n  a: {spec: r.yaml, prefix: '', parent: world}\n", encoding="utf-8")
    with pytest.raises(SpecErrors) as caught:
        xacrokit.generate(scene, tmp_path / "out")
    messages = [e.message for e in caught.value.errors]
    assert any("instance a would have link world, the scene's world link" in m for m in messages), messages


def test_a_macro_with_other_parameter_names_gets_a_hint(tmp_path):
    (tmp_path / "ur.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="arm" params="tf_prefix parent *origin">'
        '<link name="${tf_prefix}base"/><joint name="${tf_prefix}mount" type="fixed"><parent link="${parent}"/>'
        '<child link="${tf_prefix}base"/></joint></xacro:macro></robot>',
        encoding="utf-8",
    )
    scene = tmp_path / "cell.yaml"
    scene.write_text("scene: cell\ninstances:\n  a: {xacro: {file: ur.xacro, macro: arm}, prefix: a_, parent: world}\n")
    with pytest.raises(SpecErrors) as caught:
        xacrokit.generate(scene, tmp_path / "out")
    assert "set prefix_param and parent_param" in caught.value.errors[0].message
    scene.write_text(
        "scene: cell\ninstances:\n"
        "  a: {xacro: {file: ur.xacro, macro: arm, prefix_param: tf_prefix}, prefix: a_, parent: world}\n"
    )
    result = xacrokit.generate(scene, tmp_path / "out")  # with the hint followed
    assert {"world", "a_base"} == {e.get("name") for e in urdf_root(result).iter("link")}


def test_xacro_warnings_about_a_third_party_macro_come_once(tmp_path, capfd):
    (tmp_path / "lidar.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="lidar" params="prefix parent *origin '
        'range:=10"><link name="${prefix}lidar"/><joint name="${prefix}lidar_joint" type="fixed">'
        '<parent link="${parent}"/><child link="${prefix}lidar"/></joint></xacro:macro></robot>',
        encoding="utf-8",
    )
    scene = tmp_path / "cell.yaml"
    scene.write_text(
        "scene: cell\ninstances:\n  l: {xacro: {file: lidar.xacro, macro: lidar}, prefix: l_, parent: world}\n"
    )
    xacrokit.generate(scene, tmp_path / "out")
    warned = capfd.readouterr().err.count("redefining global symbol: range")
    assert warned == 1  # from the real expansion; the probe that learns the names keeps quiet


def test_a_third_party_macro_may_put_its_prefix_inside_a_name_and_a_misspelt_param_is_named(tmp_path):
    (tmp_path / "parts.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="prefix_inside" params="prefix parent '
        '*origin">' + THIRD_PARTY_FAULTS["prefix_inside"] + "</xacro:macro></robot>",
        encoding="utf-8",
    )
    scene = tmp_path / "cell.yaml"
    scene.write_text(
        "scene: cell\ninstances:\n  p: {xacro: {file: parts.xacro, macro: prefix_inside}, prefix: p_, parent: world}\n"
    )
    assert {"world_to_p_base"} <= {e.get("name") for e in urdf_root(xacrokit.generate(scene, tmp_path / "a")).iter()}
    scene.write_text(
        "scene: cell\ninstances:\n"
        "  p: {xacro: {file: parts.xacro, macro: prefix_inside, params: {lenght: 0.5}}, prefix: p_, parent: world}\n"
    )
    with pytest.raises(SpecErrors) as caught:
        xacrokit.generate(scene, tmp_path / "b")
    message = caught.value.errors[0].message
    assert "the macro has no parameter 'lenght'" in message and "prefix_param" not in message
