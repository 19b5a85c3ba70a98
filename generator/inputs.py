"""What the commands that read a robot share (graph, view, render): a URDF, xacro document, spec or scene read as URDF
text, with the packages its ``package://`` URIs may name (a spec's own meshes staged where its package will carry
them). ``packages.mesh_file`` resolves a mesh URI with them."""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

from .errors import XacrokitError

Packages = dict[str, str | os.PathLike[str]]


@contextlib.contextmanager
def robot_text(
    path: str | os.PathLike[str],
    mappings: Mapping[str, str] | None = None,
    package_paths: Mapping[str, str | os.PathLike[str]] | None = None,
    *,
    meshes: bool = True,
) -> Iterator[tuple[str, Packages]]:
    """(URDF text, packages) of the robot at ``path``, for the ``with`` block (a spec's staged meshes live that long;
    ``meshes=False`` for a reader of the text alone: nothing staged).

    Raises:
        XacrokitError: unreadable input, or name:=value arguments for input that is not xacro.
        SpecErrors: an invalid spec (located).
    """
    from .check.run import input_kind, load_urdf
    from .fileio import staged_packages
    from .packages import with_nearby_packages

    where = Path(path)
    kind = input_kind(where)
    if mappings and kind != "xacro":
        raise XacrokitError("name:=value arguments only apply to xacro input")
    packages = package_paths if kind == "spec" else with_nearby_packages(where, package_paths)
    carried: dict[str, Any] = {}
    text, _, _, _ = load_urdf(where, kind, mappings, packages, carried)
    with staged_packages(carried if meshes else {}) as staged:
        yield text, {**staged, **(packages or {})}
