"""Checking many files in one call: worker processes that each pay the imports once.

Before the workers start, this process imports what checking needs (our rules, xacro, the generator for specs, the
consumers' libraries: pinocchio, yourdfpy with trimesh, MuJoCo) and then forks ``jobs`` workers, which share those
modules with it; each worker checks one file at a time with :func:`~xacrokit.check.checker.check`, exactly as a call
per file would, and keeps what it has read for the next robot: the meshes our rules read, and what the consumers keep
(they run in one bounded host per worker, :mod:`xacrokit.check.consumer_host`, where MuJoCo keeps the meshes it has
compiled). The robots that use the same meshes go to one worker (:func:`_shares`), the largest shares first; the
results come back in the order the files were given. A file that cannot be read is a result too (its message, exit
code 2): the other files are still checked. Where there is no ``fork`` (or for one file, or one job) the files are
checked here, one by one.
"""

from __future__ import annotations

import contextlib
import importlib
import math
import os
import re
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import XacrokitError
from ..reader.robot_input import RobotInput
from ..reader.robot_source import input_kind
from ..shared.terminal_text import printable
from .consumers import LIBRARIES, chosen, hosted_consumers
from .findings import CheckReport

if TYPE_CHECKING:
    from concurrent.futures import Future


@dataclass(frozen=True)
class FileCheck:
    """One file's outcome: its report, or why it could not be checked (``error``: the file cannot be read, exit 2)."""

    source: str
    report: CheckReport | None
    error: str | None = None
    seconds: float = 0.0  # (how long the check took, for JUnit's time)

    def exit_code(self, strict: bool = False) -> int:
        if self.report is None:
            return 2
        return self.report.exit_code(strict=strict)


def run_dict(checks: Sequence[FileCheck], *, strict: bool = False) -> dict[str, Any]:
    """A run over many files as JSON data (schemas/check-run.schema.json): each file's report as ``gen-robot check
    --json FILE`` gives it, or its source and why it cannot be read."""
    codes = [check.exit_code(strict) for check in checks]
    return {
        "format": "xacrokit-check-run/1",
        "summary": {
            "files": len(checks),
            "passed": codes.count(0),
            "failed": codes.count(1),
            "unreadable": codes.count(2),
            "exit_code": max(codes, default=0),
        },
        "reports": [
            check.report.to_dict() if check.report is not None else {"source": check.source, "error": check.error}
            for check in checks
        ],
    }


@dataclass(frozen=True)
class CheckOptions:
    """What :func:`~xacrokit.check.checker.check` takes besides the path, the same for every file of a run."""

    mappings: Mapping[str, str] = field(default_factory=dict)
    prefix: str | None = None
    consumers: Sequence[str] | None = None
    package_paths: Mapping[str, str | Path] | None = None
    trust: bool = False
    srdf: Path | None = None  # (the SRDF whose disabled pairs G007 respects; None: the one beside the file)

    def check(self, path: Path, progress: Callable[[str], None] | None = None) -> CheckReport:
        """:func:`~xacrokit.check.checker.check` of ``path`` with these options."""
        from .checker import check  # (heavy: lxml)

        # (untrusted unless told, or unless the environment says so: None)
        given = RobotInput(path, self.mappings, self.package_paths or {}, True if self.trust else None)
        said = _printable(progress) if progress is not None else None
        return check(given, prefix=self.prefix, consumers=self.consumers, progress=said, srdf=self.srdf)


def _printable(progress: Callable[[str], None]) -> Callable[[str], None]:
    """``progress`` told each message :func:`printable` (the progress line says a file's name, a terminal shows it)."""
    return lambda message: progress(printable(message))


def check_files(
    files: Sequence[Path],
    options: CheckOptions,
    *,
    jobs: int | None = None,
    progress: Callable[[str], None] | None = None,
) -> Iterator[FileCheck]:
    """Check ``files`` in ``jobs`` worker processes (default: the CPU count), yielding each file's outcome in the
    order given, as soon as it and those before it are done."""

    names = chosen(options.consumers)  # (an unknown or missing consumer is refused before any file is read)
    jobs = max(1, min(jobs or os.cpu_count() or 1, len(files)))
    say = _printable(progress) if progress is not None else (lambda message: None)
    if jobs == 1 or not hasattr(os, "fork"):
        with hosted_consumers():
            for index, path in enumerate(files):
                say(f"checking {index + 1}/{len(files)}: {path.name}")
                yield check_one(path, options)
        return
    _import_for(names, files)
    yield from _in_workers(files, options, jobs, say)


