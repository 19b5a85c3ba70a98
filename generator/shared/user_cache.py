"""The user's cache folder: work one run did that the next can take instead of doing it again.

Three things are kept there, each in a folder of its own named with xacrokit's version (a new release never reads
an old release's files):

- ``templates-VERSION``: jinja2's compiled templates (its ``FileSystemBytecodeCache``: each file is written to a
  temporary name and renamed, so two runs sharing the folder never read half a file; a template whose text changed
  is compiled again, by its checksum);
- ``collisions-VERSION``: the collision matrix of a robot's SRDF (``moveit.moveit_package``), a JSON file named by
  the digest of everything the sampling reads;
- ``meshes-VERSION``: what check's geometry rules take from a mesh file (its hull, its triangle count, the solid it
  encloses: ``check.kept_meshes``), a JSON file named by the digest of the file's bytes.

Where: ``$XACROKIT_CACHE`` if set, else ``$XDG_CACHE_HOME/xacrokit``, else ``~/.cache/xacrokit``.
``XACROKIT_CACHE=off`` turns the cache off. The folder is made private (mode 0700); a folder that is not the user's
own, that others can write to, or that cannot be made, is not used: the run then does all the work itself, with the
same results (compiled templates are code, so a folder someone else can write to would let them run code as you).
Deleting the folder at any time is safe. Each key also holds :func:`source_stamp` of the code that does the work
(and of the libraries it calls), so that an edited module is never answered from its old results.
"""

from __future__ import annotations

import contextlib
import functools
import importlib.util
import os
import stat
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

OFF = "off"
T = TypeVar("T")


def cache_root() -> Path | None:
    """The cache folder, or None when it is turned off."""
    chosen = os.environ.get("XACROKIT_CACHE")
    if chosen is not None:
        return None if chosen.strip().lower() in (OFF, "") else Path(chosen)
    xdg = os.environ.get("XDG_CACHE_HOME")
    base = Path(xdg) if xdg and os.path.isabs(xdg) else Path.home() / ".cache"
    return base / "xacrokit"


def _private(folder: Path) -> bool:
    """Whether ``folder`` is a real folder of this user that nobody else can write to."""
    try:
        info = os.lstat(folder)
    except OSError:
        return False
    if not stat.S_ISDIR(info.st_mode):
        return False
    if hasattr(os, "getuid") and info.st_uid != os.getuid():
        return False
    return not info.st_mode & (stat.S_IWGRP | stat.S_IWOTH)


def cache_folder(kind: str, version: str) -> Path | None:
    """The folder ``kind-VERSION`` (``version``: xacrokit's) inside the cache folder, made if missing, or None when
    the cache is off or the folder cannot be used safely (see the module's docstring)."""
    root = cache_root()
    if root is None:
        return None
    folder = root / f"{kind}-{version}"
    for path in (root, folder):
        try:
            path.mkdir(mode=0o700, exist_ok=True)
        except OSError:
            return None
        if not _private(path):
            return None
    return folder


@functools.cache
def source_stamp(*modules: str) -> str:
    """Where each module is installed, with its file's size and time, found without importing it: a cache key that
    holds it changes when the code that does the work is installed anew or edited (an editable install), so that a
    result of older code is never taken."""
    stamps = []
    for module in modules:
        spec = importlib.util.find_spec(module)
        origin = None if spec is None else spec.origin
        try:
            info = os.stat(origin) if origin else None
        except OSError:
            info = None
        stamps.append(f"{origin} {info.st_size} {info.st_mtime_ns}" if info else str(origin))
    return "; ".join(stamps)


def kept(
    kind: str, version: str, name: str, work_out: Callable[[], T], write: Callable[[T], str], read: Callable[[str], T]
) -> T:
    """``work_out()``'s result, kept as the file ``name`` (its text ``write(result)``) in the folder ``kind-VERSION``
    (``version``: xacrokit's): a run that finds the file takes ``read(text)`` instead. A file ``read`` refuses (it
    raises ValueError: damaged, or not what was written) is worked out again and written anew; with the cache off or
    unusable, the work is simply done."""
    folder = cache_folder(kind, version)
    if folder is None:
        return work_out()
    text = read_cached(folder, name)
    if text is not None:
        with contextlib.suppress(ValueError):
            return read(text)
    result = work_out()
    write_cached(folder, name, write(result))
    return result


def read_cached(folder: Path, name: str) -> str | None:
    """The text of the cached file ``name``, or None when there is none (or it cannot be read)."""
    try:
        return (folder / name).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return None


def write_cached(folder: Path, name: str, text: str) -> None:
    """Write ``text`` as the cached file ``name``: to a temporary file first, then renamed over it, so that a run
    reading it meanwhile sees the old file or the new one, never part of one (``write.atomic`` does the same for
    packages, with their permissions; this layer cannot import it). A cache that cannot be written is left as it is:
    the work is simply done again next time."""
    try:
        descriptor, temporary = tempfile.mkstemp(dir=folder, prefix=f".{name}.", suffix=".tmp")
    except OSError:
        return
    try:
        with os.fdopen(descriptor, "w", encoding="utf-8") as handle:
            handle.write(text)
        os.replace(temporary, folder / name)
    except OSError:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
