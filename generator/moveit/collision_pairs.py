"""Which pairs of a robot's links never need a collision check, found the way MoveIt's setup assistant finds them
(moveit_setup_assistant, compute_default_collisions.cpp), on the URDF's collision geometry with pinocchio's geometry
model and coal:

* ``Adjacent``: a joint's parent and child, and links joined through links without collision geometry (the setup
  assistant's connection graph: a link without geometry joins every link it touches);
* ``Default``: in collision at the home pose (the setup assistant's is its default state: 0, or mid-limits);
* ``Always``: in collision in at least 95 % of the sampled configurations (the setup assistant judges rounds of 200);
* ``Never``: in collision in none of them (10,000 by default, as the setup assistant's default), and never closer
  than ``Sampling.margin`` (5 cm) either: stricter than the setup assistant, whose pairs that collide once in 50,000
  configurations (two grippers meeting between two arms) come out ``Never`` from 10,000, and are then never checked.
  A pair that comes within the margin stays checked; one that never does is far from colliding in every sample.

Configurations are drawn uniformly within each joint's limits (a continuous joint over one turn, -pi to pi), mimic
joints following their leaders, from a numpy generator seeded with ``Sampling.seed``: the same seed gives the same
pairs. A pair is decided as soon as it has collided once and been free in more than 5 % of the samples; the others
stay in the batch pinocchio checks in parallel, so the cost is that of the pairs that stay free (most of them).
"""

from __future__ import annotations

import itertools
import math
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pinocchio as pin

from ..shared.quiet_stderr import quietly
from ..shared.urdf_view import UrdfView, number
from .collision_matrix import Judged, Pair, Sampling, adjacent_pairs, collision_text, pair

BATCH = 500  # configurations pinocchio checks in one parallel call (pairs decided between batches drop out)


@dataclass(frozen=True)
class Follower:
    """A mimic joint's place in q, its leader's, and its value's rule (multiplier x leader + offset)."""

    q_index: int
    leader: int
    multiplier: float
    offset: float


@dataclass(frozen=True)
class CollisionBodies:
    """A robot's kinematic model and collision geometry (pinocchio's), the link of each geometry object, the joints
    one sets (``joints``: name -> (q index, lower, upper), a continuous joint's upper None: its q is cos and sin),
    the mimic joints, the adjacent pairs, and the pairs a floating or planar joint moves apart (``unbounded``: a
    sample cannot judge them)."""

    model: Any
    geometry: Any
    links: tuple[str, ...]
    joints: Mapping[str, tuple[int, float, float | None]]
    followers: tuple[Follower, ...]
    adjacent: frozenset[Pair]
    unbounded: frozenset[Pair] = frozenset()
    meshes: bool = False  # (some collision geometry is a mesh)

    @property
    def pairs(self) -> list[Pair]:
        """Every pair of two links with collision geometry, in order."""
        return sorted(pair(a, b) for a, b in itertools.combinations(sorted(set(self.links)), 2))


def collision_bodies(
    view: UrdfView, base: Path, packages: Mapping[str, str | os.PathLike[str]] | None
) -> CollisionBodies:
    """The :class:`CollisionBodies` of a URDF (``view``: its parse), meshes found from ``base`` and ``packages``.

    Raises:
        LookupError, ValueError: a collision mesh whose file cannot be found.
        ValueError: pinocchio refused the URDF (its words).
    """
    text, meshes = collision_text(view, base, packages)
    return bodies_of(view, text, meshes=bool(meshes))


