"""A robot's file to URDF text: a URDF read, a xacro document expanded, a spec generated in memory
(:func:`read_source`, with what it came from: a spec's model, lines and warnings and the files its package will
carry). :mod:`xacrokit.reader.read_robot` makes the read robot every command takes from it.

A URDF that uses a namespace prefix it never declares (``<limit drake:acceleration="..."/>``: check's U003; every
URDF consumer reads past it) is handed on with those names in a namespace of their own
(``urn:xacrokit:undeclared:PREFIX``), so that the XML readers behind these commands read it too (:func:`declared`)."""

from __future__ import annotations

import math
import os
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import SpecError, XacrokitError
from ..expansion.expression_guard import trusting
from ..shared.input_files import read_input, require_regular_file
from ..shared.ros_packages import with_nearby_packages
from . import InputKind
from .robot_input import RobotInput

if TYPE_CHECKING:
    from ..model import Robot
    from ..validate import Spec

MAX_URDF_BYTES = 256 * 1024 * 1024  # a URDF with meshes inlined runs to megabytes; 256 MiB is far beyond any robot


def input_kind(path: Path) -> InputKind:
    """spec, xacro or urdf: by the file's suffix, or for another suffix by its first 4 KiB (XML starts with '<'; a
    xacro document declares the xacro namespace or uses a xacro: element)."""
    name = path.name.lower()
    if name.endswith((".yaml", ".yml")):
        return "spec"
    if name.endswith(".xacro"):
        return "xacro"
    if name.endswith((".urdf", ".xml")):
        return "urdf"
    if not path.is_file():
        return "urdf"  # (a FIFO or a device is never opened here, it could block: reading it says why it cannot be)
    try:
        with path.open("rb") as file:
            head = file.read(4096)
    except OSError:
        return "urdf"  # (reading it again says why it cannot be read)
    text = head.decode("utf-8", "replace").lstrip("\ufeff \t\r\n")
    if not text.startswith("<"):
        return "spec"
    return "xacro" if re.search(r"xmlns:xacro\s*=|<xacro:", text) else "urdf"


@dataclass(frozen=True)
class RobotSource:
    """A robot read as URDF text, and where it came from: the input's kind, the packages its URIs may name; for a
    spec, its robot model (a scene's: None), the spec line of each link and joint, its warnings and the files its
    package will carry (by package)."""

    text: str
    kind: InputKind
    packages: Mapping[str, str | os.PathLike[str]] | None = None
    robot: Robot | None = None
    lines: dict[tuple[str, str], tuple[int, int]] | None = None  # (kind, name) -> (line, column) in the spec
    warnings: tuple[SpecError, ...] = ()
    carried: dict[str, Any] = field(default_factory=dict)
    validated: Spec | None = None  # a robot spec's validated form (its data, with every value's place)


def read_source(robot: RobotInput, *, emitted: bool = False) -> RobotSource:
    """The robot ``robot`` names as URDF text: a spec generated in memory (never written; its package expanded with
    xacro, or with ``emitted`` the URDF the direct emitter writes: :func:`~xacrokit.reader.spec_reading.spec_urdf`),
    a xacro document expanded with its mappings, a URDF read (a regular file of at most MAX_URDF_BYTES). A URDF or
    xacro file inside a ROS package finds that package and its workspace siblings for ``package://`` and ``$(find)``
    by itself.

    Raises:
        XacrokitError: unreadable input, or name:=value arguments for input that is not xacro.
        SpecErrors: an invalid spec (located); ExpandError: a xacro document that does not expand.
    """
    path = robot.path
    kind = input_kind(path)
    if robot.mappings and kind != "xacro":
        raise XacrokitError("name:=value arguments only apply to xacro input")
    if kind == "spec":  # (a spec's own reader says why it cannot be read, located)
        return _spec_source(robot, emitted=emitted)
    try:
        require_regular_file(path, MAX_URDF_BYTES)
    except OSError as exc:
        raise XacrokitError(f"cannot read {path}: {exc.strerror}") from None
    packages = with_nearby_packages(path, robot.packages)
    if kind == "xacro":
        from ..expansion.xacro_expand import expand_file  # (xacro: loaded for xacro input only)

        text = expand_file(path, robot.mappings, package_paths=packages, trust=robot.trust)
        return RobotSource(text, kind, packages)
    try:
        return RobotSource(read_input(path, MAX_URDF_BYTES).decode("utf-8"), kind, packages)
    except (OSError, UnicodeDecodeError) as exc:
        why = exc.strerror if isinstance(exc, OSError) and exc.strerror else "it is not UTF-8 text"
        raise XacrokitError(f"cannot read {path}: {why}") from None


def _spec_source(robot: RobotInput, *, emitted: bool) -> RobotSource:
    """A robot or scene spec's URDF, generated in memory (a scene's third-party macros trusted as ``robot`` says)."""
    from ..model import Robot  # (heavy: lxml)
    from .spec_reading import spec_urdf  # (the generator's readers: loaded for spec input only)

    with trusting(bool(robot.trust)):
        described = spec_urdf(robot.path, emitted=emitted)
    model = described.model if isinstance(described.model, Robot) else None  # (only a robot has DH arms)
    carried = dict(described.model.carried_files)
    lines, warnings = described.lines, described.warnings
    return RobotSource(described.urdf, "spec", robot.packages, model, lines, warnings, carried, described.spec)


UNDECLARED = "urn:xacrokit:undeclared:"


def declared(text: str, where: str = "<robot>") -> tuple[str, Any]:
    """``text`` itself and its parsed ``<robot>`` root when it is well-formed XML with its namespaces declared; when
    its only faults are namespace prefixes used without a declaration, the same document with each such name put in
    the namespace ``urn:xacrokit:undeclared:PREFIX`` (and its root, so changed: lines are the file's).

    Raises:
        XacrokitError: not well-formed XML (located: ``where:line``), or a root that is not ``<robot>``.
    """
    from lxml import etree  # (heavy: lxml)

    from ..shared.xml_parse import parse_urdf  # (heavy: lxml)

    parsed = parse_urdf(text)
    if parsed.root is None:
        raise XacrokitError(f"{parsed.where(where)}: {parsed.error}: not a URDF")
    if not parsed.undeclared:
        return text, parsed.root
    for element in parsed.root.iter(etree.Element):
        if ":" in element.tag and not element.tag.startswith("{"):
            prefix, _, local = element.tag.partition(":")
            element.tag = f"{{{UNDECLARED}{prefix}}}{local}"
        for key in [k for k in element.attrib if ":" in k and not k.startswith("{")]:
            prefix, _, local = key.partition(":")
            element.set(f"{{{UNDECLARED}{prefix}}}{local}", element.attrib.pop(key))
    return str(etree.tostring(parsed.root, encoding="unicode")), parsed.root


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
