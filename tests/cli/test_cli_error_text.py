"""The command line's own errors print outside text escaped (issue 41): a file name holding an ESC or a carriage
return cannot rewrite the terminal or forge the start of a line, while a spec's errors keep one a line."""

from __future__ import annotations

from conftest import gen_robot


def test_a_missing_file_with_an_escape_in_its_name_is_said_escaped(tmp_path):
    name = tmp_path / "robot\x1b[2J\rOK.urdf"
    done = gen_robot("pose", str(name), "tool0", cwd=tmp_path)
    assert done.returncode == 2
    assert "\x1b" not in done.stderr and "\r" not in done.stderr
    assert "robot\\x1b[2J\\rOK.urdf" in done.stderr


def test_no_robot_found_names_the_folder_escaped(tmp_path):
    folder = tmp_path / "empty\x1b]8;;x\x07"
    folder.mkdir()
    done = gen_robot("check", str(folder), "--format", "json", cwd=tmp_path)
    assert "\x1b" not in done.stderr and "\x07" not in done.stderr
    assert "empty\\x1b]8;;x\\x07" in done.stderr


def test_a_specs_errors_keep_their_lines(tmp_path):
    spec = tmp_path / "bad.yaml"
    spec.write_text("robot: r\nlinks: {a: {mass: -1}, b: {mass: -2}}\njoints: {}\n", encoding="utf-8")
    done = gen_robot(str(spec), "-o", str(tmp_path / "out"), cwd=tmp_path)
    assert done.returncode == 2
    lines = [line for line in done.stderr.splitlines() if "bad.yaml:2:" in line]
    assert len(lines) >= 2, done.stderr
    assert not (tmp_path / "out").exists()


def test_an_unknown_argument_is_said_escaped(tmp_path):
    done = gen_robot("check", "x.urdf", "--\x1b[31mred", cwd=tmp_path)
    assert done.returncode == 2
    assert "\x1b" not in done.stderr and "\\x1b[31mred" in done.stderr
