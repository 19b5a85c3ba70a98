"""gen-robot fleet: copies of one robot on a grid, as a scene built directly from the robot."""

from __future__ import annotations

import subprocess
import sys

import pytest
from lxml import etree
from scene_helpers import SCENES

import xacrokit
from conftest import REPO, gen_robot
from xacrokit.check import check
from xacrokit.emit import urdf_differences


def test_fleet_of_ten_on_a_grid(tmp_path):
    diff_drive = REPO / "examples" / "robots" / "diff_drive.yaml"
    result = gen_robot(
        "fleet", diff_drive, "--count", "10", "--grid", "2x5", "--spacing", "1.5", "-o", tmp_path / "fleet"
    )
    assert result.returncode == 0, result.stderr
    root = etree.parse(str(tmp_path / "fleet" / "urdf" / "diff_drive_fleet.urdf")).getroot()
    for index in range(10):
        mount = root.find(f"joint[@name='r{index}_base_footprint_mount_joint']")
        row, column = divmod(index, 5)
        assert [float(v) for v in mount.find("origin").get("xyz").split()] == [column * 1.5, row * 1.5, 0.0]
    assert len(root.findall("link")) == 1 + 10 * 9  # (the diff-drive example: 9 links with its camera's optical frame)
    assert not check(tmp_path / "fleet" / "urdf" / "diff_drive_fleet.urdf", consumers=["check_urdf"]).errors
    bad = gen_robot("fleet", diff_drive, "--count", "10", "--grid", "2x4")
    assert bad.returncode == 2 and "has 8 places for 10 robots" in bad.stderr


def test_fleet_command_and_the_fleet_scene_example_agree(tmp_path):
    diff_drive = REPO / "examples" / "robots" / "diff_drive.yaml"
    assert (
        gen_robot(
            "fleet", diff_drive, "--count", "10", "--grid", "2x5", "--spacing", "1.5", "-o", tmp_path / "cli"
        ).returncode
        == 0
    )
    xacrokit.generate(SCENES / "diff_drive_fleet.yaml", tmp_path / "file")
    urdf = "urdf/diff_drive_fleet.urdf"
    assert (tmp_path / "cli" / urdf).read_text(encoding="utf-8") == (tmp_path / "file" / urdf).read_text(
        encoding="utf-8"
    )


@pytest.mark.parametrize("mode", ["copy", "find"])
def test_fleets_take_the_macro_mode_and_describe_the_same_robots(tmp_path, mode):
    diff_drive = REPO / "examples" / "robots" / "diff_drive.yaml"
    for name, extra in (("default", ()), (mode, ("--macros", mode, "--via-xacro"))):
        result = gen_robot("fleet", diff_drive, "--count", "3", "-o", tmp_path / name, *extra)
        assert result.returncode == 0, result.stderr
    urdf = "urdf/diff_drive_fleet.urdf"
    texts = [(tmp_path / name / urdf).read_text(encoding="utf-8") for name in ("default", mode)]
    assert urdf_differences(*texts, rel=0.0) == []
    macro = (tmp_path / mode / "robots" / "diff_drive_description" / "urdf" / "diff_drive_macro.xacro").read_text(
        encoding="utf-8"
    )
    assert "<xacro:wheel" in macro
    assert (tmp_path / mode / "robots" / "diff_drive_description" / "urdf" / "xacrokit").is_dir() == (mode == "copy")
    depends = "<exec_depend>xacrokit</exec_depend>" in (tmp_path / mode / "package.xml").read_text(encoding="utf-8")
    assert depends == (mode == "find")


def run_with_tty_stderr(*args) -> tuple[int, str, str]:
    """Run gen-robot with stderr on a pseudo-terminal; return (exit code, stdout, what the terminal received)."""
    import os
    import pty

    leader, follower = pty.openpty()
    process = subprocess.Popen(
        [sys.executable, "-m", "xacrokit.cli", *map(str, args)], stdout=subprocess.PIPE, stderr=follower, text=True
    )
    os.close(follower)
    received = b""
    while True:
        try:
            chunk = os.read(leader, 4096)
        except OSError:  # the terminal closed: the command has ended
            break
        if not chunk:
            break
        received += chunk
    stdout = process.stdout.read()
    code = process.wait(timeout=300)
    os.close(leader)
    return code, stdout, received.decode("utf-8", errors="replace")


