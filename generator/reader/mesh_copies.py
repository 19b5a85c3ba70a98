"""Mesh files a command copies out of a robot's folder (``gen-robot import -o``; the spec's meshes then travel into
its package): read only when they are what they claim to be.

A robot folder is someone else's, and a copy carries its files on: a ``meshes/part.stl`` that is a symbolic link to
``/etc/passwd`` would put the password file beside the spec and then into a package. So a copied mesh is read

* without following a symbolic link, neither the file itself nor a folder on its way below the robot's folder;
* only inside the robot's folder (:func:`robot_folder`: the ROS or Python package that ships the URDF, else the
  folder above a ``urdf/`` folder, else the URDF's own; no ``..`` out of it, no absolute path);
* only as a plain file of at most :data:`~xacrokit.shared.mesh_solids.MAX_MESH_BYTES` (a larger one is refused before
  it is read);
* and it must read, with trimesh, as a mesh of the kind its suffix says, with at least one triangle.
"""

from __future__ import annotations

import io
import os
from pathlib import Path, PurePosixPath
from typing import Any

from ..errors import XacrokitError
from ..shared.input_files import InputError, Linked, read_below
from ..shared.mesh_solids import MAX_MESH_BYTES, MESH_SUFFIXES


def robot_folder(urdf: Path) -> Path:
    """The folder a robot's relative meshes must lie in: the package that ships the URDF, that is the nearest folder
    above it that is a ROS package (a package.xml) or a Python package (an ``__init__.py``: robot descriptions
    installed from PyPI, whose grippers name a sibling's meshes); else the folder above the URDF's when that is named
    ``urdf`` (the ROS layout: ``urdf/robot.urdf`` names ``../meshes/part.stl``); else the URDF's own folder. Found
    from the path as given (no link is resolved)."""
    here = Path(os.path.abspath(urdf)).parent
    for folder in (here, *here.parents):
        if (folder / "package.xml").is_file() or (folder / "__init__.py").is_file():
            return folder
    return here.parent if here.name == "urdf" else here


class MeshCopyRefused(XacrokitError):
    """A mesh file that is not copied: a link, outside the robot's folder, too large, or not a mesh."""


def mesh_to_copy(root: Path, source: Path, *, where: str = "") -> bytes:
    """The bytes of ``source``, a mesh file inside the robot's folder ``root``, once they are safe to copy.

    Args:
        root: the robot's folder (:func:`robot_folder`).
        source: the mesh file (absolute, or relative to the working folder), not resolved.
        where: how the messages name the mesh (``robot.urdf:12: mesh 'meshes/part.stl'``).

    Raises:
        MeshCopyRefused: it is reached through a symbolic link, lies outside ``root``, is not a plain file of at most
            MAX_MESH_BYTES, or does not read as a mesh of its suffix's kind.
    """
    said = where or str(source)
    relative = os.path.relpath(os.path.abspath(source), os.path.abspath(root))
    pure = PurePosixPath(Path(relative).as_posix())
    if pure.is_absolute() or pure.parts[:1] == ("..",):
        raise MeshCopyRefused(f"{said}: it lies outside the robot's folder {root}; only files inside it are copied")
    suffix = pure.suffix.lower()
    if suffix not in MESH_SUFFIXES:
        raise MeshCopyRefused(f"{said}: not a mesh file by its name (copied: {', '.join(MESH_SUFFIXES)})")
    try:
        data, _ = read_below(root, pure.as_posix(), MAX_MESH_BYTES)
    except Linked as exc:
        raise MeshCopyRefused(
            f"{said}: {exc.strerror}; a copied mesh is never reached through a symbolic link (copy the file itself "
            "into the robot's folder, or name it by package://)"
        ) from None
    except (InputError, OSError) as exc:
        raise MeshCopyRefused(f"{said}: cannot be copied: {exc.strerror or exc}") from None
    _require_mesh(data, suffix, said)
    return data


def _require_mesh(data: bytes, suffix: str, said: str) -> None:
    """Refuse bytes that trimesh does not read as a mesh of the kind ``suffix`` says, with a triangle."""
    import trimesh

    try:
        mesh: Any = trimesh.load(io.BytesIO(data), file_type=suffix[1:], force="mesh", process=False)
        triangles = len(mesh.faces)
    except Exception:  # noqa: BLE001  (trimesh raises what its readers raise: every one means "not this kind")
        triangles = 0
    if not triangles:
        raise MeshCopyRefused(
            f"{said}: it does not read as a {suffix[1:].upper()} mesh with a triangle; a file copied as a mesh must "
            "be one"
        )