def check_one(path: Path, options: CheckOptions) -> FileCheck:
    """One file's outcome (what ``gen-robot check PATH`` says of it alone)."""

    start = time.perf_counter()
    try:
        report = options.check(path)
    except XacrokitError as exc:
        return FileCheck(str(path), None, str(exc), time.perf_counter() - start)
    return FileCheck(str(path), report, None, time.perf_counter() - start)


def _in_workers(
    files: Sequence[Path], options: CheckOptions, jobs: int, say: Callable[[str], None]
) -> Iterator[FileCheck]:

    import multiprocessing  # (start-up: only a check of many files has workers)
    from concurrent.futures import ProcessPoolExecutor  # (start-up: only a check of many files has workers)

    # (fork: the workers start from this process with its imports; all of them before any thread of the pool runs)
    pool = ProcessPoolExecutor(
        max_workers=jobs, mp_context=multiprocessing.get_context("fork"), initializer=_worker_starts
    )
    try:
        shares = _shares(files, jobs)
        futures: list[Future[list[FileCheck]]] = [
            pool.submit(_check_share, [files[i] for i in s], options) for s in shares
        ]
        where = {index: (number, place) for number, share in enumerate(shares) for place, index in enumerate(share)}
        for index, path in enumerate(files):
            say(f"checked {index}/{len(files)}; waiting for {path.name}")
            number, place = where[index]
            yield _outcome(path, futures[number], place)
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def _shares(files: Sequence[Path], jobs: int) -> list[list[int]]:
    """The files (their indices) as the workers take them: the robots that use the same meshes together (one worker
    then reads them, and its MuJoCo compiles them, once), a share at most a worker's part of the whole (so that one
    package of many robots still keeps every worker busy), the largest shares first."""
    most = max(1, math.ceil(len(files) / jobs))
    groups: dict[str, list[int]] = {}
    for index, path in enumerate(files):
        groups.setdefault(_mesh_folder(path), []).append(index)
    shares = [group[start : start + most] for group in groups.values() for start in range(0, len(group), most)]
    return sorted(shares, key=lambda share: -sum(_size(files[i]) for i in share))


_MESH_NAME = re.compile(rb"""filename\s*=\s*["']([^"']+)["']""")


def _mesh_folder(path: Path) -> str:
    """Where a URDF's first mesh is (its URI's folder), which the robots of one package share; else its own folder."""
    found = None
    if path.suffix.lower() == ".urdf" and path.is_file():  # (never opened otherwise: a FIFO would block)
        with contextlib.suppress(OSError), path.open("rb") as stream:
            found = _MESH_NAME.search(stream.read(1 << 20))
    if found is None:
        return str(path.parent)
    return found.group(1).decode("utf-8", "replace").rpartition("/")[0]


def _check_share(files: list[Path], options: CheckOptions) -> list[FileCheck]:
    return [check_one(path, options) for path in files]


_WORKER = contextlib.ExitStack()  # (what a worker holds for its life: its consumers' host)


def _worker_starts() -> None:
    """A worker's start: its Python consumers run in one host for all its files, stopped (and waited for) when the
    worker ends."""

    from multiprocessing import util  # (start-up: only a check of many files has workers)

    _WORKER.enter_context(hosted_consumers())
    util.Finalize(None, _WORKER.close, exitpriority=10)  # (a worker ends through multiprocessing's finalizers)


def _outcome(path: Path, future: Any, place: int) -> FileCheck:
    """The worker's result for ``path`` (at ``place`` in its share); a worker that ended without one (killed, out of
    memory) is said as the file's error."""

    from concurrent.futures.process import BrokenProcessPool  # (start-up: only a check of many files has workers)

    try:
        result: FileCheck = future.result()[place]
    except BrokenProcessPool as exc:
        return FileCheck(
            str(path), None, f"{path}: the worker checking it ended without a verdict ({exc}); check it alone"
        )
    return result


def _size(path: Path) -> int:
    try:
        return path.stat().st_size
    except OSError:
        return 0


def _import_for(names: Sequence[str], files: Sequence[Path]) -> None:
    """Import what the workers will need, here, before they fork (each then has it without importing it again)."""

    modules = ["xacrokit.check.rule_table", "xacrokit.check.checker", "stl", "scipy.spatial", "trimesh"]
    modules += [LIBRARIES[name] for name in names if name in LIBRARIES]
    kinds = {input_kind(path) for path in files}
    if "xacro" in kinds:
        modules.append("xacrokit.expansion.xacro_expand")
    if "spec" in kinds:
        modules.append("xacrokit.pipeline")
    for module in modules:
        importlib.import_module(module)
