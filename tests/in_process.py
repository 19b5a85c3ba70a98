"""gen-robot run inside the test's own process, as a process would run it (conftest.gen_robot): hundreds of tests run
the command line, and a process of its own cost 0.5 to 1.5 s each, nearly all of it Python starting and importing.

What a process would give is kept: ``main`` gets the words as ``python -m xacrokit.cli`` would; file descriptors 1 and 2
are files of this call (so what C++ libraries print, and what a forked child prints, is captured too), read back and
decoded as ``subprocess.run(..., text=True)`` decodes a child's output; ``sys.exit`` and an exception that escapes
become the exit code and the traceback a process would print; the working folder, the environment, the warning
filters and the logging handlers are a fresh process's for the call and put back afterwards. What stays is what a
process of this interpreter would have anyway (the modules imported, their caches of files read, which are keyed by
the files' contents or times).

A test that proves something of the process itself (a signal, a kill, what it imports at start, the console script,
its output closed) starts a real one: conftest.gen_robot_process."""

from __future__ import annotations

import contextlib
import io
import logging
import os
import subprocess
import sys
import tempfile
import traceback
import warnings
from collections.abc import Iterator, Sequence
from typing import Any

# a fresh interpreter's warning filters (python -W and PYTHONWARNINGS unset), most specific last as filterwarnings
# inserts each at the front
FRESH_FILTERS = (
    ("ignore", ResourceWarning),
    ("ignore", ImportWarning),
    ("ignore", PendingDeprecationWarning),
    ("ignore", DeprecationWarning),
)


def run_main(words: Sequence[str], cwd: str | os.PathLike[str] | None = None) -> subprocess.CompletedProcess:
    """``python -m xacrokit.cli WORDS`` in this process: its exit code and its output, text."""
    from xacrokit.cli import main  # (start-up: the command line, once per test process)

    argv = [sys.executable, "-m", "xacrokit.cli", *words]
    with _fresh_process_state(cwd), _captured() as (out, err):
        code = _exit_code(lambda: main(list(words)))
    return subprocess.CompletedProcess(argv, code, _text(out.getvalue()), _text(err.getvalue()))


def _exit_code(call: Any) -> int:
    """The exit status ``sys.exit(call())`` gives a process: a SystemExit's code, or 1 and the traceback printed for
    an exception that escapes."""
    try:
        result = call()
    except SystemExit as exc:
        result = exc.code
    except KeyboardInterrupt:
        raise
    except BaseException:  # noqa: BLE001  (what the interpreter would print and exit 1 for)
        traceback.print_exc(file=sys.stderr)
        return 1
    if result is None:
        return 0
    if isinstance(result, int):
        return result & 0xFF
    print(result, file=sys.stderr)
    return 1


@contextlib.contextmanager
def _fresh_process_state(cwd: str | os.PathLike[str] | None) -> Iterator[None]:
    """The working folder, environment, warning filters and logging a new process would start with; the test's put
    back afterwards."""
    folder, environment = os.getcwd(), dict(os.environ)
    root = logging.getLogger()
    handlers, level = root.handlers[:], root.level
    try:
        if cwd is not None:
            os.chdir(cwd)
        root.handlers, root.level = [], logging.WARNING  # (no handler: logging's last resort prints to stderr)
        with warnings.catch_warnings():
            warnings.resetwarnings()
            for action, category in FRESH_FILTERS:
                warnings.filterwarnings(action, category=category)
            warnings.filterwarnings("default", category=DeprecationWarning, module="__main__")
            warnings.showwarning = _show_warning
            yield
    finally:
        root.handlers, root.level = handlers, level
        os.chdir(folder)
        os.environ.clear()
        os.environ.update(environment)


def _show_warning(message: Any, category: Any, filename: str, lineno: int, file: Any = None, line: Any = None) -> None:
    sys.stderr.write(warnings.formatwarning(message, category, filename, lineno, line))


@contextlib.contextmanager
def _captured() -> Iterator[tuple[io.BytesIO, io.BytesIO]]:
    """File descriptors 0, 1 and 2 and sys.stdin, stdout and stderr of the call: stdin empty (gen_robot gives a
    process none), stdout and stderr into files read back when it ends (as bytes, into the two buffers)."""
    out, err = io.BytesIO(), io.BytesIO()
    streams = (sys.stdin, sys.stdout, sys.stderr)
    for stream in streams[1:]:
        with contextlib.suppress(Exception):
            stream.flush()
    kept = [os.dup(fd) for fd in (0, 1, 2)]
    with tempfile.TemporaryFile() as out_file, tempfile.TemporaryFile() as err_file, open(os.devnull, "rb") as empty:
        try:
            for source, fd in ((empty, 0), (out_file, 1), (err_file, 2)):
                os.dup2(source.fileno(), fd)
            sys.stdin = open(0, encoding="utf-8", closefd=False)  # noqa: SIM115  (closed with the call)
            sys.stdout = _writer(1, "surrogateescape")  # (a C.UTF-8 locale's: a child's stdout and stderr)
            sys.stderr = _writer(2, "backslashreplace")
            yield out, err
        finally:
            for stream in (sys.stdout, sys.stderr):
                with contextlib.suppress(Exception):
                    stream.flush()
            sys.stdin.close()
            sys.stdin, sys.stdout, sys.stderr = streams
            for fd, saved in zip((0, 1, 2), kept, strict=True):
                os.dup2(saved, fd)
                os.close(saved)
            for file, buffer in ((out_file, out), (err_file, err)):
                file.seek(0)
                buffer.write(file.read())


def _writer(fd: int, errors: str) -> Any:
    return open(fd, "w", encoding="utf-8", errors=errors, closefd=False)  # noqa: SIM115  (flushed with the call)


def _text(data: bytes) -> str:
    """As subprocess.run(..., text=True) decodes a child's output: the locale's encoding, universal newlines."""
    import locale  # (start-up: only to decode)

    text = data.decode(locale.getpreferredencoding(False))
    return text.replace("\r\n", "\n").replace("\r", "\n")
