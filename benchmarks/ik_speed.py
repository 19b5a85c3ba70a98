"""How fast and how well our inverse kinematics answers (issue 43, item 5), side by side with ikpy and
roboticstoolbox-python's ``ik_LM`` (C++), measured in one run on this machine.

Robots: the UR5 and the UR10e of the examples (closed form, three parallel axes), the KUKA KR 560 of the examples
(closed form, spherical wrist) and example-robot-data's Panda (7 axes: numeric). Each spec is generated to a URDF
first (``xacrokit.generate``) and every solver reads that one file; the Panda's URDF is read as it ships.

Targets: joint values drawn uniformly within the limits (seed 43), posed with pinocchio, then asked back. A solver's
answer counts when its joint values are within the limits and put the frame within 1e-6 of the target: the norm of
pinocchio's log6 of the relative pose (m and rad in one vector), computed here for every solver alike. The solvers
take turns target by target (the order rotating), so that the shared machine's noise falls on all of them, after
one untimed call each (imports; our numeric solver's atlas of posed configurations, made on its first solve); the
ratio is the median over targets of (its time / ours, first solution) on the same target.

- ours, first: ``ik_solver(robot, frame).solve(T)``, the solution nearest the rest pose; ours, every:
  ``solve(T, every=True)``, every branch (success: at least one, and a count of any answer that does not reach);
- roboticstoolbox ``ik_LM`` with its defaults (tol=1e-6 on E = 1/2 e^T e, e its angle-axis pose error: |e| up to
  1.4e-3), and with tol=5e-13 (|e| up to 1e-6, our threshold); a random start within the limits, up to 100 searches;
- ikpy ``inverse_kinematics_frame(T, orientation_mode="all")`` from the rest pose (0 clipped to the limits).

Taking turns, every call starts cold (the others' allocations between two of ours: a solve of ours after one of
ikpy's took twice as long as in a row on 2026-11-29); the rows "ours, first (in a row)" and "ours, every (in a row)"
time ours again target after target with nothing between (a loop over targets, as ``ik`` in a script runs).

A comparator that is not installed is named and left out (``pip install -e '.[bench]'`` brings them).

Usage: python benchmarks/ik_speed.py [TARGETS]   (targets per robot, default 500; a small count is a smoke run)
"""

from __future__ import annotations

import contextlib
import gc
import math
import statistics
import sys
import tempfile
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parent.parent
REACH = 1e-6  # the pose error a solution must reach to count
SEED = 43
Solve = Callable[[np.ndarray], list[np.ndarray]]  # a target -> joint vectors in our model's joint order


@dataclass(frozen=True)
class Arm:
    name: str
    source: str  # a spec of the examples, or a URDF of example-robot-data
    frame: str


ARMS = (
    Arm("UR5", "examples/robots/industrial_arm_std_dh.yaml", "tool0"),
    Arm("UR10e", "examples/robots/ur10e.yaml", "tool0"),
    Arm("KR 560", "examples/robots/kuka_kr560_r3100_2.yaml", "tool0"),
    Arm("Panda", "example-robot-data/robots/panda_description/urdf/panda.urdf", "panda_hand"),
)


@dataclass
class Tally:
    """One solver's figures on one robot."""

    times: list[float] = field(default_factory=list)  # s
    errors: list[float] = field(default_factory=list)  # its best answer's pose error (inf: none)
    missed: int = 0  # answers given that do not reach (every branch: each one checked)


def share() -> Path | None:
    for entry in sys.path:
        folder = Path(entry, "cmeel.prefix", "share")
        if (folder / "example-robot-data").is_dir():
            return folder
    return None


def urdf_of(arm: Arm, folder: Path) -> Path | None:
    """The URDF every solver reads: the spec generated, or example-robot-data's file (None when not installed)."""
    import xacrokit

    if arm.source.startswith("example-robot-data/"):
        found = share()
        return None if found is None else found / arm.source
    out = folder / Path(arm.source).stem
    xacrokit.generate(REPO / arm.source, out)
    return next((out / "urdf").glob("*.urdf"))


