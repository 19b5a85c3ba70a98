"""``gen-robot graph``: the kinematic tree of a URDF, xacro document, spec or scene as Graphviz DOT (SVG through
Graphviz's ``dot`` when it is installed).

Links are boxes (name and mass), joints ellipses (name, type, axis, limits) between their parent and child. Node ids
are ``link:NAME`` and ``joint:NAME``, so a link and a joint of the same name stay two nodes (urdf_to_graphviz merges
them). Names come from the file: every label and id is a DOT quoted string with its quotes, backslashes and line
breaks escaped, and labels are written without HTML (no markup a name could inject).
"""

from __future__ import annotations

import os
import shutil
import subprocess
from typing import TYPE_CHECKING

from ..errors import XacrokitError

if TYPE_CHECKING:
    from ..reader.read_robot import ReadRobot
    from ..reader.robot_input import RobotInput
    from ..shared.urdf_view import Joint, UrdfView


DOT_SECONDS = 50  # the longest Graphviz may take to lay out an SVG (a chain of 20,000 links: about 100 s, then fails)


def dot_string(text: object) -> str:
    """``text`` as a DOT quoted string: backslashes and quotes escaped, line breaks as DOT's \\n, other control
    characters as spaces."""
    clean = "".join(" " if ord(ch) < 0x20 and ch != "\n" else ch for ch in str(text))
    escaped = clean.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
    return f'"{escaped}"'


def _number(value: str | None) -> str:
    try:
        return f"{float(value or ''):.4g}"
    except ValueError:
        return str(value)


def tree_dot(view: UrdfView, name: str | None = None) -> str:
    """The DOT text of a robot's kinematic tree (its view)."""
    lines = [
        f"digraph {dot_string(name or view.name or 'robot')} {{",
        "  rankdir=TB;",
        '  node [fontname="Helvetica", fontsize=10];',
    ]
    for link in view.links:
        mass = link.inertial.mass if link.inertial is not None else None
        label = link.name + (f"\n{_number(mass)} kg" if mass is not None else "\nno mass")
        lines.append(f"  {dot_string('link:' + link.name)} [shape=box, label={dot_string(label)}];")
    for joint in view.joints:
        node = dot_string("joint:" + joint.name)
        style = "dashed" if joint.type == "fixed" else "solid"
        lines.append(f"  {node} [shape=ellipse, style={style}, label={dot_string(chr(10).join(_joint_label(joint)))}];")
        if joint.parent is not None:
            lines.append(f"  {dot_string('link:' + joint.parent)} -> {node};")
        if joint.child is not None:
            lines.append(f"  {node} -> {dot_string('link:' + joint.child)};")
    lines.append("}")
    return "\n".join(lines) + "\n"


def _joint_label(joint: Joint) -> list[str]:
    """A joint node's lines: name, type, axis, range, effort and velocity, the joint it mimics."""
    kind = joint.type or ""
    parts = [joint.name, kind]
    if kind in ("revolute", "continuous", "prismatic", "planar"):
        parts.append("axis " + " ".join(_number(v) for v in (joint.axis or "1 0 0").split()))
    limit = joint.limit
    if limit is not None and kind in ("revolute", "prismatic"):
        parts.append(f"[{_number(limit.get('lower'))}, {_number(limit.get('upper'))}]")
    if limit is not None and kind in ("revolute", "continuous", "prismatic"):
        parts.append(f"effort {_number(limit.get('effort'))}, velocity {_number(limit.get('velocity'))}")
    if joint.mimic is not None:
        parts.append(f"mimics {joint.mimic.joint or ''}")
    return parts


def graph(robot: ReadRobot | RobotInput | str | os.PathLike[str]) -> str:
    """The DOT text of a read robot's kinematic tree (a URDF, xacro document, spec or scene; or what to read).

    Raises:
        XacrokitError: unreadable input (SpecErrors for an invalid spec, located).
    """
    from ..reader.read_robot import read_robot  # (heavy: lxml)

    return tree_dot(read_robot(robot).view)


def svg(dot: str) -> bytes:
    """The SVG Graphviz's ``dot`` draws of ``dot``. Raises XacrokitError when Graphviz is not installed."""
    program = shutil.which("dot")
    if program is None:
        raise XacrokitError("Graphviz's dot is not installed: write -o tree.dot instead, or install graphviz")
    try:
        done = subprocess.run(
            [program, "-Tsvg"], input=dot.encode("utf-8"), capture_output=True, timeout=DOT_SECONDS, check=False
        )
    except subprocess.TimeoutExpired:
        raise XacrokitError(
            f"Graphviz's dot did not lay the tree out in {DOT_SECONDS} s (a chain of 5,000 links takes about 7 s): "
            "write -o tree.dot instead and lay it out as you wish"
        ) from None
    if done.returncode:
        raise XacrokitError(f"dot failed: {done.stderr.decode('utf-8', 'replace')[-500:]}")
    return done.stdout
