"""A motion whose segments all have a duration needs no acceleration limit (issue 42, item 3): the lecture's "from
(0, 0) to (1.5, 1.5) rad in 3 s with a quintic profile" is sized from a file that gives only the waypoints and the
duration (examples/sizing/two_dof_arm_quintic.yaml), against the quintic's closed form and the energy balance
docs/size.md states, written out here from examples/robots/two_dof_arm.yaml's numbers; the report says which limits
it checked (none where none was given), and a limit the motion still needs is a located error."""

from __future__ import annotations

import json
import math

import jsonschema
import numpy as np
import pytest
import yaml

from conftest import REPO, gen_robot
from xacrokit.errors import SpecErrors
from xacrokit.sizing import GRAVITY, size

ARM = REPO / "examples" / "robots" / "two_dof_arm.yaml"
QUINTIC = REPO / "examples" / "sizing" / "two_dof_arm_quintic.yaml"
SCHEMA = json.loads((REPO / "schemas" / "size-report.schema.json").read_text(encoding="utf-8"))
# two_dof_arm.yaml: upper arm 0.3 m, 0.5 kg, its centre 0.15 m up it; forearm 0.3 kg, its centre 0.125 m up it
UPPER, UPPER_CENTRE, UPPER_LENGTH, FORE, FORE_CENTRE = 0.5, 0.15, 0.3, 0.3, 0.125
DAMPING = {"shoulder_joint": 0.1, "elbow_joint": 0.05}
DQ, T = 1.5, 3.0


def _height(q1: float, q2: float) -> float:
    """Potential energy / g: the links' first moment of mass about the shoulder's height."""
    return UPPER * UPPER_CENTRE * math.cos(q1) + FORE * (UPPER_LENGTH * math.cos(q1) + FORE_CENTRE * math.cos(q1 + q2))


