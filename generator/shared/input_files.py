"""Input files read safely: a regular file of bounded size, never a device, FIFO or folder."""

from __future__ import annotations

import contextlib
import errno
import os
import stat
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path, PurePosixPath
from typing import BinaryIO


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


class Linked(OSError):
    """The path goes through a symbolic link, or does not end at a plain file."""


def open_folders(root: Path, parts: tuple[str, ...]) -> list[int]:
    """Descriptors of root and of each folder on the way to ``parts[-1]``, never following a symbolic link below
    root. The caller closes them.

    Raises:
        Linked: a folder on the way is a symbolic link (or not a folder).
        OSError: a folder on the way cannot be opened.
    """
    fds = [os.open(root, os.O_RDONLY | os.O_DIRECTORY)]
    try:
        for part in parts[:-1]:
            try:
                fds.append(os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW, dir_fd=fds[-1]))
            except OSError as exc:
                if exc.errno in (errno.ELOOP, errno.ENOTDIR):
                    raise Linked(exc.errno, "it is reached through a symbolic link") from exc
                raise
    except BaseException:
        for fd in fds:
            os.close(fd)
        raise
    return fds


@contextlib.contextmanager
def open_below(root: Path, relative: str) -> Iterator[tuple[BinaryIO, os.stat_result]]:
    """The plain file ``relative`` (a POSIX path) below ``root``, open for reading, and its status; opened without
    following any symbolic link below root, and without blocking on a FIFO.

    Raises:
        Linked: the file or a folder on the way is a symbolic link, or the file is not a plain file.
        OSError: it cannot be opened.
    """
    parts = PurePosixPath(relative).parts
    fds = open_folders(root, parts)
    try:
        try:
            fd = os.open(parts[-1], os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK, dir_fd=fds[-1])
        except OSError as exc:
            if exc.errno == errno.ELOOP:
                raise Linked(exc.errno, "it is a symbolic link") from exc
            raise
        with os.fdopen(fd, "rb") as handle:
            status = os.fstat(handle.fileno())
            if not stat.S_ISREG(status.st_mode):
                raise Linked(errno.EISDIR, "it is not a plain file")
            yield handle, status
    finally:
        for fd in fds:
            os.close(fd)


def read_below(root: Path, relative: str, limit: int | None = None) -> tuple[bytes, tuple[int, int]]:
    """The bytes and (device, inode) of the file ``relative`` (a POSIX path) below ``root``, read without following
    any symbolic link below root; at most ``limit`` bytes (a larger file is refused before it is read).

    Raises:
        Linked: the file or a folder on the way is a symbolic link, or the file is not a plain file.
        InputError: the file is larger than ``limit``.
        OSError: it cannot be read.
    """
    with open_below(root, relative) as (handle, status):
        if limit is not None and status.st_size > limit:
            raise InputError(errno.EFBIG, f"it is larger than {limit:,} bytes")
        data = handle.read() if limit is None else handle.read(limit + 1)
        if limit is not None and len(data) > limit:
            raise InputError(errno.EFBIG, f"it is larger than {limit:,} bytes")
        return data, (status.st_dev, status.st_ino)


@dataclass(frozen=True)
class CopiedFile:
    """A file an output copies as it is, streamed at write time (never held in memory): ``relative`` below ``root``,
    read again there without following a link, and written only if it is still the file that was checked (its
    device and inode, its size and its SHA-256)."""

    root: Path
    relative: str
    identity: tuple[int, int]
    size: int
    sha256: str


PIECE = 1 << 20  # bytes read at a time when a file is copied or hashed


def copied_pieces(copied: CopiedFile) -> Iterator[bytes]:
    """The bytes of ``copied``, a piece at a time, as :func:`open_below` reads them.

    Raises:
        InputError: it is no longer the file that was checked (another file, another size).
        Linked, OSError: as :func:`open_below`.
    """
    with open_below(copied.root, copied.relative) as (handle, status):
        if (status.st_dev, status.st_ino) != copied.identity or status.st_size != copied.size:
            raise InputError(errno.ESTALE, "it changed after it was checked; run again")
        left = copied.size + 1  # (a file that grows while it is copied: at most one byte past the size checked)
        while left > 0 and (piece := handle.read(min(PIECE, left))):
            left -= len(piece)
            yield piece
