"""Our rules that read a URDF document alone (all but a spec's DH kinematics and the consumers): what ``gen-robot
check`` runs on every input, and what ``gen-robot SPEC`` runs on the URDF it writes (this module imports no part of
the generator, which imports it)."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

from .collision_rules import collision_rules, ground_rules
from .findings import Finding
from .inertia_geometry import RobotMeshes
from .inertia_rules import inertia_rules
from .joint_rules import joint_rules
from .number_rules import geometry_rules, number_rules
from .reference_rules import prefix_rules, reference_rules
from .sensor_rules import sensor_rules
from .structure_rules import name_rules, structure_rules, xacro_rules
from .urdf_document import Doc, parse_robot


def document_rules(
    doc: Doc,
    packages: Mapping[str, str | os.PathLike[str]] | None,
    base_dir: Path,
    prefix: str | None = None,
) -> list[Finding]:
    """Our rules that read the URDF alone (all but a spec's DH kinematics and the consumers)."""
    return [*first_rules(doc), *other_rules(doc, packages, base_dir, prefix)]


def first_rules(doc: Doc) -> list[Finding]:
    """The rules that say whether the document is a robot at all (xacro left in it, its tree): run first, since the
    consumers are not run on a broken tree (a rooted cycle hangs check_urdf)."""
    return [*xacro_rules(doc), *structure_rules(doc)]


def other_rules(
    doc: Doc,
    packages: Mapping[str, str | os.PathLike[str]] | None,
    base_dir: Path,
    prefix: str | None = None,
) -> list[Finding]:
    """The rest of :func:`document_rules`: numbers, geometry, names, joints, inertia, references, prefix."""
    findings = list(number_rules(doc))
    findings += geometry_rules(doc)
    findings += name_rules(doc)
    findings += joint_rules(doc)
    meshes = RobotMeshes(base_dir / Path(doc.file or "robot.urdf").name, packages)  # (read once for these rules)
    findings += inertia_rules(doc, meshes)
    findings += collision_rules(doc, meshes)
    findings += ground_rules(doc, meshes)
    findings += reference_rules(doc, packages, base_dir)
    findings += sensor_rules(doc)
    if prefix is not None:
        findings += prefix_rules(doc, prefix)
    return findings


def generated_urdf_findings(
    urdf: str,
    spec_path: Path,
    lines: dict[tuple[str, str], tuple[int, int]],
    packages: Mapping[str, str | os.PathLike[str]] | None = None,
) -> list[Finding]:
    """What ``gen-robot check SPEC`` would say of the URDF a spec generates (its rules on the URDF, with the spec's
    lines; not the DH kinematics, which the generator's own tests hold, nor the consumers): ``gen-robot SPEC`` says
    its warnings and errors when it writes the package, so that ``check --strict`` holds no surprise. ``packages``:
    where the package's own meshes are before it is written."""
    root, read = parse_robot(urdf, str(spec_path))
    if root is None:
        return read
    return [*read, *document_rules(Doc(root, str(spec_path), lines), packages, spec_path.parent)]
