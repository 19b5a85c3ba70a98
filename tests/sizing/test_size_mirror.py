"""A mirrored pair reads alike (issue 42, item 4): on the ROS 2 chapter's simple humanoid (section 4.5.2's numbers,
the right side by `mirror`, as its "TODO: mirror of left side" asks) the left and right joints' needs are the same,
printed by magnitude; the JSON keeps each torque's sign, about the joint's own axis, and a `mirror` copy's axis (-S a)
makes equal joint values give equal torques, so that the signs agree pose for pose."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from conftest import gen_robot
from xacrokit.reader.read_robot import read_robot
from xacrokit.sizing import GRAVITY
from xacrokit.sizing.sized_robot import loaded_robot
from xacrokit.sizing.static import torques

# the chapter's humanoid (003_14099ffd6e805cc7.txt, 4.5.2): masses, centres, origins and limits as it writes them
CHAPTER = """\
robot: simple_humanoid
links:
  base_link: {shape: {box: {size: [0.2, 0.15, 0.1]}}, mass: 5.0}
  torso: {shape: {box: {size: [0.25, 0.2, 0.5]}}, origin: {xyz: [0, 0, 0.25]}, mass: 10.0}
  head: {shape: {sphere: {radius: 0.1}}, mass: 2.0}
  left_upper_arm: {shape: {cylinder: {radius: 0.03, length: 0.3}}, origin: {xyz: [0, 0, -0.15]}, mass: 1.5}
  left_forearm: {shape: {cylinder: {radius: 0.025, length: 0.25}}, origin: {xyz: [0, 0, -0.125]}, mass: 1.0}
  left_thigh: {shape: {cylinder: {radius: 0.05, length: 0.4}}, origin: {xyz: [0, 0, -0.2]}, mass: 3.0}
  left_shin: {shape: {cylinder: {radius: 0.04, length: 0.35}}, origin: {xyz: [0, 0, -0.175]}, mass: 2.0}
joints:
  hip_joint: {type: fixed, parent: base_link, child: torso, origin: {xyz: [0, 0, 0.05]}}
  neck_joint:
    {type: revolute, parent: torso, child: head, origin: {xyz: [0, 0, 0.55]}, axis: [0, 0, 1],
     limit: {lower: -1.57, upper: 1.57, effort: 5, velocity: 1}}
  left_shoulder_pitch:
    {type: revolute, parent: torso, child: left_upper_arm, origin: {xyz: [0, 0.15, 0.45]}, axis: [0, 1, 0],
     limit: {lower: -3.14, upper: 3.14, effort: 20, velocity: 2}}
  left_elbow:
    {type: revolute, parent: left_upper_arm, child: left_forearm, origin: {xyz: [0, 0, -0.3]}, axis: [0, 1, 0],
     limit: {lower: 0, upper: 2.8, effort: 10, velocity: 2}}
  left_hip_pitch:
    {type: revolute, parent: base_link, child: left_thigh, origin: {xyz: [0, 0.08, 0]}, axis: [0, 1, 0],
     limit: {lower: -1.57, upper: 1.57, effort: 50, velocity: 1.5}}
  left_knee:
    {type: revolute, parent: left_thigh, child: left_shin, origin: {xyz: [0, 0, -0.4]}, axis: [0, 1, 0],
     limit: {lower: 0, upper: 2.4, effort: 40, velocity: 1.5}}
mirror:
  - {joint: left_shoulder_pitch, rename: [left_, right_]}
  - {joint: left_hip_pitch, rename: [left_, right_]}
"""
# a roll joint too (axis x: mirror turns it to -x), on an asymmetric range: one worst pose, its sign compared
ROLLING = CHAPTER.replace("left_hip_pitch", "left_hip_roll").replace(
    "axis: [0, 1, 0],\n     limit: {lower: -1.57, upper: 1.57, effort: 50",
    "axis: [1, 0, 0],\n     limit: {lower: -0.2, upper: 0.8, effort: 50",
)
PAIRS = ("shoulder_pitch", "elbow", "hip_pitch", "knee")
LEG = 3.0 * 0.2 + 2.0 * (0.4 + 0.175)  # the straight leg's first moment of mass about the hip, kg*m


def _rows(text: str) -> dict[str, list[str]]:
    """The static table's rows: joint -> [need, of it loads, effort limit, margin] as printed."""
    lines = text.splitlines()
    start = next(k for k, line in enumerate(lines) if line.startswith("  joint ")) + 1
    rows = {}
    for line in lines[start:]:
        words = line.split()
        if len(words) < 5 or not line.startswith("  ") or line.startswith("  N*m"):
            break
        rows[words[0]] = words[1:5]
    return rows


