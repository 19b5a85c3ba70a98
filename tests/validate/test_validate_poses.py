"""Named poses (issue 32, item 1): units per joint type, located errors (unknown or fixed or mimic joints, values
outside the limits), the home pose as every ros2_control joint's initial_value, mirrored joints' values copied."""

from __future__ import annotations

import math

import pytest
import yaml
from lxml import etree

from xacrokit.emit import emit_urdf
from xacrokit.errors import SpecErrors
from xacrokit.load import load_text
from xacrokit.resolve import resolve
from xacrokit.validate import validate

SPEC = """\
robot: posebot
links:
  base: {shape: {box: {size: [0.2, 0.2, 0.1]}}, mass: 2}
  left_arm: {shape: {box: {size: [0.05, 0.05, 0.3]}}, mass: 1}
  left_slider: {shape: {box: {size: [0.04, 0.04, 0.04]}}, mass: 0.2}
  left_finger: {shape: {box: {size: [0.01, 0.01, 0.04]}}, mass: 0.02}
  tool: {}
joints:
  left_shoulder: {type: revolute, parent: base, child: left_arm, origin: {xyz: [0, 0.15, 0]}, axis: [0, 1, 0],
                  limit: {lower: -90 deg, upper: 90 deg, effort: 10, velocity: 1}}
  left_slide: {type: prismatic, parent: left_arm, child: left_slider, axis: [0, 0, 1],
               limit: {lower: 0, upper: 0.2, effort: 10, velocity: 1}}
  left_finger_joint: {type: prismatic, parent: left_slider, child: left_finger, axis: [1, 0, 0],
                      limit: {lower: 0, upper: 0.4, effort: 1, velocity: 1}, mimic: {joint: left_slide, multiplier: 2}}
  tool_joint: {type: fixed, parent: base, child: tool}
mirror:
  - {joint: left_shoulder, rename: [left_, right_], plane: xz}
ros2_control: {}
"""


def _spec(poses: dict) -> str:
    return SPEC + yaml.safe_dump({"poses": poses}, sort_keys=False)


def _problems(poses: dict) -> list[str]:
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(_spec(poses), "posebot.yaml"))
    return [str(e) for e in caught.value.errors]


def test_home_is_every_controlled_joints_initial_value_and_mirrors_copy_it():
    spec = validate(load_text(_spec({"home": {"left_shoulder": "30 deg", "left_slide": "50 mm"}}), "posebot.yaml"))
    robot = resolve(spec)
    assert dict(robot.poses)["home"] == (
        ("left_shoulder", pytest.approx(math.radians(30), abs=1e-15)),
        ("left_slide", 0.05),
        ("right_shoulder", pytest.approx(math.radians(30), abs=1e-15)),  # (the mirror's: equal values, mirror images)
        ("right_slide", 0.05),
    )
    starts = {j.name: j.initial_position for j in robot.ros2_control}
    shoulder = math.radians(30)
    assert starts == pytest.approx(
        {"left_shoulder": shoulder, "left_slide": 0.05, "right_shoulder": shoulder, "right_slide": 0.05}
        | {"left_finger_joint": 0.1, "right_finger_joint": 0.1}  # (the mimic fingers: 2 x their slide's start)
    )
    root = etree.fromstring(emit_urdf(robot).encode())
    written = {
        j.get("name"): float(j.find("state_interface[@name='position']/param[@name='initial_value']").text)
        for j in root.iterfind("ros2_control/joint")
    }
    assert written == starts


def test_without_a_home_joints_start_at_0_or_the_limit_nearest_it():
    text = _spec({"open": {"left_slide": 0.1}}).replace("lower: 0, upper: 0.2", "lower: 0.05, upper: 0.2")
    robot = resolve(validate(load_text(text, "posebot.yaml")))
    starts = {j.name: j.initial_position for j in robot.ros2_control}
    assert starts == {"left_shoulder": 0.0, "left_slide": 0.05, "right_shoulder": 0.0, "right_slide": 0.05} | {
        "left_finger_joint": 0.1,
        "right_finger_joint": 0.1,
    }


def test_bad_poses_are_located_errors():
    said = _problems(
        {
            "home": {"left_shoulder": "100 deg", "left_slide": 0.3, "left_sholder": 0, "tool_joint": 0},
            "grip": {"left_finger_joint": 0.1},
        }
    )
    text = "\n".join(said)
    assert (
        "$.poses.home.left_shoulder: left_shoulder = 100 deg (1.7453292519943295 rad) is outside its limits "
        "[-90 deg, 90 deg] ([-1.5707963267948966, 1.5707963267948966] rad)"
    ) in text  # (the spec's own text beside the exact value: issue 41)
    assert "$.poses.home.left_slide: left_slide = 0.3 m is outside its limits [0.0, 0.2] m" in text
    assert "$.poses.home.left_slide: left_slide = 0.3 m puts mimic joint left_finger_joint at 0.6 m, outside" in text
    assert "'left_sholder' is not a joint (did you mean 'left_shoulder'?)" in text
    assert "'tool_joint' is a fixed joint; a pose gives the positions of moving joints" in text
    assert "'left_finger_joint' follows 'left_slide' (mimic): give 'left_slide''s position" in text
    assert len(said) == 6
    lines = _spec({}).count("\n")
    assert all(e.startswith("posebot.yaml:") and int(e.split(":")[1]) > lines for e in said)


def test_a_position_takes_the_units_of_its_joint():
    (said,) = _problems({"grip": {"left_slide": "2 kg"}})
    assert "$.poses.grip.left_slide: '2 kg' is a mass, expected a length" in said
    (said,) = _problems({"grip": {"left_shoulder": "20 mm"}})
    assert "$.poses.grip.left_shoulder:" in said and "expected an angle" in said
