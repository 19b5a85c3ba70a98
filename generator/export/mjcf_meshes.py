"""The MJCF export's meshes (:mod:`xacrokit.export.mjcf`): one asset per (file, scale), each file copied into
``meshes/`` or, when MuJoCo cannot read it, converted by trimesh (to binary STL, or OBJ beyond STL_FACES); flat meshes
refused (:class:`FlatMesh`)."""

from __future__ import annotations

import os
import threading
from collections import OrderedDict
from collections.abc import Callable, Mapping
from pathlib import Path, PurePosixPath
from typing import Any

import numpy as np
from lxml import etree

from ..errors import XacrokitError
from ..reader.mesh_copies import MeshRead, mesh_reader
from ..shared.input_files import CopiedFile
from .mjcf_actuators import num

READABLE = (".obj", ".msh")  # what MuJoCo reads as it is (binary STL too: decided by looking at the file)
STL_FACES = 200_000  # the most triangles MuJoCo's STL reader takes


def _scale(text: str) -> str:
    try:
        values = [float(v) for v in text.split()]
    except ValueError:
        values = []
    if len(values) != 3 or not all(np.isfinite(values)):
        raise XacrokitError(f"mesh scale {text!r} is not 3 finite numbers")
    return " ".join(num(v) for v in values)


class FlatMesh(XacrokitError):
    """A mesh with all its vertices in one plane (an ArUco marker's sticker): MuJoCo cannot make its convex hull, and
    it has no volume to collide with; left out of the model, visual or collision, with a note."""


class Meshes:
    """The mesh assets: one per (file, scale), the file copied into meshes/ (converted when MuJoCo cannot read it)."""

    def __init__(
        self, read: Callable[[str], MeshRead], written: dict[str, bytes | CopiedFile], notes: list[str]
    ) -> None:
        self.read = read  # (mesh_copies.mesh_reader: safe, bounded, one read per file)
        self.written = written  # NAME in meshes/ -> bytes, or the file streamed there
        self.notes = notes
        self.assets: list[Any] = []
        self.names: dict[tuple[str, str], str] = {}
        self.files: dict[str, str] = {}  # the file read -> its file name in meshes/
        self.found: dict[str, str] = {}  # the URI as written -> the file read
        self.refused: dict[str, XacrokitError] = {}  # the URI as written -> why it is not read (said once per use)
        self.keep_points = False  # keep each mesh's vertices (a free robot standing on a floor needs its lowest)
        self.vertices: dict[str, np.ndarray] = {}  # the file read -> its distinct vertices, when kept
        self.points: dict[str, np.ndarray] = {}  # an asset's name -> its vertices scaled, when kept

    def name(self, filename: str, scale: str | None) -> str:
        if filename in self.refused:  # (a mesh named by many visuals is read, and refused, once)
            raise self.refused[filename]
        path = self.found.get(filename)
        if path is None:
            try:
                read = self.read(filename)
                path = str(read.copy.root / read.copy.relative)
                if path not in self.files:
                    self.files[path] = self._copy(read, filename)
            except XacrokitError as exc:
                self.refused[filename] = exc
                raise
            self.found[filename] = path
        key = (path, " ".join(scale.split()) if scale else "1 1 1")
        if key in self.names:
            return self.names[key]
        name = f"mesh{len(self.assets)}_{Path(self.files[path]).stem}"
        element = etree.Element("mesh", name=name, file=self.files[path], inertia="shell")
        if scale:
            element.set("scale", _scale(scale))
        if path in self.vertices:
            factors = [float(v) for v in element.get("scale", "1 1 1").split()]
            self.points[name] = self.vertices[path] * np.array(factors)  # (elementwise: the same bits anywhere)
        self.assets.append(element)
        self.names[key] = name
        return name

    def _copy(self, read: MeshRead, filename: str) -> str:
        source = Path(read.copy.relative)
        stem = "".join(c if c.isalnum() or c in "_-" else "_" for c in source.stem)[:60] or "mesh"
        suffix = source.suffix.lower()
        as_read = (read.copy.sha256, suffix, bool(read.mesh.metadata.get("processed")))  # (a conversion's key)
        copied = suffix in READABLE or (
            suffix == ".stl" and _binary_stl_faces(read.head, read.copy.size) in range(1, STL_FACES + 1)
        )
        # (an STL copied as it is need not be merged when it is far from flat: merging only drops repeated vertices
        # and ones within 1e-8 of another, which moves the ratio of its spreads far less than the 1e5 between the
        # 1e-4 here and the 1e-9 that makes a mesh flat)
        spread = _spread(read.mesh.vertices) if copied and not self.keep_points else None
        solid = spread is not None and spread[0] > 1e-4 * spread[1]
        mesh = read.mesh if solid else _merged(read.mesh)
        if not solid:
            spread = _spread(mesh.vertices)
        if spread is None or spread[0] <= 1e-9 * spread[1]:
            raise FlatMesh(f"mesh {filename!r} is flat (all its vertices in one plane): MuJoCo cannot take it")
        if self.keep_points:
            self.vertices[str(read.copy.root / read.copy.relative)] = _hull_points(np.asarray(mesh.vertices, float))
        data: bytes | CopiedFile = read.copy
        if copied:
            out = f"{stem}{suffix}"
        elif len(mesh.faces) <= STL_FACES:  # (binary STL: trimesh writes it 30-40 times faster than OBJ text, and
            # MuJoCo keeps a mesh's vertices in single precision, as the STL holds them)
            data = _converted(mesh, (*as_read, "stl"))
            out = f"{stem}.stl"
            self.notes.append(f"mesh {filename!r} converted to binary STL for MuJoCo")
        else:
            data = _converted(mesh, (*as_read, "obj"))
            out = f"{stem}.obj"
            self.notes.append(f"mesh {filename!r} converted to OBJ for MuJoCo")
        taken = set(self.files.values())
        count = 1
        while out in taken:
            out = f"{stem}_{count}{Path(out).suffix}"
            count += 1
        self.written[out] = data
        return out


