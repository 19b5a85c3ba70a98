"""A spec's `mirror:` (issue 29, item 5): for every link L of a mirrored subtree and any joint values set equally on
each joint and its copy, pose(mirror(L)) = S pose(L) S in the parent frame of the mirrored joint, S the reflection;
each inertial and visual placed as the mirror image (tensor S I S, mesh scale flipped); checked with yourdfpy's
forward kinematics (an independent reader) on random limbs. Then the humanoid example against its hand-written
twin, a quadruped's legs from one by two mirrors, a lidar's rays, and the located errors."""

from __future__ import annotations

import io
import math
from pathlib import Path

import numpy as np
import pytest
import yaml
import yourdfpy
from hypothesis import given, settings
from hypothesis import strategies as st
from lxml import etree

from conftest import REPO
from xacrokit.emit import emit_urdf, urdf_differences
from xacrokit.errors import SpecErrors
from xacrokit.load import load_file, load_text
from xacrokit.resolve import resolve
from xacrokit.testing import mirrored_specs
from xacrokit.validate import validate

NORMAL = {"yz": 0, "xz": 1, "xy": 2}
HUMANOID = REPO / "examples" / "robots" / "humanoid_upper_body.yaml"
CASES = Path(__file__).parent / "mirror_cases"


def _urdf(spec: dict | str) -> str:
    text = spec if isinstance(spec, str) else yaml.safe_dump(spec, sort_keys=False)
    return emit_urdf(resolve(validate(load_text(text, "mirror.yaml"))))


def _robot(urdf: str) -> yourdfpy.URDF:
    return yourdfpy.URDF.load(io.BytesIO(urdf.encode()), load_meshes=False, build_scene_graph=True)


def _reflection(plane: str) -> np.ndarray:
    matrix = np.eye(4)
    matrix[NORMAL[plane], NORMAL[plane]] = -1.0
    return matrix


def _posed(robot: yourdfpy.URDF, rng: np.random.Generator) -> None:
    """Equal random values on each left joint and its right copy (mimic joints follow)."""
    values = {}
    for name in robot.actuated_joint_names:
        if name.startswith("left_"):
            joint = robot.joint_map[name]
            low, high = (
                (-3.0, 3.0)
                if joint.limit is None or joint.limit.lower is None
                else (joint.limit.lower, joint.limit.upper)
            )
            values[name] = values[name.replace("left_", "right_")] = float(rng.uniform(low, high))
    robot.update_cfg({name: values.get(name, 0.0) for name in robot.actuated_joint_names})


def _in_torso(robot: yourdfpy.URDF, link: str) -> np.ndarray:
    return robot.get_transform(link, "torso")


@settings(max_examples=30, deadline=None)
@given(spec=mirrored_specs(), seed=st.integers(0, 2**32 - 1))
def test_every_mirrored_link_is_the_mirror_image(spec, seed):
    robot = _robot(_urdf(spec))
    S = _reflection(spec["mirror"][0]["plane"])
    _posed(robot, np.random.default_rng(seed))
    lefts = [name for name in robot.link_map if name.startswith("left_")]
    assert lefts and sorted(n.replace("left_", "right_") for n in lefts) == sorted(
        n for n in robot.link_map if n.startswith("right_")
    )
    for name in lefts:
        left, right = robot.link_map[name], robot.link_map[name.replace("left_", "right_")]
        pose_left, pose_right = _in_torso(robot, left.name), _in_torso(robot, right.name)
        assert np.abs(pose_right - S @ pose_left @ S).max() < 1e-12, name
        _same_inertia(left, right, pose_left, pose_right, S)
        for kind in ("visuals", "collisions"):
            _same_geometry(getattr(left, kind), getattr(right, kind), pose_left, pose_right, S)


def _same_inertia(left, right, pose_left, pose_right, S):
    if left.inertial is None:
        assert right.inertial is None
        return
    assert right.inertial.mass == left.inertial.mass
    frame_left = pose_left @ left.inertial.origin
    frame_right = pose_right @ right.inertial.origin
    assert np.abs(frame_right[:3, 3] - S[:3, :3] @ frame_left[:3, 3]).max() < 1e-12  # (the centre of mass)
    tensor_left = frame_left[:3, :3] @ left.inertial.inertia @ frame_left[:3, :3].T
    tensor_right = frame_right[:3, :3] @ right.inertial.inertia @ frame_right[:3, :3].T
    assert np.abs(tensor_right - S[:3, :3] @ tensor_left @ S[:3, :3]).max() < 1e-12 * max(
        1.0, np.abs(tensor_left).max()
    )


