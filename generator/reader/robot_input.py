"""What names a robot to read: a file, the xacro arguments and package folders it is read with, and whether its xacro
expressions are trusted. The command line makes one from its shared options (``cli/arguments.robot_input``); the
Python API takes one, or a path (:func:`as_input`)."""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

Packages = Mapping[str, "str | os.PathLike[str]"]


def _copied(mapping: Mapping[str, object] | None) -> dict[str, object]:
    """A copy (a caller's dict changed later does not change what is read); a plain dict, so that the input pickles
    for a worker process (a read-only mapping proxy does not)."""
    return dict(mapping or {})


@dataclass(frozen=True)
class RobotInput:
    """A robot to read, frozen.

    Attributes:
        path: a URDF, xacro document, robot spec or scene spec.
        mappings: ``xacro:arg`` values (``name:=value`` on the command line); only a xacro document takes them.
        packages: folders for ``$(find NAME)`` and ``package://NAME`` that are not found otherwise (a URDF or xacro
            file inside a ROS package finds its package and the workspace's others by itself).
        trust: evaluate every xacro expression, as xacro does (``--trust``); False refuses the expressions that
            could reach Python's internals (docs/macros.md, Untrusted documents); None: as the environment says
            (``XACROKIT_TRUST_XACRO=1``), else untrusted.
    """

    path: Path
    mappings: Mapping[str, str] = field(default_factory=dict)
    packages: Packages = field(default_factory=dict)
    trust: bool | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "path", Path(self.path))
        object.__setattr__(self, "mappings", _copied(self.mappings))
        object.__setattr__(self, "packages", _copied(self.packages))


def as_input(robot: RobotInput | str | os.PathLike[str]) -> RobotInput:
    """``robot`` itself, or a path read with no arguments, no extra packages and the environment's trust."""
    return robot if isinstance(robot, RobotInput) else RobotInput(Path(robot))
