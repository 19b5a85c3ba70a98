"""Reference rules: what a document names exists (R001 gazebo references, R002 materials, R003 mesh files), and every
name carries the expected prefix (P001)."""

from __future__ import annotations

import dataclasses
import os
import re
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

from lxml import etree

from ..shared.ros_packages import find_package
from .findings import Finding, Severity, rule_table
from .urdf_document import Doc

RULES = rule_table(
    {
        "R001": (
            "gazebo-reference",
            "warning",
            "<gazebo reference> names an existing link or joint (Gazebo ignores a block that names none: its friction "
            "or sensor is silently lost)",
        ),
        "R002": (
            "material-defined",
            "warning",
            "a material used by name without a colour is defined (at the top level, or with a colour in any visual); "
            "consumers accept an undefined one and draw it in their default colour",
        ),
        "R003": ("mesh-resolves", "error", "mesh files resolve (package://, file:// or paths) and exist"),
        "P001": ("prefix", "error", "every link, joint, gazebo reference and ros2_control joint carries the prefix"),
    }
)


def reference_rules(
    doc: Doc, package_paths: Mapping[str, str | os.PathLike[str]] | None, base_dir: Path | None
) -> Iterator[Finding]:
    for block in doc.view.gazebo:
        reference, gazebo = block.reference, block.element
        if reference is not None and reference not in doc.link_names and reference not in doc.joint_by_name:
            yield doc.finding(
                "R001",
                "gazebo",
                reference,
                f"<gazebo reference={reference!r}> names no link or joint; Gazebo ignores the block (a typo, or a "
                "name left from another version of the robot?)",
                gazebo,
            )
    # urdfdom registers a material for the whole robot wherever it is given a colour or texture, a link's visual
    # included (the Allegro hand defines its colours in its first visuals and names them in later ones)
    used = [g.material for link in doc.view.links for g in link.visuals if g.material is not None]
    defined = {m.name for m in doc.view.materials} | {m.name or "" for m in used if m.defines}
    for material in used:
        name, has_own = material.name, material.defines
        if name and not has_own and name not in defined:
            yield doc.finding(
                "R002",
                "material",
                name,
                f"material {name!r} is used but not defined, so viewers draw it in their default colour; add "
                f"<material name={name!r}><color rgba=.../></material>",
                material.element,
            )
    # one finding per kind of problem: a file whose 180 mesh URIs all miss the package name says it once, with the
    # count (a missing folder, an unknown package and a malformed URI are each one mistake, not one per mesh)
    groups: dict[tuple[str, str], list[tuple[etree._Element, str, str, Severity]]] = {}
    folders: dict[str, str | None] = {}  # package -> its folder (None: not known), looked up once
    shapes = [g.shape for link in doc.view.links for g in (*link.visuals, *link.collisions) if g.shape is not None]
    for mesh in (shape.element for shape in shapes if shape.kind == "mesh"):
        filename = mesh.get("filename", "")
        problem, severity, group = _mesh_problem(filename, package_paths, base_dir, folders)
        if problem:
            groups.setdefault(group, []).append((mesh, filename, problem, severity))
    for same in groups.values():
        mesh, filename, problem, severity = same[0]
        if len(same) > 1:
            problem += f" (and {len(same) - 1} more mesh file name{'s' if len(same) > 2 else ''} like it)"
        finding = doc.finding("R003", "mesh", filename, problem, mesh)
        if severity == "warning":  # (a package not known here: the file cannot be looked at)
            finding = dataclasses.replace(finding, severity="warning")
        yield finding


def _mesh_problem(
    filename: str,
    package_paths: Mapping[str, str | os.PathLike[str]] | None,
    base_dir: Path | None,
    folders: dict[str, str | None],
) -> tuple[str | None, Severity, tuple[str, str]]:
    """What is wrong with a mesh file name (None when nothing), its severity, and the group of like mistakes."""
    if filename.startswith("package://"):
        package, _, rest = filename[len("package://") :].partition("/")
        if not package or not rest:
            return (
                f"{filename!r} is not a package URI: write package://PACKAGE/path/to/mesh (the package's name, "
                "then the path inside it)",
                "error",
                ("malformed", ""),
            )
        if package not in folders:
            try:
                folders[package] = find_package(package, package_paths)
            except LookupError:
                folders[package] = None
        known = folders[package]
        if known is None:
            return (
                f"package {package!r} is not known here, so {filename!r} cannot be checked; pass "
                f"--package {package}=PATH",
                "warning",
                ("package", package),
            )
        path = Path(known) / rest
    elif filename.startswith("file://"):
        path = Path(filename[len("file://") :])
    elif re.match(r"^[a-z][a-z0-9+.-]*://", filename):
        scheme = filename.split(":", 1)[0]
        return f"{filename!r}: unknown URI scheme; use package:// or file://", "error", ("scheme", scheme)
    else:
        path = (base_dir or Path.cwd()) / filename
    if not path.is_file():
        if not path.parent.is_dir():
            said = f"mesh file {filename!r} does not exist: there is no folder {path.parent}"
            return said, "error", ("folder", str(path.parent))
        return f"mesh file {filename!r} does not exist (looked at {path})", "error", ("file", str(path))
    return None, "error", ("", "")


def prefix_rules(doc: Doc, prefix: str) -> Iterator[Finding]:
    view = doc.view
    named: list[tuple[str, str, Any]] = [("link", link.name, link.element) for link in view.links]
    named += [("joint", joint.name, joint.element) for joint in view.joints]
    named += [("gazebo", g.reference, g.element) for g in view.gazebo if g.reference is not None]
    named += [("ros2_control", j.get("name", ""), j) for c in view.ros2_control for j in c.element.findall("joint")]
    for kind, name, element in named:
        if not (name or "").startswith(prefix):
            yield doc.finding(
                "P001", kind, name or "", f"{kind} {name!r} does not start with the prefix {prefix!r}", element
            )
