"""The configuration MoveIt reads beside the SRDF (issue 44, item 2), checked statically against the package itself and
against facts read from MoveIt 2's moveit_configs_utils (tests/render/ros_facts.yaml; no ROS here): every file
MoveItConfigsBuilder(NAME, package_name=NAME_description) reads by default exists and parses; the controller MoveIt
executes with is the package's JointTrajectoryController on the same joints; a KDL solver per chain group of the SRDF;
the initial positions are the SRDF's home; the launch files import only what moveit_configs_utils defines.

moveit_configs_utils itself is not run: it needs launch, launch_ros, launch_param_builder and srdfdom, which are
not installed here."""

from __future__ import annotations

import ast
import math
from functools import cache
from pathlib import Path

import pytest
import yaml
from lxml import etree

import xacrokit
from conftest import ROBOT_EXAMPLES, gen_robot

FACTS = yaml.safe_load((Path(__file__).parents[1] / "render" / "ros_facts.yaml").read_text(encoding="utf-8"))
# what MoveItConfigsBuilder reads from config/ by default (moveit_configs_builder.py, moveit2 @ 8fcb5d2): the SRDF
# (config/NAME.srdf without a .setup_assistant), kinematics.yaml, joint_limits.yaml, *_controllers.yaml (moveit_
# chosen among several), pilz_cartesian_limits.yaml (the Pilz pipeline is among its defaults)
READ = ("kinematics.yaml", "joint_limits.yaml", "moveit_controllers.yaml", "pilz_cartesian_limits.yaml")


@cache
def package(example: Path, folder: Path) -> tuple[Path, str]:
    result = xacrokit.generate(example, folder / example.stem)
    return result.output, result.name


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    return tmp_path_factory.mktemp("moveit")


@pytest.mark.parametrize("example", ROBOT_EXAMPLES, ids=lambda p: p.stem)
def test_moveit_finds_every_file_and_they_agree_with_the_package(example, folder):
    root, name = package(example, folder)
    controllers = root / "config" / f"{name}_controllers.yaml"
    if not (root / "config" / "moveit_controllers.yaml").exists():
        ros2 = yaml.safe_load(controllers.read_text()) if controllers.exists() else {}
        assert "joint_trajectory_controller" not in ros2  # (only a robot MoveIt cannot execute on goes without)
        assert not (root / "launch" / "move_group.launch.py").exists()
        return
    for file in READ:
        assert isinstance(yaml.safe_load((root / "config" / file).read_text(encoding="utf-8")), dict), file
    srdf = etree.parse(str(root / "config" / f"{name}.srdf")).getroot()
    assert (root / "urdf" / f"{name}.urdf.xacro").is_file()
    managed = yaml.safe_load((root / "config" / "moveit_controllers.yaml").read_text())
    simple = managed["moveit_simple_controller_manager"]
    assert managed["moveit_controller_manager"] == "moveit_simple_controller_manager/MoveItSimpleControllerManager"
    (controller,) = simple["controller_names"]
    ros2 = yaml.safe_load(controllers.read_text())
    assert simple[controller]["joints"] == ros2[controller]["ros__parameters"]["joints"]
    assert simple[controller]["type"] == "FollowJointTrajectory" and simple[controller]["action_ns"]
    chains = {g.get("name") for g in srdf.findall("group") if g.find("chain") is not None}
    kinematics = yaml.safe_load((root / "config" / "kinematics.yaml").read_text())
    assert set(kinematics) == chains
    assert all(v["kinematics_solver"] == "kdl_kinematics_plugin/KDLKinematicsPlugin" for v in kinematics.values())
    home = {j.get("name"): float(j.get("value")) for s in srdf.findall("group_state[@name='home']") for j in s}
    initial = yaml.safe_load((root / "config" / "initial_positions.yaml").read_text())["initial_positions"]
    assert {joint: initial[joint] for joint in home} == home
    pilz = yaml.safe_load((root / "config" / "pilz_cartesian_limits.yaml").read_text())["cartesian_limits"]
    assert set(pilz) == {"max_trans_vel", "max_trans_acc", "max_trans_dec", "max_rot_vel"}
    depends = {e.text for e in etree.parse(str(root / "package.xml")).getroot() if str(e.tag).endswith("depend")}
    assert {"moveit_configs_utils", "moveit_ros_move_group", "moveit_simple_controller_manager"} <= depends