def bodies_of(view: UrdfView, text: str, *, meshes: bool) -> CollisionBodies:
    """The :class:`CollisionBodies` of a URDF (``view``: its parse) from the text pinocchio reads of it
    (:func:`.collision_matrix.collision_text`; ``meshes``: whether its collision geometry holds meshes). Raises
    ValueError: pinocchio refused it (its words)."""
    built, failure, said = quietly(lambda: _models(text))
    if failure is not None:
        raise ValueError(f"pinocchio cannot read the robot: {failure}") from None
    model, geometry = built
    links = tuple(model.frames[g.parentFrame].name for g in geometry.geometryObjects)
    joints, free = _sampled_joints(model)
    followers = tuple(
        Follower(
            joints[j.name][0],
            joints[j.mimic.joint][0],
            number(j.mimic.multiplier, 1.0),
            number(j.mimic.offset, 0.0),
        )
        for j in view.joints
        if j.mimic is not None and j.name in joints and j.mimic.joint in joints
    )
    unbounded = _unbounded_pairs(model, geometry, links, free)
    adjacent = adjacent_pairs(((j.parent, j.child) for j in view.joints), set(links))
    return CollisionBodies(model, geometry, links, joints, followers, adjacent, unbounded, meshes)


def _models(text: str) -> tuple[Any, Any]:
    """pinocchio's model of a URDF text and its collision geometry model (coal's shapes)."""
    model = pin.buildModelFromXML(text)
    return model, pin.buildGeomFromUrdfString(model, text, pin.COLLISION)


def _sampled_joints(model: Any) -> tuple[dict[str, tuple[int, float, float | None]], set[int]]:
    """The joints sampled (name -> (q index, lower, upper); a continuous joint's upper None) and the indices of those
    that are not: a floating or planar joint, one without finite limits (no sample spans them)."""
    joints: dict[str, tuple[int, float, float | None]] = {}
    free = set()
    for index in range(1, model.njoints):
        name, joint = model.names[index], model.joints[index]
        lower, upper = model.lowerPositionLimit[joint.idx_q], model.upperPositionLimit[joint.idx_q]
        if joint.nq == 2 and joint.shortname().startswith("JointModelRUB"):
            joints[name] = (joint.idx_q, -math.pi, None)
        elif joint.nq == 1 and math.isfinite(lower) and math.isfinite(upper):
            joints[name] = (joint.idx_q, float(lower), float(upper))
        else:
            free.add(index)
    return joints, free


def _unbounded_pairs(model: Any, geometry: Any, links: tuple[str, ...], free: set[int]) -> frozenset[Pair]:
    """Pairs of links that an unsampled joint (:func:`_sampled_joints`) moves apart: never judged Never or Always."""
    above: dict[str, set[int]] = {}
    for obj, link in zip(geometry.geometryObjects, links, strict=True):
        above.setdefault(link, set()).update(set(model.supports[obj.parentJoint]) & free)
    return frozenset(pair(a, b) for a, b in itertools.combinations(sorted(above), 2) if above[a] != above[b])


def configuration(bodies: CollisionBodies, values: Mapping[str, float]) -> np.ndarray:
    """pinocchio's q with each joint at ``values`` (a joint not given at 0, or its limit nearest 0), mimic joints
    following their leaders."""
    angles = pin.neutral(bodies.model).copy()
    for name, (index, lower, upper) in bodies.joints.items():
        value = float(values.get(name, 0.0))
        angles[index] = value if upper is None else min(max(value, lower), upper)
    return _as_q(bodies, angles[None, :])[0]


def random_configurations(bodies: CollisionBodies, count: int, seed: int) -> np.ndarray:
    """``count`` configurations (rows of q) drawn uniformly within the limits from numpy's generator at ``seed``."""
    rng = np.random.default_rng(seed)
    angles = np.tile(pin.neutral(bodies.model), (count, 1))
    for index, lower, upper in bodies.joints.values():
        high = math.pi if upper is None else upper
        angles[:, index] = rng.uniform(lower, high, size=count) if high > lower else lower
    return _as_q(bodies, angles)


def _as_q(bodies: CollisionBodies, angles: np.ndarray) -> np.ndarray:
    """Rows of joint values (a continuous joint's angle at its first q slot) as pinocchio's q: mimic joints set from
    their leaders, continuous joints as (cos, sin)."""
    for follower in bodies.followers:
        angles[:, follower.q_index] = follower.multiplier * angles[:, follower.leader] + follower.offset
    q = angles.copy()
    for index, _, upper in bodies.joints.values():
        if upper is None:
            q[:, index], q[:, index + 1] = np.cos(angles[:, index]), np.sin(angles[:, index])
    return q


