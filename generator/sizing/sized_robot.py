"""The robot that ``gen-robot size`` analyses: a pinocchio model of a URDF, xacro document or spec (fixed base), its
moving joints with their limits, and the loads put on it (a payload on a named frame, a force and moment on a named
frame).

Conventions, stated once (docs/size.md says them to users): gravity is 9.80665 m/s^2 along -z of the root link's
frame; a load's force and moment are what the environment applies to the robot at the frame's origin (a hanging
weight pulls down: [0, 0, -m g]), in the world's axes; a joint torque is what the joint's motor must produce to hold
the robot still against gravity and the loads, tau = g(q) - J(q)^T w.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import XacrokitError
from ..shared.joint_types import MOVING
from ..shared.units import STANDARD_GRAVITY
from ..shared.urdf_view import UrdfView, joint_tree, read_view
from ..shared.value_text import did_you_mean

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
class MovingJoint:
    """A joint with one degree of freedom: its index in pinocchio's q and v, its range searched (continuous: one
    turn), and the URDF's effort and velocity limits (None where the URDF gives none)."""

    name: str
    kind: str  # revolute, continuous or prismatic
    q_index: int
    v_index: int
    lower: float
    upper: float
    effort: float | None
    velocity: float | None


@dataclass
class SizingRobot:
    """A pinocchio model with the payload attached, the moving joints, and the frames loads may name."""

    name: str
    model: Any  # pinocchio.Model
    joints: list[MovingJoint]
    massless: list[str] = field(default_factory=list)  # moving links without an <inertial>
    loads: list[tuple[int, Any]] = field(default_factory=list)  # (frame id, pinocchio.Force in world axes)
    data: Any = None  # pinocchio.Data of the model with its payloads (load_robot makes it)
    text: str = ""  # the URDF it was read from
    moved_links: list[str] = field(default_factory=list)  # the child links of its moving joints, in the URDF's order
    joint_friction: bool = True  # the motion's torques include the joints' <dynamics> damping and friction
    gravity: float = GRAVITY  # m/s^2, along -z of the root frame (the model's own: load_robot sets both)

    def configuration(self, values: Sequence[float] | np.ndarray) -> np.ndarray:
        """pinocchio's q with the moving joints at ``values`` (continuous joints as cos, sin) and others neutral."""
        import pinocchio as pin

        q = pin.neutral(self.model)
        for joint, value in zip(self.joints, values, strict=True):
            if joint.kind == "continuous":
                q[joint.q_index], q[joint.q_index + 1] = math.cos(value), math.sin(value)
            else:
                q[joint.q_index] = value
        return q


def configurations(robot: SizingRobot, values: np.ndarray) -> np.ndarray:
    """pinocchio's q for many rows of joint values at once (one row per sample): what
    :meth:`SizingRobot.configuration` makes for one, without a Python loop over the samples."""
    import pinocchio as pin

    result = np.tile(pin.neutral(robot.model), (len(values), 1))
    for column, joint in enumerate(robot.joints):
        if joint.kind == "continuous":
            result[:, joint.q_index] = np.cos(values[:, column])
            result[:, joint.q_index + 1] = np.sin(values[:, column])
        else:
            result[:, joint.q_index] = values[:, column]
    return result


MAX_MOVING_CHAIN = 64  # moving joints from the root to a leaf that size searches (a real arm or leg has under 10)


def moving_chain(view: UrdfView) -> int:
    """The most moving joints (revolute, continuous, prismatic) on one path from a root link to a leaf; the joints
    of a loop, which no path from a root reaches, are not counted."""
    tree = joint_tree(view)
    reached = tree.depths(tree.roots(link.name for link in view.links), lambda joint: joint.type in MOVING)
    return max(reached.values(), default=0)


def load_robot(
    path: str | os.PathLike[str],
    mappings: Mapping[str, str] | None = None,
    *,
    package_paths: Mapping[str, str | os.PathLike[str]] | None = None,
    payloads: Sequence[Payload] = (),
    loads: Sequence[Load] = (),
    gravity: float = GRAVITY,
) -> SizingRobot:
    """Read a URDF, xacro document or spec into the model ``size`` analyses (``gravity``: m/s^2 along -z of the root
    frame, standard gravity unless told).

    Raises:
        XacrokitError: the input cannot be read, names a frame the robot lacks, or nothing that moves has a mass.
        SpecErrors: a spec is invalid.
    """
    import pinocchio as pin

    from ..reader.robot_source import robot_text

    where = Path(path)
    with robot_text(where, mappings, package_paths, meshes=False) as (text, _):  # (pinocchio reads no mesh here)
        pass
    view = read_view(text, str(where))
    longest = moving_chain(view)
    if longest > MAX_MOVING_CHAIN:  # (before pinocchio, which crashes on a chain of thousands)
        raise XacrokitError(
            f"{where}: a chain of {longest} moving joints; size searches each joint's worst pose over the joints "
            f"below it, work that grows with the cube of a chain's length: at most {MAX_MOVING_CHAIN} in a chain "
            "(which takes about 20 s)"
        )
    try:
        model = pin.buildModelFromXML(text)
    except (RuntimeError, ValueError) as exc:
        raise XacrokitError(f"{where}: pinocchio cannot read the robot: {exc}") from None
    model.gravity = pin.Motion(np.array([0.0, 0.0, -gravity, 0.0, 0.0, 0.0]))  # (pinocchio's default: 9.81)
    joints = _moving_joints(model, view)
    massless = _massless_moving_links(model, view)
    robot = SizingRobot(
        name=view.name or where.stem, model=model, joints=joints, massless=massless, text=text, gravity=gravity
    )
    add_loads(robot, payloads, loads)
    if not joints:
        raise XacrokitError(f"{where}: the robot has no revolute, continuous or prismatic joint to size")
    robot.moved_links = [j.child for j in view.joints if j.type in MOVING and j.child is not None]
    return robot


