"""Free bases in the exported MuJoCo model (issue 41): each robot of a scene on its own free joint where the scene puts
it (MuJoCo refuses a joint on the world body), mobile robots free by default, a free robot standing on the floor at
every keyframe (its lowest collision point at z = 0) and odd robots (no joint, a fixed joint to world, a floating
joint below the root, names XML must escape, a name the export would give twice) written as models MuJoCo loads."""

from __future__ import annotations

import numpy as np
import pytest
import yaml
from lxml import etree

from conftest import REPO, gen_robot, tetrahedron_stl

mujoco = pytest.importorskip("mujoco")

FLEET = REPO / "examples" / "scenes" / "diff_drive_fleet.yaml"
HUMANOID = REPO / "examples" / "robots" / "winter_humanoid.yaml"  # (its torso frame 0.62 m above its soles)
INERTIA = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'


def export(path, tmp_path, *options):
    """``gen-robot export PATH --mjcf OPTIONS``: its exit code, its stderr, the parsed MJCF and MuJoCo's model."""
    target = tmp_path / "model" / "robot.xml"
    done = gen_robot("export", path, "--mjcf", "-o", target, *options)
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr
    return etree.parse(str(target)).getroot(), mujoco.MjModel.from_xml_path(str(target))


def lowest(m, d) -> float:
    """The least distance from the floor to a collision geom (negative: into it), MuJoCo's own (mj_geomDistance of
    the floor plane and each geom that collides)."""
    mujoco.mj_forward(m, d)
    floor = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "floor")
    geoms = [g for g in range(m.ngeom) if g != floor and m.geom_contype[g] and m.geom_bodyid[g] != 0]
    assert geoms, "the robot has collision geometry"
    return min(mujoco.mj_geomDistance(m, d, floor, g, 10.0, np.zeros(6)) for g in geoms)


def body_xy(m, d, name) -> np.ndarray:
    return d.xpos[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, name)][:2].copy()


def step(m, d, seconds: float) -> float:
    """Simulate ``seconds``; the deepest contact penetration on the way (0 for none)."""
    deepest = 0.0
    for _ in range(round(seconds / m.opt.timestep)):
        mujoco.mj_step(m, d)
        deepest = min(deepest, min((c.dist for c in d.contact[: d.ncon]), default=0.0))
    return deepest


def scene_robots(path) -> dict[str, list[float]]:
    """A scene's instances hung from world: the root body's name -> the xyz the scene places it at."""
    scene = yaml.safe_load(path.read_text(encoding="utf-8"))
    found = {}
    for instance in scene["instances"].values():
        if instance.get("parent", "world") == "world":
            found[f"{instance['prefix']}base_footprint"] = instance.get("origin", {}).get("xyz", [0, 0, 0])
    return found


def test_a_free_fleet_on_a_floor_frees_each_robot_where_the_scene_puts_it_and_one_drives(tmp_path):
    """`--base free --floor` of the diff-drive fleet wrote a free joint on the world body, which MuJoCo refuses
    (exit 0): each robot's root body gets its own, at the scene's place, and a robot driven goes while the others
    stay."""
    root, m = export(FLEET, tmp_path, "--base", "free", "--floor")
    world = root.find("worldbody")
    assert world.find("freejoint") is None and world.find("joint") is None
    placed = scene_robots(FLEET)
    assert len(placed) == 10
    free = {body.get("name"): body for body in world.findall("body") if body.find("freejoint") is not None}
    assert set(free) == set(placed)
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, 0)
    for name, xyz in placed.items():
        joint = m.body(name).jntadr[0]
        assert m.jnt_type[joint] == mujoco.mjtJoint.mjJNT_FREE
        assert d.qpos[m.jnt_qposadr[joint] : m.jnt_qposadr[joint] + 2] == pytest.approx(xyz[:2], abs=1e-12)
    assert abs(lowest(m, d)) < 1e-6  # (standing on the floor: its wheels and casters at z = 0)
    for side in ("left", "right"):
        d.ctrl[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, f"r3_{side}_wheel_joint")] = 5.0
    start = {name: body_xy(m, d, name) for name in placed}
    assert step(m, d, 1.0) > -5e-3  # (MuJoCo's soft contacts give a millimetre or so)
    moved = {name: np.linalg.norm(body_xy(m, d, name) - start[name]) for name in placed}
    assert moved.pop("r3_base_footprint") > 0.2  # (5 rad/s x 0.065 m for 1 s, less the start: ~0.3 m)
    assert max(moved.values()) < 1e-3


