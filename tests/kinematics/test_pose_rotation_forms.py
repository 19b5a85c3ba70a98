"""`gen-robot pose --rotation` prints any form an origin takes (issue 42, item 2): the lecture's converter's forms,
each checked against its own definition or scipy, and Euler angles of the 12 sequences, intrinsic and extrinsic."""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from conftest import REPO, gen_robot
from xacrokit.cli.kinematics_commands import pose_dict, rotation_form
from xacrokit.validate.quantities import EULER_AXES

TURN = Rotation.from_rotvec([0.3, -1.1, 0.7]).as_matrix()  # (an arbitrary rotation, away from every lock)
POSE = np.eye(4)
POSE[:3, :3] = TURN


def _value(form: str):
    return pose_dict(POSE, rotation_form(form))["rotation"]["value"]


@pytest.mark.parametrize("axes", EULER_AXES)
@pytest.mark.parametrize("kind", ["intrinsic", "extrinsic"])
def test_euler_angles_of_every_sequence_said_either_way_give_the_rotation(kind, axes):
    value = _value(f"{kind}:{axes.lower()}")
    sequence = axes.upper() if kind == "intrinsic" else axes.lower()
    assert value[kind] == sequence  # (as an origin's euler writes it: scipy's case)
    assert np.abs(Rotation.from_euler(sequence, value["angles"]).as_matrix() - TURN).max() < 1e-12


def test_the_triple_of_points_is_the_frame_by_its_definition():
    value = _value("points")
    p, q, r = (np.array(value[k]) for k in "PQR")
    x = (q - p) / np.linalg.norm(q - p)
    z = np.cross(x, r - p)
    z /= np.linalg.norm(z)
    assert np.abs(np.column_stack([x, np.cross(z, x), z]) - TURN).max() < 1e-12


def test_axis_angle_and_the_others_are_the_rotation():
    axis_angle = _value("axis_angle")
    rotvec = np.array(axis_angle["axis"]) * axis_angle["angle"]
    assert np.abs(Rotation.from_rotvec(rotvec).as_matrix() - TURN).max() < 1e-12
    assert np.abs(Rotation.from_rotvec(_value("rotvec")).as_matrix() - TURN).max() < 1e-12
    w, x, y, z = _value("quat_wxyz")
    assert np.abs(Rotation.from_quat([x, y, z, w]).as_matrix() - TURN).max() < 1e-12


@pytest.mark.parametrize("form", ["quat", "euler:xYz", "intrinsic:ABC", "extrinsic:xx", "euler", "points:XYZ"])
def test_a_form_that_is_none_is_refused_with_exit_2_saying_the_forms(form):
    done = gen_robot("pose", REPO / "examples/robots/ur10e.yaml", "tool0", "--rotation", form)
    assert done.returncode == 2 and done.stdout == ""
    assert "argument --rotation:" in done.stderr and "Traceback" not in done.stderr


def test_the_command_prints_the_form_in_text_and_json():
    spec = REPO / "examples/robots/ur10e.yaml"
    done = gen_robot("pose", spec, "tool0", "--at", "shoulder_pan_joint=0.3", "--rotation", "intrinsic:zyz", "--json")
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    matrix = np.array(out["matrix"])[:3, :3]
    assert out["rotation"]["form"] == "intrinsic:zyz" and out["rotation"]["value"]["intrinsic"] == "ZYZ"
    angles = out["rotation"]["value"]["angles"]
    assert np.abs(Rotation.from_euler("ZYZ", angles).as_matrix() - matrix).max() < 1e-12
    text = gen_robot("pose", spec, "tool0", "--at", "shoulder_pan_joint=0.3", "--rotation", "intrinsic:zyz")
    line = next(line for line in text.stdout.splitlines() if line.strip().startswith("euler"))
    assert [float(v) for v in line.split("angles")[1].split()] == pytest.approx(angles, abs=5e-10)
