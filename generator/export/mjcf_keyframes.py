"""The exported model's keyframes: one ``<key>`` per named pose (:func:`xacrokit.reader.named_poses.named_poses`:
``home`` first), a joint a pose leaves out at 0 (or the limit nearest 0). A key holds
the whole ``qpos`` in MuJoCo's order (the document order of the joints: a free joint its body's position and
orientation, a mimic joint its leader's value through the mimic's offset and multiplier) and ``ctrl`` (a position
servo's target is its joint's value, a velocity servo's and a motor's 0), so that ``mj_resetDataKeyframe`` starts the
robot holding that pose; a free body standing on the ground in each (:class:`~.mjcf_ground.Ground`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from lxml import etree

from ..shared.joint_types import mimic_positions, rest_position
from ..shared.urdf_view import Joint
from .mjcf_actuators import num
from .mjcf_ground import Ground


def keyframes(
    model: Any, poses: Mapping[str, Mapping[str, float]], joints: Sequence[Joint], ground: Ground | None = None
) -> Any:
    """The ``<keyframe>`` element of ``model`` (an MJCF tree with its joints and actuators) for ``poses``; with the
    ``ground``, each free body standing on it."""

    mimics = {j.name: j.mimic for j in joints if j.mimic is not None}
    order = list(model.find("worldbody").iter("joint", "freejoint"))  # (MuJoCo's qpos order)
    servos = list(model.find("actuator")) if model.find("actuator") is not None else []
    element = etree.Element("keyframe")
    for name, pose in poses.items():
        values = {j.get("name"): _value(j, pose) for j in order if _kind(j) in ("hinge", "slide")}
        rules = {
            follower: (
                mimic.joint,
                float(mimic.multiplier) if mimic.multiplier is not None else 1.0,
                float(mimic.offset) if mimic.offset is not None else 0.0,
            )
            for follower, mimic in mimics.items()
            if follower in values and mimic.joint is not None
        }
        values = mimic_positions(values, rules)  # (through chains, in any order)
        qpos = [
            _fixed(j, values, ground) if _kind(j) in ("free", "ball") else num(values[j.get("name")]) for j in order
        ]
        key = etree.SubElement(element, "key", name=name, qpos=" ".join(qpos))
        if servos:  # (a position servo holds its joint's value; a velocity servo and a motor rest at 0)
            ctrl = [num(values.get(a.get("joint"), 0.0)) if a.tag == "position" else "0" for a in servos]
            key.set("ctrl", " ".join(ctrl))
    return element


def _kind(joint: Any) -> str:
    return "free" if joint.tag == "freejoint" else str(joint.get("type", "hinge"))


def _fixed(joint: Any, values: Mapping[str, float], ground: Ground | None) -> str:
    """A free joint's qpos (where its body is placed; with the ``ground``, standing on it at joint ``values``) or a
    ball joint's (no turn)."""
    if _kind(joint) == "ball":
        return "1 0 0 0"
    standing = ground.qpos(joint, values) if ground is not None else None
    if standing is not None:
        return " ".join(num(v) for v in standing)
    body = joint.getparent()
    return f"{body.get('pos', '0 0 0')} {body.get('quat', '1 0 0 0')}"


def _value(joint: Any, pose: Mapping[str, float]) -> float:
    """A joint's value in a pose: given, else 0 moved into its range."""
    name = joint.get("name")
    if name in pose:
        return float(pose[name])
    bounds = joint.get("range")
    lower, upper = (float(v) for v in bounds.split()) if bounds is not None else (None, None)
    return rest_position(lower, upper)
