"""The write stage: decide what happens to every file first, then write atomically, or not at all.

Per file (copier's way):

* ``create``     the file does not exist yet;
* ``identical``  it exists with exactly this content: left alone (its mtime does not change);
* ``update``     it exists as we last generated it (its hash is in the manifest): replaced;
* ``conflict``   it exists and differs from what we last generated (someone edited it), or we never generated it:
                 kept, and nothing at all is written unless ``force``;
* ``overwrite``  a conflict replaced because ``force`` was given;
* ``remove``     we generated it last time, this run does not, and it is unchanged: deleted (with any folder
                 that leaves empty), e.g. the copied macros after switching to ``--macros inline``;
* ``keep``       the same, but someone edited it, or it is reached through a symbolic link, or the file system
                 refuses: left alone and dropped from the manifest.

A seed file (``RenderedFile.seed``, the package's extension file) is the user's: ``create`` when it is missing, else
``identical`` whatever it holds (left alone); it is never in the manifest, so never a conflict and never removed.

The manifest ``.xacrokit-manifest.json`` in the package root records the SHA-256 of each file as generated.
Nothing is ever written or removed outside the output folder.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import math
import os
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path, PurePosixPath
from typing import TYPE_CHECKING, Literal

from .. import __version__
from ..errors import XacrokitError
from ..shared.input_files import open_folders, read_below
from .atomic import digest, remove_leftover_temporaries, write_text_atomic

if TYPE_CHECKING:  # (the files only: the writer needs no renderer loaded)
    from ..render.environment import RenderedFile

LOCK_WAIT_S = 10.0  # seconds a second writer of one package waits for the first (XACROKIT_LOCK_WAIT sets another)

MANIFEST = ".xacrokit-manifest.json"
NOT_OURS = "not written by xacrokit"
Action = Literal["create", "identical", "update", "conflict", "overwrite", "remove", "keep"]


@dataclass(frozen=True)
class FileAction:
    """What the write stage did, or would do in a dry run, with one file of the package, and why."""

    path: str
    action: Action
    reason: str = ""


class WriterBusy(XacrokitError):
    """Another gen-robot holds the package folder (see :func:`package_lock`); this run wrote nothing."""


class ConflictError(XacrokitError):
    """Files were edited since they were generated; nothing was written."""

    exit_code = 1

    def __init__(self, root: Path, conflicts: list[FileAction], *, planned: bool = False):
        self.root = root
        self.conflicts = conflicts
        outcome = "a run would write nothing" if planned else "nothing was written"  # (planned: a dry run's plan)
        lines = [f"{len(conflicts)} file(s) in {root} are not as xacrokit generated them; {outcome}:"]
        lines += [f"  {c.path}: {c.reason}" for c in conflicts]
        if any(c.reason == NOT_OURS for c in conflicts):  # (a hand-written package.xml, a package of another tool)
            lines.append(
                f"A file {NOT_OURS} is not ours to replace: write the package into another folder (-o), move the "
                "file away, or run again with --force to overwrite it."
            )
        if any(c.reason != NOT_OURS for c in conflicts):
            lines.append("Keep your edits by moving them into the spec, or run again with --force to overwrite.")
        super().__init__("\n".join(lines))


Manifest = dict[str, frozenset[str]]  # path -> the SHA-256 digests of the contents we wrote there


def _read_manifest(root: Path) -> Manifest:
    """The manifest's digests per path. A run in progress (or killed) records two per file, the last run's and its
    own: whichever of them is on disk is ours."""
    try:
        data = json.loads((root / MANIFEST).read_text(encoding="utf-8"))
        files = data.get("files", {})
        if not isinstance(files, dict):
            return {}
        return {str(k): frozenset([v] if isinstance(v, str) else map(str, v)) for k, v in files.items()}
    except (OSError, ValueError, AttributeError, TypeError):
        return {}


def _manifest_text(files: dict[str, str | list[str]], *, in_progress: bool) -> str:
    data: dict[str, object] = {"generator": f"xacrokit {__version__}"}
    if in_progress:
        data["in_progress"] = "a run is writing (or was killed): each file is ours with any digest listed"
    data["files"] = files
    return json.dumps(data, indent=2, sort_keys=True) + "\n"


def _inside(root: Path, relative: str) -> Path:
    target = (root / relative).resolve()
    if not target.is_relative_to(root.resolve()):
        raise XacrokitError(f"refusing to write {relative}: it resolves outside {root}")
    return target


def plan(
    files: list[RenderedFile], root: Path, *, force: bool = False, manifest: Manifest | None = None
) -> list[FileAction]:
    """Decide the action for every file, touching nothing. ``manifest``: the folder's manifest, if already read."""
    if root.exists() and not root.is_dir():
        raise XacrokitError(f"the output {root} exists and is not a folder")
    manifest = _read_manifest(root) if manifest is None else manifest
    actions = []
    for file in files:
        target = _inside(root, file.path)
        if not target.exists():
            actions.append(FileAction(file.path, "create"))
            continue
        if not target.is_file():
            # even --force does not replace a folder with a file
            actions.append(FileAction(file.path, "conflict", "a folder stands in its place"))
            continue
        if file.seed:  # (the user's from its creation on: left as it is)
            actions.append(FileAction(file.path, "identical", "yours: created once, never rewritten"))
            continue
        current: str | bytes | None
        try:
            current = target.read_bytes() if isinstance(file.content, bytes) else target.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError):
            current = None
        if current == file.content:
            actions.append(FileAction(file.path, "identical"))
        elif current is not None and digest(current) in manifest.get(file.path, ()):
            actions.append(FileAction(file.path, "update"))
        else:
            reason = "edited since it was generated" if file.path in manifest else NOT_OURS
            actions.append(FileAction(file.path, "overwrite" if force else "conflict", reason))
    return actions + _stale(manifest, files, root)


