"""How long `gen-robot` takes where users wait for it, as whole processes (issue 45, item 1), measured in one run:

- ``fleet``: ``gen-robot fleet`` of 100 copies of a 10-link chain (1,000 links: benchmarks/bench.py's fleet robot)
  against ``xacro`` expanding the package it wrote (target: at most 0.3x);
- ``UR5``: ``gen-robot SPEC`` on the UR5 example (examples/robots/industrial_arm_std_dh.yaml), its package written
  again into the same folder, the user's cache filled by a first run (target: under 0.3 s); beside it the same with
  the cache off (``XACROKIT_CACHE=off``: the templates compiled and the collision matrix sampled every time);
- for scale: ``python -c pass`` and ``python -c "import numpy"`` (which generation needs).

Each command runs RUNS times; the commands of a round run in one order, the next round's in the reverse, so that a
slow moment of the machine hits them alike; the fleet ratio is the median of the rounds' own ratios. CPU time (user +
system, children included) is printed beside wall time, since a loaded machine disturbs it less. The cache is a
scratch folder of this run (``XACROKIT_CACHE``), so the user's own is neither read nor filled.

The package is compiled first (``python -m compileall`` on its folder): an editable install on a machine that sets
PYTHONDONTWRITEBYTECODE would otherwise compile every module on every run, which a real install never does.

Usage: python benchmarks/generation_speed.py [RUNS]   (default 7)
"""

from __future__ import annotations

import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from bench import FLEET_ROBOT_LINKS, chain_spec

import xacrokit

REPO = Path(__file__).resolve().parent.parent
UR5 = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
GEN_ROBOT = [sys.executable, "-c", "import sys; from xacrokit.cli import main; sys.exit(main())"]
XACRO = [sys.executable, "-c", "import sys; from xacro import main; sys.argv[0] = 'xacro'; sys.exit(main())"]


def timed(command: list[str], env: dict[str, str]) -> tuple[float, float]:
    """Wall and CPU seconds (user + system) of one run of ``command``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(command, check=True, env=env, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def rounds(commands: dict[str, tuple[list[str], dict[str, str]]], runs: int) -> dict[str, list[tuple[float, float]]]:
    """Each command's (wall, CPU) over ``runs`` rounds, alternating the order from round to round."""
    times: dict[str, list[tuple[float, float]]] = {name: [] for name in commands}
    names = list(commands)
    for index in range(runs):
        for name in names if index % 2 == 0 else reversed(names):
            times[name].append(timed(*commands[name]))
    return times


def line(name: str, samples: list[tuple[float, float]]) -> str:
    walls, cpus = [w for w, _ in samples], [c for _, c in samples]
    return (
        f"  {name:<34} median {statistics.median(walls):6.3f} s wall (min {min(walls):.3f}), "
        f"{statistics.median(cpus):6.3f} s CPU"
    )


def main() -> None:
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 7
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(Path(xacrokit.__file__).parent)], check=True)
    with tempfile.TemporaryDirectory(prefix="xacrokit-gen-speed-") as scratch:
        folder = Path(scratch)
        env = {**os.environ, "XACROKIT_CACHE": str(folder / "cache")}
        off = {**env, "XACROKIT_CACHE": "off"}
        spec = folder / "fleet_robot.yaml"
        spec.write_text(chain_spec(FLEET_ROBOT_LINKS), encoding="utf-8")
        fleet_out = folder / "fleet"
        fleet = [*GEN_ROBOT, "fleet", str(spec), "--count", "100", "-o", str(fleet_out), "--force"]
        ur5 = [*GEN_ROBOT, str(UR5), "-o", str(folder / "ur5"), "--force"]
        for first in (fleet, ur5):  # (fills the cache, and writes the package xacro expands)
            subprocess.run(first, check=True, env=env, stdout=subprocess.DEVNULL)
        xacro = [*XACRO, str(fleet_out / "urdf" / "chain_fleet.urdf.xacro"), "-o", str(folder / "expanded.urdf")]
        print(f"generation where users wait: {runs} rounds, commands alternated (xacrokit {xacrokit.__version__})")
        times = rounds(
            {
                "gen-robot fleet (1,000 links)": (fleet, env),
                "xacro, the same package": (xacro, env),
                "gen-robot UR5 spec": (ur5, env),
                "gen-robot UR5 spec, cache off": (ur5, off),
                "python -c pass": ([sys.executable, "-c", "pass"], env),
                "python -c 'import numpy'": ([sys.executable, "-c", "import numpy"], env),
            },
            runs,
        )
    for name, samples in times.items():
        print(line(name, samples))
    gen, xac = times["gen-robot fleet (1,000 links)"], times["xacro, the same package"]
    wall_ratios = [g[0] / x[0] for g, x in zip(gen, xac, strict=True)]
    cpu_ratios = [g[1] / x[1] for g, x in zip(gen, xac, strict=True)]
    print(
        f"fleet / xacro: {statistics.median(wall_ratios):.3f} wall ({min(wall_ratios):.3f}-{max(wall_ratios):.3f}), "
        f"{statistics.median(cpu_ratios):.3f} CPU (target <= 0.3)"
    )
    ur5_wall = statistics.median(w for w, _ in times["gen-robot UR5 spec"])
    print(f"gen-robot UR5 spec: {ur5_wall:.3f} s (target < 0.3 s)")


if __name__ == "__main__":
    main()