def colliding_pairs(bodies: CollisionBodies, q: np.ndarray, pairs: list[Pair] | None = None) -> set[Pair]:
    """The pairs of links (of ``pairs``, default all) whose collision geometries intersect at ``q``."""
    geometry = _with_pairs(bodies, bodies.pairs if pairs is None else pairs)
    data, geometry_data = bodies.model.createData(), pin.GeometryData(geometry)
    pin.computeCollisions(bodies.model, data, geometry, geometry_data, q, False)
    return _hits(bodies, geometry, geometry_data)


def _hits(bodies: CollisionBodies, geometry: Any, geometry_data: Any) -> set[Pair]:
    """The pairs of links the last computeCollisions found in collision."""
    results = geometry_data.collisionResults
    return {
        pair(bodies.links[objects.first], bodies.links[objects.second])
        for objects, result in zip(geometry.collisionPairs, results, strict=True)
        if result.isCollision()
    }


def _with_pairs(bodies: CollisionBodies, pairs: list[Pair]) -> Any:
    """A copy of the geometry model checking the object pairs of ``pairs`` (every object of one link against every
    object of the other), none else."""
    geometry = bodies.geometry.copy()
    geometry.removeAllCollisionPairs()
    objects: dict[str, list[int]] = {}
    for index, link in enumerate(bodies.links):
        objects.setdefault(link, []).append(index)
    for first, second in pairs:
        for a in objects[first]:
            for b in objects[second]:
                geometry.addCollisionPair(pin.CollisionPair(min(a, b), max(a, b)))
    return geometry


