"""Inertia rules (I001-I007): the bodies that need mass have it, with a tensor a rigid body can have, of a size that
fits the body and not a placeholder. Rigid bodies are judged as simulators see them: links joined by fixed joints are
one body."""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

from ..shared.joint_types import MOVING
from ..shared.solid_inertia import (
    TOLERANCE,
    describe_problem,
    format_moments,
    is_placeholder,
    moments_problem,
    principal_moments,
)
from ..shared.urdf_view import Link, Shape
from .findings import Finding, rule_table
from .inertia_copies import copied_inertias
from .inertia_fit import fits_at_a_glance
from .inertia_geometry import MARKER, MeshReach, ReachMemo, geometry_key, geometry_message
from .urdf_document import Doc, number_of, triple_of

RULES = rule_table(
    {
        "I001": (
            "mass-positive",
            "error",
            "no mass is negative, and every body a joint moves has mass > 0: judged per rigid body, as simulators see "
            "it (links joined by fixed joints are one body, so a massless link fixed to a massive one is fine)",
        ),
        "I002": (
            "inertia-positive-definite",
            "error",
            "every link's inertia tensor is positive definite (MuJoCo checks each link before it fuses fixed ones), or "
            "all zero (a point mass) on a link fixed to one whose tensor is",
        ),
        "I003": (
            "inertia-triangle",
            "error",
            "every link's principal moments obey the triangle inequality (MuJoCo rejects a link's that do not)",
        ),
        "I004": (
            "inertia-plausible",
            "warning",
            "inertia fits the collision geometry's size (within 100x) on a link with a tenth of its rigid body's mass "
            "or more (collisions of 5 mm or less are markers, not the body's shape)",
        ),
        "I005": (
            "inertia-placeholder",
            "warning",
            "the tensor is not an identity-like placeholder, on a link with a tenth of its rigid body's mass or more",
        ),
        "I006": (
            "inertia-present",
            "error",
            "an <inertial> with a <mass> has an <inertia> (urdfdom rejects it without)",
        ),
        "I007": (
            "base-mass",
            "warning",
            "the robot's base body (the root link and the links fixed to it) has a mass when it has geometry (a fixed "
            "base needs none; a mobile one in a simulator does); not asked of a robot fixed to a geometry-less `world` "
            "root",
        ),
    }
)

_INERTIA = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def _geometry_extent(shape: Shape | None) -> tuple[float, float, float] | None:
    """Edge lengths of the shape's own bounding box, or None when unknown (meshes)."""
    if shape is None:
        return None
    if shape.kind == "box":
        return triple_of(shape.get("size"))
    if shape.kind == "cylinder":
        r, length = number_of(shape.attributes, "radius", math.nan), number_of(shape.attributes, "length", math.nan)
        assert r is not None and length is not None  # (a default is given)
        return (2 * r, 2 * r, length)
    if shape.kind == "sphere":
        diameter = 2 * (number_of(shape.attributes, "radius", math.nan) or math.nan)
        return (diameter, diameter, diameter)
    return None


SIGNIFICANT = 0.1  # of its rigid body's mass: a link below it is judged with its body, not on its own (I004, I005)
ZERO_MOMENT = 1e-12  # kg*m^2: below it every principal moment is zero (a 1 g, 1 mm part has about 1e-10)


