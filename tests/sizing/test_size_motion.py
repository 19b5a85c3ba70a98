"""gen-robot size along a motion: inverse dynamics against the closed-form two-link arm (mass matrix, Coriolis and
gravity terms written out) and MuJoCo's mj_inverse; the energy balance of every rest-to-rest segment against the
closed-form potential energy; time scaling within the limits; the sizing file's drives and its located errors."""

from __future__ import annotations

import json
import math

import jsonschema
import numpy as np
import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import simpson
from test_size_static import GRAVITY, L1, L2, M1, M2, planar_arm

from conftest import REPO, gen_robot
from xacrokit.errors import SpecErrors
from xacrokit.reader.read_robot import read_robot
from xacrokit.sizing import Payload, format_text, size
from xacrokit.sizing.motion import Motion, Trajectory, inverse_dynamics, trajectory
from xacrokit.sizing.sized_robot import loaded_robot

I1, I2 = M1 * L1**2 / 12, M2 * L2**2 / 12  # (the bars' tensors about y, as planar_arm writes them)


def closed_form_dynamics(q, v, a, payload=0.0):
    """tau = M(q) qdd + C(q, qd) qd + g(q) of the planar two-link arm, the payload a point mass at the tip: the
    textbook terms with the second link's mass, centre and inertia including it."""
    m2 = M2 + payload
    c2 = (M2 * L2 / 2 + payload * L2) / m2
    i2 = I2 + M2 * (L2 / 2 - c2) ** 2 + payload * (L2 - c2) ** 2
    c1 = L1 / 2
    cos2, sin2 = math.cos(q[1]), math.sin(q[1])
    m11 = I1 + i2 + M1 * c1**2 + m2 * (L1**2 + c2**2 + 2 * L1 * c2 * cos2)
    m12 = i2 + m2 * (c2**2 + L1 * c2 * cos2)
    m22 = i2 + m2 * c2**2
    h = m2 * L1 * c2 * sin2
    # (angles grow from x towards -z, so a point's height is -r sin(angle) and gravity's terms carry cosines)
    g1 = -GRAVITY * ((M1 * c1 + m2 * L1) * math.cos(q[0]) + m2 * c2 * math.cos(q[0] + q[1]))
    g2 = -GRAVITY * m2 * c2 * math.cos(q[0] + q[1])
    return np.array(
        [
            m11 * a[0] + m12 * a[1] - h * (2 * v[0] * v[1] + v[1] ** 2) + g1,
            m12 * a[0] + m22 * a[1] + h * v[0] ** 2 + g2,
        ]
    )


def potential(q, payload=0.0):
    return -GRAVITY * (
        (M1 * L1 / 2 + (M2 + payload) * L1) * math.sin(q[0]) + (M2 * L2 / 2 + payload * L2) * math.sin(q[0] + q[1])
    )


@pytest.fixture(scope="module")
def arm_path(tmp_path_factory):
    path = tmp_path_factory.mktemp("arm") / "planar.urdf"
    path.write_text(planar_arm(effort=1000.0), encoding="utf-8")
    return path


values = st.floats(-3.0, 3.0)


@settings(max_examples=40, deadline=None)
@given(state=st.lists(values, min_size=6, max_size=6), payload=st.floats(0.0, 5.0))
def test_inverse_dynamics_equal_the_closed_form_arm(arm_path, state, payload):
    robot = loaded_robot(read_robot(arm_path), payloads=[Payload("tool", payload)] if payload else [])
    q, v, a = np.array(state[:2]), np.array(state[2:4]), np.array(state[4:])
    tau = inverse_dynamics(robot, Trajectory(np.zeros(1), q[None], v[None], a[None]))[0]
    want = closed_form_dynamics(q, v, a, payload)
    assert np.abs(tau - want).max() <= 1e-9 * max(np.abs(want).max(), 1.0)


def test_inverse_dynamics_equal_mujocos(arm_path):
    mujoco = pytest.importorskip("mujoco")
    model = mujoco.MjModel.from_xml_string(arm_path.read_text(encoding="utf-8"))
    model.opt.gravity[:] = [0.0, 0.0, -GRAVITY]
    data = mujoco.MjData(model)
    robot = loaded_robot(read_robot(arm_path))
    for q, v, a in np.random.default_rng(7).uniform(-3, 3, (50, 3, 2)):
        data.qpos[:], data.qvel[:], data.qacc[:] = q, v, a
        mujoco.mj_inverse(model, data)
        tau = inverse_dynamics(robot, Trajectory(np.zeros(1), q[None], v[None], a[None]))[0]
        assert np.abs(tau - data.qfrc_inverse).max() <= 1e-9 * max(np.abs(tau).max(), 1.0)


