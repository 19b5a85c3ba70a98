"""How long `gen-robot check` takes on real robots, against its consumers run alone (issue 14, item 6).

For real URDFs of about 10, 50 and 130 links (example-robot-data, which the test extra installs), each timed as a
process, median of RUNS runs, all runs of a file interleaved (so that a slow moment of the machine hits them alike):

- ``check``: ``gen-robot check FILE`` with every consumer (check_urdf, pinocchio, yourdfpy, MuJoCo);
- each consumer alone, as check runs it (check_urdf's binary; ``python -m xacrokit.check.consumers NAME FILE``);
- ``rules``: ``gen-robot check FILE --consumers none`` (our rules alone).

It prints the ratio check / slowest consumer alone (target <= 1.5) and the rules' time (target < 0.3 s on 130 links).

With ``--many`` it measures ``gen-robot check PATH...`` (issue 33, item 1) instead: the real-robot corpus of
tests/realworld.py (129 URDFs of pinned registry packages, downloaded once into its cache), every consumer on, in one
call with the default workers (the CPU count), against a process per file for every SAMPLE-th file; it prints the
seconds per file of each and their ratio (target: at most 0.15 s a file in one call, on 2 cores).
Usage: python benchmarks/check_speed.py [RUNS] | --many [FILES] (the first FILES of the corpus: all by default)
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
    return found


def timed(command: list[str], cwd: Path) -> float:
    start = time.perf_counter()
    subprocess.run(command, capture_output=True, check=False, cwd=cwd, timeout=600)
    return time.perf_counter() - start


def main(runs: int) -> None:
    folder = robots_folder()
    print(f"gen-robot check on real robots, medians of {runs} runs as processes (seconds)")
    print(f"{'robot':<42} {'links':>5} {'check':>7} {'rules':>7}  consumers alone -> check / slowest")
    for name in ROBOTS:
        path = folder / name
        links = path.read_text(encoding="utf-8").count("<link ")
        todo = commands(path)
        times: dict[str, list[float]] = {key: [] for key in todo}
        for _ in range(runs):
            for key, command in todo.items():
                times[key].append(timed(command, path.parent))
        median = {key: statistics.median(values) for key, values in times.items()}
        alone = {key: median[key] for key in CONSUMERS}
        slowest = max(alone, key=lambda key: alone[key])
        each = ", ".join(f"{key} {value:.2f}" for key, value in alone.items())
        print(
            f"{path.name:<42} {links:>5} {median['check']:>7.2f} {median['rules']:>7.3f}  {each} -> "
            f"{median['check'] / alone[slowest]:.2f} (slowest: {slowest})"
        )


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
        main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
