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
    where = "in only 5 of the 6 directions of a pose anywhere"
    return f"a continuum of solutions: the chain moves {frame} {where}; one given"


@pytest.fixture(scope="module")
def humanoid():
    share = realworld.unpacked(realworld.SOURCES[0])  # (example-robot-data: installed with the test extra)
    (path,) = (p for p in share.rglob("simple_humanoid.urdf") if p.parent.parent.name == "simple_humanoid_description")
    return read_robot(RobotInput(path, packages={"example-robot-data": str(share)})), path, share


def test_the_humanoids_arm_is_no_spherical_wrist_arm_and_says_its_continuum(humanoid):
    """Five random reachable targets: one solution each, with and without every, said singular, the list complete
    (no isolated solution), re-posed by pinocchio onto the target to 1e-9; an independent many-start search finds
    many solutions far apart for the same target (the continuum the one stands for)."""
    robot = humanoid[0]
    solver = ik_solver(robot, HAND)
    assert solver.method == NUMERIC and solver.form is None
    for k, (_, target) in enumerate(random_targets(robot, HAND, 5, seed=7)):
        for every in (True, False):
            found = solver.solve(target, every=every)
            (solution,) = found.solutions
            assert found.method == NUMERIC and found.complete and found.closest is None
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
    directions: the numeric search, one solution said singular, re-posed to 1e-9."""
    robot = read_robot(dh_arm(tmp_path, "arm", [*first, *SPHERICAL_WRIST], seed=5))
    solver = ik_solver(robot, "l7")
    assert solver.method == NUMERIC
    for _, target in random_targets(robot, "l7", 3, seed=9):
        found = solver.solve(target, every=True)
        (solution,) = found.solutions
        assert found.complete and solution.singular == said("l7")
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
    assert answer["method"] == NUMERIC and answer["complete"] is True and answer["starts"] >= 1
    (solution,) = answer["solutions"]
    assert solution["singular"] == said(HAND) and solution["error"] < 1e-9
    assert reposed_error(robot, HAND, solution["joints"], target) < 1e-9
    text = gen_robot(*argv)
    assert text.returncode == 0, text.stderr
    lines = text.stdout.splitlines()
    starts = "1 start" if answer["starts"] == 1 else f"{answer['starts']} starts"
    assert lines[0] == f"{NUMERIC}, {starts}: every solution lies on a continuum (no isolated one); one given"
    assert lines[1].startswith("solution 1 (") and lines[2] == f"  ({said(HAND)})"
    assert not any(line.startswith("solution 2") for line in lines)
