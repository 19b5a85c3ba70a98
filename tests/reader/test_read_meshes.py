"""A mesh file's bytes are read by trimesh once in a process (xacrokit.reader.mesh_copies: kept by their SHA-256,
suffix and ``process``, the least recently used dropped past a count of vertices): a second read of the same bytes
parses nothing, hands out a copy equal to a fresh read that its caller may change without changing the next one,
and changed bytes are read again. What the features make from a kept mesh is what they made from a fresh one."""

from __future__ import annotations

import io
import json

import numpy as np
import pytest
import trimesh

import xacrokit.reader.mesh_copies as mesh_copies
from xacrokit.export.mjcf import export_mjcf
from xacrokit.reader.mesh_copies import mesh_reader
from xacrokit.reader.read_robot import read_robot
from xacrokit.shared.input_files import copied_pieces
from xacrokit.view.page import robot_json


def cube_obj() -> str:
    """A box of 36 vertices (one a face's corner) with their normals, as OBJ: merged as it is read, 24 (the normals
    keep the corners of two faces apart); merged later, 8."""
    box = trimesh.creation.box(extents=(0.1, 0.2, 0.3))
    box.unmerge_vertices()
    return box.export(file_type="obj", include_normals=True)


CUBE_OBJ = cube_obj()


@pytest.fixture
def loads(monkeypatch):
    """The meshes kept emptied for the test (and emptied again after it), and trimesh's reads counted."""
    monkeypatch.setattr(mesh_copies, "_READ_MESHES", mesh_copies._ReadMeshes(mesh_copies.READ_MESH_VERTICES))
    counted = {"loads": 0}
    load = trimesh.load

    def counting(*args, **kwargs):
        counted["loads"] += 1
        return load(*args, **kwargs)

    monkeypatch.setattr(trimesh, "load", counting)
    return counted


def robot_of(folder, meshes: dict[str, bytes | str]):
    """A URDF in ``folder`` with a link whose visual and collision name each of ``meshes`` (written beside it)."""
    geometry = ""
    for name, data in meshes.items():
        (folder / name).write_bytes(data.encode() if isinstance(data, str) else data)
        geometry += f'<visual><geometry><mesh filename="{name}"/></geometry></visual>'
        geometry += f'<collision><geometry><mesh filename="{name}"/></geometry></collision>'
    inertia = 'ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"'
    inertial = f'<inertial><mass value="1"/><inertia {inertia}/></inertial>'
    urdf = folder / "r.urdf"
    urdf.write_text(f'<robot name="r"><link name="a">{geometry}{inertial}</link></robot>', encoding="utf-8")
    return urdf


def fresh(data: bytes | str, kind: str, process: bool):
    raw = data.encode() if isinstance(data, str) else data
    return trimesh.load(io.BytesIO(raw), file_type=kind, force="mesh", process=process)


@pytest.mark.parametrize("process", [False, True])
def test_a_mesh_read_again_is_parsed_once_and_handed_out_as_a_copy_its_reader_may_change(tmp_path, loads, process):
    urdf = robot_of(tmp_path, {"cube.obj": CUBE_OBJ})
    read = mesh_reader(urdf, {}, process=process)
    first = read("cube.obj").mesh
    assert loads["loads"] == 1
    first.vertices = first.vertices * 3.0  # (what check does to scale its mesh, and export's merge is in place too)
    first.merge_vertices(merge_norm=True)
    second, third = read("cube.obj").mesh, read("cube.obj").mesh
    assert loads["loads"] == 1, "read again from the file's bytes"
    want = fresh(CUBE_OBJ, "obj", process)
    assert second is not third
    for got in (second, third):
        assert np.array_equal(got.vertices, want.vertices) and np.array_equal(got.faces, want.faces)
        assert np.array_equal(got.vertex_normals, want.vertex_normals)
        assert got.metadata == want.metadata
    assert len(want.vertices) == (24 if process else 36)
    second.process()
    want.process()  # (what export does to a mesh read unmerged: a copy merges as the mesh read from the file)
    assert np.array_equal(second.vertices, want.vertices) and np.array_equal(second.faces, want.faces)


