"""Where ROS packages are, without ROS: ``$(find PKG)`` and ``package://PKG`` resolved to folders (what xacro
expansion and check's mesh rule both need; this module does not import xacro, so checking a URDF does not load it)."""

from __future__ import annotations

import contextlib
import functools
import itertools
import os
import sys
from collections.abc import Callable, Mapping
from pathlib import Path
from urllib.parse import unquote, urlparse

from .package_data import package_share_dir

PACKAGE_NAME = "xacrokit"


def _package_name(folder: Path) -> str | None:
    """The <name> in ``folder``/package.xml, or None when there is none (or it is unreadable)."""
    from lxml import etree  # (heavy: lxml)

    from .xml_parse import parser  # (heavy: lxml)

    try:  # (a file of someone else's: the hardened parse)
        name = etree.parse(str(folder / "package.xml"), parser()).getroot().findtext("name")
    except (OSError, etree.XMLSyntaxError):
        return None
    return name.strip() if name and name.strip() else None


def nearby_packages(path: str | os.PathLike[str]) -> dict[str, Path]:
    """The ROS packages a file most likely refers to: the package it lies in (the nearest folder above it with a
    package.xml) and that package's siblings, as in a workspace's ``src/``. Name -> folder."""
    folder = Path(path).resolve().parent
    own = next((f for f in (folder, *folder.parents) if (f / "package.xml").is_file()), None)
    if own is None:
        return {}
    found: dict[str, Path] = {}
    siblings: list[Path] = []
    with contextlib.suppress(OSError):
        siblings = sorted(itertools.islice(own.parent.iterdir(), 1000))  # (a workspace's src/, not a huge folder)
    for sibling in siblings:
        with contextlib.suppress(OSError):  # one unreadable folder does not hide the others
            if sibling != own and (sibling / "package.xml").is_file() and (name := _package_name(sibling)):
                found.setdefault(name, sibling)
    if name := _package_name(own):
        found[name] = own  # its own package wins over a sibling of the same name
    return found


def with_nearby_packages(
    path: str | os.PathLike[str], package_paths: Mapping[str, str | os.PathLike[str]] | None = None
) -> dict[str, str | os.PathLike[str]]:
    """``package_paths`` plus the :func:`nearby_packages` of ``path`` that :func:`find_package` finds nowhere else
    (so a sourced workspace or an explicit folder still wins, as ``$(find)`` in :func:`expand_file` does)."""
    extra: dict[str, str | os.PathLike[str]] = {}
    for name, folder in nearby_packages(path).items():
        try:
            find_package(name, package_paths)
        except LookupError:
            extra[name] = folder
    return {**extra, **(package_paths or {})}


FOUND_KEPT = 256  # packages found, remembered in this process (a check asks for one per mesh: 0.3 ms a time)
_FOUND: dict[tuple[object, ...], str] = {}


def find_package(name: str, package_paths: Mapping[str, str | os.PathLike[str]] | None = None) -> str:
    """Resolve ``$(find name)`` the way ROS would, without needing ROS.

    A package found is remembered in this process, for the same name, given folder, working folder, AMENT_PREFIX_PATH
    and sys.path, while its folder is there (check asks for it for every mesh of a robot, TIAGo dual's 85 times).

    Args:
        name: the package name.
        package_paths: explicit package folders, consulted first.

    Returns:
        The package's share folder, as a string (xacro splices it into a path).

    Raises:
        ExpandError-compatible ``LookupError`` when the package is nowhere to be found.
    """
    given = os.fspath(package_paths[name]) if package_paths and name in package_paths else None
    try:
        here = os.getcwd()
    except OSError:  # (a working folder since removed: found afresh, as before it was remembered)
        return _find_package(name, package_paths)
    key = (name, given, here, os.environ.get("AMENT_PREFIX_PATH", ""), tuple(sys.path))
    found = _FOUND.get(key)
    if found is not None and os.path.isdir(found):
        return found
    found = _find_package(name, package_paths)
    if len(_FOUND) >= FOUND_KEPT:
        _FOUND.clear()
    _FOUND[key] = found
    return found


def _find_package(name: str, package_paths: Mapping[str, str | os.PathLike[str]] | None) -> str:
    if package_paths and name in package_paths:
        return str(Path(package_paths[name]).resolve())
    if name == PACKAGE_NAME:
        return str(package_share_dir())
    ament = _ament_index()
    if ament is not None:
        get_package_share_directory, not_found = ament
        with contextlib.suppress(not_found):
            return str(get_package_share_directory(name))
    # ROS prefixes, then the ament-style prefix that pip's cmeel packages (pinocchio's family) install into
    prefixes = [p for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
    prefixes += [str(Path(entry, "cmeel.prefix")) for entry in sys.path if entry]
    for prefix in prefixes:
        candidate = Path(prefix, "share", name)
        if (candidate / "package.xml").is_file():
            return str(candidate)
    raise LookupError(
        f"$(find {name}): package {name!r} is not known here; pass its folder with --package {name}=PATH "
        f"(or package_paths={{{name!r}: PATH}} in Python), or source a ROS workspace that has it"
    )


@functools.cache
def _ament_index() -> tuple[Callable[[str], str], type[Exception]] | None:
    """ROS's package index when a ROS workspace is sourced (imported once: a failed import costs a millisecond, and
    check asks for every mesh's package)."""
    try:
        # (heavy: ament_index_python)
        from ament_index_python.packages import (  # type: ignore[import-not-found]
            PackageNotFoundError,
            get_package_share_directory,
        )
    except ImportError:
        return None
    return get_package_share_directory, PackageNotFoundError


def mesh_file(filename: str, base: Path, package_paths: Mapping[str, str | os.PathLike[str]] | None = None) -> Path:
    """The file a mesh names: ``package://PKG/path`` (through ``package_paths``, then as :func:`find_package`
    looks), ``file:///abs/path`` (percent-decoded), an absolute path, or a path relative to ``base``.

    Raises:
        LookupError: the package is not known here (the message says how to make it known).
        ValueError: another URI scheme.
    """

    if filename.startswith("package://"):
        package, _, rest = filename[len("package://") :].partition("/")
        return Path(find_package(package, package_paths), rest)
    if filename.startswith("file://"):
        return Path(unquote(urlparse(filename).path))
    if "://" in filename:
        raise ValueError(f"{filename!r}: unknown URI scheme; use a path, package:// or file://")
    return base / filename
