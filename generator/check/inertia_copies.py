"""I009: the same inertial (mass and tensor) on links whose geometries differ in size: one was copied from the other.

A left and a right part, or the fingers of a hand, share their inertial rightly: their geometry is the same part,
mirrored or repeated. Two parts of different sizes cannot have the same mass and tensor unless one was copied from the
other and never computed. The size of a link's geometry is taken as the largest distance of its points (every visual
and collision, a mesh by its convex hull: :func:`~xacrokit.check.inertia_geometry.link_reach`) from their centroid,
which turning or mirroring a part does not change; sizes more than SIZES apart are different parts. Round placeholders
(k * identity, I005) and all-zero tensors are left to their own rules.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np

from ..reader.urdf_view import Link
from .findings import Finding, rule_table
from .inertia_geometry import MeshReach, link_reach
from .urdf_document import Doc, number_of

RULES = rule_table(
    {
        "I009": (
            "inertia-copied",
            "warning",
            "no two links of different sizes (their geometries' extents more than 25% apart) carry the same mass and "
            "inertia tensor: one was copied from the other (mirrored and repeated parts of one size may share theirs)",
        ),
    }
)

SIZES = 1.25  # two geometries whose sizes differ by more than this factor are different parts
_ENTRIES = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
_PLACEHOLDERS = (1.0, 0.1, 0.01, 1e-3, 1e-4, 1e-5, 1e-6)  # (as I005's)


def _inertial_key(link: Link) -> tuple[float, ...] | None:
    """(mass, ixx, ixy, ixz, iyy, iyz, izz) when the link has a mass and a tensor that is neither zero nor a round
    placeholder, else None."""
    inertial = link.inertial
    if inertial is None or inertial.inertia is None or inertial.mass is None:
        return None
    mass = number_of({"value": inertial.mass}, "value", math.nan)
    entries = tuple(number_of(inertial.inertia, key, 0.0) or 0.0 for key in _ENTRIES)
    values = (mass or math.nan, *entries)
    if not all(math.isfinite(v) for v in values) or not values[0] > 0 or not any(entries):
        return None
    ixx, ixy, ixz, iyy, iyz, izz = entries
    if ixy == ixz == iyz == 0 and ixx == iyy == izz and ixx in _PLACEHOLDERS:
        return None
    return values


def _size(link: Link, meshes: MeshReach | None) -> float | None:
    """The largest distance of the link's geometry points from their centroid (None: no geometry, or unreadable)."""
    reach = link_reach(link, meshes)
    if reach is None:
        return None
    offsets = reach.points - reach.points.mean(axis=0)
    size = float(np.sqrt((offsets * offsets).sum(axis=1).max()))
    return size if math.isfinite(size) and size > 0 else None


def copied_inertias(doc: Doc, meshes: MeshReach | None, significant: set[str]) -> Iterator[Finding]:
    """I009 on each link whose inertial equals an earlier link's of a different size (named in the message), among
    the ``significant`` links (a tenth of their rigid body's mass or more, as I004 and I005: a 0.1 g dummy inertial
    on a sensor frame is nobody's copy worth a warning)."""
    groups: dict[tuple[float, ...], list[Link]] = {}
    for link in doc.view.links:
        key = _inertial_key(link) if link.name in significant else None
        if key is not None:
            groups.setdefault(key, []).append(link)
    for key, links in groups.items():
        if len(links) < 2:
            continue
        sized = [(link, _size(link, meshes)) for link in links]
        known = [(link, size) for link, size in sized if size is not None]
        for index, (link, size) in enumerate(known):
            other = next(((o, s) for o, s in known[:index] if max(s, size) > SIZES * min(s, size)), None)
            if other is None:
                continue
            first, first_size = other
            yield doc.finding(
                "I009",
                "link",
                link.name,
                f"it has the same mass ({key[0]:g} kg) and inertia tensor as link {first.name!r}, though its geometry "
                f"is {size / first_size:.3g} times that link's size (it reaches {size:.3g} m from its centre, that one "
                f"{first_size:.3g} m): an inertial copied from another part; compute this part's own",
                link.element,
            )
