"""The static part of ``gen-robot size``: for every moving joint, the largest torque its motor must produce to hold the
robot still anywhere in the joints' ranges, and the pose where it is needed.

tau(q) = g(q) - J(q)^T w: the generalized gravity (pinocchio's computeGeneralizedGravity, the payload included) and
the joint torques of the loads (each load's frame Jacobian in world axes at the frame's origin, transposed, times its
force and moment; written apart, so that a user sees what the tool force costs).

The worst case of joint i is a search, not a formula: |tau_i| over the box of the joints' ranges is sampled (uniform
random samples from a fixed seed, the box's corners and centre, every joint at its range's ends and middle) and the best
samples are refined by bounded quasi-Newton steps (scipy's L-BFGS-B). A pose in the interior is a stationary point of
tau_i; the search finds the global one when a sample lands in its basin, which the tests check against dense grids.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from .sized_robot import LoadedRobot

SAMPLES_PER_JOINT = 256  # uniform random samples per moving joint (seeded: the same search every run), capped
MAX_SAMPLES = 8192
STARTS = 6  # best samples refined per joint
STEP = 1e-6  # rad or m: the central differences' step
ZERO = 1e-12  # a peak below this fraction of the largest torque sampled is rounding (a vertical axis): said as 0


@dataclass(frozen=True)
class StaticPeak:
    """The worst static case of one joint: its torque there (signed: what the motor produces), the pose (every moving
    joint's value) and the loads' share of the torque (-J^T w)."""

    joint: str
    torque: float
    pose: dict[str, float]
    gravity_torque: float
    load_torque: float
    # the joints whose value changes this torque (the others may be anything): what the table shows of the pose
    moving_it: tuple[str, ...] = ()

    @property
    def need(self) -> float:
        """What the joint's motor must be able to produce: the peak's magnitude. (``torque`` keeps its sign, the
        direction about the joint's own axis at ``pose``: where both directions need as much, either may be the
        one found, as for the two joints of a mirrored pair.)"""
        return abs(self.torque)

    @property
    def loads_need(self) -> float:
        """The loads' part of :attr:`need`: ``load_torque`` taken in the peak's direction (negative where the loads
        relieve the motor)."""
        return math.copysign(1.0, self.torque) * self.load_torque + 0.0  # (+ 0.0: no -0)


def torques(robot: LoadedRobot, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(gravity, loads) joint torques of the moving joints at ``values``: g(q) and -J(q)^T w."""
    import pinocchio as pin  # (heavy: pinocchio)

    model, data = robot.model, robot.data
    q = robot.configuration(values)
    rows = [j.v_index for j in robot.joints]
    gravity = pin.computeGeneralizedGravity(model, data, q)[rows]
    loads = np.zeros(len(rows))
    if robot.loads:
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacements(model, data)
        for frame, force in robot.loads:
            jacobian = pin.getFrameJacobian(model, data, frame, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
            loads -= (jacobian.T @ force.vector)[rows]
    return gravity, loads


def gravity_gradient(robot: LoadedRobot, values: np.ndarray) -> np.ndarray:
    """d g / d q of the moving joints at ``values`` (row: the torque, column: the joint), pinocchio's
    computeGeneralizedGravityDerivatives (for a continuous joint, along its angle)."""
    import pinocchio as pin  # (heavy: pinocchio)

    rows = [j.v_index for j in robot.joints]
    derivative = pin.computeGeneralizedGravityDerivatives(robot.model, robot.data, robot.configuration(values))
    return np.asarray(derivative)[np.ix_(rows, rows)]


def static_peaks(robot: LoadedRobot, *, seed: int = 0) -> list[StaticPeak]:
    """The worst static torque of every moving joint over the joints' ranges (see the module's notes)."""
    from scipy.optimize import minimize  # (heavy: scipy)

    joints = robot.joints
    lower = np.array([j.span[0] for j in joints])
    upper = np.array([j.span[1] for j in joints])
    count = min(MAX_SAMPLES, SAMPLES_PER_JOINT * len(joints))
    unit = np.random.default_rng(seed).random((count, len(joints)))
    samples = [*(lower + unit * (upper - lower)), *_landmarks(lower, upper)]
    table = np.array([np.add(*torques(robot, s)) for s in samples])
    peaks = []
    for index, joint in enumerate(joints):

        def cost(values: np.ndarray, index: int = index) -> tuple[float, np.ndarray]:
            """-|tau_i| and its gradient: pinocchio's derivatives of the generalized gravity without loads, central
            differences with them (exact to O(h^2) = 1e-12: the search stops on the true maximum)."""
            value = float(np.add(*torques(robot, values))[index])
            if robot.loads:
                gradient = np.empty(len(values))
                for k in range(len(values)):
                    step = np.zeros(len(values))
                    step[k] = STEP
                    ahead = float(np.add(*torques(robot, values + step))[index])
                    behind = float(np.add(*torques(robot, values - step))[index])
                    gradient[k] = (ahead - behind) / (2 * STEP)
            else:
                gradient = gravity_gradient(robot, values)[index]
            return -abs(value), -math.copysign(1.0, value) * gradient

        best = np.argsort(-np.abs(table[:, index]))[:STARTS]
        found = [samples[k] for k in best]
        for start in list(found):
            result = minimize(
                cost,
                start,
                jac=True,
                method="L-BFGS-B",
                bounds=list(zip(lower, upper, strict=True)),
                options={"ftol": 1e-15, "gtol": 1e-12},
            )
            found.append(np.clip(result.x, lower, upper))
        pose = max(found, key=lambda values: -cost(values)[0])
        gravity, loads = torques(robot, pose)
        scale = max(float(np.abs(table).max()), 1e-300)
        if abs(gravity[index] + loads[index]) <= ZERO * scale:  # (a joint gravity never loads: rounding, not torque)
            gravity[index] = loads[index] = 0.0
        torque = float(gravity[index] + loads[index])
        peaks.append(
            StaticPeak(
                joint=joint.name,
                torque=torque,
                pose={j.name: float(v) for j, v in zip(joints, pose, strict=True)},
                gravity_torque=float(gravity[index]),
                load_torque=float(loads[index]),
                moving_it=_moving_it(robot, pose, index, (lower, upper), ZERO * scale) if torque else (),
            )
        )
    return peaks


def _moving_it(
    robot: LoadedRobot, pose: np.ndarray, index: int, ranges: tuple[np.ndarray, np.ndarray], tolerance: float
) -> tuple[str, ...]:
    """The joints whose value changes joint ``index``'s torque from ``pose``: each tried at the ends and the middle
    of its range, the others held (a shoulder pan about the vertical changes no gravity torque: it is left out)."""
    here = float(np.add(*torques(robot, pose))[index])
    found = []
    for k, joint in enumerate(robot.joints):
        for value in (ranges[0][k], ranges[1][k], (ranges[0][k] + ranges[1][k]) / 2):
            moved = pose.copy()
            moved[k] = value
            if abs(float(np.add(*torques(robot, moved))[index]) - here) > tolerance:
                found.append(joint.name)
                break
    return tuple(found)


def _landmarks(lower: np.ndarray, upper: np.ndarray) -> list[np.ndarray]:
    """The centre of the range box, each joint at its ends and middle with the others centred, and the corners (all
    of them up to 10 joints): where gravity torques of arms often peak (links stretched out at a limit)."""
    centre = (lower + upper) / 2
    points = [centre]
    for k in range(len(lower)):
        for value in (lower[k], upper[k]):
            point = centre.copy()
            point[k] = value
            points.append(point)
    if len(lower) <= 10:
        points += [np.array(c) for c in itertools.product(*zip(lower, upper, strict=True))]
    return points
