"""A robot's mesh files, as the commands that copy or show them read them (``gen-robot import -o`` copies them
beside the spec, and they then travel into its package; ``export --mjcf`` copies them beside the model; ``view`` and
``render`` draw them into a page or picture): read only when they are what they claim to be.

A robot folder is someone else's, and a copy carries its files on: a ``meshes/part.stl`` that is a symbolic link to
``/etc/passwd`` would put the password file beside the spec and then into a package. So a mesh is read

* without following a symbolic link, neither the file itself nor a folder on its way below the robot's folder;
* only inside the robot's folder (:func:`robot_folder`: the ROS or Python package that ships the URDF, else the
  folder above a ``urdf/`` folder, else the URDF's own; no ``..`` out of it), or inside the package a
  ``package://`` URI names (:func:`mesh_root`);
* only as a plain file of at most :data:`~xacrokit.shared.mesh_solids.MAX_MESH_BYTES` (a larger one is refused before
  it is read);
* and it must read, with trimesh, as a mesh of the kind its suffix says, with at least one triangle.

What is copied as it is is streamed from the file when the output is written
(:class:`~xacrokit.shared.input_files.CopiedFile`), and only if it is still the file that was read: a run reads one
mesh at a time, whatever the robot's count. (The OBJ an export converts a mesh to is held until it is written; a
spec's staged meshes are read into memory while the staging lasts.)
"""

from __future__ import annotations

import errno
import gc
import hashlib
import io
import os
import threading
from collections import OrderedDict
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path, PurePosixPath
from typing import Any

from ..errors import XacrokitError
from ..shared.input_files import CopiedFile, InputError, Linked, open_below, read_below
from ..shared.mesh_solids import MAX_MESH_BYTES, MESH_SUFFIXES, is_relative
from ..shared.ros_packages import find_package, mesh_file


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


@dataclass(frozen=True)
class MeshRead:
    """A robot's mesh file, read safely once: the mesh trimesh reads from it, the file to stream into an output, and
    its first bytes (a binary STL's header and triangle count)."""

    mesh: Any
    copy: CopiedFile
    head: bytes


def mesh_to_copy(root: Path, source: Path, *, where: str = "") -> CopiedFile:
    """The file ``source``, a mesh inside the robot's folder ``root``, once it is safe to copy (streamed when it is
    written: :func:`read_mesh_below` says what is refused)."""
    return read_mesh_below(root, source, where=where, process=False).copy


# (the file's bytes, its suffix, how messages name it, the bytes' SHA-256, taken once for both) -> the mesh
MeshParser = Callable[[bytes, str, str, bytes], Any]


def read_mesh_below(
    root: Path, source: Path, *, where: str = "", process: bool = True, parse: MeshParser | None = None
) -> MeshRead:
    """``source``, a mesh file inside the robot's folder ``root``, read once and safely.

    Args:
        root: the robot's folder (:func:`robot_folder`), or the package a ``package://`` URI names.
        source: the mesh file (absolute, or relative to the working folder), not resolved.
        where: how the messages name the mesh (``robot.urdf:12: mesh 'meshes/part.stl'``).
        process: trimesh's ``process`` (merge duplicate vertices), for the reader that draws or converts it.
        parse: reads the bytes instead of trimesh (``gen-robot check`` reads STL with numpy-stl, which starts in a
            fifth of trimesh's time); it raises MeshCopyRefused for a file that is no mesh with a triangle.

    Raises:
        MeshCopyRefused: it is reached through a symbolic link, lies outside ``root``, is not a plain file of at most
            MAX_MESH_BYTES, or does not read as a mesh of its suffix's kind with a triangle.
    """
    said = where or str(source)
    pure = _inside(root, source, said)
    _collect_read_meshes()
    try:
        data, identity = read_below(root, pure.as_posix(), MAX_MESH_BYTES)
    except Linked as exc:
        raise MeshCopyRefused(
            f"{said}: {exc.strerror}; a robot's mesh is never read through a symbolic link (copy the file itself "
            "into the robot's folder, or name it by package://)"
        ) from None
    except InputError as exc:
        raise MeshCopyRefused(
            f"{said}: {exc.strerror}; a part's mesh is expected below {MAX_MESH_BYTES >> 20} MiB (simplify it in the "
            "CAD tool or a mesh tool)"
        ) from None
    except OSError as exc:
        raise MeshCopyRefused(f"{said}: cannot be read: {exc.strerror or exc}") from None
    suffix = pure.suffix.lower()
    digest = hashlib.sha256(data)
    if parse is not None:
        mesh = parse(data, suffix, said, digest.digest())
    else:
        mesh = _memo_or_read(data, digest.digest(), suffix, said, process)
    copy = CopiedFile(root, pure.as_posix(), identity, len(data), digest.hexdigest())
    return MeshRead(mesh, copy, data[:84])


