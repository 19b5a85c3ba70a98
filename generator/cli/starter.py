"""``gen-robot new``: a commented starter spec to edit, one per kind of robot."""

from __future__ import annotations

import os
import re
from pathlib import Path

from ..errors import XacrokitError
from ..render import environment

KINDS = ("arm", "mobile", "humanoid")


MAX_NAME = 200  # (the schema's limit on a robot name: the files made from it must fit the file system)


def starter_text(name: str, kind: str = "arm") -> str:
    """The starter spec for robot ``name`` of ``kind`` (arm, mobile or humanoid)."""
    if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name):
        raise XacrokitError(f"robot name {name!r} must be letters, digits and _, not starting with a digit")
    from ..validate.names import robot_name_problem  # (the spec's own rule: a starter the spec refuses is no start)

    problem = robot_name_problem(name)
    if problem is not None or len(name) > MAX_NAME:
        raise XacrokitError(f"robot name {name!r} {problem or f'is over {MAX_NAME} characters'}; choose another name")
    if kind not in KINDS:
        raise XacrokitError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    # No schema modeline: the only schema file we could name is the installed copy, an absolute path of this machine
    # that breaks once the spec is shared or the venv goes; the starter says how to get one next to the spec instead.
    return environment().get_template(f"specs/{kind}.yaml.j2").render(name=name)


def write_starter(name: str, *, kind: str = "arm", output: str | Path | None = None) -> Path:
    """Write the starter spec; an existing file is never overwritten.

    ``output``: the spec file (a name ending in .yaml or .yml), or a folder for ``NAME.yaml`` (an existing folder, a
    name ending in a slash, or a name without such a suffix); missing folders are made. Default: ``./NAME.yaml``.
    """
    text = starter_text(name, kind)  # (the name is checked before any folder is made)
    path = Path(output) if output else Path.cwd() / f"{name}.yaml"
    as_folder = str(output).endswith(("/", os.sep)) or path.is_dir() or path.suffix.lower() not in (".yaml", ".yml")
    if output and as_folder:
        path = path / f"{name}.yaml"
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise XacrokitError(
            f"cannot make the folder {path.parent}: {exc.strerror or exc} (a file in the way?)"
        ) from None
    if os.path.lexists(path):  # (never overwritten, not even a starter of ours: it may be someone's first edit away)
        raise XacrokitError(f"{path} already exists; not overwritten (choose another name or -o PATH)")
    from ..write.outputs import output_file  # (atomic, never through a link; an interrupted run is repaired)

    output_file(path, text)
    return path
