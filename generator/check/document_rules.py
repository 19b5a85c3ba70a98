"""Our rules that read a URDF document alone (all but a spec's DH kinematics and the consumers): what ``gen-robot
check`` runs on every input, and what ``gen-robot SPEC`` asks of the URDF it writes (:func:`generation_warnings`:
the command composes generation and check; the generator imports nothing of check)."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import SpecError
from ..write.atomic import staged_packages
from .collision_rules import collision_rules, ground_rules
from .findings import Finding
from .inertia_geometry import RobotMeshes
from .inertia_rules import inertia_rules
from .joint_rules import joint_rules
from .number_rules import geometry_rules, number_rules
from .reference_rules import prefix_rules, reference_rules
from .rule_table import RULES
from .sensor_rules import sensor_rules
from .structure_rules import name_rules, structure_rules, xacro_rules
from .urdf_document import Doc, parse_robot

if TYPE_CHECKING:
    from ..pipeline import GenerateResult, SpecSource


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


def generation_warnings(result: GenerateResult) -> tuple[SpecError, ...]:
    """What ``gen-robot SPEC`` says when it writes a package: the generator's warnings (``result.warnings``) and what
    ``gen-robot check --strict SPEC`` would fail on in the URDF it wrote (check's warnings, and the errors a valid
    spec can still give, such as a mesh file that is not there), located at the spec's lines, in line order; at one
    place the spec's own come first, then check's, then the generator's others. A scene's are its warnings as they
    are (check's rules judge a robot spec's URDF).

    ``generate`` itself leaves check's out (generation imports nothing of check): ask this for what the command says.
    """
    source = result.source
    if source is None:
        return result.warnings
    with staged_packages(result.model.carried_files) as staged:  # (its meshes, where the package carries them)
        found = generated_urdf_findings(result.urdf, source.file, source.lines, staged or None)
    said = [(warning, 0 if any(warning is w for w in source.warnings) else 2) for warning in result.warnings]
    said += [(warning, 1) for warning in _as_warnings(found, source)]
    return tuple(w for w, _ in sorted(said, key=lambda pair: (pair[0].line or 0, pair[0].column or 0, pair[1])))


def _as_warnings(findings: list[Finding], source: SpecSource) -> list[SpecError]:
    """The findings that ``check --strict`` fails on, as warnings at the spec's lines."""
    said = []
    for finding in findings:
        if finding.severity == "info":
            continue
        rule = f"{finding.rule} {RULES[finding.rule][0]} ({finding.severity} of gen-robot check)"
        message = f"{rule}: {finding.element_kind} {finding.element!r}: {finding.message}"
        said.append(SpecError(message, file=str(source.file), line=finding.line, column=finding.column))
    return said
