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

Every answer is finite numbers: a result that overflows a float (a mimic joint's multiplier of 1e308) is refused,
saying what overflowed, never answered with inf or NaN; a mimic joint of a joint the robot does not have is refused.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..errors import XacrokitError
from ..reader.kinematic_model import (
    FollowerValueError,
    KinematicModel,
    LimitWarning,
    UnknownName,
    joint_values,
    require_leaders,
    shown,
)
from ..reader.read_robot import ReadRobot, read_robot
from ..reader.robot_input import RobotInput
from ..shared.transforms import rpy_matrix
from .inverse_solver import REACHED, IkSolver, MovingFrame, Solution, Solutions

__all__ = [
    "REACHED",
    "IkSolver",
    "Jacobian",
    "MovingFrame",
    "Pose",
    "Robot",
    "Solution",
    "Solutions",
    "ik",
    "ik_solver",
    "inverse_kinematics",
    "jacobian",
    "joint_torques",
    "pose",
]

Robot = ReadRobot | RobotInput | str | os.PathLike[str]  # what the functions take: a read robot (or what to read)


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
    matrix = np.array(robot.data.oMf[base].actInv(robot.data.oMf[target]).homogeneous)
    if not np.isfinite(matrix).all():  # (a backstop: the values and lengths taken keep every pose finite)
        raise XacrokitError(f"the pose of {frame!r} in {in_frame!r} overflows: it is not finite numbers")
    return Pose(frame, in_frame, matrix, values, warnings)


def _read(robot: Robot) -> tuple[ReadRobot, KinematicModel]:
    """The read robot and its kinematic model, a mimic joint of no joint refused (said with the file)."""
    read = read_robot(robot)
    model = read.kinematics
    try:
        require_leaders(read.view)
    except XacrokitError as exc:
        raise XacrokitError(f"{read.where}: {exc}") from None
    return read, model


@contextlib.contextmanager
def _located(read: ReadRobot) -> Iterator[None]:
    """A mimic joint's value that overflows, and a frame or joint the robot does not have, said with the file (an
    UnknownName keeps its role, name and detail: the command line says them with the option that named it)."""
    try:
        yield
    except FollowerValueError as exc:
        raise XacrokitError(f"{read.where}: {exc}") from None
    except UnknownName as exc:
        exc.args = (f"{read.where}: {exc}",)
        raise


def pose(robot: Robot, frame: str, *, in_frame: str | None = None, at: Mapping[str, str] | None = None) -> Pose:
    """The pose of ``frame`` in ``in_frame`` (default: the root link) of the read ``robot`` with the joints ``at``
    (name -> value text with an optional unit; 0 where not given).

    Raises:
        UnknownName: an unknown frame or joint (with the closest names); JointValueError: a value that does not
            parse; XacrokitError: a robot the kinematics cannot take (and, given a path, unreadable input).
    """
    read, model = _read(robot)
    with _located(read):
        values, warnings = joint_values(model, at or {})
        return _pose(model, frame, in_frame or model.root, values, warnings)


def jacobian(robot: Robot, frame: str, *, in_frame: str | None = None, at: Mapping[str, str] | None = None) -> Jacobian:
    """The geometric Jacobian of ``frame``'s origin (see the module's conventions) at the joints ``at``.

    Raises:
        as :func:`pose`.
    """
    import pinocchio as pin  # (heavy: pinocchio)

    read, model = _read(robot)
    with _located(read):
        values, warnings = joint_values(model, at or {})
        placed = _pose(model, frame, in_frame or model.root, values, warnings)
        q = model.configuration(values)
    target, base = model.frame_id(frame), model.frame_id(placed.in_frame)
    world = pin.computeFrameJacobian(model.model, model.data, q, target, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    world = np.asarray(world).reshape(6, model.model.nv)  # (pinocchio gives a 1-DOF robot's as a vector)
    columns = {j.name: world[:, j.v_index].copy() for j in model.joints}
    turn = model.data.oMf[base].rotation.T  # (world axes -> IN's axes)
    with np.errstate(over="ignore", invalid="ignore"):  # (judged below: a mimic's multiplier may overflow it)
        for follower in model.followers:
            moved = follower.multiplier * world[:, follower.joint.v_index]
            columns[follower.leader] = columns[follower.leader] + moved
        matrix = np.array([np.concatenate([turn @ c[:3], turn @ c[3:]]) for c in columns.values()]).T
    matrix = matrix.reshape(6, len(model.joints))
    for name, column in zip(columns, matrix.T, strict=True):
        if not np.isfinite(column).all():
            raise XacrokitError(f"{read.where}: the Jacobian of {frame!r} overflows: {_overflowed(model, name)}")
    return Jacobian(placed, [j.name for j in model.joints], matrix)


def _overflowed(model: KinematicModel, leader: str) -> str:
    """Why joint ``leader``'s column of the Jacobian is not finite numbers: the mimic joints that add to it."""
    followers = [f for f in model.followers if f.leader == leader]
    added = [f"{f.joint.name!r} moves {shown(f.multiplier)} times as fast" for f in followers]
    through = f" (mimic joints that follow it: {', '.join(added)})" if added else ""
    return f"the column of joint {leader!r} is beyond what a float holds{through}"


def joint_torques(jac: Jacobian, wrench: Sequence[float]) -> np.ndarray:
    """tau = J^T w for a wrench (3 forces, or 3 forces and 3 moments) the tool exerts, in the Jacobian's axes.

    Raises:
        XacrokitError: a torque beyond what a float holds (the joint and the wrench said).
    """
    w = np.zeros(6)
    w[: len(wrench)] = wrench
    with np.errstate(over="ignore", invalid="ignore"):  # (judged below)
        torques = np.asarray(jac.matrix.T @ w)
    for name, torque in zip(jac.joints, torques, strict=True):
        if not np.isfinite(torque):
            wrench_text = ", ".join(shown(v) for v in wrench)
            raise XacrokitError(
                f"tau = J^T w overflows: joint {name!r}'s torque for the wrench ({wrench_text}) is beyond what a "
                "float holds"
            )
    return torques


def _require_ranges(read: ReadRobot, model: KinematicModel) -> None:
    """What ik searches: a joint to move, each within limits that hold a value."""
    if not model.joints:
        raise XacrokitError(f"{read.where}: the robot has no revolute, continuous or prismatic joint to move")
    for joint in model.joints:
        if joint.limits is not None and joint.limits[0] > joint.limits[1]:
            lower, upper = (shown(v) for v in joint.limits)
            raise XacrokitError(
                f"{read.where}: joint {joint.name!r}: its lower limit {lower} is above its upper {upper}, so no value "
                "is within them; ik searches within the limits: swap them in its <limit>"
            )


def ik_solver(robot: Robot, frame: str, *, in_frame: str | None = None) -> IkSolver:
    """The inverse kinematics of ``frame`` with targets in ``in_frame`` (default: the root link; a frame fixed to it)
    on the read ``robot``: made once per robot, frame and ``in_frame`` (kept on the robot's kinematic model), then
    :meth:`~.inverse_solver.IkSolver.solve` answers any number of targets.

    Raises:
        XacrokitError: as :func:`pose`, an ``in_frame`` that moves with a joint (:class:`MovingFrame`), a robot
            without a joint to move, or a joint whose lower limit is above its upper (no value is within them).
    """
    return _solver(*_read(robot), frame, in_frame)


def _solver(read: ReadRobot, model: KinematicModel, frame: str, in_frame: str | None) -> IkSolver:
    """:func:`ik_solver` of the robot read (the solver kept on its kinematic model)."""
    key = (frame, in_frame or model.root)
    solver = model.solvers.get(key)
    if solver is None:
        _require_ranges(read, model)
        with _located(read):
            solver = model.solvers[key] = IkSolver(model, frame, in_frame or model.root)
    assert isinstance(solver, IkSolver)  # (the only kind kept there)
    return solver


def ik(
    robot: Robot,
    frame: str,
    target: np.ndarray | Sequence[Sequence[float]],
    *,
    in_frame: str | None = None,
    every: bool = False,
    position_only: bool = False,
) -> Solutions:
    """Joint values within the limits that put ``frame`` at ``target`` (a 4x4 pose T_IN_FRAME) on the read ``robot``:
    every branch (``every``), else the one nearest the rest pose (``ik_solver(...).solve(..., near=)`` takes other
    values). The solver is made on the first call and kept (:func:`ik_solver`): a loop over targets reads and
    prepares once.

    Raises:
        as :func:`ik_solver`; XacrokitError: a target that is no pose (not a 4x4, or its top 3x4, of finite numbers
            with a rotation in its top-left 3x3 and 0 0 0 1 below: said at once, with the file), a search whose pose
            error overflows at every start.
    """
    read, model = _read(robot)  # (read and checked once: a loop over targets pays the solve alone)
    solver = _solver(read, model, frame, in_frame)
    try:
        return solver.solve(target, every=every, position_only=position_only)
    except MovingFrame:
        raise
    except XacrokitError as exc:  # (a mimic joint's value that overflows, as :func:`_located` says it, or a search)
        raise XacrokitError(f"{read.where}: {exc}") from None


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
    it must not move with a joint): :func:`ik` with the target as numbers.

    Raises:
        as :func:`ik`.
    """
    position_only = position_only or len(to) == 3
    target = np.eye(4)
    target[:3, 3] = to[:3]
    if not position_only:
        target[:3, :3] = rpy_matrix(*to[3:6])
    return ik(robot, frame, target, in_frame=in_frame, every=every, position_only=position_only)
