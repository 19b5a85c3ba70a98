"""Run one piece of untrusted work (expanding a xacro document from elsewhere) in a forked child process, with bounds.

xacro evaluates a document's expressions with Python's ``eval``. :mod:`xacrokit.expansion.expression_guard` refuses the
expressions that reach Python's internals, but no check of an expression's text can bound what it costs: ``${'x' *
10**10}`` asks for 10 GB, ``${10**10**10}`` computes for hours inside one C call that no signal interrupts, and a macro
that calls itself twice, 30 levels deep, makes 2**30 elements. So the work runs in a child (``os.fork``: a few
milliseconds, the modules already imported), which:

* may use at most ``memory`` bytes more address space than the parent had (``RLIMIT_AS``): past it, Python raises
  ``MemoryError`` in the child;
* is killed after ``seconds`` of wall time (and by ``RLIMIT_CPU`` a second later, should the parent be gone);
* may return at most ``output`` characters.

The child sends its result back as JSON (never pickle: a child that has run a hostile document is not trusted either)
and what it printed on stderr, which the parent prints. A fork copies the parent, so the child sees every module,
setting and test patch the parent has; it leaves with ``os._exit``, running none of the parent's cleanups (a
temporary folder the parent made stays the parent's). Where ``os.fork`` does not exist, the work runs in-process,
unbounded.
"""

from __future__ import annotations

import contextlib
import faulthandler
import io
import json
import math
import os
import resource
import select
import signal
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Bounds:
    seconds: float  # wall time
    memory: int  # bytes of address space beyond the parent's
    output: int  # characters of the result


class OutOfBounds(Exception):
    """The work went past one of its bounds: ``which`` is ``seconds``, ``memory`` or ``output``."""

    def __init__(self, which: str, bounds: Bounds) -> None:
        self.which = which
        self.bounds = bounds
        super().__init__(which)


class ChildFailed(Exception):
    """The child ended without a result (killed by a signal other than ours, or a bug): ``detail`` says how."""

    def __init__(self, detail: str) -> None:
        self.detail = detail
        super().__init__(detail)


def run_bounded(
    work: Callable[[], str], bounds: Bounds, *, errors: Callable[[BaseException], dict[str, Any] | None]
) -> tuple[str | None, dict[str, Any] | None]:
    """Run ``work`` in a child within ``bounds``.

    Args:
        work: returns the result text, or raises.
        bounds: the limits.
        errors: turns an exception ``work`` raised into plain data (JSON types) for the parent, or None when it is
            not an expected error (the parent then gets :class:`ChildFailed`).

    Returns:
        ``(text, None)`` when ``work`` returned, ``(None, data)`` when it raised an error ``errors`` described.

    Raises:
        OutOfBounds: the work went past a bound (it was stopped).
        ChildFailed: the child ended without a result.
    """
    return start_bounded(work, bounds, errors=errors)()


def start_bounded(
    work: Callable[[], str],
    bounds: Bounds,
    *,
    errors: Callable[[BaseException], dict[str, Any] | None],
    quiet: bool = False,
) -> Callable[[], tuple[str | None, dict[str, Any] | None]]:
    """:func:`run_bounded`, started: the child runs while the caller goes on, and the function returned waits for
    its result (the time bound counts from now). Start every child before starting any thread: a fork copies only
    the thread that forks, and a lock another thread holds stays held in the child. With ``quiet``, what the work
    prints (C libraries included: file descriptors 1 and 2) goes nowhere instead of to the parent's stderr."""
    if not hasattr(os, "fork"):  # (no fork, no bounds: the work runs here, when its result is asked for)
        return _unbounded(work, errors)
    for stream in (sys.stdout, sys.stderr):  # (else the child would print the parent's buffered output again)
        with contextlib.suppress(Exception):
            stream.flush()
    deadline = time.monotonic() + bounds.seconds
    reader, writer = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: never returns
        os.close(reader)
        if quiet:
            silence()
        _child(work, bounds, errors, writer)
    os.close(writer)

    def wait() -> tuple[str | None, dict[str, Any] | None]:
        try:
            received, overflowed, timed_out = _collect(reader, bounds, deadline)
        finally:
            os.close(reader)
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)  # (a no-op for a child that has already exited and waits to be reaped)
            _, status = os.waitpid(pid, 0)
        return _outcome(received, overflowed, timed_out, status, bounds, quiet=quiet)

    return wait


def _unbounded(
    work: Callable[[], str], errors: Callable[[BaseException], dict[str, Any] | None]
) -> Callable[[], tuple[str | None, dict[str, Any] | None]]:
    """The work run in this process when its result is asked for (where there is no fork)."""

    def here() -> tuple[str | None, dict[str, Any] | None]:
        try:
            return work(), None
        except BaseException as exc:
            data = errors(exc)
            if data is None:
                raise
            return None, data

    return here