class _Bodies:
    """The rigid bodies of a document as consumers see them: links joined by fixed joints are one body (pinocchio,
    MuJoCo and Gazebo fuse them), so mass and inertia are asked of the body, not of each link. A body is moved when
    one of its links is the child of a moving joint; the body that holds the root link is the robot's base."""

    def __init__(self, doc: Doc, masses: dict[str, float | None], solid: set[str]) -> None:
        self.owner: dict[str, str] = {name: name for name in doc.link_names}  # union-find: link -> representative
        for joint in doc.view.joints:
            if joint.type == "fixed" and joint.parent is not None and joint.child is not None:
                self._join(joint.parent, joint.child)
        self.members: dict[str, list[str]] = {}
        for name in (link.name for link in doc.view.links):  # (in the document's order: messages list them)
            self.members.setdefault(self.body(name), []).append(name)
        self.massive = {self.body(n) for n, m in masses.items() if m is not None and m > 0}
        self.mass: dict[str, float] = {}  # body -> the sum of its links' masses
        for n, m in masses.items():
            if m is not None and m > 0 and math.isfinite(m):
                self.mass[self.body(n)] = self.mass.get(self.body(n), 0.0) + m
        self.solid = {self.body(n) for n in solid}  # bodies with a link whose tensor is positive definite

    def body(self, name: str) -> str:
        root = self.owner.setdefault(name, name)
        while self.owner[root] != root:
            self.owner[root] = self.owner[self.owner[root]]  # (path halving)
            root = self.owner[root]
        return root

    def _join(self, a: str, b: str) -> None:
        self.owner[self.body(a)] = self.body(b)

    def others(self, name: str) -> str:
        """The links fixed to ``name``, for messages: 'a, b' (at most four)."""
        rest = [n for n in self.members.get(self.body(name), []) if n != name]
        return ", ".join(rest[:4]) + (f" and {len(rest) - 4} more" if len(rest) > 4 else "")


@dataclass
class _Context:
    """What every link's inertia rules read: the links a joint moves, each link's tensor entries and principal
    moments (None when it has none or they do not read), its mass, the rigid bodies and the bases said (I007)."""

    moved: set[str]
    entries: list[tuple[float, ...] | None]
    moments: list[Any]
    masses: dict[str, float | None]
    bodies: _Bodies
    moved_bodies: set[str]
    said_base: set[str] = field(default_factory=set)
    reaches: ReachMemo = field(default_factory=lambda: ReachMemo(None))  # (I008, I009: each geometry's, made once)
    said_i008: dict[tuple[Any, ...], str | None] = field(default_factory=dict)  # (a geometry and inertial: I008)
    # (links judged on their own, with their mass and tensor entries: I009 compares them)
    significant: dict[str, tuple[float, tuple[float, ...]]] = field(default_factory=dict)


def _context(doc: Doc) -> _Context:
    moved = {j.child for j in doc.view.joints if j.type in MOVING and j.child is not None}
    # (ixx, ixy, ixz, iyy, iyz, izz) of every link that has them; the principal moments of all the finite ones in one
    # batched eigvalsh, consumed in link order below (per-link numpy calls cost ten times more)
    entries = [_inertia_entries(link) for link in doc.view.links]
    finite = [e is not None and all(math.isfinite(v) for v in e) for e in entries]
    moments_in_order = iter(principal_moments([e for e in entries if e is not None and all(map(math.isfinite, e))]))
    moments_of = [next(moments_in_order) if ok else None for ok in finite]
    masses = {link.name: _mass(link) for link in doc.view.links}
    solid = {
        link.name
        for link, moments in zip(doc.view.links, moments_of, strict=True)
        if moments is not None and max(moments) >= ZERO_MOMENT and moments_problem(moments) is None
    }
    bodies = _Bodies(doc, masses, solid)
    return _Context(moved, entries, moments_of, masses, bodies, {bodies.body(n) for n in moved})


def inertia_rules(doc: Doc, meshes: MeshReach | None = None) -> Iterator[Finding]:
    """I001-I009 for every link; ``meshes`` reads a mesh's hull for I008 and I009 (without it, links drawn by meshes
    are not judged by them)."""
    context = _context(doc)
    context.reaches = ReachMemo(meshes)  # (a mesh's convex hull and solid; without meshes, they are not read)
    for link, entry, moments in zip(doc.view.links, context.entries, context.moments, strict=True):
        yield from _link_inertia(doc, context, link, entry, moments)
    yield from copied_inertias(doc, context.reaches, context.significant)


