"""The UR10e example (issue 31) against Universal Robots' published numbers, each an independent oracle:

- its forward kinematics equals the product of UR's standard DH table (UR's "DH parameters for calculations of
  kinematics and dynamics" article, UR10e rows) to 1e-9 m, tool0 in base, at random joint values;
- every named frame sits where UR's own ROS 2 description puts it: the chain of Universal_Robots_ROS2_Description
  2.4.5 (urdf/ur_macro.xacro's fixed joints, config/ur10e/default_kinematics.yaml's joint origins), rebuilt here
  from those numbers, read by yourdfpy from our URDF;
- each link's mass, centre of mass and tensor equal UR's config/ur10e/physical_parameters.yaml (which states them in
  UR's link frames), and the limits its joint_limits.yaml;
- its tree is UR's (issue 42): the links and joints of urdf/ur_macro.xacro, named as there, with the same parents,
  children, types and origins, so that a launch file or a tf listener written for UR's description works unchanged;
  and the names changed nothing else: tool0 is where the example put it before (its numbers to 1e-12).
"""

from __future__ import annotations

import io
import math

import numpy as np
import pytest
import yourdfpy
from hypothesis import given, settings
from hypothesis import strategies as st
from lxml import etree
from scipy.spatial.transform import Rotation

import xacrokit
from conftest import REPO
from xacrokit.kinematics import pose
from xacrokit.reader.read_robot import read_robot

UR10E = REPO / "examples" / "robots" / "ur10e.yaml"
JOINTS = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint", "wrist_3_joint"]

# UR's DH article, UR10e: a, d (m), alpha (rad)
A = [0.0, -0.6127, -0.57155, 0.0, 0.0, 0.0]
D = [0.1807, 0.0, 0.0, 0.17415, 0.11985, 0.11655]
ALPHA = [math.pi / 2, 0.0, 0.0, math.pi / 2, -math.pi / 2, 0.0]