@pytest.mark.parametrize("example", ROBOT_EXAMPLES, ids=lambda p: p.stem)
def test_the_moveit_launch_files_build_on_moveit_configs_utils(example, folder):
    root, name = package(example, folder)
    for launch in ("move_group.launch.py", "moveit_demo.launch.py"):
        path = root / "launch" / launch
        if not (root / "config" / "moveit_controllers.yaml").exists():
            assert not path.exists()
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        imported = {(n.module, a.name) for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) for a in n.names}
        assert ("moveit_configs_utils", "MoveItConfigsBuilder") in imported
        assert all(alias in FACTS["launch_api"][module] for module, alias in imported), imported
        builder = next(
            c for c in ast.walk(tree) if isinstance(c, ast.Call) and getattr(c.func, "id", "") == "MoveItConfigsBuilder"
        )
        assert [ast.literal_eval(a) for a in builder.args] == [name]
        assert {k.arg: ast.literal_eval(k.value) for k in builder.keywords} == {"package_name": f"{name}_description"}
        described = next(
            c for c in ast.walk(tree) if isinstance(c, ast.Call) and getattr(c.func, "attr", "") == "robot_description"
        )
        (file_path,) = [ast.literal_eval(k.value) for k in described.keywords if k.arg == "file_path"]
        assert (root / file_path).is_file()


def test_the_config_check_can_fail(folder):
    """A controller file naming other joints than the package's controller fails the comparison above."""
    root, name = package(ROBOT_EXAMPLES[[p.stem for p in ROBOT_EXAMPLES].index("ur10e")], folder)
    managed = yaml.safe_load((root / "config" / "moveit_controllers.yaml").read_text())
    ros2 = yaml.safe_load((root / "config" / f"{name}_controllers.yaml").read_text())
    joints = managed["moveit_simple_controller_manager"]["joint_trajectory_controller"]["joints"]
    assert joints == ros2["joint_trajectory_controller"]["ros__parameters"]["joints"]
    assert joints[:-1] != ros2["joint_trajectory_controller"]["ros__parameters"]["joints"]


def test_an_acceleration_limit_reaches_joint_limits_yaml_and_a_bad_one_is_located(tmp_path):
    """``limit: {acceleration: 180 deg/s2}`` on one joint: MoveIt's joint_limits.yaml claims it (in rad/s^2) and no
    other; -1 is refused at its line, exit 2, nothing written."""
    spec = (ROBOT_EXAMPLES[[p.stem for p in ROBOT_EXAMPLES].index("two_dof_arm")]).read_text(encoding="utf-8")
    joint = next(line for line in spec.splitlines() if "velocity:" in line and "limit" in line)
    given = joint.replace("velocity:", "acceleration: 180 deg/s2, velocity:")
    (tmp_path / "robot.yaml").write_text(spec.replace(joint, given), encoding="utf-8")
    result = xacrokit.generate(tmp_path / "robot.yaml", tmp_path / "pkg")
    limits = yaml.safe_load((tmp_path / "pkg" / "config" / "joint_limits.yaml").read_text())["joint_limits"]
    accelerated = {
        name: entry["max_acceleration"] for name, entry in limits.items() if entry["has_acceleration_limits"]
    }
    assert list(accelerated.values()) == [pytest.approx(math.pi)] and len(limits) > 1, result.name
    (tmp_path / "bad.yaml").write_text(spec.replace(joint, joint.replace("velocity:", "acceleration: -1, velocity:")))
    run = gen_robot(tmp_path / "bad.yaml", "-o", tmp_path / "bad")
    line = spec.splitlines().index(joint) + 1
    assert run.returncode == 2 and f"bad.yaml:{line}:" in run.stderr and "acceleration" in run.stderr
    assert not (tmp_path / "bad").exists()
