"""How long the test suite takes (issue 45, item 3: at most 6 minutes on the project's 2-core machine): the README's
test command, timed from start to end, with pyproject's options (a worker a core, the ten slowest tests named).

It prints the wall time, the count of tests passed and skipped (and each test that failed), and the ten slowest tests
as pytest names them; with ``--by-module`` also the work (the tests' durations summed: what the workers share) by test
folder and the modules that take the most, so that the next slowness shows where it is. Run it with nothing else on
the machine: the workers take every core. (No test runs it: it is the suite.)

Usage: python benchmarks/suite_time.py [--by-module] [PYTEST ARGS...]   (e.g. -n 0 for one process)
"""

from __future__ import annotations

import collections
import os
import re
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
DURATION = re.compile(r"([0-9.]+)s (?:call|setup|teardown) +(\S+?)(?:::|$)")


def main() -> None:
    words = sys.argv[1:]
    by_module = "--by-module" in words
    words = [w for w in words if w != "--by-module"] + (["--durations=0"] if by_module else [])
    command = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", *words]
    start = time.perf_counter()
    done = subprocess.run(command, cwd=REPO, capture_output=True, text=True, env=os.environ)
    wall = time.perf_counter() - start
    lines = done.stdout.splitlines()
    summary = next((line for line in reversed(lines) if " passed" in line or " failed" in line), "(no summary)")
    slowest_at = next((k for k, line in enumerate(lines) if "slowest" in line and "durations" in line), None)
    print(f"test suite: {wall:.0f} s wall ({os.cpu_count()} cores, load average then {os.getloadavg()[0]:.1f})")
    print(f"  {summary.strip('= ')}")
    for line in lines:  # (pytest's -ra summary: a failure is named, not only counted)
        if line.startswith(("FAILED ", "ERROR ")):
            print(f"    {line}")
    if slowest_at is not None:
        print("  the ten slowest:")
        for line in lines[slowest_at + 1 : slowest_at + 11]:
            print(f"    {line}")
    if by_module:
        print_work(lines)
    sys.exit(done.returncode)


def print_work(lines: list[str]) -> None:
    """The tests' durations summed, by test folder and by module (the twelve that take the most)."""
    modules: collections.Counter[str] = collections.Counter()
    for line in lines:
        found = DURATION.match(line)
        if found:
            modules[found[2]] += float(found[1])
    folders: collections.Counter[str] = collections.Counter()
    for module, seconds in modules.items():
        folders[module.rpartition("/")[0]] += seconds
    print(f"  work: {sum(modules.values()):.0f} s of tests' time (the workers share it)")
    for title, table in (("by folder", folders), ("the twelve modules that take the most", modules)):
        print(f"  {title}:")
        for name, seconds in table.most_common(12):
            print(f"    {seconds:7.1f} s  {name}")


if __name__ == "__main__":
    main()
