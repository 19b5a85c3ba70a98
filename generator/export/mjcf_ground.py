"""A free robot standing on the ground, z = 0: the floor of the exported model (:mod:`xacrokit.export.mjcf`,
``floor=True``), or the one a model that includes it provides (MuJoCo Menagerie's robots stand on z = 0 the same way,
their scene.xml adding the floor).

A free body (a robot's root on a free joint) is placed so that, at each keyframe's pose and at the model's own zero
pose (``qpos0``, where ``mj_resetData`` starts it), its lowest collision point is on the ground: a robot's own root,
which the URDF places nowhere, is raised or lowered onto it; a robot a scene places keeps its place and is only
raised out of the ground when its shapes reach below it (it may stand on something the scene puts under it). Its x,
y and orientation stay as placed.

The lowest point is found in the MJCF tree itself, as MuJoCo's ``mj_kinematics`` places its bodies: each body at its
``pos`` and ``quat`` in its parent's frame, then its joints in order (a hinge turns about the body's origin, a slide
moves along its axis), the collision geoms (class ``collision``) at theirs: a box's lowest corner, a sphere's and a
cylinder's lowest point, a mesh's lowest vertex (MuJoCo collides with its convex hull, whose lowest point is one of
them). Products are written out (no BLAS), so the numbers written are the same on every machine.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..shared.transforms import exact_product
from .mjcf_actuators import num

Frame = tuple[np.ndarray, np.ndarray]  # (rotation, translation) in the world


def _floats(text: str | None, default: Sequence[float]) -> list[float]:
    return [float(v) for v in text.split()] if text else list(default)


def quaternion_matrix(wxyz: Sequence[float]) -> np.ndarray:
    """The rotation of a quaternion in MuJoCo's order (w, x, y, z), normalised as MuJoCo does, multiplied out."""
    norm = math.sqrt(math.fsum(v * v for v in wxyz))
    w, x, y, z = (v / norm for v in wxyz)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def _axis_angle(axis: Sequence[float], angle: float) -> np.ndarray:
    half = angle / 2.0
    s = math.sin(half)
    return quaternion_matrix([math.cos(half), axis[0] * s, axis[1] * s, axis[2] * s])


def _placed(frame: Frame, element: Any) -> Frame:
    """``frame`` composed with an element's ``pos`` and ``quat`` (in that frame)."""
    rotation, translation = frame
    pos = np.array(_floats(element.get("pos"), (0.0, 0.0, 0.0)))
    turn = quaternion_matrix(_floats(element.get("quat"), (1.0, 0.0, 0.0, 0.0)))
    return exact_product(rotation, turn), translation + exact_product(rotation, pos)


def _moved(frame: Frame, body: Any, values: Mapping[str, float]) -> Frame:
    """``frame`` (a body's placement) moved by its hinge and slide joints at ``values`` (0 for one not given)."""
    rotation, translation = frame
    for joint in body.findall("joint"):
        kind, value = joint.get("type", "hinge"), values.get(joint.get("name"), 0.0)
        axis = _floats(joint.get("axis"), (0.0, 0.0, 1.0))
        if kind == "hinge":
            rotation = exact_product(rotation, _axis_angle(axis, value))
        elif kind == "slide":
            translation = translation + exact_product(rotation, np.array(axis) * value)
    return rotation, translation


def _geom_low(geom: Any, frame: Frame, points: Mapping[str, np.ndarray]) -> float | None:
    """The lowest z of a collision geom placed in its body's ``frame`` (None for a kind MuJoCo does not write)."""
    rotation, centre = _placed(frame, geom)
    size = _floats(geom.get("size"), (0.0, 0.0, 0.0))
    row = rotation[2]
    kind = geom.get("type", "sphere")
    if kind == "box":
        return float(centre[2] - math.fsum(abs(r) * h for r, h in zip(row, size, strict=True)))
    if kind == "sphere":
        return float(centre[2] - size[0])
    if kind == "cylinder":  # (its axis is the geom's z: row[2] is that axis' vertical part)
        return float(centre[2] - size[1] * abs(row[2]) - size[0] * math.sqrt(max(0.0, 1.0 - row[2] ** 2)))
    if kind == "mesh" and geom.get("mesh") in points:
        vertices = points[geom.get("mesh")]
        heights = vertices[:, 0] * row[0] + vertices[:, 1] * row[1] + vertices[:, 2] * row[2]  # (elementwise)
        return float(centre[2] + heights.min())
    return None


def lowest_point(
    body: Any, frame: Frame, values: Mapping[str, float], points: Mapping[str, np.ndarray]
) -> float | None:
    """The lowest z of the collision geoms of ``body`` (placed at ``frame``, after its own joints) and of the bodies
    below it at joint ``values``; None when none has any."""
    lows: list[float] = []
    stack = [(body, frame)]
    while stack:  # (a tree 490 bodies deep: no recursion)
        here, placed = stack.pop()
        for geom in here.findall("geom"):
            if geom.get("class") == "collision":
                low = _geom_low(geom, placed, points)
                if low is not None:
                    lows.append(low)
        for child in here.findall("body"):
            stack.append((child, _moved(_placed(placed, child), child, values)))
    return min(lows) if lows else None


def free_body(joint: Any) -> bool:
    """Whether an MJCF joint element is a free joint (``<freejoint>`` or ``type="free"``)."""
    return bool(joint.tag == "freejoint" or joint.get("type") == "free")


@dataclass(frozen=True)
class Ground:
    """Where the free bodies of a model stand on the ground (see the module's docstring).

    Attributes:
        points: each mesh asset's vertices (scaled), by its name.
        own: the free bodies that are a robot's root (raised or lowered onto the ground); the others, placed by a
            scene, are only raised.
    """

    points: Mapping[str, np.ndarray]
    own: frozenset[str]

    def qpos(self, joint: Any, values: Mapping[str, float]) -> list[float] | None:
        """A free joint's qpos (position, then MuJoCo's w x y z) at joint ``values``, its body standing on the
        ground; None when its robot has no collision geometry (it stays where it is placed)."""
        body = joint.getparent()
        pos = _floats(body.get("pos"), (0.0, 0.0, 0.0))
        quat = _floats(body.get("quat"), (1.0, 0.0, 0.0, 0.0))
        low = lowest_point(body, _placed((np.eye(3), np.zeros(3)), body), values, self.points)
        if low is None:
            return None
        lift = -low if body.get("name") in self.own else max(-low, 0.0)
        return [pos[0], pos[1], pos[2] + lift, *quat]

    def stand(self, world: Any) -> None:
        """Place every free body of ``world`` (the worldbody) on the ground at the zero pose (its ``pos``: where
        ``mj_resetData`` starts it)."""
        for body in world.findall("body"):
            joint = next((j for j in body if j.tag in ("joint", "freejoint") and free_body(j)), None)
            if joint is None:
                continue
            placed = self.qpos(joint, {})
            if placed is not None:
                body.set("pos", " ".join(num(v) for v in placed[:3]))
