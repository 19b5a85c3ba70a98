"""Mesh files a spec names: where they are, and the volume, centre of mass and inertia of the solid they enclose.

trimesh reads the file and integrates over the closed surface (exact for a polyhedron: a box mesh has the box's
tensor); a surface that does not enclose a solid (not watertight, faces wound inconsistently, or wound inside out so
that the volume is negative) has no meaningful volume, so it is refused with what to do instead. Read once per file
and scale in a run (the validate and resolve stages both ask).
"""

from __future__ import annotations

import functools
import hashlib
import os
from dataclasses import dataclass
from pathlib import Path, PurePosixPath
from typing import TYPE_CHECKING, Any

from .ros_packages import mesh_file, with_nearby_packages

if TYPE_CHECKING:
    pass

MAX_MESH_BYTES = 32 * 1024 * 1024  # a CAD part's mesh is a few MB (the largest of 600 in the corpus: 15 MB); trimesh
# takes about 13 times a binary STL's size in memory to read it, so this keeps a read under 0.5 GB
MESH_FOLDER = "meshes"  # where a package keeps the meshes gen-robot copies or makes
MESH_SUFFIXES = (".stl", ".obj", ".ply", ".dae", ".glb", ".gltf", ".off")  # what a copied mesh file may be


class MeshError(ValueError):
    """A mesh file that cannot give a body's inertia; the message says why and what to do."""


@dataclass(frozen=True)
class MeshSolid:
    """The solid a closed mesh encloses, after its scale, in the mesh's own frame (m, m^3; ``unit_inertia`` is the
    tensor about the centre of mass for a density of 1 kg/m^3: multiply by the density)."""

    volume: float
    center: tuple[float, float, float]
    unit_inertia: tuple[tuple[float, float, float], ...]
    extents: tuple[float, float, float]  # the bounding box's edges


def is_relative(filename: str) -> bool:
    """Whether a spec's mesh file name is a path relative to the spec (no URI scheme, not absolute): gen-robot copies
    such a file into the package it writes."""
    return "://" not in filename and not PurePosixPath(filename).is_absolute() and not Path(filename).is_absolute()


def package_mesh_path(filename: str) -> str:
    """Where gen-robot copies a spec's relative mesh in the package it writes: below ``meshes/``, the spec's own
    folders kept (``cad/bracket.stl`` -> ``meshes/cad/bracket.stl``), a leading ``meshes/`` not doubled
    (``meshes/visual/arm.obj`` -> ``meshes/visual/arm.obj``). ``filename`` stays inside the spec's folder (validate
    refuses one that leaves it), so its normal form has no ``..``."""
    parts = PurePosixPath(os.path.normpath(PurePosixPath(filename).as_posix())).parts
    return PurePosixPath(MESH_FOLDER, *(parts[1:] if parts[:1] == (MESH_FOLDER,) else parts)).as_posix()


def mesh_path(filename: str, spec_path: str | os.PathLike[str]) -> Path:
    """The file a spec's mesh names: ``package://PKG/...`` (the package found as ``gen-robot check`` finds it),
    ``file:///abs/path``, an absolute path, or a path relative to the spec's folder.

    Raises:
        MeshError: the package is not known here, or the URI's scheme is not one of those.
    """
    try:
        return mesh_file(filename, Path(spec_path).parent, with_nearby_packages(spec_path))
    except (LookupError, ValueError) as exc:
        raise MeshError(str(exc)) from None


def mesh_solid(path: Path, scale: tuple[float, float, float]) -> MeshSolid:
    """The solid ``path`` encloses, scaled by ``scale`` (negative factors mirror it).

    Raises:
        MeshError: the file cannot be read as a mesh, or it does not enclose a solid.
    """
    try:
        stat = path.stat()
    except OSError as exc:
        raise MeshError(f"cannot read {path}: {exc.strerror}") from None
    return _solid(str(path.resolve()), stat.st_size, stat.st_mtime_ns, scale)