def _same_geometry(lefts, rights, pose_left, pose_right, S):
    """Each right piece is the mirror image of a left one (a capsule's two spheres may change places)."""
    assert len(lefts) == len(rights)
    unmatched = list(lefts)
    for right in rights:
        placed_right = pose_right @ _placement(right)
        twin = next(p for p in unmatched if np.abs(placed_right - S @ pose_left @ _placement(p) @ S).max() < 1e-12)
        unmatched.remove(twin)
        if twin.geometry.mesh is not None and "/meshes/xacrokit/" not in twin.geometry.mesh.filename:
            scale = twin.geometry.mesh.scale if twin.geometry.mesh.scale is not None else np.ones(3)
            assert np.array_equal(right.geometry.mesh.scale, np.diag(S)[:3] * scale)  # (reflected in its own frame)
        else:  # (a box, a cylinder, a sphere, a made tube: symmetric under S)
            assert repr(right.geometry) == repr(twin.geometry)


def _placement(piece) -> np.ndarray:
    return piece.origin if piece.origin is not None else np.eye(4)


def test_the_humanoid_example_is_its_hand_written_twin():
    """The example's right arm comes from `mirror`; the example as it was written before, both arms by hand, is the
    same robot (every element, every number to 1e-12)."""
    text = HUMANOID.read_text(encoding="utf-8")
    assert "mirror:" in text and "right_upper_arm" not in text
    by_hand = (CASES / "humanoid_by_hand.yaml").read_text(encoding="utf-8")
    assert urdf_differences(_urdf(by_hand), _urdf(text)) == []


QUADRUPED = """\
robot: dog
links:
  base: {shape: {box: {size: [0.5, 0.3, 0.1]}}, mass: 6}
  lf_upper: {shape: {cylinder: {radius: 0.02, length: 0.2}}, origin: {xyz: [0, 0, -0.1]}, mass: 0.5}
  lf_lower:
    shape: {mesh: {filename: BRACKET, scale: [0.001, 0.001, 0.001]}}
    origin: {xyz: [0.01, 0.02, -0.1], rpy: [0.1, 0.2, 0.3]}
    mass: 0.3
joints:
  lf_hip_joint:
    type: revolute
    parent: base
    child: lf_upper
    origin: {xyz: [0.2, 0.1, 0], quat_wxyz: [0.9, 0.1, 0.3, 0.2]}
    axis: [1, 0, 0]
    limit: {lower: -0.5, upper: 0.8, effort: 20, velocity: 5}
  lf_knee_joint:
    type: revolute
    parent: lf_upper
    child: lf_lower
    origin: {xyz: [0, 0, -0.2]}
    axis: [0, 1, 0]
    limit: {lower: -2.5, upper: 0, effort: 20, velocity: 5}
frames:
  lf_foot: {parent: lf_lower, origin: {xyz: [0, 0, -0.2]}}
ros2_control:
  joints:
    lf_knee_joint: {command: [effort], state: [position]}
gazebo:
  links:
    lf_lower: {mu1: 0.9, mu2: 0.8}
mirror:
  - {joint: lf_hip_joint, rename: [lf_, rf_]}
  - {joint: lf_hip_joint, rename: [lf_, lh_], plane: yz}
  - {joint: rf_hip_joint, rename: [rf_, rh_], plane: yz}
"""
BRACKET = REPO / "examples" / "robots" / "cad" / "motor_bracket.stl"


def _quadruped(tmp_path, text=QUADRUPED):
    spec = tmp_path / "dog.yaml"
    spec.write_text(text.replace("BRACKET", str(BRACKET)), encoding="utf-8")
    return resolve(validate(load_file(spec)))


