"""benchmarks/kinematics_speed.py runs and says a ratio for each command and input (one pair each, without the
untimed warm-up pair, whose calls are the timed pair's: that it measures, not how well; the figures are RESULTS.md's).
Beside tests/test_benchmarks.py, which runs the other scripts."""

from __future__ import annotations

import subprocess
import sys

from conftest import REPO


def test_kinematics_speed_script_prints_a_ratio_per_command_and_input():
    done = subprocess.run(
        [sys.executable, str(REPO / "benchmarks" / "kinematics_speed.py"), "1", "--no-warm-up"],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr
    rows = {" ".join(line.split()[:2]): line.split()[2:] for line in done.stdout.splitlines()[2:]}
    assert set(rows) == {f"{command} ({given})" for command in ("pose", "jacobian", "ik") for given in ("spec", "URDF")}
    for values in rows.values():
        ours, bare, wall_ratio, ours_cpu, bare_cpu, cpu_ratio = map(float, values)
        assert 0.2 < wall_ratio < 50 and abs(wall_ratio - ours / bare) < 0.5 * wall_ratio
        assert ours_cpu > 0 and bare_cpu > 0 and cpu_ratio > 0
