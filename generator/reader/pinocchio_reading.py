"""A URDF as pinocchio reads it, for the kinematic model and the free-floating one
(:class:`~xacrokit.reader.read_robot.ReadRobot`): the joints' axes read as directions, and urdfdom's complaints said
as an error of ours.

* An axis is scaled by its largest component before its norm (:func:`unit_axis`): an axis of 1e308 1e308 0 is the
  diagonal it names, where pinocchio's own normalisation overflows and leaves the joint still; a zero axis is refused.
* urdfdom, inside pinocchio, prints its complaints from C++ on the process's standard error, each followed by the
  place in urdfdom's own source (the machine that built it); they are kept off the terminal, and the first one is the
  error's reason (:func:`pinocchio_model`).
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np
from lxml import etree

from ..errors import XacrokitError
from ..shared.joint_types import MOVING
from ..shared.quiet_stderr import quietly
from ..shared.urdf_view import Joint, UrdfView
from ..shared.value_text import comment_text
from .robot_source import urdf_floats


def line_of(joint: Joint, tag: str = "") -> str:
    """`` (line N)``: where a joint's element ``tag`` (the joint itself when not given or absent) is in the text read
    (the file's own line for a URDF; the expansion's for xacro and specs); empty when not known."""
    found = joint.element.find(tag) if tag and joint.element is not None else None
    line = found.sourceline if found is not None and found.sourceline else joint.line
    return f" (line {line})" if line else ""


def unit_axis(joint: Joint) -> np.ndarray:
    """A joint's axis as a unit vector (URDF's default 1 0 0 without ``<axis>``), scaled before its norm so that an
    axis of 1e308 1e308 0 is the diagonal it names, and one of 5e-324 5e-324 0 too.

    Raises:
        XacrokitError: not three finite numbers, or all zero (said with the joint and the axis's line).
    """
    said = f"joint {joint.name!r} axis"
    try:
        given = urdf_floats(joint.axis, 3, where=said) if joint.axis is not None else [1.0, 0.0, 0.0]
    except XacrokitError as exc:
        raise XacrokitError(f"{exc}{line_of(joint, 'axis')}") from None
    axis = np.array(given)
    largest = float(np.abs(axis).max())
    if not largest > 0:
        raise XacrokitError(
            f"joint {joint.name!r}: its axis is zero{line_of(joint, 'axis')}: it names no direction to turn or slide "
            "along; give one, such as 0 0 1"
        )
    axis = axis / largest  # (first: the norm of an axis of 1e308 overflows, of 1e-320 underflows)
    return np.asarray(axis / np.linalg.norm(axis))


def pinocchio_model(text: str, view: UrdfView, *, free: bool = False) -> Any:
    """pinocchio's model of the URDF ``text`` (whose view is ``view``): fixed at its root link, or on a free-flyer
    root joint when ``free``; the moving joints' axes as :func:`unit_axis` reads them.

    Raises:
        XacrokitError: pinocchio cannot read it (urdfdom's first complaint said, without its source's places).
    """
    import pinocchio as pin  # (heavy: pinocchio)

    readable = _with_unit_axes(text, view)
    roots = (pin.JointModelFreeFlyer(),) if free else ()
    model, failure, said = quietly(lambda: pin.buildModelFromXML(readable, *roots))
    if failure is None:
        return model
    complaint = urdfdom_complaint(said)
    raise XacrokitError(f"pinocchio cannot read the robot: {complaint or failure}")


_COMPLAINT = re.compile(r"^\s*Error:\s*(.*?)\s*$")


def urdfdom_complaint(printed: str) -> str:
    """The first complaint urdfdom printed (``Error:   joint [j]: lower value (nan) is not a valid float``), its
    non-printable characters escaped; empty when it printed none. The line after each (``at line 124 in
    /project/urdfdom/urdf_parser/src/joint.cpp``) is the place in urdfdom's source, not in the robot: left out."""
    for line in printed.splitlines():
        found = _COMPLAINT.match(line)
        if found and found.group(1):
            return comment_text(found.group(1))
    return ""


def _with_unit_axes(text: str, view: UrdfView) -> str:
    """``text``, or, when a moving joint's axis would not survive pinocchio's own normalisation (its norm overflows
    or underflows), a copy with those axes written as unit vectors (the view stays as read; a caller refuses the
    axes that are not finite numbers or zero first: :func:`unit_axis` says why)."""
    rewritten: dict[str, np.ndarray] = {}
    for joint in view.joints:
        if joint.axis is not None and (joint.type in MOVING or joint.type == "planar"):
            given = np.array(urdf_floats(joint.axis, 3))
            with np.errstate(over="ignore", under="ignore"):  # (as pinocchio's own norm: its square overflows)
                norm = float(np.sqrt(np.sum(given * given)))
            if not (math.isfinite(norm) and norm > 1e-150):
                rewritten[joint.name] = unit_axis(joint)
    if not rewritten:
        return text
    root = etree.fromstring(etree.tostring(view.root))
    for element in root.iterchildren("joint"):
        unit = rewritten.get(element.get("name", ""))
        found = element.find("axis")
        if unit is not None and found is not None:
            found.set("xyz", " ".join(repr(float(v)) for v in unit))
    return str(etree.tostring(root, encoding="unicode"))