def test_four_legs_from_one_by_mirrors_of_mirrors(tmp_path):
    """rf is lf through xz, lh through yz, rh the mirror (yz) of the mirror (xz): at equal joint values each foot is
    where the two reflections put lf's; the mesh leg's inertia (computed from the reflected surface) is S I S."""
    model = _quadruped(tmp_path)
    robot = _robot(emit_urdf(model))
    rng = np.random.default_rng(7)
    values = {"hip": rng.uniform(-0.5, 0.8), "knee": rng.uniform(-2.5, 0)}
    robot.update_cfg({n: values[n.split("_")[1]] for n in robot.actuated_joint_names})
    flips = {
        "lf": np.eye(4),
        "rf": _reflection("xz"),
        "lh": _reflection("yz"),
        "rh": _reflection("xz") @ _reflection("yz"),
    }
    for leg, S in flips.items():
        for link in ("upper", "lower", "foot"):
            found = robot.get_transform(f"{leg}_{link}", "base")
            assert np.abs(found - S @ robot.get_transform(f"lf_{link}", "base") @ S).max() < 1e-12, (leg, link)
        lower, left = robot.link_map[f"{leg}_lower"].inertial, robot.link_map["lf_lower"].inertial
        frame, frame_left = (
            robot.get_transform(f"{leg}_lower", "base") @ lower.origin,
            robot.get_transform("lf_lower", "base") @ left.origin,
        )
        tensor = frame[:3, :3] @ lower.inertia @ frame[:3, :3].T
        expected = S[:3, :3] @ frame_left[:3, :3] @ left.inertia @ frame_left[:3, :3].T @ S[:3, :3]
        assert np.abs(tensor - expected).max() < 1e-9 * np.abs(expected).max()  # (trimesh on the mirrored mesh)
        assert np.abs(frame[:3, 3] - S[:3, :3] @ frame_left[:3, 3]).max() < 1e-9
    assert [j.name for j in model.ros2_control if j.name.endswith("knee_joint")] == [
        "lf_knee_joint",
        "rf_knee_joint",
        "lh_knee_joint",
        "rh_knee_joint",
    ]
    assert all(j.interfaces.command == ("effort",) for j in model.ros2_control if j.name.endswith("knee_joint"))
    assert {(s.link, s.mu1, s.mu2) for s in model.surfaces} == {(f"{leg}_lower", 0.9, 0.8) for leg in flips}
    limits = {j.name: (j.limit.lower, j.limit.upper) for j in model.joints if j.limit is not None}
    assert all(limits[f"{leg}_knee_joint"] == (-2.5, 0.0) for leg in flips)  # (limits as written: the axes turn)


@pytest.mark.parametrize("plane", ["xz", "yz", "xy"])
def test_a_lidar_scans_the_mirror_image_of_its_twin(plane, tmp_path):
    """The copy's first and last rays, in the torso's frame, are the reflections of the source's last and first (a
    lidar cannot be reflected: its rays are turned instead)."""
    text = QUADRUPED.split("frames:")[0] + (
        "frames:\n  lf_lidar:\n    parent: lf_lower\n    origin: {xyz: [0.05, 0, 0], rpy: [0.3, -0.2, 1.0]}\n"
        "    sensor: {type: lidar, topic: lf_scan, horizontal: {samples: 90, min_angle: -1.0, max_angle: 2.0}}\n"
        f"mirror:\n  - {{joint: lf_hip_joint, rename: [lf_, rf_], plane: {plane}}}\n"
    )
    model = _quadruped(tmp_path, text)
    robot = _robot(emit_urdf(model))
    S = _reflection(plane)[:3, :3]
    sensors = {s.link: s for s in model.sensors}
    assert sensors["rf_lidar"].topic == "rf_scan"

    def rays(name):
        turn = robot.get_transform(name, "base")[:3, :3]
        return [turn @ [math.cos(a), math.sin(a), 0.0] for a in (sensors[name].min_angle, sensors[name].max_angle)]

    first, last = rays("lf_lidar")
    mirrored = {tuple(np.round(S @ first, 12)), tuple(np.round(S @ last, 12))}
    assert {tuple(np.round(r, 12)) for r in rays("rf_lidar")} == mirrored
    width = sensors["lf_lidar"].max_angle - sensors["lf_lidar"].min_angle
    assert sensors["rf_lidar"].max_angle - sensors["rf_lidar"].min_angle == pytest.approx(width, abs=1e-15)


