"""Orientations given as a quaternion or an axis and an angle: converted to the rpy URDF writes, checked against an
independent library (scipy's Rotation; the conversion itself uses pinocchio), and refused or noted where they are
not rotations."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from conftest import REPO, gen_robot
from xacrokit.errors import SpecErrors
from xacrokit.pipeline import build_robot
from xacrokit.shared.transforms import rpy_matrix

SPEC = {
    "robot": "rot",
    "links": {
        "base_link": {"shape": {"box": {"size": [0.2, 0.2, 0.1]}}, "mass": 2.0},
        "camera": {"shape": {"box": {"size": [0.02, 0.08, 0.02]}}, "mass": 0.1},
    },
    "joints": {"camera_joint": {"type": "fixed", "parent": "base_link", "child": "camera", "origin": {}}},
}


def camera_rpy(tmp_path, origin):
    spec = yaml.safe_load(yaml.safe_dump(SPEC))
    spec["joints"]["camera_joint"]["origin"] = origin
    path = tmp_path / "rot.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    (joint,) = build_robot(path).joints
    return joint.origin.rpy


# a direction not too close to zero (normalising it is then well conditioned); any length within the accepted range
directions = st.lists(st.floats(-10, 10, allow_nan=False), min_size=3, max_size=3).filter(
    lambda v: math.hypot(*v) > 1e-3
)
quaternions = st.lists(st.floats(-10, 10, allow_nan=False), min_size=4, max_size=4).filter(
    lambda q: abs(math.sqrt(sum(v * v for v in q)) - 1.0) <= 1e-6 or math.sqrt(sum(v * v for v in q)) > 1e-3
)


@settings(max_examples=60, deadline=None)
@given(quat=quaternions)
def test_a_quaternion_gives_the_rotation_scipy_gives(tmp_path_factory, quat):
    rpy = camera_rpy(tmp_path_factory.mktemp("q"), {"quat": quat})
    expected = Rotation.from_quat(quat).as_matrix()  # scipy's order is ROS's: [x, y, z, w]; it normalises too
    assert np.allclose(rpy_matrix(*rpy), expected, rtol=0, atol=1e-12)
    assert -math.pi / 2 <= rpy[1] <= math.pi / 2  # (the pitch URDF reads back)


@settings(max_examples=60, deadline=None)
@given(axis=directions, angle=st.floats(-4 * math.pi, 4 * math.pi, allow_nan=False))
def test_an_axis_and_angle_give_the_rotation_scipy_gives(tmp_path_factory, axis, angle):
    rpy = camera_rpy(tmp_path_factory.mktemp("a"), {"axis_angle": {"axis": axis, "angle": angle}})
    unit = np.array(axis) / np.linalg.norm(axis)
    expected = Rotation.from_rotvec(unit * angle).as_matrix()
    assert np.allclose(rpy_matrix(*rpy), expected, rtol=0, atol=1e-12)


def test_units_and_the_written_urdf(tmp_path):
    assert camera_rpy(tmp_path, {"axis_angle": {"axis": [0, 0, 2], "angle": "90 deg"}}) == (0.0, 0.0, math.pi / 2)
    spec = yaml.safe_load(yaml.safe_dump(SPEC))
    half = math.sqrt(0.5)
    spec["joints"]["camera_joint"]["origin"] = {"xyz": [0.1, 0, 0.05], "quat": [0, half, 0, half]}  # pitch 90 deg
    path = tmp_path / "rot.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    assert gen_robot(path, "-o", tmp_path / "pkg").returncode == 0
    urdf = (tmp_path / "pkg" / "urdf" / "rot.urdf").read_text(encoding="utf-8")
    line = next(line for line in urdf.splitlines() if 'xyz="0.1 0.0 0.05"' in line)
    roll, pitch, yaw = (float(v) for v in line.split('rpy="')[1].split('"')[0].split())
    assert np.allclose(rpy_matrix(roll, pitch, yaw), Rotation.from_quat([0, half, 0, half]).as_matrix(), atol=1e-12)


@pytest.mark.parametrize(
    ("origin", "where", "said"),
    [
        ({"rpy": [0, 0, 1], "quat": [0, 0, 0, 1]}, "origin.quat", "an origin gives one orientation: rpy or quat"),
        ({"quat": [0, 0, 0, 1], "axis_angle": {"axis": [0, 0, 1], "angle": 1}}, "origin.axis_angle", "not both"),
        ({"quat": [0, 0, 0, 0]}, "origin.quat", "quat [0, 0, 0, 0] has length 0: a rotation's quaternion"),
        ({"axis_angle": {"axis": [0, 0, 0], "angle": 1}}, "origin.axis_angle.axis", "axis [0, 0, 0] has length 0"),
        ({"axis_angle": {"axis": [0, 0, 1], "angle": "90 m"}}, "origin.axis_angle.angle", "angle"),
        ({"quat": [0, 0, 1]}, "origin.quat", ""),  # (the schema: four numbers)
    ],
)
def test_what_is_not_a_rotation_is_refused_where_it_stands(tmp_path, origin, where, said):
    with pytest.raises(SpecErrors) as caught:
        camera_rpy(tmp_path, origin)
    (error,) = caught.value.errors
    assert error.path == f"$.joints.camera_joint.{where}" and said in error.message, error
    lines = (tmp_path / "rot.yaml").read_text(encoding="utf-8").splitlines()
    key = f"{where.rsplit('.', 1)[-1]}:"  # located at the value: on its key's line, or the next (a block list)
    assert key in lines[error.line - 1] or key in lines[error.line - 2], (error.line, lines)


def test_a_quaternion_not_of_unit_length_is_normalised_with_a_warning(tmp_path):
    spec = yaml.safe_load(yaml.safe_dump(SPEC))
    spec["joints"]["camera_joint"]["origin"] = {"quat": [0, 1, 0, 1]}
    path = tmp_path / "rot.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False, default_flow_style=None), encoding="utf-8")
    result = gen_robot(path, "-o", tmp_path / "pkg")
    assert result.returncode == 0
    assert "$.joints.camera_joint.origin.quat: quat [0, 1, 0, 1] has length 1.41421356, not 1; normalised" in (
        result.stderr
    )
    (joint,) = build_robot(path).joints
    assert np.allclose(joint.origin.rpy, (0.0, math.pi / 2, 0.0), atol=1e-12)
    spec["joints"]["camera_joint"]["origin"] = {"quat": [0, 0, 0.0000001, 1]}  # 5e-15 off: quiet
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    assert "warning" not in gen_robot(path, "--dry-run").stderr


def test_the_docs_example_generates_what_it_says(tmp_path):
    docs = (REPO / "docs" / "spec.md").read_text(encoding="utf-8")
    (block,) = [
        b for b in re.findall(r"```yaml\n(.*?)\n```", docs, flags=re.S) if "camera_joint:" in b and "quat:" in b
    ]
    links = """robot: rot
