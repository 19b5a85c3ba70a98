"""What the geometry rules take from a mesh file is kept across runs (issue 45: check's own time on a robot of meshes):
read back bit for bit, worked out afresh when the file's bytes change or the kept file is damaged, never kept when
the cache is off; and a second check of an unchanged robot reads none of its meshes, with the same findings."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

from conftest import REPO
from xacrokit.check import check, inertia_geometry, kept_meshes

BRACKET = REPO / "examples" / "robots" / "cad" / "motor_bracket.stl"


@pytest.fixture
def cache(tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    monkeypatch.setenv("XACROKIT_CACHE", str(folder))
    return folder


def _counted(facts):
    calls = []

    def work_out():
        calls.append(1)
        return facts

    return work_out, calls


def test_facts_are_read_back_bit_for_bit_and_worked_out_once(cache):
    rng = np.random.default_rng(45)
    points = rng.normal(size=(500, 3)).astype(np.float32)
    work_out, calls = _counted((points, 996))
    first = kept_meshes.kept_facts(b"mesh bytes", ".stl", work_out)
    again = kept_meshes.kept_facts(b"mesh bytes", ".stl", work_out)
    assert len(calls) == 1 and again[1] == first[1] == 996
    assert again[0].dtype == np.float32 and again[0].tobytes() == points.tobytes()
    again[0][0, 0] = 1.0  # (a kept array the caller owns: writable)
    kept_meshes.kept_facts(b"mesh bytes!", ".stl", work_out)  # (other bytes: worked out)
    kept_meshes.kept_facts(b"mesh bytes", ".obj", work_out)  # (another reader: worked out)
    assert len(calls) == 3


def test_a_damaged_kept_file_is_worked_out_again(cache):
    work_out, calls = _counted((np.zeros((4, 3), dtype=np.float32), 4))
    kept_meshes.kept_facts(b"m", ".stl", work_out)
    (kept,) = (cache / "meshes-0.1.0").glob("*.json")
    for damaged in ('{"triangles": 4, "vertices": 5, "points": "AAAA"}', "not json", '{"points": 1}'):
        kept.write_text(damaged, encoding="utf-8")
        facts = kept_meshes.kept_facts(b"m", ".stl", work_out)
        assert facts[1] == 4 and facts[0].shape == (4, 3)
    assert len(calls) == 4


def test_values_and_none_are_kept_and_nothing_when_the_cache_is_off(cache, monkeypatch):
    work_out, calls = _counted([0.1, 1e-300, -2.5])
    assert kept_meshes.kept_values(b"m", "solid", work_out) == [0.1, 1e-300, -2.5]
    assert kept_meshes.kept_values(b"m", "solid", work_out) == [0.1, 1e-300, -2.5]
    nothing, none_calls = _counted(None)
    assert kept_meshes.kept_values(b"flat", "solid", nothing) is None
    assert kept_meshes.kept_values(b"flat", "solid", nothing) is None
    assert len(calls) == len(none_calls) == 1
    monkeypatch.setenv("XACROKIT_CACHE", "off")
    kept_meshes.kept_values(b"m", "solid", work_out)
    assert len(calls) == 2


def test_a_second_check_reads_no_mesh_and_says_the_same(cache, tmp_path, monkeypatch):
    """The lecture's bracket with an inertia far beyond its hull (I008, whose message names the solid it encloses):
    the second check, in a new process' state (the in-memory meshes dropped), reads neither the STL nor its solid."""
    shutil.copy(BRACKET, tmp_path / "bracket.stl")
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(
        """<?xml version="1.0"?>
<robot name="r">
  <link name="base_link"/>
  <link name="part">
    <visual><geometry><mesh filename="bracket.stl" scale="0.001 0.001 0.001"/></geometry></visual>
    <collision><geometry><mesh filename="bracket.stl" scale="0.001 0.001 0.001"/></geometry></collision>
    <inertial><mass value="1"/><inertia ixx="10" ixy="0" ixz="0" iyy="10" iyz="0" izz="10"/></inertial>
  </link>
  <joint name="j" type="revolute"><parent link="base_link"/><child link="part"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/><dynamics damping="0.1"/></joint>
</robot>
""",
        encoding="utf-8",
    )
    first = check(urdf, consumers=[])
    assert any(f.rule == "I008" and "uniform solid" in f.message for f in first.findings)
    read = []
    for name in ("_read_mesh_points", "_solid_values"):
        real = getattr(inertia_geometry, name)
        monkeypatch.setattr(inertia_geometry, name, lambda *a, real=real, name=name: read.append(name) or real(*a))
    inertia_geometry._MESHES.clear()
    second = check(urdf, consumers=[])
    assert read == [] and second.findings == first.findings
    monkeypatch.setenv("XACROKIT_CACHE", "off")
    inertia_geometry._MESHES.clear()
    assert check(urdf, consumers=[]).findings == first.findings and read == ["_read_mesh_points", "_solid_values"]


def test_a_mesh_other_than_stl_is_known_kept_once_a_check_read_it(cache, tmp_path):
    """What decides whether check loads trimesh before it forks yourdfpy's child: a mesh other than STL whose facts
    are not kept (a file that cannot be read needs no reader)."""
    (tmp_path / "part.obj").write_text(
        "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n", encoding="utf-8"
    )
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(
        """<?xml version="1.0"?>
<robot name="r">
  <link name="part">
    <collision><geometry><mesh filename="part.obj"/></geometry></collision>
    <inertial><mass value="1"/><inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial>
  </link>
</robot>
""",
        encoding="utf-8",
    )
    assert not inertia_geometry.RobotMeshes(urdf, {}).kept("part.obj")
    inertia_geometry._MESHES.clear()
    check(urdf, consumers=[])
    assert inertia_geometry.RobotMeshes(urdf, {}).kept("part.obj")
    assert inertia_geometry.RobotMeshes(urdf, {}).kept("missing.obj")
