"""gen-robot ik (issue 29, item 3): the two-link arm's two elbow branches against the closed form; every solution on
the UR5 and the humanoid re-posed by `pose` within 1e-9 of its target; an unreachable target exits 1 with the closest
reach; bad targets are errors."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import REPO, gen_robot
from xacrokit.kinematics import inverse_kinematics, pose
from xacrokit.shared.transforms import rpy_matrix

PLANAR = REPO / "examples" / "robots" / "planar_2dof.yaml"
UR5 = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
L1, L2, HEIGHT = 0.6, 0.4, 0.06


@settings(max_examples=15, deadline=None)
@given(reach=st.floats(0.35, 0.95), bearing=st.floats(-math.pi, math.pi))  # (|q2| <= 150 deg: r >= 0.323)
def test_the_two_link_arm_has_both_elbow_branches(reach, bearing):
    """q2 = +-acos((r^2 - L1^2 - L2^2) / (2 L1 L2)), q1 = atan2(y, x) - atan2(L2 sin q2, L1 + L2 cos q2): the
    textbook's two solutions, both within the joints' limits here, both found with --all (1e-9)."""
    x, y = reach * math.cos(bearing), reach * math.sin(bearing)
    found = inverse_kinematics(PLANAR, "tool_link", [x, y, HEIGHT], every=True)
    elbow = math.acos((reach**2 - L1**2 - L2**2) / (2 * L1 * L2))
    expected = []
    for q2 in (elbow, -elbow):
        q1 = math.atan2(y, x) - math.atan2(L2 * math.sin(q2), L1 + L2 * math.cos(q2))
        expected.append((math.remainder(q1, 2 * math.pi), q2))
    got = [(s.values["joint_1"], s.values["joint_2"]) for s in found.solutions]
    for q1, q2 in expected:
        assert any(abs(math.remainder(a - q1, 2 * math.pi)) < 1e-9 and abs(b - q2) < 1e-9 for a, b in got), (
            expected,
            got,
        )


def test_every_ur5_solution_reposes_onto_its_target():
    """A pose the UR5 reaches at random joint values: every distinct solution, re-posed by pose, is on it within
    1e-9 in position and orientation."""
    rng = np.random.default_rng(5)
    names = [
        "shoulder_pan_joint",
        "shoulder_lift_joint",
        "elbow_joint",
        "wrist_1_joint",
        "wrist_2_joint",
        "wrist_3_joint",
    ]
    values = dict(zip(names, map(float, rng.uniform(-2.5, 2.5, 6)), strict=True))
    goal = pose(UR5, "tool0", at={k: repr(v) for k, v in values.items()}).matrix
    import pinocchio as pin

    rpy = pin.rpy.matrixToRpy(goal[:3, :3])
    found = inverse_kinematics(UR5, "tool0", [*goal[:3, 3], *rpy], every=True)
    assert len(found.solutions) >= 2
    for solution in found.solutions:
        assert solution.error < 1e-9
        again = pose(UR5, "tool0", at={k: repr(v) for k, v in solution.values.items()}).matrix
        assert np.abs(again[:3, 3] - goal[:3, 3]).max() < 1e-9
        assert np.abs(again[:3, :3] - goal[:3, :3]).max() < 1e-9


def test_position_only_and_a_target_in_a_frame_fixed_to_the_root():
    found = inverse_kinematics(UR5, "tool0", [0.3, 0.2, 0.4], in_frame="base_link")
    first, *_ = found.solutions
    again = pose(UR5, "tool0", in_frame="base_link", at={k: repr(v) for k, v in first.values.items()}).matrix
    assert first.error < 1e-9 and np.abs(again[:3, 3] - [0.3, 0.2, 0.4]).max() < 1e-9


def test_ik_as_a_command(tmp_path):
    shown = gen_robot("ik", PLANAR, "tool_link", "--to", "0.5196152422706632,0.7,60mm", "--all", "--json")
    assert shown.returncode == 0, shown.stderr
    said = json.loads(shown.stdout)
    assert len(said["solutions"]) == 2 and all(s["error"] < 1e-9 for s in said["solutions"])
    assert {round(s["joints"]["joint_2"], 9) for s in said["solutions"]} == {
        round(math.pi / 3, 9),
        -round(math.pi / 3, 9),
    }
    far = gen_robot("ik", PLANAR, "tool_link", "--to", "2,0.7,0.06")
    assert far.returncode == 1 and "out of reach: the closest tool_link comes is 1.1" in far.stdout
    # the closest reach: 1 m of arm towards a point 2.119 m away (1e-3: damped least squares stops near it)
    closest = json.loads(gen_robot("ik", PLANAR, "tool_link", "--to", "2,0.7,0.06", "--json").stdout)["closest"]
    assert abs(closest["error"] - (math.hypot(2, 0.7) - 1.0)) < 1e-3


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--to", "1,2"], "give X,Y,Z (m), or X,Y,Z and the 3 numbers of the orientation"),
        (["--to", "1,2,3 parsec"], "--to '1,2,3 parsec'"),
        (["--to", "0.3,0,0", "--in", "link_2"], "it moves with joint 'joint_2'"),
    ],
)
def test_a_bad_target_is_a_clear_error(argv, words):
    result = gen_robot("ik", PLANAR, "tool_link", *argv)
    assert result.returncode == 2 and "Traceback" not in result.stderr and words in result.stderr, result.stderr


def test_rpy_matrix_is_urdfs():  # (the target's orientation is read as URDF's rpy: R = Rz(y) Ry(p) Rx(r))
    r, p, y = 0.1, 0.2, 0.3
    rz = np.array([[math.cos(y), -math.sin(y), 0], [math.sin(y), math.cos(y), 0], [0, 0, 1]])
    ry = np.array([[math.cos(p), 0, math.sin(p)], [0, 1, 0], [-math.sin(p), 0, math.cos(p)]])
    rx = np.array([[1, 0, 0], [0, math.cos(r), -math.sin(r)], [0, math.sin(r), math.cos(r)]])
    assert np.abs(rpy_matrix(r, p, y) - rz @ ry @ rx).max() < 1e-15


def _write(tmp_path, name, body):
    path = tmp_path / name
    path.write_text(f'<robot name="r">{body}</robot>', encoding="utf-8")
    return path


REVOLUTE = '<axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/>'


def test_a_robot_of_one_joint_has_a_jacobian_and_inverse_kinematics(tmp_path):
    """pinocchio gives a 1-DOF robot's Jacobian as a vector (once an IndexError, exit 70: a review found it)."""
    from xacrokit.kinematics import jacobian

    one = _write(
        tmp_path,
        "one.urdf",
        '<link name="base"/><link name="arm"/><link name="tip"/>'
        f'<joint name="j" type="revolute"><parent link="base"/><child link="arm"/>{REVOLUTE}</joint>'
        '<joint name="t" type="fixed"><parent link="arm"/><child link="tip"/><origin xyz="0.5 0 0"/></joint>',
    )
    jac = jacobian(one, "tip", at={"j": "90deg"})
    assert np.abs(jac.matrix[:, 0] - [-0.5, 0, 0, 0, 0, 1]).max() < 1e-12
    first, *_ = inverse_kinematics(one, "tip", [0, 0.5, 0]).solutions
    assert abs(first.values["j"] - math.pi / 2) < 1e-9 and first.error < 1e-9