def test_by_default_the_robots_of_a_fleet_are_free_to_drive_and_fixed_welds_them(tmp_path):
    """Without `--base`, a fleet was welded to the world (its wheels turned, nothing went): auto frees each robot
    with a wheel, as it frees one mobile robot; `--base fixed` still welds them all."""
    root, m = export(FLEET, tmp_path / "auto", "--floor")
    assert sum(m.jnt_type == mujoco.mjtJoint.mjJNT_FREE) == 10
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, 0)
    d.ctrl[:] = 5.0
    start = body_xy(m, d, "r0_base_footprint")
    step(m, d, 1.0)
    assert np.linalg.norm(body_xy(m, d, "r0_base_footprint") - start) > 0.2
    root, m = export(FLEET, tmp_path / "fixed", "--base", "fixed", "--floor")
    assert root.find(".//freejoint") is None and not any(m.jnt_type == mujoco.mjtJoint.mjJNT_FREE)


def test_a_free_humanoid_stands_on_the_floor_at_home_and_does_not_sink(tmp_path):
    """The humanoid's home put its torso at z = 0 and its soles 0.62 m under the floor: at home and at the model's
    zero pose its lowest collision point is at z = 0 (1e-6), and after 1 s it still stands on it; without a floor
    it stands on z = 0 all the same."""
    root, m = export(HUMANOID, tmp_path, "--base", "free", "--floor")
    home = [float(v) for v in root.find("keyframe/key[@name='home']").get("qpos").split()]
    assert home[:3] == pytest.approx([0.0, 0.0, 0.62], abs=1e-12)  # (0.30 thigh + 0.32 shin below the hips)
    d = mujoco.MjData(m)
    mujoco.mj_resetData(m, d)
    assert abs(lowest(m, d)) < 1e-6
    mujoco.mj_resetDataKeyframe(m, d, 0)
    assert abs(lowest(m, d)) < 1e-6
    assert step(m, d, 1.0) > -5e-3  # (MuJoCo's soft contacts give a millimetre or so)
    assert d.qpos[2] > 0.6  # (the torso still 0.62 m up, give or take the contacts' give)
    root, m = export(HUMANOID, tmp_path / "no_floor", "--base", "free")  # (for a scene that brings its own floor)
    assert root.find("worldbody/geom[@name='floor']") is None
    assert root.find("keyframe/key[@name='home']").get("qpos").split()[:3] == ["0", "0", "0.62"]
    assert root.find("worldbody/body[@name='torso']").get("pos") == "0 0 0.62"


