"""How long `gen-robot check` takes on real robots, against its consumers run alone (issue 14, item 6).

For real URDFs of about 10, 50 and 130 links (example-robot-data, which the test extra installs), each timed as a
process, median of RUNS runs, all runs of a file interleaved (so that a slow moment of the machine hits them alike):

- ``check``: ``gen-robot check FILE`` with every consumer (check_urdf, pinocchio, yourdfpy, MuJoCo);
- each consumer alone, as check runs it (check_urdf's binary; ``python -m xacrokit.check.consumers NAME FILE``);
- ``rules``: ``gen-robot check FILE --consumers none`` (our rules alone).

It prints the ratio check / slowest consumer alone (target <= 1.2; it was 1.5) and the rules' time (target < 0.3 s on
130 links). Since issue 45 it also times ``yourdfpy+meshes``: a process that loads the URDF with yourdfpy as its users
do, meshes and all (``yourdfpy.URDF.load(FILE)``), a consumer that check does not run but that a user compares with;
the ratio is also given against the slowest of all five. The commands of a run go in one order, the next run's in
the reverse (pairs side by side), and each ratio is the median of the runs' own ratios; CPU time (user + system,
children included: the consumers' too) is printed beside wall time, since a loaded machine disturbs it less, and the
load average with each robot. On a machine whose CPUs other work keeps busy, check's processes share what the kernel
gives one session (autogroup), so its wall ratio approaches its CPU ratio: the target is for a quiet machine. Run
``python -m compileall -q generator`` first when the package is installed editable with PYTHONDONTWRITEBYTECODE set
(a real install compiles its modules). Check keeps what it reads of a mesh in the user's cache folder
(``check.kept_meshes``): the untimed first run fills it; ``XACROKIT_CACHE=off python benchmarks/check_speed.py`` times
a check that reads every mesh each time (a first check, or a CI machine without a kept cache).

With ``--many`` it measures ``gen-robot check PATH...`` (issue 33, item 1) instead: the real-robot corpus of
tests/realworld.py (129 URDFs of pinned registry packages, downloaded once into its cache), every consumer on, in one
call with the default workers (the CPU count), against a process per file for every SAMPLE-th file; it prints the
seconds per file of each and their ratio (target: at most 0.15 s a file in one call, on 2 cores).
Usage: python benchmarks/check_speed.py [RUNS [ROBOT...]] [--no-warm-up] | --many [FILES] (the first FILES of the
corpus: all by default; ROBOT: a part of a file name of ROBOTS or ASKED_ONLY, e.g. xarm7 or panda: those robots only;
--no-warm-up: no untimed first run, for a smoke run that only shows the script works)
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

from xacrokit.check.consumers import CONSUMERS, _check_urdf_binary

ROBOTS = (  # (links) file inside example-robot-data's robots folder
    "xarm_description/urdf/xarm7.urdf",  # 10 links
    "g1_description/urdf/g1_29dof_with_hand_rev_1_0.urdf",  # 53
    "tiago_description/robots/tiago_dual.urdf",  # 130
)
ASKED_ONLY = ("panda_description/urdf/panda.urdf",)  # 11 links; measured when named (issue 45 names it)
WITH_MESHES = "import sys, yourdfpy; robot = yourdfpy.URDF.load(sys.argv[1]); print(len(robot.link_map))"
GEN_ROBOT = str(Path(sys.executable).with_name("gen-robot"))


def robots_folder() -> Path:
    for entry in sys.path:
        folder = Path(entry, "cmeel.prefix", "share", "example-robot-data", "robots")
        if folder.is_dir():
            return folder
    raise SystemExit("example-robot-data is not installed (pip install -e '.[test]')")


def commands(path: Path) -> dict[str, list[str]]:
    found = {"check": [GEN_ROBOT, "check", str(path)], "rules": [GEN_ROBOT, "check", str(path), "--consumers", "none"]}
    for name in CONSUMERS:
        if name == "check_urdf":
            found[name] = [_check_urdf_binary() or "check_urdf", str(path)]
        else:
            found[name] = [sys.executable, "-m", "xacrokit.check.consumers", name, str(path), "{}"]
    found["yourdfpy+meshes"] = [sys.executable, "-c", WITH_MESHES, str(path)]
    return found


def timed(command: list[str], cwd: Path) -> float:
    return timed_cpu(command, cwd)[0]


def timed_cpu(command: list[str], cwd: Path) -> tuple[float, float]:
    """Wall and CPU seconds (user + system of the process and the children it waited for) of one process."""
    before = os.times()
    start = time.perf_counter()
    subprocess.run(command, capture_output=True, check=False, cwd=cwd, timeout=600)
    wall = time.perf_counter() - start
    after = os.times()
    return wall, after.children_user - before.children_user + after.children_system - before.children_system


def main(runs: int, only: list[str], warm_up: bool = True) -> None:
    folder = robots_folder()
    print(f"gen-robot check on real robots, medians of {runs} runs as processes (wall seconds; CPU seconds after /)")
    print(f"load average at the start: {os.getloadavg()[0]:.1f} (on {os.cpu_count()} CPUs)")
    print(
        f"{'robot':<34} {'links':>5} {'check':>11} {'rules':>11}  consumers alone -> check / slowest consumer "
        "(wall, CPU); / slowest with yourdfpy+meshes"
    )
    for name in (*ROBOTS, *ASKED_ONLY):
        if (only or name in ASKED_ONLY) and not any(part in name for part in only):
            continue
        path = folder / name
        links = path.read_text(encoding="utf-8").count("<link ")
        todo = commands(path)
        times: dict[str, list[tuple[float, float]]] = {key: [] for key in todo}
        for command in todo.values() if warm_up else ():  # (untimed: the files in the page cache, the meshes' facts)
            timed_cpu(command, path.parent)
        for run in range(runs):
            for key, command in list(todo.items())[:: 1 if run % 2 == 0 else -1]:
                times[key].append(timed_cpu(command, path.parent))
        wall = {key: statistics.median(t[0] for t in values) for key, values in times.items()}
        cpu = {key: statistics.median(t[1] for t in values) for key, values in times.items()}
        slowest = max(CONSUMERS, key=lambda key: wall[key])
        heaviest = max(times, key=lambda key: wall[key] if key not in ("check", "rules") else 0.0)
        each = ", ".join(f"{key} {wall[key]:.2f}/{cpu[key]:.2f}" for key in (*CONSUMERS, "yourdfpy+meshes"))
        print(
            f"{path.name:<34} {links:>5} {wall['check']:>5.2f}/{cpu['check']:<5.2f} "
            f"{wall['rules']:>5.2f}/{cpu['rules']:<5.2f}  {each} -> {paired(times, slowest, 0):.2f} wall, "
            f"{paired(times, slowest, 1):.2f} CPU (slowest: {slowest}); {paired(times, heaviest, 0):.2f} wall, "
            f"{paired(times, heaviest, 1):.2f} CPU ({heaviest}); load average {os.getloadavg()[0]:.1f}"
        )


def paired(times: dict[str, list[tuple[float, float]]], alone: str, which: int) -> float:
    """The median over runs of check's time over ``alone``'s in the same run (which: 0 wall, 1 CPU)."""
    return statistics.median(a[which] / b[which] for a, b in zip(times["check"], times[alone], strict=True))


SAMPLE = 8  # every 8th corpus file is also checked in a process of its own (17 of 129)


def many(limit: int | None = None) -> None:
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
    from realworld import SOURCES, corpus, unpacked

    files = corpus()[:limit]
    packages = [f"--package={name}={unpacked(s) / folder}" for s in SOURCES for name, folder in s.packages]
    one_call = [GEN_ROBOT, "check", *(str(f.path) for f in files), *packages, "--json"]
    start = time.perf_counter()
    done = subprocess.run(one_call, capture_output=True, text=True, check=False, timeout=1200)
    together = (time.perf_counter() - start) / len(files)
    reports = json.loads(done.stdout)["reports"]
    alone = []
    for robot in files[::SAMPLE]:
        alone.append(timed([GEN_ROBOT, "check", str(robot.path), *packages, "--json"], robot.path.parent))
    each = statistics.mean(alone)
    print(f"gen-robot check on the real-robot corpus ({len(files)} files, {len(reports)} reports), every consumer on")
    print(f"one call, {os.cpu_count()} workers: {together:.3f} s a file ({together * len(files):.1f} s in all)")
    print(f"a process per file ({len(alone)} files, mean): {each:.3f} s a file")
    print(f"ratio one call / a process per file: {together / each:.2f}")


if __name__ == "__main__":
    if sys.argv[1:2] == ["--many"]:
        many(int(sys.argv[2]) if len(sys.argv) > 2 else None)
    else:
        words = [w for w in sys.argv[1:] if w != "--no-warm-up"]
        main(int(words[0]) if words else 5, words[1:], warm_up="--no-warm-up" not in sys.argv)