@pytest.mark.parametrize(
    ("change", "path", "words"),
    [
        (
            ("joint: lf_hip_joint, rename: [lf_, rf_]", "joint: lf_hip_jiont, rename: [lf_, rf_]"),
            "$.mirror[0].joint",
            "no joint 'lf_hip_jiont' in joints (did you mean 'lf_hip_joint'?)",
        ),
        (
            ("  lf_foot:", "  foot:"),
            "$.mirror[0].rename",
            "frame 'foot', which the mirror of lf_hip_joint copies, has no 'lf_'",
        ),
        (
            ("rename: [lf_, lh_]", "rename: [lf_, rf_]"),
            "$.mirror[1].rename",
            "is named 'rf_hip_joint', a name the spec",
        ),
        (
            ("rename: [lf_, rf_]}", 'rename: [lf_, "3"]}'),
            "$.mirror[0].rename",
            "would be named '3hip_joint', not a valid name",
        ),
        (
            ("  lf_foot: {", "  rf_upper: {parent: base}\n  lf_foot: {"),
            "$.mirror[0].rename",
            "the mirror of link 'lf_upper' is named 'rf_upper', a name the spec already has",
        ),
        (
            ("mirror:", "wheels:\n  lf_wheel: {parent: lf_lower, radius: 0.05, width: 0.02, mass: 0.2}\nmirror:"),
            "$.mirror[0].joint",
            "a wheel (lf_wheel) hangs below lf_hip_joint, on lf_lower",
        ),
        (
            ("    type: revolute\n    parent: lf_upper", "    type: planar\n    parent: lf_upper"),
            "$.mirror[0].joint",
            "joint lf_knee_joint below lf_hip_joint is planar",
        ),
    ],
)
def test_a_mirror_that_cannot_copy_says_why_at_its_entry(change, path, words, tmp_path):
    text = QUADRUPED.replace(*change)
    with pytest.raises(SpecErrors) as raised:
        _quadruped(tmp_path, text)
    found = [e for e in raised.value.errors if e.path == path and words in e.message]
    assert found, raised.value
    entries = [n for n, line in enumerate(text.splitlines(), 1) if line.startswith("  - {joint:")]
    assert found[0].line == entries[int(path[len("$.mirror[")])]  # (at its entry's line)
    # a later entry's joint that a failed entry would have made is not said again; when the failed entry made no names
    # (its joint unknown) or others (rename [lf_, 3]), the later entry's missing joint is said: it may be a typo
    later = [e for e in raised.value.errors if e.path.startswith("$.mirror[2]")]
    assert bool(later) == ("no joint" in words or "3hip" in words), later


def test_a_problem_of_the_source_is_said_once_and_a_copy_is_located_at_its_source(tmp_path):
    text = QUADRUPED.replace("mass: 0.5}", "mass: -0.5}")
    with pytest.raises(SpecErrors) as raised:
        _quadruped(tmp_path, text)
    assert [(e.path, e.line) for e in raised.value.errors] == [("$.links.lf_upper.mass", 4)]
    model_raw = validate(load_text(QUADRUPED.replace("BRACKET", str(BRACKET)), str(tmp_path / "dog.yaml"))).raw
    assert model_raw.locate(("links", "rh_upper", "mass")) == model_raw.locate(("links", "lf_upper", "mass"))
    knee = QUADRUPED.splitlines().index("  lf_knee_joint:") + 1
    assert model_raw.locate(("joints", "rh_knee_joint"), key=True) == (knee, 3)  # (rh from rf from lf)


def test_a_copy_only_error_names_its_source_and_a_repeated_one_is_dropped():
    from xacrokit.errors import SpecError
    from xacrokit.validate.mirror import copies_said

    aliases = {("links", "right_arm"): ("links", "left_arm")}
    source = SpecError("mass must be > 0", file="s.yaml", path="$.links.left_arm.mass", line=4, column=9)
    repeated = SpecError("mass must be > 0", file="s.yaml", path="$.links.right_arm.mass", line=4, column=9)
    alone = SpecError("too deep", file="s.yaml", path="$.links.right_arm", line=3, column=3)
    said = list(copies_said([source, repeated, alone], aliases))
    assert [(e.path, e.message) for e in said] == [
        ("$.links.left_arm.mass", "mass must be > 0"),
        ("$.links.right_arm", "too deep (in the mirror `mirror` makes of $.links.left_arm)"),
    ]


@pytest.mark.parametrize(
    ("plane", "xyz", "rpy", "revolute", "prismatic"),
    [
        ("xz", "0.1 -0.2 0.3", "-0.4 0.5 -0.6", "-1 0 0", "0 -1 0"),
        ("yz", "-0.1 0.2 0.3", "0.4 -0.5 -0.6", "1 0 0", "0 1 0"),
        ("xy", "0.1 0.2 -0.3", "-0.4 -0.5 0.6", "-1 0 0", "0 1 0"),
    ],
)
def test_the_table_of_docs_spec_signs_exactly(plane, xyz, rpy, revolute, prismatic):
    """docs/spec.md's table: a placement's coordinates and angles change sign, digit for digit (no rounding through
    a matrix); a revolute axis becomes -S a, a prismatic one S a."""
    text = f"""\
robot: signs
links:
  base: {{}}
  left_a: {{shape: {{sphere: {{radius: 0.05}}}}, mass: 1}}
  left_b: {{shape: {{sphere: {{radius: 0.05}}}}, mass: 1}}
joints:
  left_turn: {{type: revolute, parent: base, child: left_a, origin: {{xyz: [0.1, 0.2, 0.3], rpy: [0.4, 0.5, 0.6]}},
              axis: [1, 0, 0], limit: {{lower: -1, upper: 2, effort: 1, velocity: 1}}}}
  left_slide: {{type: prismatic, parent: left_a, child: left_b, axis: [0, 1, 0],
               limit: {{lower: 0, upper: 0.1, effort: 1, velocity: 1}}}}
mirror:
  - {{joint: left_turn, rename: [left_, right_], plane: {plane}}}
"""
    urdf = _urdf(text)
    origin = etree.fromstring(urdf.encode()).find("joint[@name='right_turn']/origin")
    assert (origin.get("xyz"), origin.get("rpy")) == (xyz, rpy)
    copy = _robot(urdf)
    turn, slide = copy.joint_map["right_turn"], copy.joint_map["right_slide"]
    assert np.array_equal(turn.axis, [float(v) for v in revolute.split()])
    assert np.array_equal(slide.axis, [float(v) for v in prismatic.split()])
    assert (turn.limit.lower, turn.limit.upper, slide.limit.lower, slide.limit.upper) == (-1, 2, 0, 0.1)


