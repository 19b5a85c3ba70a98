"""ik on a chain that moves its frame in fewer directions than a pose has (issue 43: "a wrist singularity has a
continuum: say so, give one"): example-robot-data's simple humanoid from the root to its left arm (a waist of three
axes meeting at a point, then a shoulder of three more) moves the hand in 5 of the 6 directions anywhere, so every
target it reaches has a continuum of solutions. It is no spherical-wrist arm (its first three joints cannot place the
wrist centre in finitely many ways), the numeric search gives one solution, said singular, and the command says so;
an arm built here with the same structure answers alike, and a regular arm at a singular pose does not."""

from __future__ import annotations

import json
import math
import sys

import numpy as np
import pinocchio as pin
import pytest
from test_ik_branches import dh_arm, random_targets, reposed_error, same_turns, searched

from conftest import REPO, gen_robot
from xacrokit.kinematics import ik_solver
from xacrokit.reader.read_robot import read_robot
from xacrokit.reader.robot_input import RobotInput

sys.path.insert(0, str(REPO / "tests"))
import realworld  # noqa: E402

NUMERIC = "numeric (damped least squares)"
HAND = "LARM_LINK3"


def said(frame):
    """The singularity's words, as the issue's "say so, give one" asks."""
    where = "in only 5 of the 6 directions of a pose at any configuration"
    return f"on a continuum of solutions: the joints move {frame} {where}"


@pytest.fixture(scope="module")
def humanoid():
    share = realworld.unpacked(realworld.SOURCES[0])  # (example-robot-data: installed with the test extra)
    (path,) = (p for p in share.rglob("simple_humanoid.urdf") if p.parent.parent.name == "simple_humanoid_description")
    return read_robot(RobotInput(path, packages={"example-robot-data": str(share)})), path, share


def test_the_humanoids_arm_is_no_spherical_wrist_arm_and_says_its_continuum(humanoid):
    """Five random reachable targets: every solution found, with and without every, said singular (on a
    continuum), re-posed by pinocchio onto the target to 1e-9, the list said possibly incomplete (a continuum may
    come in parts apart); an independent many-start search finds many solutions far apart for the same target."""
    robot = humanoid[0]
    solver = ik_solver(robot, HAND)
    assert solver.method == NUMERIC and solver.form is None
    for k, (_, target) in enumerate(random_targets(robot, HAND, 5, seed=7)):
        for every in (True, False):
            found = solver.solve(target, every=every)
            assert found.method == NUMERIC and not found.complete and found.closest is None
            assert found.solutions and (every or len(found.solutions) == 1)
            for solution in found.solutions:
                assert solution.singular == said(HAND)
                assert reposed_error(robot, HAND, solution.values, target) < 1e-9
        if k == 0:
            others = searched(robot, HAND, target, count=32)
            assert len(others) >= 4, others
    position = solver.solve(target, every=True, position_only=True)  # (3 of 3 directions: no continuum said)
    assert position.solutions and not any(s.singular for s in position.solutions) and not position.complete


SPHERICAL_WRIST = ((0, 0, 0, math.pi / 2), (0, 0, 0, -math.pi / 2), (0, 0.1, 0, 0))  # (axes 4 to 6 meet)
TWO_GROUPS = ((0, 0.3, 0, math.pi / 2), (0, 0, 0, -math.pi / 2), (0, 0.4, 0.25, math.pi / 2))  # (axes 1 to 3 meet)
WRIST_ON_AXIS_3 = ((0, 0.3, 0, math.pi / 2), (0, 0, 0.3, -0.6), (0, 0.4, 0, math.pi / 2))  # (the wrist centre on it)


@pytest.mark.parametrize("first", [TWO_GROUPS, WRIST_ON_AXIS_3], ids=["axes_1_2_3_meet", "wrist_centre_on_axis_3"])
def test_a_built_arm_whose_first_joints_cannot_place_the_wrist_centre_answers_alike(tmp_path, first):
    """Six-joint arms built from DH rows in frames of their own, with a spherical wrist and axes 1 and 2 meeting:
    axis 3 through that point too, or through the wrist centre. Joint 3 then keeps the wrist centre's distance from
    where axes 1 and 2 meet, the closed form's step 1 has no finite roots, and the arm moves its tool in 5
    directions: the numeric search, every solution said singular, re-posed to 1e-9."""
    robot = read_robot(dh_arm(tmp_path, "arm", [*first, *SPHERICAL_WRIST], seed=5))
    solver = ik_solver(robot, "l7")
    assert solver.method == NUMERIC
    for _, target in random_targets(robot, "l7", 3, seed=9):
        found = solver.solve(target, every=True)
        assert found.solutions and not found.complete
        for solution in found.solutions:
            assert solution.singular == said("l7")
            assert reposed_error(robot, "l7", solution.values, target) < 1e-9


