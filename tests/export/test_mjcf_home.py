"""Named poses in the exported MuJoCo model (issue 32, items 1 and 2): a keyframe per pose, `home` first with every
position servo's target; at every example's home no two bodies penetrate, and a fixed-base robot held by its
servos comes to rest there (joint speeds below 1e-6 rad/s after 3 s)."""

from __future__ import annotations

import numpy as np
import pytest
import yaml

from conftest import REPO, ROBOT_EXAMPLES, SCENE_EXAMPLES
from xacrokit.export.mjcf import export_mjcf, write_export

mujoco = pytest.importorskip("mujoco")

UR_HOME = {"shoulder_lift_joint": -1.57, "wrist_1_joint": -1.57}  # (UR's config/initial_positions.yaml)


def _load(path, tmp_path):
    target = tmp_path / "model" / "robot.xml"
    write_export(export_mjcf(path), target)
    return mujoco.MjModel.from_xml_path(str(target))


def _qpos_of(m, d, name):
    return d.qpos[m.jnt_qposadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, name)]]


@pytest.mark.parametrize("example", [*ROBOT_EXAMPLES, *SCENE_EXAMPLES], ids=lambda p: p.stem)
def test_every_example_starts_at_home_without_penetrating_and_an_arm_settles(example, tmp_path):
    m = _load(example, tmp_path)
    assert m.nkey >= 1 and mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_KEY, 0) == "home"
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, 0)
    mujoco.mj_forward(m, d)
    deepest = min((c.dist for c in d.contact[: d.ncon]), default=0.0)
    pairs = [(m.body(m.geom_bodyid[c.geom1]).name, m.body(m.geom_bodyid[c.geom2]).name) for c in d.contact[: d.ncon]]
    assert deepest > -1e-6, f"penetrating at home: {pairs}"
    free = m.njnt > 0 and m.jnt_type[0] == mujoco.mjtJoint.mjJNT_FREE
    if free or m.nu == 0:
        return  # (a mobile base falls without a floor; a robot without servos has nothing holding it)
    for _ in range(round(3.0 / m.opt.timestep)):
        mujoco.mj_step(m, d)
    assert np.abs(d.qvel).max() < 1e-6


@pytest.mark.parametrize("example", ["ur10e", "industrial_arm_std_dh"])
def test_the_ur_examples_start_at_urs_home(example, tmp_path):
    spec = REPO / "examples" / "robots" / f"{example}.yaml"
    m = _load(spec, tmp_path)
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, 0)
    for joint in ("shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint"):
        assert _qpos_of(m, d, joint) == UR_HOME.get(joint, 0.0)
        servo = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, joint)
        assert d.ctrl[servo] == UR_HOME.get(joint, 0.0)  # (the servo holds the pose it starts in)


def test_every_pose_is_a_keyframe_and_a_mimic_follows_its_leader(tmp_path):
    spec = {
        "robot": "gripper_arm",
        "links": {
            "base": {"shape": {"box": {"size": [0.2, 0.2, 0.1]}}, "mass": 2.0},
            "arm": {
                "shape": {"cylinder": {"radius": 0.03, "length": 0.4}},
                "origin": {"xyz": [0, 0, 0.2]},
                "mass": 1.0,
            },
            "finger_a": {"shape": {"box": {"size": [0.01, 0.02, 0.05]}}, "mass": 0.05},
            "finger_b": {"shape": {"box": {"size": [0.01, 0.02, 0.05]}}, "mass": 0.05},
        },
        "joints": {
            "lift": {
                "type": "revolute",
                "parent": "base",
                "child": "arm",
                "origin": {"xyz": [0, 0, 0.05]},
                "axis": [0, 1, 0],
                "limit": {"lower": -2, "upper": 2, "effort": 50, "velocity": 1},
            },
            "grip": {
                "type": "prismatic",
                "parent": "arm",
                "child": "finger_a",
                "origin": {"xyz": [0, 0.03, 0.42]},
                "axis": [0, 1, 0],
                "limit": {"lower": 0, "upper": 0.04, "effort": 20, "velocity": 0.1},
            },
            "grip_mirror": {
                "type": "prismatic",
                "parent": "arm",
                "child": "finger_b",
                "origin": {"xyz": [0, -0.03, 0.42]},
                "axis": [0, 1, 0],
                "limit": {"lower": -0.04, "upper": 0, "effort": 20, "velocity": 0.1},
                "mimic": {"joint": "grip", "multiplier": -1},
            },
        },
        "poses": {"ready": {"lift": "30 deg"}, "home": {"lift": -0.5, "grip": "20 mm"}, "open": {"grip": 0.04}},
        "ros2_control": {},
    }
    path = tmp_path / "gripper_arm.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    m = _load(path, tmp_path)
    names = [mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_KEY, k) for k in range(m.nkey)]
    assert names == ["home", "ready", "open"]  # (home first, then as the spec gives them)
    d = mujoco.MjData(m)
    expected = {"home": (-0.5, 0.02), "ready": (np.radians(30), 0.0), "open": (0.0, 0.04)}
    for key, name in enumerate(names):
        mujoco.mj_resetDataKeyframe(m, d, key)
        lift, grip = expected[name]
        assert _qpos_of(m, d, "lift") == pytest.approx(lift, abs=1e-15)
        assert _qpos_of(m, d, "grip") == pytest.approx(grip, abs=1e-15)
        assert _qpos_of(m, d, "grip_mirror") == pytest.approx(-grip, abs=1e-15)  # (the mimic's q = -q_leader)
        servos = {mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_ACTUATOR, a): d.ctrl[a] for a in range(m.nu)}
        assert servos == pytest.approx({"lift": lift, "grip": grip}, abs=1e-15)  # (the mimic has no servo)


