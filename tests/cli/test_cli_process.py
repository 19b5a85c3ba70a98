"""The tests run gen-robot in their own process (conftest.gen_robot, tests/in_process.py) and start a real process
only where the process itself is proven: here, a real ``python -m xacrokit.cli`` and the in-process run give the same
exit code, standard output and standard error on a generation, a check with findings, a refusal of bad input, a usage
mistake, the help and the version; so that what the other tests prove in-process holds of the command. The in-process
run leaves the test's working folder, environment and warning filters as they were, catches what is printed to the
file descriptors (urdfdom's C++ prints there), and turns an escaping exception into a process's traceback and exit 1."""

from __future__ import annotations

import os
import warnings

import pytest

import xacrokit.cli.app
from conftest import ROBOT_EXAMPLES, gen_robot, gen_robot_process

SPEC = next(p for p in ROBOT_EXAMPLES if p.stem == "two_dof_arm")
CORPUS = SPEC.parent.parent.parent / "tests" / "check" / "corpus"


@pytest.mark.parametrize(
    "words",
    [
        ("{spec}", "-o", "{out}/pkg", "--dry-run"),
        ("check", str(CORPUS / "I003_fail.urdf"), "--consumers", "check_urdf"),
        ("check", "{out}/missing.urdf"),
        ("pose", "{spec}", "no_such_frame"),
        ("fleet", "{spec}", "--count", "0"),
        ("genrate", "{spec}"),
        ("--help",),
        ("--version",),
    ],
    ids=["generate", "check-findings", "missing-file", "bad-frame", "bad-count", "typo", "help", "version"],
)
def test_a_real_process_and_the_in_process_run_say_the_same(words, tmp_path):
    argv = [w.format(spec=SPEC, out=tmp_path) for w in words]
    real, here = gen_robot_process(*argv, cwd=tmp_path), gen_robot(*argv, cwd=tmp_path)
    assert (here.returncode, here.stdout, here.stderr) == (real.returncode, real.stdout, real.stderr)
    assert real.stdout or real.stderr
    assert "Traceback" not in real.stderr


def test_the_in_process_run_leaves_the_tests_process_as_it_was(tmp_path):
    before = (os.getcwd(), dict(os.environ), list(warnings.filters))
    result = gen_robot(SPEC, "-o", tmp_path / "pkg", cwd=tmp_path)
    assert result.returncode == 0 and (tmp_path / "pkg" / "package.xml").is_file()
    assert (os.getcwd(), dict(os.environ), list(warnings.filters)) == before


def test_what_the_command_prints_to_the_file_descriptors_is_its_output(monkeypatch):
    def printing(args):
        os.write(1, b"out from C\n")
        os.write(2, b"err from C\n")
        return 0

    monkeypatch.setattr(xacrokit.cli.app, "_cmd_schema", printing)
    result = gen_robot("schema")
    assert (result.returncode, result.stdout, result.stderr) == (0, "out from C\n", "err from C\n")


def test_an_exception_that_escapes_is_a_traceback_and_exit_1(monkeypatch):
    def escaping(argv=None):
        raise MemoryError("a bug above main's handlers")

    monkeypatch.setattr(xacrokit.cli, "main", escaping)
    result = gen_robot("schema")
    assert result.returncode == 1 and result.stdout == ""
    assert "Traceback" in result.stderr and "MemoryError: a bug above main's handlers" in result.stderr
