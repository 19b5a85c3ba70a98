"""The benchmark script runs: the check timings and one measurement of every stage."""

from __future__ import annotations

import shutil
import subprocess
import sys

import pytest

from conftest import REPO


def run_script(name: str, *args: str) -> subprocess.CompletedProcess:
    """A benchmark script run as a reader would run it; it must end well (its figures are the test's to read)."""
    result = subprocess.run(
        [sys.executable, str(REPO / "benchmarks" / name), *args], capture_output=True, text=True, timeout=600
    )
    assert result.returncode == 0, result.stderr
    return result


def test_benchmark_script_runs():
    """bench.py's check and cli sections, each measurement taken once where the script takes the median of 9 (that
    it runs and says every figure, not how well: the figures are RESULTS.md's), in a process of its own."""
    once = (
        "import sys; sys.path.insert(0, sys.argv[1]); import bench; bench.STAGE_RUNS = 1; "
        "sys.exit(bench.main(sys.argv[2:]))"
    )
    result = subprocess.run(
        [sys.executable, "-c", once, str(REPO / "benchmarks"), "check", "cli"],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert result.returncode == 0, result.stderr
    for words in ("1000 links:", "ratio t(3000)/t(1000)", "rooted cycle reported (S002)", "gen-robot --help"):
        assert words in result.stdout


def test_benchmark_stage_measurement_runs(tmp_path, monkeypatch):
    monkeypatch.syspath_prepend(str(REPO / "benchmarks"))
    import bench
    from bench import measure_size, touch

    monkeypatch.setattr(bench, "STAGE_RUNS", 1)  # (that it measures every stage, not how well: one run each)
    row = measure_size(10, tmp_path)
    stages = {"load", "validate", "resolve", "render", "write", "emit", "xacro", "check", "full", "lxml"}
    assert set(row) == stages | {"touch"}  # (touch: the reference walk, not a stage)
    assert all(value > 0 for value in row.values())
    assert touch({"a": [1, {"b": 2.0}], "c": {}}) == 4  # it reaches every mapping and list


def test_check_speed_script_runs():
    """benchmarks/check_speed.py: gen-robot check against its consumers alone, on one real robot named (one run; the
    three robots of its default list go through the same code, each about 13 s a run: RESULTS.md's runs time them;
    no untimed warm-up run, the same calls as the timed one)."""
    result = run_script("check_speed.py", "1", "xarm7", "--no-warm-up")
    rows = [line for line in result.stdout.splitlines() if "(slowest: " in line]
    assert [row.split()[0] for row in rows] == ["xarm7.urdf"]
    for row in rows:
        ratio = float(row.split("-> ")[1].split()[0])
        assert 0.5 < ratio < 10  # (a ratio, measured: not a timing target, which RESULTS.md records)


def test_check_speed_script_times_many_files_in_one_call():
    """benchmarks/check_speed.py --many: the corpus in one call against a process per file (its first 2 files: the
    call's workers, one a file on 2 cores or more, and the first file alone in a process; more take the same paths)."""
    result = run_script("check_speed.py", "--many", "2")
    lines = result.stdout.splitlines()
    assert "(2 files, 2 reports)" in lines[0]
    ratio = float(lines[-1].rsplit(" ", 1)[1])
    assert 0.01 < ratio < 10  # (a ratio, measured: the target is RESULTS.md's)


def test_size_speed_script_runs():
    """benchmarks/size_speed.py: the static search's time and the motion analysis against bare pinocchio (one run)."""
    result = run_script("size_speed.py", "1")
    assert "static worst-case search, 6-axis UR5 with 5 kg:" in result.stdout
    ratio = float(result.stdout.split("ratio ")[1].split()[0])
    assert 0.5 < ratio < 20  # (a ratio, measured: not a timing target, which RESULTS.md records)


def test_import_speed_script_runs():
    """benchmarks/import_speed.py: gen-robot import of a 130-link robot as a process (one run)."""
    result = run_script("import_speed.py", "1")
    assert "130-link robot (TIAGo dual): gen-robot import as a process" in result.stdout
    assert "of which starting gen-robot" in result.stdout


@pytest.mark.skipif(not (shutil.which("chromium") and shutil.which("chromedriver")), reason="no chromium here")
def test_view_speed_script_runs():
    """benchmarks/view_speed.py: a fleet's page opened in headless Chromium, a joint move timed in the page, a real
    robot's page made and opened: every step of it, at its smallest (fleets of 2 and 1 diff-drives, 3 moves, the
    Panda; its 1,000-link fleet, 50 moves and the Go1 besides take 20 s more: RESULTS.md's runs time them)."""
    result = run_script("view_speed.py", "--fleets", "2", "1", "--moves", "3", "--real", "Panda")
    lines = result.stdout.splitlines()
    assert lines[0].startswith("19-link fleet page: open and draw ")  # (2 x 9 links, and the world)
    assert lines[1].startswith("10-link robot: a joint move re-poses and draws in ") and "(median of 3;" in lines[1]
    assert len(lines) == 3 and lines[2].startswith("Panda page: ")  # (example-robot-data: the test extra's)


def test_mesh_memory_script_runs():
    """benchmarks/mesh_memory.py: import and export of a robot with 1 and with 2 meshes, peak memory (one run; meshes
    of 320 triangles: the steps are the same for 81,920, whose memory RESULTS.md's runs measure)."""
    result = run_script("mesh_memory.py", "2", "2")
    for command in ("import", "export"):
        assert f"gen-robot {command}: peak" in result.stdout and " MB with 2 (0 MB of meshes): ratio" in result.stdout


def test_ik_speed_script_runs():
    """benchmarks/ik_speed.py: our ik against ikpy and roboticstoolbox where installed (3 targets a robot; the times
    are RESULTS.md's to record, not this test's to judge)."""
    result = run_script("ik_speed.py", "3")
    rows = [[cell.strip() for cell in line.strip("|").split("|")] for line in result.stdout.splitlines()]
    rows = [row for row in rows if len(row) == 8 and row[2] == "3"]
    robots = ["UR5", "UR10e", "KR 560"] + ([] if "Panda: left out" in result.stdout else ["Panda"])
    assert sorted({row[0] for row in rows}) == sorted(robots)
    for robot in robots:
        solvers = {row[1]: row for row in rows if row[0] == robot}
        for ours in ("ours, first", "ours, every"):  # (seeded targets drawn within reach: every one answered)
            assert solvers[ours][3].startswith("100.0% (100.0% at 1e-9)"), solvers[ours]
            assert float(solvers[ours][4]) > 0 and float(solvers[ours][7].split()[0]) > 0
        for theirs, package in (("rtb ik_LM", "rtb"), ("rtb ik_LM tol=5e-13", "rtb"), ("ikpy", "ikpy")):
            assert theirs in solvers or f"comparator unavailable: {package}:" in result.stdout