def _link_inertia(doc: Doc, context: _Context, view: Link, entry: Any, moments: Any) -> Iterator[Finding]:
    """One link's I001-I008, in the order a reader fixes them: the mass, then the tensor, then its size."""
    name, link = view.name, view.element
    body, mass = context.bodies.body(name), context.masses[name]
    inertial = view.inertial
    if inertial is not None and inertial.mass_line is not None and inertial.inertia is None:
        yield doc.finding(
            "I006",
            "link",
            name,
            "<inertial> has a mass but no <inertia>; urdfdom rejects it: give <inertia ixx iyy izz ixy ixz iyz> "
            "(kg*m^2)",
            link,
        )
    if mass is not None and not mass >= 0:
        yield doc.finding("I001", "link", name, f"mass is {mass}; it must be > 0 kg (or 0 on a massless frame)", link)
        return
    if body not in context.bodies.massive:
        yield from _massless(doc, context, view, body)
        return
    if entry is None or moments is None:
        if entry is not None:
            yield doc.finding("I002", "link", name, "the inertia tensor has unreadable entries", link)
        return
    if max(abs(m) for m in moments) < ZERO_MOMENT:  # (a point mass, or a massless frame's zeros)
        if mass and body not in context.bodies.solid and body in context.moved_bodies:
            yield doc.finding(
                "I002",
                "link",
                name,
                f"mass {mass:g} kg with no rotational inertia (all principal moments below {ZERO_MOMENT:g} "
                "kg*m^2), and no link fixed to it has any: give the body its inertia",
                link,
            )
        return
    problem = _tensor_problem(moments)
    if problem is not None:
        # per link, not per rigid body: MuJoCo reads each link's tensor before it fuses fixed links, and rejects
        # any that is not all zero and not a rigid body's (a part's tensor fused into a solid body included)
        rule, said = problem
        yield doc.finding(rule, "link", name, said, link)
        return
    # a link of a tenth of its body's mass or less (an IMU frame on a trunk) changes the body's dynamics by little:
    # a placeholder or an odd size there is no mistake worth a warning
    if mass and mass >= SIGNIFICANT * context.bodies.mass.get(body, 0.0):
        context.significant[name] = (mass, tuple(entry))
        yield from _placeholder(doc, link, name, entry)
        yield from _plausibility(doc, view, mass, sum(moments))
        message = _geometry_message(context, view, mass, entry)
        if message is not None:
            yield doc.finding("I008", "link", name, message, link)


def _geometry_message(context: _Context, view: Link, mass: float, entry: tuple[float, ...]) -> str | None:
    """I008's message for a link (None: nothing to say), worked out once for each geometry and inertial: the copies of
    a fleet's robot, or a hand's identical fingers, are judged once."""
    origin = view.inertial.origin if view.inertial is not None else None
    key = (geometry_key(view), None if origin is None else (origin.xyz, origin.rpy), mass, tuple(entry))
    if key not in context.said_i008 and fits_at_a_glance(view, origin, mass, entry):
        context.said_i008[key] = None  # (far inside the bounds, shown without numpy: nothing to say)
    if key not in context.said_i008:
        reach = context.reaches.reach(view)
        context.said_i008[key] = None if reach is None else geometry_message(origin, mass, entry, reach)
    return context.said_i008[key]


def _massless(doc: Doc, context: _Context, view: Link, body: str) -> Iterator[Finding]:
    """I001 for a moved link of a body without mass; I007 (once per base) for a base with geometry but no mass."""
    name, link = view.name, view.element
    if name in context.moved:
        fixed = context.bodies.others(name)
        what = f"neither it nor a link fixed to it ({fixed}) has a mass" if fixed else "it has no mass"
        yield doc.finding(
            "I001",
            "link",
            name,
            f"it is moved by a joint but {what}: give it <inertial> with mass > 0 (kg) and its inertia "
            "(simulators cannot move a massless body; MuJoCo rejects it, even between two joints)",
            link,
        )
        return
    has_geometry = bool(view.visuals or view.collisions)
    if doc.fixed_to_world:  # (its base is fixed: the file says so, and a fixed base needs no mass)
        return
    if has_geometry and body not in context.moved_bodies and body not in context.said_base:
        context.said_base.add(body)
        yield doc.finding(
            "I007",
            "link",
            name,
            "the robot's base has geometry but no mass anywhere (it or a link fixed to it): enough for a "
            "fixed base, but a simulator that lets the robot move (a mobile base in Gazebo) needs its mass",
            link,
        )