def _stale(manifest: Manifest, files: list[RenderedFile], root: Path) -> list[FileAction]:
    """What happens to the files we generated last time that this run does not generate.

    Only plain files reached without a symbolic link, named in normal form inside the folder, are candidates: a
    manifest edited by hand or a linked folder never makes us delete anything else. A name that is not a path inside
    the folder, or whose file is gone, is dropped silently; anything else we will not remove is reported as kept.
    """
    generated = {f.path for f in files} | {MANIFEST}  # (seeds included: a seed of an older run is never stale)
    actions = []
    for path in sorted(manifest.keys() - generated):
        if not _normal(path):
            continue
        try:
            data, _ = read_below(root, path)
        except FileNotFoundError:
            continue
        except (OSError, ValueError) as exc:
            actions.append(FileAction(path, "keep", f"no longer generated, but not removable: {_why(exc)}"))
            continue
        if digest(data) in manifest[path]:
            actions.append(FileAction(path, "remove", "no longer generated"))
        else:
            actions.append(FileAction(path, "keep", "no longer generated, but edited since: kept"))
    return actions


def _normal(relative: str) -> bool:
    """A relative POSIX path in normal form, inside the folder (no ``..``, ``.``, empty parts or NUL)."""
    pure = PurePosixPath(relative)
    return (
        bool(relative)
        and "\0" not in relative
        and not pure.is_absolute()
        and pure.as_posix() == relative
        and not any(part in ("..", ".") for part in pure.parts)
    )


def _why(exc: BaseException) -> str:
    return exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)


def write(files: list[RenderedFile], root: Path, *, force: bool = False, dry_run: bool = False) -> list[FileAction]:
    """Plan, then (unless ``dry_run``) write every created, updated or overwritten file atomically, record the
    manifest, and remove the stale files planned for removal (a removal the file system refuses, or a file changed
    since the plan, becomes ``keep``). A dry run returns the plan, ``conflict`` actions included.

    Raises:
        ConflictError: some file was edited since it was generated (and ``force`` is off); nothing is written.
            Not raised by a dry run.
        XacrokitError: the file system refused a write (the message names the file and what was written before it).
    """
    if dry_run:  # conflicts included: the plan shows them
        return plan(files, root, force=force, manifest=_read_manifest(root))
    made = _first_missing(root)  # the topmost folder this run makes (the package, maybe folders above it)
    written: list[Path] = []
    fresh = made is not None
    try:
        with package_lock(root):
            # a run that waited for another writer of a new folder finds that run's package: an update, not ours to
            # undo (undoing would delete the files of it that this run had replaced, its manifest among them)
            fresh = fresh and _empty(root)
            return _write_planned(files, root, force=force, fresh=fresh, written=written)
    except WriterBusy:  # never held the folder: what is in it (maybe just made, still empty) is the other run's
        raise
    except BaseException:
        if fresh and made is not None:  # a fresh package that could not be written leaves nothing behind
            _undo_fresh(root, made, written)
        raise


