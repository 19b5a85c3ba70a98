"""Joint speed and effort limits in the units datasheets use: rpm and deg/s, kgf*cm and N*m, mm/s and N; masses in lb
and oz. Converted by the joint's type (a prismatic joint's are linear), each > 0, and refused with the units that
fit."""

from __future__ import annotations

import math

import pytest

from xacrokit.errors import SpecErrors
from xacrokit.pipeline import build_robot

SPEC = """robot: servo
links:
  base_link: {shape: {box: {size: [0.2, 0.2, 0.1]}}, mass: "1.5 lb"}
  arm: {shape: {box: {size: [0.05, 0.05, 0.3]}}, mass: "8 oz"}
  slider: {shape: {box: {size: [0.05, 0.05, 0.05]}}, mass: 0.1}
joints:
  shoulder: {type: revolute, parent: base_link, child: arm, axis: [0, 1, 0],
             limit: {lower: -90 deg, upper: 90 deg, effort: 15 kgf*cm, velocity: 60 rpm}, dynamics: {damping: 0.1}}
  rail: {type: prismatic, parent: base_link, child: slider, axis: [1, 0, 0],
         limit: {lower: 0, upper: 200 mm, effort: 2 kgf, velocity: 250 mm/s}, dynamics: {damping: 0.1}}
wheels:
  wheel: {parent: base_link, origin: {xyz: [0, 0.12, 0]}, radius: 0.05, width: 0.02, mass: 0.1,
          limit: {effort: 50 N*cm, velocity: 180 deg/s}}
"""


def build(tmp_path, text):
    path = tmp_path / "servo.yaml"
    path.write_text(text, encoding="utf-8")
    return build_robot(path)


def test_datasheet_units_become_si_by_the_joint_type(tmp_path):
    robot = build(tmp_path, SPEC)
    joints = {joint.name: joint.limit for joint in robot.joints}
    assert (joints["shoulder"].effort, joints["shoulder"].velocity) == (15 * 9.80665 / 100, 2 * math.pi)
    assert (joints["rail"].effort, joints["rail"].velocity) == (19.6133, 0.25)
    (wheel,) = robot.wheels
    assert (wheel.effort, wheel.velocity) == (0.5, math.pi)
    masses = {link.name: link.inertial.mass for link in robot.links if link.inertial}
    assert masses == {"base_link": 0.680388555, "arm": 0.226796185, "slider": 0.1}  # 1.5 lb, 8 oz: exact decimals


@pytest.mark.parametrize(
    ("change", "where", "said"),
    [
        (("effort: 15 kgf*cm", "effort: 15 rpm"), "shoulder.limit.effort", "is an angular velocity, expected a torque"),
        (("velocity: 250 mm/s", "velocity: 250 rpm"), "rail.limit.velocity", "expected a linear velocity (m/s, mm/s"),
        (("effort: 2 kgf", "effort: 2 N*m"), "rail.limit.effort", "is a torque, expected a force (N, kN, kgf)"),
        (("velocity: 60 rpm", 'velocity: "0 rpm"'), "shoulder.limit.velocity", "velocity must be > 0, got '0 rpm'"),
        (("effort: 15 kgf*cm", "effort: -1 N*m"), "shoulder.limit.effort", "effort must be > 0, got '-1 N*m'"),
    ],
)
def test_a_limit_in_the_wrong_units_is_refused_at_its_value(tmp_path, change, where, said):
    with pytest.raises(SpecErrors) as caught:
        build(tmp_path, SPEC.replace(*change))
    (error,) = caught.value.errors
    assert error.path == f"$.joints.{where}" and said in error.message, error