def export_reader(urdf: Path, packages: Mapping[str, str | os.PathLike[str]]) -> Callable[[str], MeshRead]:
    """The export's mesh reader: :func:`~xacrokit.reader.mesh_copies.mesh_reader`, merging duplicate vertices as it
    reads (trimesh's ``process``), but for an STL, which is read as it is and merged only when the export needs its
    vertices (:func:`_merged`): most are binary STL files copied as they are, and merging took a fifth of exporting a
    robot of them. (An STL merged later is the mesh merged as it is read: every STL of the real-robot corpus, 802,
    gives the same vertices, faces and metadata either way; trimesh's readers of the other kinds differ.)"""
    merged, plain = mesh_reader(urdf, packages), mesh_reader(urdf, packages, process=False)

    def read(filename: str) -> MeshRead:
        return (plain if PurePosixPath(filename).suffix.lower() == ".stl" else merged)(filename)

    return read


CONVERTED_BYTES = 128 << 20  # the converted files kept in a process hold at most this many bytes
# (the file's SHA-256, its suffix, whether its reader merged its vertices, the kind written) -> the bytes written
_CONVERTED: OrderedDict[tuple[str, str, bool, str], bytes] = OrderedDict()
_KEPT = [0]  # the bytes _CONVERTED holds
_CONVERTING = threading.Lock()  # (export_mjcf is public: exports from threads share the kept bytes)


def _converted(mesh: Any, key: tuple[str, str, bool, str]) -> bytes:
    """``mesh`` (merged) as trimesh writes it in the kind ``key`` ends with, "stl" (binary) or "obj" (text); kept in
    this process by the file's bytes and how they were read (``key``), the least recently used dropped first past
    CONVERTED_BYTES: robots share meshes (the real-robot corpus's Stretch, B1 and iCub variants; a fleet), and the
    Go1's two OBJ files of 200,000 triangles took 3.3 s of its 10 s export. The same bytes read the same way give the
    same mesh (vertices, faces, colours, name) and so the same file (tests/export/test_mjcf_deterministic.py)."""
    with _CONVERTING:
        data = _CONVERTED.get(key)
        if data is not None:
            _CONVERTED.move_to_end(key)
            return data
    if key[3] == "stl":  # (converted outside the lock: two threads converting one mesh write the same bytes)
        data = bytes(mesh.export(file_type="stl"))
    else:
        exported = mesh.export(file_type="obj", include_normals=False, include_texture=False)
        data = exported.encode("utf-8") if isinstance(exported, str) else bytes(exported)
    with _CONVERTING:
        if len(data) <= CONVERTED_BYTES and key not in _CONVERTED:
            _CONVERTED[key] = data
            _KEPT[0] += len(data)
        while _KEPT[0] > CONVERTED_BYTES:
            _KEPT[0] -= len(_CONVERTED.popitem(last=False)[1])
    return data


def _merged(mesh: Any) -> Any:
    """The mesh with its duplicate vertices merged (in place), as a reader's ``process`` gives it."""
    if not mesh.metadata.get("processed"):
        mesh.process()
    return mesh


def _spread(vertices: np.ndarray) -> tuple[float, float] | None:
    """A mesh's thinnest and widest spread about its centre (the singular values of its centred vertices); None for
    fewer than 4 vertices."""
    if len(vertices) < 4:
        return None
    spread = np.linalg.svd(vertices - vertices.mean(axis=0), compute_uv=False)
    return float(spread[-1]), float(spread[0])


def _hull_points(vertices: np.ndarray) -> np.ndarray:
    """The vertices of a mesh's convex hull (what MuJoCo collides with; a few thousand of a mesh's hundreds of
    thousands, kept while the model is written), in the mesh's order; all of them when qhull cannot make it."""
    from scipy.spatial import ConvexHull, QhullError  # (heavy: scipy, for a free robot's meshes only)

    try:
        return vertices[np.sort(ConvexHull(vertices).vertices)]
    except (QhullError, ValueError):
        return vertices


def _binary_stl_faces(head: bytes, size: int) -> int:
    """The triangle count of a binary STL of ``size`` bytes that starts with ``head`` (its header's count, when the
    size agrees), -1 for anything else (an STL in text, which MuJoCo cannot read)."""
    if len(head) >= 84:
        count = int.from_bytes(head[80:84], "little")
        if 84 + 50 * count == size:
            return count
    return -1
