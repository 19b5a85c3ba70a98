"""gen-robot export --mjcf reads an STL without merging its vertices and merges them only where it needs them
(xacrokit.export.mjcf_meshes.export_reader: a mesh converted to binary STL, a free robot's hull, a mesh that may be
flat): what it writes is what it wrote when every mesh was merged as it was read, byte for byte, on real robots of
binary STL meshes (fixed and free), a robot whose STL is text (converted), and one with a flat STL (left out)."""

from __future__ import annotations

import pytest
import trimesh

import xacrokit.export.mjcf as mjcf_module
from realworld import robots
from xacrokit.export.mjcf import export_mjcf
from xacrokit.reader.mesh_copies import mesh_reader
from xacrokit.reader.read_robot import read_robot
from xacrokit.reader.robot_input import RobotInput
from xacrokit.shared.input_files import copied_pieces


def written(export) -> tuple[str, dict[str, bytes], list[str]]:
    meshes = {n: d if isinstance(d, bytes) else b"".join(copied_pieces(d)) for n, d in export.meshes.items()}
    return export.xml, meshes, export.notes


def merged_as_read(urdf, packages):
    """The reader the export had before: every mesh merged as it is read."""
    return mesh_reader(urdf, packages)


def both(robot, monkeypatch, **options):
    ours = written(export_mjcf(robot, **options))
    with monkeypatch.context() as patched:
        patched.setattr(mjcf_module, "export_reader", merged_as_read)
        before = written(export_mjcf(robot, **options))
    return ours, before


@pytest.mark.parametrize(
    ("key", "base"),
    [
        ("hello-robot-stretch-urdf/RE2V0/stretch_description_RE2V0_tool_stretch_dex_wrist.urdf", "fixed"),
        ("example-robot-data/ur_description/urdf/ur5_robot.urdf", "free"),
        ("robot-properties-fingers/pro/trifingerpro.urdf", "free"),
    ],
)
def test_real_robots_of_stl_meshes_export_the_same_bytes(key, base, monkeypatch):
    robot = robots()[key]
    read = read_robot(RobotInput(robot.path, packages=robot.packages))
    ours, before = both(read, monkeypatch, base=base)
    assert any(name.lower().endswith(".stl") for name in ours[1]), sorted(ours[1])
    assert ours == before


def test_a_text_stl_is_converted_and_a_flat_one_left_out_as_before(tmp_path, monkeypatch):
    trimesh.creation.icosphere(subdivisions=2, radius=0.05).export(tmp_path / "ball.stl", file_type="stl_ascii")
    flat = trimesh.Trimesh([[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0.1, 0.1, 0]], [[0, 1, 2], [1, 3, 2]])
    flat.export(tmp_path / "sticker.stl")
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        '<robot name="r"><link name="a"><visual><geometry><mesh filename="ball.stl"/></geometry></visual>'
        '<collision><geometry><mesh filename="ball.stl"/></geometry></collision>'
        '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'
        '<visual><geometry><mesh filename="sticker.stl"/></geometry></visual></link></robot>',
        encoding="utf-8",
    )
    ours, before = both(urdf, monkeypatch, base="fixed")
    assert ours == before
    assert list(ours[1]) == ["ball.stl"] and any("sticker.stl" in note for note in ours[2]), ours[2]
    assert ours[1]["ball.stl"][:5] != b"solid"  # (the text STL converted: binary, which MuJoCo reads)