def require_load(robot: SizingRobot, where: str) -> None:
    """Refuse a robot whose torques would all be 0: no moving link has a mass, and no payload or force loads it (a
    massless arm with a payload is the lecture's model of tau = J^T F, and is sized)."""
    model = robot.model
    if robot.loads or any(model.inertias[j].mass > 0.0 for j in range(1, model.njoints)):
        return
    named = ", ".join(robot.moved_links[:10]) + (" ..." if len(robot.moved_links) > 10 else "")
    raise XacrokitError(
        f"{where}: no link a joint moves has a mass and nothing loads the robot, so every torque would be 0: give "
        f"those links a mass ({named}: `mass:` in a spec, <inertial> in a URDF), or size it with a payload "
        "(--payload, payloads:) or a force (--force, loads:)"
    )


def add_loads(robot: SizingRobot, payloads: Sequence[Payload] = (), loads: Sequence[Load] = ()) -> None:
    """Attach payloads to the bodies that carry their frames and register the loads (then make the model's data
    anew). Raises XacrokitError for a frame the robot lacks."""
    import pinocchio as pin

    for payload in payloads:
        _attach(robot, payload)
    for load in loads:
        frame = _frame_id(robot, load.frame, "--force")
        robot.loads.append((frame, pin.Force(np.array(load.force, dtype=float), np.array(load.moment, dtype=float))))
    robot.data = robot.model.createData()


def frame_names(robot: SizingRobot) -> list[str]:
    """The frames payloads and loads may name (links and joints)."""
    return [f.name for f in robot.model.frames if f.name != "universe"]


def _moving_joints(model: Any, view: UrdfView) -> list[MovingJoint]:
    limits = {j.name: j.limit for j in view.joints}
    kinds = {j.name: j.type or "" for j in view.joints}
    found = []
    for index in range(1, model.njoints):
        name = model.names[index]
        if model.nvs[index] != 1 or kinds.get(name) not in ("revolute", "continuous", "prismatic"):
            continue  # (a floating or planar root stays at its neutral pose: a fixed base is sized)
        limit = limits.get(name)
        kind = kinds[name]
        lower, upper = (-math.pi, math.pi) if kind == "continuous" else _bounds(limit)
        found.append(
            MovingJoint(
                name=name,
                kind=kind,
                q_index=model.idx_qs[index],
                v_index=model.idx_vs[index],
                lower=lower,
                upper=upper,
                effort=_given(limit, "effort"),
                velocity=_given(limit, "velocity"),
            )
        )
    return found


def _bounds(limit: Mapping[str, str] | None) -> tuple[float, float]:
    """A joint's range: its limits, or one turn either way where the URDF gives none."""
    try:
        lower, upper = float((limit or {}).get("lower", "")), float((limit or {}).get("upper", ""))
    except ValueError:
        return -math.pi, math.pi
    return (lower, upper) if lower <= upper else (upper, lower)


def _given(limit: Mapping[str, str] | None, key: str) -> float | None:
    """A limit's effort or velocity; None when not given or not a number >= 0 (a limit of 0 is a limit: its margin
    is 0, not "no limit")."""
    try:
        value = float((limit or {}).get(key, ""))
    except ValueError:
        return None
    return value if 0 <= value < math.inf else None


def _massless_moving_links(model: Any, view: UrdfView) -> list[str]:
    """The links moved by a joint that have a shape but no <inertial>, in the URDF's order (a link with neither is a
    frame, such as tool0: massless by design)."""
    shaped_without = {link.name for link in view.links if link.visuals and link.inertial is None}
    return [name for name in _moved_links(model, view) if name in shaped_without]


def _moved_links(model: Any, view: UrdfView) -> list[str]:
    """The links below a joint (pinocchio's body frames with a parent joint), in the URDF's order."""
    import pinocchio as pin

    moving = {f.name for f in model.frames if f.type == pin.FrameType.BODY and f.parentJoint > 0}
    return [link.name for link in view.links if link.name in moving]


def _frame_id(robot: SizingRobot, name: str, option: str) -> int:
    model = robot.model
    if not model.existFrame(name):
        raise XacrokitError(f"{option}: the robot has no frame {name!r}{did_you_mean(name, frame_names(robot))}")
    return int(model.getFrameId(name))


def _attach(robot: SizingRobot, payload: Payload) -> None:
    """Add the payload's inertia to the body of the joint that carries ``payload.frame``."""
    import pinocchio as pin

    frame = robot.model.frames[_frame_id(robot, payload.frame, "--payload")]
    xx, xy, xz, yy, yz, zz = payload.inertia
    tensor = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]], dtype=float)
    inertia = pin.Inertia(payload.mass, np.array(payload.com, dtype=float), tensor)
    robot.model.appendBodyToJoint(frame.parentJoint, inertia, frame.placement)
