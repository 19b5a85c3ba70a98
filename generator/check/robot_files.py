"""Which files ``gen-robot check`` takes: the paths it is given, and the robots in the folders among them.

In a folder (searched recursively, in name order, without following symbolic links or entering folders whose name
starts with a dot) a robot file is

- a URDF: ``*.urdf``;
- a xacro entry: a ``*.xacro`` (``*.urdf.xacro`` too) that makes something at its top level (an element other than
  ``xacro:macro``, ``xacro:property``, ``xacro:arg`` and ``xacro:include``), or defines no macro and includes the
  files that make its parts, and that no xacro document of the folder includes (by its file name); a file that
  defines macros and makes nothing is a library, and an included one a part, each checked through the entries that
  include it;
- a spec: ``*.yaml``/``*.yml`` whose top level has ``robot`` and ``links`` (a robot spec) or ``scene`` and
  ``instances`` (a scene spec); other YAML (controllers, launch parameters, sizing files) is not a robot.

The search reads no file through a symbolic link: a link to a file (``vendor.urdf -> ~/secret.urdf``), to a link,
or to nothing is passed over, and so is a FIFO, a socket or a device with a robot's file name (reading one could
block). Each passed over file with a robot's suffix is said (``skipped``: the file and why; by default a warning of
the ``xacrokit.check`` logger, which Python prints on stderr when the program sets up no logging), never its content.
A link named on the command line is read (the user named it).

A file named on the command line is checked whatever it is, unless ``robots_only`` (what the pre-commit hook passes:
it names every changed ``.urdf``, ``.xacro`` and YAML file). ``exclude`` globs leave out the files found in folders
whose path below the folder, or one of its folders' names or its own name, matches one (``build``, ``*_macro.xacro``,
``legacy/*.urdf``).
"""

from __future__ import annotations

import fnmatch
import logging
import os
import re
import stat
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path, PurePosixPath
from typing import Any

from lxml import etree

from ..errors import XacrokitError
from ..shared.terminal_text import printable
from ..shared.xml_parse import parser

HEAD_BYTES = 1 << 20  # bytes of a YAML or xacro file read to tell whether it is a robot (its top level comes first)
_LIBRARY = {"macro", "property", "arg", "include"}  # xacro's top-level elements that make nothing by themselves
# (xacro knows its elements by the prefix xacro:, whichever namespace URI it is bound to: both ros.org forms are used)
_SPEC_KEYS = re.compile(r"^(robot|links|scene|instances)\s*:", re.MULTILINE)
_ROBOT_SUFFIXES = (".urdf", ".xacro", ".yaml", ".yml")  # (a file the search would read to tell whether it is a robot)
Skipped = Callable[[Path, str], None]  # told a file the search passes over, and why


def _log_skipped(path: Path, why: str) -> None:
    logging.getLogger("xacrokit.check").warning("note: %s: skipped: %s", printable(path), why)


def robot_files(
    paths: Sequence[str | os.PathLike[str]],
    *,
    exclude: Sequence[str] = (),
    robots_only: bool = False,
    skipped: Skipped | None = None,
) -> list[Path]:
    """The files to check, each once, in the order given (a folder's in name order); ``skipped`` is told each file
    with a robot's suffix that a folder's search passes over (a symbolic link, a FIFO), and why.

    Raises:
        XacrokitError: a path that does not exist (a FIFO or a device named is taken: check says it cannot read it).
    """
    found: dict[Path, None] = {}
    for given in paths:
        path = Path(given)
        if path.is_dir():
            found.update(dict.fromkeys(_search(path, exclude, skipped or _log_skipped)))
        elif os.path.lexists(path):  # (a file; or a FIFO, a device, a broken link: check says why it cannot read it)
            if not robots_only or is_robot_file(path):
                found[path] = None
        else:
            raise XacrokitError(
                f"{printable(path)}: no such file or folder; give a URDF, xacro document, spec or a folder of them"
                + _hint(str(given))
            )
    return list(found)


def _hint(given: str) -> str:
    if given.startswith("-"):  # (after --, as the pre-commit hook's entry ends, every word is a path)
        return (
            "; after -- every word is a path: give options before it (the pre-commit hook's entry ends with --: "
            "put options in the hook's entry, before the --, not in its args)"
        )
    return " (a xacro argument is written name:=value)" if "=" in given else ""


