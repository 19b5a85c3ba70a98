"""gen-robot pose and jacobian (issue 29, items 1 and 2): the lecture's two-link arm against its closed form; every
example, and real robots, against yourdfpy's forward kinematics (an independent reader and walk) and against the
geometric Jacobian built from yourdfpy's joint frames (z x (p - o) and z); errors named, values outside limits a
warning."""

from __future__ import annotations

import io
import json
import math

import numpy as np
import pytest
import yourdfpy
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import REPO, ROBOT_EXAMPLES, gen_robot
from xacrokit.errors import XacrokitError
from xacrokit.kinematics import jacobian, joint_torques, pose
from xacrokit.reader.read_robot import read_robot
from xacrokit.reader.robot_input import RobotInput

PLANAR = REPO / "examples" / "robots" / "planar_2dof.yaml"
L1, L2 = 0.6, 0.4  # (the spec's links; the tool frame at the second's tip)
HEIGHT = 0.035 + 0.025  # joint_1's and joint_2's z offsets

angles = st.floats(-math.pi, math.pi, allow_nan=False)


@settings(max_examples=25, deadline=None)
@given(q1=angles, q2=st.floats(-2.6, 2.6))
def test_the_two_link_arm_is_its_closed_form(q1, q2):
    """x = L1 cos q1 + L2 cos(q1 + q2), y = L1 sin q1 + L2 sin(q1 + q2), yaw q1 + q2; J its derivative."""
    at = {"joint_1": repr(q1), "joint_2": repr(q2)}
    found = pose(PLANAR, "tool_link", at=at).matrix
    x, y = L1 * math.cos(q1) + L2 * math.cos(q1 + q2), L1 * math.sin(q1) + L2 * math.sin(q1 + q2)
    assert np.abs(found[:3, 3] - [x, y, HEIGHT]).max() < 1e-12
    c, s = math.cos(q1 + q2), math.sin(q1 + q2)
    assert np.abs(found[:3, :3] - [[c, -s, 0], [s, c, 0], [0, 0, 1]]).max() < 1e-12
    jac = jacobian(PLANAR, "tool_link", at=at)
    expected = np.array([[-y, -L2 * s], [x, L2 * c], [0, 0], [0, 0], [0, 0], [1, 1]])
    assert jac.joints == ["joint_1", "joint_2"] and np.abs(jac.matrix - expected).max() < 1e-12
    tau = joint_torques(jac, [3.0, -2.0, 0.0])  # (tau = J^T F, the lecture's statics)
    assert np.abs(tau - expected[:3].T @ [3.0, -2.0, 0.0]).max() < 1e-12


def _yourdfpy(path):
    text = read_robot(path).text
    return yourdfpy.URDF.load(io.BytesIO(text.encode("utf-8")), load_meshes=False, build_scene_graph=True)


def _random_values(robot, rng):
    values = {}
    for joint in robot.robot.joints:
        if joint.type not in ("revolute", "continuous", "prismatic") or joint.mimic is not None:
            continue
        low, high = (-math.pi, math.pi)
        if joint.type != "continuous" and joint.limit is not None:
            low, high = joint.limit.lower, joint.limit.upper
        values[joint.name] = float(rng.uniform(low, high))
    return values


