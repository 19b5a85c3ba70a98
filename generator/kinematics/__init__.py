"""Kinematics without ROS (``gen-robot pose``, ``jacobian`` and ``ik``): where a frame is in another at given joint
values, the geometric Jacobian of its origin, and the joint values that put it at a pose, with pinocchio on the robot
the one reader reads.

Conventions, stated once (docs/kinematics.md says them to users):

* a pose of FRAME in IN is the transform T_IN_FRAME: a point p given in FRAME's axes is T p in IN's; ``xyz`` is
  FRAME's origin in IN (m), ``rpy`` URDF's fixed-axis roll, pitch, yaw (R = Rz(y) Ry(p) Rx(r)), ``quat_xyzw`` the
  same rotation as a unit quaternion, scalar last (w >= 0);
* the Jacobian J (6 x n) maps the moving joints' speeds to the velocity of FRAME's origin relative to the root link:
  linear (m/s) rows first, then angular (rad/s), both in IN's axes; one column per joint one sets (a mimic joint's
  motion is added to its leader's column, times its multiplier), in the file's order;
* ``tau = J^T w``, w the wrench (force N, moment N*m, in IN's axes, at FRAME's origin) the tool exerts on the
  environment: tau is the torque each joint's motor must add to exert it (held still, gravity aside); the reaction
  the environment applies is -w, which is what ``size --load`` takes.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..errors import XacrokitError
from ..reader.kinematic_model import KinematicModel, LimitWarning, joint_values
from ..reader.read_robot import ReadRobot, read_robot
from ..reader.robot_input import RobotInput
from ..shared.transforms import rpy_matrix
from .inverse import Chain, distinct, solve, starts

Robot = ReadRobot | RobotInput | str | os.PathLike[str]  # what the functions take: a read robot (or what to read)

REACHED = 1e-9  # m, or the pose error's norm: a solution farther from the target than this is not one


@dataclass(frozen=True)
class Pose:
    """T_IN_FRAME (4x4) at the joint values asked, with the frames' names and what was said about the values."""

    frame: str
    in_frame: str
    matrix: np.ndarray
    values: dict[str, float]
    warnings: list[LimitWarning]


@dataclass(frozen=True)
class Jacobian:
    """The 6 x n Jacobian of ``frame``'s origin in ``in_frame``'s axes, its columns' joints, and the pose it is at."""

    pose: Pose
    joints: list[str]
    matrix: np.ndarray


def _placed(robot: KinematicModel, q: np.ndarray) -> None:
    import pinocchio as pin  # (heavy: pinocchio)

    pin.framesForwardKinematics(robot.model, robot.data, q)


def _pose(
    robot: KinematicModel, frame: str, in_frame: str, values: dict[str, float], warnings: list[LimitWarning]
) -> Pose:
    target, base = robot.frame_id(frame), robot.frame_id(in_frame)
    _placed(robot, robot.configuration(values))
    matrix = robot.data.oMf[base].actInv(robot.data.oMf[target]).homogeneous
    return Pose(frame, in_frame, np.array(matrix), values, warnings)


def pose(robot: Robot, frame: str, *, in_frame: str | None = None, at: Mapping[str, str] | None = None) -> Pose:
    """The pose of ``frame`` in ``in_frame`` (default: the root link) of the read ``robot`` with the joints ``at``
    (name -> value text with an optional unit; 0 where not given).

    Raises:
        UnknownName: an unknown frame or joint (with the closest names); JointValueError: a value that does not
            parse; XacrokitError: a robot the kinematics cannot take (and, given a path, unreadable input).
    """
    model = read_robot(robot).kinematics
    values, warnings = joint_values(model, at or {})
    return _pose(model, frame, in_frame or model.root, values, warnings)


