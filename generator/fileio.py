"""Atomic file writes: a reader never sees a half-written file, and a failed write leaves the old file in place."""

from __future__ import annotations

import contextlib
import errno
import glob
import os
import re
import stat
import tempfile
from collections.abc import Iterable, Iterator, Mapping
from pathlib import Path
from typing import Any

TEMPORARY = re.compile(r"\..+\.[A-Za-z0-9_]{8}\.tmp")  # what mkstemp names ours: .NAME.XXXXXXXX.tmp


def write_text_atomic(path: Path, text: str | bytes) -> None:
    """Write ``text`` (UTF-8; bytes as they are) to ``path`` through a temporary file in the same folder and
    ``os.replace``; the file gets the permissions a plain ``open`` would give (0644 under umask 022: mkstemp makes it
    0600)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        os.fchmod(fd, 0o666 & ~_umask())
        if isinstance(text, bytes):
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
    with tempfile.TemporaryDirectory(prefix="xacrokit-staged-") as scratch:
        found: dict[str, Path] = {}
        for package, items in files.items():
            found[package] = root = Path(scratch, package)
            for item in items:
                write_text_atomic(root / item.path, item.content)
        yield found


def _umask() -> int:
    mask = os.umask(0o022)  # (the only way to read it is to set it: put back at once, read afresh on each write)
    os.umask(mask)
    return mask


def remove_leftover_temporaries(root: Path, paths: Iterable[str]) -> list[Path]:
    """Delete the temporary files :func:`write_text_atomic` left for the files ``paths`` (relative to ``root``) when a
    run was killed mid-write: ``.NAME.XXXXXXXX.tmp`` beside each, mkstemp's names only, nothing else and nowhere else.
    Returns what was removed."""
    removed: list[Path] = []
    for relative in paths:
        target = root / relative
        if not target.parent.is_dir():
            continue
        for candidate in target.parent.glob(f".{glob.escape(target.name)}.*.tmp"):
            if TEMPORARY.fullmatch(candidate.name) and candidate.is_file() and not candidate.is_symlink():
                with contextlib.suppress(OSError):
                    candidate.unlink()
                    removed.append(candidate)
    return removed


class InputError(OSError):
    """An input file that cannot be read as one: missing, a folder, a device or FIFO, a link loop, too large."""


def read_input(path: str | os.PathLike[str], limit: int) -> bytes:
    """The bytes of a regular file of at most ``limit`` bytes. A device (``/dev/zero``), a FIFO or a folder is
    refused before anything is read (a FIFO's open would block), and at most ``limit + 1`` bytes are ever read (a
    file that grows while it is read).

    Raises:
        InputError: with ``strerror`` saying why, in words for the user.
    """
    require_regular_file(path, limit)
    try:
        with open(path, "rb") as handle:
            data = handle.read(limit + 1)
    except OSError as exc:
        raise InputError(exc.errno or 0, exc.strerror or str(exc)) from None
    if len(data) > limit:
        raise InputError(errno.EFBIG, f"it is larger than {limit:,} bytes")
    return data


def require_regular_file(path: str | os.PathLike[str], limit: int) -> None:
    """Refuse (:class:`InputError`) what :func:`read_input` refuses that a look at the file can tell, reading
    nothing: a missing file, a folder, a device, a FIFO, a link loop, a file over ``limit`` bytes."""
    try:
        status = os.stat(path)
    except FileNotFoundError:
        raise InputError(errno.ENOENT, os.strerror(errno.ENOENT)) from None
    except OSError as exc:
        why = "a loop of symbolic links" if exc.errno == errno.ELOOP else exc.strerror or str(exc)
        raise InputError(exc.errno or 0, why) from None
    except ValueError:  # (a NUL in the path)
        raise InputError(errno.EINVAL, "the path holds a NUL character") from None
    if stat.S_ISDIR(status.st_mode):
        raise InputError(errno.EISDIR, "it is a folder, not a file")
    if not stat.S_ISREG(status.st_mode):
        raise InputError(errno.EINVAL, "it is not a regular file (a device, a FIFO or a socket)")
    if status.st_size > limit:
        raise InputError(errno.EFBIG, f"it is larger than {limit:,} bytes")
