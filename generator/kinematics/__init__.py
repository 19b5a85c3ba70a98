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
  the environment applies is -w, which is what ``size --force`` takes.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..errors import XacrokitError
from .inverse import Chain, distinct, solve, starts
from .kinematic_model import KinematicRobot, joint_values, load_kinematics

REACHED = 1e-9  # m, or the pose error's norm: a solution farther from the target than this is not one


@dataclass(frozen=True)
class Pose:
    """T_IN_FRAME (4x4) at the joint values asked, with the frames' names and what was said about the values."""

    frame: str
    in_frame: str
    matrix: np.ndarray
    values: dict[str, float]
    warnings: list[str]


@dataclass(frozen=True)
class Jacobian:
    """The 6 x n Jacobian of ``frame``'s origin in ``in_frame``'s axes, its columns' joints, and the pose it is at."""

    pose: Pose
    joints: list[str]
    matrix: np.ndarray


def _placed(robot: KinematicRobot, q: np.ndarray) -> None:
    import pinocchio as pin

    pin.framesForwardKinematics(robot.model, robot.data, q)


def _pose(robot: KinematicRobot, frame: str, in_frame: str, values: dict[str, float], warnings: list[str]) -> Pose:
    target, base = robot.frame_id(frame, "FRAME"), robot.frame_id(in_frame, "--in")
    _placed(robot, robot.configuration(values))
    matrix = robot.data.oMf[base].actInv(robot.data.oMf[target]).homogeneous
    return Pose(frame, in_frame, np.array(matrix), values, warnings)


def pose(
    path: str | os.PathLike[str],
    frame: str,
    *,
    in_frame: str | None = None,
    at: Mapping[str, str] | None = None,
    mappings: Mapping[str, str] | None = None,
    package_paths: Mapping[str, str | os.PathLike[str]] | None = None,
) -> Pose:
    """The pose of ``frame`` in ``in_frame`` (default: the root link) with the joints ``at`` (name -> value text with
    an optional unit; 0 where not given).

    Raises:
        XacrokitError: unreadable input, an unknown frame or joint (with the closest names), a value that does not
            parse.
        SpecErrors: an invalid spec (located).
    """
    robot = load_kinematics(path, mappings, package_paths=package_paths)
    values, warnings = joint_values(robot, at or {})
    return _pose(robot, frame, in_frame or robot.root, values, warnings)


def jacobian(
    path: str | os.PathLike[str],
    frame: str,
    *,
    in_frame: str | None = None,
    at: Mapping[str, str] | None = None,
    mappings: Mapping[str, str] | None = None,
    package_paths: Mapping[str, str | os.PathLike[str]] | None = None,
) -> Jacobian:
    """The geometric Jacobian of ``frame``'s origin (see the module's conventions) at the joints ``at``.

    Raises:
        as :func:`pose`.
    """
    import pinocchio as pin

    robot = load_kinematics(path, mappings, package_paths=package_paths)
    values, warnings = joint_values(robot, at or {})
    placed = _pose(robot, frame, in_frame or robot.root, values, warnings)
    q = robot.configuration(values)
    target, base = robot.frame_id(frame, "FRAME"), robot.frame_id(placed.in_frame, "--in")
    world = pin.computeFrameJacobian(robot.model, robot.data, q, target, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    world = np.asarray(world).reshape(6, robot.model.nv)  # (pinocchio gives a 1-DOF robot's as a vector)
    columns = {j.name: world[:, j.v_index].copy() for j in robot.joints}
    for follower in robot.followers:
        columns[follower.leader] = columns[follower.leader] + follower.multiplier * world[:, follower.joint.v_index]
    turn = robot.data.oMf[base].rotation.T  # (world axes -> IN's axes)
    matrix = np.array([np.concatenate([turn @ c[:3], turn @ c[3:]]) for c in columns.values()]).T
    return Jacobian(placed, [j.name for j in robot.joints], matrix.reshape(6, len(robot.joints)))


def joint_torques(jac: Jacobian, wrench: Sequence[float]) -> np.ndarray:
    """tau = J^T w for a wrench (3 forces, or 3 forces and 3 moments) the tool exerts, in the Jacobian's axes."""
    w = np.zeros(6)
    w[: len(wrench)] = wrench
    return np.asarray(jac.matrix.T @ w)


@dataclass(frozen=True)
class Solutions:
    """What ``ik`` found: the solutions (joint values by name, and the pose error left), in the order of the starts
    that found them; when there is none, the closest reach instead."""

    frame: str
    in_frame: str
    joints: list[str]
    solutions: list[tuple[dict[str, float], float]]
    closest: tuple[dict[str, float], float] | None


def _chain(robot: KinematicRobot, frame: int) -> Chain:
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
    path: str | os.PathLike[str],
    frame: str,
    to: Sequence[float],
    *,
    in_frame: str | None = None,
    position_only: bool = False,
    every: bool = False,
    mappings: Mapping[str, str] | None = None,
    package_paths: Mapping[str, str | os.PathLike[str]] | None = None,
) -> Solutions:
    """Joint values within the limits that put ``frame`` at ``to`` (x, y, z in m, then roll, pitch, yaw in rad,
    URDF's convention; 3 numbers or ``position_only``: the position only) in ``in_frame`` (default: the root link;
    it must not move with a joint). ``every``: every distinct solution of the STARTS starts, else the first found.

    Raises:
        XacrokitError: as :func:`pose`, or an ``in_frame`` that moves with a joint.
    """
    import pinocchio as pin

    from ..shared.transforms import rpy_matrix

    robot = load_kinematics(path, mappings, package_paths=package_paths)
    target_id, base = robot.frame_id(frame, "FRAME"), robot.frame_id(in_frame or robot.root, "--in")
    if robot.model.frames[base].parentJoint != 0:
        moved_by = robot.model.names[robot.model.frames[base].parentJoint]
        raise XacrokitError(f"--in {in_frame}: it moves with joint {moved_by!r}; give a frame fixed to the root")
    if not robot.joints:
        raise XacrokitError(f"{path}: the robot has no revolute, continuous or prismatic joint to move")
    position_only = position_only or len(to) == 3
    _placed(robot, robot.configuration({}))
    rotation = rpy_matrix(*to[3:6]) if not position_only else np.eye(3)
    goal = robot.data.oMf[base] * pin.SE3(rotation, np.array(to[:3], dtype=float))
    chain = _chain(robot, target_id)
    found = []
    for start in starts(chain, np.zeros(len(robot.joints))):
        values, error = solve(chain, goal, position_only=position_only, start=start)
        found.append((values, error))
        if error <= REACHED and not every:
            break
    names = [j.name for j in robot.joints]
    named = [(dict(zip(names, map(float, v), strict=True)), e) for v, e in found]
    reached = [
        (dict(zip(names, map(float, v), strict=True)), e) for v, e in distinct([f for f in found if f[1] <= REACHED])
    ]
    closest = None if reached else min(named, key=lambda item: item[1])
    return Solutions(frame, in_frame or robot.root, names, reached, closest)