def test_every_keyframe_of_a_free_robot_stands_on_the_floor_whatever_its_pose(tmp_path):
    """A free robot whose poses reach lower or higher (a leg bent at the knee, a pose held on one mesh foot tilted by
    its joint): each keyframe lifts or lowers it so its lowest collision point is at z = 0."""
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "foot.stl").write_bytes(tetrahedron_stl())
    spec = {
        "robot": "hopper",
        "links": {
            "body": {"shape": {"box": {"size": [0.3, 0.2, 0.1]}}, "mass": 3.0},
            "leg": {"shape": {"cylinder": {"radius": 0.03, "length": 0.4}}, "origin": {"xyz": [0, 0, -0.2]}, "mass": 1},
            "foot": {"shape": {"mesh": {"filename": "meshes/foot.stl", "scale": [0.1, 0.1, 0.1]}}, "mass": 0.2},
        },
        "joints": {
            "hip": {
                "type": "revolute",
                "parent": "body",
                "child": "leg",
                "origin": {"xyz": [0, 0, -0.05]},
                "axis": [0, 1, 0],
                "limit": {"lower": -1.5, "upper": 1.5, "effort": 50, "velocity": 1},
            },
            "ankle": {
                "type": "revolute",
                "parent": "leg",
                "child": "foot",
                "origin": {"xyz": [0, 0, -0.4]},
                "axis": [1, 0, 0],
                "limit": {"lower": -1, "upper": 1, "effort": 50, "velocity": 1},
            },
        },
        "poses": {"home": {"hip": 0.3, "ankle": 0.7}, "tucked": {"hip": 1.4}, "low": {"ankle": -0.9}},
        "ros2_control": {},
    }
    path = tmp_path / "hopper.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    root, m = export(path, tmp_path, "--base", "free", "--floor")
    assert m.nkey == 3
    d = mujoco.MjData(m)
    heights = []
    for key in range(m.nkey):
        mujoco.mj_resetDataKeyframe(m, d, key)
        assert abs(lowest(m, d)) < 1e-6, mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_KEY, key)
        heights.append(d.qpos[2])
    assert max(heights) - min(heights) > 0.05  # (the poses do differ in height: not one lift for all)


def test_a_robot_a_scene_places_above_the_floor_keeps_its_place_and_one_below_is_raised(tmp_path):
    """A scene's placement is the scene's: a free robot put 0.3 m up (on something, perhaps) stays there; one put
    into the floor is raised until it stands on it."""
    robot = tmp_path / "diff_drive.yaml"
    robot.write_text((REPO / "examples" / "robots" / "diff_drive.yaml").read_text(encoding="utf-8"), encoding="utf-8")
    instances = {
        "up": {"spec": "diff_drive.yaml", "prefix": "up_", "parent": "world", "origin": {"xyz": [0, 0, 0.3]}},
        "down": {"spec": "diff_drive.yaml", "prefix": "down_", "parent": "world", "origin": {"xyz": [2, 0, -0.1]}},
    }
    scene = tmp_path / "scene.yaml"
    scene.write_text(yaml.safe_dump({"scene": "two", "instances": instances}), encoding="utf-8")
    root, m = export(scene, tmp_path, "--floor")
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, 0)
    joints = {name: m.jnt_qposadr[m.body(f"{name}_base_footprint").jntadr[0]] for name in ("up", "down")}
    assert d.qpos[joints["up"] : joints["up"] + 3] == pytest.approx([0, 0, 0.3], abs=1e-12)
    assert d.qpos[joints["down"] : joints["down"] + 3] == pytest.approx([2, 0, 0], abs=1e-12)


def urdf(tmp_path, body: str, name: str = "r") -> str:
    path = tmp_path / f"{name}.urdf"
    path.write_text(f'<robot name="{name}">{body}</robot>', encoding="utf-8")
    return path


