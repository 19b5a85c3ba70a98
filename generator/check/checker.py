"""The check stage: a strict verifier for any URDF, xacro document or spec.

Our own rules run first (structure, numbers, joints, inertia, references, prefix, DH kinematics), then independent
consumers (check_urdf, pinocchio, yourdfpy, MuJoCo when installed). Every finding has a stable rule id, a severity, the
element it is about, where it came from when that can be known, and a message saying what is wrong and what would be
right. This module reads the input and runs the rule families in turn; each family's module holds its rules.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import SpecErrors, XacrokitError
from ..expansion.expression_guard import trusting
from ..shared.gc_pause import collector_paused
from ..shared.input_files import read_input, require_regular_file
from ..shared.ros_packages import with_nearby_packages
from ..write.atomic import staged_packages
from .consumers import chosen, consumer_findings, start_verdicts
from .document_rules import first_rules, other_rules
from .findings import CheckReport, Finding, InputKind
from .urdf_document import Doc, parse_robot

if TYPE_CHECKING:
    from ..model import Robot

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
    try:
        with path.open("rb") as file:
            head = file.read(4096)
    except OSError:
        return "urdf"  # (reading it again says why it cannot be read)
    text = head.decode("utf-8", "replace").lstrip("\ufeff \t\r\n")
    if not text.startswith("<"):
        return "spec"
    return "xacro" if re.search(r"xmlns:xacro\s*=|<xacro:", text) else "urdf"


def load_urdf(
    path: Path,
    kind: InputKind,
    mappings: Mapping[str, str] | None,
    package_paths: Mapping[str, str | os.PathLike[str]] | None,
    carried: dict[str, Any],
) -> tuple[str, Robot | None, dict[tuple[str, str], int] | None, tuple[Finding, ...]]:
    """URDF text, and for spec input the robot model, the spec lines and the spec's warnings; a spec's package files
    (meshes its package will carry) are added to ``carried``, by package."""
    if kind == "spec":
        from ..model import Robot
        from ..pipeline import spec_urdf  # (the whole generator: loaded for spec input only)
        from .spec_rules import spec_findings

        described = spec_urdf(path)
        robot = described.model if isinstance(described.model, Robot) else None  # (only a robot has DH arms)
        carried.update(described.model.carried_files)
        return described.urdf, robot, described.lines, spec_findings(described.warnings)
    if kind == "xacro":
        from ..expansion.xacro_expand import expand_file  # (xacro: loaded for xacro input only)

        return expand_file(path, mappings, package_paths=package_paths), None, None, ()
    try:
        return read_input(path, MAX_URDF_BYTES).decode("utf-8"), None, None, ()
    except (OSError, UnicodeDecodeError) as exc:
        why = exc.strerror if isinstance(exc, OSError) and exc.strerror else "it is not UTF-8 text"
        raise XacrokitError(f"cannot read {path}: {why}") from None


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
    if mappings and kind != "xacro":
        raise XacrokitError("name:=value arguments only apply to xacro input")
    names = chosen(consumers)
    if kind != "spec":  # (a spec's own reader says why it cannot be read, located)
        try:
            require_regular_file(path, MAX_URDF_BYTES)
        except OSError as exc:
            raise XacrokitError(f"cannot read {path}: {exc.strerror}") from None
    packages: Mapping[str, str | os.PathLike[str]] | None = package_paths
    if kind != "spec":  # a file inside a package finds that package (and its workspace siblings) by itself
        packages = with_nearby_packages(path, package_paths)
    say(f"reading {path.name}")
    carried: dict[str, Any] = {}
    try:
        with trusting(trust):
            text, robot, lines, notes = load_urdf(path, kind, mappings, packages, carried)
    except SpecErrors as exc:
        if all(e.line is None for e in exc.errors):  # the file itself cannot be read: no report to give
            raise
        from .spec_rules import spec_findings

        return CheckReport(str(path), kind, None, spec_findings(exc.errors, "V002"))
    with staged_packages(carried) as staged:  # (a spec's meshes, where its package will carry them)
        packages = {**staged, **(packages or {})} if staged else packages
        return _judge(path, kind, text, robot, lines, notes, names, packages, prefix, say)


def _judge(
    path: Path,
    kind: InputKind,
    text: str,
    robot: Robot | None,
    lines: dict[tuple[str, str], int] | None,
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
    doc = Doc(root, str(path), lines, source_lines=kind == "urdf")
    findings = [*notes, *read, *first_rules(doc)]
    structural = any(f.rule.startswith("S") for f in findings)
    # the consumers run while our other rules do (each in its own process): check takes about as long as the slowest
    if names and not structural:
        say(f"running {', '.join(names)} (and our other rules meanwhile)")
    pending = start_verdicts(names, text, structural=structural, package_paths=packages, base_dir=path.parent)
    findings += other_rules(doc, packages, path.parent, prefix)
    if robot is not None and not structural and robot.arms:
        from .spec_rules import kinematics_rules

        findings += kinematics_rules(doc, robot, text)
    results = pending()
    findings += consumer_findings(results, str(path))
    unique = tuple(dict.fromkeys(findings))  # (a spec's visual and collision share a mesh: one finding, not two)
    return CheckReport(str(path), kind, root.get("name"), unique, tuple(results))
