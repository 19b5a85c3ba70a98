"""An SRDF read back (for ``gen-robot check``): the pairs of links it disables, with their reasons, and where it is
for a URDF: given, beside the URDF (``NAME.srdf``), or in its package's ``config/NAME.srdf``."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from ..errors import XacrokitError
from ..shared.input_files import InputError, read_input
from ..shared.urdf_view import number
from ..shared.xml_parse import parse_xml
from .collision_matrix import Pair, pair

SRDF_LIMIT = 16 * 1024 * 1024  # bytes of an SRDF read (the largest real ones are a few hundred kB)


def srdf_beside(urdf: Path) -> Path | None:
    """The SRDF a URDF (or xacro document) at ``urdf`` comes with: ``NAME.srdf`` beside it, else its package's
    ``config/NAME.srdf`` (MoveIt's configuration packages, ours) or ``srdf/NAME.srdf`` (example-robot-data's);
    ``NAME`` is the file's name up to its first dot (``urdf/NAME.urdf``, ``urdf/NAME.urdf.xacro``). None without one."""
    name = urdf.name.split(".", 1)[0]
    package = urdf.parent.parent
    for candidate in (
        urdf.parent / f"{name}.srdf",
        package / "config" / f"{name}.srdf",
        package / "srdf" / f"{name}.srdf",
    ):
        if candidate.is_file():
            return candidate
    return None


@dataclass(frozen=True)
class SrdfFacts:
    """What check reads of an SRDF: its disabled pairs (pair -> reason, ``""`` where it gives none) and its
    ``home`` states' joint values (every group's ``<group_state name="home">``)."""

    disabled: dict[Pair, str]
    home: dict[str, float]


def read_srdf(srdf: Path) -> SrdfFacts:
    """The SRDF's disabled pairs and home.

    Raises:
        XacrokitError: the file cannot be read, or is no SRDF (located).
    """
    try:
        data = read_input(srdf, SRDF_LIMIT)
    except InputError as exc:
        raise XacrokitError(f"{srdf}: cannot read the SRDF: {exc.strerror}") from None
    root = parse_xml(data, str(srdf))
    if root.tag != "robot":
        raise XacrokitError(f"{srdf}:{root.sourceline}: an SRDF's root is <robot>, not <{root.tag}>")
    found = {}
    for element in root.iter("disable_collisions"):
        first, second = element.get("link1"), element.get("link2")
        if first and second:
            found[pair(first, second)] = element.get("reason", "")
    home = {}
    for joint in root.iterfind("group_state[@name='home']/joint"):
        value = number(joint.get("value"), math.nan)
        if joint.get("name") and math.isfinite(value):
            home[joint.get("name", "")] = value
    return SrdfFacts(found, home)