def test_the_chapters_mirrored_humanoid_reads_alike_left_and_right(tmp_path):
    """Before: left_elbow 1.226 and right_elbow -1.226 (each elbow's worst case is the forearm held level, forward
    or back: the search found one on each side). Now each pair's row is the same, its need the closed form's."""
    spec = tmp_path / "simple_humanoid.yaml"
    spec.write_text(CHAPTER, encoding="utf-8")
    result = gen_robot("size", spec)
    assert result.returncode == 0, result.stderr
    rows = _rows(result.stdout)
    assert len(rows) == 9
    for joint in PAIRS:
        assert rows["left_" + joint] == rows["right_" + joint], joint
    report = json.loads(gen_robot("size", spec, "--json").stdout)
    static = {j["name"]: j["static"]["peak_torque"] for j in report["joints"]}
    # the forearm held level: m g r; the whole arm level: g (m_u r_u + m_f (l_u + r_f)); likewise the leg
    needs = {
        "elbow": GRAVITY * 1.0 * 0.125,
        "shoulder_pitch": GRAVITY * (1.5 * 0.15 + 1.0 * (0.3 + 0.125)),
        "knee": GRAVITY * 2.0 * 0.175,
        # (the hip's range ends at 1.57 rad, the thigh just short of level; the knee levels the shin)
        "hip_pitch": GRAVITY * ((3.0 * 0.2 + 2.0 * 0.4) * math.sin(1.57) + 2.0 * 0.175),
    }
    for joint in PAIRS:
        for side in ("left_", "right_"):
            assert abs(static[side + joint]) == pytest.approx(needs[joint], rel=1e-9), side + joint
            assert float(rows[side + joint][0]) == pytest.approx(needs[joint], rel=1e-3)  # (printed to 4 digits)


def test_a_mirrored_joints_torque_is_about_its_mirrored_axis(tmp_path):
    """mirror gives a turning joint the axis -S a (a pitch about y keeps y through the xz plane; a roll about x turns
    to -x): equal joint values give mirror-image poses and equal torques, the signed ones of the JSON included."""
    spec = tmp_path / "rolling.yaml"
    spec.write_text(ROLLING, encoding="utf-8")
    robot = loaded_robot(read_robot(spec))
    names = [j.name for j in robot.joints]
    left = [k for k, name in enumerate(names) if name.startswith("left_")]
    right = [names.index(names[k].replace("left_", "right_")) for k in left]
    rng = np.random.default_rng(7)
    lower = np.array([j.span[0] for j in robot.joints])
    upper = np.array([j.span[1] for j in robot.joints])
    for values in lower + rng.random((50, len(names))) * (upper - lower):
        values[right] = values[left]  # (each right joint at its left twin's value)
        gravity, _ = torques(robot, values)
        assert np.allclose(gravity[right], gravity[left], rtol=1e-12, atol=1e-12)
    report = json.loads(gen_robot("size", spec, "--json").stdout)
    static = {j["name"]: j["static"] for j in report["joints"]}
    # the roll's worst case is one pose (0.8 rad, the leg swung out straight): the same signed torque on both sides
    assert static["left_hip_roll"]["pose"]["left_hip_roll"] == pytest.approx(0.8, abs=1e-9)
    assert static["right_hip_roll"]["pose"]["right_hip_roll"] == pytest.approx(0.8, abs=1e-9)
    assert static["left_hip_roll"]["peak_torque"] == pytest.approx(static["right_hip_roll"]["peak_torque"], rel=1e-12)
    assert abs(static["left_hip_roll"]["peak_torque"]) == pytest.approx(GRAVITY * LEG * math.sin(0.8), rel=1e-9)