@pytest.mark.parametrize("base", ["auto", "fixed", "free"])
def test_odd_robots_give_models_mujoco_loads_and_simulates(tmp_path, base):
    """A robot of one link; one fixed to a link called world (`--base free` frees the robot, not the world body);
    a floating joint below the root (MuJoCo takes a free joint only on a body of the world: three slides and a
    ball); names with &, <, >, quotes and a newline; and a URDF joint already called what the export names a free
    joint: each a model MuJoCo loads and steps, every URDF name kept."""
    box = '<collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>'
    link, joint = "a &amp; &quot;q&quot; &lt;b&gt;", "j &lt;1&gt; --&#10;"  # (a & "q" <b>, and a newline)
    limit = '<limit lower="-1" upper="1" effort="10" velocity="1"/>'
    robots = {
        "one_link": f'<link name="only">{INERTIA}{box}</link>',
        "to_world": '<link name="world"/><joint name="fix" type="fixed"><parent link="world"/><child link="base"/>'
        f'<origin xyz="1 2 0.5"/></joint><link name="base">{INERTIA}{box}</link>',
        "deep_floating": f'<link name="base">{INERTIA}{box}</link><joint name="f" type="floating">'
        f'<parent link="base"/><child link="b"/><origin xyz="0.5 0 0"/></joint><link name="b">{INERTIA}{box}</link>'
        '<joint name="f_x" type="fixed"><parent link="b"/><child link="c"/></joint><link name="c"/>',
        "escaped": f'<link name="{link}">{INERTIA}{box}</link><joint name="{joint}" type="revolute">'
        f'<parent link="{link}"/><child link="arm\'s"/><origin xyz="0 0 0.3"/><axis xyz="0 1 0"/>{limit}</joint>'
        f'<link name="arm\'s">{INERTIA}</link><ros2_control name="c" type="system"><hardware><plugin>x</plugin>'
        f'</hardware><joint name="{joint}"><command_interface name="position"/></joint></ros2_control>',
        "clash": f'<link name="base">{INERTIA}{box}</link><joint name="base_free" type="continuous">'
        f'<parent link="base"/><child link="wheel"/><axis xyz="0 1 0"/></joint><link name="wheel">{INERTIA}'
        '<collision><geometry><cylinder radius="0.1" length="0.05"/></geometry></collision></link>',
    }
    for name, body in robots.items():
        path = urdf(tmp_path, body, name)
        links = [link.get("name") for link in etree.parse(str(path)).getroot().findall("link")]
        joints = [joint.get("name") for joint in etree.parse(str(path)).getroot().findall("joint")]
        root, m = export(path, tmp_path / name / base, "--base", base, "--floor")
        bodies = {m.body(b).name for b in range(m.nbody)}
        assert set(links) <= bodies, name
        names = {m.joint(j).name for j in range(m.njnt)}
        assert {j for j, t in zip(joints, _types(path), strict=True) if t not in ("fixed", "floating")} <= names
        assert len(names) == m.njnt, name  # (each joint's name once)
        d = mujoco.MjData(m)
        mujoco.mj_resetDataKeyframe(m, d, 0)
        step(m, d, 0.2)
        assert np.all(np.isfinite(d.qpos)), name
        free = [m.body(m.jnt_bodyid[j]).name for j in range(m.njnt) if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE]
        root_link = {"one_link": "only", "escaped": 'a & "q" <b>'}.get(name, "base")  # (to_world's: not world)
        assert free == ([root_link] if base == "free" or (base == "auto" and name == "clash") else []), name


def _types(path) -> list[str]:
    return [joint.get("type") for joint in etree.parse(str(path)).getroot().findall("joint")]


def test_a_robot_fixed_to_world_freed_stands_where_its_joint_puts_it_in_x_and_y(tmp_path):
    """`--base free` of a robot that a URDF fixes to a link called world: its base (not the world body) is free, where
    the fixed joint puts it (a placement is kept, raised only out of the floor: 0.5 m up), and it falls onto the
    floor."""
    path = urdf(
        tmp_path,
        '<link name="world"/><joint name="fix" type="fixed"><parent link="world"/><child link="base"/>'
        f'<origin xyz="1 2 0.5"/></joint><link name="base">{INERTIA}'
        '<collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>',
    )
    root, m = export(path, tmp_path, "--base", "free", "--floor")
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, 0)
    assert d.qpos[:3] == pytest.approx([1, 2, 0.5], abs=1e-12)
    step(m, d, 1.0)
    assert d.qpos[:3] == pytest.approx([1, 2, 0.1], abs=2e-3)  # (landed on the floor: half its 0.2 m box up)