# UR's config/ur10e/default_kinematics.yaml: joint origins (x, y, z, roll, pitch, yaw), parent link -> link
KINEMATICS = {
    "shoulder_link": (0, 0, 0.1807, 0, 0, 0),
    "upper_arm_link": (0, 0, 0, 1.570796327, 0, 0),
    "forearm_link": (-0.6127, 0, 0, 0, 0, 0),
    "wrist_1_link": (-0.57155, 0, 0.17415, 0, 0, 0),
    "wrist_2_link": (0, -0.11985, -2.458164590756244e-11, 1.570796327, 0, 0),
    "wrist_3_link": (0, 0.11655, -2.390480459346185e-11, 1.570796326589793, 3.141592653589793, 3.141592653589793),
}
# ur_macro.xacro's fixed joints: child -> (parent, rpy)
FIXED = {
    "base_link_inertia": ("base_link", (0, 0, math.pi)),
    "base": ("base_link", (0, 0, math.pi)),
    "flange": ("wrist_3_link", (0, -math.pi / 2, -math.pi / 2)),
    "tool0": ("flange", (math.pi / 2, 0, math.pi / 2)),
    "ft_frame": ("wrist_3_link", (math.pi, 0, 0)),
}
# The tree of Universal_Robots_ROS2_Description 2.4.5 (commit 2221ec0f, tag 2.4.5), urdf/ur_macro.xacro, macro
# ur_robot with tf_prefix '': joint -> (type, parent, child). Its base_joint (fixed, `parent` -> base_link) mounts the
# robot on the macro's `parent` and is the mount joint here (test_mounted_as_urs_macro_mounts_it).
UR_JOINTS = {
    "base_link-base_link_inertia": ("fixed", "base_link", "base_link_inertia"),
    "shoulder_pan_joint": ("revolute", "base_link_inertia", "shoulder_link"),
    "shoulder_lift_joint": ("revolute", "shoulder_link", "upper_arm_link"),
    "elbow_joint": ("revolute", "upper_arm_link", "forearm_link"),
    "wrist_1_joint": ("revolute", "forearm_link", "wrist_1_link"),
    "wrist_2_joint": ("revolute", "wrist_1_link", "wrist_2_link"),
    "wrist_3_joint": ("revolute", "wrist_2_link", "wrist_3_link"),  # (revolute: UR10e's wrist 3 has limits)
    "wrist_3_link-ft_frame": ("fixed", "wrist_3_link", "ft_frame"),
    "base_link-base_fixed_joint": ("fixed", "base_link", "base"),
    "wrist_3-flange": ("fixed", "wrist_3_link", "flange"),
    "flange-tool0": ("fixed", "flange", "tool0"),
}
UR_LINKS = {
    "base_link",
    "base_link_inertia",
    "shoulder_link",
    "upper_arm_link",
    "forearm_link",
    "wrist_1_link",
    "wrist_2_link",
    "wrist_3_link",
    "ft_frame",
    "base",
    "flange",
    "tool0",
}
# tool0 in base_link at joint values (shoulder_pan .. wrist_3), as the example put it before it took UR's tree and
# names (commit 1d4ab59: ur10e_base between base_link_inertia and shoulder_pan_joint, its own joint names): rows 0-2
TOOL0_BEFORE = [
    (
        (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
        [
            [-1.0, 2.2204460492503128e-16, 3.4450928483976665e-16, 1.18425],
            [3.4450928483976655e-16, -2.2204460492503136e-16, 1.0, 0.29069999999999985],
            [2.220446049250313e-16, 1.0, 2.2204460492503126e-16, 0.06085000000000007],
        ],
    ),
    (
        (-1.57, -1.57, 0.0, -1.57, 0.0, 0.0),
        [
            [0.0007963257007741264, -1.2682720581036322e-06, 0.9999996829318346, 0.2907008108065209],
            [-0.9999984146597763, 0.001592652411507512, 0.0007963267107333629, -0.000902436824883788],
            [-0.0015926529164870503, -0.9999987317275396, 2.223982449126554e-16, 1.4847994725095706],
        ],
    ),
    (
        (0.3, -1.1, 2.0, -0.7, 1.2, -2.5),
        [
            [0.3788829710840468, -0.5199404413445418, 0.7655779723039114, 0.6199348180460307],
            [-0.6644042140885603, 0.42304102071896754, 0.6161195785644346, 0.4182673501726178],
            [-0.6442163724432094, -0.7420904474816378, -0.18516758148394918, 0.13998999333582632],
        ],
    ),
    (
        (-5.5, 4.0, -3.0, 6.1, -0.4, 2.2),
        [
            [0.5189327417893931, -0.1648987006565875, -0.8387593385594655, -0.34751074703394313],
            [0.8400260977899763, 0.28010316453677886, 0.46464865462866434, 0.0512464543670122],
            [0.15831918560518352, -0.9457011344702146, 0.28387391520014676, 0.11449273435162129],
        ],
    ),
]
# physical_parameters.yaml: mass, cog (in UR's link frame), rotation (roll of the tensor's frame), tensor
PHYSICAL = {
    "shoulder_link": (
        7.369,
        (0.021, -0.027, 0.0),
        math.pi / 2,
        (0.03408, 0.00002, -0.00425, 0.03529, 0.00008, 0.02156),
    ),
    "upper_arm_link": (13.051, (-0.2327, 0.0, 0.158), 0.0, (0.02814, 0.00005, -0.01561, 0.77068, 0.00002, 0.76943)),
    "forearm_link": (3.989, (-0.33155, 0.0, 0.068), 0.0, (0.01014, 0.00008, 0.00916, 0.30928, 0.0, 0.30646)),
    "wrist_1_link": (2.1, (0.0, -0.018, 0.007), math.pi / 2, (0.00296, -0.00001, 0.0, 0.00222, -0.00024, 0.00258)),
    "wrist_2_link": (1.98, (0.0, 0.018, -0.007), -math.pi / 2, (0.00296, -0.00001, 0.0, 0.00222, -0.00024, 0.00258)),
    "wrist_3_link": (0.615, (0.0, 0.0, -0.026), 0.0, (0.00040, 0.0, 0.0, 0.00041, 0.0, 0.00034)),
}
# joint_limits.yaml: effort (N*m), velocity (deg/s), position (+- deg)
LIMITS = {
    "shoulder_pan_joint": (330.0, 120.0, 360.0),
    "shoulder_lift_joint": (330.0, 120.0, 360.0),
    "elbow_joint": (150.0, 180.0, 180.0),
    "wrist_1_joint": (54.0, 180.0, 360.0),
    "wrist_2_joint": (54.0, 180.0, 360.0),
    "wrist_3_joint": (54.0, 180.0, 360.0),
}


def _rpy(roll, pitch, yaw):
    """URDF's rpy: Rz(yaw) Ry(pitch) Rx(roll), i.e. extrinsic x-y-z (scipy's, not our own code)."""
    return Rotation.from_euler("xyz", [roll, pitch, yaw]).as_matrix()


def _pose(x, y, z, roll, pitch, yaw):
    out = np.eye(4)
    out[:3, :3], out[:3, 3] = _rpy(roll, pitch, yaw), (x, y, z)
    return out


def _ur_dh(q):
    """tool0 in base: the DH product Rz(q) Tz(d) Tx(a) Rx(alpha), row by row."""
    out = np.eye(4)
    for qi, a, d, alpha in zip(q, A, D, ALPHA, strict=True):
        ct, st_, ca, sa = math.cos(qi), math.sin(qi), math.cos(alpha), math.sin(alpha)
        out = out @ np.array(
            [[ct, -st_ * ca, st_ * sa, a * ct], [st_, ct * ca, -ct * sa, a * st_], [0, sa, ca, d], [0, 0, 0, 1]]
        )
    return out


def _ur_description_frames(q):
    """Every named frame of UR's description in base_link, at joint values q."""
    frames = {"base_link": np.eye(4)}
    for child, (parent, rpy) in FIXED.items():
        if parent in frames:
            frames[child] = frames[parent] @ _pose(0, 0, 0, *rpy)
    parent = "base_link_inertia"
    for (link, origin), qi in zip(KINEMATICS.items(), q, strict=True):
        frames[link] = frames[parent] @ _pose(*origin) @ _pose(0, 0, 0, 0, 0, qi)
        parent = link
    for child, (parent, rpy) in FIXED.items():
        if child not in frames:
            frames[child] = frames[parent] @ _pose(0, 0, 0, *rpy)
    return frames


@pytest.fixture(scope="module")
def ours():
    text = read_robot(UR10E).text
    return yourdfpy.URDF.load(io.BytesIO(text.encode("utf-8")), load_meshes=False, build_scene_graph=True)


def _our_frames(ours, q):
    """Every link of our URDF (as yourdfpy parses it) in its root, at joint values q: each joint's origin, then its
    turn about its axis (scipy's rotation vector). Composed here, not by yourdfpy's scene graph: trimesh caches a
    transform under a hash that a change of about 1e-9 rad leaves the same, so a posed robot keeps the last pose's."""
    by_child = {joint.child: joint for joint in ours.joint_map.values()}
    frames: dict[str, np.ndarray] = {}

    def frame(link):
        if link not in frames:
            joint = by_child.get(link)
            if joint is None:
                frames[link] = np.eye(4)
            else:
                turn = np.eye(4)
                if joint.type in ("revolute", "continuous"):
                    axis = np.asarray(joint.axis, dtype=float)
                    turn[:3, :3] = Rotation.from_rotvec(axis / np.linalg.norm(axis) * q[joint.name]).as_matrix()
                frames[link] = frame(joint.parent) @ joint.origin @ turn
        return frames[link]

    return {link: frame(link) for link in ours.link_map}


joint_values = st.lists(st.floats(-2 * math.pi, 2 * math.pi, allow_nan=False), min_size=6, max_size=6)


@settings(max_examples=25, deadline=None)
@given(q=joint_values)
def test_tool0_in_base_is_urs_dh_product(q):
    q[2] = max(-math.pi, min(math.pi, q[2]))  # (the elbow's limit)
    found = pose(UR10E, "tool0", in_frame="base", at={j: repr(v) for j, v in zip(JOINTS, q, strict=True)}).matrix
    expected = _ur_dh(q)
    assert np.abs(found[:3, 3] - expected[:3, 3]).max() < 1e-9
    assert np.abs(found[:3, :3] - expected[:3, :3]).max() < 1e-9


@settings(max_examples=15, deadline=None)
@given(q=joint_values)
def test_every_named_frame_is_where_urs_description_puts_it(ours, q):
    q[2] = max(-math.pi, min(math.pi, q[2]))
    theirs = _ur_description_frames(q)
    assert set(theirs) <= set(ours.link_map)
    placed = _our_frames(ours, dict(zip(JOINTS, q, strict=True)))
    for frame, expected in theirs.items():
        found = placed[frame] if frame == "base_link" else np.linalg.inv(placed["base_link"]) @ placed[frame]
        # UR's calibration numbers carry 1e-11 m and 1e-10 rad of rounding (its 1.570796327 for pi/2)
        assert np.abs(found[:3, 3] - expected[:3, 3]).max() < 1e-9, frame
        assert np.abs(found[:3, :3] - expected[:3, :3]).max() < 1e-9, frame


def test_masses_centres_of_mass_and_tensors_are_urs(ours):
    for link, (mass, cog, roll, tensor) in PHYSICAL.items():
        inertial = ours.link_map[link].inertial
        assert inertial.mass == mass, link
        assert np.abs(inertial.origin[:3, 3] - cog).max() < 1e-12, link
        # the tensor is UR's in its rotated frame: compare it turned into the link frame both ways
        ours_in_link = inertial.origin[:3, :3] @ inertial.inertia @ inertial.origin[:3, :3].T
        ixx, ixy, ixz, iyy, iyz, izz = tensor
        turn = _rpy(roll, 0, 0)
        theirs_in_link = turn @ np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]]) @ turn.T
        assert np.abs(ours_in_link - theirs_in_link).max() < 1e-15, link
    assert ours.link_map["base_link_inertia"].inertial.mass == 4.0
    assert ours.link_map["base_link"].inertial is None  # (UR's mounting frame has no body)


