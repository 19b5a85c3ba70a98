"""The example scenes: every one generates and checks clean; the bin-sorting cell prefixes and mounts as specified."""

from __future__ import annotations

import ast

import pytest
import yaml
from scene_helpers import SCENES, urdf_root

import xacrokit
from conftest import SCENE_EXAMPLES, gen_robot
from xacrokit.check import check
from xacrokit.model import Scene


@pytest.fixture(scope="module")
def cell(tmp_path_factory):
    return xacrokit.generate(SCENES / "bin_sorting_cell.yaml", tmp_path_factory.mktemp("cell") / "pkg")


def test_bin_sorting_cell_prefixes_every_name_and_mounts_as_specified(cell):
    scene, root = cell.model, urdf_root(cell)
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
    # the UR10e mounted as UR's macro mounts it (ur_robot with tf_prefix left_): base_joint to left_base_link, and
    # shoulder_pan_joint straight on base_link_inertia (issue 42)
    arm_mount = root.find("joint[@name='left_base_joint']")
    assert (arm_mount.find("parent").get("link"), arm_mount.find("child").get("link")) == (
        "table_top",
        "left_base_link",
    )
    assert root.find("joint[@name='left_shoulder_pan_joint']/parent").get("link") == "left_base_link_inertia"
    mimic = root.find("joint[@name='left_gripper_right_finger_joint']/mimic")
    assert mimic.get("joint") == "left_gripper_left_finger_joint"  # the mimic reference is prefixed too
    control = {c.get("name"): [j.get("name") for j in c.findall("joint")] for c in root.findall("ros2_control")}
    assert control["left_ur10e"][0] == "left_shoulder_pan_joint"
    # the mimic finger listed too, with state interfaces only: gz_ros2_control holds it to its leader so (issue 32)
    assert control["left_gripper_parallel_gripper"] == [
        "left_gripper_left_finger_joint",
        "left_gripper_right_finger_joint",
    ]
    finger = root.find("ros2_control/joint[@name='left_gripper_right_finger_joint']")
    assert finger.find("command_interface") is None and finger.find("state_interface[@name='position']") is not None


def test_bin_sorting_cell_checks_clean_with_every_consumer():
    report = check(SCENES / "bin_sorting_cell.yaml")
    said = [f for f in report.findings if f.rule != "G008"]  # (G008: a note naming its pairs at home, Default)
    assert not said, [str(f) for f in said]
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
    assert world == cell.model.world
    rviz = yaml.safe_load(files[f"rviz/{cell.name}.rviz"])
    assert rviz["Visualization Manager"]["Global Options"]["Fixed Frame"] == world


def test_per_instance_controller_configs_list_prefixed_joints(cell):
    config = yaml.safe_load({f.path: f.content for f in cell.files}["config/arm_controllers.yaml"])
    assert config["left_position_controller"]["ros__parameters"]["joints"][0] == "left_shoulder_pan_joint"
    assert "left_joint_state_broadcaster" in config["controller_manager"]["ros__parameters"]


@pytest.mark.parametrize("example", SCENE_EXAMPLES, ids=lambda p: p.stem)
def test_a_scene_runs_one_joint_state_broadcaster(example, tmp_path):
    """Each broadcaster without `joints` publishes every joint of the controller manager: one per instance would put
    each message on /joint_states once per robot (issue 32)."""
    import ast

    result = xacrokit.generate(example, tmp_path / "pkg")
    files = {f.path: f.content for f in result.files}
    merged = yaml.safe_load(files[f"config/{result.model.name}_controllers.yaml"])
    kinds = merged["controller_manager"]["ros__parameters"]
    broadcasters = [n for n, v in kinds.items() if isinstance(v, dict) and "JointStateBroadcaster" in v["type"]]
    assert broadcasters == ["joint_state_broadcaster"]
    launch = ast.parse(files["launch/gazebo.launch.py"])
    spawned = [
        e.value
        for node in ast.walk(launch)
        if isinstance(node, ast.List)
        for e in node.elts
        if isinstance(e, ast.Constant) and isinstance(e.value, str) and e.value.endswith("broadcaster")
    ]
    assert spawned == ["joint_state_broadcaster"]


def test_two_identical_arms_share_one_macro_and_materials(tmp_path):
    result = xacrokit.generate(SCENES / "two_arm_cell.yaml", tmp_path / "pkg")
    root = urdf_root(result)
    materials = [m.get("name") for m in root.findall("material")]
    assert len(materials) == len(set(materials))
    assert {"left_tool0", "right_tool0"} <= {e.get("name") for e in root.findall("link")}
    entry = (tmp_path / "pkg" / "urdf" / "two_arm_cell.urdf.xacro").read_text(encoding="utf-8")
    assert entry.count("ur5_macro.xacro") == 1
    assert not check(tmp_path / "pkg" / "urdf" / "two_arm_cell.urdf", consumers=[]).errors


@pytest.mark.parametrize("scene", SCENE_EXAMPLES, ids=lambda p: p.stem)
def test_every_scene_example_generates_and_checks_clean(tmp_path, scene):
    result = xacrokit.generate(scene, tmp_path / "pkg")
    assert isinstance(result.model, Scene) and len(result.model.instances) >= 2
    report = check(tmp_path / "pkg" / "urdf" / f"{result.name}.urdf")
    said = [f for f in report.findings if f.rule != "G008"]  # (G008: a note on what the package's SRDF disables)
    assert not said, [str(f) for f in said]
    assert report.consumers and all(c.status == "accepted" for c in report.consumers)
    again = xacrokit.generate(scene, tmp_path / "pkg")
    assert {a.action for a in again.actions} == {"identical"}


def test_a_scene_takes_gazebo_and_refuses_other_hardware_by_name(tmp_path):
    xacrokit.generate(SCENES / "two_arm_cell.yaml", tmp_path / "pkg")
    entry = tmp_path / "pkg" / "urdf" / "two_arm_cell.urdf.xacro"
    result = gen_robot("expand", entry, "ros2_control:=gz")
    assert result.returncode == 2
    assert "ros2_control must be mock, gazebo or none, got 'gz'" in result.stderr
    result = gen_robot("expand", entry, "ros2_control:=gazebo")  # (its package found beside it: $(find ...))
    assert result.returncode == 0, result.stderr
    assert result.stdout.count("gz_ros2_control::GazeboSimROS2ControlPlugin") == 1  # (one plugin for every robot)