@settings(max_examples=15, deadline=None)
@given(
    start=st.lists(st.floats(-1.5, 1.5), min_size=2, max_size=2),
    end=st.lists(st.floats(-1.5, 1.5), min_size=2, max_size=2),
    payload=st.floats(0.0, 3.0),
)
def test_energy_balance_of_a_rest_to_rest_segment(arm_path, start, end, payload):
    """The integral of tau . qdot over a segment at rest at both ends is the potential energy gained (frictionless:
    the kinetic energy is 0 at both ends), Simpson's rule on the quintic's uniform samples."""
    if max(abs(s - e) for s, e in zip(start, end, strict=True)) < 1e-3:
        return
    robot = loaded_robot(read_robot(arm_path), payloads=[Payload("tool", payload)] if payload else [])
    motion = Motion(waypoints=(tuple(start), tuple(end)), velocity=(2.0, 3.0), acceleration=(4.0, 6.0), step=2e-4)
    path = trajectory(motion)
    tau = inverse_dynamics(robot, path)
    work = simpson(np.sum(tau * path.v, axis=1), x=path.t)
    gained = potential(end, payload) - potential(start, payload)
    scale = GRAVITY * (M1 * L1 + (M2 + payload) * (L1 + L2))
    assert work == pytest.approx(gained, abs=1e-9 * scale)


@pytest.mark.parametrize("scaling", ["quintic", "trapezoid"])
def test_each_segment_is_as_fast_as_the_limits_allow_and_within_them(scaling):
    motion = Motion(
        waypoints=((0.0, 0.0), (1.0, -0.2), (1.0, 0.3), (0.2, 0.3)),
        velocity=(1.0, 0.5),
        acceleration=(2.0, 3.0),
        scaling=scaling,
        step=1e-4,
    )
    path = trajectory(motion)
    assert np.all(np.abs(path.v) <= np.array(motion.velocity) * (1 + 1e-9))
    assert np.all(np.abs(path.a) <= np.array(motion.acceleration) * (1 + 1e-9))
    assert path.v[0].tolist() == [0.0, 0.0] and abs(path.v[-1]).max() < 1e-9
    np.testing.assert_allclose(path.q[-1], motion.waypoints[-1], atol=1e-12)
    # every segment reaches one of its limits (else it could have been faster), within the sampling
    bounds = np.searchsorted(path.t, np.cumsum([0.0, *(_durations(motion))]))
    for lo, hi in zip(bounds, bounds[1:], strict=False):
        used = max((np.abs(path.v[lo:hi]) / motion.velocity).max(), (np.abs(path.a[lo:hi]) / motion.acceleration).max())
        assert used == pytest.approx(1.0, abs=1e-3)


def _durations(motion):
    from xacrokit.sizing.motion import segment_duration

    points = [np.array(w) for w in motion.waypoints]
    return [segment_duration(motion, b - a) for a, b in zip(points, points[1:], strict=False)]


def test_a_held_pose_has_its_static_torque_as_rms(arm_path, tmp_path):
    sizing = tmp_path / "hold.yaml"
    sizing.write_text(
        yaml.safe_dump(
            {
                "motion": {
                    "waypoints": [{"shoulder": 0.3, "elbow": -0.4}, {"shoulder": 0.3, "elbow": -0.4}],
                    "acceleration": 1.0,
                    "dwell": 1.0,
                }
            }
        ),
        encoding="utf-8",
    )
    report = size(arm_path, sizing=sizing)
    want = closed_form_dynamics([0.3, -0.4], [0, 0], [0, 0])
    for moved, torque in zip(report.motions, want, strict=True):
        assert moved.rms_torque == pytest.approx(abs(torque), rel=1e-12) and moved.peak_speed == 0.0


