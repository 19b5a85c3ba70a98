"""The read robot: what every command that takes a robot works on (pose, jacobian, ik, size, report, view, render,
export, graph, import). A :class:`~xacrokit.reader.robot_input.RobotInput` is read once by :func:`read_robot`: its
URDF text, the typed view parsed from it once, for a spec its model, lines and warnings, the packages its URIs may
name; the kinematic model (pinocchio) is built the first time a feature asks for it, and then kept.

The flow (docs/development.md): a path -> :class:`RobotInput` (the command line's ``robot_input``) ->
:func:`read_robot` -> :class:`ReadRobot` -> a feature."""

from __future__ import annotations

import contextlib
import functools
import os
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import SpecError, XacrokitError
from ..shared.urdf_view import UrdfView, view_of
from ..write.atomic import staged_packages
from . import InputKind
from .robot_input import Packages, RobotInput, as_input
from .robot_source import declared, read_source

if TYPE_CHECKING:
    from ..model import Robot
    from ..validate import Spec
    from .kinematic_model import KinematicModel


@dataclass(frozen=True)
class ReadRobot:
    """A robot read once (frozen; the models built from it are built once, on first use).

    Attributes:
        input: what was read.
        kind: urdf, xacro or spec (a scene spec too).
        text: its URDF (a spec's generated in memory; a xacro document's expanded).
        view: the typed view of ``text``, parsed once.
        packages: the folders its ``package://`` URIs may name (given, and the ROS packages found near the file).
        spec: a robot spec's model (None for a URDF, a xacro document or a scene).
        lines: a spec's line and column of each link and joint, ``(kind, name) -> (line, column)``.
        warnings: a spec's warnings (valid values that look like a units mistake).
        carried: the files a spec's package will carry (its meshes), by package; staged by :meth:`mesh_packages`.
        validated: a robot spec's validated form (its data with every value's place; None otherwise).
    """

    input: RobotInput
    kind: InputKind
    text: str
    view: UrdfView = field(repr=False)
    packages: Packages = field(default_factory=dict)
    spec: Robot | None = None
    lines: Mapping[tuple[str, str], tuple[int, int]] | None = None
    warnings: tuple[SpecError, ...] = ()
    carried: Mapping[str, Any] = field(default_factory=dict, repr=False)
    validated: Spec | None = field(default=None, repr=False)

    @property
    def path(self) -> Path:
        return self.input.path

    @property
    def name(self) -> str:
        """The robot's name: its ``<robot name>``, else the file's stem."""
        return self.view.name or self.path.stem.split(".")[0]

    @property
    def where(self) -> str:
        """The file as messages name it: ``robot.urdf``, or ``robot.xacro (as expanded)`` where lines are the
        expansion's."""
        return str(self.path) if self.kind == "urdf" else f"{self.path} (as expanded)"

    @functools.cached_property
    def kinematics(self) -> KinematicModel:
        """The kinematic model, fixed at the root link (built on first use, then kept).

        Raises:
            XacrokitError: a robot the kinematics cannot take (:func:`.kinematic_model.build_kinematics`), said with
                the file.
        """
        from .kinematic_model import build_kinematics  # (heavy: numpy)

        try:
            return build_kinematics(self.text, self.view, self.name)
        except XacrokitError as exc:  # (its lines are the text's: a xacro document's or a spec's as expanded)
            raise XacrokitError(f"{self.where}: {exc}") from None

    @functools.cached_property
    def free_floating(self) -> Any:
        """A pinocchio model of the robot on a free-flyer root joint (what a mobile base's and a free body's
        dynamics need; built on first use, then kept).

        Raises:
            XacrokitError: pinocchio cannot read the robot.
        """
        from .pinocchio_reading import pinocchio_model  # (heavy: numpy; only the features that need dynamics)

        try:  # (its axes read as the kinematic model's: an axis of 1e308 1e308 0 is the diagonal, not a still joint)
            return pinocchio_model(self.text, self.view, free=True)
        except XacrokitError as exc:
            raise XacrokitError(f"{self.where}: {exc}") from None

    @contextlib.contextmanager
    def mesh_packages(self) -> Iterator[Mapping[str, str | os.PathLike[str]]]:
        """The packages its meshes are found in, for the ``with`` block: a spec's own meshes staged where its
        package will carry them (they last as long as the block), then the others."""

        with staged_packages(dict(self.carried)) as staged:
            yield {**staged, **self.packages}


def read_robot(robot: ReadRobot | RobotInput | str | os.PathLike[str], *, emitted: bool = False) -> ReadRobot:
    """Read the robot ``robot`` names (a :class:`RobotInput`, or a path read with its defaults): its text once, its
    view once. A robot already read is returned as it is (the features' Python API takes either). A spec's URDF is
    its package's expanded with xacro, or with ``emitted`` the one ``gen-robot SPEC`` writes (the same robot:
    :func:`~xacrokit.reader.spec_reading.spec_urdf`; what the kinematics commands read, without xacro's or
    jinja2's time).

    Raises:
        XacrokitError: unreadable input, name:=value arguments for input that is not xacro, or not a URDF.
        SpecErrors: an invalid spec (located); ExpandError: a xacro document that does not expand.
    """
    if isinstance(robot, ReadRobot):
        return robot
    given = as_input(robot)
    source = read_source(given, emitted=emitted)
    made = "as generated" if emitted and source.kind == "spec" else "as expanded"
    where = str(given.path) if source.kind == "urdf" else f"{given.path} ({made})"
    text, root = declared(source.text, where)
    return ReadRobot(
        given,
        source.kind,
        text,
        view_of(root),
        source.packages or {},
        source.robot,
        source.lines,
        source.warnings,
        source.carried,
        source.validated,
    )


def read_text(text: str, path: str | os.PathLike[str] = "robot.urdf") -> ReadRobot:
    """A URDF ``text`` as a read robot (``path``: the file it stands for, what messages name and where relative
    mesh names are found from).

    Raises:
        XacrokitError: not well-formed XML, or not a ``<robot>``.
    """
    where = Path(path)
    text, root = declared(text, str(where))
    return ReadRobot(RobotInput(where), "urdf", text, view_of(root))