def _empty(folder: Path) -> bool:
    with os.scandir(folder) as entries:
        return next(entries, None) is None


def _undo_fresh(root: Path, made: Path, written: list[Path]) -> None:
    """Remove what a run that made ``made`` wrote, then every folder from ``root`` up to ``made`` that this leaves
    empty. Only this run's files go and only empty folders: another run's package in the same folders stays whole."""
    for path in written:
        with contextlib.suppress(OSError):
            path.unlink()
    if root.is_dir() and not root.is_symlink():
        for inner, _, _ in sorted(os.walk(root), key=lambda entry: -len(entry[0])):  # (deepest first)
            with contextlib.suppress(OSError):
                os.rmdir(inner)
    for above in (root, *root.parents):
        with contextlib.suppress(OSError):
            os.rmdir(above)  # (fails, and stops nothing, when another run's files are in it)
        if above == made:
            break


def _first_missing(root: Path) -> Path | None:
    """The topmost folder of ``root`` (itself included) that does not exist yet, or None when ``root`` exists."""
    missing = None
    for folder in (root, *root.parents):
        if folder.exists() or folder.is_symlink():
            return missing
        missing = folder
    return missing


@contextlib.contextmanager
def package_lock(root: Path, wait: float | None = None) -> Iterator[None]:
    """Hold an exclusive lock on the package folder (made if missing) while a run plans and writes it: a second
    gen-robot writing the same folder waits up to ``wait`` seconds, then stops with a message, instead of mixing its
    files with ours. (flock on the folder itself: no lock file in the package.)"""
    if wait is None:
        wait = lock_wait()
    try:
        root.mkdir(parents=True, exist_ok=True)
        fd = os.open(root, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError as exc:
        where = exc.filename or root
        raise XacrokitError(
            f"cannot write the package in {root}: {where}: {exc.strerror or exc}; nothing was written"
        ) from exc
    try:
        deadline = time.monotonic() + wait
        while True:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                if time.monotonic() > deadline:
                    raise WriterBusy(
                        f"another gen-robot is writing {root} (waited {wait:g} s); run again when it is done"
                    ) from None
                time.sleep(0.05)
        yield
    finally:
        os.close(fd)  # (closing releases the lock)


def lock_wait() -> float:
    """Seconds to wait for another writer: XACROKIT_LOCK_WAIT when set (0 to 3600), else LOCK_WAIT_S."""
    text = os.environ.get("XACROKIT_LOCK_WAIT", "").strip()
    if not text:
        return LOCK_WAIT_S
    try:
        wait = float(text)
    except ValueError:
        wait = math.nan
    if not 0 <= wait <= 3600:  # (nan fails too)
        raise XacrokitError(f"XACROKIT_LOCK_WAIT must be a number of seconds from 0 to 3600, got {text!r}")
    return wait


def _write_planned(
    files: list[RenderedFile], root: Path, *, force: bool, fresh: bool, written: list[Path]
) -> list[FileAction]:
    """:func:`write` under the lock; each file written is appended to ``written``."""
    previous = _read_manifest(root)
    actions = plan(files, root, force=force, manifest=previous)
    conflicts = [a for a in actions if a.action == "conflict"]
    if conflicts:
        raise ConflictError(root, conflicts)
    # a killed run leaves temporaries beside the files it was writing: this run's, or those its manifest lists
    listed = [path for path in previous if _normal(path) and (root / path).resolve().is_relative_to(root.resolve())]
    remove_leftover_temporaries(root, [a.path for a in actions] + listed + [MANIFEST])
    by_path = {f.path: f for f in files}
    digests = {f.path: digest(f.content) for f in files if not f.seed}  # (a seed is the user's: not in the manifest)
    manifest_path = root / MANIFEST
    done = 0
    try:
        if any(a.action in ("create", "update", "overwrite", "remove") for a in actions):
            # first the manifest "in progress": every file ours with the last run's digest or this run's, so that a
            # run killed midway leaves a folder the next run (of either spec) takes over without a false conflict
            pending = {path: sorted(previous.get(path, frozenset()) | {digests[path]}) for path in digests}
            pending |= {path: sorted(previous[path]) for path in previous.keys() - digests.keys()}
            write_text_atomic(manifest_path, _manifest_text(dict(pending), in_progress=True))
            written.append(manifest_path)
        for action in actions:
            if action.action in ("create", "update", "overwrite"):
                target = _inside(root, action.path)
                write_text_atomic(target, by_path[action.path].content)
                written.append(target)
                done += 1
    except OSError as exc:
        raise _write_error(root, exc, fresh=fresh, done=done) from exc
    if any(a.action == "remove" for a in actions):
        actions = _remove_stale(files, root, actions, previous)
    try:  # last: the manifest of what is on disk now
        text = _manifest_text(dict(digests), in_progress=False)
        if not manifest_path.is_file() or manifest_path.read_bytes() != text.encode("utf-8"):
            write_text_atomic(manifest_path, text)
            written.append(manifest_path)
    except OSError as exc:
        raise _write_error(root, exc, fresh=fresh, done=done) from exc
    return actions


def _write_error(root: Path, exc: OSError, *, fresh: bool, done: int) -> XacrokitError:
    """The file system refused a write: what, where, and what was written before it."""
    where = exc.filename or root
    said = (
        "; nothing was written (what this run wrote is removed)"
        if fresh
        else f"; {done} file(s) were written before it, each whole"
        if done
        else "; nothing was written"
    )
    return XacrokitError(f"cannot write the package in {root}: {where}: {exc.strerror or exc}{said}")


def _remove_stale(
    files: list[RenderedFile], root: Path, actions: list[FileAction], previous: Manifest
) -> list[FileAction]:
    """Remove the stale files planned for removal (see :func:`_remove`); the actions with each outcome."""
    identities: set[tuple[int, int]] = set()  # what this run wrote: on a case-blind disk a stale name may be one
    for file in files:
        with contextlib.suppress(OSError):
            status = (root / file.path).stat()
            identities.add((status.st_dev, status.st_ino))
    return [
        _remove(root, a, previous.get(a.path, frozenset()), identities) if a.action == "remove" else a for a in actions
    ]


def _remove(root: Path, action: FileAction, digests: frozenset[str], written: set[tuple[int, int]]) -> FileAction:
    """Delete a stale file if it is still as generated and is not a file this run wrote, then each folder above it
    that this leaves empty. Every step goes through folder descriptors opened without following symbolic links, so
    a folder swapped for a link while we ran cannot lead us outside the package."""
    parts = PurePosixPath(action.path).parts
    try:
        data, identity = read_below(root, action.path)
        if identity in written:
            return FileAction(
                action.path, "keep", "no longer generated under this name, but the same file as one that is"
            )
        if digest(data) not in digests:
            return FileAction(action.path, "keep", "no longer generated, but changed while we ran: kept")
        fds = open_folders(root, parts)
    except (OSError, ValueError) as exc:
        return FileAction(action.path, "keep", f"no longer generated; could not remove it: {_why(exc)}")
    try:
        try:
            os.unlink(parts[-1], dir_fd=fds[-1])
        except OSError as exc:
            return FileAction(action.path, "keep", f"no longer generated; could not remove it: {_why(exc)}")
        for depth in range(len(fds) - 1, 0, -1):  # the folders it leaves empty, innermost first
            try:
                os.rmdir(parts[depth - 1], dir_fd=fds[depth - 1])
            except OSError:  # not empty (or not ours to remove): the folders above are not empty either
                break
    finally:
        for fd in fds:
            os.close(fd)
    return action
