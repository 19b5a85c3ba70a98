"""`gen-robot check FILE` starts the Python consumers' children with the command (issue 45, item 2): each imports
its library at once, before check has read the file, and is sent the URDF once the structure is sound. Their
verdicts are those of the children check forks otherwise; a crash, a hang, a refusal or noise stays in the child;
nothing is left running; a run of many files and a broken tree are unchanged."""

from __future__ import annotations

import dataclasses
import json
import os
import signal
import sys
import time
from pathlib import Path

import pytest
from check_helpers import CORPUS

from conftest import gen_robot
from xacrokit.check import check, consumers
from xacrokit.check.consumer_host import ConsumerHost

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="the consumers' children are forked")


def test_a_warm_host_imports_its_module_before_anything_is_sent(tmp_path, monkeypatch):
    """The child imports the module it is warmed with as it starts: a module that writes a file when imported has
    written it before the first URDF is sent (and the parent has not imported it)."""
    marker = tmp_path / "imported"
    (tmp_path / "warm_marker.py").write_text(f"open({str(marker)!r}, 'w').write('yes')\n", encoding="utf-8")
    monkeypatch.syspath_prepend(str(tmp_path))
    host = ConsumerHost(
        lambda name, path, packages: f"{name} saw {Path(path).name}", consumers.CONSUMER_BOUNDS, "warm_marker"
    )
    try:
        host.warm_up()
        for _ in range(200):
            if marker.exists():
                break
            time.sleep(0.05)
        assert marker.read_text() == "yes" and "warm_marker" not in sys.modules
        found = host.start(["pinocchio"], tmp_path / "robot.urdf", None)()
        assert (found["pinocchio"].status, found["pinocchio"].message) == ("accepted", "pinocchio saw robot.urdf")
    finally:
        host.stop()


def _stand_in(behaviour):
    def load(name, path, packages=None):
        if behaviour == "crash":
            os.kill(os.getpid(), signal.SIGSEGV)
        if behaviour == "hang":
            time.sleep(60)
        if behaviour == "noise":
            os.write(1, b"noise on stdout\n")
            os.write(2, b"noise on stderr\n")
        if behaviour == "refuse":
            raise ValueError("no such\njoint")
        return f"{name} saw it in {os.getpid()}"

    return load


@pytest.mark.parametrize(
    ("behaviour", "status", "message"),
    [
        ("crash", "crashed", "killed by SIGSEGV"),
        ("hang", "timeout", "no verdict within 1 s; stopped"),
        ("noise", "accepted", "pinocchio saw it in"),
        ("refuse", "rejected", "ValueError: no such joint"),
    ],
)
def test_warm_consumers_are_isolated_bounded_and_quiet(monkeypatch, capfd, behaviour, status, message):
    """As a forked consumer (tests/check/test_check_consumers.py): its crash, hang or output stays in its child, and
    the verdict is the same; the child is one started when the context began, and it is gone after."""
    monkeypatch.setattr(consumers, "load_with", _stand_in(behaviour))
    monkeypatch.setattr(consumers, "CONSUMER_BOUNDS", dataclasses.replace(consumers.CONSUMER_BOUNDS, seconds=1.0))
    with consumers.warm_consumers(["pinocchio"]):
        child = consumers._WARM["pinocchio"]._pid
        report = check(CORPUS / "J002_pass.urdf", consumers=["pinocchio"])
    assert [(c.name, c.status) for c in report.consumers] == [("pinocchio", status)]
    assert report.consumers[0].message.startswith(message)
    if behaviour == "noise":
        assert report.consumers[0].message.endswith(f" {child}")  # (the warm child answered, not a new fork)
    out, err = capfd.readouterr()
    assert "noise" not in out + err
    assert not consumers._WARM
    with pytest.raises(ChildProcessError):
        os.waitpid(child, os.WNOHANG)  # (stopped and reaped)


def test_a_broken_tree_sends_the_warm_children_nothing_and_leaves_none(tmp_path):
    urdf = tmp_path / "rooted.urdf"
    urdf.write_text(
        '<robot name="rc"><link name="root"/><link name="a"/><link name="b"/>'
        '<joint name="ra" type="fixed"><parent link="root"/><child link="a"/></joint>'
        '<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>'
        '<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint></robot>',
        encoding="utf-8",
    )
    with consumers.warm_consumers(None):
        children = [host._pid for host in consumers._WARM.values()]
        report = check(urdf)
    assert children and {c.status for c in report.consumers} == {"skipped"}
    for child in children:
        with pytest.raises(ChildProcessError):
            os.waitpid(child, os.WNOHANG)


@pytest.mark.parametrize("name", ["I001_fail.urdf", "U003_fail.urdf"])
def test_the_command_line_gives_the_verdicts_of_the_forked_consumers(name):
    """`gen-robot check FILE` (warm children) says what check() (a child forked per consumer) says, every consumer's
    status and message alike, on files some consumers accept and some refuse."""
    forked = check(CORPUS / name)
    result = gen_robot("check", CORPUS / name, "--json")
    said = json.loads(result.stdout)
    assert [(c["name"], c["status"], c["message"]) for c in said["consumers"]] == [
        (c.name, c.status, c.message) for c in forked.consumers
    ]
    assert len(forked.consumers) >= 3  # (the Python consumers the test extra installs, and check_urdf)
