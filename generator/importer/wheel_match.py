"""gen-robot import, wheels: a link that is exactly what the spec's ``wheels:`` entry writes becomes one (issue 19).

A continuous joint's child is a wheel when the generated wheel would be the same robot: one cylinder as visual and
as collision (the same), turned onto the joint's axis as the ``wheel`` macro turns it (rpy ``pi/2 0 0`` for the y
axle, ``0 pi/2 0`` for x, none for z), the inertial of a uniform cylinder of its mass about its centre (the importer
said it as ``mass`` alone, or as the same tensor in the link's axes, to 1e-12), an axis of exactly [1, 0, 0],
[0, 1, 0] or [0, 0, 1], a limit of effort and velocity, no mimic, safety controller or calibration, and no link
hanging from it, and a Gazebo block holding only ``mu1`` and ``mu2``, which becomes the wheel's (the spec writes a
wheel's friction: without the file's own block, the wheel would gain one). The link and joint keep their names, which
must then be letters, digits and _ (``joint:`` when it is not ``NAME_joint``).
"""

from __future__ import annotations

import math
import re
from typing import TYPE_CHECKING, Any

from ..shared.solid_inertia import wheel_moments

if TYPE_CHECKING:
    from ..shared.urdf_view import UrdfView

AXLES = {"x": ([1.0, 0.0, 0.0], [0.0, math.pi / 2, 0.0]), "y": ([0.0, 1.0, 0.0], [math.pi / 2, 0.0, 0.0])}
AXLES["z"] = ([0.0, 0.0, 1.0], [0.0, 0.0, 0.0])
IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")  # (the spec's wheel and wheel joint names)
JOINT_KEYS = {"type", "parent", "child", "origin", "axis", "limit", "dynamics"}
LINK_KEYS = {"shape", "origin", "material", "mass", "inertia"}


def wheels(spec: dict[str, Any], view: UrdfView) -> tuple[list[str], set[Any]]:
    """Move each wheel of ``spec`` (links and joints) into ``spec['wheels']``: the wheels' names, and the
    ``<gazebo>`` elements of ``view`` now said by them (not to be kept in the extension file)."""
    links, joints = spec.get("links", {}), spec.get("joints", {})
    parents = {j.get("parent") for j in joints.values()}
    mimicked = {j["mimic"]["joint"] for j in joints.values() if j.get("mimic")}
    friction = _friction_blocks(view)
    found: dict[str, Any] = {}
    absorbed: set[Any] = set()
    for name, joint in list(joints.items()):
        child = joint.get("child")
        link = links.get(child)
        axle = _axle(joint, link) if link is not None and child not in parents and name not in mimicked else None
        named = IDENTIFIER.fullmatch(child) and IDENTIFIER.fullmatch(name)  # (a wheel's names are identifiers)
        if axle is None or friction.get(child) is None or not named:
            continue  # (a wheel's friction is written: without the file's own block, it would gain one)
        wheel: dict[str, Any] = {"parent": joint["parent"]}
        if joint.get("origin"):
            wheel["origin"] = joint["origin"]
        cylinder = link["shape"]["cylinder"]
        wheel.update(radius=cylinder["radius"], width=cylinder["length"], mass=link["mass"], axis=axle)
        if "material" in link:
            wheel["material"] = link["material"]
        wheel["limit"] = {"effort": joint["limit"]["effort"], "velocity": joint["limit"]["velocity"]}
        dynamics = joint.get("dynamics", {})
        wheel["dynamics"] = {"damping": dynamics.get("damping", 0.0), "friction": dynamics.get("friction", 0.0)}
        element, (mu1, mu2) = friction[child]
        wheel.update(mu1=mu1, mu2=mu2)
        absorbed.add(element)
        if name != f"{child}_joint":
            wheel["joint"] = name
        found[child] = wheel
        del joints[name], links[child]
    if found:
        spec["wheels"] = found
    return list(found), absorbed


def _axle(joint: dict[str, Any], link: dict[str, Any]) -> str | None:
    """The wheel's axle (x, y or z) when the joint and its child are exactly a generated wheel's, else None."""
    if joint.get("type") != "continuous" or not set(joint) <= JOINT_KEYS or not set(link) <= LINK_KEYS:
        return None
    limit = joint.get("limit", {})
    if not {"effort", "velocity"} <= set(limit) or "cylinder" not in link.get("shape", {}):
        return None
    if not link.get("mass", 0.0) > 0:
        return None
    for axle, (axis, rpy) in AXLES.items():
        if joint.get("axis") == axis and link.get("origin", {}) == ({"rpy": rpy} if any(rpy) else {}):
            return axle if "inertia" not in link or _cylinders(link, axle) else None
    return None


def _cylinders(link: dict[str, Any], axle: str) -> bool:
    """Whether a link's explicit inertia is the wheel's: a uniform cylinder's about its centre, in the link's axes
    (the wheel macro's), to 1e-12 of its largest moment."""
    inertia = link["inertia"]
    if inertia.get("origin", {}) not in ({}, {"xyz": [0.0, 0.0, 0.0]}) or any(
        inertia.get(k, 0.0) for k in ("ixy", "ixz", "iyz")
    ):
        return False
    cylinder = link["shape"]["cylinder"]
    moments = wheel_moments(link["mass"], cylinder["radius"], cylinder["length"], axle)  # (what resolve gives a wheel)
    want = dict(zip(("ixx", "iyy", "izz"), moments, strict=True))
    return all(abs(inertia.get(k, 0.0) - v) <= 1e-12 * max(moments) for k, v in want.items())


def _friction_blocks(view: UrdfView) -> dict[str, Any]:
    """Per referenced link: (its <gazebo> element, (mu1, mu2)) when it holds only those two numbers, else None (a
    block that says more: that link is left a link, and the block is kept in the extension file)."""
    found: dict[str, Any] = {}
    for block in view.gazebo:
        reference, element = block.reference, block.element
        if reference is None:
            continue
        children = {c.tag: (c.text or "").strip() for c in element.iterchildren() if isinstance(c.tag, str)}
        if reference in found:  # (two blocks for one link: both kept, the link left a link)
            found[reference] = None
            continue
        ok = set(children) == {"mu1", "mu2"} and len(element) == 2 and set(element.attrib) == {"reference"}
        try:
            values = (float(children["mu1"]), float(children["mu2"])) if ok else None
        except ValueError:
            values = None
        found[reference] = (
            (element, values) if values is not None and all(math.isfinite(v) and v >= 0 for v in values) else None
        )
    return found
