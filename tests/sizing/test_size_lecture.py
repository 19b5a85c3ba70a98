"""The lecture's sizing exercises as docs/size.md works them (issue 31, item 3), each against its closed form at the
gravity the exercise states (9.81 m/s^2), written out here from the example's numbers, not from the tool:

- two-link statics with a payload (examples/robots/two_dof_arm.yaml, 1 kg at the forearm's tip): the worst holding
  torques are g times the first moments of mass with the links horizontal;
- the quintic from (0, 0) to (1.5, 1.5) rad in 3 s: peak speed 15/8 dq/T, and the energy balance
  sum of the motors' energy = change of potential energy + the damping's loss d dq^2/T * 10/7 per joint
  (the quintic's integral of s'(u)^2 is 10/7).
"""

from __future__ import annotations

import json
import math

import pytest

from conftest import REPO, gen_robot

G = 9.81
# two_dof_arm.yaml: the upper arm's centre 0.15 m up its 0.3 m, 0.5 kg; the forearm's 0.125 m up its 0.25 m, 0.3 kg
UPPER, UPPER_CENTRE, UPPER_LENGTH = 0.5, 0.15, 0.3
FORE, FORE_CENTRE = 0.3, 0.125
PAYLOAD, PAYLOAD_AT = 1.0, 0.25
DAMPING = {"shoulder_joint": 0.1, "elbow_joint": 0.05}
SHOULDER_UPPER = 1.57  # (the shoulder's limit: the upper arm never quite horizontal)


def _report(*options: str):
    result = gen_robot(
        "size",
        "examples/robots/two_dof_arm.yaml",
        "--sizing",
        "examples/sizing/two_dof_arm_lecture.yaml",
        "--json",
        *options,
        cwd=REPO,
    )
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


@pytest.fixture(scope="module")
def report():
    return _report()


def _height(q1, q2):
    """Potential energy / g: the first moment of mass about the shoulder's height."""
    return (
        UPPER * UPPER_CENTRE * math.cos(q1)
        + FORE * (UPPER_LENGTH * math.cos(q1) + FORE_CENTRE * math.cos(q1 + q2))
        + PAYLOAD * (UPPER_LENGTH * math.cos(q1) + PAYLOAD_AT * math.cos(q1 + q2))
    )


def test_the_statics_are_the_first_moments_with_the_links_horizontal(report):
    assert report["gravity"] == G
    joints = {j["name"]: j for j in report["joints"]}
    # the shoulder at its 1.57 limit, the forearm (and the payload) exactly horizontal: q1 + q2 = pi/2
    forearm_moment = FORE * FORE_CENTRE + PAYLOAD * PAYLOAD_AT
    shoulder = G * (
        (UPPER * UPPER_CENTRE + (FORE + PAYLOAD) * UPPER_LENGTH) * math.sin(SHOULDER_UPPER) + forearm_moment
    )
    assert -joints["shoulder_joint"]["static"]["peak_torque"] == pytest.approx(shoulder, rel=1e-9)
    assert -joints["elbow_joint"]["static"]["peak_torque"] == pytest.approx(G * forearm_moment, rel=1e-9)
    pose = joints["elbow_joint"]["static"]["pose"]
    assert math.cos(pose["shoulder_joint"] + pose["elbow_joint"]) == pytest.approx(0.0, abs=1e-9)


def test_the_quintic_in_3_s_peaks_at_15_8_and_balances_its_energy(report):
    # (the file gives no acceleration limit: the duration fixes the quintic, and the report says none was checked)
    checked = {"velocity": ["shoulder_joint", "elbow_joint"], "acceleration": []}
    assert report["motion_timing"] == {"segments": [3.0], "dwell": 0.0, "cycle": 3.0, "limits_checked": checked}
    joints = {j["name"]: j for j in report["joints"]}
    dq, duration = 1.5, 3.0
    for joint in joints.values():
        assert joint["motion"]["peak_speed"] == pytest.approx(15 / 8 * dq / duration, rel=1e-9)
        # (its peak falls between the 1 ms samples: 1.3e-9 below)
        assert joint["motion"]["peak_acceleration"] == pytest.approx(10 / math.sqrt(3) * dq / duration**2, rel=1e-6)
    lost = sum(d * dq**2 / duration * 10 / 7 for d in DAMPING.values())
    change = G * (_height(1.5, 1.5) - _height(0.0, 0.0))
    spent = sum(j["motion"]["energy"] for j in joints.values())
    assert spent == pytest.approx(change + lost, rel=1e-9)  # (found: 7e-15)
    assert lost == pytest.approx(0.160714, abs=1e-6) and change == pytest.approx(-9.8515, abs=1e-4)


def test_the_damping_is_what_makes_up_the_difference():
    """--no-joint-friction: the motors' energy is the potential energy's change alone."""
    joints = _report("--no-joint-friction")["joints"]
    change = G * (_height(1.5, 1.5) - _height(0.0, 0.0))
    assert sum(j["motion"]["energy"] for j in joints) == pytest.approx(change, rel=1e-9)


def test_the_winter_humanoids_hip_and_knee_hold_the_leg_level():
    """examples/robots/winter_humanoid.yaml: thigh 0.30 m, 3.0 kg; shin 0.32 m, 1.8 kg; arm 0.50 m, 1.5 kg; each
    centre halfway. With the torso held: hip g (m_t l_t/2 + m_s (l_t + l_s/2)), knee g m_s l_s/2, shoulder g m_a l_a/2,
    the same on the mirrored right side. (The chapter's humanoid, simple_humanoid.yaml, is
    tests/pipeline/test_chapter_humanoid.py's.)"""
    result = gen_robot("size", "examples/robots/winter_humanoid.yaml", "--gravity", "9.81", "--json", cwd=REPO)
    assert result.returncode == 0, result.stderr
    report = json.loads(result.stdout)
    assert report["gravity"] == G
    static = {j["name"]: -j["static"]["peak_torque"] for j in report["joints"]}
    expected = {
        "hip_joint": G * (3.0 * 0.15 + 1.8 * (0.30 + 0.16)),
        "knee_joint": G * 1.8 * 0.16,
        "shoulder_joint": G * 1.5 * 0.25,
    }
    assert len(static) == 6
    for side in ("left_", "right_"):
        for joint, torque in expected.items():
            assert static[side + joint] == pytest.approx(torque, rel=1e-9), side + joint
