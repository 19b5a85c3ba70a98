"""gen-robot check on a hostile file system and hostile names (issue 41): a folder's search reads nothing through a
symbolic link (the secret a link points at reaches no report), says what it passes over, and blocks on no FIFO; the
text report and the progress line escape the control characters and undecodable bytes of names; check_urdf's
complaint comes without urdfdom's build paths, at the joint or link it names."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from check_helpers import CORPUS
from hypothesis import given
from hypothesis import strategies as st

from conftest import gen_robot
from xacrokit.check import check
from xacrokit.check.file_workers import CheckOptions, check_files
from xacrokit.check.robot_files import robot_files
from xacrokit.reader.robot_source import MAX_URDF_BYTES
from xacrokit.shared.terminal_text import printable

CLEAN = (CORPUS / "J009_pass.urdf").read_text(encoding="utf-8")  # (no finding at all, without consumers)
SECRET_URDF = """<robot name="SECRET_ROBOT">
  <link name="SECRET_BASE"><inertial><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="SECRET_ARM"><inertial><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="SECRET_JOINT" type="revolute"><parent link="SECRET_BASE"/><child link="SECRET_ARM"/></joint>
</robot>
"""
SECRET_BROKEN = '<robot name="r"><link name="a"><SECRET_TAG></link></robot>\n'  # (the parser's error names the tag)
SECRET_SPEC = "robot: SECRET_SPEC\nlinks: {SECRET_SPEC_LINK: 1}\n"
SECRET_XACRO = (
    '<robot name="SECRET_X" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="SECRET_XACRO_LINK"/>'
    '<joint name="SECRET_XACRO_JOINT" type="revolute"><parent link="SECRET_XACRO_LINK"/><child link="b"/></joint>'
    '<link name="b"/></robot>\n'
)


def hostile_repository(tmp_path: Path) -> tuple[Path, set[Path]]:
    """A repository whose robot files link out of it (and to each other, and to nothing), next to the secrets they
    point at; and the links (what the search must pass over, and say so)."""
    secrets = tmp_path / "home"
    secrets.mkdir()
    for name, text in (
        ("secret.urdf", SECRET_URDF),
        ("broken.urdf", SECRET_BROKEN),
        ("secret.yaml", SECRET_SPEC),
        ("secret.xacro", SECRET_XACRO),
    ):
        (secrets / name).write_text(text, encoding="utf-8")
    repo = tmp_path / "repo"
    (repo / "sub" / "deep").mkdir(parents=True)
    (repo / "clean.urdf").write_text(CLEAN, encoding="utf-8")
    links = {
        repo / "vendor.urdf": secrets / "secret.urdf",  # (the case)
        repo / "sub" / "deep" / "nested.urdf": secrets / "broken.urdf",  # (in a nested folder)
        repo / "chain.urdf": repo / "vendor.urdf",  # (a link to a link)
        repo / "inside.urdf": repo / "clean.urdf",  # (a link within the folder: the search follows none)
        repo / "dangling.urdf": repo / "missing.urdf",  # (a link to nothing)
        repo / "robot.yaml": secrets / "secret.yaml",
        repo / "robot.urdf.xacro": secrets / "secret.xacro",
        repo / "upper.URDF": secrets / "secret.urdf",
    }
    for link, target in links.items():
        link.symlink_to(target)
    (repo / "linked_folder").symlink_to(secrets, target_is_directory=True)  # (never entered)
    return repo, set(links)


def _noted(stderr: str) -> set[str]:
    """The paths the notes on stderr say were skipped (``note: PATH: skipped: why``)."""
    return {line[len("note: ") :].split(": skipped: ")[0] for line in stderr.splitlines() if line.startswith("note: ")}


def test_a_folder_search_reads_nothing_through_a_symbolic_link(tmp_path):
    """``vendor.urdf -> ~/secret.urdf`` in a repository put the secret's names (and its tags, through the parser's
    errors) into the text, JSON and SARIF reports: the search now checks the plain file alone, in every format, and
    says which links it passed over."""
    repo, links = hostile_repository(tmp_path)
    for form in ("text", "json", "sarif", "junit"):
        result = gen_robot("check", repo, "--consumers", "none", "--format", form)
        assert result.returncode == 0, (form, result.stdout, result.stderr)
        assert "Traceback" not in result.stderr and "SECRET" not in result.stdout + result.stderr, form
        assert _noted(result.stderr) == {str(link) for link in links}, form
    run = json.loads(gen_robot("check", repo, "--consumers", "none", "--json").stdout)
    assert [report["source"] for report in run["reports"]] == [str(repo / "clean.urdf")]
    assert run["summary"] == {"files": 1, "passed": 1, "failed": 0, "unreadable": 0, "exit_code": 0}
    sarif = json.loads(gen_robot("check", repo, "--consumers", "none", "--format", "sarif").stdout)
    assert sarif["runs"][0]["results"] == []


def test_a_link_named_on_the_command_line_is_read(tmp_path):
    """The user named it: a file given as a path, not found by a search, is read through its link."""
    repo, _ = hostile_repository(tmp_path)
    result = gen_robot("check", repo / "vendor.urdf", "--consumers", "none", "--json")
    report = json.loads(result.stdout)
    assert result.returncode == 1 and report["source"] == str(repo / "vendor.urdf")
    assert ("J001", "SECRET_JOINT") in {(f["rule"], f["element"]["name"]) for f in report["findings"]}
    assert robot_files([repo / "chain.urdf"], robots_only=True) == [repo / "chain.urdf"]


def test_the_search_tells_what_it_passes_over_and_why(tmp_path):
    repo, links = hostile_repository(tmp_path)
    os.mkfifo(repo / "pipe.xacro")  # (reading a FIFO would block the search)
    (repo / "notes.txt").symlink_to(tmp_path / "home" / "secret.urdf")  # (no robot's name: passed over unsaid)
    said: dict[Path, str] = {}
    found = robot_files([repo], skipped=lambda path, why: said.setdefault(path, why))
    assert found == [repo / "clean.urdf"]
    assert set(said) == links | {repo / "pipe.xacro"}
    assert all(why.startswith("a symbolic link") for path, why in said.items() if path in links)
    assert said[repo / "pipe.xacro"].startswith("not a plain file")


@pytest.fixture
def hostile_names(tmp_path: Path) -> tuple[Path, dict[str, str]]:
    """A folder of failing URDFs named with an ESC sequence, a newline forging a report line, a right-to-left
    override and a byte that is not UTF-8; each name, and how the report must print it."""
    folder = tmp_path / "names"
    folder.mkdir()
    failing = (CORPUS / "J001_fail.urdf").read_bytes()
    names = {
        b"a_esc\x1b[2J\x1b]8;;http:x\x07.urdf": r"a_esc\x1b[2J\x1b]8;;http:x\x07.urdf",
        b"b_line\nx.urdf: OK: 0 error(s), 0 warning(s)\n.urdf": r"b_line\nx.urdf: OK: 0 error(s), 0 warning(s)\n.urdf",
        "c_rtl\u202egpj.urdf".encode(): r"c_rtl\u202egpj.urdf",
        b"d_bytes\xff\xfe.urdf": r"d_bytes\udcff\udcfe.urdf",
        b"e_back\\x1b.urdf": r"e_back\\x1b.urdf",  # (a real backslash: told apart from an escape)
    }
    for name in names:  # (bytes paths: each name exactly as written)
        with open(os.fsencode(folder) + b"/" + name, "wb") as out:
            out.write(failing)
    return folder, {os.fsdecode(name): shown for name, shown in names.items()}


def _strict_utf8(*args: object) -> subprocess.CompletedProcess[bytes]:
    """gen-robot with stdout a strict UTF-8 stream (as on a UTF-8 terminal or a CI runner), its output as bytes."""
    environment = {**os.environ, "PYTHONIOENCODING": "utf-8"}
    command = [sys.executable, "-m", "xacrokit.cli", *(os.fspath(a) if isinstance(a, Path) else a for a in args)]
    return subprocess.run(command, capture_output=True, env=environment, timeout=300, check=False)


def test_the_text_report_escapes_what_names_hold(hostile_names):
    """A file name's ESC, newline, bidirectional override or undecodable byte is printed as its escape: one line per
    file and finding (none forged), nothing a terminal acts on, and no crash (exit 70) on a strict UTF-8 stream."""
    folder, names = hostile_names
    result = _strict_utf8("check", folder, "--consumers", "none")
    text = result.stdout.decode("utf-8")  # (strict: a lone surrogate written raw fails here)
    assert result.returncode == 1, result.stderr
    assert all(line.isprintable() for line in text.splitlines()), text
    run = json.loads(_strict_utf8("check", folder, "--consumers", "none", "--json").stdout)
    counts = [1 + report["summary"]["errors"] + report["summary"]["warnings"] for report in run["reports"]]
    lines = text.splitlines()
    assert len(lines) == sum(counts) + 1 and lines[-1] == f"{len(names)} file(s) checked: 0 passed, 5 failed"
    heads = [line.split(": FAILED: ")[0] for line in lines[:-1] if not line.startswith("  ")]
    assert heads == [f"{folder}/{shown}" for _, shown in sorted(names.items())]
    findings = [line for line in lines if line.startswith("  ")]  # (each at its file: FILE:LINE:COLUMN: ...)
    placed = [[shown for shown in names.values() if line.startswith(f"  {folder}/{shown}:")] for line in findings]
    assert all(len(found) == 1 for found in placed) and {found[0] for found in placed} == set(names.values())


def test_one_files_report_escapes_its_name(hostile_names):
    folder, names = hostile_names
    name = next(n for n in names if n.startswith("b_line"))
    result = _strict_utf8("check", folder / name, "--consumers", "none")
    lines = result.stdout.decode("utf-8").splitlines()
    assert result.returncode == 1 and lines[0] == f"{folder}/{names[name]}: urdf, robot 'corpus'"
    assert lines[-1].startswith("FAILED: ") and all(line.isprintable() for line in lines)


def test_the_progress_line_escapes_file_names(hostile_names):
    folder, names = hostile_names
    said: list[str] = []
    files = sorted(folder.iterdir())
    outcomes = list(check_files(files, CheckOptions(consumers=[]), jobs=1, progress=said.append))
    assert [o.exit_code() for o in outcomes] == [1] * len(names)
    assert said and all(message.isprintable() for message in said)
    assert any(names[next(n for n in names if n.startswith("a_esc"))] in message for message in said)
    said.clear()
    CheckOptions(consumers=[]).check(files[0], said.append)  # (one file's steps: 'reading NAME', ...)
    assert said and all(message.isprintable() for message in said)


@given(st.text())
def test_printable_text_is_printable_and_reads_back(text):
    shown = printable(text)
    assert shown.isprintable()
    assert shown.encode("ascii", "backslashreplace").decode("unicode_escape") == text


def test_a_folder_of_hostile_files_gives_a_clean_run(tmp_path):
    """A FIFO named like a robot (never opened: it would block), a folder named a.urdf (searched), a file past the
    size limit (sparse: unreadable, the others still checked) give a run with exit 2, no hang and no traceback."""
    folder = tmp_path / "repo"
    (folder / "a.urdf").mkdir(parents=True)
    (folder / "a.urdf" / "inner.urdf").write_text(CLEAN, encoding="utf-8")
    (folder / "clean.urdf").write_text(CLEAN, encoding="utf-8")
    os.mkfifo(folder / "pipe.urdf")
    with open(folder / "huge.urdf", "wb") as huge:
        huge.truncate(MAX_URDF_BYTES + 1)
    result = gen_robot("check", folder, "--consumers", "none", "--json")
    run = json.loads(result.stdout)
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert [report["source"] for report in run["reports"]] == [
        str(folder / "a.urdf" / "inner.urdf"),
        str(folder / "clean.urdf"),
        str(folder / "huge.urdf"),
    ]
    assert run["summary"] == {"files": 3, "passed": 2, "failed": 0, "unreadable": 1, "exit_code": 2}
    assert "larger than" in run["reports"][2]["error"]
    assert _noted(result.stderr) == {str(folder / "pipe.urdf")}


def test_yaml_the_search_cannot_read_is_said_not_failed(tmp_path, monkeypatch):
    """Whether unreadable YAML is a robot spec is unknown: the search says it passed it over (as root every file is
    readable, so the refusal is the operating system's answer made up here)."""
    (tmp_path / "robot.yaml").write_text("robot: r\nlinks: {}\n", encoding="utf-8")
    (tmp_path / "arm.urdf").write_text(CLEAN, encoding="utf-8")
    real = os.access
    monkeypatch.setattr(os, "access", lambda path, mode: Path(path).suffix != ".yaml" and real(path, mode))
    said: dict[Path, str] = {}
    assert robot_files([tmp_path], skipped=lambda path, why: said.setdefault(path, why)) == [tmp_path / "arm.urdf"]
    assert list(said) == [tmp_path / "robot.yaml"] and "cannot be read" in said[tmp_path / "robot.yaml"]


NO_LIMIT = """<robot name="r">
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="arm"><inertial><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="NAME" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/><dynamics damping="0.1"/>
  </joint>
</robot>
"""


def test_check_urdfs_finding_is_at_the_joint_it_names(tmp_path):
    """urdfdom names the joint it stopped at: the C001 finding is placed there (it had no line), and says urdfdom's
    message without the places in urdfdom's own C++ source."""
    urdf = tmp_path / "no_limit.urdf"
    urdf.write_text(NO_LIMIT.replace("NAME", "elbow"), encoding="utf-8")
    report = check(urdf, consumers=["check_urdf"])
    (c001,) = [f for f in report.findings if f.rule == "C001"]
    assert (c001.file, c001.line, c001.column) == (str(urdf), 6, 3)
    assert c001.message == (
        "check_urdf rejected: Joint [elbow] is of type REVOLUTE but it does not specify limits | joint xml is not "
        "initialized correctly"
    )


def test_check_urdfs_message_keeps_a_name_with_a_line_break_whole(tmp_path):
    """A joint name holding a line break (and what looks like urdfdom's source place) cut urdfdom's message short:
    the message runs to urdfdom's own place line."""
    urdf = tmp_path / "no_limit.urdf"
    urdf.write_text(NO_LIMIT.replace("NAME", "a&#10;at line 5 in /x.cpp"), encoding="utf-8")
    (consumer,) = check(urdf, consumers=["check_urdf"]).consumers
    assert consumer.status == "rejected"
    assert consumer.message.startswith("Joint [a\nat line 5 in /x.cpp] is of type REVOLUTE but"), consumer.message


def test_check_urdfs_build_paths_are_left_out(tmp_path, monkeypatch):
    """A urdfdom build that throws (its message FILE:LINE: text) and dies: the verdict keeps urdfdom's words, not the
    paths of the machine that built it."""
    import xacrokit.check.consumers as consumers

    fake = tmp_path / "fake_check_urdf"
    fake.write_text(
        "#!/bin/sh\necho \"terminate called after throwing an instance of 'std::runtime_error'\"\n"
        "echo '  what():  /home/builder/ws/src/urdfdom/urdf_parser/src/model.cpp:274: Failed to find root link'\n"
        "echo '         at line 243 in /home/builder/ws/src/urdfdom/urdf_parser/src/model.cpp'\nexit 134\n",
        encoding="utf-8",
    )
    fake.chmod(0o755)
    monkeypatch.setattr(consumers, "_check_urdf_binary", lambda: str(fake))
    result = consumers.run_consumer("check_urdf", CORPUS / "J002_pass.urdf")
    assert result.status == "rejected"
    assert result.message == (
        "terminate called after throwing an instance of 'std::runtime_error' | what(): Failed to find root link"
    )