def test_limits_are_urs(ours):
    for name, (effort, velocity, position) in LIMITS.items():
        limit = ours.joint_map[name].limit
        assert limit.effort == effort and limit.velocity == pytest.approx(math.radians(velocity), rel=1e-15), name
        assert limit.lower == pytest.approx(-math.radians(position), rel=1e-15), name
        assert limit.upper == pytest.approx(math.radians(position), rel=1e-15), name


def _urdf_tree(root):
    """(links, {joint: (type, parent, child)}) of a parsed URDF."""
    links = {e.get("name") for e in root.findall("link")}
    joints = {
        e.get("name"): (e.get("type"), e.find("parent").get("link"), e.find("child").get("link"))
        for e in root.findall("joint")
    }
    return links, joints


def test_the_tree_is_urs_link_by_link_and_joint_by_joint(ours):
    root = etree.fromstring(read_robot(UR10E).text.encode("utf-8"))
    links, joints = _urdf_tree(root)
    assert links == UR_LINKS
    assert joints == UR_JOINTS
    # origins, joint by joint: the fixed ones as ur_macro.xacro writes them, the moving ones as its
    # default_kinematics.yaml places them (to its calibration's rounding, 1e-10)
    for child, (_, rpy) in FIXED.items():
        name = next(n for n, (_, _, c) in UR_JOINTS.items() if c == child)
        assert np.abs(ours.joint_map[name].origin - _pose(0, 0, 0, *rpy)).max() < 1e-15, name
    for (link, origin), name in zip(KINEMATICS.items(), JOINTS, strict=True):
        assert ours.joint_map[name].child == link
        assert np.abs(ours.joint_map[name].origin - _pose(*origin)).max() < 1e-9, name


