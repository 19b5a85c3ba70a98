"""I009: the same inertial (mass and tensor) on links whose geometries differ in size: one was copied from the other.

A left and a right part, or the fingers of a hand, share their inertial rightly: their geometry is the same part,
mirrored or repeated. Two parts of different sizes cannot have the same mass and tensor unless one was copied from the
other and never computed. The size of a link's geometry is taken as the largest distance of its points (every visual
and collision, a mesh by its convex hull: :func:`~xacrokit.check.inertia_geometry.link_reach`) from their centroid,
which turning or mirroring a part does not change; sizes more than SIZES apart are different parts. Round placeholders
(k * identity, I005) and all-zero tensors are left to their own rules.

Of the links sharing an inertial, the first (in the file's order) is taken for the part it was computed for: each
link of a size different from the first's is said, naming the latest link before it of the first's size. So a
fleet's copies of one robot get that robot's findings, each naming a link of its own copy, and two links of the
first's size are never said for a third between them. Each distinct geometry's reach is read once (``ReachMemo``).
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping

from ..shared.solid_inertia import is_placeholder
from ..shared.urdf_view import Link
from .findings import Finding, rule_table
from .inertia_geometry import ReachMemo
from .urdf_document import Doc

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


def _size(link: Link, reaches: ReachMemo) -> float | None:
    """The largest distance of the link's geometry points from their centroid (None: no geometry, or unreadable)."""
    import numpy as np  # (heavy: numpy)

    reach = reaches.reach(link)
    if reach is None:
        return None
    offsets = reach.points - reach.points.mean(axis=0)
    size = float(np.sqrt((offsets * offsets).sum(axis=1).max()))
    return size if math.isfinite(size) and size > 0 else None


def copied_inertias(
    doc: Doc, reaches: ReachMemo, significant: Mapping[str, tuple[float, tuple[float, ...]]]
) -> Iterator[Finding]:
    """I009 on each link whose inertial equals an earlier link's of a different size, among
    the ``significant`` links (name -> mass and tensor entries: a tenth of their rigid body's mass or more, as I004
    and I005 judge; a 0.1 g dummy inertial on a sensor frame is nobody's copy worth a warning)."""
    groups: dict[tuple[float, ...], list[Link]] = {}
    for link in doc.view.links:
        mass, entries = significant.get(link.name, (0.0, ()))
        if any(entries) and not is_placeholder(*entries):
            groups.setdefault((mass, *entries), []).append(link)
    for key, links in groups.items():
        if len(links) < 2:
            continue
        known = [(link, size) for link in links if (size := _size(link, reaches)) is not None]
        if not known:
            continue
        like_first = known[0]  # (the latest link of the first one's size: the one a copy is said to copy)
        for link, size in known[1:]:
            first, first_size = like_first
            if max(first_size, size) <= SIZES * min(first_size, size):
                like_first = (link, size)
                continue
            yield doc.finding(
                "I009",
                "link",
                link.name,
                f"it has the same mass ({key[0]:g} kg) and inertia tensor as link {first.name!r}, though its geometry "
                f"is {size / first_size:.3g} times that link's size (it reaches {size:.3g} m from its centre, that one "
                f"{first_size:.3g} m): an inertial copied from another part; compute this part's own",
                link.element,
            )
