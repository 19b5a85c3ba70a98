"""gen-robot export --mjcf, proven in MuJoCo: for every example and scene, the exported model's mass matrix and
gravity torques equal pinocchio's on the URDF at random joint values (1e-9 relative); the diff-drive robot driven by
its wheel actuators goes straight at omega r and turns at r (omega_r - omega_l) / separation; an arm holds a pose
under gravity with its position actuators; a scene simulates with every robot; tool frames keep their names."""

from __future__ import annotations

import re
import sys

import numpy as np
import pinocchio as pin
import pytest
from lxml import etree

from conftest import REPO, ROBOT_EXAMPLES, SCENE_EXAMPLES, gen_robot
from xacrokit.errors import XacrokitError
from xacrokit.export.mjcf import MASSLESS, export_mjcf, mjcf, write_export
from xacrokit.reader.read_robot import read_text

mujoco = pytest.importorskip("mujoco")


def urdf_of(path) -> str:
    from xacrokit.reader.robot_input import RobotInput
    from xacrokit.reader.robot_source import read_source

    return read_source(RobotInput(path)).text


def load(path, tmp_path, **options):
    model = export_mjcf(path, **options)
    target = tmp_path / "model" / "robot.xml"
    write_export(model, target)
    return mujoco.MjModel.from_xml_path(str(target)), model


def compare_dynamics(m, urdf: str, free: bool, rng, export=None) -> None:
    """M(q) and g(q) of MuJoCo's model against pinocchio's of the URDF at random q (a free base at identity
    orientation, where MuJoCo's world-frame linear velocity is pinocchio's local one); with the ``export``, what its
    inertia repairs may add to an entry of M (their 2-norms summed: each changes M_ij = a_i^T dI a_j by at most its
    norm, the a unit axes), gravity untouched by them. Moving links without mass get 1e-12 kg and 1e-14 kg m^2:
    allowed for by 1e-11 N m s^2 each (1e-12 kg at up to 3 m)."""
    bound = 0.0 if export is None else sum(export.repairs.values()) + 1e-11 * len(export.massless)
    model = pin.buildModelFromXML(urdf, pin.JointModelFreeFlyer()) if free else pin.buildModelFromXML(urdf)
    model.gravity = pin.Motion(np.array([0.0, 0.0, -9.80665, 0.0, 0.0, 0.0]))  # (standard gravity: pinocchio's is 9.81)
    data = model.createData()
    d = mujoco.MjData(m)
    order = []  # pinocchio's v index of each MuJoCo dof
    for j in range(m.njnt):
        name = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j)
        joint = model.joints[1] if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE else model.joints[model.getJointId(name)]
        order.extend(range(joint.idx_v, joint.idx_v + joint.nv))
    assert sorted(order) == list(range(model.nv)), "every dof of pinocchio's model is one of MuJoCo's"
    for _ in range(5):
        q = pin.neutral(model)
        d.qpos[:] = m.qpos0
        for j in range(m.njnt):
            name = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j)
            address = m.jnt_qposadr[j]
            if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE:
                position = rng.uniform(-1, 1, 3)
                d.qpos[address : address + 7] = [*position, 1, 0, 0, 0]
                q[:3] = position
                continue
            joint = model.joints[model.getJointId(name)]
            value = rng.uniform(-1.5, 1.5)
            d.qpos[address] = value
            if joint.nq == 2:
                q[joint.idx_q : joint.idx_q + 2] = np.cos(value), np.sin(value)
            else:
                q[joint.idx_q] = value
        d.qvel[:] = 0
        mujoco.mj_forward(m, d)
        dense = np.zeros((m.nv, m.nv))
        mujoco.mj_fullM(m, d, dense)  # (MuJoCo 4: from d, into dst)
        want = pin.crba(model, data, q)
        want = np.triu(want) + np.triu(want, 1).T
        want = want[np.ix_(order, order)]
        if m.nv == 0:
            return
        assert np.abs(dense - want).max() <= 1e-9 * np.abs(want).max() + bound
        gravity = pin.computeGeneralizedGravity(model, data, q)[order]
        assert np.abs(d.qfrc_bias - gravity).max() <= 1e-9 * max(np.abs(gravity).max(), 1.0)


