"""The check stage: a strict verifier for any URDF, xacro document or spec.

Our own rules run first (structure, numbers, joints, inertia, references, prefix, DH kinematics), then independent
consumers (check_urdf, pinocchio, yourdfpy, MuJoCo when installed). Every finding has a stable rule id, a severity, the
element it is about, where it came from when that can be known, and a message saying what is wrong and what would be
right. This module reads the input and runs the rule families in turn; each family's module holds its rules.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import SpecErrors
from ..reader import InputKind
from ..reader.robot_input import RobotInput
from ..reader.robot_source import input_kind, read_source
from ..shared.gc_pause import collector_paused
from ..write.atomic import staged_packages
from .consumers import chosen, consumer_findings, start_verdicts
from .document_rules import first_rules, other_rules
from .findings import CheckReport, Finding
from .inertia_geometry import preload_mesh_readers
from .urdf_document import Doc, parse_robot

if TYPE_CHECKING:
    from ..model import Robot


@collector_paused()
def check(
    path: str | Path,
    mappings: Mapping[str, str] | None = None,
    *,
    prefix: str | None = None,
    consumers: Sequence[str] | None = None,
    package_paths: Mapping[str, str | Path] | None = None,
    progress: Callable[[str], None] | None = None,
    trust: bool = False,
) -> CheckReport:
    """Check a URDF, a xacro document (expanded with ``mappings``) or a spec (generated in memory, never written).

    Args:
        path: the file; ``.yaml``/``.yml`` is a spec, ``.xacro`` a xacro document, ``.urdf``/``.xml`` URDF; any
            other name is told by its content (XML is URDF, or xacro when it declares the xacro namespace; else a
            spec). A URDF or xacro file inside a ROS package finds that package and its siblings for ``package://``
            and ``$(find)`` without ``package_paths``.
        mappings: ``xacro:arg`` values for a xacro document.
        prefix: when given, every link, joint, gazebo reference and ros2_control joint must start with it.
        consumers: which independent consumers to run (default: every installed one of check_urdf, pinocchio,
            yourdfpy, mujoco); ``[]`` for none.
        package_paths: folders for ``$(find PKG)`` and ``package://PKG`` of packages not otherwise found.
        progress: called with a short message as each step starts (the CLI shows it on a terminal).
        trust: evaluate every expression of a xacro document (and of a scene's third-party macros); by default those
            that could reach Python's internals are refused (:mod:`xacrokit.expansion.expression_guard`).

    Raises:
        XacrokitError: the input cannot be read (a spec file that cannot be read raises SpecErrors, a xacro
            ExpandError). A spec with located errors gives a report of V002 findings instead.
    """
    path = Path(path)
    say = progress or (lambda message: None)
    kind = input_kind(path)
    names = chosen(consumers)
    say(f"reading {path.name}")
    try:
        # (untrusted unless told, or unless the environment says so: None)
        source = read_source(RobotInput(path, mappings or {}, package_paths or {}, True if trust else None))
    except SpecErrors as exc:
        if all(e.line is None for e in exc.errors):  # the file itself cannot be read: no report to give
            raise
        from .spec_rules import spec_findings

        return CheckReport(str(path), kind, None, spec_findings(exc.errors, "V002"))
    notes: tuple[Finding, ...] = ()
    if source.warnings:
        from .spec_rules import spec_findings

        notes = spec_findings(source.warnings)
    with staged_packages(source.carried) as staged:  # (a spec's meshes, where its package will carry them)
        packages = {**staged, **(source.packages or {})} if staged else source.packages
        return _judge(path, kind, source.text, source.robot, source.lines, notes, names, packages, prefix, say)


def _judge(
    path: Path,
    kind: InputKind,
    text: str,
    robot: Robot | None,
    lines: dict[tuple[str, str], tuple[int, int]] | None,
    notes: tuple[Finding, ...],
    names: list[str],
    packages: Mapping[str, str | os.PathLike[str]] | None,
    prefix: str | None,
    say: Callable[[str], None],
) -> CheckReport:
    """The rest of :func:`check`, once the URDF text is read: our rules, and the consumers while they run."""
    root, read = parse_robot(text, str(path))
    if root is None:  # U001: not a URDF, nothing more to read
        return CheckReport(str(path), kind, None, tuple(read))
    say("running our rules")
    doc = Doc(root, str(path), lines, source=text if kind == "urdf" else None)
    findings = [*notes, *read, *first_rules(doc)]
    structural = any(f.rule.startswith("S") for f in findings)
    # the consumers run while our other rules do (each in its own process): check takes about as long as the slowest
    if names and not structural:
        say(f"running {', '.join(names)} (and our other rules meanwhile)")
        preload_mesh_readers(doc)  # (before the consumers fork: they inherit it, and yourdfpy needs it too)
    pending = start_verdicts(
        names, text, structural=structural, package_paths=packages, base_dir=path.parent, shown_as=str(path)
    )
    findings += other_rules(doc, packages, path.parent, prefix)
    if robot is not None and not structural and robot.arms:
        from .spec_rules import kinematics_rules

        findings += kinematics_rules(doc, robot, text)
    results = pending()
    findings += consumer_findings(results, str(path))
    unique = tuple(dict.fromkeys(findings))  # (a spec's visual and collision share a mesh: one finding, not two)
    return CheckReport(str(path), kind, root.get("name"), unique, tuple(results))