def _outcome(
    received: bytes, overflowed: bool, timed_out: bool, status: int, bounds: Bounds, *, quiet: bool
) -> tuple[str | None, dict[str, Any] | None]:
    """What the child's message says: its text, or the error it reported as data; the bounds it broke raised."""
    if timed_out:
        raise OutOfBounds("seconds", bounds)
    if overflowed:
        raise OutOfBounds("output", bounds)
    try:
        message = json.loads(received.decode("utf-8"))
    except ValueError:
        raise ChildFailed(status_words(status)) from None
    if not quiet:
        with contextlib.suppress(Exception):
            sys.stderr.write(message.get("stderr", ""))
    kind = message.get("kind")
    if kind == "result":
        return str(message["text"]), None
    if kind == "error":
        return None, dict(message["error"])
    if kind in ("memory", "output"):
        raise OutOfBounds(kind, bounds)
    raise ChildFailed(str(message.get("detail", "no result")))


def silence() -> None:
    """The child's standard output and error, to nowhere: the file descriptors (what C code prints) and Python's
    streams (new objects: the parent's may have been locked by another thread at the fork)."""
    faulthandler.disable()  # (a crash is the child's verdict; faulthandler, on in a test run, would print it)
    with contextlib.suppress(OSError):
        nowhere = os.open(os.devnull, os.O_WRONLY)
        os.dup2(nowhere, 1)
        os.dup2(nowhere, 2)
        os.close(nowhere)
        sys.stdout = open(os.devnull, "w")  # noqa: SIM115  (the child's for good: it ends with os._exit)
        sys.stderr = open(os.devnull, "w")  # noqa: SIM115


def _collect(reader: int, bounds: Bounds, deadline: float) -> tuple[bytes, bool, bool]:
    """What the child sends, until it closes the pipe or ``deadline`` (a monotonic time) passes: (bytes, more than
    the output bound, out of time)."""
    limit = 4 * bounds.output + 64 * 1024  # characters to UTF-8 bytes, escaped in JSON: a generous ceiling
    chunks: list[bytes] = []
    size = 0
    poller = select.poll()  # (not select.select: it refuses descriptors above 1023, which a busy process may hold)
    poller.register(reader, select.POLLIN | select.POLLHUP)
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            return b"", False, True
        if not poller.poll(min(left, 1.0) * 1000):
            continue
        chunk = os.read(reader, 1 << 20)
        if not chunk:
            return b"".join(chunks), False, False
        chunks.append(chunk)
        size += len(chunk)
        if size > limit:
            return b"", True, False


def _child(
    work: Callable[[], str],
    bounds: Bounds,
    errors: Callable[[BaseException], dict[str, Any] | None],
    writer: int,
) -> None:
    code = 0
    try:
        signal.signal(signal.SIGINT, signal.SIG_DFL)  # (Ctrl-C reaches the child too: let it just end)
        limit_resources(bounds)
        captured = io.StringIO()
        message: dict[str, Any]
        try:
            with contextlib.redirect_stderr(captured):
                text = work()
            if len(text) > bounds.output:
                message = {"kind": "output"}
            else:
                message = {"kind": "result", "text": text}
        except MemoryError:
            message = {"kind": "memory"}
        except BaseException as exc:
            data = errors(exc)
            message = (
                {"kind": "error", "error": data}
                if data is not None
                else {"kind": "crash", "detail": f"{type(exc).__name__}: {exc}"[:2000]}
            )
        message["stderr"] = captured.getvalue()[-64 * 1024 :]
        payload = json.dumps(message).encode("utf-8")
        with os.fdopen(writer, "wb") as pipe:
            pipe.write(payload)
    except BaseException:  # (MemoryError while writing the answer, a closed pipe): the parent sees no result
        code = 1
    finally:
        os._exit(code)


def limit_resources(bounds: Bounds, *, cpu: bool = True) -> None:
    """This child's resource limits: address space (its parent's, plus ``bounds.memory``) and, with ``cpu``, CPU
    time (a child that lives for many pieces of work takes none: its parent stops it when a piece is late)."""
    with contextlib.suppress(OSError, ValueError):
        with open("/proc/self/statm") as statm:  # (Linux: the size of the address space, in pages, first)
            pages = int(statm.read().split()[0])
        _, hard = resource.getrlimit(resource.RLIMIT_AS)
        wanted = pages * resource.getpagesize() + bounds.memory
        resource.setrlimit(resource.RLIMIT_AS, (wanted if hard == resource.RLIM_INFINITY else min(wanted, hard), hard))
    if not cpu:
        return
    with contextlib.suppress(OSError, ValueError):
        _, hard = resource.getrlimit(resource.RLIMIT_CPU)
        seconds = math.ceil(bounds.seconds) + 1
        resource.setrlimit(
            resource.RLIMIT_CPU, (seconds if hard == resource.RLIM_INFINITY else min(seconds, hard), hard)
        )


def status_words(status: int) -> str:
    """How a child ended, in words: 'killed by SIGSEGV', 'exit status 1'."""
    if os.WIFSIGNALED(status):
        number = os.WTERMSIG(status)
        with contextlib.suppress(ValueError):
            return f"killed by {signal.Signals(number).name}"
        return f"killed by signal {number}"
    return f"exit status {os.waitstatus_to_exitcode(status)}"
