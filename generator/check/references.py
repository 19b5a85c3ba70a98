"""Reference rules: what a document names exists (R001 gazebo references, R002 materials, R003 mesh files), and every
name carries the expected prefix (P001)."""

from __future__ import annotations

import dataclasses
import os
import re
from collections.abc import Iterator, Mapping
from pathlib import Path

from ..expansion import find_package
from .document import Doc
from .findings import Finding, Severity, rule_table

RULES = rule_table(
    {
        "R001": ("gazebo-reference", "error", "<gazebo reference> names an existing link or joint"),
        "R002": ("material-defined", "error", "a material used by name without a colour is defined"),
        "R003": ("mesh-resolves", "error", "mesh files resolve (package://, file:// or paths) and exist"),
        "P001": ("prefix", "error", "every link, joint, gazebo reference and ros2_control joint carries the prefix"),
    }
)


def reference_rules(
    doc: Doc, package_paths: Mapping[str, str | os.PathLike[str]] | None, base_dir: Path | None
) -> Iterator[Finding]:
    for gazebo in doc.root.findall("gazebo"):
        reference = gazebo.get("reference")
        if reference is not None and reference not in doc.link_names and reference not in doc.joint_by_name:
            yield doc.finding(
                "R001", "gazebo", reference, f"<gazebo reference={reference!r}> names no link or joint", gazebo
            )
    defined = {m.get("name") for m in doc.root.findall("material")}
    for material in doc.root.iter("material"):
        if material.getparent() is doc.root:
            continue
        name = material.get("name")
        has_own = material.find("color") is not None or material.find("texture") is not None
        if name and not has_own and name not in defined:
            yield doc.finding(
                "R002",
                "material",
                name,
                f"material {name!r} is used but not defined; add <material name={name!r}><color rgba=.../></material>",
                material,
            )
    for mesh in doc.root.iter("mesh"):
        filename = mesh.get("filename", "")
        problem, severity = _mesh_problem(filename, package_paths, base_dir)
        if problem:
            finding = doc.finding("R003", "mesh", filename, problem, mesh)
            if severity == "warning":  # (a package not known here: the file cannot be looked at)
                finding = dataclasses.replace(finding, severity="warning")
            yield finding


def _mesh_problem(
    filename: str, package_paths: Mapping[str, str | os.PathLike[str]] | None, base_dir: Path | None
) -> tuple[str | None, Severity]:
    if filename.startswith("package://"):
        package, _, rest = filename[len("package://") :].partition("/")
        try:
            folder = Path(find_package(package, package_paths))
        except LookupError:
            return (
                f"package {package!r} is not known here, so {filename!r} cannot be checked; pass "
                f"--package {package}=PATH",
                "warning",
            )
        path = folder / rest
    elif filename.startswith("file://"):
        path = Path(filename[len("file://") :])
    elif re.match(r"^[a-z][a-z0-9+.-]*://", filename):
        return f"{filename!r}: unknown URI scheme; use package:// or file://", "error"
    else:
        path = (base_dir or Path.cwd()) / filename
    if not path.is_file():
        return f"mesh file {filename!r} does not exist (looked at {path})", "error"
    return None, "error"


def prefix_rules(doc: Doc, prefix: str) -> Iterator[Finding]:
    named = [("link", e) for e in doc.links] + [("joint", e) for e in doc.joints]
    named += [("gazebo", g) for g in doc.root.findall("gazebo") if g.get("reference") is not None]
    named += [("ros2_control", j) for j in doc.root.findall("ros2_control/joint")]
    for kind, element in named:
        name = element.get("reference") if kind == "gazebo" else element.get("name", "")
        if not (name or "").startswith(prefix):
            yield doc.finding(
                "P001", kind, name or "", f"{kind} {name!r} does not start with the prefix {prefix!r}", element
            )