@pytest.mark.parametrize("example", [*ROBOT_EXAMPLES, *SCENE_EXAMPLES], ids=lambda p: p.stem)
def test_every_example_has_pinocchios_mass_matrix_and_gravity_in_mujoco(example, tmp_path):
    scene = example in SCENE_EXAMPLES  # (compared on fixed bases: pinocchio's URDF model has one free-flyer root)
    m, export = load(example, tmp_path, base="fixed" if scene else "auto")
    urdf = urdf_of(example)
    root = etree.fromstring(urdf.encode("utf-8"))
    links = [link.get("name") for link in root.findall("link")]
    bodies = {mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_BODY, b) for b in range(m.nbody)}
    assert set(links) - {"world"} <= bodies  # (every link a body of its name: none fused away)
    massless = [link.get("name") for link in root.findall("link") if link.find("inertial") is None]
    for name in massless:
        if name != "world":
            assert mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE, name) >= 0, name
    free = m.njnt > 0 and m.jnt_type[0] == mujoco.mjtJoint.mjJNT_FREE
    assert free == (example.stem in ("diff_drive", "rover"))  # (the mobile robots)
    compare_dynamics(m, urdf, free, np.random.default_rng(len(links)), export)


def test_mujocos_own_urdf_import_loses_the_tool_frames_the_export_keeps(tmp_path):
    """The reason for writing MJCF ourselves: MuJoCo's URDF compiler fuses bodies fixed to their parent."""
    example = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
    urdf = urdf_of(example)
    theirs = mujoco.MjModel.from_xml_string(urdf)
    ours, _ = load(example, tmp_path)
    assert mujoco.mj_name2id(theirs, mujoco.mjtObj.mjOBJ_BODY, "tool0") == -1
    assert mujoco.mj_name2id(ours, mujoco.mjtObj.mjOBJ_BODY, "tool0") >= 0
    assert mujoco.mj_name2id(ours, mujoco.mjtObj.mjOBJ_SITE, "tool0") >= 0
    assert theirs.nu == 0 and ours.nu == 6  # (no actuators from MuJoCo's import: a converted arm sags)


def drive(m, d, left: float, right: float, seconds: float) -> None:
    d.ctrl[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, "left_wheel_joint")] = left
    d.ctrl[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, "right_wheel_joint")] = right
    for _ in range(int(round(seconds / m.opt.timestep))):
        mujoco.mj_step(m, d)