def test_an_arm_whose_axis_3_misses_both_points_stays_in_closed_form(tmp_path):
    """Axes 1 and 2 meeting, axis 3 neither through that point nor through the wrist centre: the closed form (its
    shoulder of meeting axes), every branch re-posed to 1e-9 and the target's own joint values among them."""
    first = ((0, 0.3, 0, math.pi / 2), (0, 0, 0.3, -0.6), (0, 0.4, 0.2, math.pi / 2))
    robot = read_robot(dh_arm(tmp_path, "arm", [*first, *SPHERICAL_WRIST], seed=5))
    solver = ik_solver(robot, "l7")
    assert solver.method == "closed form (spherical wrist)" and solver.form.shoulder is not None
    names = [j.name for j in robot.kinematics.joints]
    for values, target in random_targets(robot, "l7", 3, seed=9):
        found = solver.solve(target, every=True)
        assert found.complete and not any(s.singular for s in found.solutions)
        assert any(same_turns(values, s.values, names) for s in found.solutions)
        assert all(reposed_error(robot, "l7", s.values, target) < 1e-9 for s in found.solutions)


def test_a_regular_arm_at_a_singular_pose_is_no_continuum(tmp_path):
    """A six-joint arm whose first three axes neither meet nor are parallel (numeric) with a spherical wrist, asked
    for a pose with wrist axes 4 and 6 in line: a singular pose, but the chain moves its frame in 6 directions
    elsewhere, so nothing is said singular and the list is the search's (may be incomplete)."""
    rows = [
        (0, 0.3, 0.1, math.pi / 2),
        (0, 0.05, 0.4, 0.3),
        (0, 0.02, 0.05, math.pi / 2),
        (0, 0.35, 0, -math.pi / 2),
        (0, 0, 0, math.pi / 2),
        (0, 0.1, 0, 0),
    ]
    robot = read_robot(dh_arm(tmp_path, "regular", rows, seed=3))
    model = robot.kinematics
    values = {"j1": 0.4, "j2": -0.7, "j3": 0.9, "j4": 0.5, "j5": 0.0, "j6": -0.2}
    pin.framesForwardKinematics(model.model, model.data, model.configuration(values))
    target = model.data.oMf[model.frame_id("l7")].homogeneous.copy()
    solver = ik_solver(robot, "l7")
    assert solver.method == NUMERIC
    found = solver.solve(target, every=True)
    assert found.solutions and not found.complete
    assert not any(s.singular for s in found.solutions)
    assert all(reposed_error(robot, "l7", s.values, target) < 1e-9 for s in found.solutions)


def test_ik_all_on_the_humanoid_says_the_continuum(humanoid):
    robot, path, share = humanoid
    (_, target), *_ = random_targets(robot, HAND, 1, seed=11)
    rpy = pin.rpy.matrixToRpy(target[:3, :3])
    to = ",".join(repr(float(v)) for v in [*target[:3, 3], *rpy])
    argv = ["ik", path, HAND, "--to", to, "--all", "--package", f"example-robot-data={share}"]
    shown = gen_robot(*argv, "--json")
    assert shown.returncode == 0, shown.stderr
    answer = json.loads(shown.stdout)
    assert answer["method"] == NUMERIC and answer["complete"] is False and answer["starts"] >= 1
    assert answer["solutions"]
    for solution in answer["solutions"]:
        assert solution["singular"] == said(HAND) and solution["error"] < 1e-9
        assert reposed_error(robot, HAND, solution["joints"], target) < 1e-9
    text = gen_robot(*argv)
    assert text.returncode == 0, text.stderr
    lines = text.stdout.splitlines()
    starts = "1 start" if answer["starts"] == 1 else f"{answer['starts']} starts"
    assert lines[0] == f"{NUMERIC}, {starts}: the list may be incomplete"
    assert lines[1].startswith("solution 1 (") and lines[2] == f"  ({said(HAND)})"
    shown_solutions = [k for k, line in enumerate(lines) if line.startswith("solution ")]
    assert len(shown_solutions) == len(answer["solutions"])
    assert all(lines[k + 1] == f"  ({said(HAND)})" for k in shown_solutions)


