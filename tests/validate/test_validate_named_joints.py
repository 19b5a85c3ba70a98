"""Wheels, frames and arms' tools may name their joint (``joint: wheel_left_joint``), as real robots do (TurtleBot3's
wheel_left_joint and scan_joint, Universal Robots' wrist_3-flange and base_link-base_fixed_joint), and an arm may hang
its first joint on its parent (``base: false``, UR's shoulder_pan_joint on base_link_inertia); the names reach the
URDF by both writers, the controllers and the checks."""

from __future__ import annotations

import json

import pytest
import yaml
from lxml import etree

from conftest import assert_refused, gen_robot, snapshot
from xacrokit.errors import SpecErrors
from xacrokit.pipeline import build_robot

TURTLE = {
    "robot": "tb",
    "links": {"base_footprint": {}, "base_link": {"shape": {"box": {"size": [0.2, 0.2, 0.1]}}, "mass": 1.0}},
    "joints": {"base_joint": {"type": "fixed", "parent": "base_footprint", "child": "base_link"}},
    "wheels": {
        "wheel_left_link": {
            "parent": "base_link",
            "joint": "wheel_left_joint",
            "radius": 0.033,
            "width": 0.018,
            "mass": 0.03,
            "origin": {"xyz": [0, 0.08, 0]},
        },
        "wheel_right_link": {
            "parent": "base_link",
            "radius": 0.033,
            "width": 0.018,
            "mass": 0.03,
            "origin": {"xyz": [0, -0.08, 0]},
        },
    },
    "frames": {"base_scan": {"parent": "base_link", "joint": "scan_joint", "origin": {"xyz": [0, 0, 0.1]}}},
    "ros2_control": {},
}


def write_spec(tmp_path, spec):
    path = tmp_path / "tb.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    return path


def joints_of(urdf_path):
    root = etree.parse(str(urdf_path)).getroot()
    return {j.get("name"): (j.get("type"), j.find("child").get("link")) for j in root.findall("joint")}


@pytest.mark.parametrize("mode", [["--macros", "inline"], ["--macros", "copy", "--via-xacro"]])
def test_named_joints_reach_the_urdf_and_the_controllers(tmp_path, mode):
    spec = write_spec(tmp_path, TURTLE)
    result = gen_robot(spec, "-o", tmp_path / "out", *mode)
    assert result.returncode == 0, result.stderr
    joints = joints_of(tmp_path / "out" / "urdf" / "tb.urdf")
    assert joints["wheel_left_joint"] == ("continuous", "wheel_left_link")
    assert joints["wheel_right_link_joint"] == ("continuous", "wheel_right_link")  # (not named: the default)
    assert joints["scan_joint"] == ("fixed", "base_scan")
    assert "wheel_left_link_joint" not in joints and "base_scan_joint" not in joints
    controllers = yaml.safe_load((tmp_path / "out" / "config" / "tb_controllers.yaml").read_text())
    params = [v.get("ros__parameters", {}) for v in controllers.values()]
    drive = next(p for p in params if "left_wheel_names" in p)
    assert drive["left_wheel_names"] == ["wheel_left_joint"]
    assert drive["right_wheel_names"] == ["wheel_right_link_joint"]
    control = etree.parse(str(tmp_path / "out" / "urdf" / "tb.urdf")).getroot().find("ros2_control")
    assert {j.get("name") for j in control.iter("joint")} == {"wheel_left_joint", "wheel_right_link_joint"}


def test_a_named_joint_that_clashes_is_a_located_error(tmp_path):
    spec = yaml.safe_load(yaml.safe_dump(TURTLE))
    spec["frames"]["base_scan"]["joint"] = "base_joint"
    path = write_spec(tmp_path, spec)
    with pytest.raises(SpecErrors) as caught:
        build_robot(path)
    (error,) = caught.value.errors
    assert error.path == "$.frames.base_scan.joint"
    assert "base_joint" in error.message
    assert error.line == path.read_text().splitlines().index("    joint: base_joint") + 1


def test_a_mimic_may_follow_a_named_wheel_joint(tmp_path):
    spec = yaml.safe_load(yaml.safe_dump(TURTLE))
    spec["links"]["caster"] = {"shape": {"sphere": {"radius": 0.01}}, "mass": 0.01}
    spec["joints"]["caster_joint"] = {
        "type": "continuous",
        "parent": "base_link",
        "child": "caster",
        "limit": {"effort": 1, "velocity": 1},
        "mimic": {"joint": "wheel_left_joint"},
    }
    robot = build_robot(write_spec(tmp_path, spec))
    assert next(j for j in robot.joints if j.name == "caster_joint").mimic.joint == "wheel_left_joint"
    spec["joints"]["caster_joint"]["mimic"]["joint"] = "wheel_left_link_joint"  # (the default name is gone)
    with pytest.raises(SpecErrors) as caught:
        build_robot(write_spec(tmp_path, spec))
    assert [e.path for e in caught.value.errors] == ["$.joints.caster_joint.mimic.joint"]


