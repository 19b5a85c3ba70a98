"""A mesh as Wavefront OBJ text for MuJoCo (:mod:`xacrokit.export.mjcf_meshes` converts what MuJoCo cannot read):
the bytes trimesh's ``export_obj`` writes without normals and texture (a header line, the mesh's name when it has one,
``v`` lines with eight decimals, with the vertex colours when it has them, then ``f`` lines), written with one
%-format over Python floats. trimesh formats every number with ``str.format`` on numpy scalars, which took more than
half of exporting a robot of COLLADA meshes (the Go1: 7 of 12 s); tests/export/test_obj_text.py holds the bytes equal
to trimesh's."""

from __future__ import annotations

from typing import Any

import numpy as np

HEADER = "# https://github.com/mikedh/trimesh"  # (trimesh's, kept: the files stay the bytes they were)
DIGITS = 8  # decimals of a vertex number (trimesh's default)


def obj_text(mesh: Any) -> bytes:
    """The OBJ file of ``mesh`` (a trimesh Trimesh), as UTF-8 bytes."""
    from trimesh.visual.color import to_float  # (heavy: trimesh, loaded already by the mesh's reader)

    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    visual = mesh.visual
    if visual.kind in ("vertex", "face") and len(visual.vertex_colors):  # (trimesh writes r g b after x y z)
        vertices = np.column_stack((vertices, to_float(visual.vertex_colors[:, :3])))
    faces = np.asarray(mesh.faces, dtype=np.int64) + 1
    parts = [f"v {_rows(vertices, f'%.{DIGITS}f', 'v')}", f"f {_rows(faces, '%d', 'f')}"]
    if "name" in mesh.metadata:
        parts.insert(0, f"\no {mesh.metadata['name']}")
    return "\n".join([HEADER, "\n".join(parts), "\n"]).encode("utf-8")


def _rows(array: np.ndarray, number: str, tag: str) -> str:
    """The rows of a 2-D array, numbers separated by a space, rows by a newline and ``tag`` (the first row's tag is
    the caller's)."""
    if len(array) == 0:
        return ""
    row = " ".join([number] * array.shape[1])
    return (f"{row}\n{tag} " * len(array))[: -len(tag) - 2] % tuple(array.ravel().tolist())
