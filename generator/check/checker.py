"""The check stage: a strict verifier for any URDF, xacro document or spec.

Our own rules run first (structure, numbers, joints, inertia, references, prefix, DH kinematics), then independent
consumers (check_urdf, pinocchio, yourdfpy, MuJoCo when installed). Every finding has a stable rule id, a severity, the
element it is about, where it came from when that can be known, and a message saying what is wrong and what would be
right. This module reads the input and runs the rule families in turn; each family's module holds its rules.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import SpecErrors
from ..reader import InputKind
from ..reader.named_poses import named_poses, spec_poses
from ..reader.robot_input import RobotInput, as_input
from ..reader.robot_source import RobotSource, input_kind, read_source
from ..shared.gc_pause import collector_paused
from ..shared.joint_types import HOME_POSE
from ..write.atomic import staged_packages
from .consumers import SHARING, chosen, consumer_findings, skipped, start_verdicts, warm_consumers
from .document_rules import first_rules, other_rules
from .findings import CheckReport, Finding
from .inertia_geometry import RobotMeshes, preload_mesh_readers
from .self_collision_rules import SelfCollisionInput, self_collision_rules
from .spec_rules import kinematics_rules, spec_findings
from .urdf_document import Doc, parse_robot

if TYPE_CHECKING:
    from ..model import Robot


@collector_paused()
def check(
    robot: RobotInput | str | os.PathLike[str],
    *,
    prefix: str | None = None,
    consumers: Sequence[str] | None = None,
    progress: Callable[[str], None] | None = None,
    srdf: str | os.PathLike[str] | None = None,
) -> CheckReport:
    """Check a URDF, a xacro document (expanded with its input's mappings) or a spec (generated in memory, never
    written).

    Args:
        robot: the robot input (:class:`~xacrokit.reader.robot_input.RobotInput`: the file, a xacro document's
            ``xacro:arg`` values, folders for ``$(find PKG)`` and ``package://PKG`` of packages not otherwise found,
            and whether its expressions are trusted: by default those that could reach Python's internals are
            refused, :mod:`xacrokit.expansion.expression_guard`), or the file alone. ``.yaml``/``.yml`` is a spec,
            ``.xacro`` a xacro document, ``.urdf``/``.xml`` URDF; any other name is told by its content (XML is URDF,
            or xacro when it declares the xacro namespace; else a spec). A URDF or xacro file inside a ROS package
            finds that package and its siblings for ``package://`` and ``$(find)`` by itself.
        prefix: when given, every link, joint, gazebo reference and ros2_control joint must start with it.
        consumers: which independent consumers to run (default: every installed one of check_urdf, pinocchio,
            yourdfpy, mujoco); ``[]`` for none.
        progress: called with a short message as each step starts (the CLI shows it on a terminal).
        srdf: the robot's SRDF, whose disabled pairs G007 respects (default: ``NAME.srdf`` beside the URDF, or its
            package's ``config/NAME.srdf``; a spec's is the one its package carries).

    Raises:
        XacrokitError: the input cannot be read (a spec file that cannot be read raises SpecErrors, a xacro
            ExpandError). A spec with located errors gives a report of V002 findings instead.
    """
    given = as_input(robot)
    path = given.path
    say = progress or (lambda message: None)
    kind = input_kind(path)
    names = chosen(consumers)
    # (the Python consumers' children start now, each importing its library while the file is read)
    with warm_consumers(names):
        say(f"reading {path.name}")
        source = _source_or_report(given, kind)
        if isinstance(source, CheckReport):
            return source
        notes: tuple[Finding, ...] = spec_findings(source.warnings) if source.warnings else ()
        with staged_packages(source.carried) as staged:  # (a spec's meshes, where its package will carry them)
            packages = {**staged, **(source.packages or {})} if staged else source.packages
            judging = Judging(
                path=path,
                kind=kind,
                text=source.text,
                robot=source.robot,
                lines=source.lines,
                notes=notes,
                consumers=names,
                packages=packages,
                prefix=prefix,
                say=say,
                srdf=Path(srdf) if srdf is not None else None,
            )
            return _judge(judging)


def _source_or_report(given: RobotInput, kind: InputKind) -> RobotSource | CheckReport:
    """The input read, or, for a spec with located errors, the report of them (V002)."""
    try:
        return read_source(given)
    except SpecErrors as exc:
        if all(e.line is None for e in exc.errors):  # the file itself cannot be read: no report to give
            raise
        return CheckReport(str(given.path), kind, None, spec_findings(exc.errors, "V002"))


@dataclass(frozen=True)
class Judging:
    """An input read, and what :func:`check` judges it with.

    Attributes:
        path: the file checked; ``kind``: what it is (urdf, xacro or spec).
        text: its URDF text (a xacro document's expanded, a spec's generated).
        robot: a robot spec's model (its DH arms for K001); None for other input.
        lines: a spec's line and column of each link and joint, ``(kind, name) -> (line, column)``.
        notes: a spec's warnings, as findings (V001, V003).
        consumers: the independent consumers to run.
        packages: the folders its ``package://`` URIs may name (a spec's meshes staged where its package carries them).
        prefix: when given, the prefix every name must start with.
        say: called with a short message as each step starts.
        srdf: the SRDF given for G007 (None: the one beside the file, if any).
    """

    path: Path
    kind: InputKind
    text: str
    robot: Robot | None
    lines: dict[tuple[str, str], tuple[int, int]] | None
    notes: tuple[Finding, ...]
    consumers: list[str]
    packages: Mapping[str, str | os.PathLike[str]] | None
    prefix: str | None
    say: Callable[[str], None]
    srdf: Path | None = None


def _judge(judging: Judging) -> CheckReport:
    """The rest of :func:`check`, once the URDF text is read: our rules, and the consumers while they run."""
    j = judging
    where = str(j.path)
    root, read = parse_robot(j.text, where)
    if root is None:  # U001: not a URDF, nothing more to read
        return CheckReport(where, j.kind, None, tuple(read))
    j.say("running our rules")
    doc = Doc(root, where, j.lines, source=j.text if j.kind == "urdf" else None)
    findings = [*j.notes, *read, *first_rules(doc)]
    structural = any(f.rule.startswith("S") for f in findings)
    # the consumers run while our other rules do (each in its own process): check takes about as long as the slowest
    if j.consumers and not structural:
        j.say(f"running {', '.join(j.consumers)} (and our other rules meanwhile)")
    # (trimesh, when our rules may read meshes with it, loaded once for them and yourdfpy's child, which inherits it)
    meshes = RobotMeshes(j.path.parent / Path(doc.file or "robot.urdf").name, j.packages)
    prepare = (lambda: preload_mesh_readers(doc, meshes)) if any(n in SHARING for n in j.consumers) else None
    pending = None  # (a tree that is not a tree hangs check_urdf and crashes others: the consumers are not run)
    if not structural:
        pending = start_verdicts(
            j.consumers, j.text, package_paths=j.packages, base_dir=j.path.parent, shown_as=where, prepare=prepare
        )
    findings += other_rules(doc, j.packages, j.path.parent, j.prefix)
    if j.robot is not None and not structural and j.robot.arms:
        findings += kinematics_rules(doc, j.robot, j.text)
    if not structural:
        home = named_poses(spec_poses(j.robot), doc.view)[HOME_POSE]
        given = SelfCollisionInput(j.path, j.packages, home, j.srdf, spec=j.kind == "spec")
        findings += self_collision_rules(doc, given)
    results = skipped(j.consumers) if pending is None else pending()
    findings += consumer_findings(results, where, doc)  # (placed at the link or joint a message names)
    unique = tuple(dict.fromkeys(findings))  # (a spec's visual and collision share a mesh: one finding, not two)
    return CheckReport(where, j.kind, root.get("name"), unique, tuple(results))