class Judge:
    """Our model of the robot, read once: targets drawn and every answer's pose error, with pinocchio."""

    def __init__(self, robot, frame: str) -> None:
        self.model = robot.kinematics
        self.names = [j.name for j in self.model.joints]
        self.lower = np.array([j.limits[0] if j.limits else -math.pi for j in self.model.joints])
        self.upper = np.array([j.limits[1] if j.limits else math.pi for j in self.model.joints])
        self.frame = self.model.frame_id(frame)
        self.root = self.model.frame_id(self.model.root)

    def placed(self, values: np.ndarray):
        import pinocchio as pin

        model = self.model
        q = model.configuration(dict(zip(self.names, map(float, values), strict=True)))
        pin.framesForwardKinematics(model.model, model.data, q)
        return model.data.oMf[self.root].actInv(model.data.oMf[self.frame])

    def targets(self, count: int, seed: int = SEED) -> list[np.ndarray]:
        rng = np.random.default_rng(seed)
        return [self.placed(rng.uniform(self.lower, self.upper)).homogeneous.copy() for _ in range(count)]

    def error(self, target: np.ndarray, values: np.ndarray) -> float:
        import pinocchio as pin

        if np.any(values < self.lower - 1e-9) or np.any(values > self.upper + 1e-9):
            return math.inf
        goal = pin.SE3(target[:3, :3], target[:3, 3])
        return float(np.linalg.norm(pin.log6(goal.actInv(self.placed(values))).vector))


def ours(robot, judge: Judge, frame: str, *, every: bool) -> Solve:
    from xacrokit.kinematics import ik_solver

    solver = ik_solver(robot, frame)  # (made once, before the clock: the closed form recognised)

    def solve(target: np.ndarray) -> list[np.ndarray]:
        found = solver.solve(target, every=every)
        return [np.array([s.values[n] for n in judge.names]) for s in found.solutions]

    return solve


def roboticstoolbox(path: Path, judge: Judge, frame: str, *, tol: float | None) -> Solve:
    import roboticstoolbox as rtb
    import xacrodoc.packages
    from roboticstoolbox.models.URDF.URDFRobot import URDF_read

    found = share()
    if found is not None:  # (the Panda's package:// meshes: roboticstoolbox expands every URDF with xacro)
        xacrodoc.packages.update_package_cache({"example-robot-data": str(found / "example-robot-data")})
    links, name, _ = URDF_read(path)  # (what rtb.Robot.URDF did; it is deprecated)
    robot = rtb.Robot(links, name=name)
    joints = {link.jindex: link._joint_name for link in robot.links if link.isjoint}  # (no public name for it)
    chain = [judge.names.index(joints[k]) for k in robot.ets(end=frame).jindices]
    options = {} if tol is None else {"tol": tol}
    rest = np.clip(np.zeros(len(judge.names)), judge.lower, judge.upper)

    def solve(target: np.ndarray) -> list[np.ndarray]:
        answer = robot.ik_LM(target, end=frame, **options)
        if not answer.success:
            return []
        values = rest.copy()
        values[chain] = answer.q
        return [values]

    return solve


