"""Collision geometry as simulators use it: G005, a link colliding with its full-detail visual mesh itself; G006,
a link that touches the ground without friction of its own."""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from typing import TYPE_CHECKING

from ..shared.transforms import transform
from ..shared.urdf_view import Geometry, Joint, joint_tree
from .findings import Finding, rule_table
from .inertia_geometry import RobotMeshes, placement, shape_in_link
from .urdf_document import Doc, triple_of

if TYPE_CHECKING:
    import numpy as np

RULES = rule_table(
    {
        "G005": (
            "collision-not-visual-mesh",
            "warning",
            "no link collides with its visual mesh itself (the same file and scale) when that mesh has more than "
            "1,000 triangles: physics engines test contacts on every triangle of a collision mesh; said once per file",
        ),
        "G006": (
            "ground-friction",
            "warning",
            "a robot on wheels or feet (not fixed to a world link) gives friction (mu1, mu2) in a <gazebo reference> "
            "block to each link that touches the ground in its default pose; a note when the file has no <gazebo> "
            "at all (it is not written for Gazebo)",
        ),
    }
)

FULL_DETAIL = 1000  # triangles: a mesh beyond this is a visual's detail (a decimated collision mesh has a few hundred)
SHOWN = 5  # links named in the message


def collision_rules(doc: Doc, meshes: RobotMeshes) -> Iterator[Finding]:
    """G005, once for the file, at the first link that collides with its own full-detail visual mesh."""
    found = []  # (link, triangles)
    for link in doc.view.links:
        drawn = {_file(g) for g in link.visuals if _mesh(g)}
        counts = [meshes.triangles(_file(g)[0]) for g in link.collisions if _mesh(g) and _file(g) in drawn]
        most = max((c for c in counts if c is not None), default=0)
        if most > FULL_DETAIL:
            found.append((link, most))
    if not found:
        return
    first = found[0][0]
    largest = sorted(found, key=lambda item: -item[1])[:SHOWN]
    named = ", ".join(f"{link.name} ({count:,} triangles)" for link, count in largest)
    what = (
        f"its collision is its visual mesh itself ({found[0][1]:,} triangles)"
        if len(found) == 1
        else f"{len(found)} links collide with their visual meshes themselves, each of more than {FULL_DETAIL:,} "
        f"triangles (the largest: {named})"
    )
    yield doc.finding(
        "G005",
        "link",
        first.name,
        f"{what}; physics engines test contacts on every triangle of a collision mesh (slow, and jittery where a "
        "detailed surface meets the ground): give a primitive, a convex hull (a spec: collision: hull) or a decimated "
        "mesh (a few hundred triangles)",
        first.element,
    )


def _file(geometry: Geometry) -> tuple[str, tuple[float, float, float]]:
    """A mesh geometry's file and scale (an absent scale is 1 1 1, as "1.0 1.0 1.0" is)."""
    assert geometry.shape is not None
    return geometry.shape.get("filename") or "", triple_of(geometry.shape.get("scale"), "1 1 1")


def _mesh(geometry: Geometry) -> bool:
    return geometry.shape is not None and geometry.shape.kind == "mesh"


# G006: what touches the ground. A link named like a foot or a wheel (or the child of a continuous joint) that a joint
# moves, among the lowest, makes the robot one that stands on its wheels or feet; then every lowest link (a fixed
# caster too) touches the ground, and Gazebo needs its friction.
GROUND_NAMES = re.compile(r"foot|feet|sole|toe|wheel|caster|paw|track", re.IGNORECASE)
CONTACT = 0.01  # m: a link whose collision reaches this close to the lowest point touches the ground too


def ground_rules(doc: Doc, meshes: RobotMeshes) -> Iterator[Finding]:
    """G006 on each link that touches the ground in the default pose of a robot on wheels or feet (not fixed to a
    ``world`` root: :attr:`Doc.fixed_to_world`) and has no mu1, mu2 or mu (SDF's own) in a ``<gazebo reference>``
    block of its rigid body; a note when the file has no ``<gazebo>`` at all (it is not written for Gazebo)."""
    tree = joint_tree(doc.view)
    roots = tree.roots(doc.link_names)
    if len(roots) != 1 or doc.fixed_to_world:
        return
    moved = tree.down(roots, False, lambda above, joint: above or joint.type != "fixed")
    wheels = {joint.child for joint in doc.view.joints if joint.type == "continuous"}
    if not any(moved[name] and (name in wheels or GROUND_NAMES.search(name)) for name in moved):
        return  # (no moved wheel or foot anywhere, so none on the ground: the poses are not worked out)
    import numpy as np  # (heavy: numpy)

    poses = tree.down(roots, np.eye(4), lambda above, joint: above @ _joint_origin(joint))
    lows = _lowest_points(doc, meshes, poses)
    if not lows:
        return
    ground = min(lows.values())
    touching = [name for name, z in lows.items() if z <= ground + CONTACT]
    if not any(moved[name] and (name in wheels or GROUND_NAMES.search(name)) for name in touching):
        return  # (an arm on its base, a body lying on its side: not a robot on wheels or feet)
    # friction given to any link of a rigid body counts for all of it: Gazebo lumps links joined by fixed joints,
    # and keeps the lumped link's <gazebo> surface (ANYmal's friction is on its FOOT, its sphere on the ADAPTER)
    body = tree.down(roots, roots[0], lambda above, joint: above if joint.type == "fixed" else joint.child or "")
    given = {b.reference for b in doc.view.gazebo if any(e.tag in ("mu1", "mu2", "mu") for e in b.element.iter())}
    gripping = {body[name] for name in given if name in body}
    for name in touching:
        link = doc.view.link(name)
        if body.get(name) in gripping or link is None:
            continue
        yield doc.finding(
            "G006",
            "link",
            name,
            f"it touches the ground in the default pose (its collision reaches z = {lows[name]:.3g} m in "
            f"{roots[0]}'s frame, the robot's lowest) but no <gazebo reference={name!r}> gives it friction, so "
            "Gazebo takes SDF's default mu = mu2 = 1 (rubber on concrete; a caster or a skid needs far less): give "
            "<mu1> and <mu2> (a spec: gazebo: links: NAME: {mu1, mu2}; its wheels have theirs)",
            link.element,
            None if doc.view.gazebo else "info",
        )


def _joint_origin(joint: Joint) -> np.ndarray:
    turn, shift = placement(joint.origin)
    return transform(turn, shift.tolist())


def _lowest_points(doc: Doc, meshes: RobotMeshes, poses: dict[str, np.ndarray]) -> dict[str, float]:
    """Each posed link's lowest collision point (z in the root's frame), for links whose collisions all read."""
    lows = {}
    for link in doc.view.links:
        placed = [shape_in_link(g, meshes) for g in link.collisions]
        if link.name not in poses or not placed or any(p is None for p in placed):
            continue
        pose = poses[link.name]
        z = min(float((p[0] @ pose[:3, :3].T + pose[:3, 3])[:, 2].min()) for p in placed if p is not None)
        if math.isfinite(z):
            lows[link.name] = z
    return lows
