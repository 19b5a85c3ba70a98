"""How fast `gen-robot import` is (issue 19, item 5), measured in one run on this machine: importing a 130-link real
robot (example-robot-data's TIAGo dual, from the test extra) as a process, from start to spec written (target under
1 s), the median of RUNS; and, beside it, the time of a process that only starts gen-robot (`gen-robot --version`),
which the import's time includes.

Usage: python benchmarks/import_speed.py [RUNS]   (median of RUNS, default 3)
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def tiago_dual() -> Path:
    for entry in sys.path:
        path = Path(entry, "cmeel.prefix", "share", "example-robot-data", "robots", "tiago_description", "robots")
        if (path / "tiago_dual.urdf").is_file():
            return path / "tiago_dual.urdf"
    raise SystemExit("example-robot-data is not installed (pip install -e '.[test]')")


def median_time(command: list[str], runs: int) -> float:
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    urdf = tiago_dual()
    links = urdf.read_text(encoding="utf-8").count("<link ")
    cli = [sys.executable, "-m", "xacrokit.cli"]
    with tempfile.TemporaryDirectory() as scratch:
        spec = Path(scratch) / "tiago_dual.yaml"
        whole = median_time([*cli, "import", str(urdf), "-o", str(spec)], runs)
        start = median_time([*cli, "--version"], runs)
    print(f"{links}-link robot (TIAGo dual): gen-robot import as a process {whole:.2f} s (target < 1 s)")
    print(f"of which starting gen-robot: {start:.2f} s")


if __name__ == "__main__":
    main()
