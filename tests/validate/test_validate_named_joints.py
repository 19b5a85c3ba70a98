"""Wheels and frames may name their joint (``joint: wheel_left_joint``), as real robots do (TurtleBot3's
wheel_left_joint and scan_joint); the name reaches the URDF by both writers, the controllers and the checks."""

from __future__ import annotations

import pytest
import yaml
from lxml import etree

from conftest import gen_robot
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
