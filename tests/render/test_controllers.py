"""config/NAME_controllers.yaml: a diff_drive_controller for wheels that make a differential drive, forward command
controllers for the other controlled joints."""

from __future__ import annotations

import copy

import pytest
import yaml

import xacrokit
from conftest import REPO
from xacrokit.pipeline import build_robot
from xacrokit.render import controllers, render_package, render_scene
from xacrokit.scene import fleet_scene

DIFF_DRIVE = REPO / "examples" / "robots" / "diff_drive.yaml"


def config_of(files, path: str) -> dict:
    return yaml.safe_load({f.path: f.content for f in files}[path])


def test_a_two_wheel_base_gets_a_diff_drive_controller_with_its_geometry():
    robot = build_robot(DIFF_DRIVE)
    config = config_of(render_package(robot), "config/diff_drive_controllers.yaml")
    manager = config["controller_manager"]["ros__parameters"]
    assert manager["diff_drive_controller"]["type"] == "diff_drive_controller/DiffDriveController"
    assert "velocity_controller" not in manager and "velocity_controller" not in config  # the wheels are the drive's
    drive = config["diff_drive_controller"]["ros__parameters"]
    left, right = (next(w for w in robot.wheels if w.name == n) for n in ("left_wheel", "right_wheel"))
    assert drive["left_wheel_names"] == ["left_wheel_joint"] and drive["right_wheel_names"] == ["right_wheel_joint"]
    assert drive["wheel_separation"] == left.origin.xyz[1] - right.origin.xyz[1] == pytest.approx(0.36)
    assert drive["wheel_radius"] == left.radius == 0.065
    assert (drive["base_frame_id"], drive["odom_frame_id"], drive["enable_odom_tf"]) == ("base_footprint", "odom", True)


def test_fleet_drives_carry_prefixes_and_leave_the_transform_to_the_scene(tmp_path):
    scene = fleet_scene(DIFF_DRIVE, 2)
    config = config_of(render_scene(scene), "config/r1_controllers.yaml")
    assert "r1_diff_drive_controller" in config["controller_manager"]["ros__parameters"]
    drive = config["r1_diff_drive_controller"]["ros__parameters"]
    assert drive["left_wheel_names"] == ["r1_left_wheel_joint"] and drive["base_frame_id"] == "r1_base_footprint"
    assert drive["odom_frame_id"] == "r1_odom" and drive["enable_odom_tf"] is False  # the URDF fixes r1_base_footprint


@pytest.mark.parametrize(
    ("change", "why"),
    [
        (lambda w: w["left_wheel"].update(axis="x"), "an axle not along y"),
        (lambda w: w["left_wheel"].update(radius="70 mm"), "wheels of two radii"),
        (lambda w: w["right_wheel"]["origin"]["xyz"].__setitem__(1, 0.2), "both wheels on the left"),
        (lambda w: w["left_wheel"]["origin"].update(rpy=[0, 0, 0.1]), "a turned axle"),
    ],
)
def test_wheels_that_are_no_differential_drive_keep_a_velocity_controller(tmp_path, change, why):
    data = yaml.safe_load(DIFF_DRIVE.read_text(encoding="utf-8"))
    wheels = copy.deepcopy(data["wheels"])
    change(wheels)
    data["wheels"] = wheels
    spec = tmp_path / "base.yaml"
    spec.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
    robot = build_robot(spec)
    assert controllers(robot)["drive"] is None, why
    config = config_of(render_package(robot), "config/diff_drive_controllers.yaml")
    assert config["velocity_controller"]["ros__parameters"]["joints"] == ["left_wheel_joint", "right_wheel_joint"]
    assert "diff_drive_controller" not in config


def test_a_four_wheel_skid_steer_base_drives_with_two_wheels_per_side(tmp_path):
    data = yaml.safe_load(DIFF_DRIVE.read_text(encoding="utf-8"))
    for side, y in (("left", 0.18), ("right", -0.18)):
        for end, x in (("front", 0.12), ("rear", -0.12)):
            wheel = copy.deepcopy(data["wheels"][f"{side}_wheel"])
            wheel["origin"]["xyz"] = [x, y + (0.02 if (end, side) == ("rear", "left") else 0.0), -0.055]
            data["wheels"][f"{end}_{side}_wheel"] = wheel
    del data["wheels"]["left_wheel"], data["wheels"]["right_wheel"]
    data["joints"].pop("caster_joint")
    data["links"].pop("caster_link")
    data.pop("gazebo")
    data["ros2_control"] = {}  # every moving joint: the four wheels, velocity-commanded
    spec = tmp_path / "skid.yaml"
    spec.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
    result = xacrokit.generate(spec, tmp_path / "pkg")
    drive = config_of(result.files, "config/diff_drive_controllers.yaml")["diff_drive_controller"]["ros__parameters"]
    assert sorted(drive["left_wheel_names"]) == ["front_left_wheel_joint", "rear_left_wheel_joint"]
    assert sorted(drive["right_wheel_names"]) == ["front_right_wheel_joint", "rear_right_wheel_joint"]
    assert drive["wheel_separation"] == pytest.approx((0.18 + 0.20) / 2 + 0.18)  # mean left y - mean right y


def test_an_arm_keeps_its_forward_command_controllers():
    robot = build_robot(REPO / "examples" / "robots" / "two_dof_arm.yaml")
    config = config_of(render_package(robot), "config/two_dof_arm_controllers.yaml")
    assert "diff_drive_controller" not in config
    groups = controllers(robot)["command_groups"]
    assert groups and all(config[f"{kind}_controller"]["ros__parameters"]["joints"] == j for kind, j in groups.items())


def test_mock_hardware_integrates_velocity_commands_only_where_there_are_some():
    """mock_components/GenericSystem mirrors commands into states; a velocity command moves the position state only
    with calculate_dynamics, and diff_drive_controller's odometry reads that position."""
    from lxml import etree

    from xacrokit.emit import emit_urdf

    for example, integrates in (("diff_drive.yaml", True), ("two_dof_arm.yaml", False)):
        robot = build_robot(REPO / "examples" / "robots" / example)
        hardware = etree.fromstring(emit_urdf(robot).encode()).find("ros2_control/hardware")
        params = {p.get("name"): p.text for p in hardware.findall("param")}
        assert params == ({"calculate_dynamics": "true"} if integrates else {}), example


@pytest.mark.parametrize("macros", ["inline", "copy"])
def test_gazebo_reads_the_controllers_file_it_is_given(tmp_path, macros):
    from lxml import etree

    xacrokit.generate(DIFF_DRIVE, tmp_path / "pkg", macros=macros)
    entry = tmp_path / "pkg" / "urdf" / "diff_drive.urdf.xacro"
    packages = {"diff_drive_description": tmp_path / "pkg"}

    def parameters(**arguments):
        root = etree.fromstring(xacrokit.expand(entry, arguments, package_paths=packages).encode())
        return [e.text for e in root.iter("parameters")]

    default = str((tmp_path / "pkg").resolve() / "config" / "diff_drive_controllers.yaml")
    assert parameters(ros2_control="gazebo") == [default]
    assert parameters(ros2_control="gazebo", prefix="r1_", controllers="/ws/r1_controllers.yaml") == [
        "/ws/r1_controllers.yaml"
    ]
    assert parameters(ros2_control="mock") == []