def test_a_urdfs_ros2_control_start_is_home_and_odd_values_are_left_out(tmp_path):
    """A URDF (no spec): home is its <ros2_control> initial_values; one that is not a finite number (nan, 1e999, a
    word) is left out, the joint at 0, the model still loading."""
    joint = (
        '<joint name="{n}" type="revolute"><parent link="{p}"/><child link="{c}"/><origin xyz="0 0 0.1"/>'
        '<axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="10" velocity="1"/></joint>'
    )
    link = (
        '<link name="{n}"><inertial><mass value="1"/>'
        '<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>'
    )
    control = (
        '<joint name="{n}"><command_interface name="position"/><state_interface name="position">'
        '<param name="initial_value">{v}</param></state_interface></joint>'
    )
    values = {"j1": "0.75", "j2": "nan", "j3": "1e999", "j4": "abc"}
    links = "".join(link.format(n=f"l{i}") for i in range(5))
    joints = "".join(joint.format(n=f"j{i}", p=f"l{i - 1}", c=f"l{i}") for i in range(1, 5))
    blocks = "".join(control.format(n=n, v=v) for n, v in values.items())
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        f'<robot name="r">{links}{joints}<ros2_control name="r" type="system"><hardware><plugin>x</plugin>'
        f"</hardware>{blocks}</ros2_control></robot>",
        encoding="utf-8",
    )
    m = _load(urdf, tmp_path)
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, 0)
    assert [_qpos_of(m, d, f"j{i}") for i in range(1, 5)] == [0.75, 0.0, 0.0, 0.0]
    assert list(d.ctrl) == [0.75, 0.0, 0.0, 0.0]


def test_a_specs_armature_adds_to_the_mass_matrix_diagonal_only(tmp_path):
    """dynamics.armature (J_rotor N^2), which a URDF cannot hold, reaches MuJoCo from the spec: the mass matrix is
    pinocchio's (of the URDF, without it) plus the armature on its joint's diagonal entry."""
    import pinocchio as pin

    from xacrokit.reader.robot_input import RobotInput
    from xacrokit.reader.robot_source import read_source

    text = (REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml").read_text(encoding="utf-8")
    text = text.replace(
        "limit: {lower: -2*pi, upper: 2*pi, effort: 150, velocity: 3.15}, dynamics: {damping: 0.0, friction: 0.0}}",
        "limit: {lower: -2*pi, upper: 2*pi, effort: 150, velocity: 3.15}, dynamics: {damping: 0.0, friction: 0.0, "
        "armature: 0.1}}",
        2,
    )
    spec = tmp_path / "ur5_armature.yaml"
    spec.write_text(text, encoding="utf-8")
    m = _load(spec, tmp_path)
    names = [mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j) for j in range(m.njnt)]
    assert dict(zip(names, m.dof_armature, strict=True)) == {
        n: (0.1 if n in ("shoulder_pan_joint", "shoulder_lift_joint") else 0.0) for n in names
    }
    model = pin.buildModelFromXML(read_source(RobotInput(spec)).text)
    q = np.array([0.3, -1.2, 0.8, -0.5, 0.4, 0.2])
    d = mujoco.MjData(m)
    d.qpos[:] = q
    mujoco.mj_forward(m, d)
    dense = np.zeros((m.nv, m.nv))
    mujoco.mj_fullM(m, d, dense)
    want = pin.crba(model, model.createData(), q)
    want = np.triu(want) + np.triu(want, 1).T + np.diag(m.dof_armature)
    assert np.abs(dense - want).max() < 1e-9


def test_a_mimic_of_a_mimic_listed_before_its_leader_follows_it_in_the_keyframe(tmp_path):
    """tip = mid + 0.1, mid = 2 x lead, the tip written first: each keyframe runs the chain (the tip was at 0.1)."""
    urdf = tmp_path / "chain.urdf"
    box = '<inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>'
    joint = '<joint name="{0}" type="revolute"><parent link="{1}"/><child link="{2}"/><axis xyz="0 0 1"/>'
    limit = '<limit lower="-3" upper="3" effort="1" velocity="1"/>'
    urdf.write_text(
        '<robot name="chain"><link name="base"/>'
        + "".join(f'<link name="{n}">{box}</link>' for n in ("a", "b", "c"))
        + joint.format("tip", "b", "c")
        + limit
        + '<mimic joint="mid" multiplier="1" offset="0.1"/></joint>'
        + joint.format("mid", "a", "b")
        + limit
        + '<mimic joint="lead" multiplier="2"/></joint>'
        + joint.format("lead", "base", "a")
        + limit
        + "</joint>"
        + '<ros2_control name="c" type="system"><joint name="lead"><state_interface name="position">'
        + '<param name="initial_value">0.4</param></state_interface></joint></ros2_control></robot>',
        encoding="utf-8",
    )
    m = _load(urdf, tmp_path)
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, 0)
    assert _qpos_of(m, d, "lead") == pytest.approx(0.4, abs=1e-15)
    assert _qpos_of(m, d, "mid") == pytest.approx(0.8, abs=1e-15)
    assert _qpos_of(m, d, "tip") == pytest.approx(0.9, abs=1e-15)
