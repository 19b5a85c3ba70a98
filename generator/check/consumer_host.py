"""The Python consumers (pinocchio, yourdfpy, MuJoCo) in one long-lived child, for a worker checking many files.

A check of one file forks a child per consumer (:mod:`xacrokit.check.consumers`): cheap, but what a consumer keeps
between loads dies with its child, and MuJoCo keeps much: the meshes it has compiled (its asset cache), which the
robots of one package share. Loading the 129 corpus files one child each costs MuJoCo 24 CPU-seconds; in one process,
6. So a worker of ``gen-robot check PATH...`` hands its consumers to a host: a child forked once, which loads each URDF
it is sent with each consumer in turn and answers one JSON line per consumer. Its bounds are those of a consumer's
child: it is quiet, its address space is bounded (its parent's plus CONSUMER_BOUNDS.memory), and a load that takes
longer than CONSUMER_BOUNDS.seconds, breaks the memory bound or crashes the host is that consumer's verdict (timeout,
rejected, crashed) and ends the host; the next file gets a new one. A host that has grown by half its memory bound
(MuJoCo's cache grows with every mesh it compiles) is started afresh before the next file, so that a long run never
meets the bound by what it kept. Answers are JSON, never pickle.
"""

from __future__ import annotations

import contextlib
import importlib
import json
import os
import select
import signal
import time
from collections.abc import Callable, Mapping
from pathlib import Path

from ..expansion.bounded_child import Bounds, limit_resources, silence, status_words
from .findings import ConsumerResult

Load = Callable[[str, str, Mapping[str, str]], str]  # (consumer, URDF path, packages) -> what it saw; raises to refuse


class ConsumerHost:
    """A child that loads URDFs with the Python consumers (``load``), within ``bounds`` for each load, started when
    first asked and again after it ends."""

    def __init__(self, load: Load, bounds: Bounds, warm: str = "", nice: int = 0) -> None:
        self.load, self.bounds = load, bounds
        self.warm = warm  # (a module the child imports as it starts, before anything is sent: its library)
        self.nice = nice  # (how much the child yields the CPU to the others: a consumer that finishes early)
        self._pid: int | None = None
        self._send = self._receive = -1
        self._pending = b""
        self._grown = 0  # (bytes the host has grown by since it started, as its last answer says)

    def start(
        self, names: list[str], urdf: Path, packages: Mapping[str, str | os.PathLike[str]] | None
    ) -> Callable[[], dict[str, ConsumerResult]]:
        """Send the host ``urdf`` for each named consumer (starting the host when none runs: call this before
        starting any thread); the function returned waits for their verdicts. A consumer that ends the host (late,
        out of memory, crashed) has that verdict; those after it are sent again, to a new host."""
        if self._pid is not None and self._grown > self.bounds.memory // 2:
            self.stop()  # (what MuJoCo keeps grows with every mesh: a host past half its bound starts afresh)
        if self._pid is None:
            self._start()
        said = {k: str(v) for k, v in (packages or {}).items()}
        for name in names:
            request = {"name": name, "path": str(urdf), "packages": said}
            with contextlib.suppress(OSError):  # (a host that has ended: its answer says so)
                os.write(self._send, json.dumps(request).encode("utf-8") + b"\n")

        def collect() -> dict[str, ConsumerResult]:
            found = {}
            for index, name in enumerate(names):
                found[name] = self._result(name, self._answer(time.monotonic() + self.bounds.seconds))
                if self._pid is None and index + 1 < len(names):
                    found.update(self.start(names[index + 1 :], urdf, packages)())
                    break
            return found

        return collect

    def warm_up(self) -> None:
        """Start the host now (before any thread is started), which imports ``warm`` while the caller goes on: a
        library's import (yourdfpy's is a second) is done by the time the first URDF is sent."""
        if self._pid is None:
            self._start()

    def _result(self, name: str, answer: dict[str, str] | str) -> ConsumerResult:
        if answer == "timeout":
            self.stop()
            return ConsumerResult(name, "timeout", f"no verdict within {self.bounds.seconds:g} s; stopped")
        if isinstance(answer, str):  # (the host ended without an answer: its end is the verdict)
            return ConsumerResult(name, "crashed", self.stop() or "ended without a verdict")
        if answer["status"] in ("memory", "output"):
            self.stop()
            return ConsumerResult(name, "rejected", f"went past its {answer['status']} bound; stopped")
        self._grown = int(answer.get("grown", 0))
        return ConsumerResult(name, "accepted" if answer["status"] == "accepted" else "rejected", answer["message"])

    def _answer(self, deadline: float) -> dict[str, str] | str:
        """The host's next answer line, 'timeout' past ``deadline``, 'ended' when the host is gone."""
        poller = select.poll()
        poller.register(self._receive, select.POLLIN | select.POLLHUP)
        while b"\n" not in self._pending:
            left = deadline - time.monotonic()
            if left <= 0:
                return "timeout"
            if not poller.poll(min(left, 1.0) * 1000):
                continue
            chunk = os.read(self._receive, 1 << 16)
            if not chunk:
                return "ended"
            self._pending += chunk
            if len(self._pending) > 4 << 20:  # (a verdict is a line of a few hundred bytes)
                return "ended"
        line, _, self._pending = self._pending.partition(b"\n")
        try:
            answer = json.loads(line.decode("utf-8"))
        except ValueError:
            return "ended"
        return answer if isinstance(answer, dict) and "status" in answer else "ended"

    def _start(self) -> None:
        requests, self._send = os.pipe()
        self._receive, answers = os.pipe()
        pid = os.fork()
        if pid == 0:  # the host: never returns
            os.close(self._send)
            os.close(self._receive)
            code = 1
            try:
                signal.signal(signal.SIGINT, signal.SIG_DFL)
                silence()
                limit_resources(self.bounds, cpu=False)
                if self.nice:
                    os.nice(self.nice)
                if self.warm:
                    with contextlib.suppress(Exception):  # (one that fails to import fails again in the load)
                        importlib.import_module(self.warm)
                _serve(self.load, requests, answers, self.bounds.output)
                code = 0
            finally:
                os._exit(code)
        os.close(requests)
        os.close(answers)
        self._pid, self._pending, self._grown = pid, b"", 0

    def stop(self) -> str:
        """End the host (if it runs); how it ended, in words ('' when it was not running)."""
        if self._pid is None:
            return ""
        with contextlib.suppress(OSError):
            os.close(self._send)
        with contextlib.suppress(OSError):
            os.close(self._receive)
        with contextlib.suppress(ProcessLookupError):
            os.kill(self._pid, signal.SIGKILL)
        _, status = os.waitpid(self._pid, 0)
        self._pid = None
        return "" if os.WIFSIGNALED(status) and os.WTERMSIG(status) == signal.SIGKILL else status_words(status)