def test_mirrors_of_mirrors_that_double_stop_at_the_cap(tmp_path):
    """15 entries, each mirroring the joint above the last one's (so each copies every copy before it), would make
    about 65,000 links and joints: refused at the entry that passes 10,000, in well under a second of work."""
    from xacrokit.validate.mirror import MAX_COPIES

    depth = 15
    token = ["L"] + [f"_x{k}_" for k in range(depth)]
    links = {"base": {}} | {
        "".join(token[: d + 2]): {"shape": {"sphere": {"radius": 0.01}}, "mass": 0.1} for d in range(depth)
    }
    names = list(links)
    joints = {
        "J" + names[d + 1][1:]: {
            "type": "revolute",
            "parent": names[d],
            "child": names[d + 1],
            "origin": {"xyz": [0, 0.1, 0]},
            "axis": [0, 0, 1],
            "limit": {"lower": -1, "upper": 1, "effort": 1, "velocity": 1},
        }
        for d in range(depth)
    }
    mirror = [{"joint": "J" + names[d + 1][1:], "rename": [f"_x{d}_", f"_y{d}_"]} for d in reversed(range(depth))]
    with pytest.raises(SpecErrors) as raised:
        _urdf({"robot": "doubling", "links": links, "joints": joints, "mirror": mirror})
    (error,) = raised.value.errors
    assert error.path.startswith("$.mirror[") and f"beyond the {MAX_COPIES:,}" in error.message
    made = int(error.message.split("make ")[1].split(" ")[0].replace(",", ""))
    assert MAX_COPIES < made < 2 * MAX_COPIES + 10  # (the entry that passed it: at most twice what was made before)


@settings(max_examples=40, deadline=None)
@given(data=st.data())
def test_any_mirror_of_any_spec_gives_a_robot_or_located_errors(data):
    """A mirror entry on any valid spec (any joint, any renaming, any plane): a robot yourdfpy reads with each copy
    present, or errors every one of which has a line; never a traceback."""
    from xacrokit.testing import valid_specs

    spec = data.draw(valid_specs())
    joints = list(spec.get("joints", {})) + ["nowhere"]
    old = data.draw(st.sampled_from(["link", "joint", "_", "-", ".", "k_", "arm"]))
    entry = {"joint": data.draw(st.sampled_from(joints)), "rename": [old, data.draw(st.sampled_from(["", "r_", "Z"]))]}
    entry["plane"] = data.draw(st.sampled_from(["xz", "yz", "xy"]))
    spec["mirror"] = [entry]
    try:
        urdf = _urdf(spec)
    except SpecErrors as raised:
        assert all(error.line is not None for error in raised.errors), raised
        return
    robot = _robot(urdf)
    copy = entry["joint"].replace(*entry["rename"])
    assert copy != entry["joint"] and copy in robot.joint_map  # (the copy of the mirrored joint is there)


def test_a_copys_name_may_not_outgrow_a_name(tmp_path):
    """Renaming a to 200 characters in every name (and again in a later entry's copy) would make names longer than
    any name may be: refused at the entry, before the copy is made."""
    text = QUADRUPED.split("mirror:")[0] + "mirror:\n  - {joint: lf_hip_joint, rename: [f, " + "f" * 150 + "]}\n"
    with pytest.raises(SpecErrors) as raised:
        _quadruped(tmp_path, text)
    assert any("characters, beyond the 200 a name may have" in e.message for e in raised.value.errors)
