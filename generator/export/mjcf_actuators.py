"""The MJCF export's actuators and mimic constraints (:mod:`xacrokit.export.mjcf`).

Actuators come from the URDF's ``<ros2_control>`` blocks, one per joint that has a command interface (the first of
position, velocity, effort it lists):

- position: ``<position kp dampratio="1">``, ``ctrlrange`` the joint's limits (none for a continuous joint);
- velocity: ``<velocity kv>``, ``ctrlrange`` plus or minus the velocity limit;
- effort: ``<motor gear="1">``, ``ctrlrange`` plus or minus the effort limit;

with ``forcerange`` plus or minus the URDF's effort limit (when it gives one). A position servo has the bandwidth
``BANDWIDTH`` (10 Hz) about the robot's zero pose: kp = M_ii (2 pi f)^2, M_ii the diagonal of the joint-space mass
matrix at q = 0 (pinocchio's crba; a free-flyer root for a mobile robot), critically damped, so that a light wrist
and a heavy shoulder respond alike and a 2 ms step stays far inside the stable range (omega dt = 0.13). A velocity
servo gives its full effort when it lags by ``SLIP`` (a tenth) of its velocity limit: kv = effort / (0.1 velocity)
(M_ii 2 pi f without both limits). M_ii cannot be its gain: a wheel's diagonal entry is the wheel's own inertia,
while what it drives through the ground is the whole robot. MuJoCo's implicitfast integrator takes kv implicitly,
so any kv is stable.
A mimic joint follows its leader through ``<equality><joint polycoef="offset multiplier 0 0 0">``: MuJoCo holds
q_mimic = offset + multiplier q_leader.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from lxml import etree

from ..errors import XacrokitError
from ..shared.urdf_view import Joint, UrdfView

BANDWIDTH = 10.0  # Hz
SLIP = 0.1  # a velocity servo gives its full effort when it lags by this fraction of the velocity limit
KINDS = ("position", "velocity", "effort")


def num(value: float) -> str:
    """A number as MJCF reads it back exactly (shortest repr; integers without a fraction)."""
    value = float(value)
    return str(int(value)) if value.is_integer() and abs(value) < 1e15 else repr(value)


def _limit(joint: Joint, key: str) -> float | None:
    text = joint.limit.get(key) if joint.limit is not None else None
    if text is None:
        return None
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def commanded(view: UrdfView) -> dict[str, str]:
    """Each joint of the ``<ros2_control>`` blocks with its actuator kind (the first of position, velocity, effort
    among its command interfaces)."""
    found: dict[str, str] = {}
    for block in view.ros2_control:
        for joint in block.element.findall("joint"):
            names = [c.get("name") for c in joint.findall("command_interface")]
            kind = next((k for k in KINDS if k in names), None)
            if kind is not None and joint.get("name"):
                found.setdefault(joint.get("name"), kind)
    return found


def gains(model: Any, joints: Sequence[str]) -> dict[str, float]:
    """M_ii at q = 0 of each named joint (kg m^2 or kg), from pinocchio's crba on the robot's ``model`` (fixed, or on
    a free-flyer root as the MJCF's base)."""
    import pinocchio as pin  # (heavy: pinocchio)

    data = model.createData()
    mass = pin.crba(model, data, pin.neutral(model))
    mass = np.triu(mass) + np.triu(mass, 1).T
    found = {}
    for name in joints:
        if model.existJointName(name):
            joint = model.joints[model.getJointId(name)]
            if joint.nv == 1:
                found[name] = float(mass[joint.idx_v, joint.idx_v])
    return found


def actuators(view: UrdfView, joints: Mapping[str, Joint], inertia: Mapping[str, float], notes: list[str]) -> Any:
    """The ``<actuator>`` element (empty when nothing is commanded)."""

    element = etree.Element("actuator")
    omega = 2.0 * math.pi * BANDWIDTH
    for name, kind in commanded(view).items():
        joint = joints.get(name)
        if joint is None or joint.type not in ("revolute", "continuous", "prismatic"):
            notes.append(f"ros2_control joint {name!r} is not a moving joint of the robot: no actuator")
            continue
        if joint.mimic is not None:
            notes.append(f"ros2_control joint {name!r} mimics another: it follows it, no actuator of its own")
            continue
        effort, velocity = _limit(joint, "effort"), _limit(joint, "velocity")
        lower, upper = _limit(joint, "lower"), _limit(joint, "upper")
        m_ii = inertia.get(name, 0.0)
        if kind == "position":
            actuator = etree.SubElement(element, "position", name=name, joint=name)
            actuator.set("kp", num(m_ii * omega**2))
            actuator.set("dampratio", "1")
            if joint.type != "continuous" and lower is not None and upper is not None and lower < upper:
                actuator.set("ctrlrange", f"{num(lower)} {num(upper)}")
        elif kind == "velocity":
            gain = abs(effort) / (SLIP * abs(velocity)) if effort and velocity else m_ii * omega
            actuator = etree.SubElement(element, "velocity", name=name, joint=name, kv=num(gain))
            if velocity:
                actuator.set("ctrlrange", f"{num(-abs(velocity))} {num(abs(velocity))}")
        else:
            actuator = etree.SubElement(element, "motor", name=name, joint=name, gear="1")
            if effort:
                actuator.set("ctrlrange", f"{num(-abs(effort))} {num(abs(effort))}")
        if effort:
            actuator.set("forcerange", f"{num(-abs(effort))} {num(abs(effort))}")
        if kind != "effort" and not m_ii > 0:
            notes.append(f"joint {name!r}: no inertia moves with it at q = 0, its {kind} servo has no gain")
    return element


def mimics(joints: Sequence[Joint], notes: list[str]) -> Any:
    """The ``<equality>`` element of the mimic joints (empty without one); a mimic of a joint that is not there (or
    does not move) is said in ``notes`` and left unconstrained."""

    element = etree.Element("equality")
    names = {j.name for j in joints if j.type in ("revolute", "continuous", "prismatic")}
    for joint in joints:
        mimic = joint.mimic
        if mimic is None or joint.name not in names:
            continue
        leader = mimic.joint
        if leader not in names:
            notes.append(f"joint {joint.name!r} mimics {leader!r}, which is not a moving joint: it moves freely")
            continue
        try:
            multiplier = float(mimic.multiplier if mimic.multiplier is not None else 1)
            offset = float(mimic.offset if mimic.offset is not None else 0)
        except ValueError:
            raise XacrokitError(f"joint {joint.name!r}: its mimic multiplier or offset is not a number") from None
        etree.SubElement(
            element,
            "joint",
            name=f"{joint.name}_mimic",
            joint1=joint.name,
            joint2=leader,
            polycoef=f"{num(offset)} {num(multiplier)} 0 0 0",
        )
    return element


def compensate_gravity(world: Any, acts: Any, equality: Any) -> None:
    """Make the position servos carry the weight of what they alone hold, as an arm's controller does: each body
    whose every joint up to the world is a position servo's, or a mimic joint (``equality``) of one (its leader's
    motor drives it through the linkage the mimic stands for), gets ``gravcomp="1"``, and those joints
    ``actuatorgravcomp="true"``: MuJoCo adds the torque that cancels that weight, -J^T m g summed over those bodies,
    to the joints' actuator force, and clamps the sum into ``actuatorfrcrange`` (the servo's forcerange, the URDF's
    effort limit). A body below anything else (a free base, a wheel, a joint without a servo) keeps its weight."""
    servos = {a.get("joint"): a for a in acts if a.tag == "position"}
    follows = {e.get("joint1"): e.get("joint2") for e in (equality if equality is not None else [])}
    driven = set(servos)
    while grown := {joint for joint, leader in follows.items() if leader in driven} - driven:
        driven |= grown  # (a mimic of a mimic: driven through its chain, as keyframes and ros2_control follow it)
    held: set[str] = set()
    stack = [(body, False) for body in world.findall("body")]
    while stack:
        body, moved = stack.pop()
        own = [j for j in body if j.tag in ("joint", "freejoint")]
        if any(j.tag == "freejoint" or j.get("name") not in driven for j in own):
            continue  # (neither it nor a body below it is held by servos alone)
        held.update(j.get("name") for j in own)
        moved = moved or bool(own)
        if moved:  # (a body welded to the world has no joint to carry it)
            body.set("gravcomp", "1")
        stack.extend((child, moved) for child in body.findall("body"))
    for joint in world.iter("joint"):
        if joint.get("name") in held:
            joint.set("actuatorgravcomp", "true")
            limit = servos[joint.get("name")].get("forcerange") if joint.get("name") in servos else None
            if limit is not None:
                joint.set("actuatorfrcrange", limit)
