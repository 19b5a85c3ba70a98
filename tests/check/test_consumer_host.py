"""The consumers' host of a worker checking many files: a consumer that crashes, hangs or runs out of memory there
is that consumer's verdict, the consumers after it still give theirs, and the next file gets a new host."""

from __future__ import annotations

import os
import signal
import time
from dataclasses import replace

import pytest

from xacrokit.check import consumers
from xacrokit.check.consumer_host import ConsumerHost

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="the host is a forked child")


KEPT: list[bytearray] = []


def fake_load(name: str, path: str, packages: object = None) -> str:
    """A consumer that does what the file's name says."""
    if name == "pinocchio" and "crash" in path:
        os.kill(os.getpid(), signal.SIGSEGV)
    if name == "pinocchio" and "hang" in path:
        time.sleep(60)
    if name == "pinocchio" and "greedy" in path:
        return str(len(bytearray(8 * 2**30)))  # (past the host's 4 GiB bound)
    if name == "yourdfpy" and "refused" in path:
        raise ValueError("no such link")
    if "hoard" in path:
        kept = bytearray(80 * 2**20)
        kept[::4096] = b"\x01" * len(range(0, len(kept), 4096))  # (every page written, so resident)
        KEPT.append(kept)  # (kept, as MuJoCo keeps what it compiled)
    return f"{name} loaded {os.path.basename(path)} in {os.getpid()}"


@pytest.fixture
def host():
    started = ConsumerHost(fake_load, replace(consumers.CONSUMER_BOUNDS, seconds=2.0))
    yield started
    started.stop()


def verdicts(host: ConsumerHost, path: str) -> dict[str, tuple[str, str]]:
    found = host.start(["pinocchio", "yourdfpy"], path, None)()  # type: ignore[arg-type]
    return {name: (result.status, result.message) for name, result in found.items()}


def test_one_host_serves_file_after_file(host, tmp_path):
    first = verdicts(host, str(tmp_path / "a.urdf"))
    second = verdicts(host, str(tmp_path / "b.urdf"))
    assert first["pinocchio"][0] == second["yourdfpy"][0] == "accepted"
    pids = {message.rsplit(" ", 1)[1] for _, message in [*first.values(), *second.values()]}
    assert len(pids) == 1 and pids != {str(os.getpid())}  # (one child, not this process)
    assert verdicts(host, str(tmp_path / "refused.urdf"))["yourdfpy"] == ("rejected", "ValueError: no such link")


@pytest.mark.parametrize(
    ("name", "status", "said"),
    [
        ("crash.urdf", "crashed", "killed by SIGSEGV"),
        ("hang.urdf", "timeout", "no verdict within 2 s; stopped"),
        ("greedy.urdf", "rejected", "went past its memory bound; stopped"),
    ],
)
def test_a_consumer_that_ends_the_host_is_its_verdict_and_the_rest_go_on(host, tmp_path, name, status, said):
    found = verdicts(host, str(tmp_path / name))
    assert found["pinocchio"] == (status, said)
    assert found["yourdfpy"][0] == "accepted"  # (sent again, to a new host)
    assert verdicts(host, str(tmp_path / "next.urdf"))["pinocchio"][0] == "accepted"


def test_a_host_grown_past_half_its_memory_bound_starts_afresh(tmp_path):
    """MuJoCo's cache grows with every mesh: a host that has grown by half its bound is replaced before the next file
    (here a bound of 128 MiB and 80 MiB kept by the first load), so a long run never meets the bound by what it
    kept."""
    host = ConsumerHost(fake_load, replace(consumers.CONSUMER_BOUNDS, memory=128 * 2**20))
    try:
        first = host.start(["pinocchio"], tmp_path / "hoard.urdf", None)()["pinocchio"]  # type: ignore[arg-type]
        again = host.start(["pinocchio"], tmp_path / "plain.urdf", None)()["pinocchio"]  # type: ignore[arg-type]
        after = host.start(["pinocchio"], tmp_path / "plain.urdf", None)()["pinocchio"]  # type: ignore[arg-type]
    finally:
        host.stop()
    assert first.status == again.status == after.status == "accepted"
    pids = [result.message.rsplit(" ", 1)[1] for result in (first, again, after)]
    assert pids[0] != pids[1] == pids[2]
