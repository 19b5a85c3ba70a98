"""The independent consumers: chosen by name or installed, stopped when they hang or print forever, their verdicts
said in one line, and nothing left behind."""

from __future__ import annotations

import dataclasses
import os
import signal
import sys
import time
from pathlib import Path

import pytest
from check_helpers import BODY, CORPUS, MOVED_MASSLESS, ROOTED_CYCLE

import xacrokit
from conftest import gen_robot
from xacrokit.check import check
from xacrokit.check.consumers import run_consumer


def test_rooted_cycle_is_reported_and_check_urdf_is_not_left_running(tmp_path):
    urdf = tmp_path / "rooted.urdf"
    urdf.write_text(ROOTED_CYCLE, encoding="utf-8")
    report = check(urdf)
    assert [f.message for f in report.findings if f.rule == "S002"] == [
        "joint 'ba' closes a cycle a -> b -> a; remove it"
    ]
    assert {c.status for c in report.consumers} == {"skipped"}
    # run check_urdf anyway: it prints forever on this file; the output cap stops it
    forced = run_consumer("check_urdf", urdf, timeout=20)
    assert forced.status in ("rejected", "timeout") and forced.failed


def running(pid: int) -> bool:
    """Whether process ``pid`` runs (a zombie, dead but not yet reaped by whoever adopted it, does not)."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (OSError, IndexError):
        return False
    return state != "Z"


def test_consumer_that_hangs_is_stopped_and_reported(tmp_path, monkeypatch):
    import xacrokit.check.consumers as consumers

    monkeypatch.setattr(consumers, "_check_urdf_binary", lambda: str(tmp_path / "sleeper"))
    sleeper = tmp_path / "sleeper"
    sleeper.write_text(f"#!/bin/sh\nsleep 30 &\necho $! > {tmp_path / 'child'}\nwait\n", encoding="utf-8")
    sleeper.chmod(0o755)
    started = time.monotonic()
    result = consumers.run_consumer("check_urdf", CORPUS / "J002_pass.urdf", timeout=0.5)
    assert result.status == "timeout" and result.failed
    assert time.monotonic() - started < 4  # (a child holding the pipe open once kept the reader 5 s more)
    child = int((tmp_path / "child").read_text())
    for _ in range(50):  # what the consumer started is stopped with it (its process group)
        if not running(child):
            break
        time.sleep(0.05)
    else:
        pytest.fail(f"the consumer's child {child} is still running")


def test_consumers_asked_for_by_name_must_be_installed(monkeypatch, tmp_path):
    import xacrokit.check.consumers as consumers

    monkeypatch.setattr(consumers, "available", lambda name: name != "mujoco")
    with pytest.raises(xacrokit.XacrokitError, match="mujoco asked for but not installed"):
        check(CORPUS / "I001_pass.urdf", consumers=["check_urdf", "mujoco"])
    with pytest.raises(xacrokit.XacrokitError, match="unknown consumer"):
        check(CORPUS / "I001_pass.urdf", consumers=["nosuch"])
    report = check(CORPUS / "I001_pass.urdf")  # 'all' means those installed: mujoco left out, not an error
    assert "mujoco" not in {c.name for c in report.consumers} and not report.errors


@pytest.mark.skipif(not __import__("importlib").util.find_spec("mujoco"), reason="MuJoCo is not installed")
def test_mujoco_consumer_accepts_good_and_rejects_bad_inertia():
    good = check(CORPUS / "I003_pass.urdf", consumers=["mujoco"])
    assert [c.status for c in good.consumers] == ["accepted"]
    bad = check(CORPUS / "I003_fail.urdf", consumers=["mujoco"])
    (verdict,) = bad.consumers
    assert verdict.status == "rejected" and "inertia" in verdict.message and "\n" not in verdict.message
    assert {f.rule for f in bad.errors} == {"I003", "C001"}


def test_consumers_leave_nothing_in_the_working_folder(tmp_path):
    result = gen_robot("check", CORPUS / "I003_fail.urdf", cwd=tmp_path)  # MuJoCo, when installed, rejects it
    assert result.returncode == 1
    assert list(tmp_path.iterdir()) == []


def test_check_urdf_says_what_urdfdom_found_first(tmp_path):
    """urdfdom prints the cause first and where it gave up after; the finding keeps the cause."""
    urdf = tmp_path / "no_limit.urdf"
    urdf.write_text(
        MOVED_MASSLESS.replace("BODY", BODY).replace('<limit lower="-1" upper="1" effort="1" velocity="1"/>', "")
    )
    report = check(urdf, consumers=["check_urdf"])
    (consumer,) = report.consumers
    assert consumer.status == "rejected" and "does not specify limits" in consumer.message, consumer.message
    assert "at line" not in consumer.message  # urdfdom's own source locations are left out


def test_check_urdf_printing_an_error_is_a_rejection_even_when_it_exits_0():
    """urdfdom reports an unreadable rpy ("pi/2", left by a xacro macro) and carries on to exit 0."""
    report = check(CORPUS / "U002_fail.urdf", consumers=["check_urdf"])
    (consumer,) = report.consumers
    assert consumer.status == "rejected" and "pi/2" in consumer.message, consumer
    assert {f.rule for f in report.errors} == {"U002", "C001"}


def test_check_urdf_printing_a_big_robots_whole_tree_is_no_rejection(tmp_path):
    """check_urdf prints the whole tree, indented by depth: about 2 MB for a 1,000-link chain. Its verdict is its exit
    status and its error lines (once, output over 64 KiB was called a rejection: robots gen-robot wrote FAILED)."""
    links = 1000
    parts = ['<robot name="chain">']
    for i in range(links):
        parts.append(
            f'<link name="l{i}"><inertial><mass value="1"/>'
            '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>'
        )
        if i:
            parts.append(
                f'<joint name="j{i}" type="revolute"><parent link="l{i - 1}"/><child link="l{i}"/>'
                '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
            )
    urdf = tmp_path / "chain.urdf"
    urdf.write_text("".join(parts) + "</robot>", encoding="utf-8")
    result = run_consumer("check_urdf", urdf)
    assert result.status == "accepted", result
    broken = tmp_path / "broken.urdf"  # (check_urdf stops at the unreadable limit: a plain rejection)
    broken.write_text("".join(parts).replace('<limit lower="-1"', '<limit lower="x"', 1) + "</robot>", encoding="utf-8")
    assert run_consumer("check_urdf", broken).status == "rejected"


def test_an_error_line_after_a_long_printout_is_a_rejection(tmp_path, monkeypatch):
    """The output kept is its start and end and every Error: line between: one after 64 KiB still counts."""
    import xacrokit.check.consumers as consumers

    fake = tmp_path / "fake_check_urdf"
    fake.write_text(
        "#!/bin/sh\necho 'Successfully Parsed XML'\nhead -c 300000 /dev/zero | tr '\\0' 'x'\necho\n"
        "echo 'Error:   limit lower is not a number'\nhead -c 100000 /dev/zero | tr '\\0' 'y'\necho\nexit 0\n",
        encoding="utf-8",
    )
    fake.chmod(0o755)
    monkeypatch.setattr(consumers, "_check_urdf_binary", lambda: str(fake))
    result = consumers.run_consumer("check_urdf", CORPUS / "J002_pass.urdf")
    assert result.status == "rejected" and "limit lower is not a number" in result.message, result


def test_an_undeclared_namespace_prefix_reaches_every_consumer_as_written():
    """Drake's exporters write drake: attributes without declaring the prefix; every consumer reads past them, and so
    must the copy of the file check hands them (it crashed on it: a strict XML parse of the text)."""
    report = check(CORPUS / "U003_fail.urdf")
    assert [f.rule for f in report.findings] == ["U003"], [str(f) for f in report.findings]
    assert report.consumers and all(c.status == "accepted" for c in report.consumers), report.consumers


def test_mujoco_judges_a_robot_without_the_meshes_it_cannot_read(tmp_path):
    """MuJoCo reads no .dae: the visual made of one is left out and the rest judged, which is said; a physics fault
    elsewhere is still MuJoCo's rejection."""
    (tmp_path / "part.dae").write_text("<COLLADA/>", encoding="utf-8")
    text = (CORPUS / "I001_pass.urdf").read_text(encoding="utf-8")
    mesh = '<visual><geometry><mesh filename="part.dae"/></geometry></visual></link>'
    (tmp_path / "robot.urdf").write_text(text.replace("</link>", mesh, 1), encoding="utf-8")
    result = run_consumer("mujoco", tmp_path / "robot.urdf")
    assert (result.status, result.message.split(" (")[1]) == (
        "accepted",
        "1 .dae mesh left out: MuJoCo cannot read them)",
    )
    (tmp_path / "bad.urdf").write_text(
        (CORPUS / "I001_fail.urdf").read_text(encoding="utf-8").replace("</link>", mesh, 1), encoding="utf-8"
    )
    bad = run_consumer("mujoco", tmp_path / "bad.urdf")
    assert bad.status == "rejected" and "mass and inertia of moving bodies" in bad.message, bad