def ikpy(path: Path, judge: Judge, frame: str, robot) -> Solve:
    from ikpy.chain import Chain

    by_child = {j.child: j for j in robot.view.joints}
    path_names: list[str] = [frame]
    while path_names[-1] in by_child:  # (ikpy follows a link's first child unless told the way)
        joint = by_child[path_names[-1]]
        path_names += [joint.name, joint.parent]
    path_names.reverse()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        whole = Chain.from_urdf_file(str(path), base_elements=path_names)
        links = whole.links[: 1 + (len(path_names) - 1) // 2]  # (the origin link, then one per joint of the way)
        chain = Chain(links, active_links_mask=[link.joint_type != "fixed" for link in links])
    columns = [(i, judge.names.index(link.name)) for i, link in enumerate(links) if link.joint_type != "fixed"]
    start = np.zeros(len(links))
    for i, k in columns:
        start[i] = min(max(0.0, judge.lower[k]), judge.upper[k])
    rest = np.clip(np.zeros(len(judge.names)), judge.lower, judge.upper)

    def solve(target: np.ndarray) -> list[np.ndarray]:
        answer = chain.inverse_kinematics_frame(target, initial_position=start, orientation_mode="all")
        values = rest.copy()
        for i, k in columns:
            values[k] = answer[i]
        return [values]

    return solve


def comparators(path: Path, judge: Judge, frame: str, robot, missing: dict[str, str]) -> dict[str, Solve]:
    made: dict[str, Solve] = {}
    makers = {
        "rtb ik_LM": lambda: roboticstoolbox(path, judge, frame, tol=None),
        "rtb ik_LM tol=5e-13": lambda: roboticstoolbox(path, judge, frame, tol=5e-13),
        "ikpy": lambda: ikpy(path, judge, frame, robot),
    }
    for name, make in makers.items():
        try:
            made[name] = make()
        except ImportError as exc:
            missing[name.split()[0]] = f"not installed ({exc.name})"
    return made


def run(solvers: dict[str, Solve], judge: Judge, targets: list[np.ndarray]) -> dict[str, Tally]:
    """Every solver on every target, taking turns (the order rotating target by target), each call timed alone."""
    tallies = {name: Tally() for name in solvers}
    order = list(solvers)
    for solve in solvers.values():  # (untimed: the first call's imports, scipy's Sobol for one, 2 s)
        solve(judge.targets(1, seed=SEED + 1)[0])
    gc.collect()
    gc.freeze()  # (what was made before: out of the collector's way, so that a collection costs what a solve made)
    for index, target in enumerate(targets):
        shift = index % len(order)
        for name in order[shift:] + order[:shift]:
            gc.disable()
            started = time.perf_counter()
            answers = solvers[name](target)
            elapsed = time.perf_counter() - started
            gc.enable()
            errors = [judge.error(target, values) for values in answers]
            tally = tallies[name]
            tally.times.append(elapsed)
            tally.errors.append(min(errors, default=math.inf))
            tally.missed += sum(e > REACH for e in errors)
        gc.collect()
    gc.unfreeze()
    return tallies


def in_a_row(solvers: dict[str, Solve], judge: Judge, targets: list[np.ndarray]) -> dict[str, Tally]:
    """Ours again, each target after the one before with nothing between (answers judged afterwards)."""
    tallies: dict[str, Tally] = {}
    for name in ("ours, first", "ours, every"):
        tally, answers = Tally(), []
        gc.collect()
        gc.disable()
        for target in targets:
            started = time.perf_counter()
            answers.append(solvers[name](target))
            tally.times.append(time.perf_counter() - started)
        gc.enable()
        for target, found in zip(targets, answers, strict=True):
            errors = [judge.error(target, values) for values in found]
            tally.errors.append(min(errors, default=math.inf))
            tally.missed += sum(e > REACH for e in errors)
        tallies[f"{name} (in a row)"] = tally
    return tallies


def rows(arm: str, tallies: dict[str, Tally]) -> list[str]:
    base = tallies["ours, first"].times
    lines = []
    for name, tally in tallies.items():
        n = len(tally.times)
        reached = sum(e <= REACH for e in tally.errors) / n
        fine = f" ({sum(e <= 1e-9 for e in tally.errors) / n:.1%} at 1e-9)" if name.startswith("ours") else ""
        finite = [e for e in tally.errors if math.isfinite(e)]
        residual = f"{statistics.median(finite):.1e}" if finite else "-"
        ratio = statistics.median(t / b for t, b in zip(tally.times, base, strict=True))
        missed = f" (answers not reaching: {tally.missed})" if tally.missed else ""
        lines.append(
            f"| {arm} | {name} | {n} | {reached:.1%}{fine} | {1e3 * statistics.median(tally.times):.3f} | "
            f"{1e3 * statistics.mean(tally.times):.3f} | {residual} | {ratio:.2f}{missed} |"
        )
    return lines


def machine() -> str:
    import os
    import platform
    from importlib.metadata import PackageNotFoundError, version

    cpu = platform.processor() or "?"
    with contextlib.suppress(OSError):
        names = [line for line in Path("/proc/cpuinfo").read_text().splitlines() if line.startswith("model name")]
        cpu = names[0].split(":", 1)[1].strip() if names else cpu
    found = []
    for package in ("numpy", "pin", "roboticstoolbox-python", "ikpy"):
        with contextlib.suppress(PackageNotFoundError):
            found.append(f"{package} {version(package)}")
    return f"Python {platform.python_version()}, {cpu}, {os.cpu_count()} cores; {', '.join(found)}"


def main(count: int) -> None:
    from xacrokit.reader.read_robot import read_robot

    print(machine())

    np.random.seed(SEED)  # (roboticstoolbox draws its starts from numpy's global generator)
    missing: dict[str, str] = {}
    table = [
        "| robot | solver | targets | success (<= 1e-6) | median ms | mean ms | median residual | ratio to ours |",
        "|---|---|---|---|---|---|---|---|",
    ]
    with tempfile.TemporaryDirectory() as folder:
        for arm in ARMS:
            path = urdf_of(arm, Path(folder))
            if path is None:
                print(f"{arm.name}: left out: example-robot-data is not installed (the test extra brings it)")
                continue
            robot = read_robot(path)
            judge = Judge(robot, arm.frame)
            solvers = {
                "ours, first": ours(robot, judge, arm.frame, every=False),
                "ours, every": ours(robot, judge, arm.frame, every=True),
            }
            solvers |= comparators(path, judge, arm.frame, robot, missing)
            from xacrokit.kinematics import ik_solver

            print(f"{arm.name}: {path.name}, frame {arm.frame}, ours {ik_solver(robot, arm.frame).method}")
            targets = judge.targets(count)
            table += rows(arm.name, run(solvers, judge, targets) | in_a_row(solvers, judge, targets))
    for name, why in missing.items():
        print(f"comparator unavailable: {name}: {why} (pip install -e '.[bench]')")
    print("\n".join(table))


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 500)
