"""The OBJ that gen-robot export --mjcf writes for a mesh MuJoCo cannot read (xacrokit.export.obj_text) holds the
bytes trimesh's own writer gave for it before (export_obj without normals and texture, which the export called): on
COLLADA meshes of the real-robot corpus (the Go1's, converted on export), an STL in text, a mesh with a name and with
vertex and face colours, negative zeros and large numbers, and a mesh of no triangle."""

from __future__ import annotations

import io

import numpy as np
import pytest
import trimesh

from realworld import robots
from xacrokit.export.obj_text import obj_text
from xacrokit.reader.mesh_copies import require_mesh


def trimesh_obj(mesh) -> bytes:
    """What the export wrote before: trimesh's writer, called as it called it."""
    return mesh.export(file_type="obj", include_normals=False, include_texture=False).encode("utf-8")


def box_with(**visual) -> trimesh.Trimesh:
    box = trimesh.creation.box(extents=(0.1, 2.5e6, 3.0))
    box.vertices[0] = (-0.0, 1e-9, -123456.789012345)
    if visual:
        box.visual = trimesh.visual.ColorVisuals(box, **visual)
    return box


@pytest.mark.parametrize(
    "mesh",
    [
        box_with(),
        box_with(face_colors=np.tile([200, 10, 30, 255], (12, 1))),
        box_with(vertex_colors=np.arange(32).reshape(8, 4) * 7),
        trimesh.Trimesh(vertices=np.zeros((0, 3)), faces=np.zeros((0, 3), dtype=np.int64)),
    ],
    ids=["plain", "face-colours", "vertex-colours", "empty"],
)
def test_made_meshes_are_written_as_trimesh_wrote_them(mesh):
    assert obj_text(mesh) == trimesh_obj(mesh)
    mesh.metadata["name"] = "part_7"
    assert obj_text(mesh) == trimesh_obj(mesh) and b"\no part_7\n" in obj_text(mesh)


def test_a_text_stl_read_as_the_export_reads_it_is_written_as_trimesh_wrote_it():
    text = trimesh.creation.icosphere(subdivisions=2).export(file_type="stl_ascii").encode()
    mesh = require_mesh(text, ".stl", "ball.stl", process=False)
    assert len(mesh.faces) == 320 and obj_text(mesh) == trimesh_obj(mesh)


def test_real_collada_meshes_are_written_as_trimesh_wrote_them():
    folder = robots()["example-robot-data/go1_description/urdf/go1.urdf"].path.parent.parent / "meshes"
    files = sorted(folder.glob("*.dae"))[:3]
    assert len(files) == 3
    for file in files:
        mesh = require_mesh(file.read_bytes(), ".dae", file.name, process=False)
        written = obj_text(mesh)
        assert written == trimesh_obj(mesh), file.name
        again = trimesh.load(io.BytesIO(written), file_type="obj", force="mesh", process=False)
        assert len(again.faces) == len(mesh.faces) > 100, file.name