def planar(tmp_path, third, rail=None):
    """Links 0.3 m apart on joints about z (the third's limits ``third``), a tool 0.3 m beyond; with ``rail``, a
    prismatic joint along x of those limits before them and a spherical wrist after (a regular six-joint chain)."""
    inertial = (
        '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'
    )

    def joint(name, child, kind, axis, xyz, limits):
        return (
            f'<joint name="{name}" type="{kind}"><parent link="l{child - 1}"/><child link="l{child}"/>'
            f'<origin xyz="{xyz}"/><axis xyz="{axis}"/>'
            f'<limit lower="{limits[0]!r}" upper="{limits[1]!r}" effort="1" velocity="1"/></joint>'
        )

    if rail is None:
        joints = [
            ("j1", "0 0 1", "0 0 0", (-3, 3)),
            ("j2", "0 0 1", "0.3 0 0", (-3, 3)),
            ("j3", "0 0 1", "0.3 0 0", third),
        ]
        kinds = ["revolute"] * 3
    else:
        joints = [
            ("a", "0 0 1", "0 0 0.1", (-3, 3)),
            ("rail", "1 0 0", "0 0 0.1", rail),
            ("w1", "1 0 0", "0 0 0.1", (-3, 3)),
        ]
        joints += [
            ("w2", "0 1 0", "0 0 0", (-3, 3)),
            ("w3", "0 0 1", "0 0 0", (-3, 3)),
            ("ext", "0 0 1", "0 0 0.1", (-1, 1)),
        ]
        kinds = ["revolute", "prismatic", "revolute", "revolute", "revolute", "prismatic"]
    body = "".join(f'<link name="l{k}">{inertial}</link>' for k in range(len(joints) + 2))
    body += "".join(
        joint(n, k + 1, kind, a, x, lim) for k, ((n, a, x, lim), kind) in enumerate(zip(joints, kinds, strict=True))
    )
    last = len(joints)
    tool = f'<parent link="l{last}"/><child link="l{last + 1}"/><origin xyz="0.3 0 0"/>'
    body += f'<joint name="tool" type="fixed">{tool}</joint>'
    path = tmp_path / "planar.urdf"
    path.write_text(f'<robot name="r">{body}</robot>', encoding="utf-8")
    return read_robot(RobotInput(path)), f"l{last + 1}"


def test_a_joint_without_room_between_its_limits_counts_for_no_direction(tmp_path):
    """A planar arm of three joints whose third is held at 0 by its limits is a two-joint arm: asked for a position
    it has two isolated solutions (elbow up and down), and no continuum is said; with room for the third joint the
    arm moves the point in its 2 directions with 3 joints, and every solution is said to be on a continuum."""
    target = np.eye(4)
    target[:3, 3] = (0.5, 0.4, 0.0)
    robot, tool = planar(tmp_path, (0, 0))
    found = ik_solver(robot, tool).solve(target, every=True, position_only=True)
    assert len(found.solutions) == 2 and not any(s.singular for s in found.solutions)
    assert {math.copysign(1.0, s.values["j2"]) for s in found.solutions} == {1.0, -1.0}
    robot, tool = planar(tmp_path, (-1, 1))
    found = ik_solver(robot, tool).solve(target, every=True, position_only=True)
    assert len(found.solutions) > 2 and not found.complete
    assert all(
        s.singular.startswith(f"on a continuum of solutions: the joints move {tool} in only 2 of the 3")
        for s in found.solutions
    )


@pytest.mark.parametrize("rail", [10.0, 1e200])
def test_a_rail_of_any_length_leaves_a_regular_chain_regular(tmp_path, rail):
    """A regular six-joint chain (a turn, a rail along x, a spherical wrist, a telescope) moves its frame in all 6
    directions whatever its rail's limits: lengths of 1e200 m in the Jacobian do not overflow the count into 3."""
    robot, tool = planar(tmp_path, None, rail=(-rail, rail))
    target = np.eye(4)
    target[:3, 3] = (0.7, 0.4, 0.3)
    found = ik_solver(robot, tool).solve(target, every=True)
    assert found.solutions and not any(s.singular for s in found.solutions)