def test_a_chain_of_mimics_follows_the_joint_at_its_end_and_a_loop_is_refused(tmp_path):
    """j3 follows j2, which follows j1: j3 = 2 j2 + 0.1 = 2 (3 j1) + 0.1. A loop of mimics is an error, not exit 70."""
    from xacrokit.errors import XacrokitError
    from xacrokit.kinematics import jacobian

    def chain(mimic_of_j1: str) -> str:
        return (
            '<link name="a"/><link name="b"/><link name="c"/><link name="d"/>'
            f'<joint name="j1" type="revolute"><parent link="a"/><child link="b"/>{REVOLUTE}{mimic_of_j1}</joint>'
            f'<joint name="j2" type="revolute"><parent link="b"/><child link="c"/><origin xyz="1 0 0"/>{REVOLUTE}'
            '<mimic joint="j1" multiplier="3"/></joint>'
            f'<joint name="j3" type="revolute"><parent link="c"/><child link="d"/><origin xyz="1 0 0"/>{REVOLUTE}'
            '<mimic joint="j2" multiplier="2" offset="0.1"/></joint>'
        )

    urdf = _write(tmp_path, "chain.urdf", chain(""))
    found = pose(urdf, "d", at={"j1": "0.1"}).matrix
    assert abs(math.atan2(found[1, 0], found[0, 0]) - (0.1 + 0.3 + 0.7)) < 1e-12
    assert jacobian(urdf, "d", at={"j1": "0.1"}).joints == ["j1"]
    loop = _write(tmp_path, "loop.urdf", chain('<mimic joint="j3"/>'))
    with pytest.raises(XacrokitError, match="follow each other in a loop"):
        pose(loop, "d")


def test_what_the_kinematics_commands_cannot_take_is_said(tmp_path):
    """More degrees of freedom than MAX_DOF (pinocchio's data grows with their cube: 1.8 GB at 300), a robot with
    nothing to move, a target beyond 1e4 m: exit 2 with the reason."""
    links = "".join(f'<link name="l{k}"/>' for k in range(160))
    joints = "".join(
        f'<joint name="j{k}" type="revolute"><parent link="l{k - 1}"/><child link="l{k}"/>{REVOLUTE}</joint>'
        for k in range(1, 160)
    )
    many = _write(tmp_path, "many.urdf", links + joints)
    result = gen_robot("pose", many, "l159")
    assert (
        result.returncode == 2 and "159 degrees of freedom; the kinematics commands take at most 150" in result.stderr
    )
    still = _write(
        tmp_path,
        "still.urdf",
        '<link name="a"/><link name="b"/><joint name="f" type="fixed"><parent link="a"/><child link="b"/></joint>',
    )
    result = gen_robot("ik", still, "b", "--to", "0,0,0")
    assert result.returncode == 2 and "no revolute, continuous or prismatic joint to move" in result.stderr
    far = gen_robot("ik", PLANAR, "tool_link", "--to", "1e300,0,0")
    assert far.returncode == 2 and "beyond what xacrokit takes" in far.stderr
