"""A mesh MuJoCo cannot read is converted by trimesh: to binary STL (MuJoCo keeps vertices in single precision, as the
STL holds them), or to OBJ past MuJoCo's STL limit of 200,000 triangles; MuJoCo compiles either with the mesh's
every triangle, and the vertices are the source's (to single precision)."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest
import trimesh

import xacrokit.export.mjcf_meshes as mjcf_meshes
from xacrokit.export.mjcf import export_mjcf, write_export
from xacrokit.reader.read_robot import read_robot
from xacrokit.reader.robot_input import RobotInput

INERTIAL = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'


@pytest.mark.parametrize(("limit", "suffix"), [(mjcf_meshes.STL_FACES, ".stl"), (10, ".obj")])
def test_a_ply_mesh_is_converted_to_what_mujoco_reads_with_its_vertices(tmp_path, monkeypatch, limit, suffix):
    # (a box of 12 triangles: binary STL under the limit; past a limit of 10 triangles, OBJ)
    monkeypatch.setattr(mjcf_meshes, "STL_FACES", limit)
    source = trimesh.creation.box(extents=(0.1, 0.2, 0.3))
    source.apply_translation((0.0123456789, -0.0456789, 0.3))
    source.export(tmp_path / "part.ply")
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        f'<robot name="r"><link name="a"><collision><geometry><mesh filename="part.ply"/></geometry></collision>'
        f"{INERTIAL}</link></robot>",
        encoding="utf-8",
    )
    model = export_mjcf(read_robot(RobotInput(urdf)), base="fixed")
    assert list(model.meshes) == [f"part{suffix}"], model.meshes
    assert any(f"part.ply' converted to {'binary STL' if suffix == '.stl' else 'OBJ'}" in n for n in model.notes)
    write_export(model, tmp_path / "out" / "robot.xml")
    written = trimesh.load(tmp_path / "out" / "meshes" / f"part{suffix}", force="mesh", process=True)
    expected = np.unique(np.asarray(source.vertices, dtype=np.float32), axis=0)
    assert np.array_equal(np.unique(np.asarray(written.vertices, dtype=np.float32), axis=0), expected)
    m = mujoco.MjModel.from_xml_path(str(tmp_path / "out" / "robot.xml"))
    assert m.nmesh == 1 and m.mesh_facenum[0] == 12 and m.mesh_vertnum[0] == 8


def test_a_mesh_converted_again_is_the_kept_conversion_and_a_changed_one_is_converted_anew(tmp_path):
    """Robots that name a mesh of the same bytes (the corpus's Stretch variants, a fleet) convert it once in a
    process (mjcf_meshes._converted): the second export writes the very bytes of the first, under its own name; a
    file whose bytes changed is converted again."""

    def exported(folder, lift):
        folder.mkdir()
        trimesh.creation.box(extents=(0.1, 0.2, 0.3)).apply_translation((0.0, 0.0, lift)).export(folder / "part.ply")
        urdf = folder / "r.urdf"
        urdf.write_text(
            f'<robot name="r"><link name="a"><visual><geometry><mesh filename="part.ply"/></geometry></visual>'
            f"{INERTIAL}</link></robot>",
            encoding="utf-8",
        )
        return export_mjcf(read_robot(RobotInput(urdf)), base="fixed").meshes["part.stl"]

    first, again, changed = exported(tmp_path / "a", 0.5), exported(tmp_path / "b", 0.5), exported(tmp_path / "c", 0.7)
    assert isinstance(first, bytes) and again is first
    assert changed != first
    lifted = trimesh.load(trimesh.util.wrap_as_stream(changed), file_type="stl", force="mesh")
    assert np.isclose(lifted.vertices[:, 2].max(), 0.85)


def test_conversions_kept_from_many_threads_stay_within_their_bound(monkeypatch):
    """export_mjcf is public: exports running in threads share the kept conversions (under a lock: without it, 7 of 8
    such threads stopped at "OrderedDict mutated during iteration"), and the bytes kept stay within CONVERTED_BYTES
    and equal to their running count however the threads interleave (the switch interval at a microsecond)."""
    import sys
    import threading

    class Made:
        def export(self, file_type, **_):
            return b"x" * 1000

    monkeypatch.setattr(mjcf_meshes, "CONVERTED_BYTES", 50_000)
    monkeypatch.setattr(mjcf_meshes, "_CONVERTED", type(mjcf_meshes._CONVERTED)())
    monkeypatch.setattr(mjcf_meshes, "_KEPT", [0])
    interval, failed = sys.getswitchinterval(), []

    def convert(thread):
        try:
            for index in range(3_000):
                assert mjcf_meshes._converted(Made(), (f"{thread}-{index % 120}", ".ply", True, "stl")) == b"x" * 1000
        except Exception as exc:  # (a thread's failure, said by the test)
            failed.append(repr(exc))

    sys.setswitchinterval(1e-6)
    try:
        threads = [threading.Thread(target=convert, args=(t,)) for t in range(6)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    finally:
        sys.setswitchinterval(interval)
    assert failed == []
    kept = sum(map(len, mjcf_meshes._CONVERTED.values()))
    assert kept == mjcf_meshes._KEPT[0] <= 50_000 and kept > 0