@pytest.mark.parametrize("example", ROBOT_EXAMPLES, ids=lambda p: p.stem)
def test_every_link_of_every_example_is_where_yourdfpy_puts_it(example):
    reference = _yourdfpy(example)
    rng = np.random.default_rng(7)
    values = _random_values(reference, rng)
    reference.update_cfg(values)
    at = {k: repr(v) for k, v in values.items()}
    links = [link.name for link in reference.robot.links]
    other = links[len(links) // 2]
    for link in links:
        mine = pose(example, link, at=at).matrix
        assert np.abs(mine - reference.get_transform(link)).max() < 1e-12, link
        relative = pose(example, link, in_frame=other, at=at).matrix
        assert np.abs(relative - reference.get_transform(link, other)).max() < 1e-12, (link, other)


def _geometric_jacobian(reference, frame, leaders):
    """Columns z x (p - o) over z (revolute, continuous) or z over 0 (prismatic) from yourdfpy's joint frames, a
    mimic joint's added to its leader's times its multiplier: the textbook construction, in the root's axes."""
    point = reference.get_transform(frame)[:3, 3]
    columns = {name: np.zeros(6) for name in leaders}
    for joint in reference.robot.joints:
        if joint.type not in ("revolute", "continuous", "prismatic"):
            continue
        placed = reference.get_transform(joint.child)
        above = frame == joint.child or _is_below(reference, frame, joint.child)
        if not above:
            continue
        axis = placed[:3, :3] @ np.asarray(joint.axis, dtype=float)
        axis = axis / np.linalg.norm(axis)  # (a unit z: Romeo writes axes of norm 1 +- 1e-7)
        column = (
            np.concatenate([np.cross(axis, point - placed[:3, 3]), axis])
            if joint.type != "prismatic"
            else np.concatenate([axis, np.zeros(3)])
        )
        leader, multiplier = (joint.mimic.joint, joint.mimic.multiplier or 1.0) if joint.mimic else (joint.name, 1.0)
        columns[leader] = columns[leader] + multiplier * column
    return np.array(list(columns.values())).T


def _is_below(reference, link, ancestor):
    parents = {j.child: j.parent for j in reference.robot.joints}
    while link in parents:
        link = parents[link]
        if link == ancestor:
            return True
    return False


@pytest.mark.parametrize("example", ROBOT_EXAMPLES, ids=lambda p: p.stem)
def test_every_examples_jacobian_is_the_textbook_one_from_yourdfpys_frames(example):
    reference = _yourdfpy(example)
    values = _random_values(reference, np.random.default_rng(11))
    reference.update_cfg(values)
    at = {k: repr(v) for k, v in values.items()}
    leaders = [j.name for j in reference.robot.joints if j.name in values]
    for link in [link.name for link in reference.robot.links][-3:]:
        jac = jacobian(example, link, at=at)
        assert jac.joints == leaders
        assert np.abs(jac.matrix - _geometric_jacobian(reference, link, leaders)).max() < 1e-12, link


def test_pose_and_jacobian_as_commands(tmp_path):
    shown = gen_robot("pose", PLANAR, "tool_link", "--at", "joint_1=30deg", "--at", "joint_2=60deg", "--json")
    assert shown.returncode == 0, shown.stderr
    found = json.loads(shown.stdout)
    assert found["frame"] == "tool_link" and found["in"] == "base_link"
    assert np.abs(np.array(found["xyz"]) - [L1 * math.cos(math.pi / 6), L1 * 0.5 + L2, HEIGHT]).max() < 1e-12
    assert np.abs(np.array(found["rpy"]) - [0, 0, math.pi / 2]).max() < 1e-12
    assert np.abs(np.array(found["quat_xyzw"]) - [0, 0, math.sqrt(0.5), math.sqrt(0.5)]).max() < 1e-12
    assert np.array(found["matrix"]).shape == (4, 4)
    rotated = gen_robot("pose", PLANAR, "tool_link", "--at", "joint_1=90deg", "--rotation", "rotvec", "--json")
    assert np.abs(np.array(json.loads(rotated.stdout)["rotation"]["value"]) - [0, 0, math.pi / 2]).max() < 1e-12
    jac = gen_robot("jacobian", PLANAR, "tool_link", "--at", "joint_2=90deg", "--exerts", "0,10,0", "--json")
    assert jac.returncode == 0, jac.stderr
    said = json.loads(jac.stdout)
    assert said["joints"] == ["joint_1", "joint_2"] and len(said["jacobian"]) == 6
    assert abs(said["torques"]["joint_1"] - 10 * L1) < 1e-12 and abs(said["torques"]["joint_2"]) < 1e-12


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["pose", PLANAR, "tool_lnk"], "no link or frame 'tool_lnk' (did you mean 'tool_link'?)"),
        (["pose", PLANAR, "tool_link", "--in", "nowhere"], "--in: the robot has no link or frame 'nowhere'"),
        (["pose", PLANAR, "tool_link", "--at", "joint_3=1"], "--at joint_3: no moving joint of that name"),
        (["pose", PLANAR, "tool_link", "--at", "joint_1=1 parsec"], "--at joint_1=1 parsec"),
        (["pose", PLANAR, "tool_link", "--at", "joint_1"], "give NAME=VALUE"),
        (["jacobian", PLANAR, "tool_link", "--exerts", "1,2"], "give FX,FY,FZ or FX,FY,FZ,MX,MY,MZ"),
    ],
)
def test_a_bad_question_is_a_clear_error(argv, words):
    result = gen_robot(*argv)
    assert result.returncode == 2 and "Traceback" not in result.stderr and words in result.stderr, result.stderr


def test_a_value_outside_the_limits_is_a_warning_and_still_answered():
    result = gen_robot("pose", PLANAR, "tool_link", "--at", "joint_2=170deg")
    assert result.returncode == 0
    assert "warning: --at joint_2=170deg: 2.96706 rad is outside its limits [-2.61799, 2.61799] rad" in result.stderr