SWEEP_BYTES = 2 * 1024 * 1024  # mesh bytes read between two collections of the meshes dropped since
FULL_SWEEPS = 16  # one collection in this many is a full one
_unswept = [0, 0]  # (bytes since the last collection, collections since the last full one)


def _collect_read_meshes() -> None:
    """Free the meshes read before and dropped since, once they add up to SWEEP_BYTES: trimesh's caches make
    reference cycles, which only the cyclic collector frees, and it seldom runs for a few large arrays (16 meshes of
    4 MB took 362 MB instead of 170 MB). Not on every mesh: a full collection per mesh made a page of TIAGo's 130
    small meshes 1 s slower. The young generations hold the meshes read since the last collection (the collector is
    paused while a stage runs: nothing else promotes them), so most collections take those alone (a full one scans
    every module loaded too: 23 ms in a check worker with pinocchio and MuJoCo, 88 times over the 129 corpus files);
    every FULL_SWEEPS-th is full, for meshes a caller held through a collection and dropped later."""
    if _unswept[0] >= SWEEP_BYTES:
        _unswept[1] = (_unswept[1] + 1) % FULL_SWEEPS
        gc.collect(2 if _unswept[1] == 0 else 1)
        _unswept[0] = 0


def _inside(root: Path, source: Path, said: str) -> PurePosixPath:
    """``source`` relative to ``root`` (a POSIX path), refused when it leaves root or is no mesh file by its name."""
    relative = os.path.relpath(os.path.abspath(source), os.path.abspath(root))
    pure = PurePosixPath(Path(relative).as_posix())
    if pure.is_absolute() or pure.parts[:1] == ("..",):
        raise MeshCopyRefused(f"{said}: it lies outside the robot's folder {root}; only files inside it are read")
    if pure.suffix.lower() not in MESH_SUFFIXES:
        raise MeshCopyRefused(f"{said}: not a mesh file by its name (read: {', '.join(MESH_SUFFIXES)})")
    return pure


def require_mesh_file(root: Path, source: Path, *, where: str = "") -> None:
    """Refuse (MeshCopyRefused) what :func:`read_mesh_below` refuses without reading the file: a link, a path out of
    ``root``, no mesh by its name, not a plain file, larger than MAX_MESH_BYTES (for a reader that opens the file
    itself: yourdfpy drawing a picture)."""
    said = where or str(source)
    pure = _inside(root, source, said)
    try:
        with open_below(root, pure.as_posix()) as (_, status):
            if status.st_size > MAX_MESH_BYTES:
                raise InputError(errno.EFBIG, f"it is larger than {MAX_MESH_BYTES:,} bytes")
    except Linked as exc:
        raise MeshCopyRefused(f"{said}: {exc.strerror}; a robot's mesh is never read through a symbolic link") from None
    except OSError as exc:
        raise MeshCopyRefused(f"{said}: cannot be read: {exc.strerror or exc}") from None


def require_mesh(data: bytes, suffix: str, said: str, process: bool) -> Any:
    """The mesh trimesh reads from ``data`` as the kind ``suffix`` says (a copy of the one read before from the same
    bytes, :class:`_ReadMeshes`); refused (MeshCopyRefused) when it reads none with a triangle."""
    return _memo_or_read(data, hashlib.sha256(data).digest(), suffix, said, process)


def _memo_or_read(data: bytes, digest: bytes, suffix: str, said: str, process: bool) -> Any:
    _unswept[0] += len(data)  # (what trimesh reads or copies makes the cycles a later sweep frees)
    key = (digest, suffix, process)
    kept = _READ_MESHES.get(key)
    if kept is None:
        kept = _read_mesh(data, suffix, said, process)
        _READ_MESHES.put(key, kept)
    # a copy for the caller, who may change it (export merges an STL's vertices, check scales them): the arrays,
    # visual and metadata copied, and the cache's items (none as trimesh reads a file: the copy is the mesh as read)
    return kept.copy(include_cache=True)


