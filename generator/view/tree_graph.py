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
from collections.abc import Mapping

from ..errors import XacrokitError


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


def tree_dot(urdf: str, name: str | None = None) -> str:
    """The DOT text of the URDF's kinematic tree."""
    from lxml import etree

    root = etree.fromstring(urdf.encode("utf-8"), etree.XMLParser(resolve_entities=False, no_network=True))
    lines = [
        f"digraph {dot_string(name or root.get('name', 'robot'))} {{",
        "  rankdir=TB;",
        '  node [fontname="Helvetica", fontsize=10];',
    ]
    for link in root.findall("link"):
        mass = link.find("inertial/mass")
        label = link.get("name", "") + (f"\n{_number(mass.get('value'))} kg" if mass is not None else "\nno mass")
        lines.append(f"  {dot_string('link:' + link.get('name', ''))} [shape=box, label={dot_string(label)}];")
    for joint in root.findall("joint"):
        kind = joint.get("type", "")
        parts = [joint.get("name", ""), kind]
        axis = joint.find("axis")
        if kind in ("revolute", "continuous", "prismatic", "planar"):
            xyz = axis.get("xyz", "1 0 0") if axis is not None else "1 0 0"
            parts.append("axis " + " ".join(_number(v) for v in xyz.split()))
        limit = joint.find("limit")
        if limit is not None and kind in ("revolute", "prismatic"):
            parts.append(f"[{_number(limit.get('lower'))}, {_number(limit.get('upper'))}]")
        if limit is not None and kind in ("revolute", "continuous", "prismatic"):
            parts.append(f"effort {_number(limit.get('effort'))}, velocity {_number(limit.get('velocity'))}")
        mimic = joint.find("mimic")
        if mimic is not None:
            parts.append(f"mimics {mimic.get('joint', '')}")
        node = dot_string("joint:" + joint.get("name", ""))
        style = "dashed" if kind == "fixed" else "solid"
        lines.append(f"  {node} [shape=ellipse, style={style}, label={dot_string(chr(10).join(parts))}];")
        parent, child = joint.find("parent"), joint.find("child")
        if parent is not None:
            lines.append(f"  {dot_string('link:' + parent.get('link', ''))} -> {node};")
        if child is not None:
            lines.append(f"  {node} -> {dot_string('link:' + child.get('link', ''))};")
    lines.append("}")
    return "\n".join(lines) + "\n"


def graph(
    path: str | os.PathLike[str],
    mappings: Mapping[str, str] | None = None,
    *,
    package_paths: Mapping[str, str | os.PathLike[str]] | None = None,
) -> str:
    """The DOT text of a URDF, xacro document, spec or scene's kinematic tree.

    Raises:
        XacrokitError: unreadable input (SpecErrors for an invalid spec, located).
    """
    from ..reader.robot_source import robot_text

    with robot_text(path, mappings, package_paths, meshes=False) as (text, _):
        try:
            return tree_dot(text)
        except Exception as exc:  # noqa: BLE001  (lxml's parse errors: the file is not XML)
            raise XacrokitError(f"{path}: not a URDF: {exc}") from None


def svg(dot: str) -> bytes:
    """The SVG Graphviz's ``dot`` draws of ``dot``. Raises XacrokitError when Graphviz is not installed."""
    program = shutil.which("dot")
    if program is None:
        raise XacrokitError("Graphviz's dot is not installed: write -o tree.dot instead, or install graphviz")
    done = subprocess.run([program, "-Tsvg"], input=dot.encode("utf-8"), capture_output=True, timeout=120, check=False)
    if done.returncode:
        raise XacrokitError(f"dot failed: {done.stderr.decode('utf-8', 'replace')[-500:]}")
    return done.stdout