def _placeholder(doc: Doc, link: Any, name: str, entry: tuple[float, ...]) -> Iterator[Finding]:
    """I005: a round multiple of the identity, the placeholder tensor."""
    ixx = entry[0]
    if is_placeholder(*entry):
        yield doc.finding(
            "I005",
            "link",
            name,
            f"inertia is {ixx:g} * identity, a common placeholder; compute it from the body (e.g. xacrokit's inertia "
            "macros)",
            link,
        )


def _tensor_problem(moments: tuple[float, ...] | list[float]) -> tuple[str, str] | None:
    """(rule, message) for principal moments no rigid body has, or None. Moments within rounding of zero (1e-9 of the
    largest) are zero: a rod's or a sheet's tensor, which no real part has, is I002 like a negative moment."""
    problem = moments_problem(moments)
    if problem is None:
        return None
    if problem == "triangle-inequality":
        return "I003", describe_problem(problem, moments) + " (a real body's always are; MuJoCo rejects it)"
    shown = format_moments(moments)
    if min(moments) < -max(ZERO_MOMENT, TOLERANCE * max(abs(m) for m in moments)):
        return "I002", (
            f"the inertia tensor has a negative principal moment ({shown} kg*m^2); every principal moment of a "
            "body is > 0 (MuJoCo rejects it): the entries are wrong (a sign, or products of inertia where zeros were "
            "meant?)"
        )
    return "I002", (
        f"the inertia tensor has a principal moment of zero ({shown} kg*m^2): a thin rod's or a flat sheet's, "
        "which no real part has; MuJoCo rejects it (write all six entries 0 for a point mass, or give the part its "
        "thickness)"
    )


def _mass(link: Link) -> float | None:
    inertial = link.inertial
    if inertial is None or inertial.mass_line is None:
        return None
    return number_of({"value": inertial.mass} if inertial.mass is not None else None, "value")


def _inertia_entries(link: Link) -> tuple[float, ...] | None:
    inertia = link.inertial.inertia if link.inertial is not None else None
    return None if inertia is None else tuple(number_of(inertia, key, 0.0) or 0.0 for key in _INERTIA)


def _plausibility(doc: Doc, view: Link, mass: float, trace: float) -> Iterator[Finding]:
    """Compare trace(I) with a solid box filling the collision geometry: m * diagonal^2 / 6, the box bounding every
    collision geometry where it sits (several small spheres far apart make a large body)."""
    low, high = [math.inf] * 3, [-math.inf] * 3
    collisions = view.collisions
    for collision in collisions:
        extent = _geometry_extent(collision.shape)
        if extent is None or not all(math.isfinite(v) for v in extent):
            return  # (a mesh, or an unreadable size: the body's size is not known)
        if max(extent) <= MARKER:
            return  # (a dummy collision, a 1 mm sphere some exporters write: it says nothing of the body's size)
        origin = collision.origin
        centre = triple_of(origin.xyz if origin is not None else None)
        turned = any(v != 0 for v in triple_of(origin.rpy)) if origin is not None else False
        radius = 0.5 * math.sqrt(sum(v * v for v in extent))  # (turned: the bounding sphere holds it in any pose)
        half = (radius, radius, radius) if turned else tuple(v / 2 for v in extent)
        for axis in range(3):
            low[axis] = min(low[axis], centre[axis] - half[axis])
            high[axis] = max(high[axis], centre[axis] + half[axis])
    if not collisions or not all(math.isfinite(v) for v in (*low, *high)):
        return
    spans = [high[axis] - low[axis] for axis in range(3)]
    diagonal_sq = sum(span * span for span in spans)  # (not ** 2, which raises OverflowError on a float of 1e300)
    expected = mass * diagonal_sq / 6.0
    if not math.isfinite(expected):
        return
    if expected > 0 and not 1e-2 <= trace / expected <= 1e2:
        yield doc.finding(
            "I004",
            "link",
            view.name,
            f"inertia (trace {trace:.3g} kg*m^2) is {trace / expected:.3g} times "
            f"that of a solid body filling the collision geometry ({expected:.3g}); "
            "a units mistake (mm for m, g for kg)?",
            view.element,
        )
