"""The robot that ``gen-robot size`` analyses: the read robot's kinematic model (fixed base) with its moving
joints and their limits, and the loads put on it (a payload on a named frame, a force and moment on a named
frame).

Conventions, stated once (docs/size.md says them to users): gravity is 9.80665 m/s^2 along -z of the root link's
frame; a load's force and moment are what the environment applies to the robot at the frame's origin (a hanging
weight pulls down: [0, 0, -m g]), in the world's axes; a joint torque is what the joint's motor must produce to hold
the robot still against gravity and the loads, tau = g(q) - J(q)^T w.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import SpecErrors, XacrokitError
from ..reader.kinematic_model import KinematicJoint, KinematicModel, configurations
from ..reader.read_robot import ReadRobot, read_robot
from ..reader.robot_input import RobotInput
from ..shared.joint_types import MOVING
from ..shared.units import STANDARD_GRAVITY
from ..shared.urdf_view import UrdfView, joint_tree
from ..validate.physics import Implausible

GRAVITY = STANDARD_GRAVITY  # m/s^2, along -z of the root frame


@dataclass(frozen=True)
class Payload:
    """A rigid payload held by ``frame``: mass (kg), centre of mass in the frame (m), inertia about it (kg*m^2)."""

    frame: str
    mass: float
    com: tuple[float, float, float] = (0.0, 0.0, 0.0)
    inertia: tuple[float, float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # xx xy xz yy yz zz


@dataclass(frozen=True)
class Load:
    """A force (N) and moment (N*m) the environment applies to the robot at the origin of ``frame``, world axes."""

    frame: str
    force: tuple[float, float, float]
    moment: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class LoadedRobot:
    """The read robot as ``size`` analyses it: its kinematic model's pinocchio model copied with the payloads attached
    and gravity set (the read robot's own model is left as it is), every moving joint (mimic joints as joints of their
    own, pinocchio's order), the loads, and what the report says of it."""

    robot: ReadRobot
    model: Any  # pinocchio.Model: a copy, with the payloads
    data: Any  # its pinocchio.Data
    joints: tuple[KinematicJoint, ...]
    loads: tuple[tuple[int, Any], ...] = ()  # (frame id, pinocchio.Force in world axes)
    gravity: float = GRAVITY  # m/s^2, along -z of the root frame (the model's own too)
    joint_friction: bool = True  # the motion's torques include the joints' <dynamics> damping and friction
    massless: tuple[str, ...] = ()  # moving links with a shape but no <inertial>
    moved_links: tuple[str, ...] = ()  # the child links of its moving joints, in the URDF's order
    payloads: tuple[Payload, ...] = ()  # as given (the model holds them attached)
    applied: tuple[Load, ...] = ()  # the loads as given (``loads`` holds them as pinocchio forces)

    @property
    def name(self) -> str:
        return self.robot.kinematics.name

    def configuration(self, values: Sequence[float] | np.ndarray) -> np.ndarray:
        """pinocchio's q with the moving joints at ``values`` (in ``joints``' order) and the others neutral."""
        return configurations(self.model, self.joints, np.array([values], dtype=float))[0]


def joint_configurations(robot: LoadedRobot, values: np.ndarray) -> np.ndarray:
    """pinocchio's q for many rows of joint values at once (one row per sample, in ``robot.joints``' order)."""
    return configurations(robot.model, robot.joints, values)


MAX_MOVING_CHAIN = 64  # moving joints from the root to a leaf that size searches (a real arm or leg has under 10)


def moving_chain(view: UrdfView) -> int:
    """The most moving joints (revolute, continuous, prismatic) on one path from a root link to a leaf; the joints
    of a loop, which no path from a root reaches, are not counted."""
    tree = joint_tree(view)
    reached = tree.depths(tree.roots(link.name for link in view.links), lambda joint: joint.type in MOVING)
    return max(reached.values(), default=0)


def loaded_robot(
    robot: ReadRobot,
    *,
    payloads: Sequence[Payload] = (),
    loads: Sequence[Load] = (),
    gravity: float = GRAVITY,
    joint_friction: bool = True,
) -> LoadedRobot:
    """The read ``robot`` as ``size`` analyses it, with ``payloads`` attached and ``loads`` applied (``gravity``:
    m/s^2 along -z of the root frame, standard gravity unless told).

    Raises:
        XacrokitError: a chain too long to search, a robot the kinematics cannot take, no joint to size, or a frame
            the robot lacks (:class:`~xacrokit.reader.kinematic_model.UnknownName`).
    """
    import pinocchio as pin  # (heavy: pinocchio)

    longest = moving_chain(robot.view)
    if longest > MAX_MOVING_CHAIN:  # (before pinocchio, which crashes on a chain of thousands)
        raise XacrokitError(
            f"{robot.path}: a chain of {longest} moving joints; size searches each joint's worst pose over the joints "
            f"below it, work that grows with the cube of a chain's length: at most {MAX_MOVING_CHAIN} in a chain "
            "(which takes about 20 s)"
        )
    kinematics = robot.kinematics
    if not kinematics.moving:
        raise XacrokitError(f"{robot.path}: the robot has no revolute, continuous or prismatic joint to size")
    model = kinematics.model.copy()
    model.gravity = pin.Motion(np.array([0.0, 0.0, -gravity, 0.0, 0.0, 0.0]))  # (pinocchio's default: 9.81)
    for payload in payloads:
        _attach(model, kinematics, payload)
    forces = tuple(
        (kinematics.frame_id(load.frame), pin.Force(np.array(load.force, float), np.array(load.moment, float)))
        for load in loads
    )
    moved = tuple(j.child for j in robot.view.joints if j.type in MOVING and j.child is not None)
    return LoadedRobot(
        robot,
        model,
        model.createData(),
        kinematics.moving,
        forces,
        gravity,
        joint_friction,
        tuple(_massless_moving_links(model, robot.view)),
        moved,
        tuple(payloads),
        tuple(loads),
    )


def require_load(robot: LoadedRobot, where: str) -> None:
    """Refuse a robot whose torques would all be 0: no moving link has a mass, and no payload or force loads it (a
    massless arm with a payload is the lecture's model of tau = J^T F, and is sized)."""
    model = robot.model
    if robot.loads or any(model.inertias[j].mass > 0.0 for j in range(1, model.njoints)):
        return
    named = ", ".join(robot.moved_links[:10]) + (" ..." if len(robot.moved_links) > 10 else "")
    raise XacrokitError(
        f"{where}: no link a joint moves has a mass and nothing loads the robot, so every torque would be 0: give "
        f"those links a mass ({named}: `mass:` in a spec, <inertial> in a URDF), or size it with a payload "
        "or a load (a sizing file's payloads: and loads:, or the command's --payload and --load)"
    )


AS_WRITTEN = (
    "; to size the robot as written (links without mass, a payload or load carrying the weight: the lecture's "
    "tau = J^T F model), write `strict: false` at the top of the spec"
)


def read_sized(robot: ReadRobot | RobotInput | str | os.PathLike[str]) -> ReadRobot:
    """The robot ``size`` analyses, read (:func:`~xacrokit.reader.read_robot.read_robot`). A spec's values that no
    real body has (a moving link without mass, above all) are errors, as for every command; for sizing the first
    such error names the way to size the robot as written: ``strict: false``, which makes them warnings.

    Raises:
        SpecErrors: an invalid spec (located), as read_robot's, with that way out.
    """
    try:
        return read_robot(robot)
    except SpecErrors as exc:
        first = next((e for e in exc.errors if isinstance(e, Implausible)), None)
        if first is None:
            raise
        said = Implausible(
            first.message + AS_WRITTEN, file=first.file, path=first.path, line=first.line, column=first.column
        )
        raise SpecErrors([said if e is first else e for e in exc.errors]) from None


def frame_names(robot: LoadedRobot) -> list[str]:
    """The frames payloads and loads may name (links and joints)."""
    return list(robot.robot.kinematics.frames)


def _massless_moving_links(model: Any, view: UrdfView) -> list[str]:
    """The links moved by a joint that have a shape but no <inertial>, in the URDF's order (a link with neither is a
    frame, such as tool0: massless by design)."""
    shaped_without = {link.name for link in view.links if link.visuals and link.inertial is None}
    return [name for name in _moved_links(model, view) if name in shaped_without]


def _moved_links(model: Any, view: UrdfView) -> list[str]:
    """The links below a joint (pinocchio's body frames with a parent joint), in the URDF's order."""
    import pinocchio as pin  # (heavy: pinocchio)

    moving = {f.name for f in model.frames if f.type == pin.FrameType.BODY and f.parentJoint > 0}
    return [link.name for link in view.links if link.name in moving]


def _attach(model: Any, kinematics: KinematicModel, payload: Payload) -> None:
    """Add the payload's inertia to the body of the joint that carries ``payload.frame`` (in ``model``, a copy)."""
    import pinocchio as pin  # (heavy: pinocchio)

    frame = model.frames[kinematics.frame_id(payload.frame)]
    xx, xy, xz, yy, yz, zz = payload.inertia
    tensor = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]], dtype=float)
    inertia = pin.Inertia(payload.mass, np.array(payload.com, dtype=float), tensor)
    model.appendBodyToJoint(frame.parentJoint, inertia, frame.placement)