links:
  base_link: {shape: {box: {size: [0.2, 0.2, 0.1]}}, mass: 2.0}
  camera: {shape: {box: {size: [0.02, 0.08, 0.02]}}, mass: 0.1}
  lidar: {shape: {cylinder: {radius: 0.03, length: 0.04}}, mass: 0.2}
joints:
"""
    path = tmp_path / "rot.yaml"
    path.write_text(links + block, encoding="utf-8")
    joints = {joint.name: joint.origin.rpy for joint in build_robot(path).joints}
    assert np.allclose(joints["camera_joint"], (0.0, math.pi / 4, 0.0), atol=1e-7)  # (the docs' 7 digits)
    assert joints["lidar_joint"] == (0.0, 0.0, math.pi / 2)


def test_scene_instances_take_the_same_orientations(tmp_path):
    arm = REPO / "examples" / "robots" / "two_dof_arm.yaml"
    scene = tmp_path / "cell.yaml"
    scene.write_text(
        f"""scene: cell
instances:
  a: {{spec: {arm}, prefix: a_, parent: world, origin: {{quat: [0, 0, 0.7071067811865476, 0.7071067811865476]}}}}
  b: {{spec: {arm}, prefix: b_, parent: world,
      origin: {{xyz: [1, 0, 0], axis_angle: {{axis: [0, 0, 1], angle: 180 deg}}}}}}
