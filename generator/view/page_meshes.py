"""The meshes of a ``gen-robot view`` page (:mod:`xacrokit.view.page`): a table with each mesh file once, however many
visuals name it and by whatever URI, which the visuals refer to by index (scale and colour stay with each visual).

A mesh is embedded as the triangles the page draws: its vertices merged by position, then split again where faces
meet at a crease (:func:`drawn`), so that the normals three.js computes keep the creases (a COLLADA mesh as trimesh
reads it held three to five times as many vertices, and drew much the same), as two little-endian arrays, each
deflated (zlib) and in base64: ``positions`` float32 x, y, z and ``indices`` three per triangle, uint16 when every
index is below 0xFFFF (which WebGL 2 reserves to restart a primitive), else uint32 (``indexType``). The page
inflates them with the browser's DecompressionStream."""

from __future__ import annotations

import base64
import zlib
from collections.abc import Callable
from typing import Any

import numpy as np

from ..errors import XacrokitError

UINT16_INDICES = 0xFFFF  # indices below this fit uint16 (0xFFFF itself restarts a primitive in WebGL 2)
CREASE = np.radians(20.0)  # faces meeting at more than this are drawn with a crease between them (trimesh's angle)
# zlib's fastest level: the Panda's and Go1's pages within 1 % of the default level's size, at a fifth of the time
DEFLATE_LEVEL = 1


class PageMeshes:
    """The page's table of meshes, filled as visuals ask for them (``read``: a
    :func:`~xacrokit.reader.mesh_copies.mesh_reader`). Its twin for MuJoCo's assets, which are also keyed by scale,
    is :class:`xacrokit.export.mjcf_meshes.Meshes`."""

    def __init__(self, read: Callable[[str], Any]) -> None:
        self.read = read
        self.table: list[dict[str, str]] = []
        self.found: dict[str, int] = {}  # the URI as written -> its entry in the table
        self.files: dict[str, int] = {}  # the file read -> its entry in the table
        self.refused: dict[str, XacrokitError] = {}  # the URI as written -> why it is not read (said once per use)

    def index(self, filename: str) -> int:
        """The entry of the mesh file ``filename`` names, read and added the first time.

        Raises:
            XacrokitError: the mesh cannot be found or read (as the reader says; every time it is asked for).
        """
        if filename in self.refused:
            raise self.refused[filename]
        if filename not in self.found:
            try:
                read = self.read(filename)
            except XacrokitError as exc:
                self.refused[filename] = exc
                raise
            path = str(read.copy.root / read.copy.relative)
            if path not in self.files:
                self.files[path] = len(self.table)
                self.table.append({"uri": filename, **mesh_arrays(*drawn(read.mesh))})
            self.found[filename] = self.files[path]
        return self.found[filename]


def drawn(mesh: Any) -> tuple[np.ndarray, np.ndarray]:
    """The vertices and triangles the page draws for ``mesh`` (a trimesh mesh): merged by position, then split where
    faces meet at more than CREASE, so that each smooth patch has vertices of its own. (trimesh.graph.smooth_shade
    does much the same, large flat facets apart, but makes a submesh per patch: the page took three times as long
    on robots of many small patches.)"""
    import trimesh  # (heavy: trimesh)

    plain = trimesh.Trimesh(np.asarray(mesh.vertices), np.asarray(mesh.faces), process=True)
    vertices, faces = np.asarray(plain.vertices, dtype=float), np.asarray(plain.faces, dtype=np.int64)
    if len(faces) == 0:
        return vertices, faces
    smooth = plain.face_adjacency[plain.face_adjacency_angles < CREASE]
    patch = trimesh.graph.connected_component_labels(smooth, node_count=len(faces))
    corners = patch[:, None].astype(np.int64) * len(vertices) + faces  # (a vertex once per patch that uses it)
    kept, inverse = np.unique(corners, return_inverse=True)
    return vertices[kept % len(vertices)], inverse.reshape(-1, 3)


def mesh_arrays(vertices: np.ndarray, faces: np.ndarray) -> dict[str, str]:
    """A mesh's entry in the page: ``positions``, ``indices`` (deflated, base64) and ``indexType``."""
    small = faces.size == 0 or int(faces.max()) < UINT16_INDICES
    return {
        "positions": _packed(np.asarray(vertices, dtype="<f4")),
        "indices": _packed(np.asarray(faces, dtype="<u2" if small else "<u4")),
        "indexType": "uint16" if small else "uint32",
    }


def _packed(array: np.ndarray) -> str:
    return base64.b64encode(zlib.compress(array.tobytes(), DEFLATE_LEVEL)).decode("ascii")