@pytest.mark.parametrize(("q", "before"), TOOL0_BEFORE)
def test_tool0_is_where_the_example_put_it_before_it_took_urs_names(q, before):
    found = pose(UR10E, "tool0", in_frame="base_link", at={j: repr(v) for j, v in zip(JOINTS, q, strict=True)})
    assert np.abs(found.matrix[:3] - np.array(before)).max() <= 1e-12


@pytest.mark.parametrize("mode", ["inline", "copy"])
def test_mounted_as_urs_macro_mounts_it(tmp_path, mode):
    # UR's ur.urdf.xacro: a link world and ur_robot(tf_prefix, parent="world") -> base_joint, world -> base_link; here
    # the entry's world:=true (a scene's instance, the macro's parent too), with a prefix as UR's tf_prefix
    out = tmp_path / "ur10e_description"
    xacrokit.generate(UR10E, out, macros=mode)
    text = xacrokit.expand(
        out / "urdf" / "ur10e.urdf.xacro", {"world": "true", "prefix": "left_"}, package_paths={out.name: out}
    )
    links, joints = _urdf_tree(etree.fromstring(text.encode("utf-8")))
    expected = {"left_base_joint": ("fixed", "world", "left_base_link")}
    expected |= {"left_" + name: (kind, "left_" + p, "left_" + c) for name, (kind, p, c) in UR_JOINTS.items()}
    assert joints == expected
    assert links == {"world"} | {"left_" + name for name in UR_LINKS}