SIZING = {
    "payloads": [{"frame": "tool0", "mass": "5 kg", "com": [0, 0, "50 mm"]}],
    "motion": {
        "scaling": "trapezoid",
        "dwell": 0.2,
        "velocity": "90 deg/s",
        "acceleration": 4.0,
        "waypoints": [
            {"shoulder_lift_joint": "-90 deg", "elbow_joint": "90 deg"},
            {"shoulder_pan_joint": "90 deg", "shoulder_lift_joint": "-45 deg", "elbow_joint": "45 deg"},
        ],
    },
    "drives": {
        "shoulder_lift_joint": {
            "gear_ratio": 101,
            "efficiency": 0.8,
            "rotor_inertia": 3.3e-5,
            "rated_torque": "1.2 N*m",
            "peak_torque": "3.5 N*m",
            "max_speed": "3000 rpm",
        }
    },
}


def test_drives_give_the_motor_side_and_fail_the_motor_that_is_too_small(tmp_path):
    ur5 = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
    sizing = tmp_path / "ur5.sizing.yaml"
    sizing.write_text(yaml.safe_dump(SIZING), encoding="utf-8")
    result = gen_robot("size", ur5, "--sizing", sizing, "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    jsonschema.validate(report, json.loads((REPO / "schemas" / "size-report.schema.json").read_text()))
    lift = next(j for j in report["joints"] if j["name"] == "shoulder_lift_joint")
    drive, moved = lift["drive"], lift["motion"]
    peak = max(abs(moved["peak_torque"]), abs(lift["static"]["peak_torque"]))
    assert drive["motor_peak_torque"] == pytest.approx(peak / (101 * 0.8), rel=1e-12)
    # the pan turns 90 deg at its 90 deg/s limit while the lift turns 45 deg: the lift peaks at 45 deg/s
    assert moved["peak_speed"] == pytest.approx(math.pi / 4, rel=1e-9)
    assert drive["motor_peak_speed"] == pytest.approx(math.pi / 4 * 101, rel=1e-9)
    assert drive["reflected_inertia"] == pytest.approx(3.3e-5 * 101**2, rel=1e-12)
    assert drive["speed_margin"] == pytest.approx(3000 * 2 * math.pi / 60 / (math.pi / 4 * 101), rel=1e-9)
    SIZING["drives"]["shoulder_lift_joint"]["peak_torque"] = "0.5 N*m"
    sizing.write_text(yaml.safe_dump(SIZING), encoding="utf-8")
    failing = gen_robot("size", ur5, "--sizing", sizing)
    SIZING["drives"]["shoulder_lift_joint"]["peak_torque"] = "3.5 N*m"
    assert failing.returncode == 1
    assert "FAIL shoulder_lift_joint: motor peak torque over the motor's peak torque" in failing.stdout


def _moving(**motion):
    """A sizing file moving the UR5's elbow by 1 rad at 1 rad/s^2, with ``motion``'s fields in place of these."""
    return {"motion": {"acceleration": 1.0, "waypoints": [{"elbow_joint": 0}, {"elbow_joint": 1}], **motion}}


@pytest.mark.parametrize(
    ("change", "path", "words"),
    [
        (
            {"motion": {"waypoints": [{"elbow_jiont": 0}, {"elbow_joint": 1}], "acceleration": 1}},
            "$.motion.waypoints[0].elbow_jiont",
            "did you mean 'elbow_joint'",
        ),
        (
            {"motion": {"waypoints": [{"elbow_joint": "400 deg"}, {"elbow_joint": 0}], "acceleration": 1}},
            "$.motion.waypoints",
            "outside its range",
        ),
        (
            {"motion": {"waypoints": [{"elbow_joint": 0}, {"elbow_joint": 1}]}},
            "$.motion",
            "needs an acceleration limit",
        ),
        ({"payloads": [{"frame": "tool9", "mass": 1}]}, "$.payloads[0].frame", "did you mean 'tool0'"),
        ({"drives": {"elbow_joint": {"gear_ratio": -5}}}, "$.drives.elbow_joint.gear_ratio", "> 0"),
        ({"drives": {"elbo_joint": {"gear_ratio": 5}}}, "$.drives.elbo_joint", "did you mean 'elbow_joint'"),
        ({"payloads": [{"frame": "tool0", "mass": "5 parsecs"}]}, "$.payloads[0].mass", "unknown unit"),
        # cycles too long to sample (issue 28): refused before sampling, at the field that makes them long
        (_moving(dwell=1e4), "$.motion.dwell", "20,0"),
        (_moving(dwell=1e9), "$.motion.dwell", "at most 200,000 times"),
        (_moving(velocity={"elbow_joint": 1e-12}), "$.motion.velocity.elbow_joint", "elbow_joint's velocity limit"),
        (_moving(velocity=1e-320), "$.motion.velocity", "than a number can hold"),
        (_moving(acceleration="1e-300"), "$.motion.acceleration", "acceleration limit of 1e-300"),
        (_moving(step=1e-9), "$.motion.step", "leave it out"),
        (  # (two segments of about 1.2e308 samples each: an int sum past the largest float, once an OverflowError)
            _moving(
                step=1.9634954084936204e-308, waypoints=[{"elbow_joint": 0}, {"elbow_joint": 1}, {"elbow_joint": 0}]
            ),
            "$.motion.step",
            "leave it out (1 ms)",
        ),
        (_moving(waypoints=[{"elbow_joint": k % 2 * 2.0} for k in range(300)]), "$.motion.waypoints", "299 segments"),
        (_moving(waypoints=[{"elbow_joint": 0} for _ in range(1001)]), "$.motion.waypoints", "2 to 1000 entries"),
        # numbers that overflow or no body has (issue 28: exit 70 or NaN before)
        (
            {"payloads": [{"frame": "tool0", "mass": 1, "inertia": {"ixx": -1e308, "iyy": 1, "izz": 1}}]},
            "$.payloads[0].inertia",
            "beyond what xacrokit takes",
        ),
        (
            {"payloads": [{"frame": "tool0", "mass": 1, "inertia": {"ixx": 1, "iyy": 1, "izz": 5}}]},
            "$.payloads[0].inertia",
            "triangle inequality",
        ),
        ({"drives": {"elbow_joint": {"gear_ratio": 1e300}}}, "$.drives.elbow_joint.gear_ratio", "100000"),
        (
            {"drives": {"elbow_joint": {"gear_ratio": 10, "efficiency": 1e-320}}},
            "$.drives.elbow_joint.efficiency",
            "0.01",
        ),
    ],
)
def test_bad_sizing_files_are_located_errors(tmp_path, change, path, words):
    sizing = tmp_path / "bad.yaml"
    sizing.write_text(yaml.safe_dump(change), encoding="utf-8")
    with pytest.raises(SpecErrors) as caught:
        size(REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml", sizing=sizing)
    errors = caught.value.errors
    assert any(e.path == path and words in e.message and e.line is not None for e in errors), [str(e) for e in errors]
    result = gen_robot("size", REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml", "--sizing", sizing)
    assert result.returncode == 2 and "Traceback" not in result.stderr and str(sizing) in result.stderr


@settings(max_examples=10, deadline=None)
@given(seed=st.integers(0, 10_000))
def test_pose_waypoints_are_reached_by_inverse_kinematics(tmp_path_factory, seed):
    """A pose the arm reaches at random joint values (pinocchio's forward kinematics of the file, rebuilt here) is
    found again from the zero pose: the frame ends on it within 1e-9 (position and orientation)."""
    import pinocchio as pin

    from xacrokit.sizing.motion import reach

    ur5 = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
    robot = loaded_robot(read_robot(ur5))
    rng = np.random.default_rng(seed)
    values = rng.uniform(-2.5, 2.5, len(robot.joints))
    model = robot.model
    data = model.createData()
    pin.framesForwardKinematics(model, data, robot.configuration(values))
    goal = data.oMf[model.getFrameId("tool0")]
    rpy = pin.rpy.matrixToRpy(goal.rotation)
    found, error = reach(robot, "tool0", goal.translation, rpy, values * 0.8)
    pin.framesForwardKinematics(model, data, robot.configuration(np.array(found)))
    reached = data.oMf[model.getFrameId("tool0")]
    assert error < 1e-9
    assert np.abs(reached.translation - goal.translation).max() < 1e-9
    assert np.abs(reached.rotation - goal.rotation).max() < 1e-9


@settings(max_examples=30, deadline=None)
@given(
    points=st.lists(st.lists(st.floats(-3, 3), min_size=2, max_size=2), min_size=2, max_size=5),
    velocity=st.floats(0.05, 20),
    acceleration=st.floats(0.05, 50),
    dwell=st.sampled_from([0.0, 0.0004, 0.25]),
    step=st.sampled_from([1e-3, 7e-3, 0.05]),
    scaling=st.sampled_from(["quintic", "trapezoid"]),
)
def test_the_sample_count_the_cap_is_checked_on_is_the_trajectorys(
    points, velocity, acceleration, dwell, step, scaling
):
    """sample_count, which the sizing file's reader compares with MAX_SAMPLES before sampling, is the number of
    samples the trajectory then takes: the cap refuses exactly the cycles that would exceed it."""
    from xacrokit.sizing.motion import MAX_SAMPLES, sample_count, segment_duration

    motion = Motion(tuple(map(tuple, points)), (velocity, velocity), (acceleration, acceleration), scaling, dwell, step)
    durations = [segment_duration(motion, np.subtract(b, a)) for a, b in zip(points, points[1:], strict=False)]
    needed = sample_count(motion, durations)
    if needed > MAX_SAMPLES:
        with pytest.raises(ValueError, match="more than 200,000 samples"):
            trajectory(motion)
    else:
        assert needed == len(trajectory(motion).t)


def test_a_cycle_beyond_the_cap_is_never_sampled():
    from xacrokit.sizing.motion import MAX_SAMPLES

    motion = Motion(((0.0,), (1.0,)), (1.0,), (1.0,), dwell=MAX_SAMPLES * 1e-3)
    with pytest.raises(ValueError, match="more than 200,000 samples"):
        trajectory(motion)
    assert len(trajectory(Motion(((0.0,), (1.0,)), (1.0,), (1.0,), dwell=10.0)).t) < MAX_SAMPLES


def test_a_motor_side_result_that_is_not_a_number_fails(tmp_path):
    """A gear ratio of 1e-320 (within the schema's > 0) asks an infinite motor torque: listed as failed, exit 1,
    even though the drive gives no motor limit to compare it with."""
    sizing = tmp_path / "tiny.yaml"
    sizing.write_text(yaml.safe_dump({"drives": {"elbow_joint": {"gear_ratio": 1e-320}}, **_moving()}), "utf-8")
    report = size(REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml", sizing=sizing)
    assert ("elbow_joint", "motor-side result not a finite number") in report.failures
    assert report.exit_code == 1 and "elbow_joint" in report.failed


def test_an_unreachable_pose_is_a_located_error(tmp_path):
    sizing = tmp_path / "far.yaml"
    far = {"acceleration": 2.0, "waypoints": [{"elbow_joint": 1.0}, {"pose": {"frame": "tool0", "xyz": [2.4, 0, 0.3]}}]}
    sizing.write_text(yaml.safe_dump({"motion": far}), encoding="utf-8")
    with pytest.raises(SpecErrors) as caught:
        size(REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml", sizing=sizing)
    (error,) = caught.value.errors
    assert error.path == "$.motion.waypoints[1].pose" and "cannot put 'tool0' there" in error.message


def test_a_pose_waypoint_takes_every_rotation_form(tmp_path):
    """The same goal orientation given as rpy, rotvec, quat_wxyz, matrix and intrinsic euler (scipy writes each from
    one rotation): the same motion, to 1e-9 in every joint's peak and RMS torque; a matrix that is no rotation is a
    located error."""
    from scipy.spatial.transform import Rotation

    turn = Rotation.from_euler("xyz", [2.8, 0.3, -1.2])  # (a pose the UR5's tool reaches from its first waypoint)
    forms = {
        "rpy": {"rpy": turn.as_euler("xyz").tolist()},
        "rotvec": {"rotvec": turn.as_rotvec().tolist()},
        "quat_wxyz": {"quat_wxyz": turn.as_quat(scalar_first=True).tolist()},
        "matrix": {"matrix": turn.as_matrix().tolist()},
        "euler": {"euler": {"sequence": "ZYX", "angles": turn.as_euler("ZYX").tolist()}},
    }
    results = {}
    for name, rotation in forms.items():
        pose = {"frame": "tool0", "xyz": [0.4, 0.2, 0.3], **rotation}
        motion = {"acceleration": 2.0, "waypoints": [{"elbow_joint": 1.0, "shoulder_lift_joint": -1.0}, {"pose": pose}]}
        sizing = tmp_path / f"{name}.yaml"
        sizing.write_text(yaml.safe_dump({"motion": motion}), encoding="utf-8")
        report = size(REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml", sizing=sizing)
        results[name] = np.array([[m.peak_torque, m.rms_torque] for m in report.motions])
    assert np.abs(results["rpy"]).max() > 1.0  # (a real motion)
    for name, found in results.items():
        assert np.abs(found - results["rpy"]).max() < 1e-9, name
    pose = {"frame": "tool0", "xyz": [0.4, 0.2, 0.3], "matrix": [[1, 0, 0], [0, 1, 0], [0, 0, -1]]}
    motion = {"acceleration": 2.0, "waypoints": [{"elbow_joint": 1.0}, {"pose": pose}]}
    sizing = tmp_path / "mirror.yaml"
    sizing.write_text(yaml.safe_dump({"motion": motion}), encoding="utf-8")
    with pytest.raises(SpecErrors) as caught:
        size(REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml", sizing=sizing)
    (error,) = caught.value.errors
    assert error.path == "$.motion.waypoints[1].pose.matrix" and "determinant is -1" in error.message
    assert error.line is not None
    pose = {"frame": "tool0", "xyz": [0.4, 0.2, 0.3], "quat_wxyz": [2, 0, 0, 0]}  # (a sizing file has no warnings)
    sizing.write_text(yaml.safe_dump({"motion": {**motion, "waypoints": [{"elbow_joint": 1.0}, {"pose": pose}]}}))
    with pytest.raises(SpecErrors) as caught:
        size(REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml", sizing=sizing)
    (error,) = caught.value.errors
    assert error.path == "$.motion.waypoints[1].pose.quat_wxyz" and "give it of length 1" in error.message


def test_the_sizing_schema_takes_the_rotation_forms_of_a_robot_origin():
    """sizing.schema.json's waypoint pose copies the rotation forms of robot.schema.json's origin (the two files are
    read by editors on their own): kept equal here."""
    from xacrokit.validate.quantities import ORIENTATIONS
    from xacrokit.validate.schema import inline_refs

    robot = json.loads((REPO / "schemas" / "robot.schema.json").read_text(encoding="utf-8"))
    origin = inline_refs({"$defs": robot["$defs"], "origin": {"$ref": "#/$defs/origin"}})["origin"]["properties"]
    sizing = json.loads((REPO / "schemas" / "sizing.schema.json").read_text(encoding="utf-8"))
    waypoint = sizing["properties"]["motion"]["properties"]["waypoints"]["items"]
    pose = waypoint["properties"]["pose"]["properties"]
    assert set(ORIENTATIONS) <= set(pose)

    def rules(schema):  # (the descriptions differ where a sizing file refuses what a spec warns of)
        return {k: v for k, v in schema.items() if k != "description"}

    forms = [form for form in ORIENTATIONS if form != "rpy"]  # (rpy was the pose's own before: its own words)
    assert all(rules(pose[form]) == rules(origin[form]) and pose[form]["description"] for form in forms)


def _planar_motion(tmp_path, motion):
    sizing = tmp_path / "motion.yaml"
    sizing.write_text(yaml.safe_dump({"motion": motion}), encoding="utf-8")
    return size(REPO / "examples" / "robots" / "planar_2dof.yaml", sizing=sizing)


def test_a_motion_lasts_the_duration_asked(tmp_path):
    """Issue 31: the lecture's 'from (0, 0) to (1.5, 1.5) rad in 3 s with a quintic profile': peak speed 15/8 * 1.5 / 3
    and peak acceleration 10/sqrt(3) * 1.5 / 9 (the quintic's closed form), the cycle 3 s in the JSON and the table;
    a trapezoid stretched to 3 s keeps the acceleration limit and cruises at the smaller root of v^2 - aTv + a."""
    quintic = {"duration": "3 s", "velocity": 10, "acceleration": 100}
    quintic["waypoints"] = [{"joint_1": 0, "joint_2": 0}, {"joint_1": 1.5, "joint_2": 1.5}]
    report = _planar_motion(tmp_path, quintic)
    for moved in report.motions:
        assert moved.peak_speed == pytest.approx(15 / 8 * 1.5 / 3, rel=1e-6)
        assert moved.peak_acceleration == pytest.approx(10 / math.sqrt(3) * 1.5 / 9, rel=1e-4)  # (sampled at 1 ms)
    checked = {"velocity": ["joint_1", "joint_2"], "acceleration": ["joint_1", "joint_2"]}
    assert report.to_dict()["motion_timing"] == {
        "segments": [3.0],
        "dwell": 0.0,
        "cycle": 3.0,
        "limits_checked": checked,
    }
    assert "segments of 3 s; the cycle takes 3 s" in format_text(report)
    trapezoid = {"scaling": "trapezoid", "velocity": 10, "acceleration": 2, "dwell": 0.5, "duration": 3}
    trapezoid["waypoints"] = [{"joint_1": 0}, {"joint_1": 1, "duration": "4000 ms"}, {"joint_1": 0}]  # (4 s wins)
    report = _planar_motion(tmp_path, trapezoid)
    cruise = {t: (2 * t - math.sqrt(4 * t * t - 8)) / 2 for t in (3, 4)}  # (the shortest, a triangle, is 1.41 s)
    assert report.motions[0].peak_speed == pytest.approx(max(cruise.values()), rel=1e-9)
    assert report.motions[0].peak_acceleration == pytest.approx(2.0, rel=1e-9)
    timing = {"segments": [4.0, 3.0], "dwell": 0.5, "cycle": 8.5, "limits_checked": checked}
    assert report.to_dict()["motion_timing"] == timing


@pytest.mark.parametrize(
    ("motion", "path", "words"),
    [
        ({"duration": 0.1, "velocity": 10, "acceleration": 100}, "$.motion.duration", "shortest the joints' limits"),
        (
            {"velocity": 10, "acceleration": 100, "waypoints": [{"joint_1": 0, "duration": 2}, {"joint_1": 1.5}]},
            "$.motion.waypoints[0].duration",
            "the first waypoint is where the cycle starts",
        ),
        ({"duration": "1e9 s", "velocity": 10, "acceleration": 100}, "$.motion.duration", "is asked to last 1e+09 s"),
    ],
)
def test_a_duration_that_cannot_be_is_a_located_error(tmp_path, motion, path, words):
    motion.setdefault("waypoints", [{"joint_1": 0, "joint_2": 0}, {"joint_1": 1.5, "joint_2": 1.5}])
    with pytest.raises(SpecErrors) as caught:
        _planar_motion(tmp_path, motion)
    assert any(e.path == path and words in e.message and e.line is not None for e in caught.value.errors), [
        str(e) for e in caught.value.errors
    ]


def test_joint_damping_and_friction_count_in_the_motion_unless_left_out(tmp_path):
    """Issue 31: the URDF's <dynamics damping friction> add d qdot + f sign(qdot) to every sample's torque (the course's
    arm states damping); --no-joint-friction leaves them out, and the report says which."""
    spec = (REPO / "examples" / "robots" / "two_dof_arm.yaml").read_text(encoding="utf-8")
    assert "damping: 0.1" in spec  # (the example's shoulder; its elbow has 0.05)
    arm = tmp_path / "arm.yaml"
    arm.write_text(spec.replace("friction: 0.0", "friction: 0.3", 1), encoding="utf-8")
    sizing = tmp_path / "motion.yaml"
    waypoints = [{"shoulder_joint": 0, "elbow_joint": 0}, {"shoulder_joint": 1, "elbow_joint": 1}]
    motion = {"acceleration": 2.0, "velocity": 1.0, "waypoints": waypoints}
    sizing.write_text(yaml.safe_dump({"motion": motion}), encoding="utf-8")
    counted, left_out = size(arm, sizing=sizing), size(arm, sizing=sizing, joint_friction=False)
    (path, torque), (_, bare) = counted.samples, left_out.samples
    damping, friction = np.array([0.1, 0.05]), np.array([0.3, 0.0])
    assert np.abs(torque - bare - (damping * path.v + friction * np.sign(path.v))).max() < 1e-12
    assert np.abs(path.v).max() > 0.5  # (it moves: the terms are not zero)
    assert counted.to_dict()["joint_friction"] is True and left_out.to_dict()["joint_friction"] is False
    assert "damping and friction included" in format_text(counted) and "left out" in format_text(left_out)