def _stand_in(behaviour):
    """A Python consumer that behaves as told, for the forked children (a fork copies the patched module)."""

    def load(name, path, packages=None):
        if behaviour == "crash":
            os.kill(os.getpid(), signal.SIGSEGV)
        if behaviour == "hang":
            time.sleep(60)
        if behaviour == "noise":
            os.write(1, b"noise on stdout\n")
            os.write(2, b"noise on stderr\n")
            print("more noise", file=sys.stderr)
        if behaviour == "refuse":
            raise ValueError("no such\njoint")
        return f"{name} saw it"

    return load


@pytest.mark.skipif(not hasattr(os, "fork"), reason="consumers run in forked children where os.fork exists")
@pytest.mark.parametrize(
    ("behaviour", "status", "message"),
    [
        ("crash", "crashed", "killed by SIGSEGV"),
        ("hang", "timeout", "no verdict within 1 s; stopped"),  # (the bound set below, as a warm child says it)
        ("noise", "accepted", "pinocchio saw it"),
        ("refuse", "rejected", "ValueError: no such joint"),
    ],
)
@pytest.mark.parametrize("started", ["with the check", "after our rules"])
def test_forked_consumers_are_isolated_bounded_and_quiet(monkeypatch, capfd, behaviour, status, message, started):
    """A Python consumer runs in a child forked from check's process: its crash, hang or output stays there. The same
    whether its child started with the check (warm: check's own) or is forked once the URDF is sound (``verdicts``)."""
    from xacrokit.check import consumers

    monkeypatch.setattr(consumers, "load_with", _stand_in(behaviour))
    monkeypatch.setattr(consumers, "CONSUMER_BOUNDS", dataclasses.replace(consumers.CONSUMER_BOUNDS, seconds=1.0))
    begun = time.monotonic()
    if started == "with the check":
        results = check(CORPUS / "J002_pass.urdf", consumers=["pinocchio"]).consumers
    else:
        text = (CORPUS / "J002_pass.urdf").read_text(encoding="utf-8")
        results = tuple(consumers.verdicts(["pinocchio"], text, structural=False, package_paths=None, base_dir=CORPUS))
    assert time.monotonic() - begun < 20
    assert [(c.name, c.status) for c in results] == [("pinocchio", status)]
    assert results[0].message == message
    out, err = capfd.readouterr()
    assert "noise" not in out + err


def test_check_urdf_runs_without_cmeels_python_launcher():
    """pin's check_urdf is a Python launcher of the program in cmeel.prefix: check runs the program itself, with the
    launcher's libraries, and it gives the launcher's verdicts (55 ms of Python a file less)."""
    import subprocess

    from xacrokit.check.consumers import _check_urdf_binary, check_urdf_command

    launcher = _check_urdf_binary()
    if launcher is None:
        pytest.skip("check_urdf is not installed")
    program, environment = check_urdf_command(launcher)
    if environment is None:
        pytest.skip("this check_urdf is not cmeel's launcher")
    assert program != [launcher] and "cmeel.prefix" in program[0]
    for name in ("J002_pass.urdf", "J001_fail.urdf"):
        direct = subprocess.run([*program, str(CORPUS / name)], capture_output=True, text=True, env=environment)
        launched = subprocess.run([launcher, str(CORPUS / name)], capture_output=True, text=True)
        assert (direct.returncode, direct.stdout) == (launched.returncode, launched.stdout)
