"""The entry's arguments (prefix, ros2_control hardware) and the robot macro mounted on a parent, expanded by xacro."""

from __future__ import annotations

import pytest
from lxml import etree

import xacrokit
from conftest import REPO


@pytest.fixture(scope="module")
def diff_drive_package(tmp_path_factory):
    out = tmp_path_factory.mktemp("dd") / "diff_drive_description"
    xacrokit.generate(REPO / "examples" / "robots" / "diff_drive.yaml", out)
    return out


def test_generated_entry_arguments_choose_the_hardware_and_prefix(diff_drive_package):

    entry = diff_drive_package / "urdf" / "diff_drive.urdf.xacro"
    paths = {"diff_drive_description": diff_drive_package}

    def expand(**args):
        return etree.fromstring(xacrokit.expand(entry, args, package_paths=paths).encode())

    mock = expand()
    assert mock.findtext("ros2_control/hardware/plugin") == "mock_components/GenericSystem"
    assert [j.get("name") for j in mock.findall("ros2_control/joint")] == ["left_wheel_joint", "right_wheel_joint"]
    assert mock.find("ros2_control/joint/command_interface").get("name") == "velocity"
    gazebo = expand(ros2_control="gazebo", prefix="r1_")
    assert gazebo.findtext("ros2_control/hardware/plugin") == "gz_ros2_control/GazeboSimSystem"
    plugin = gazebo.find("gazebo/plugin")
    assert plugin.findtext("parameters") == f"{diff_drive_package}/config/diff_drive_controllers.yaml"
    names = [e.get("name") for e in gazebo.iter("link", "joint") if e.getparent().tag == "robot"]
    names += [j.get("name") for j in gazebo.findall("ros2_control/joint")]
    names += [g.get("reference") for g in gazebo.findall("gazebo") if g.get("reference")]
    assert names and all(n.startswith("r1_") for n in names)
    assert gazebo.find("ros2_control").get("name") == "r1_diff_drive"
    assert expand(ros2_control="none").find("ros2_control") is None
    with pytest.raises(xacrokit.ExpandError, match="ros2_control must be mock, gazebo or none, got 'gz'"):
        expand(ros2_control="gz")


def test_robot_macro_mounts_on_a_parent_with_an_origin(diff_drive_package, tmp_path):

    scene = tmp_path / "scene.urdf.xacro"
    scene.write_text(
        '<?xml version="1.0"?>\n<robot name="scene" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        f'  <xacro:include filename="{diff_drive_package}/urdf/diff_drive_macro.xacro"/>\n'
        '  <link name="world"/>\n'
        '  <xacro:diff_drive prefix="a_" parent="world"><origin xyz="1 2 0" rpy="0 0 0.5"/></xacro:diff_drive>\n'
        '  <xacro:diff_drive prefix="b_" parent="world"><origin xyz="-1 0 0" rpy="0 0 0"/></xacro:diff_drive>\n'
        "</robot>\n",
        encoding="utf-8",
    )
    root = etree.fromstring(xacrokit.expand(scene).encode())
    mount = root.find("joint[@name='a_base_footprint_mount_joint']")
    assert mount.find("parent").get("link") == "world" and mount.find("child").get("link") == "a_base_footprint"
    assert mount.find("origin").get("xyz") == "1 2 0"
    materials = [m.get("name") for m in root.findall("material")]
    assert len(materials) == len(set(materials)) == 3  # one definition, however many instances
    links = [e.get("name") for e in root.findall("link")]
    assert len(links) == len(set(links)) == 1 + 2 * 9  # world + two robots of 9 links (the camera's optical frame too)