def test_the_diff_drive_robot_drives_straight_at_omega_r_and_turns_as_its_separation_says(tmp_path):
    """The diff_drive example: wheels of r = 0.065 m, 0.36 m apart (its spec), velocity actuators on the wheels; on
    a floor, after 1 s to get going, the base's speed over 2 s is omega r (2 %); with 3 and 6 rad/s its yaw rate is
    r (omega_r - omega_l) / separation of the wheels' speeds (2 %), and within 5 % of the commanded ones (a velocity
    servo lags by the load over its gain, effort / (0.1 velocity limit): 1.9 % here, the caster and the wheels'
    width scrubbing as the robot turns)."""
    m, _ = load(REPO / "examples" / "robots" / "diff_drive.yaml", tmp_path, floor=True)
    radius, separation = 0.065, 0.36
    d = mujoco.MjData(m)
    base = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "base_link")
    drive(m, d, 5.0, 5.0, 1.0)
    start = d.xpos[base].copy()
    drive(m, d, 5.0, 5.0, 2.0)
    moved = d.xpos[base] - start
    assert abs(np.linalg.norm(moved[:2]) / 2.0 - 5.0 * radius) < 0.02 * 5.0 * radius
    assert abs(moved[1]) < 0.01 * abs(moved[0])  # (straight: along x, the robot's forward)
    assert moved[0] > 0
    d = mujoco.MjData(m)
    drive(m, d, 3.0, 6.0, 1.0)
    wheels = [
        m.jnt_dofadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, f"{s}_wheel_joint")] for s in ("left", "right")
    ]
    yaw, spin = [], []
    for _ in range(2):
        matrix = d.xmat[base].reshape(3, 3)
        yaw.append(np.arctan2(matrix[1, 0], matrix[0, 0]))
        spin.append(d.qvel[wheels[1]] - d.qvel[wheels[0]])
        drive(m, d, 3.0, 6.0, 0.25)
    rate = (np.unwrap(yaw)[1] - yaw[0]) / 0.25
    kinematic = radius * np.mean(spin) / separation  # (the wheels' own speeds: the servos lag under the turn's load)
    assert abs(rate - kinematic) < 0.02 * kinematic
    assert abs(rate - radius * (6.0 - 3.0) / separation) < 0.05 * radius * 3.0 / separation


def test_an_arm_holds_a_pose_under_gravity_with_its_position_actuators(tmp_path):
    """The UR5 example: its position servos (kp = M_ii (2 pi 10 Hz)^2, carrying the arm's weight) hold a pose away
    from home: each joint within 1e-6 rad after 2 s, and still. The same model without the compensation sags there
    by its static sag (gravity torque over kp): what holds the arm is the servos' carrying its weight."""
    m, _ = load(REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml", tmp_path)
    target = np.array([0.3, -1.0, 1.2, -0.5, 0.8, 0.2])

    def held(model):
        d = mujoco.MjData(model)
        d.qpos[:] = target
        d.ctrl[:] = target
        for _ in range(1000):
            mujoco.mj_step(model, d)
        mujoco.mj_forward(model, d)
        return d

    d = held(m)
    assert np.abs(d.qpos - target).max() < 1e-6 and np.abs(d.qvel).max() < 1e-6
    m.body_gravcomp[:] = 0
    d = held(m)
    kp = -m.actuator_biasprm[:, 1]
    sag = np.abs(d.qfrc_bias) / kp
    assert np.all(np.abs(d.qpos - target) <= sag + 1e-4)
    assert np.abs(d.qpos - target).max() > 1e-3  # (gravity does pull: the hold above is not vacuous)


def test_a_scene_simulates_with_every_robot_and_its_mimic_joints_follow(tmp_path):
    """two_arm_cell: two prefixed arms with grippers; 1 s holding the start with every actuator, no instability,
    every robot's bodies and actuators there, and each mimic joint at offset + multiplier x its leader."""
    m, model = load(REPO / "examples" / "scenes" / "two_arm_cell.yaml", tmp_path)
    urdf = urdf_of(REPO / "examples" / "scenes" / "two_arm_cell.yaml")
    root = etree.fromstring(urdf.encode("utf-8"))
    prefixes = {j.get("name").split("_", 1)[0] for j in root.findall("joint") if j.get("type") != "fixed"}
    assert len(prefixes) >= 2
    actuated = {mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_ACTUATOR, a) for a in range(m.nu)}
    assert all(any(name.startswith(p) for name in actuated) for p in prefixes)
    d = mujoco.MjData(m)
    leader_of = {}
    for joint in root.findall("joint"):
        mimic = joint.find("mimic")
        if mimic is not None:
            leader_of[joint.get("name")] = (mimic.get("joint"), float(mimic.get("multiplier", 1)))
    assert leader_of and m.neq == len(leader_of)
    leader = next(iter(leader_of.values()))[0]
    d.ctrl[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, leader)] = 0.02
    for _ in range(500):
        mujoco.mj_step(m, d)
    assert np.all(np.isfinite(d.qpos)) and d.warning[mujoco.mjtWarning.mjWARN_BADQACC].number == 0
    for follower, (name, multiplier) in leader_of.items():
        q = d.qpos[m.jnt_qposadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, follower)]]
        q_leader = d.qpos[m.jnt_qposadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, name)]]
        assert abs(q - multiplier * q_leader) < 1e-3, follower
    assert abs(d.qpos[m.jnt_qposadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, leader)]] - 0.02) < 2e-3