def _serve(load: Load, requests: int, answers: int, output: int) -> None:
    """The host's loop: a request line in, an answer line out (with how much the host has grown), until the parent
    closes the requests. A consumer's description longer than ``output`` characters is out of its bounds, as in a
    child of its own (:func:`~xacrokit.expansion.bounded_child.start_bounded`)."""
    start = _resident()
    with os.fdopen(requests, "rb") as incoming, os.fdopen(answers, "wb", buffering=0) as outgoing:
        for line in incoming:
            request = json.loads(line)
            answer: dict[str, str]
            try:
                os.chdir(Path(request["path"]).parent)  # (MuJoCo writes MUJOCO_LOG.TXT where it runs)
                seen = load(request["name"], request["path"], request["packages"])
                answer = {"status": "accepted", "message": seen} if len(seen) <= output else {"status": "output"}
            except MemoryError:
                answer = {"status": "memory", "message": ""}
            except Exception as exc:  # noqa: BLE001  (a consumer's own complaint is its verdict)
                answer = {"status": "rejected", "message": one_line(exc)}
            outgoing.write(json.dumps({**answer, "grown": _resident() - start}).encode("utf-8") + b"\n")
            if answer["status"] in ("memory", "output"):
                return  # (a host that went past a bound is not trusted with the next file)


def _resident() -> int:
    """This process's resident memory (bytes; 0 where /proc cannot tell)."""
    try:
        with open("/proc/self/statm") as statm:
            return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return 0


def one_line(exc: BaseException) -> str:
    """A consumer's complaint as check reports it: the exception's type and text on one line, at most 2,000
    characters."""
    return " ".join(f"{type(exc).__name__}: {exc}".split())[:2000]
