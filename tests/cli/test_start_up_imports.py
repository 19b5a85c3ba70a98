"""Each command imports only what it uses: the table of docs/development.md ("Start-up") names, for each command, the
modules it must not import; each row is run here in a process of its own and the modules it imported are read."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
TABLE = re.compile(r"<!-- start-up imports: begin -->\n(.*?)<!-- start-up imports: end -->", re.S)
UR5 = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
DIFF_DRIVE = REPO / "examples" / "robots" / "diff_drive.yaml"
LINKAGE = REPO / "examples" / "robots" / "linkage_lecture.urdf"
UR10E = REPO / "examples" / "robots" / "ur10e.yaml"
# the command of each row: its arguments, and whether its cache is filled by a first run
COMMANDS = {
    "`gen-robot --help`": (["--help"], False),
    "`gen-robot SPEC`, the UR5 example (its collision matrix cached)": ([str(UR5), "-o", "{out}", "--force"], True),
    "`gen-robot fleet SPEC --count 3` (its collision matrix cached)": (
        ["fleet", str(UR5), "--count", "3", "-o", "{out}", "--force"],
        True,
    ),
    "`gen-robot fleet SPEC --count 3`, a spec of boxes, cylinders and spheres (its collision matrix cached)": (
        ["fleet", str(DIFF_DRIVE), "--count", "3", "-o", "{out}", "--force"],
        True,
    ),
    "`gen-robot pose URDF FRAME`": (["pose", str(LINKAGE), "link_C", "--at", "joint_A=0.3"], False),
    "`gen-robot jacobian URDF FRAME`": (["jacobian", str(LINKAGE), "link_C"], False),
    "`gen-robot pose SPEC FRAME`": (["pose", str(UR10E), "tool0", "--q", "0.1,0.2,0.3,0.4,0.5,0.6"], False),
    "`gen-robot check URDF --consumers none` (its pairs at home kept)": (
        ["check", str(LINKAGE), "--consumers", "none"],
        True,
    ),
}
# runs gen-robot's entry point, then writes the names of the modules the process imported
PROBE = """
import atexit, sys
out = sys.argv[1]
sys.argv = ["gen-robot", *sys.argv[2:]]
atexit.register(lambda: open(out, "w", encoding="utf-8").write("\\n".join(sorted(sys.modules))))
from xacrokit.cli import main
main()
"""


def documented_rows() -> dict[str, list[str]]:
    text = (REPO / "docs" / "development.md").read_text(encoding="utf-8")
    rows = {}
    for line in TABLE.search(text).group(1).splitlines()[2:]:
        command, modules = (cell.strip() for cell in line.strip("|").split("|"))
        rows[command] = [name.strip() for name in modules.split(",")]
    return rows


def imported_by(arguments: list[str], folder: Path, env: dict[str, str]) -> set[str]:
    listing = folder / "modules.txt"
    done = subprocess.run(
        [sys.executable, "-c", PROBE, str(listing), *arguments], capture_output=True, text=True, env=env, timeout=300
    )
    assert done.returncode in (0, 1), done.stderr  # (check: 1 when it finds what --strict would fail on)
    return set(listing.read_text(encoding="utf-8").split())


def test_the_documented_commands_are_the_ones_run_here():
    assert set(documented_rows()) == set(COMMANDS)


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_a_command_does_not_import_what_its_row_forbids(command, tmp_path):
    arguments, cached = COMMANDS[command]
    arguments = [a.replace("{out}", str(tmp_path / "out")) for a in arguments]
    env = {**os.environ, "XACROKIT_CACHE": str(tmp_path / "cache")}
    if cached:
        imported_by(arguments, tmp_path, env)  # (the first run samples the matrix: pinocchio, once)
    imported = imported_by(arguments, tmp_path, env)
    forbidden = documented_rows()[command]
    assert "xacrokit.cli" in imported  # (the probe saw the command run)
    assert not imported & set(forbidden), f"{command} imported {sorted(imported & set(forbidden))}"


def test_the_probe_sees_a_forbidden_import(tmp_path):
    """The test above can fail: a first run, which samples the collision matrix, imports pinocchio."""
    env = {**os.environ, "XACROKIT_CACHE": str(tmp_path / "cache")}
    assert "pinocchio" in imported_by([str(UR5), "-o", str(tmp_path / "out")], tmp_path, env)