def test_massless_moving_links_get_the_documented_speck_of_mass(tmp_path):
    urdf = (
        '<robot name="r"><link name="base"/><link name="a"/><link name="b"><inertial><mass value="2"/>'
        '<origin xyz="0.1 0 0" rpy="0.3 0.2 0.1"/><inertia ixx="2" iyy="2.5" izz="3" ixy="0.1" ixz="0.2" iyz="0.3"/>'
        '</inertial></link><joint name="j1" type="revolute"><parent link="base"/><child link="a"/>'
        '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="3" velocity="1"/></joint>'
        '<joint name="j2" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0 0 0.5"/>'
        '<axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="3" velocity="1"/></joint></robot>'
    )
    export = mjcf(read_text(urdf), str)
    assert "given 1e-12 kg, 1e-14 kg m^2: a." in export.xml
    m = mujoco.MjModel.from_xml_string(export.xml)
    assert m.body_mass[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "a")] == MASSLESS[0]
    compare_dynamics(m, urdf, False, np.random.default_rng(1), export)  # (the rotated inertial too)


def test_bad_robots_are_refused_with_nothing_written(tmp_path):
    two_roots = tmp_path / "two.urdf"
    two_roots.write_text('<robot name="t"><link name="a"/><link name="b"/></robot>', encoding="utf-8")
    result = gen_robot("export", two_roots, "--mjcf", "-o", tmp_path / "out" / "t.xml")
    assert result.returncode == 2 and "2 root links" in result.stderr and "Traceback" not in result.stderr
    assert not (tmp_path / "out").exists()
    missing = tmp_path / "m.urdf"
    missing.write_text(
        '<robot name="m"><link name="a"><collision><geometry><mesh filename="gone.stl"/></geometry></collision>'
        "</link></robot>",
        encoding="utf-8",
    )
    result = gen_robot("export", missing, "--mjcf", "-o", tmp_path / "out" / "m.xml")
    assert result.returncode == 2 and "link 'a': collision mesh 'gone.stl' is not there" in result.stderr
    assert not (tmp_path / "out").exists()
    missing.write_text(missing.read_text(encoding="utf-8").replace("collision", "visual"), encoding="utf-8")
    result = gen_robot("export", missing, "--mjcf", "-o", tmp_path / "out" / "m.xml")
    assert result.returncode == 0 and "note: link 'a': visual left out: mesh 'gone.stl' is not there" in result.stderr
    assert mujoco.MjModel.from_xml_path(str(tmp_path / "out" / "m.xml")).ngeom == 0  # (its one visual left out)
    with pytest.raises(XacrokitError, match="auto, fixed or free"):
        export_mjcf(two_roots, base="floating")


@pytest.mark.parametrize(
    ("element", "said"),
    [
        ('<limit lower="-inf" upper="1" effort="1" velocity="1"/>', "joint 'j' limit lower: '-inf' is not 1 finite"),
        ('<origin xyz="0 0 nan"/>', "joint 'j' origin xyz: '0 0 nan' is not 3 finite"),
        ('<axis xyz="0 1"/>', "joint 'j' axis: '0 1' is not 3 finite"),
    ],
)
def test_a_number_that_does_not_read_is_named_by_its_element_and_attribute(tmp_path, element, said):
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        '<robot name="r"><link name="a"/><joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
        + element
        + ('<limit lower="-1" upper="1" effort="1" velocity="1"/>' if "limit" not in element else "")
        + '</joint><link name="b"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/></inertial></link>'
        "</robot>",
        encoding="utf-8",
    )
    with pytest.raises(XacrokitError, match=re.escape(said)):
        export_mjcf(urdf)


