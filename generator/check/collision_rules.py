"""Collision geometry as simulators use it: G005, a link colliding with its full-detail visual mesh itself."""

from __future__ import annotations

from collections.abc import Iterator

from ..reader.urdf_view import Geometry
from .findings import Finding, rule_table
from .inertia_geometry import RobotMeshes
from .urdf_document import Doc

RULES = rule_table(
    {
        "G005": (
            "collision-not-visual-mesh",
            "warning",
            "no link collides with its visual mesh itself (the same file and scale) when that mesh has more than "
            "1,000 triangles: physics engines test contacts on every triangle of a collision mesh; said once per file",
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
        "detailed surface meets the ground): give a primitive, a convex hull or a decimated mesh (a few hundred "
        "triangles)",
        first.element,
    )


def _file(geometry: Geometry) -> tuple[str, str]:
    """A mesh geometry's file and scale as written (an absent scale is 1 1 1)."""
    assert geometry.shape is not None
    return geometry.shape.get("filename") or "", " ".join((geometry.shape.get("scale") or "1 1 1").split())


def _mesh(geometry: Geometry) -> bool:
    return geometry.shape is not None and geometry.shape.kind == "mesh"
