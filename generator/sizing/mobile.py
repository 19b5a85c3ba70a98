"""The mobile-base part of ``gen-robot size``: what each driven wheel's motor must deliver for the robot to reach a
speed and an acceleration up a slope, with rolling resistance.

The closed form (every driven wheel sharing the effort equally, rolling without slip):

- traction force F = m a + m g sin(theta) + C_rr m g cos(theta), m the whole robot's mass (payloads included);
- each wheel's torque tau = F r / n + I_w a / r (its share of F at its radius, and its own spin-up: I_w its inertia
  about the axle);
- each wheel's speed omega = v / r, its power tau omega at the top speed (the acceleration still applied: the
  conservative corner of the speed-torque plane), and the whole drive's power n tau omega.

Beside it, a check by dynamics: pinocchio's inverse dynamics of the whole robot on a free-flyer root, accelerated up
the slope with gravity turned by it, needs m a + m g sin(theta) along the slope (``dynamics_force``; the report
shows both).

Wheels are the continuous joints whose child link is drawn with a cylinder (its radius is the wheel's), unless the
sizing file names them.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..reader.kinematic_model import unit_axis
from .sized_robot import GRAVITY, LoadedRobot


@dataclass(frozen=True)
class BaseMotion:
    """What the sizing file asks of a mobile base: speed (m/s), acceleration (m/s^2), slope (rad), rolling
    resistance coefficient, and the wheels (joint names; empty: found)."""

    speed: float
    acceleration: float
    slope: float = 0.0
    rolling_resistance: float = 0.0
    wheels: tuple[str, ...] = ()


@dataclass(frozen=True)
class Wheel:
    joint: str
    radius: float  # m
    inertia: float  # kg*m^2 about the axle
    effort: float | None
    velocity: float | None


@dataclass(frozen=True)
class BaseSizing:
    """The base's figures: the robot's mass, the traction force, and per wheel torque, speed and power."""

    mass: float
    force: float
    wheels: tuple[Wheel, ...]
    torques: tuple[float, ...]
    speeds: tuple[float, ...]
    powers: tuple[float, ...]
    dynamics_force: float = math.nan  # the check: m a + m g sin(theta) from pinocchio's rnea on a free-flyer root

    @property
    def power(self) -> float:
        return math.fsum(self.powers)


def find_wheels(robot: LoadedRobot, named: Sequence[str] = ()) -> list[Wheel]:
    """The wheels: continuous joints whose child link has a cylinder (or those ``named``), with radius, inertia about
    the axle (pinocchio's body inertia, moved to the joint's axis) and limits."""

    view = robot.robot.view
    radii = {}
    for link in view.links:  # (its first cylinder collision's radius, else its first cylinder visual's)
        cylinders = [g.shape for g in (*link.collisions, *link.visuals) if g.shape and g.shape.kind == "cylinder"]
        if cylinders and cylinders[0].get("radius"):
            radii[link.name] = float(cylinders[0].get("radius") or "")
    children = {j.name: j.child for j in view.joints if j.child is not None}
    declared = {j.name: j for j in view.joints}
    found = []
    for joint in robot.joints:
        child = children.get(joint.name)
        wanted = joint.name in named if named else joint.kind == "continuous" and child in radii
        if not wanted or child not in radii:
            continue
        axis = unit_axis(declared[joint.name])
        body = robot.model.inertias[robot.model.getJointId(joint.name)]
        lever = np.asarray(body.lever)
        about_origin = np.asarray(body.inertia) + body.mass * (lever @ lever * np.eye(3) - np.outer(lever, lever))
        found.append(Wheel(joint.name, radii[child], float(axis @ about_origin @ axis), joint.effort, joint.velocity))
    return found


def whole_mass(free_floating: Any, extra: float) -> float:
    """The robot's mass: every link's (its model on a free-flyer root, so that the root link counts) plus
    ``extra``."""
    import pinocchio as pin  # (heavy: pinocchio)

    return float(pin.computeTotalMass(free_floating)) + extra


def size_base(drive: BaseMotion, wheels: Sequence[Wheel], mass: float, gravity: float = GRAVITY) -> BaseSizing:
    """The closed form of the module's notes (``gravity`` in m/s^2)."""
    force = mass * drive.acceleration + mass * gravity * (
        math.sin(drive.slope) + drive.rolling_resistance * math.cos(drive.slope)
    )
    share = force / len(wheels)
    torques = tuple(share * w.radius + w.inertia * drive.acceleration / w.radius for w in wheels)
    speeds = tuple(drive.speed / w.radius for w in wheels)
    powers = tuple(t * s for t, s in zip(torques, speeds, strict=True))
    return BaseSizing(mass, force, tuple(wheels), torques, speeds, powers)


def dynamics_force(free_floating: Any, drive: BaseMotion, extra: float, gravity: float = GRAVITY) -> float:
    """The check beside the closed form: the force along the slope that pinocchio's inverse dynamics needs on a
    free-flyer root to accelerate the whole robot (joints still, ``extra`` kg of payload on the root) at ``a`` up
    the slope, gravity turned by it: m a + m g sin(theta) when the closed form is right (rolling resistance is not a
    body force: it is added after)."""
    import pinocchio as pin  # (heavy: pinocchio)

    model = free_floating.copy()  # (the read robot's model stays as it is)
    if extra:
        model.appendBodyToJoint(1, pin.Inertia(extra, np.zeros(3), np.zeros((3, 3))), pin.SE3.Identity())
    model.gravity = pin.Motion(
        np.array([-gravity * math.sin(drive.slope), 0.0, -gravity * math.cos(drive.slope), 0.0, 0.0, 0.0])
    )
    acceleration = np.zeros(model.nv)
    acceleration[0] = drive.acceleration
    tau = pin.rnea(model, model.createData(), pin.neutral(model), np.zeros(model.nv), acceleration)
    return float(tau[0])


def base_of(robot: LoadedRobot, drive: BaseMotion, payload_mass: float) -> BaseSizing | str:
    """The base sizing of the robot, or why there is none (no wheels found)."""
    wheels = find_wheels(robot, drive.wheels)
    if not wheels:
        return "no wheels found (continuous joints whose child link is drawn as a cylinder); name them in mobile.wheels"
    free = robot.robot.free_floating
    sized = size_base(drive, wheels, whole_mass(free, payload_mass), robot.gravity)
    return dataclasses.replace(sized, dynamics_force=dynamics_force(free, drive, payload_mass, robot.gravity))