def jacobian(robot: Robot, frame: str, *, in_frame: str | None = None, at: Mapping[str, str] | None = None) -> Jacobian:
    """The geometric Jacobian of ``frame``'s origin (see the module's conventions) at the joints ``at``.

    Raises:
        as :func:`pose`.
    """
    import pinocchio as pin  # (heavy: pinocchio)

    model = read_robot(robot).kinematics
    values, warnings = joint_values(model, at or {})
    placed = _pose(model, frame, in_frame or model.root, values, warnings)
    q = model.configuration(values)
    target, base = model.frame_id(frame), model.frame_id(placed.in_frame)
    world = pin.computeFrameJacobian(model.model, model.data, q, target, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    world = np.asarray(world).reshape(6, model.model.nv)  # (pinocchio gives a 1-DOF robot's as a vector)
    columns = {j.name: world[:, j.v_index].copy() for j in model.joints}
    for follower in model.followers:
        columns[follower.leader] = columns[follower.leader] + follower.multiplier * world[:, follower.joint.v_index]
    turn = model.data.oMf[base].rotation.T  # (world axes -> IN's axes)
    matrix = np.array([np.concatenate([turn @ c[:3], turn @ c[3:]]) for c in columns.values()]).T
    return Jacobian(placed, [j.name for j in model.joints], matrix.reshape(6, len(model.joints)))


def joint_torques(jac: Jacobian, wrench: Sequence[float]) -> np.ndarray:
    """tau = J^T w for a wrench (3 forces, or 3 forces and 3 moments) the tool exerts, in the Jacobian's axes."""
    w = np.zeros(6)
    w[: len(wrench)] = wrench
    return np.asarray(jac.matrix.T @ w)


class MovingFrame(XacrokitError):
    """The frame a target is given in (``frame``) moves with a joint (``joint``); the command line says which option
    named it."""

    def __init__(self, frame: str, joint: str) -> None:
        super().__init__(f"frame {frame!r} moves with joint {joint!r}; give a frame fixed to the root")
        self.frame, self.joint = frame, joint


@dataclass(frozen=True)
class Solutions:
    """What ``ik`` found: the solutions (joint values by name, and the pose error left), in the order of the starts
    that found them; when there is none, the closest reach instead."""

    frame: str
    in_frame: str
    joints: list[str]
    solutions: list[tuple[dict[str, float], float]]
    closest: tuple[dict[str, float], float] | None


def _chain(robot: KinematicModel, frame: int) -> Chain:
    columns = {j.name: [(j.v_index, 1.0)] for j in robot.joints}
    for follower in robot.followers:
        columns[follower.leader].append((follower.joint.v_index, follower.multiplier))
    lower = np.array([j.limits[0] if j.limits else -np.pi for j in robot.joints])
    upper = np.array([j.limits[1] if j.limits else np.pi for j in robot.joints])
    names = [j.name for j in robot.joints]

    def configuration(values: np.ndarray) -> np.ndarray:
        return robot.configuration(dict(zip(names, map(float, values), strict=True)))

    return Chain(robot.model, frame, list(columns.values()), lower, upper, configuration, robot.data)


def inverse_kinematics(
    robot: Robot,
    frame: str,
    to: Sequence[float],
    *,
    in_frame: str | None = None,
    position_only: bool = False,
    every: bool = False,
) -> Solutions:
    """Joint values within the limits that put ``frame`` at ``to`` (x, y, z in m, then roll, pitch, yaw in rad,
    URDF's convention; 3 numbers or ``position_only``: the position only) in ``in_frame`` (default: the root link;
    it must not move with a joint). ``every``: every distinct solution of the STARTS starts, else the first found.

    Raises:
        XacrokitError: as :func:`pose`, an ``in_frame`` that moves with a joint (:class:`MovingFrame`), or a robot
            without a joint to move.
    """
    import pinocchio as pin  # (heavy: pinocchio)

    read = read_robot(robot)
    model = read.kinematics
    target_id, base = model.frame_id(frame), model.frame_id(in_frame or model.root)
    if model.model.frames[base].parentJoint != 0:
        moved_by = model.model.names[model.model.frames[base].parentJoint]
        raise MovingFrame(in_frame or model.root, moved_by)
    if not model.joints:
        raise XacrokitError(f"{read.path}: the robot has no revolute, continuous or prismatic joint to move")
    position_only = position_only or len(to) == 3
    _placed(model, model.configuration({}))
    rotation = rpy_matrix(*to[3:6]) if not position_only else np.eye(3)
    goal = model.data.oMf[base] * pin.SE3(rotation, np.array(to[:3], dtype=float))
    chain = _chain(model, target_id)
    found = []
    for start in starts(chain, np.zeros(len(model.joints))):
        values, error = solve(chain, goal, position_only=position_only, start=start)
        found.append((values, error))
        if error <= REACHED and not every:
            break
    names = [j.name for j in model.joints]
    named = [(dict(zip(names, map(float, v), strict=True)), e) for v, e in found]
    reached = [
        (dict(zip(names, map(float, v), strict=True)), e) for v, e in distinct([f for f in found if f[1] <= REACHED])
    ]
    closest = None if reached else min(named, key=lambda item: item[1])
    return Solutions(frame, in_frame or model.root, names, reached, closest)
