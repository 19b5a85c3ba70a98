"""G007: two links of a robot that collide with each other at its home pose, as MoveIt would find them (pinocchio's
geometry model and coal on the collision geometry), unless a joint joins them or the robot's SRDF disables the pair;
a note counts the pairs that never collide."""

from __future__ import annotations

import os
from collections.abc import Iterator, Mapping
from collections.abc import Set as AbstractSet
from dataclasses import dataclass
from pathlib import Path

from ..errors import XacrokitError
from ..moveit.collision_matrix import Pair, collision_text, home_pairs_key, kept_home_pairs
from ..moveit.srdf_reading import SrdfFacts, read_srdf, srdf_beside
from .findings import Finding, rule_table
from .urdf_document import Doc

RULES = rule_table(
    {
        "G007": (
            "no-self-collision-at-home",
            "warning",
            "no two links' collision geometries intersect at the robot's home pose (a spec's `home`, else its "
            "SRDF's and its ros2_control initial values, else every joint at 0 or its limit nearest 0) unless a "
            "joint joins them (directly, or through links without collision geometry) or the robot's SRDF disables "
            "the pair (the one given with --srdf FILE, NAME.srdf beside the URDF, or its package's config/NAME.srdf or "
            "srdf/NAME.srdf; "
            "a spec's is the one its package carries, which disables them as Default: G008 names them); a URDF whose "
            "collision geometry holds meshes is posed only when it has an SRDF (reading every mesh into coal costs "
            "about 5 times check's other rules), and a robot of more than 400 links with collision geometry not at "
            "all (the pairs outgrow memory)",
        ),
        "G008": (
            "never-colliding-pairs",
            "info",
            "a note on a robot with an SRDF (given, or beside the URDF as G007 finds it): how many pairs of links it "
            "disables as never colliding (gen-robot samples 10,000 configurations for them); on a spec whose links "
            "intersect at home: those pairs, which its package's SRDF disables as Default",
        ),
    }
)

SHOWN = 6  # pairs named in a note
MAX_SOLID = 400  # links with collision geometry posed at most (pinocchio's pairs grow with their square)


@dataclass(frozen=True)
class SelfCollisionInput:
    """What G007 reads besides the URDF document: where its meshes are, its home (joint -> value), the SRDF given
    (else the one beside the file is looked for) and whether the input is a spec (its package's SRDF is then the
    one that generating it writes)."""

    path: Path
    packages: Mapping[str, str | os.PathLike[str]] | None
    home: Mapping[str, float]
    srdf: Path | None = None
    spec: bool = False


def self_collision_rules(doc: Doc, given: SelfCollisionInput) -> Iterator[Finding]:
    """G007 for each pair in collision at home that no joint joins and no SRDF disables; notes on what the SRDF
    disables and on the pairs that never collide."""
    solid = sum(1 for link in doc.view.links if link.collisions)
    if solid < 2 or solid > MAX_SOLID:
        return  # (beyond MAX_SOLID links, the pairs' geometry model outgrows memory: a fleet of 3,000 links was killed)
    srdf = given.srdf or (None if given.spec else srdf_beside(given.path))
    meshes = any(g.shape is not None and g.shape.kind == "mesh" for link in doc.view.links for g in link.collisions)
    if meshes and srdf is None and not given.spec:
        return  # (coal reading every collision mesh costs 5 times check's other rules: asked for by an SRDF)
    try:
        text, mesh_files = collision_text(doc.view, given.path.parent, given.packages)
    except (ValueError, LookupError):
        return  # (a mesh not found: R003 says so)
    facts, complaint = SrdfFacts({}, {}), None
    if srdf is not None:
        try:
            facts = read_srdf(srdf)
        except XacrokitError as exc:
            said = f"{exc}: its disabled pairs are not respected"
            complaint = doc.finding("G007", "robot", doc.view.name or "", said)
            srdf = None  # (nor counted)
    at_home = _pairs_at_home(doc, text, mesh_files, {**given.home, **facts.home})  # (an SRDF's home: the spec's)
    if at_home is None:
        return  # (a mesh unreadable, a URDF pinocchio refuses: R003 and the consumers say so)
    if complaint is not None:
        yield complaint
    disabled = {p: "Default" for p in at_home} if given.spec else facts.disabled
    for first, second in sorted(at_home - disabled.keys()):
        link = doc.view.link(first)
        yield doc.finding(
            "G007",
            "link",
            first,
            f"its collision geometry intersects {second!r}'s at the home pose, and no joint joins them: a planner "
            "would find the robot in collision where it starts; move or shrink one of them, start elsewhere, or "
            f'disable the pair in an SRDF beside the URDF (reason="Default": gen-robot writes config/NAME.srdf)',
            link.element if link is not None else None,
        )
    note = _note(doc, srdf, disabled, at_home if given.spec else frozenset())
    if note is not None:  # (a bare URDF gets none: nothing says which pairs it means to skip)
        yield note


def _pairs_at_home(doc: Doc, text: str, meshes: list[Path], home: Mapping[str, float]) -> frozenset[Pair] | None:
    """The pairs of links whose collision geometries intersect at ``home`` and that no joint joins (pinocchio and
    coal on ``text``, :func:`~xacrokit.moveit.collision_matrix.collision_text`), kept in the user's cache folder for
    the next check of the same robot (the same text, mesh bytes, home and installs:
    :func:`~xacrokit.moveit.collision_matrix.home_pairs_key`); None when they cannot be posed."""
    try:
        key = home_pairs_key(text, meshes, home)
    except OSError:
        return None

    def pose() -> frozenset[Pair]:
        from ..moveit.collision_pairs import bodies_of, colliding_pairs, configuration  # (heavy: pinocchio)

        bodies = bodies_of(doc.view, text, meshes=bool(meshes))
        return frozenset(colliding_pairs(bodies, configuration(bodies, home)) - bodies.adjacent)

    try:
        return kept_home_pairs(key, pose)
    except (RuntimeError, ValueError, LookupError):
        return None  # (pinocchio or coal refused the robot: the consumers say so)


def _note(doc: Doc, srdf: Path | None, disabled: dict[Pair, str], default: AbstractSet[Pair]) -> Finding | None:
    """The note: the SRDF's count of pairs disabled as never colliding; a spec's pairs that intersect at home, which
    its package's SRDF disables as Default (None for a spec without any: its package's SRDF says the rest)."""
    said = ""
    if srdf is not None:
        never = sum(1 for reason in disabled.values() if reason == "Never")
        said = f"{srdf.name} disables {len(disabled):,} pairs of links, {never:,} of them as never in collision"
    if default:
        named = ", ".join(f"{a}-{b}" for a, b in sorted(default)[:SHOWN]) + (", ..." if len(default) > SHOWN else "")
        said = (
            f"{len(default)} pairs of links intersect at home, which the package's SRDF (config/{doc.view.name}.srdf) "
            f"disables as Default: {named}"
        )
    return doc.finding("G008", "robot", doc.view.name or "", said) if said else None
