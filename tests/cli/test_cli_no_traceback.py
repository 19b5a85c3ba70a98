"""No input gives a traceback: inputs that are not files, documents that never end expanding, paths no file system
takes, a closed output. Each is a clear message and the documented exit code; a bug of ours is exit 70 with a short
report, never a bare traceback."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

import xacrokit.cli.app
from conftest import ROBOT_EXAMPLES, XACRO_HEADER, assert_refused, gen_robot

SPEC = next(p for p in ROBOT_EXAMPLES if p.stem == "two_dof_arm")


def refused(result: subprocess.CompletedProcess, words: str) -> None:
    assert_refused(result.returncode, result.stderr, words)


@pytest.fixture
def odd_files(tmp_path):
    (tmp_path / "loop_a.urdf").symlink_to(tmp_path / "loop_b.urdf")
    (tmp_path / "loop_b.urdf").symlink_to(tmp_path / "loop_a.urdf")
    os.mkfifo(tmp_path / "fifo.urdf")
    os.mkfifo(tmp_path / "fifo")
    (tmp_path / "binary.xacro").write_bytes(bytes(range(128, 256)) * 8)
    (tmp_path / "recursive.xacro").write_text(
        XACRO_HEADER + '<xacro:macro name="m" params="n"><xacro:m n="${n}"/></xacro:macro><xacro:m n="1"/></robot>'
    )
    (tmp_path / "self.xacro").write_text(XACRO_HEADER + '<xacro:include filename="self.xacro"/></robot>')
    (tmp_path / "keyword.xacro").write_text(XACRO_HEADER + "<xacro:include/></robot>")
    return tmp_path


@pytest.mark.parametrize(
    ("words", "message"),
    [
        (("check", "/dev/zero"), "cannot read /dev/zero: it is not a regular file"),
        (("check", "{d}/fifo"), "it is not a regular file (a device, a FIFO or a socket)"),  # (no suffix: never read)
        (("check", "{d}/fifo.urdf"), "it is not a regular file (a device, a FIFO or a socket)"),
        (("check", "{d}/loop_a.urdf"), "a loop of symbolic links"),
        (("expand", "{d}/loop_a.urdf"), "a loop of symbolic links"),
        (("expand", "{d}/binary.xacro"), "it is not UTF-8 text"),
        (("check", "{d}/binary.xacro"), "it is not UTF-8 text"),
        (("expand", "{d}/recursive.xacro"), "never ends expanding: macro m calls itself without end"),
        (("check", "{d}/recursive.xacro", "--consumers", "none"), "macro m calls itself without end"),
        (("expand", "{d}/self.xacro"), "includes itself"),
        (("expand", "{d}/keyword.xacro"), "xacro:include: missing attribute 'filename'"),
    ],
)
def test_inputs_that_are_no_document_are_refused_with_a_reason(odd_files, words, message):
    result = gen_robot(*(w.format(d=odd_files) for w in words))
    refused(result, message)


def test_a_folder_of_odd_files_is_searched_without_opening_what_is_no_file(odd_files):
    """check searches a folder: a FIFO and a loop of links are no robot files (never opened: a FIFO would block), nor
    is a document its folder includes (self.xacro includes itself), the documents that cannot be read are said each
    with its reason, and the exit code is 2."""
    result = gen_robot("check", odd_files, "--consumers", "none", "-j", "2")
    assert result.returncode == 2 and "Traceback" not in result.stderr
    said = {line.split(": UNREADABLE: ")[0]: line for line in result.stdout.splitlines() if ": UNREADABLE: " in line}
    assert sorted(Path(name).name for name in said) == ["binary.xacro", "keyword.xacro", "recursive.xacro"]
    assert "not UTF-8" in said[str(odd_files / "binary.xacro")]
    assert "calls itself without end" in said[str(odd_files / "recursive.xacro")]
    assert "missing attribute 'filename'" in said[str(odd_files / "keyword.xacro")]
    assert result.stdout.splitlines()[-1] == "3 file(s) checked: 0 passed, 0 failed, 3 unreadable"


def test_scene_paths_no_file_system_takes_and_macros_named_like_xacro_elements(tmp_path):
    (tmp_path / "m.xacro").write_text(
        XACRO_HEADER + '<xacro:macro name="include" params="prefix parent *origin"/></robot>', encoding="utf-8"
    )
    nul = tmp_path / "nul.yaml"
    nul.write_text('scene: s\ninstances:\n  a: {spec: "x\\0y.yaml", prefix: a_, parent: world}\n', encoding="utf-8")
    refused(gen_robot(nul, "--dry-run"), "nul.yaml:3:13: $.instances.a.spec: cannot use this path: it holds a NUL")
    keyword = tmp_path / "keyword.yaml"
    keyword.write_text(
        "scene: s\ninstances:\n  a: {xacro: {file: m.xacro, macro: include}, prefix: a_, parent: world}\n",
        encoding="utf-8",
    )
    refused(gen_robot(keyword, "--dry-run"), "'include' is a xacro keyword")


def test_a_closed_output_is_exit_141_quietly():
    result = subprocess.run(
        [sys.executable, "-m", "xacrokit.cli", "schema"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
        close_fds=True, preexec_fn=lambda: os.close(1),
    )  # fmt: skip
    assert result.returncode == 141 and result.stderr == ""


def test_a_bug_of_ours_is_exit_70_with_a_short_report(monkeypatch, capsys):
    def broken(args):
        raise KeyError("no such thing")

    monkeypatch.setattr(xacrokit.cli.app, "_cmd_schema", broken)
    assert xacrokit.cli.app.main(["schema"]) == 70
    err = capsys.readouterr().err
    assert "gen-robot: internal error (a bug in xacrokit" in err and "KeyError: 'no such thing'" in err
    assert "Traceback" not in err and len(err.splitlines()) == 2


@pytest.mark.parametrize("command", ["expand", "generate"])
def test_output_must_be_a_plain_path(tmp_path, command):
    doc = tmp_path / "a.xacro"
    doc.write_text('<robot name="r"><link name="a"/></robot>', encoding="utf-8")
    source = doc if command == "expand" else SPEC
    words = ["expand", source] if command == "expand" else [source]
    device = "/dev/null: it is a device, FIFO or socket" if command == "expand" else "-o /dev/null: it exists and is"
    refused(gen_robot(*words, "-o", "/dev/null"), device)
    empty = "not a file name to write" if command == "expand" else "-o needs a path"
    refused(gen_robot(*words, "-o", ""), empty)
    assert os.path.exists("/dev/null") and not os.path.isfile("/dev/null")  # (still the device)


def test_the_refusal_check_can_fail():
    """assert_refused fails on another message, on words every message holds, on another exit code, on a traceback."""
    assert_refused(2, "gen-robot: error: s.yaml:1:1: the spec is empty", "the spec is empty")
    for code, err, words in [
        (2, "gen-robot: error: s.yaml:1:1: something else", "the spec is empty"),
        (2, "gen-robot: error: s.yaml:1:1: the spec is empty", "error"),
        (1, "gen-robot: error: the spec is empty", "the spec is empty"),
        (2, "Traceback (most recent call last): the spec is empty", "the spec is empty"),
    ]:
        with pytest.raises(AssertionError):
            assert_refused(code, err, words)
