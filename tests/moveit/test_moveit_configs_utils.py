"""MoveIt's own moveit_configs_utils builds its configuration from a generated package (issue 44, item 2): the real
MoveItConfigsBuilder, from MoveIt 2's sources, under the real launch and launch_param_builder, reads the package's
URDF (xacro with ros2_control:=mock), SRDF, kinematics, controllers, joint limits and Pilz limits, without error.

ROS is not installed here, so the test runs only where XACROKIT_ROS_SOURCES names a folder holding those sources as
``moveit2/moveit_configs_utils``, ``launch/launch``, ``launch_param_builder`` and a ``deps`` folder with launch's
own requirements (lark, osrf_pycommon), e.g. from ``git archive`` of github.com/moveit/moveit2,
github.com/ros2/launch and github.com/PickNikRobotics/launch_param_builder and ``pip install --target deps lark
osrf-pycommon``. Two stand-ins are written here: ament_index_python's package lookup (the package folders by name)
and launch_ros's ParameterValue (launch_ros imports rclpy and ROS messages; the builder uses ParameterValue only for
mappings that are substitutions, which these are not)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from lxml import etree

import xacrokit
from conftest import ROBOT_EXAMPLES

SOURCES = os.environ.get("XACROKIT_ROS_SOURCES")
pytestmark = pytest.mark.skipif(not SOURCES, reason="XACROKIT_ROS_SOURCES names no ROS sources (see the docstring)")

AMENT = """import os


class PackageNotFoundError(KeyError):
    pass


def get_package_share_directory(name):
    folders = dict(item.split("=", 1) for item in os.environ["AMENT_SHIM"].split(";") if item)
    if name not in folders:
        raise PackageNotFoundError(name)
    return folders[name]


def get_package_prefix(name):
    return os.path.dirname(os.path.dirname(get_package_share_directory(name)))
"""
PARAMETER_VALUE = """class ParameterValue:
    def __init__(self, value, *, value_type=None):
        self.value, self.value_type = value, value_type
"""
BUILD = """import json, sys
from moveit_configs_utils import MoveItConfigsBuilder
name = sys.argv[1]
config = (
    MoveItConfigsBuilder(name, package_name=name + "_description")
    .robot_description(file_path="urdf/" + name + ".urdf.xacro", mappings={"ros2_control": "mock"})
    .to_moveit_configs()
)
print(json.dumps({
    "keys": sorted(config.to_dict()),
    "controllers": config.trajectory_execution["moveit_simple_controller_manager"],
    "kinematics": config.robot_description_kinematics["robot_description_kinematics"],
    "srdf": config.robot_description_semantic["robot_description_semantic"],
    "urdf": config.robot_description["robot_description"],
    "pipelines": config.planning_pipelines["planning_pipelines"],
}))
"""


@pytest.mark.parametrize("example", ["industrial_arm_mod_dh", "ur10e"])
def test_moveit_configs_utils_builds_the_configuration_of_a_generated_package(example, tmp_path):
    spec = next(p for p in ROBOT_EXAMPLES if p.stem == example)
    result = xacrokit.generate(spec, tmp_path / "share" / "pkg")
    root = tmp_path / "share" / result.package
    result.output.rename(root)
    shim = tmp_path / "shim"
    (shim / "ament_index_python").mkdir(parents=True)
    (shim / "ament_index_python" / "__init__.py").write_text("")
    (shim / "ament_index_python" / "packages.py").write_text(AMENT)
    (shim / "launch_ros").mkdir()
    (shim / "launch_ros" / "__init__.py").write_text("")
    (shim / "launch_ros" / "parameter_descriptions.py").write_text(PARAMETER_VALUE)
    ros = Path(SOURCES or "")
    path = [
        shim,
        ros / "deps",
        ros / "launch_param_builder",
        ros / "launch" / "launch",
        ros / "moveit2" / "moveit_configs_utils",
    ]
    env = dict(
        os.environ,
        PYTHONPATH=os.pathsep.join(map(str, path)),
        AMENT_SHIM=f"moveit_configs_utils={ros / 'moveit2' / 'moveit_configs_utils'};{result.package}={root}",
    )
    run = subprocess.run(
        [sys.executable, "-c", BUILD, result.name], env=env, capture_output=True, text=True, timeout=120
    )
    assert run.returncode == 0, run.stderr
    built = yaml.safe_load(run.stdout)
    read, ours = etree.fromstring(built["srdf"].encode()), etree.parse(str(root / "config" / f"{result.name}.srdf"))
    assert elements(read) == elements(ours.getroot()) and len(read) > 1  # (through xacro, element for element)
    assert f'<robot name="{result.name}">' in built["urdf"] and "mock_components/GenericSystem" in built["urdf"]
    assert (
        built["controllers"]
        == yaml.safe_load((root / "config" / "moveit_controllers.yaml").read_text())["moveit_simple_controller_manager"]
    )
    assert built["kinematics"] == yaml.safe_load((root / "config" / "kinematics.yaml").read_text())
    assert "ompl" in built["pipelines"] and "robot_description_planning" in built["keys"]


def elements(root) -> list[tuple[str, dict[str, str], list]]:
    """An element tree as (tag, attributes, children), whitespace and comments left out."""
    return [(e.tag, dict(e.attrib), elements(e)) for e in root if isinstance(e.tag, str)]