def _read_mesh(data: bytes, suffix: str, said: str, process: bool) -> Any:
    import trimesh  # (heavy: trimesh)

    try:
        mesh: Any = trimesh.load(io.BytesIO(data), file_type=suffix[1:], force="mesh", process=process)
        triangles = len(mesh.faces)
    except Exception:  # noqa: BLE001  (trimesh raises what its readers raise: every one means "not this kind")
        triangles = 0
    if not triangles:
        raise MeshCopyRefused(
            f"{said}: it does not read as a {suffix[1:].upper()} mesh with a triangle; a file read as a mesh must "
            "be one"
        )
    return mesh


READ_MESH_VERTICES = 8_000_000  # the vertices the meshes kept hold at most (about 200 MB of float64, faces apart)


class _ReadMeshes:
    """The meshes trimesh read in this process, by their file's bytes (SHA-256), suffix and ``process``, the least
    recently used dropped first once they hold more than READ_MESH_VERTICES: robots share meshes (the corpus's 129
    name 2,533 files, of 885 contents), ``view --watch`` reads a robot's again on every change, and a run of several
    features reads a robot's meshes in each. Sized by vertices, which functools.lru_cache cannot bound by; the
    standard library's OrderedDict keeps the order (its documented LRU use). Callers get copies, never these."""

    def __init__(self, most: int) -> None:
        self.most = most
        self.meshes: OrderedDict[tuple[bytes, str, bool], Any] = OrderedDict()
        self.vertices = 0
        self.lock = threading.Lock()  # (view --watch serves pages from threads)

    def get(self, key: tuple[bytes, str, bool]) -> Any:
        with self.lock:
            mesh = self.meshes.get(key)
            if mesh is not None:
                self.meshes.move_to_end(key)
            return mesh

    def put(self, key: tuple[bytes, str, bool], mesh: Any) -> None:
        with self.lock:
            if key in self.meshes or len(mesh.vertices) > self.most:
                return
            self.meshes[key] = mesh
            self.vertices += len(mesh.vertices)
            while self.vertices > self.most:
                _, dropped = self.meshes.popitem(last=False)
                self.vertices -= len(dropped.vertices)


_READ_MESHES = _ReadMeshes(READ_MESH_VERTICES)


def mesh_root(urdf: Path, filename: str, packages: Mapping[str, str | os.PathLike[str]]) -> Path:
    """The folder a robot's mesh ``filename`` must lie in to be read: the package a ``package://`` URI names (found
    as :func:`~xacrokit.shared.ros_packages.mesh_file` finds it), else the robot's folder (:func:`robot_folder`);
    for an absolute path or a ``file://`` URI, also a package folder the command was given that holds it.

    Raises:
        LookupError: the package is not known here. ValueError: another URI scheme.
    """

    if filename.startswith("package://"):
        return Path(find_package(filename[len("package://") :].partition("/")[0], packages))
    own = robot_folder(urdf)
    if is_relative(filename):
        return own
    target = os.path.abspath(mesh_file(filename, urdf.parent, packages))
    for folder in packages.values():
        if _holds(os.path.abspath(folder), target):
            return Path(os.path.abspath(folder))
    return own


def _holds(folder: str, path: str) -> bool:
    return os.path.commonpath([folder, path]) == folder


def mesh_reader(
    urdf: Path,
    packages: Mapping[str, str | os.PathLike[str]],
    *,
    process: bool = True,
    parse: MeshParser | None = None,
) -> Callable[[str], MeshRead]:
    """A reader of the meshes the robot at ``urdf`` names (by the URI as written): each found as
    :func:`~xacrokit.shared.ros_packages.mesh_file` finds it and read by :func:`read_mesh_below` below its
    :func:`mesh_root` (``process``, ``parse``: as there). The reader raises XacrokitError naming the mesh: not there,
    its package not known, or refused."""

    def read(filename: str) -> MeshRead:
        try:
            path, root = mesh_file(filename, urdf.parent, packages), mesh_root(urdf, filename, packages)
        except (LookupError, ValueError) as exc:
            raise XacrokitError(f"mesh {filename!r}: {exc}") from None
        if not path.is_file() and not path.is_symlink():
            raise XacrokitError(f"mesh {filename!r} is not there ({path})")
        return read_mesh_below(root, path, where=f"mesh {filename!r}", process=process, parse=parse)

    return read