def _quintic(t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """q, qdot, qddot of 1.5 rad in 3 s: q = dq (10 u^3 - 15 u^4 + 6 u^5), u = t / T."""
    u = t / T
    return (
        DQ * (10 * u**3 - 15 * u**4 + 6 * u**5),
        DQ * (30 * u**2 - 60 * u**3 + 30 * u**4) / T,
        DQ * (60 * u - 180 * u**2 + 120 * u**3) / T**2,
    )


def test_the_lectures_quintic_in_3_s_needs_only_the_waypoints_and_the_duration():
    """The file gives no limit: the command sizes it (it said "needs a acceleration limit" and exit 2 before), the
    quintic's peaks are its closed form's (15/8 dq/T, 10/sqrt(3) dq/T^2), and the motors' energies add up to the fall
    of potential energy plus the damping's d dq^2/T * 10/7 per joint."""
    assert "acceleration" not in yaml.safe_load(QUINTIC.read_text(encoding="utf-8"))["motion"]
    result = gen_robot("size", ARM, "--sizing", QUINTIC, "--json", cwd=REPO)
    assert result.returncode == 0, result.stderr
    report = json.loads(result.stdout)
    jsonschema.validate(report, SCHEMA)
    assert report["motion_timing"]["segments"] == [T] and report["motion_timing"]["cycle"] == T
    joints = {j["name"]: j for j in report["joints"]}
    for joint in joints.values():
        assert joint["motion"]["peak_speed"] == pytest.approx(15 / 8 * DQ / T, rel=1e-9)  # 0.9375 rad/s
        assert 15 / 8 * DQ / T == 0.9375
        # (the peak acceleration falls between the 1 ms samples: within 1e-6 of it)
        assert joint["motion"]["peak_acceleration"] == pytest.approx(10 / math.sqrt(3) * DQ / T**2, rel=1e-6)
        assert joint["motion"]["velocity_margin"] == pytest.approx(1.0 / 0.9375, rel=1e-9)  # (the URDF's 1 rad/s)
    lost = sum(d * DQ**2 / T * 10 / 7 for d in DAMPING.values())
    change = GRAVITY * (_height(DQ, DQ) - _height(0.0, 0.0))
    spent = sum(j["motion"]["energy"] for j in joints.values())
    assert spent == pytest.approx(change + lost, rel=1e-9)


def test_the_sampled_motion_is_the_closed_form_quintic():
    """Every sample of the cycle is the quintic of 1.5 rad in 3 s, at rest at both ends."""
    report = size(ARM, sizing=QUINTIC)
    assert report.samples is not None
    path, _ = report.samples
    q, v, a = _quintic(path.t)
    for column in range(2):
        assert np.abs(path.q[:, column] - q).max() < 1e-12
        assert np.abs(path.v[:, column] - v).max() < 1e-12
        assert np.abs(path.a[:, column] - a).max() < 1e-12
    assert path.t[0] == 0.0 and path.t[-1] == pytest.approx(T, abs=1e-12)
    assert v[0] == v[-1] == 0.0 and path.q[-1] == pytest.approx([DQ, DQ], abs=1e-12)


def test_the_report_says_no_acceleration_limit_was_checked():
    """Text and JSON: the speeds were checked against the URDF's velocity limits, no acceleration limit against
    anything (none given)."""
    result = gen_robot("size", ARM, "--sizing", QUINTIC, cwd=REPO)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    header = next(k for k, line in enumerate(lines) if line.startswith("  along the motion: segments of 3 s"))
    assert lines[header + 1] == "  no acceleration limit was given, so none was checked: the durations set the motion"
    report = json.loads(gen_robot("size", ARM, "--sizing", QUINTIC, "--json", cwd=REPO).stdout)
    checked = report["motion_timing"]["limits_checked"]
    assert checked == {"velocity": ["shoulder_joint", "elbow_joint"], "acceleration": []}


CONTINUOUS = """<?xml version="1.0"?>
<robot name="free"><link name="base"/>
  <link name="arm"><inertial><origin xyz="0.5 0 0"/><mass value="2"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.2"/></inertial></link>
  <joint name="spin" type="continuous"><parent link="base"/><child link="arm"/><axis xyz="0 1 0"/></joint>
</robot>
"""


def test_without_any_limit_nothing_is_checked_and_the_header_says_so(tmp_path):
    """A continuous joint without <limit> (no velocity limit) moved by a duration alone: sized, every limit list
    empty, and the header says that no velocity or acceleration limit was checked."""
    robot, sizing = tmp_path / "free.urdf", tmp_path / "turn.yaml"
    robot.write_text(CONTINUOUS, encoding="utf-8")
    sizing.write_text(yaml.safe_dump({"motion": {"duration": 2, "waypoints": [{"spin": 0}, {"spin": 3}]}}))
    result = gen_robot("size", robot, "--sizing", sizing, "--json")
    assert result.returncode == 0, result.stderr
    report = json.loads(result.stdout)
    jsonschema.validate(report, SCHEMA)
    assert report["motion_timing"]["limits_checked"] == {"velocity": [], "acceleration": []}
    (joint,) = report["joints"]
    assert joint["motion"]["peak_speed"] == pytest.approx(15 / 8 * 3 / 2, rel=1e-9)
    assert joint["motion"]["velocity_margin"] is None
    text = gen_robot("size", robot, "--sizing", sizing).stdout.splitlines()
    said = "  no velocity or acceleration limit was given, so none was checked: the durations set the motion"
    assert said in text


def _located(tmp_path, motion: dict) -> list:
    sizing = tmp_path / "motion.yaml"
    sizing.write_text(yaml.safe_dump({"motion": motion}), encoding="utf-8")
    with pytest.raises(SpecErrors) as caught:
        size(ARM, sizing=sizing)
    result = gen_robot("size", ARM, "--sizing", sizing)
    assert result.returncode == 2 and "Traceback" not in result.stderr and result.stdout == ""
    return caught.value.errors


WAYPOINTS = [{"shoulder_joint": 0, "elbow_joint": 0}, {"shoulder_joint": 1.5, "elbow_joint": 1.5}]


@pytest.mark.parametrize(
    ("motion", "path", "words"),
    [
        # no duration: the limits set the profile, and an acceleration limit is needed (in good grammar)
        ({"waypoints": WAYPOINTS}, "$.motion", "joint 'shoulder_joint' needs an acceleration limit: give"),
        ({"waypoints": WAYPOINTS}, "$.motion", "or a `duration:` for every segment"),
        # a segment without a duration still needs it
        (
            {"waypoints": [WAYPOINTS[0], {**WAYPOINTS[1], "duration": 3}, {"elbow_joint": 0}]},
            "$.motion",
            "needs an acceleration limit",
        ),
        # a trapezoid's ramps take the acceleration limit even with a duration
        ({"waypoints": WAYPOINTS, "duration": 3, "scaling": "trapezoid"}, "$.motion", "a trapezoid's ramps"),
        # the URDF's velocity limit (1 rad/s) still bounds the duration: 15/8 * 1.5 / 1 = 2.8125 s at least
        ({"waypoints": WAYPOINTS, "duration": 2}, "$.motion.duration", "shortest the joints' limits allow is 2.8125"),
    ],
)
def test_a_limit_the_motion_still_needs_is_a_located_error(tmp_path, motion, path, words):
    errors = _located(tmp_path, motion)
    assert any(e.path == path and words in e.message and e.line is not None for e in errors), [str(e) for e in errors]