def test_a_mimic_joint_follows_its_leader_and_is_not_set_itself(tmp_path):
    urdf = tmp_path / "m.urdf"
    urdf.write_text(
        '<robot name="m"><link name="a"/><link name="b"/><link name="c"/>'
        '<joint name="lead" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
        '<limit lower="-2" upper="2" effort="1" velocity="1"/></joint>'
        '<joint name="follow" type="revolute"><parent link="b"/><child link="c"/><origin xyz="1 0 0"/>'
        '<axis xyz="0 0 1"/><limit lower="-4" upper="4" effort="1" velocity="1"/>'
        '<mimic joint="lead" multiplier="2" offset="0.1"/></joint></robot>',
        encoding="utf-8",
    )
    with pytest.raises(XacrokitError, match="a mimic joint follows 'lead'; set that one"):
        pose(urdf, "c", at={"follow": "1"})
    found = pose(urdf, "c", at={"lead": "0.3"}).matrix
    turn = 0.3 + 2 * 0.3 + 0.1
    assert abs(math.atan2(found[1, 0], found[0, 0]) - turn) < 1e-12
    jac = jacobian(urdf, "c", at={"lead": "0.3"})
    assert jac.joints == ["lead"] and abs(jac.matrix[5, 0] - 3.0) < 1e-12  # (1 + the multiplier 2)


def test_real_robots_links_and_jacobians_are_yourdfpys():
    """Every fourth robot of the real-robot corpus (32 files: arms, hands, humanoids, mobile bases): every link's pose
    against yourdfpy's at random joint values, the deepest link's Jacobian against the textbook one (1e-12)."""
    from realworld import corpus_or_skip

    checked = 0
    for robot in list(corpus_or_skip())[::4]:
        try:
            read = read_robot(RobotInput(robot.path, packages=robot.packages))
            reference = yourdfpy.URDF.load(
                io.BytesIO(read.text.encode("utf-8")), load_meshes=False, build_scene_graph=True
            )
            values = _random_values(reference, np.random.default_rng(3))
            reference.update_cfg(values)
        except Exception:  # noqa: BLE001  (yourdfpy cannot read or pose some files (no robot name, mimic chains))
            continue
        at = {k: repr(v) for k, v in values.items()}
        try:
            first = pose(read, reference.robot.links[0].name, at=at)
        except XacrokitError:
            continue  # (a file pinocchio or the reader refuses: check says why)
        assert first.warnings == []
        for link in [link.name for link in reference.robot.links]:
            mine = pose(read, link, at=at).matrix
            assert np.abs(mine - reference.get_transform(link)).max() < 1e-12, (robot.key, link)
        deepest = reference.robot.links[-1].name
        leaders = [j.name for j in reference.robot.joints if j.name in values]
        jac = jacobian(read, deepest, at=at)
        expected = _geometric_jacobian(reference, deepest, leaders).reshape(6, len(leaders))
        assert np.abs(jac.matrix - expected).max(initial=0.0) < 1e-12, robot.key
        checked += 1
    assert checked >= 25, checked


def test_the_outputs_docs_kinematics_shows_are_the_commands_own():
    """Every ```console block of docs/kinematics.md: its command run again prints exactly what the page shows."""
    import re
    import shlex

    page = (REPO / "docs" / "kinematics.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```console\n\$ gen-robot (.+?)\n(.*?)```", page, flags=re.S)
    assert len(blocks) == 6
    for command, shown in blocks:
        argv = [REPO / word if word.startswith("examples/") else word for word in shlex.split(command)]
        result = gen_robot(*argv, cwd=REPO)
        assert result.returncode == 0, result.stderr
        assert result.stdout == shown, command


def test_a_point_a_camera_sees_is_put_in_the_base_frame():
    """The rover's camera: 75 mm ahead of and 75 mm above base_link (itself 33 mm above base_footprint), tilted 15 deg
    down (pitch +15 deg: x turns towards -z). A point 1 m along the camera's x is at 0.075 + cos 15 deg ahead and
    0.108 - sin 15 deg up."""
    rover = REPO / "examples" / "robots" / "rover.yaml"
    result = gen_robot("pose", rover, "camera_link", "--point", "1,0,0", "--json")
    assert result.returncode == 0, result.stderr
    point = json.loads(result.stdout)["point"]
    tilt = math.radians(15)
    assert (
        np.abs(np.array(point) - [0.075 + math.cos(tilt), 0, 0.108 - math.sin(tilt)]).max() < 1e-7
    )  # (quat: 7 digits)
    bad = gen_robot("pose", rover, "camera_link", "--point", "1,0")
    assert bad.returncode == 2 and "give X,Y,Z in metres" in bad.stderr
