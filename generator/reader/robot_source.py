"""What the commands that read a robot share (graph, view, render): a URDF, xacro document, spec or scene read as URDF
text, with the packages its ``package://`` URIs may name (a spec's own meshes staged where its package will carry
them). ``packages.mesh_file`` resolves a mesh URI with them.

A URDF that uses a namespace prefix it never declares (``<limit drake:acceleration="..."/>``: check's U003; every
URDF consumer reads past it) is handed on with those names in a namespace of their own
(``urn:xacrokit:undeclared:PREFIX``), so that the XML readers behind these commands read it too."""

from __future__ import annotations

import contextlib
import math
import os
from collections.abc import Callable, Iterator, Mapping
from pathlib import Path
from typing import Any

from ..errors import XacrokitError

Packages = dict[str, str | os.PathLike[str]]


@contextlib.contextmanager
def robot_text(
    path: str | os.PathLike[str],
    mappings: Mapping[str, str] | None = None,
    package_paths: Mapping[str, str | os.PathLike[str]] | None = None,
    *,
    meshes: bool = True,
) -> Iterator[tuple[str, Packages]]:
    """(URDF text, packages) of the robot at ``path``, for the ``with`` block (a spec's staged meshes live that long;
    ``meshes=False`` for a reader of the text alone: nothing staged).

    Raises:
        XacrokitError: unreadable input, or name:=value arguments for input that is not xacro.
        SpecErrors: an invalid spec (located).
    """
    from ..check.checker import input_kind, load_urdf
    from ..shared.ros_packages import with_nearby_packages
    from ..write.atomic import staged_packages

    where = Path(path)
    kind = input_kind(where)
    if mappings and kind != "xacro":
        raise XacrokitError("name:=value arguments only apply to xacro input")
    packages = package_paths if kind == "spec" else with_nearby_packages(where, package_paths)
    carried: dict[str, Any] = {}
    text, _, _, _ = load_urdf(where, kind, mappings, packages, carried)
    text = declared(text, str(where) if kind == "urdf" else f"{where} (as expanded)")
    with staged_packages(carried if meshes else {}) as staged:
        yield text, {**staged, **(packages or {})}


def mesh_resolver(base: Path, packages: Mapping[str, str | os.PathLike[str]]) -> Callable[[str], str]:
    """The file of a mesh URI (``package://``, ``file://``, relative to ``base``), as a path; XacrokitError naming the
    mesh when its package is not known or the URI is malformed (whether the file is there is the caller's to say)."""
    from ..shared.ros_packages import mesh_file

    def resolve(filename: str) -> str:
        try:
            return str(mesh_file(filename, base, packages))
        except (LookupError, ValueError) as exc:
            raise XacrokitError(f"mesh {filename!r}: {exc}") from None

    return resolve


UNDECLARED = "urn:xacrokit:undeclared:"


def declared(text: str, where: str = "<robot>") -> str:
    """``text`` itself when it is well-formed XML with its namespaces declared and a ``<robot>`` root; when its only
    faults are namespace prefixes used without a declaration, the same document with each such name put in the
    namespace ``urn:xacrokit:undeclared:PREFIX``.

    Raises:
        XacrokitError: not well-formed XML (located: ``where:line``), or a root that is not ``<robot>``.
    """
    from lxml import etree

    from ..shared.xml_parse import parse_urdf

    parsed = parse_urdf(text)
    if parsed.root is None:
        raise XacrokitError(f"{parsed.where(where)}: {parsed.error}: not a URDF")
    if not parsed.undeclared:
        return text
    for element in parsed.root.iter(etree.Element):
        if ":" in element.tag and not element.tag.startswith("{"):
            prefix, _, local = element.tag.partition(":")
            element.tag = f"{{{UNDECLARED}{prefix}}}{local}"
        for key in [k for k in element.attrib if ":" in k and not k.startswith("{")]:
            prefix, _, local = key.partition(":")
            element.set(f"{{{UNDECLARED}{prefix}}}{local}", element.attrib.pop(key))
    return str(etree.tostring(parsed.root, encoding="unicode"))


def urdf_floats(text: str | None, count: int, default: float = 0.0, *, where: str = "") -> list[float]:
    """``count`` finite numbers from an attribute (``default`` each when it is absent); XacrokitError otherwise,
    saying ``where``."""
    if text is None:
        return [default] * count
    try:
        values = [float(v) for v in text.split()]
    except ValueError:
        values = []
    if len(values) != count or not all(math.isfinite(v) for v in values):
        raise XacrokitError(f"{where + ': ' if where else ''}{text!r} is not {count} finite number(s)")
    return values
