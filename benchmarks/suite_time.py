"""How long the test suite takes (issue 45, item 3: at most 6 minutes on the project's 2-core machine): the README's
test command, timed from start to end, with pyproject's options (a worker a core, the ten slowest tests named).

It prints the wall time, the count of tests passed and skipped, and the ten slowest tests as pytest names them. Run it
with nothing else on the machine: the workers take every core. (No test runs it: it is the suite.)

Usage: python benchmarks/suite_time.py [PYTEST ARGS...]   (e.g. -n 0 for one process)
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


def main() -> None:
    command = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", *sys.argv[1:]]
    start = time.perf_counter()
    done = subprocess.run(command, cwd=REPO, capture_output=True, text=True, env=os.environ)
    wall = time.perf_counter() - start
    lines = done.stdout.splitlines()
    summary = next((line for line in reversed(lines) if " passed" in line or " failed" in line), "(no summary)")
    slowest_at = next((k for k, line in enumerate(lines) if "slowest" in line and "durations" in line), None)
    print(f"test suite: {wall:.0f} s wall ({os.cpu_count()} cores, load average then {os.getloadavg()[0]:.1f})")
    print(f"  {summary.strip('= ')}")
    if slowest_at is not None:
        print("  the ten slowest:")
        for line in lines[slowest_at + 1 : slowest_at + 11]:
            print(f"    {line}")
    sys.exit(done.returncode)


if __name__ == "__main__":
    main()