UR_LIKE = {
    "robot": "ur_like",
    "links": {"base_link": {}},
    "frames": {
        "base_link_inertia": {
            "parent": "base_link",
            "joint": "base_link-base_link_inertia",
            "origin": {"rpy": [0, 0, "pi"]},
            "shape": {"cylinder": {"radius": 0.07, "length": 0.04}},
            "mass": 4.0,
        },
        "tool0": {"parent": "flange", "joint": "flange-tool0", "origin": {"rpy": ["pi/2", 0, "pi/2"]}},
    },
    "arms": {
        "ur": {
            "parent": "base_link_inertia",
            "base": False,
            "joints": [
                {
                    "name": "shoulder_pan_joint",
                    "link": "shoulder_link",
                    "a": 0,
                    "d": 0.18,
                    "alpha": "pi/2",
                    "mass": 7.0,
                    "limit": {"lower": -3, "upper": 3, "effort": 300, "velocity": 2},
                },
                {
                    "name": "shoulder_lift_joint",
                    "link": "upper_arm_link",
                    "a": -0.6,
                    "d": 0,
                    "alpha": 0,
                    "mass": 13.0,
                    "limit": {"lower": -3, "upper": 3, "effort": 300, "velocity": 2},
                },
            ],
            "tool": {"name": "flange", "joint": "upper_arm-flange", "origin": {"rpy": [0, "-pi/2", "-pi/2"]}},
        }
    },
    "ros2_control": {},
}


@pytest.mark.parametrize("mode", [["--macros", "inline"], ["--macros", "copy", "--via-xacro"]])
def test_an_arm_without_a_base_and_names_with_dashes_reach_every_writer(tmp_path, mode):
    spec = tmp_path / "ur_like.yaml"
    spec.write_text(yaml.safe_dump(UR_LIKE, sort_keys=False), encoding="utf-8")
    out = tmp_path / "out"
    result = gen_robot(spec, "-o", out, *mode)
    assert result.returncode == 0, result.stderr
    root = etree.parse(str(out / "urdf" / "ur_like.urdf")).getroot()
    links = {e.get("name") for e in root.findall("link")}
    joints = {
        j.get("name"): (j.get("type"), j.find("parent").get("link"), j.find("child").get("link"))
        for j in root.findall("joint")
    }
    assert "ur_base" not in links and links == {
        "base_link",
        "base_link_inertia",
        "shoulder_link",
        "upper_arm_link",
        "flange",
        "tool0",
    }
    assert joints == {
        "base_link-base_link_inertia": ("fixed", "base_link", "base_link_inertia"),
        "shoulder_pan_joint": ("revolute", "base_link_inertia", "shoulder_link"),
        "shoulder_lift_joint": ("revolute", "shoulder_link", "upper_arm_link"),
        "upper_arm-flange": ("fixed", "upper_arm_link", "flange"),
        "flange-tool0": ("fixed", "flange", "tool0"),
    }
    assert [float(v) for v in root.find("joint[@name='shoulder_pan_joint']/origin").get("xyz").split()] == [0, 0, 0.18]
    # every written file stays what its reader takes: the checks (K001: the URDF's kinematics are the DH product)
    for checked in (spec, out / "urdf" / "ur_like.urdf", out / "urdf" / "ur_like.urdf.xacro"):
        found = gen_robot("check", checked, "--format", "json")
        assert found.returncode == 0, found.stdout + found.stderr
        assert json.loads(found.stdout)["summary"]["errors"] == 0
    controllers = yaml.safe_load((out / "config" / "ur_like_controllers.yaml").read_text(encoding="utf-8"))
    params = [v.get("ros__parameters", {}) for v in controllers.values()]
    assert ["shoulder_pan_joint", "shoulder_lift_joint"] in [p.get("joints") for p in params]


def test_an_arm_without_a_base_takes_no_origin(tmp_path):
    spec = yaml.safe_load(yaml.safe_dump(UR_LIKE))
    spec["arms"]["ur"]["origin"] = {"xyz": [0, 0, 0.1]}
    path = tmp_path / "ur_like.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    before = snapshot(tmp_path)
    result = gen_robot(path, "-o", tmp_path / "out")
    line = path.read_text(encoding="utf-8").splitlines().index("    origin:") + 1
    assert_refused(
        result.returncode, result.stderr, f"ur_like.yaml:{line}:5: $.arms.ur.origin: an arm with base: false"
    )
    assert "place 'base_link_inertia' there instead, or drop base: false" in result.stderr
    assert snapshot(tmp_path) == before  # (nothing written)


def test_a_tool_joint_that_clashes_is_a_located_error(tmp_path):
    spec = yaml.safe_load(yaml.safe_dump(UR_LIKE))
    spec["arms"]["ur"]["tool"]["joint"] = "flange-tool0"
    path = tmp_path / "ur_like.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    with pytest.raises(SpecErrors) as caught:
        build_robot(path)
    (error,) = caught.value.errors
    assert error.path == "$.frames.tool0.joint"  # (arms come before frames: the frame's is the second use)
    assert error.message.startswith("joint name 'flange-tool0' is already used by $.arms.ur.tool.joint")
    assert error.line == path.read_text(encoding="utf-8").splitlines().index("    joint: flange-tool0") + 1


def test_a_mount_joint_that_clashes_is_a_located_error(tmp_path):
    spec = {"robot": "ur_like", "mount_joint": "base_joint", **{k: v for k, v in UR_LIKE.items() if k != "robot"}}
    path = tmp_path / "ur_like.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    assert build_robot(path).mount_joint_name == "base_joint"
    spec["mount_joint"] = "shoulder_pan_joint"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    with pytest.raises(SpecErrors) as caught:
        build_robot(path)
    (error,) = caught.value.errors
    assert error.path == "$.mount_joint" and error.line == 2
    assert error.message.startswith("joint name 'shoulder_pan_joint' is already used by $.arms.ur.joints[0].name")