def test_changed_bytes_are_read_again_and_process_is_part_of_the_key(tmp_path, loads):
    urdf = robot_of(tmp_path, {"cube.obj": CUBE_OBJ})
    assert len(mesh_reader(urdf, {})("cube.obj").mesh.faces) == 12
    assert len(mesh_reader(urdf, {}, process=False)("cube.obj").mesh.faces) == 12
    assert loads["loads"] == 2
    ball = trimesh.creation.icosphere(subdivisions=1).export(file_type="obj")
    (tmp_path / "cube.obj").write_text(ball, encoding="utf-8")
    assert len(mesh_reader(urdf, {})("cube.obj").mesh.faces) == 80
    assert loads["loads"] == 3


def test_the_least_recently_used_meshes_go_first_past_the_vertices_kept():
    box, ball = trimesh.creation.box(), trimesh.creation.icosphere(subdivisions=1)  # (8 and 42 vertices)
    kept = mesh_copies._ReadMeshes(most=60)
    kept.put(("a",), box)
    kept.put(("b",), ball)
    assert kept.vertices == 50
    assert kept.get(("a",)) is box  # (used: now the newest)
    kept.put(("c",), trimesh.creation.box())
    assert kept.vertices == 58 and kept.get(("a",)) is box and kept.get(("c",)) is not None
    kept.put(("d",), trimesh.creation.icosphere(subdivisions=1))  # (past 60: b goes, the least recently used)
    assert kept.get(("b",)) is None and kept.vertices == 58
    assert kept.get(("a",)) is box  # (the order now c, d, a)
    kept.put(("f",), trimesh.creation.box())  # (past 60 again: c goes)
    assert kept.get(("c",)) is None and kept.get(("a",)) is box and kept.get(("d",)) is not None
    assert kept.vertices == 58 <= kept.most
    kept.put(("e",), trimesh.creation.icosphere(subdivisions=2))  # (162 vertices: more than all, never kept)
    assert kept.get(("e",)) is None and kept.vertices == 58


def written(robot) -> tuple[str, dict[str, bytes], list[str]]:
    export = export_mjcf(robot, base="free")
    meshes = {n: d if isinstance(d, bytes) else b"".join(copied_pieces(d)) for n, d in export.meshes.items()}
    return export.xml, meshes, export.notes


def page_robot(urdf) -> str:
    return json.dumps(robot_json(read_robot(urdf).view, mesh_reader(urdf, {}, process=False)))


def test_export_and_page_make_the_same_bytes_from_kept_meshes_as_from_fresh_ones(tmp_path, loads, monkeypatch):
    """A text STL (export merges it in place, then converts it to binary STL; the page reads it unmerged: the same
    key), an OBJ with normals and a binary STL, read by the page, the export, the page and the export again, then by
    both with the meshes kept emptied."""
    text_stl = trimesh.creation.icosphere(subdivisions=2, radius=0.05).export(file_type="stl_ascii")
    binary_stl = trimesh.creation.cylinder(radius=0.02, height=0.1).export(file_type="stl")
    urdf = robot_of(tmp_path, {"ball.stl": text_stl, "cube.obj": CUBE_OBJ, "rod.stl": binary_stl})
    warm = [page_robot(urdf), written(urdf), page_robot(urdf), written(urdf)]
    reads = loads["loads"]
    assert reads <= 5, "each file once a process flag (the export merges an OBJ as it reads it)"
    assert warm[0] == warm[2] and warm[1] == warm[3]
    assert "ball.stl" in warm[1][1] and "rod.stl" in warm[1][1], sorted(warm[1][1])
    monkeypatch.setattr(mesh_copies, "_READ_MESHES", mesh_copies._ReadMeshes(0))
    cold = [page_robot(urdf), written(urdf)]
    assert loads["loads"] > reads * 1.5
    assert cold == warm[:2]