def disabled_pairs(bodies: CollisionBodies, home: np.ndarray, sampling: Sampling) -> Judged:
    """Each pair whose check MoveIt may skip, with its reason (:data:`REASONS`), in order, and how many
    configurations judged them (fewer than asked when the robot has too many pairs within reach of each other for
    the sampling's budget)."""
    found = {p: "Adjacent" for p in bodies.adjacent}
    apart = far_apart(bodies, sampling.margin)
    found.update({p: "Never" for p in apart if p not in found})  # (beyond reach of each other: no sample needed)
    rest = [p for p in bodies.pairs if p not in found]
    if len(rest) > MAX_PAIRS:
        return Judged(dict(sorted(found.items())), 0, len(rest))
    found.update({p: "Default" for p in sorted(colliding_pairs(bodies, home, rest))})
    rest = [p for p in rest if p not in found and p not in bodies.unbounded]
    if bodies.meshes and not sampling.meshes:  # (TIAGo dual's 10,000 samples took 447 s: asked for, not default)
        return Judged(dict(sorted(found.items())), 0, len(rest), meshes=True)
    samples = min(sampling.samples, sampling.budget // max(1, len(rest)))
    if samples < MIN_SAMPLES:
        return Judged(dict(sorted(found.items())), 0, len(rest))
    q = random_configurations(bodies, samples, sampling.seed)
    near = collision_counts(bodies, rest, q, margin=sampling.margin, enough=lambda hits, free: hits > 0)
    found.update({p: "Never" for p, hits in near.items() if hits == 0})
    free_enough = (1.0 - sampling.always) * samples
    touched = [p for p, hits in near.items() if hits]
    counts = collision_counts(bodies, touched, q, enough=lambda hits, free: hits > 0 and free > free_enough)
    found.update({p: "Always" for p, hits in counts.items() if hits >= sampling.always * samples})
    return Judged(dict(sorted(found.items())), samples, len(rest))


MAX_PAIRS = 200_000  # pairs within reach of each other beyond which not even home is judged (a 630-link chain)
MIN_SAMPLES = 1_000  # fewer samples than this judge nothing: Never would be a guess


def far_apart(bodies: CollisionBodies, margin: float) -> set[Pair]:
    """Pairs of links that no configuration brings within ``margin``: each geometry object stays in a ball about the
    origin of the first moving joint above it (the sum of the lengths below that joint, a prismatic joint's longest
    travel, and the object's own bounding radius; a fixed object, its bounding ball), and two balls farther apart
    than their radii and the margin hold objects that never meet (a fleet's robots, an arm and a far table)."""
    centres, radii = _reach_balls(bodies)
    gap = np.linalg.norm(centres[:, None, :] - centres[None, :, :], axis=2) - radii[:, None] - radii[None, :]
    links = bodies.links
    close = {pair(links[a], links[b]) for a, b in zip(*np.nonzero(gap <= margin), strict=True) if links[a] != links[b]}
    return {p for p in bodies.pairs if p not in close}


def _reach_balls(bodies: CollisionBodies) -> tuple[np.ndarray, np.ndarray]:
    """Each geometry object's ball (centre, radius) in the root's frame that holds it in every configuration."""
    model = bodies.model
    data = model.createData()
    pin.forwardKinematics(model, data, pin.neutral(model))
    centres, radii = [], []
    for obj in bodies.geometry.geometryObjects:
        obj.geometry.computeLocalAABB()
        local = obj.placement.act(np.asarray(obj.geometry.aabb_center, dtype=float))
        chain = list(model.supports[obj.parentJoint])[1:]
        if not chain:
            centres.append(local)
            radii.append(float(obj.geometry.aabb_radius))
            continue
        reach = float(np.linalg.norm(local)) + float(obj.geometry.aabb_radius)
        reach += sum(float(np.linalg.norm(model.jointPlacements[k].translation)) for k in chain[1:])
        reach += sum(_travel(model, k) for k in chain)
        centres.append(np.asarray(data.oMi[model.parents[chain[0]]].act(model.jointPlacements[chain[0]].translation)))
        radii.append(reach)
    return np.array(centres).reshape(-1, 3), np.array(radii)


def _travel(model: Any, index: int) -> float:
    """How far a joint moves its child's origin: 0 for a revolute joint, a prismatic joint's longest travel, and
    infinity for any other (planar, floating: no bound)."""
    kind = model.joints[index].shortname()
    if kind in PRISMATIC:
        q = model.joints[index].idx_q
        return float(max(abs(model.lowerPositionLimit[q]), abs(model.upperPositionLimit[q])))
    return 0.0 if kind.startswith("JointModelR") else math.inf  # (RX, RUBZ, RevoluteUnaligned, ...)


PRISMATIC = ("JointModelPX", "JointModelPY", "JointModelPZ", "JointModelPrismaticUnaligned")


def collision_counts(
    bodies: CollisionBodies,
    pairs: list[Pair],
    q: np.ndarray,
    *,
    margin: float = 0.0,
    enough: Callable[[int, int], bool],
) -> dict[Pair, int]:
    """How many configurations of ``q`` (rows) bring each pair closer than ``margin`` (0: into collision), a pair
    counted until ``enough(hits, free)`` says its verdict cannot change (then dropped from the batches to come)."""
    counts = dict.fromkeys(pairs, 0)
    open_pairs, seen = list(pairs), dict.fromkeys(pairs, 0)
    threads = max(1, min(4, os.cpu_count() or 1))
    for start in range(0, len(q), BATCH):
        if not open_pairs:
            break
        batch = q[start : start + BATCH]
        geometry = _with_pairs(bodies, open_pairs)
        pool = pin.GeometryPool(bodies.model, geometry, threads)
        for pooled in pool.getGeometryDatas():
            _set_margin(pooled, margin)
        hits = pin.computeCollisionsInParallel(threads, pool, batch.T)
        data, geometry_data = bodies.model.createData(), pin.GeometryData(geometry)
        _set_margin(geometry_data, margin)
        for row in np.flatnonzero(hits):
            pin.computeCollisions(bodies.model, data, geometry, geometry_data, batch[row], False)
            for p in _hits(bodies, geometry, geometry_data):
                counts[p] += 1
        for p in open_pairs:
            seen[p] += len(batch)
        open_pairs = [p for p in open_pairs if not enough(counts[p], seen[p] - counts[p])]
    return counts


def _set_margin(geometry_data: Any, margin: float) -> None:
    """Every pair of ``geometry_data`` in collision when closer than ``margin`` (coal's security margin)."""
    for request in geometry_data.collisionRequests:
        request.security_margin = margin
