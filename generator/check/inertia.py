"""Inertia rules (I001-I005): the bodies that need mass have it, with a tensor a rigid body can have, of a size that
fits the body and not a placeholder."""

from __future__ import annotations

import math
from collections.abc import Iterator

from lxml import etree

from ..model import MOVING
from ..physics import describe_problem, moments_problem, principal_moments
from .document import Doc, read_float, read_triple
from .findings import Finding, rule_table

RULES = rule_table(
    {
        "I001": (
            "mass-positive",
            "error",
            "links with geometry have an inertial with mass > 0; so does the body a moving joint moves (its child link "
            "or a link fixed to it)",
        ),
        "I002": ("inertia-positive-definite", "error", "the inertia tensor is positive definite"),
        "I003": ("inertia-triangle", "error", "principal moments obey the triangle inequality"),
        "I004": ("inertia-plausible", "warning", "inertia fits the collision geometry's size (within 100x)"),
        "I005": ("inertia-placeholder", "warning", "the tensor is not an identity-like placeholder"),
    }
)

_INERTIA = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
_PLACEHOLDERS = (1.0, 0.1, 0.01, 1e-3, 1e-4, 1e-5, 1e-6)


def _geometry_extent(geometry: etree._Element | None) -> tuple[float, float, float] | None:
    """Edge lengths of the geometry's own bounding box, or None when unknown (meshes)."""
    if geometry is None:
        return None
    if (box := geometry.find("box")) is not None:
        return read_triple(box, "size")
    if (cylinder := geometry.find("cylinder")) is not None:
        r, length = read_float(cylinder, "radius", math.nan), read_float(cylinder, "length", math.nan)
        return (2 * r, 2 * r, length)
    if (sphere := geometry.find("sphere")) is not None:
        diameter = 2 * (read_float(sphere, "radius", math.nan) or math.nan)
        return (diameter, diameter, diameter)
    return None


def _massive(link: etree._Element) -> bool:
    inertial = link.find("inertial")
    mass = read_float(inertial.find("mass"), "value") if inertial is not None else None
    return mass is not None and mass > 0


class _BodyMass:
    """Whether the rigid body of a link has mass: a link hanging from it by fixed joints may carry it (consumers merge
    fixed children into their parent, so a moving joint may move a massless link whose fixed child carries the mass).
    The fixed joints are read when first asked; each fixed-joint component has one moved link at its top, so all
    questions together are linear."""

    def __init__(self, doc: Doc) -> None:
        self.doc = doc
        self.fixed_children: dict[str, list[str]] | None = None
        self.massive: set[str] = set()

    def __call__(self, name: str) -> bool:
        if self.fixed_children is None:
            self.fixed_children = {}
            for joint in self.doc.joints:
                parent, child = joint.find("parent"), joint.find("child")
                if joint.get("type") == "fixed" and parent is not None and child is not None:
                    self.fixed_children.setdefault(parent.get("link", ""), []).append(child.get("link", ""))
            self.massive = {link.get("name", "") for link in self.doc.links if _massive(link)}
        seen, stack = {name}, [name]
        while stack:  # (a cycle of fixed joints is S002's; ``seen`` keeps this walk finite)
            current = stack.pop()
            if current in self.massive:
                return True
            for child in self.fixed_children.get(current, ()):
                if child not in seen:
                    seen.add(child)
                    stack.append(child)
        return False


def inertia_rules(doc: Doc) -> Iterator[Finding]:
    moved = {j.find("child").get("link") for j in doc.joints if j.get("type") in MOVING and j.find("child") is not None}
    body_has_mass = _BodyMass(doc)
    # (ixx, ixy, ixz, iyy, iyz, izz) of every link that has them; the principal moments of all the finite ones in one
    # batched eigvalsh, consumed in link order below (per-link numpy calls cost ten times more)
    entries = [_inertia_entries(link) for link in doc.links]
    moments_in_order = iter(
        principal_moments([e for e in entries if e is not None and all(math.isfinite(v) for v in e)])
    )
    for link, entry in zip(doc.links, entries, strict=True):
        moments = next(moments_in_order) if entry is not None and all(math.isfinite(v) for v in entry) else None
        name = link.get("name", "")
        inertial = link.find("inertial")
        has_geometry = link.find("visual") is not None or link.find("collision") is not None
        mass = read_float(inertial.find("mass"), "value") if inertial is not None else None
        if has_geometry or name in moved:
            why = "has geometry" if has_geometry else "is moved by a joint"
            if mass is None:
                if not has_geometry and body_has_mass(name):
                    continue  # a massless link whose fixed children carry the moved body's mass
                where = "" if has_geometry else " (nor any link fixed to it)"
                yield doc.finding(
                    "I001",
                    "link",
                    name,
                    f"link {why} but no <inertial> mass{where}; give mass > 0 (kg) and its inertia",
                    link,
                )
                continue
            if not mass > 0:
                yield doc.finding("I001", "link", name, f"mass is {mass}; it must be > 0 kg", link)
                continue
        if entry is None:
            continue
        if mass == 0 and not any(entry) and not (has_geometry or name in moved):
            continue  # an explicit all-zero inertial on a bare frame: a massless frame, as many descriptions write
        if moments is None:
            yield doc.finding("I002", "link", name, "the inertia tensor has unreadable entries", link)
            continue
        problem = moments_problem(moments)
        if problem is not None:
            rule = "I002" if problem == "not-positive-definite" else "I003"
            yield doc.finding(rule, "link", name, describe_problem(problem, moments), link)
            continue
        total = sum(moments)
        ixx, ixy, ixz, iyy, iyz, izz = entry
        if ixy == ixz == iyz == 0 and ixx == iyy == izz and ixx in _PLACEHOLDERS:
            yield doc.finding(
                "I005",
                "link",
                name,
                f"inertia is {ixx:g} * identity, a common placeholder; "
                "compute it from the body (e.g. xacrokit's inertia macros)",
                link,
            )
        if mass and mass > 0:
            yield from _plausibility(doc, link, name, mass, total)


def _inertia_entries(link: etree._Element) -> tuple[float, ...] | None:
    inertial = link.find("inertial")
    inertia = inertial.find("inertia") if inertial is not None else None
    return None if inertia is None else tuple(read_float(inertia, key, 0.0) for key in _INERTIA)


def _plausibility(doc: Doc, link: etree._Element, name: str, mass: float, trace: float) -> Iterator[Finding]:
    """Compare trace(I) with a solid box filling the collision geometry's bounding box: m * diagonal^2 / 6."""
    extents = [_geometry_extent(c.find("geometry")) for c in link.findall("collision")]
    known = [e for e in extents if e is not None and all(math.isfinite(v) for v in e)]
    if not extents or len(known) != len(extents):
        return
    diagonal_sq = max(sum(v * v for v in e) for e in known)
    expected = mass * diagonal_sq / 6.0
    if expected > 0 and not 1e-2 <= trace / expected <= 1e2:
        yield doc.finding(
            "I004",
            "link",
            name,
            f"inertia (trace {trace:.3g} kg*m^2) is {trace / expected:.3g} times "
            f"that of a solid body filling the collision geometry ({expected:.3g}); "
            "a units mistake (mm for m, g for kg)?",
            link,
        )
