"""A check starts the Python consumers' children as it begins (issue 45, item 2): each imports its library at once,
before check has read the file, and is sent the URDF once the structure is sound. Their verdicts are those of the
children forked once the URDF is read (``consumers.verdicts``); a crash, a hang, a refusal or noise stays in the child
(tests/check/test_check_consumers.py, both ways); nothing is left running; a broken tree sends them nothing."""

from __future__ import annotations

import json
import os
import sys
import time
from dataclasses import replace
from pathlib import Path

import pytest
from check_helpers import CORPUS, ROOTED_CYCLE

from conftest import gen_robot_process
from xacrokit.check import check, consumers
from xacrokit.check.consumer_host import ConsumerHost

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="the consumers' children are forked")


def _waited(predicate, seconds: float = 20.0) -> bool:
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if predicate():
            return True
        time.sleep(0.02)
    return False


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
        assert _waited(marker.exists) and marker.read_text() == "yes" and "warm_marker" not in sys.modules
        found = host.start(["pinocchio"], tmp_path / "robot.urdf", None)()
        assert (found["pinocchio"].status, found["pinocchio"].message) == ("accepted", "pinocchio saw robot.urdf")
    finally:
        host.stop()


def test_a_host_yields_the_cpu_when_asked_and_bounds_what_a_consumer_says(tmp_path):
    """A host started with ``nice`` runs at that much lower a priority (pinocchio's, which loads in a few
    hundredths, leaves the CPU to the slow consumers); a description past the output bound is a rejection, as in a
    child of its own, and ends the host."""
    host = ConsumerHost(lambda name, path, packages: "x" * 100, replace(consumers.CONSUMER_BOUNDS, output=99), nice=7)
    try:
        host.warm_up()
        child = host._pid
        mine = os.getpriority(os.PRIO_PROCESS, 0)
        assert _waited(lambda: os.getpriority(os.PRIO_PROCESS, child) == min(mine + 7, 19))
        found = host.start(["pinocchio"], tmp_path / "robot.urdf", None)()
        assert (found["pinocchio"].status, found["pinocchio"].message) == (
            "rejected",
            "went past its output bound; stopped",
        )
        assert host._pid is None
    finally:
        host.stop()


def test_check_sends_the_urdf_to_the_children_started_before_it_and_leaves_none(monkeypatch):
    """The children started before the check (here by an outer :func:`warm_consumers`, as check starts its own) get
    the URDF: the check forks no other; once the context ends they are stopped and reaped."""
    monkeypatch.setattr(consumers, "load_with", lambda name, path, packages=None: f"{name} in {os.getpid()}")
    with consumers.warm_consumers(["pinocchio"]):
        child = consumers._WARM["pinocchio"]._pid
        report = check(CORPUS / "J002_pass.urdf", consumers=["pinocchio"])
        assert consumers._WARM  # (check's own context did not stop the outer one's child)
    assert [(c.name, c.status, c.message) for c in report.consumers] == [
        ("pinocchio", "accepted", f"pinocchio in {child}")
    ]
    assert not consumers._WARM
    with pytest.raises(ChildProcessError):
        os.waitpid(child, os.WNOHANG)  # (stopped and reaped)


def test_a_broken_tree_sends_the_warm_children_nothing_and_leaves_none(tmp_path, monkeypatch):
    urdf = tmp_path / "rooted.urdf"
    urdf.write_text(ROOTED_CYCLE, encoding="utf-8")
    sent = tmp_path / "sent"
    monkeypatch.setattr(consumers, "load_with", lambda name, path, packages=None: sent.write_text(name) or "")
    started: list[int] = []
    warm_up = ConsumerHost.warm_up

    def noted(host: ConsumerHost) -> None:
        warm_up(host)
        started.append(host._pid or 0)

    monkeypatch.setattr(ConsumerHost, "warm_up", noted)
    report = check(urdf)
    assert started and {c.status for c in report.consumers} == {"skipped"} and not sent.exists()
    for child in started:
        with pytest.raises(ChildProcessError):
            os.waitpid(child, os.WNOHANG)


@pytest.mark.parametrize("name", ["I001_fail.urdf", "U003_fail.urdf"])
def test_the_command_line_gives_the_verdicts_of_the_children_forked_after_the_rules(name):
    """`gen-robot check FILE` (children started with the check) says what the consumers forked once the URDF is read
    say (``consumers.verdicts``), every consumer's status and message alike, on files some consumers accept and
    some refuse."""
    text = (CORPUS / name).read_text(encoding="utf-8")
    forked = consumers.verdicts(consumers.chosen(None), text, structural=False, package_paths=None, base_dir=CORPUS)
    said = json.loads(gen_robot_process("check", CORPUS / name, "--json").stdout)
    assert [(c["name"], c["status"], c["message"]) for c in said["consumers"]] == [
        (c.name, c.status, c.message.replace("the URDF", str(CORPUS / name))) for c in forked
    ]
    assert len(forked) >= 3  # (the Python consumers the test extra installs, and check_urdf)
