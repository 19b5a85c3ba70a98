"""xacrokit benchmarks: prints times and ratios measured in this one run (no assertions: machines are noisy).

    python benchmarks/bench.py            # all sections
    python benchmarks/bench.py check      # one section

Sections:
  check   gen-robot check (our rules, no external consumers) on chains of 10 / 100 / 1,000 / 3,000 links, the
          t(3,000)/t(1,000) ratio, the time to report a cycle hanging off the root, and the time check_urdf would
          take to be stopped on it.
  cli     wall time of `gen-robot --help`.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

RUNS = 5


def median_time(action: Callable[[], object], runs: int = RUNS) -> float:
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        action()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def chain_urdf(links: int) -> str:
    """A valid serial chain: box links with their inertia, revolute joints with limits and dynamics."""
    parts = ['<?xml version="1.0"?>', '<robot name="chain">']
    inertia = (
        'ixx="0.0016666666666666668" ixy="0" ixz="0" iyy="0.0016666666666666668" iyz="0" izz="0.0016666666666666668"'
    )
    for i in range(links):
        parts.append(
            f'<link name="link_{i}"><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
            f'<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
            f'<inertial><mass value="1.0"/><inertia {inertia}/></inertial></link>'
        )
        if i:
            parts.append(
                f'<joint name="joint_{i}" type="revolute"><parent link="link_{i - 1}"/><child link="link_{i}"/>'
                '<origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
                '<dynamics damping="0.1" friction="0"/></joint>'
            )
    parts.append("</robot>")
    return "\n".join(parts)


ROOTED_CYCLE = (
    '<robot name="rc"><link name="root"/><link name="a"/><link name="b"/>'
    '<joint name="ra" type="fixed"><parent link="root"/><child link="a"/></joint>'
    '<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>'
    '<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint></robot>'
)


def bench_check(folder: Path) -> None:
    from xacrokit.check import check
    from xacrokit.consumers import run_consumer

    print("== check (our rules, no external consumers), median of", RUNS, "runs")
    times = {}
    for links in (10, 100, 1000, 3000):
        path = folder / f"chain_{links}.urdf"
        path.write_text(chain_urdf(links), encoding="utf-8")
        report = check(path, consumers=[])
        assert not report.findings, report.findings[:3]  # the benchmark robot itself must be clean
        times[links] = median_time(lambda path=path: check(path, consumers=[]))
        print(f"  {links:>5} links: {times[links] * 1000:8.1f} ms")
    print(f"  ratio t(3000)/t(1000): {times[3000] / times[1000]:.2f}   (linear would be 3.0)")
    print(f"  1,000 links: {times[1000]:.3f} s   (target < 1 s)")
    cycle = folder / "rooted_cycle.urdf"
    cycle.write_text(ROOTED_CYCLE, encoding="utf-8")
    report_time = median_time(lambda: check(cycle))
    rules = sorted({f.rule for f in check(cycle).findings})
    print(f"  rooted cycle reported ({', '.join(rules)}) with consumers on: {report_time:.3f} s   (target < 1 s)")
    start = time.perf_counter()
    forced = run_consumer("check_urdf", cycle, timeout=30)
    print(
        f"  check_urdf forced on the rooted cycle: {forced.status} after {time.perf_counter() - start:.3f} s "
        f"({forced.message})"
    )


def bench_cli() -> None:
    print("== cli")
    command = [sys.executable, "-m", "xacrokit.cli", "--help"]
    wall = median_time(lambda: subprocess.run(command, capture_output=True, check=True))
    print(f"  gen-robot --help: {wall:.3f} s   (target <= 0.15 s)")


def main(argv: list[str]) -> int:
    sections = set(argv) or {"check", "cli"}
    print(f"python {sys.version.split()[0]} on {sys.platform}; {time.strftime('%Y-%m-%d %H:%M:%S')}")
    with tempfile.TemporaryDirectory(prefix="xacrokit-bench-") as folder:
        if "check" in sections:
            bench_check(Path(folder))
        if "cli" in sections:
            bench_cli()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
