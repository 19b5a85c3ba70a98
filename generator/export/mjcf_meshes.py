"""The MJCF export's meshes (:mod:`xacrokit.export.mjcf`): one asset per (file, scale), each file copied into
``meshes/`` or, when MuJoCo cannot read it, converted to OBJ by trimesh; flat meshes refused (:class:`FlatMesh`)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ..errors import XacrokitError
from ..shared.mesh_solids import read_mesh
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

    def __init__(self, resolve: Any, written: dict[str, bytes], notes: list[str]) -> None:
        self.resolve = resolve
        self.written = written  # meshes/NAME -> bytes
        self.notes = notes
        self.assets: list[Any] = []
        self.names: dict[tuple[str, str], str] = {}
        self.files: dict[str, str] = {}  # resolved path -> file name in meshes/

    def name(self, filename: str, scale: str | None) -> str:
        from lxml import etree

        path = str(self.resolve(filename))
        key = (path, " ".join(scale.split()) if scale else "1 1 1")
        if key in self.names:
            return self.names[key]
        if path not in self.files:
            self.files[path] = self._copy(Path(path), filename)
        name = f"mesh{len(self.assets)}_{Path(self.files[path]).stem}"
        element = etree.Element("mesh", name=name, file=self.files[path], inertia="shell")
        if scale:
            element.set("scale", _scale(scale))
        self.assets.append(element)
        self.names[key] = name
        return name

    def _copy(self, path: Path, filename: str) -> str:
        if not path.is_file():
            raise XacrokitError(f"mesh {filename!r} is not there ({path})")
        data = path.read_bytes()
        mesh = read_mesh(path, filename)
        spread = np.linalg.svd(mesh.vertices - mesh.vertices.mean(axis=0), compute_uv=False)
        if len(mesh.vertices) < 4 or spread[-1] <= 1e-9 * spread[0]:
            raise FlatMesh(f"mesh {filename!r} is flat (all its vertices in one plane): MuJoCo cannot take it")
        stem = "".join(c if c.isalnum() or c in "_-" else "_" for c in path.stem)[:60] or "mesh"
        suffix = path.suffix.lower()
        if suffix in READABLE or (suffix == ".stl" and _binary_stl_faces(data) in range(1, STL_FACES + 1)):
            out = f"{stem}{suffix}"
        else:
            exported = mesh.export(file_type="obj", include_normals=False, include_texture=False)
            data = exported.encode("utf-8") if isinstance(exported, str) else bytes(exported)
            out = f"{stem}.obj"
            self.notes.append(f"mesh {filename!r} converted to OBJ for MuJoCo")
        taken = set(self.files.values())
        count = 1
        while out in taken:
            out = f"{stem}_{count}{Path(out).suffix}"
            count += 1
        self.written[out] = data
        return out


def _binary_stl_faces(data: bytes) -> int:
    """The triangle count of a binary STL (its header's count, when the size agrees), -1 for anything else (an STL
    in text, which MuJoCo cannot read)."""
    if len(data) >= 84:
        count = int.from_bytes(data[80:84], "little")
        if 84 + 50 * count == len(data):
            return count
    return -1