def test_progress_shows_on_a_terminal_only(tmp_path):
    diff_drive = REPO / "examples" / "robots" / "diff_drive.yaml"
    code, stdout, terminal = run_with_tty_stderr("fleet", diff_drive, "--count", "4", "-o", tmp_path / "fleet")
    assert code == 0 and "4 robots r0_ .. r3_" in stdout
    for step in (
        "checking 4 copies of diff_drive.yaml",
        "rendering 4 instances of 1 robot(s)",
        "emitting the URDF",
        "writing",
    ):
        assert step in terminal, terminal
    assert terminal.endswith("\r\x1b[K")  # the line is cleared when the work is done
    code, stdout, terminal = run_with_tty_stderr("check", diff_drive, "--consumers", "check_urdf")
    assert code == 0 and "running check_urdf" in terminal and "OK: 0 error(s)" in stdout
    quiet = gen_robot("fleet", diff_drive, "--count", "2", "-o", tmp_path / "quiet")
    assert quiet.returncode == 0 and quiet.stderr == ""  # not a terminal: nothing on stderr


def test_a_fleet_readme_says_how_to_make_it_again(tmp_path):
    spec = REPO / "examples" / "robots" / "diff_drive.yaml"
    result = gen_robot("fleet", spec, "--count", 3, "--grid", "1x3", "--spacing", "150 cm", "-o", tmp_path / "f")
    assert result.returncode == 0, result.stderr
    readme = (tmp_path / "f" / "README.md").read_text(encoding="utf-8")
    assert "run `gen-robot fleet diff_drive.yaml --count 3 --grid 1x3 --spacing 1.5` again" in readme


def test_a_fleet_is_the_scene_its_scene_spec_would_be():
    """The fleet is built as data (no spec text in between) and resolves to the very scene the equivalent scene spec
    does: the same instances, names, parents and poses."""
    from xacrokit.load import load_file
    from xacrokit.scene import build_scene, fleet_scene

    fleet = fleet_scene(REPO / "examples" / "robots" / "diff_drive.yaml", 10, columns=5, spacing=1.5)
    spec = build_scene(load_file(SCENES / "diff_drive_fleet.yaml"))
    assert fleet.instances == spec.instances and (fleet.name, fleet.world) == (spec.name, spec.world)
    assert fleet.command == "gen-robot fleet diff_drive.yaml --count 10 --grid 2x5 --spacing 1.5"


def test_what_a_fleet_cannot_be_is_refused_with_the_reason(tmp_path):
    from xacrokit.errors import SpecErrors, XacrokitError
    from xacrokit.scene import fleet_scene

    arm = REPO / "examples" / "robots" / "two_dof_arm.yaml"
    for count in (0, 1001):
        with pytest.raises(XacrokitError, match=f"a fleet has 1 to 1,000 robots, got count {count:,}"):
            fleet_scene(arm, count)
    for spacing in (0.0, -1.0, float("inf"), float("nan")):
        with pytest.raises(XacrokitError, match="the spacing of a fleet must be > 0 m"):
            fleet_scene(arm, 2, spacing=spacing)
    with pytest.raises(XacrokitError, match="the spacing of a fleet is too large: 1e[+]308 m puts r2 at"):
        fleet_scene(arm, 9, spacing=1e308)  # the grid's third column would be at x = inf
    with pytest.raises(XacrokitError, match="is a scene spec; a fleet copies one robot spec"):
        fleet_scene(SCENES / "two_arm_cell.yaml", 2)
    with pytest.raises(SpecErrors, match="cannot read the spec: No such file or directory"):
        fleet_scene(tmp_path / "missing.yaml", 2)
    bad = tmp_path / "bad.yaml"
    bad.write_text(arm.read_text(encoding="utf-8").replace("mass: 0.5", "mass: -1"), encoding="utf-8")
    with pytest.raises(SpecErrors) as caught:
        fleet_scene(bad, 3)
    (error,) = caught.value.errors  # once, however many copies, located in the robot's own spec
    assert (error.file, error.path) == (str(bad), "$.links.upper_arm.mass") and error.line is not None
    assert "mass must be > 0" in error.message
