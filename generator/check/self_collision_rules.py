"""G007: two links of a robot that collide with each other at its home pose, as MoveIt would find them (pinocchio's
geometry model and coal on the collision geometry), unless a joint joins them or the robot's SRDF disables the pair;
a note counts the pairs that never collide."""

from __future__ import annotations

import os
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import XacrokitError
from ..moveit.collision_pairs import (
    CollisionBodies,
    Pair,
    Sampling,
    colliding_pairs,
    collision_bodies,
    configuration,
    disabled_pairs,
)
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
            "the pair (the one given, NAME.srdf beside the URDF, or its package's config/NAME.srdf or srdf/NAME.srdf; "
            "a spec's is the one its package carries, which disables them as Default: G008 names them); a URDF whose "
            "collision geometry holds meshes is posed only when it has an SRDF (reading every mesh into coal costs "
            "about 5 times check's other rules)",
        ),
        "G008": (
            "never-colliding-pairs",
            "info",
            "a note on a robot with an SRDF (given, or beside the URDF as G007 finds it) or a spec: how many pairs of "
            "links never collide (the SRDF's Never pairs; a spec's, those never within 5 cm of each other in the "
            "10,000 configurations its package's SRDF is sampled from)",
        ),
    }
)

SAMPLING = Sampling()  # (a spec's note: as generating its package samples, 10,000 configurations)
SHOWN = 6  # pairs named in a note


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
    if sum(1 for link in doc.view.links if link.collisions) < 2:
        return
    srdf = given.srdf or (None if given.spec else srdf_beside(given.path))
    meshes = any(g.shape is not None and g.shape.kind == "mesh" for link in doc.view.links for g in link.collisions)
    if meshes and srdf is None and not given.spec:
        return  # (coal reading every collision mesh costs 5 times check's other rules: asked for by an SRDF)
    try:
        bodies = collision_bodies(doc.view, given.path.parent, given.packages)
    except (RuntimeError, ValueError, LookupError):
        return  # (a mesh not found, a URDF pinocchio refuses: R003 and the consumers say so)
    facts = SrdfFacts({}, {})
    if srdf is not None:
        try:
            facts = read_srdf(srdf)
        except XacrokitError as exc:
            yield doc.finding("G007", "robot", doc.view.name or "", f"{exc}: its disabled pairs are not respected")
            srdf = None  # (nor counted)
    home = configuration(bodies, {**given.home, **facts.home})  # (an SRDF's home: the spec's, where it came from)
    at_home = colliding_pairs(bodies, home) - bodies.adjacent
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
    if srdf is not None or given.spec:  # (a bare URDF gets no note: nothing says which pairs it means to skip)
        yield _note(doc, bodies, home, srdf, disabled, at_home if given.spec else set())


def _note(
    doc: Doc,
    bodies: CollisionBodies,
    home: np.ndarray,
    srdf: Path | None,
    disabled: dict[Pair, str],
    default: set[Pair],
) -> Finding:
    """The note on the pairs that never collide: the SRDF's count, else a sample's."""
    if srdf is not None:
        never = sum(1 for reason in disabled.values() if reason == "Never")
        said = f"{srdf.name} disables {len(disabled):,} pairs of links, {never:,} of them as never in collision"
    else:  # a spec: what its package's SRDF says, sampled as generating it samples
        judged = disabled_pairs(bodies, home, SAMPLING)
        never = sum(1 for reason in judged.disabled.values() if reason == "Never")
        said = (
            f"the package's SRDF (config/{doc.view.name}.srdf) disables {never:,} of {len(bodies.pairs):,} pairs of "
            f"links as never in collision (never within {SAMPLING.margin:g} m of each other in "
            f"{judged.samples:,} configurations, seed {SAMPLING.seed}, or beyond each other's reach)"
        )
    if default:
        named = ", ".join(f"{a}-{b}" for a, b in sorted(default)[:SHOWN]) + (", ..." if len(default) > SHOWN else "")
        said += f"; {len(default)} intersecting at home, which the package's SRDF disables as Default: {named}"
    return doc.finding("G008", "robot", doc.view.name or "", said)
