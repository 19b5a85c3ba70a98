"""The write stage for every command's output (``import``, ``export``, ``view``, ``render``, ``graph``, ``report``,
``size -o/--report``, ``expand -o``): the guarantees ``generate`` gives its package, for a file or a few beside it.

Planned first, then written, or nothing is:

* a path that is a symbolic link, a device, a FIFO, a socket or a folder is refused (:class:`OutputRefused`), and so
  is a folder on the way below the output's folder that is a symbolic link: nothing is ever written through a link;
* a file that is not there is created; one that holds exactly the new content is left alone (``identical``);
* a file that a gen-robot command wrote there and nobody changed since is replaced (``update``): the record
  ``.xacrokit-outputs.json`` in the output's folder keeps the SHA-256 of each file written there;
* any other existing file is not ours: a conflict (:class:`OutputConflict`, exit 2), kept, and nothing at all is
  written, unless ``force`` (``overwrite``).

Every file is replaced atomically (a temporary file beside it, then ``os.replace``): a reader never sees half a file.
"""

from __future__ import annotations

import contextlib
import json
import os
import stat
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path, PurePosixPath

from ..errors import XacrokitError
from ..shared.input_files import CopiedFile
from .atomic import digest, file_digest, remove_leftover_temporaries, write_text_atomic
from .package_writer import FileAction

RECORD = ".xacrokit-outputs.json"
NOT_OURS = "it exists and was not written by gen-robot (or was changed since)"


@dataclass(frozen=True)
class OutputFile:
    """One file to write: ``relative`` is a POSIX path below the output's folder (``robot.xml``, ``meshes/a.obj``)."""

    relative: str
    content: str | bytes | CopiedFile  # (a CopiedFile is streamed from its source when written)


class OutputRefused(XacrokitError):
    """An output path that is never written: a symbolic link, a device, a FIFO, a socket, a folder."""


class OutputConflict(XacrokitError):
    """Existing files that a gen-robot command did not write there; nothing was written."""

    def __init__(self, folder: Path, conflicts: list[FileAction]):
        self.folder = folder
        self.conflicts = conflicts
        lines = [f"{folder / c.path}: {c.reason}; kept" for c in conflicts]
        lines.append("nothing was written: choose another output path, move the file away, or run again with --force")
        super().__init__("\n".join(lines))


def output_file(path: str | os.PathLike[str], content: str | bytes, *, force: bool = False) -> list[FileAction]:
    """Write one output file (see :func:`write_outputs`); its folder is the path's parent."""
    target = Path(path)
    if not str(path).strip() or target.name in ("", ".", ".."):
        raise OutputRefused(f"{str(path)!r}: not a file name to write")
    return write_outputs(target.parent, [OutputFile(target.name, content)], force=force)


def write_outputs(folder: Path, files: Sequence[OutputFile], *, force: bool = False) -> list[FileAction]:
    """Plan every file, then write the created, updated and overwritten ones atomically and record their digests.

    Raises:
        OutputRefused: a path (or a folder on its way below ``folder``) is a link, device, FIFO, socket or folder.
        OutputConflict: an existing file was not written by gen-robot, and ``force`` is off. Nothing is written.
        XacrokitError: the file system refused a write (the message names the file).
    """
    record = _read_record(folder)
    actions = [_plan(folder, item, record, force=force) for item in files]
    conflicts = [a for a in actions if a.action == "conflict"]
    if conflicts:
        raise OutputConflict(folder, conflicts)
    remove_leftover_temporaries(folder, [item.relative for item in files])
    digests = {item.relative: digest(item.content) for item in files}
    # first recorded with both digests, the file's last and this run's: a run killed among its writes leaves files
    # that are each one or the other, and the next run takes them over (as the package writer does)
    _write_record(folder, {**record, **{k: [*record.get(k, []), v] for k, v in digests.items()}})
    # copies first: a source that changed since it was read stops the run before the files that name it are written
    for item, action in sorted(
        zip(files, actions, strict=True), key=lambda pair: not isinstance(pair[0].content, CopiedFile)
    ):
        if action.action in ("create", "update", "overwrite"):
            try:
                write_text_atomic(folder / item.relative, item.content)
            except OSError as exc:
                raise XacrokitError(f"cannot write {folder / item.relative}: {exc.strerror or exc}") from None
    _write_record(folder, {**record, **{k: [v] for k, v in digests.items()}})
    return actions


def _plan(folder: Path, item: OutputFile, record: dict[str, list[str]], *, force: bool) -> FileAction:
    pure = PurePosixPath(item.relative)
    normal = bool(item.relative) and pure.as_posix() == item.relative and "\0" not in item.relative
    if not normal or pure.is_absolute() or ".." in pure.parts:
        raise OutputRefused(f"{item.relative!r}: not a path inside {folder}")
    for depth in range(1, len(pure.parts)):  # the folders below `folder` on the way: never a link
        _refuse_special(folder.joinpath(*pure.parts[:depth]), folder=True)
    target = folder / item.relative
    status = _refuse_special(target, folder=False)
    if status is None:
        return FileAction(item.relative, "create")
    content = item.content
    size = (
        content.size
        if isinstance(content, CopiedFile)
        else len(content.encode() if isinstance(content, str) else content)
    )
    try:
        held = file_digest(target)  # (read in pieces: an -o naming a large file of someone else's costs no memory)
    except OSError as exc:
        raise XacrokitError(f"cannot read {target}: {exc.strerror or exc}") from None
    if status.st_size == size and held == digest(content):
        return FileAction(item.relative, "identical")
    if held in record.get(item.relative, []):
        return FileAction(item.relative, "update")
    return FileAction(item.relative, "overwrite" if force else "conflict", NOT_OURS)


def _refuse_special(path: Path, *, folder: bool) -> os.stat_result | None:
    """The path's status (None when it is not there) when it is a plain file (or, ``folder``, a plain folder)."""
    try:
        status = os.lstat(path)
    except FileNotFoundError:
        return None
    except OSError as exc:
        raise OutputRefused(f"{path}: {exc.strerror or exc}") from None
    mode = status.st_mode
    if stat.S_ISLNK(mode):
        raise OutputRefused(f"{path}: it is a symbolic link; gen-robot never writes through one (give the real path)")
    if folder and not stat.S_ISDIR(mode):
        raise OutputRefused(f"{path}: it is not a folder")
    if not folder and stat.S_ISDIR(mode):
        raise OutputRefused(f"{path}: it is a folder; give a file name")
    if not folder and not stat.S_ISREG(mode):
        raise OutputRefused(f"{path}: it is a device, FIFO or socket, which gen-robot never writes (nor replaces)")
    return status


def _read_record(folder: Path) -> dict[str, list[str]]:
    """The record's digests per file; a record that is missing or cannot be read records nothing (a link or a
    special file in its place is refused: it is written at the end)."""
    _refuse_special(folder / RECORD, folder=False)
    try:
        files = json.loads((folder / RECORD).read_text(encoding="utf-8")).get("files", {})
    except (OSError, ValueError, AttributeError):
        return {}
    if not isinstance(files, dict):
        return {}
    return {str(k): [str(d) for d in v] for k, v in files.items() if isinstance(v, list)}


def _write_record(folder: Path, record: dict[str, list[str]]) -> None:
    text = json.dumps({"written_by": "gen-robot", "files": record}, indent=1, sort_keys=True) + "\n"
    with contextlib.suppress(OSError):  # (the outputs are written: a record that cannot be is only a later conflict)
        write_text_atomic(folder / RECORD, text)