""",
        encoding="utf-8",
    )
    assert gen_robot(scene, "-o", tmp_path / "pkg").returncode == 0
    urdf = (tmp_path / "pkg" / "urdf" / "cell.urdf").read_text(encoding="utf-8")
    assert '<origin xyz="0.0 0.0 0.0" rpy="0.0 0.0 1.5707963267948968"/>' in urdf  # (pinocchio's last bit)
    assert '<origin xyz="1.0 0.0 0.0" rpy="0.0 0.0 3.141592653589793"/>' in urdf


# every other form of one rotation (issue 29, item 4), against scipy's Rotation
rotations = st.lists(st.floats(-1, 1, allow_nan=False), min_size=4, max_size=4).filter(
    lambda q: math.sqrt(sum(v * v for v in q)) > 1e-2
)


@settings(max_examples=40, deadline=None)
@given(quat=rotations, sequence=st.sampled_from(["XYZ", "ZYX", "ZXZ", "xyz", "zyx", "zyz", "YXY"]))
def test_every_rotation_form_gives_the_rotation_scipy_gives(tmp_path_factory, quat, sequence):
    rotation = Rotation.from_quat(quat)
    expected = rotation.as_matrix()
    x, y, z, w = rotation.as_quat()
    forms = {
        "quat_wxyz": [float(w), float(x), float(y), float(z)],
        "rotvec": [float(v) for v in rotation.as_rotvec()],
        "matrix": [[float(v) for v in row] for row in expected],
        "euler": {"sequence": sequence, "angles": [float(v) for v in rotation.as_euler(sequence)]},
    }
    folder = tmp_path_factory.mktemp("forms")
    for name, value in forms.items():
        rpy = camera_rpy(folder, {name: value})
        # (Euler angles against scipy's own rotation of them: near gimbal lock as_euler loses digits)
        wanted = Rotation.from_euler(sequence, forms["euler"]["angles"]).as_matrix() if name == "euler" else expected
        assert np.allclose(rpy_matrix(*rpy), wanted, rtol=0, atol=1e-12), name


def test_the_lectures_r_xyz_is_not_urdfs_rpy(tmp_path):
    """The tf lecture's R_XYZ = Rx Ry Rz (intrinsic XYZ) at (0.1, 0.2, 0.3) rad and URDF's rpy (extrinsic xyz,
    Rz Ry Rx) at the same numbers are 0.0695 rad apart; euler: {sequence: XYZ} writes the first, in degrees too."""
    lecture = camera_rpy(tmp_path, {"euler": {"sequence": "XYZ", "angles": ["0.1 rad", 0.2, 0.3]}})
    rx, ry, rz = (Rotation.from_euler(a, v).as_matrix() for a, v in (("x", 0.1), ("y", 0.2), ("z", 0.3)))
    assert np.allclose(rpy_matrix(*lecture), rx @ ry @ rz, rtol=0, atol=1e-15)
    apart = Rotation.from_matrix(rpy_matrix(*lecture).T @ rpy_matrix(0.1, 0.2, 0.3)).magnitude()
    assert round(apart, 4) == 0.0695
    degrees = camera_rpy(tmp_path, {"euler": {"sequence": "xyz", "angles": ["30 deg", 0, 0]}})
    assert np.allclose(degrees, (math.pi / 6, 0, 0), rtol=0, atol=1e-15)
    assert camera_rpy(tmp_path, {"rotvec": [0, 0, 0]}) == (0.0, 0.0, 0.0)


@pytest.mark.parametrize(
    ("origin", "where", "said"),
    [
        ({"matrix": [[1, 0, 0], [0, 1, 0], [0, 0, -1]]}, "origin.matrix", "its determinant is -1"),
        ({"matrix": [[1, 0.01, 0], [0, 1, 0], [0, 0, 1]]}, "origin.matrix", "R^T R is 0.01 from the identity"),
        ({"quat_wxyz": [0, 0, 0, 0]}, "origin.quat_wxyz", "quat_wxyz [0, 0, 0, 0] has length 0"),
        ({"rotvec": [0, 0, 1], "matrix": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}, "origin.matrix", "not both"),
        ({"axis_angle": [0, 0, 1.5708]}, "origin.axis_angle", "write rotvec: [rx, ry, rz]"),
        ({"euler": {"sequence": "XyZ", "angles": [0, 0, 0]}}, "origin.euler.sequence", ""),
        ({"euler": {"sequence": "XXY", "angles": [0, 0, 0]}}, "origin.euler.sequence", "consecutive axes must differ"),
        ({"rotvec": [1e300, 1e300, 0]}, "origin.rotvec", "of at most 1000 turns"),  # (wrote rpy="nan nan nan")
    ],
)
def test_a_form_that_is_no_rotation_is_refused_where_it_stands(tmp_path, origin, where, said):
    with pytest.raises(SpecErrors) as caught:
        camera_rpy(tmp_path, origin)
    (error,) = caught.value.errors
    assert error.path == f"$.joints.camera_joint.{where}" and said in error.message, error


def test_the_table_of_forms_in_docs_spec_writes_one_rotation(tmp_path):
    """docs/spec.md writes rpy [0.1, 0.2, 0.3] in every form (to 7 digits): each line, as an origin, gives it."""
    page = (REPO / "docs" / "spec.md").read_text(encoding="utf-8")
    block = re.search(r"One rotation written each way.*?```yaml\n(.*?)```", page, flags=re.S).group(1)
    forms = yaml.safe_load(block)
    assert list(forms) == ["rpy", "quat", "quat_wxyz", "rotvec", "axis_angle", "matrix", "euler", "points"]
    for name, value in forms.items():
        rpy = camera_rpy(tmp_path, {name: value})
        assert np.allclose(rpy_matrix(*rpy), rpy_matrix(0.1, 0.2, 0.3), rtol=0, atol=2e-7), name