@pytest.mark.parametrize(
    ("link_b", "said"),
    [
        (
            '<link name="b"><inertial><mass value="1"/><inertia ixx="1e308" iyy="1e308" izz="1e308"/>'
            "</inertial></link>",
            "link 'b': inertial: a moment of 1e+308 kg m^2 is beyond what xacrokit takes",
        ),
        (
            '<link name="b"><inertial><mass value="1e300"/><inertia ixx="1" iyy="1" izz="1"/></inertial></link>',
            "link 'b': inertial: 1e+300 kg is beyond what xacrokit takes",
        ),
    ],
)
def test_an_inertial_beyond_the_bounds_is_refused_not_a_crash(tmp_path, link_b, said):
    """1e308 inertias crashed the export (numpy's eigensolver: exit 70): refused, naming the link."""
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        '<robot name="r"><link name="a"/><joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>' + link_b + "</robot>",
        encoding="utf-8",
    )
    result = gen_robot("export", urdf, "--mjcf", "-o", tmp_path / "r.xml")
    assert result.returncode == 2 and said in result.stderr, result.stderr
    assert not (tmp_path / "r.xml").exists()


def test_a_link_named_world_below_the_root_is_refused(tmp_path):
    """MuJoCo refuses a body called world that is not its world body: the export said exit 0 and wrote it."""
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        '<robot name="r"><link name="base"/><joint name="j" type="fixed"><parent link="base"/>'
        '<child link="world"/></joint><link name="world"/></robot>',
        encoding="utf-8",
    )
    result = gen_robot("export", urdf, "--mjcf", "-o", tmp_path / "r.xml")
    assert result.returncode == 2 and "link 'world' hangs from joint 'j'" in result.stderr, result.stderr
    assert not (tmp_path / "r.xml").exists()


def _chain(links: int) -> str:
    parts = [
        f'<link name="l{k}"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01"/></inertial>'
        '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>'
        for k in range(links)
    ]
    parts += [
        f'<joint name="j{k}" type="revolute"><parent link="l{k - 1}"/><child link="l{k}"/><origin xyz="0 0 0.1"/>'
        '<axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>'
        for k in range(1, links)
    ]
    return f'<robot name="c">{"".join(parts)}</robot>'


def test_a_tree_deeper_than_mujocos_reader_takes_is_refused_and_the_deepest_it_takes_loads():
    """MuJoCo's XML reader (tinyxml2) refuses elements nested about 500 deep: a chain of 20,000 links once ended in
    exit 70 (RecursionError), one of 491 in a model MuJoCo refuses; 490 loads (issue 28). The long chain here is 5,000
    links, five times Python's recursion limit (1,000: a walk that recursed a link a level failed at any depth past
    it), read in 0.6 s where 20,000 took 2.7 s."""
    from xacrokit.export.mjcf import MAX_DEPTH

    model = mujoco.MjModel.from_xml_string(mjcf(read_text(_chain(MAX_DEPTH)), str).xml)
    assert model.nbody == MAX_DEPTH + 1
    assert sys.getrecursionlimit() <= 1_000
    for links in (MAX_DEPTH + 1, 5_000):
        with pytest.raises(XacrokitError, match=f"the robot's tree is {links} links deep"):
            mjcf(read_text(_chain(links)), str)


def test_links_in_a_loop_off_the_root_are_refused_not_dropped():
    urdf = (
        '<robot name="r"><link name="base"/><link name="a"/><link name="b"/>'
        '<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>'
        '<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint></robot>'
    )
    with pytest.raises(XacrokitError, match="links 'a', 'b' hang in a loop of joints"):
        mjcf(read_text(urdf), str)