def _search(folder: Path, exclude: Sequence[str], skipped: Skipped) -> Iterable[Path]:
    found: list[Path] = []
    included: set[str] = set()  # (the file names xacro documents of the folder include: parts, not entries)

    def unread(exc: OSError) -> None:  # (a folder below that cannot be listed: said, and the search goes on)
        skipped(Path(exc.filename or folder), f"a folder that cannot be searched ({exc.strerror or exc})")

    # (symbolic links to folders are not followed: no loop, no escape)
    for top, folders, files in os.walk(folder, onerror=unread):
        below = PurePosixPath(Path(top).relative_to(folder).as_posix())
        folders[:] = sorted(f for f in folders if not f.startswith(".") and not _excluded(below / f, exclude))
        for name in sorted(files):
            path = Path(top, name)
            if _excluded(below / name, exclude) or not _plain(path, skipped):
                continue
            root = _xacro_root(path) if name.lower().endswith(".xacro") else None  # (each xacro file read once)
            if root is not None:
                included.update(_included_names(root))
            if _is_robot(path, root):
                found.append(path)
    kept = [path for path in found if not path.name.lower().endswith(".xacro") or path.name not in included]
    return sorted(kept, key=lambda path: path.relative_to(folder).parts)  # (name order, folders among files)


def _plain(path: Path, skipped: Skipped) -> bool:
    """Whether the search may read a file it found: a plain file, not a symbolic link (whatever it points at: a file
    outside the folder, another link, nothing) nor a FIFO, socket or device, nor YAML it cannot read. A file with a
    robot's suffix that it may not read is said to ``skipped``."""
    try:
        mode = path.lstat().st_mode  # (lstat: the link itself, never what it points at)
    except OSError as exc:
        why = f"cannot be looked at ({exc.strerror or exc})"
    else:
        if stat.S_ISREG(mode) and (os.access(path, os.R_OK) or not path.name.lower().endswith((".yaml", ".yml"))):
            return True  # (a URDF or xacro file that cannot be read is checked: check says why, exit 2)
        if stat.S_ISREG(mode):  # (YAML that cannot be read may be a robot spec or not: said, not failed)
            why = "it cannot be read (permission denied), so whether it is a robot spec is unknown"
        elif stat.S_ISLNK(mode):
            why = "a symbolic link: a folder's search follows none (name the file it points at to check it)"
        else:
            why = "not a plain file (a FIFO, a socket or a device): never read"
    if path.name.lower().endswith(_ROBOT_SUFFIXES):
        skipped(path, why)
    return False


def _excluded(relative: PurePosixPath, exclude: Sequence[str]) -> bool:
    text = relative.as_posix()
    return any(fnmatch.fnmatchcase(text, glob) or fnmatch.fnmatchcase(relative.name, glob) for glob in exclude)


def is_robot_file(path: Path) -> bool:
    """Whether ``path`` is a robot ``gen-robot check`` takes from a folder (see the module's notes; that no other
    xacro document of the folder includes it is asked by the search)."""
    return _is_robot(path, _xacro_root(path) if path.name.lower().endswith(".xacro") else None)


def _is_robot(path: Path, root: Any) -> bool:
    """:func:`is_robot_file`, a xacro file's ``root`` already read (None: it does not read as XML)."""
    name = path.name.lower()
    if name.endswith(".urdf"):
        return True
    if name.endswith(".xacro"):
        return _makes_something(root)
    if name.endswith((".yaml", ".yml")):
        keys = {m.group(1) for m in _SPEC_KEYS.finditer(_head(path))}
        return {"robot", "links"} <= keys or {"scene", "instances"} <= keys
    return False


def _head(path: Path) -> str:
    if not path.is_file():
        return ""  # (a FIFO, a device: never opened, it could block; check says why it cannot read it)
    try:
        with path.open("rb") as stream:
            return stream.read(HEAD_BYTES).decode("utf-8", "replace")
    except OSError:
        return ""


def _xacro_root(path: Path) -> Any:
    """The root element of a xacro file (None when it does not read as XML)."""
    try:
        return etree.fromstring(_head(path).encode("utf-8"), parser(recover=False))
    except etree.XMLSyntaxError:
        return None


def _makes_something(root: Any) -> bool:
    """Whether a xacro document is an entry: it makes something at its top level (an element other than xacro's
    macro, property, arg and include), or it defines no macro and includes the files that make the robot's parts. A
    file defining macros and making nothing is a library, named or not (a camera's ``_d435.urdf.xacro``). One that
    does not read as XML is taken: check says why."""
    if root is None:
        return True
    tops = [etree.QName(child).localname for child in root if isinstance(child.tag, str) and child.prefix == "xacro"]
    if any(
        isinstance(child.tag, str) and (child.prefix != "xacro" or etree.QName(child).localname not in _LIBRARY)
        for child in root
    ):
        return True
    return "macro" not in tops and ("include" in tops or bool(root.get("name")))


def _included_names(root: Any) -> set[str]:
    """The file names a xacro document (its root element) includes (``xacro:include filename``'s last part)."""
    return {
        PurePosixPath(element.get("filename", "")).name
        for element in root.iter()
        if isinstance(element.tag, str) and element.prefix == "xacro" and etree.QName(element).localname == "include"
    }
