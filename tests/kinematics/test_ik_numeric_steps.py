"""The numeric search's steps on the Panda (issue 43: at least 99.5% of random reachable targets): the step that
holds the joints it would take past a limit and the starts chosen with the rotation weighed less, against the plain
damped least-squares step they replaced, on the same 1,000 targets. Counts of starts and of poses evaluated, never
times."""

from __future__ import annotations

import math
import sys

import numpy as np
import pinocchio as pin

from conftest import REPO
from xacrokit.kinematics import ik_solver, inverse, inverse_solver
from xacrokit.reader.read_robot import read_robot
from xacrokit.reader.robot_input import RobotInput

sys.path.insert(0, str(REPO / "tests"))
import realworld  # noqa: E402

TARGETS = 1000


def plain_solve(chain, target, *, position_only, start, iterations=inverse.ITERATIONS):
    """The search as it was: each step the damped least-squares step on every joint, shortened to LONGEST_STEP and
    clipped at the limits joint by joint (a clipped joint's share of the step lost)."""
    values = np.clip(np.array(start, dtype=float), chain.lower, chain.upper)
    error, best = math.inf, (math.inf, 0)
    for count in range(iterations):
        residual, full = inverse.residual_and_jacobian(chain, target, values, position_only=position_only)
        error = math.sqrt(float(residual @ residual))
        if not inverse.TOLERANCE <= error < math.inf:
            break
        part = chain.selected(full)
        normal = part @ part.T + (1e-12 + 1e-3 * error) * np.eye(len(residual))
        step = -part.T @ np.linalg.solve(normal, residual)
        if error < 0.5 * best[0]:
            best = (error, count)
        elif count - best[1] > inverse.STALL:
            break
        largest = np.abs(step).max()
        if largest > inverse.LONGEST_STEP:
            step *= inverse.LONGEST_STEP / largest
        values = np.clip(values + step, chain.lower, chain.upper)
    return values, error


def searched(robot, targets, monkeypatch, *, plain):
    """Solutions found, starts run and poses evaluated over ``targets``, each answer re-posed by pinocchio."""
    model = robot.kinematics
    frame = model.frame_id("panda_hand")
    evaluated = [0]
    evaluate = inverse.residual_and_jacobian

    def counted(*args, **kwargs):
        evaluated[0] += 1
        return evaluate(*args, **kwargs)

    with monkeypatch.context() as patch:
        patch.setattr(inverse, "residual_and_jacobian", counted)
        if plain:
            patch.setattr(inverse_solver, "solve", plain_solve)
            patch.setattr(inverse_solver, "TURNS_WEIGHT", 1.0)
        solver = ik_solver(robot, "panda_hand")
        solved = starts = 0
        for target in targets:
            found = solver.solve(target)
            starts += found.starts
            for solution in found.solutions:
                pin.framesForwardKinematics(model.model, model.data, model.configuration(solution.values))
                error = np.linalg.norm(pin.log6(pin.SE3(target).actInv(model.data.oMf[frame])).vector)
                assert error < 1e-9
                assert all(j.limits[0] <= solution.values[j.name] <= j.limits[1] for j in model.joints)
            solved += bool(found.solutions)
    return solved, starts, evaluated[0]


def test_the_panda_search_solves_as_many_targets_in_fewer_starts_and_steps(monkeypatch):
    share = realworld.unpacked(realworld.SOURCES[0])  # (example-robot-data: installed with the test extra)
    path = share / "robots" / "panda_description" / "urdf" / "panda.urdf"
    robot = read_robot(RobotInput(path, packages={"example-robot-data": str(share)}))
    model = robot.kinematics
    frame = model.frame_id("panda_hand")
    rng = np.random.default_rng(2026)
    targets = []
    for _ in range(TARGETS):
        values = {j.name: float(rng.uniform(*j.span)) for j in model.joints}
        pin.framesForwardKinematics(model.model, model.data, model.configuration(values))
        targets.append(model.data.oMf[frame].homogeneous.copy())
    solved, starts, evaluated = searched(robot, targets, monkeypatch, plain=False)
    plain_solved, plain_starts, plain_evaluated = searched(robot, targets, monkeypatch, plain=True)
    assert solved >= 0.995 * TARGETS and solved >= plain_solved, (solved, plain_solved)
    assert starts < plain_starts and evaluated < plain_evaluated, (starts, plain_starts, evaluated, plain_evaluated)
