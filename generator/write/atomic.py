"""Atomic file writes: a reader never sees a half-written file, and a failed write leaves the old file in place."""

from __future__ import annotations

import contextlib
import errno
import hashlib
import os
import re
import tempfile
from collections.abc import Iterable, Iterator, Mapping
from pathlib import Path
from typing import Any, BinaryIO

from ..shared.input_files import PIECE, CopiedFile, InputError, copied_pieces

TEMPORARY = re.compile(r"\..+\.[A-Za-z0-9_]{8}\.tmp")  # what mkstemp names ours: .NAME.XXXXXXXX.tmp


def write_text_atomic(path: Path, text: str | bytes | CopiedFile) -> None:
    """Write ``text`` (UTF-8; bytes as they are; a :class:`CopiedFile` streamed from its source) to ``path`` through
    a temporary file in the same folder and ``os.replace``; the file gets the permissions a plain ``open`` would give
    (0644 under umask 022: mkstemp makes it 0600).

    Raises:
        OSError: the write failed, or a copied file is no longer what was checked (InputError): nothing replaced.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        os.fchmod(fd, 0o666 & ~_umask())
        if isinstance(text, CopiedFile):
            with os.fdopen(fd, "wb") as binary:
                _stream(text, binary)
        elif isinstance(text, bytes):
            with os.fdopen(fd, "wb") as binary:
                binary.write(text)
        else:
            with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as handle:
                handle.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


@contextlib.contextmanager
def staged_packages(files: Mapping[str, Iterable[Any]]) -> Iterator[dict[str, Path]]:
    """Package folders holding ``files`` (package name -> files with ``path`` and ``content``) in a scratch folder for
    the ``with`` block: where ``package://`` URIs of a package not yet written resolve (checking a spec's URDF)."""
    if not files:
        yield {}
        return
    with tempfile.TemporaryDirectory(prefix=STAGED_PREFIX) as scratch:
        found: dict[str, Path] = {}
        for package, items in files.items():
            found[package] = root = Path(scratch, package)
            for item in items:
                write_text_atomic(root / item.path, item.content)
        yield found


STAGED_PREFIX = "xacrokit-staged-"


def is_staged(folder: Path) -> bool:
    """Whether ``folder`` is a package :func:`staged_packages` made (gone after its ``with`` block: a file of it to
    copy later must be read while it lasts)."""
    parent = Path(os.path.realpath(folder)).parent  # (both sides resolved: /tmp may be a link, as on macOS)
    return parent.name.startswith(STAGED_PREFIX) and parent.parent == Path(os.path.realpath(tempfile.gettempdir()))


def _umask() -> int:
    mask = os.umask(0o022)  # (the only way to read it is to set it: put back at once, read afresh on each write)
    os.umask(mask)
    return mask


def remove_leftover_temporaries(root: Path, paths: Iterable[str]) -> list[Path]:
    """Delete the temporary files :func:`write_text_atomic` left for the files ``paths`` (relative to ``root``) when a
    run was killed mid-write: ``.NAME.XXXXXXXX.tmp`` beside each, mkstemp's names only, nothing else and nowhere else.
    Returns what was removed. (Each folder is listed once, its names matched as text: a glob per file compiled a
    pattern each, a sixth of generating the UR5 example under a profiler.)"""
    names_in: dict[Path, set[str]] = {}
    for relative in paths:
        target = root / relative
        names_in.setdefault(target.parent, set()).add(target.name)
    removed: list[Path] = []
    for folder, names in names_in.items():
        try:
            with os.scandir(folder) as listing:
                entries = [entry.name for entry in listing]
        except OSError:  # (no folder, or one that cannot be read: nothing of ours to remove there)
            continue
        for entry in sorted(entries):
            if not (TEMPORARY.fullmatch(entry) and entry[1:].rsplit(".", 2)[0] in names):
                continue
            candidate = folder / entry
            if candidate.is_file() and not candidate.is_symlink():
                with contextlib.suppress(OSError):
                    candidate.unlink()
                    removed.append(candidate)
    return removed


def _stream(copied: CopiedFile, out: BinaryIO) -> None:
    """Copy ``copied`` into ``out`` a piece at a time; InputError when its SHA-256 is not the one checked."""
    hashed = hashlib.sha256()
    for piece in copied_pieces(copied):
        hashed.update(piece)
        out.write(piece)
    if hashed.hexdigest() != copied.sha256:
        raise InputError(errno.ESTALE, f"{copied.root / copied.relative} changed after it was checked; run again")


def digest(content: str | bytes | CopiedFile) -> str:
    """SHA-256 of a file's content (text as UTF-8; a copied file's as checked): what the package manifest and the
    outputs record hold."""
    if isinstance(content, CopiedFile):
        return content.sha256
    return hashlib.sha256(content.encode("utf-8") if isinstance(content, str) else content).hexdigest()


def file_digest(path: Path) -> str:
    """:func:`digest` of a file's content, read in pieces (a large file costs no memory)."""
    hashed = hashlib.sha256()
    with path.open("rb") as handle:
        for piece in iter(lambda: handle.read(PIECE), b""):
            hashed.update(piece)
    return hashed.hexdigest()