@functools.lru_cache(maxsize=256)
def _solid(path: str, size: int, mtime: int, scale: tuple[float, float, float]) -> MeshSolid:
    """(size and mtime: a file changed on disk is read again)"""
    import numpy as np  # (heavy: numpy)
    import trimesh  # (heavy: trimesh)

    if size > MAX_MESH_BYTES:
        raise MeshError(f"{path} is {size / 2**20:.0f} MiB; a part's mesh is expected below {MAX_MESH_BYTES >> 20} MiB")
    try:
        mesh = trimesh.load(path, force="mesh")
    except Exception as exc:  # noqa: BLE001  (trimesh raises what its readers raise: every one means "not readable")
        raise MeshError(
            f"cannot read {path} as a mesh ({type(exc).__name__}: {exc}); STL, OBJ and PLY are read (export "
            "the part as binary STL)"
        ) from None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise MeshError(f"{path} holds no triangles; export the part as a closed triangle mesh (binary STL)")
    # on the vertices themselves: trimesh's apply_transform skips a matrix within 1e-8 of the identity (a scale of
    # 1 + 5e-9, an offset of 1e-9 m would be lost); a mirroring scale turns the faces back outwards
    mesh.vertices = mesh.vertices * np.asarray(scale, dtype=float)
    if scale[0] * scale[1] * scale[2] < 0:
        mesh.invert()
    name = Path(path).name
    if not mesh.is_watertight:
        raise MeshError(
            f"{name} is not watertight (its surface has holes or loose edges), so it encloses no volume and its "
            "inertia cannot be computed; close it in the CAD tool or a mesh repair tool, or give mass and inertia: "
            "with its origin"
        )
    if not mesh.is_winding_consistent:
        raise MeshError(
            f"{name} has faces wound inconsistently (some normals point in, some out), so its volume is wrong; fix "
            "the normals in the CAD tool or a mesh repair tool, or give mass and inertia: with its origin"
        )
    if not mesh.volume > 0:
        raise MeshError(
            f"{name} encloses a negative volume ({mesh.volume:.3g} m^3): its faces are wound inside out; flip its "
            "normals, or give mass and inertia: with its origin"
        )
    # integrated about the middle of its bounds: far from the file's origin, the sums over its faces lose digits
    middle = mesh.bounds.mean(axis=0)
    mesh.vertices = mesh.vertices - middle  # (not apply_translation, which skips an offset below 1e-8)
    mesh.density = 1.0
    inertia = np.asarray(mesh.moment_inertia, dtype=float)
    center = tuple(float(v) + 0.0 for v in mesh.center_mass + middle)
    extents = tuple(float(v) for v in mesh.extents)
    return MeshSolid(
        volume=float(mesh.volume),
        center=(center[0], center[1], center[2]),
        unit_inertia=tuple((float(r[0]) + 0.0, float(r[1]) + 0.0, float(r[2]) + 0.0) for r in inertia),
        extents=(extents[0], extents[1], extents[2]),
    )


def mesh_hull(path: Path) -> tuple[str, bytes]:
    """The convex hull of the mesh at ``path`` as a binary STL (its own units: a link's ``scale`` applies to it as
    to the mesh) and the file name a package keeps it under, made from its content (meshes alike share a hull).

    Raises:
        MeshError: the file cannot be read as a mesh, or its hull has no volume (a flat part).
    """
    try:
        stat = path.stat()
    except OSError as exc:
        raise MeshError(f"cannot read {path}: {exc.strerror}") from None
    return _hull(str(path.resolve()), stat.st_size, stat.st_mtime_ns)


@functools.lru_cache(maxsize=64)
def _hull(path: str, size: int, mtime: int) -> tuple[str, bytes]:
    """(size and mtime: a file changed on disk is read again)"""

    import trimesh  # (heavy: trimesh)

    if size > MAX_MESH_BYTES:
        raise MeshError(f"{path} is {size / 2**20:.0f} MiB; a part's mesh is expected below {MAX_MESH_BYTES >> 20} MiB")
    try:
        mesh: Any = trimesh.load(path, force="mesh")
        hull = mesh.convex_hull
    except Exception as exc:  # noqa: BLE001  (trimesh and qhull raise what they meet: every one means "no hull")
        raise MeshError(f"cannot make the convex hull of {Path(path).name} ({type(exc).__name__}: {exc})") from None
    if not hull.volume > 0:
        raise MeshError(f"{Path(path).name} is flat: its convex hull has no volume to collide with")
    data = bytes(hull.export(file_type="stl"))
    return f"{MESH_FOLDER}/xacrokit/hull_{hashlib.sha256(data).hexdigest()[:16]}.stl", data


TUBE_SIDES = 64  # a tube's mesh: its circles as 64-gons (the radius' error at mid-side: 1 - cos(pi/64) = 0.12%)


def tube_obj(inner: float, outer: float, length: float) -> str:
    """A hollow cylinder along z, centred on the origin, as Wavefront OBJ text (trimesh's annulus and OBJ writer): the
    geometry URDF has no element for. OBJ because it is text every consumer reads (MuJoCo reads no ASCII STL)."""
    import trimesh  # (heavy: trimesh)

    mesh = trimesh.creation.annulus(r_min=inner, r_max=outer, height=length, sections=TUBE_SIDES)
    text: str = trimesh.exchange.obj.export_obj(mesh, include_normals=False, include_texture=False, digits=12)
    return text
