"""The SRDF's collision matrix (issue 44): how long sampling takes against the sample count, and whether an
independent sample of 100,000 configurations finds any pair the SRDF marks Never in collision.

- ``speed``: the Panda example (7 joints) carrying the scene example's parallel gripper (a scene made here), and the
  two-arm cell: seconds of :func:`xacrokit.moveit.collision_pairs.disabled_pairs` (the bodies built once, outside
  the clock) for 1,000, 10,000 (the default) and 100,000 samples, one run each, with their ratio to 10,000;
- ``never``: every example's generated SRDF against COUNT configurations (default 100,000) drawn here with another
  seed, straight through pinocchio and coal (a GeometryPool of the Never pairs alone, checked in parallel batches),
  not through xacrokit's sampler; it prints each example's Never pairs and those found colliding (target: none).

Usage: python benchmarks/srdf_speed.py [speed | never [COUNT]] (both by default)
"""

from __future__ import annotations

import math
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pinocchio as pin
from lxml import etree

import xacrokit
from xacrokit.moveit.collision_pairs import Sampling, collision_bodies, configuration, disabled_pairs
from xacrokit.moveit.moveit_package import semantics_of
from xacrokit.shared.urdf_view import read_view

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = sorted((REPO / "examples" / "robots").glob("*.yaml")) + sorted((REPO / "examples" / "scenes").glob("*.yaml"))
SEED = 12_345
PANDA_WITH_GRIPPER = f"""scene: panda_gripper
instances:
  panda: {{spec: {REPO / "examples/robots/industrial_arm_mod_dh.yaml"}, prefix: "", parent: world}}
  hand: {{spec: {REPO / "examples/scenes/robots/gripper.yaml"}, prefix: hand_, parent: panda/panda_link8}}
"""


def speed(folder: Path) -> None:
    folder.mkdir(parents=True)
    scene = folder / "panda_gripper.yaml"
    scene.write_text(PANDA_WITH_GRIPPER, encoding="utf-8")
    for spec in (scene, REPO / "examples/scenes/two_arm_cell.yaml"):
        result = xacrokit.generate(spec, folder / spec.stem)
        view = read_view(result.urdf)
        bodies = collision_bodies(view, folder / spec.stem / "urdf", {result.package: folder / spec.stem})
        home = configuration(bodies, dict(semantics_of(result.model).home))
        times = {}
        for count in (1_000, 10_000, 100_000):
            start = time.perf_counter()
            judged = disabled_pairs(bodies, home, Sampling(samples=count))
            times[count] = time.perf_counter() - start
            reasons = {r: list(judged.disabled.values()).count(r) for r in ("Adjacent", "Default", "Never", "Always")}
            print(
                f"{spec.stem}: {bodies.model.nq} q, {len(bodies.pairs)} pairs, {count:>7,} samples: "
                f"{times[count]:.3f} s {reasons}"
            )
        print(
            f"{spec.stem}: t(1,000)/t(10,000) {times[1_000] / times[10_000]:.2f}, "
            f"t(100,000)/t(10,000) {times[100_000] / times[10_000]:.2f}"
        )


def never(folder: Path, count: int) -> int:
    colliding_total = 0
    for spec in EXAMPLES:
        root = folder / spec.stem
        result = xacrokit.generate(spec, root / "pkg")
        package = root / result.package
        result.output.rename(package)
        urdf, srdf = package / "urdf" / f"{result.name}.urdf", package / "config" / f"{result.name}.srdf"
        model = pin.buildModelFromUrdf(str(urdf))
        geometry = pin.buildGeomFromUrdf(model, str(urdf), pin.COLLISION, package_dirs=[str(root)])
        link = [model.frames[g.parentFrame].name for g in geometry.geometryObjects]
        never_pairs = {
            frozenset((e.get("link1"), e.get("link2")))
            for e in etree.parse(str(srdf)).getroot().iter("disable_collisions")
            if e.get("reason") == "Never"
        }
        for a in range(len(link)):
            for b in range(a + 1, len(link)):
                if frozenset((link[a], link[b])) in never_pairs:
                    geometry.addCollisionPair(pin.CollisionPair(a, b))
        start = time.perf_counter()
        found = colliding(model, geometry, link, mimics(urdf), count) if geometry.collisionPairs else set()
        colliding_total += len(found)
        print(
            f"{spec.stem}: {len(never_pairs)} Never pairs, {count:,} configurations (seed {SEED}) in "
            f"{time.perf_counter() - start:.1f} s: {len(found)} colliding {sorted(map(sorted, found))}"
        )
    return colliding_total


def mimics(urdf: Path) -> dict[str, tuple[str, float, float]]:
    root = etree.parse(str(urdf)).getroot()
    return {
        j.get("name"): (m.get("joint"), float(m.get("multiplier", 1)), float(m.get("offset", 0)))
        for j in root.findall("joint")
        if (m := j.find("mimic")) is not None
    }


def colliding(model, geometry, link, rules, count: int) -> set[frozenset[str]]:
    """The Never pairs found in collision in ``count`` configurations, uniform within the URDF's limits."""
    rng = np.random.default_rng(SEED)
    q = np.tile(pin.neutral(model), (count, 1))
    angle = {}
    for index in range(1, model.njoints):
        joint = model.joints[index]
        lower, upper = model.lowerPositionLimit[joint.idx_q], model.upperPositionLimit[joint.idx_q]
        if joint.nq == 2:
            angle[model.names[index]] = values = rng.uniform(-math.pi, math.pi, count)
            q[:, joint.idx_q], q[:, joint.idx_q + 1] = np.cos(values), np.sin(values)
        elif joint.nq == 1 and np.isfinite(lower) and np.isfinite(upper):
            angle[model.names[index]] = q[:, joint.idx_q] = rng.uniform(lower, upper, count)
    for follower, (leader, multiplier, offset) in rules.items():
        joint = model.joints[model.getJointId(follower)]
        q[:, joint.idx_q] = multiplier * angle[leader] + offset
    pool = pin.GeometryPool(model, geometry, 2)
    hits = pin.computeCollisionsInParallel(2, pool, np.asfortranarray(q.T))
    found: set[frozenset[str]] = set()
    data, geometry_data = model.createData(), pin.GeometryData(geometry)
    for row in np.flatnonzero(hits):
        pin.computeCollisions(model, data, geometry, geometry_data, q[row], False)
        for p, r in zip(geometry.collisionPairs, geometry_data.collisionResults, strict=True):
            if r.isCollision():
                found.add(frozenset((link[p.first], link[p.second])))
    return found


def main(argv: list[str]) -> int:
    section = argv[0] if argv else "all"
    with tempfile.TemporaryDirectory() as scratch:
        if section in ("speed", "all"):
            speed(Path(scratch, "speed"))
        if section in ("never", "all"):
            count = int(argv[1]) if len(argv) > 1 else 100_000
            return 1 if never(Path(scratch, "never"), count) else 0
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
