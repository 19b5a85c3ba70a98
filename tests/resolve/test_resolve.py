"""The resolve stage: a validated spec becomes the frozen model, with defaults filled in and shape inertia computed."""

from __future__ import annotations

import dataclasses
import math

import pytest
import yaml

from xacrokit.load import load_text
from xacrokit.model import Box, Collision, Cylinder, Origin, Robot, Sphere, Visual
from xacrokit.resolve import resolve
from xacrokit.validate import validate

SPEC = {
    "robot": "r",
    "materials": {"gray": [0.5, 0.5, 0.5, 1.0]},
    "links": {
        "base": {"shape": {"box": {"size": ["400 mm", 0.3, 0.1]}}, "mass": "2000 g", "material": "gray"},
        "arm": {
            "shape": {"cylinder": {"radius": 0.05, "length": 0.3}},
            "origin": {"xyz": [0, 0, 0.15], "rpy": [0, "90 deg", 0]},
            "mass": 1.0,
            "collision": "none",
        },
        "ball": {
            "shape": {"sphere": {"radius": 0.1}},
            "mass": 0.5,
            "collision": {"shape": {"box": {"size": [0.2, 0.2, 0.2]}}, "origin": {"xyz": [0, 0, 0.01]}},
            "com": {"xyz": [0, 0, 0.02]},
        },
    },
    "joints": {
        "shoulder": {
            "type": "revolute",
            "parent": "base",
            "child": "arm",
            "axis": [0, 0, 2],
            "limit": {"lower": 0.5, "upper": 1.0, "effort": 5.0, "velocity": 1.0},
        },
        "ball_joint": {"type": "fixed", "parent": "arm", "child": "ball", "axis": None},
    },
    "wheels": {"wheel": {"parent": "base", "radius": 0.1, "width": 0.05, "mass": 0.4, "origin": {"xyz": [0, 0.2, 0]}}},
    "frames": {"camera": {"parent": "base", "origin": {"xyz": [0.2, 0, 0.1]}}},
    "ros2_control": {},
}


def robot_of(spec: dict) -> Robot:
    spec = {k: v for k, v in spec.items() if v is not None}
    spec["joints"] = {n: {k: v for k, v in j.items() if v is not None} for n, j in spec.get("joints", {}).items()}
    return resolve(validate(load_text(yaml.safe_dump(spec, sort_keys=False), file="spec.yaml")))


@pytest.fixture(scope="module")
def robot() -> Robot:
    return robot_of(SPEC)


def test_quantities_arrive_in_si_and_the_root_is_found(robot):
    base = next(link for link in robot.links if link.name == "base")
    assert base.visuals == (Visual(Box((0.4, 0.3, 0.1)), Origin(), "gray"),)
    assert base.inertial is not None and base.inertial.mass == 2.0
    assert robot.root == "base"
    assert robot.materials == (("gray", (0.5, 0.5, 0.5, 1.0)),)


def test_shape_inertia_is_the_closed_form_in_the_shapes_frame(robot):
    links = {link.name: link for link in robot.links}
    box = links["base"].inertial
    assert box is not None and (box.kind, box.origin, box.mass) == ("box", Origin(), 2.0)
    tensor = (box.ixx, box.ixy, box.ixz, box.iyy, box.iyz, box.izz)
    assert tensor == pytest.approx((2.0 / 12 * 0.1, 0.0, 0.0, 2.0 / 12 * 0.17, 0.0, 2.0 / 12 * 0.25), rel=1e-12)
    cylinder = links["arm"].inertial
    assert cylinder is not None and cylinder.kind == "cylinder"
    assert cylinder.izz == pytest.approx(1.0 * 0.05**2 / 2) and cylinder.ixx == pytest.approx((3 * 0.05**2 + 0.09) / 12)
    assert cylinder.origin == links["arm"].visuals[0].origin  # about the cylinder's own axis, where the shape sits
    sphere = links["ball"].inertial
    assert sphere is not None and sphere.kind == "sphere" and sphere.ixx == pytest.approx(2 * 0.5 * 0.01 / 5)
    assert sphere.origin == Origin(xyz=(0.0, 0.0, 0.02))  # com moves the inertial frame, not the shape


def test_collision_same_none_or_its_own(robot):
    links = {link.name: link for link in robot.links}
    assert links["base"].collisions == (Collision(Box((0.4, 0.3, 0.1)), Origin()),)
    assert links["arm"].collisions == ()
    assert links["ball"].collisions == (Collision(Box((0.2, 0.2, 0.2)), Origin(xyz=(0.0, 0.0, 0.01))),)
    assert len(links["ball"].visuals) == 1 and isinstance(links["ball"].visuals[0].shape, Sphere)
    assert isinstance(links["arm"].visuals[0].shape, Cylinder)


def test_joint_axes_are_unit_vectors_and_fixed_joints_have_none(robot):
    joints = {joint.name: joint for joint in robot.joints}
    assert joints["shoulder"].axis == (0.0, 0.0, 1.0)
    assert joints["ball_joint"].axis is None and joints["ball_joint"].limit is None


def test_frames_become_a_link_on_a_fixed_joint_named_after_it(robot):
    joints = {joint.name: joint for joint in robot.joints}
    camera = joints["camera_joint"]
    assert (camera.type, camera.parent, camera.child, camera.origin.xyz) == ("fixed", "base", "camera", (0.2, 0.0, 0.1))
    assert "camera" in robot.link_names and "camera_joint" in robot.joint_names


def test_wheels_get_their_defaults(robot):
    (wheel,) = robot.wheels
    assert (wheel.axis, wheel.effort, wheel.velocity, wheel.damping, wheel.friction) == ("y", 10.0, 10.0, 0.01, 0.0)
    assert (wheel.mu1, wheel.mu2, wheel.joint_name) == (1.0, 1.0, "wheel_joint")


def test_ros2_control_interfaces_and_a_start_inside_the_limits(robot):
    control = {joint.name: joint for joint in robot.ros2_control or ()}
    assert set(control) == {"shoulder", "wheel_joint"}  # moving joints only
    assert control["shoulder"].interfaces.command == ("position",)
    assert control["shoulder"].initial_position == 0.5  # zero lies outside [0.5, 1.0]: the nearest limit
    assert control["wheel_joint"].interfaces.command == ("velocity",)
    assert robot.mock_integrates  # a velocity-commanded wheel: mock hardware must integrate


def test_without_ros2_control_there_is_none():
    spec = {k: v for k, v in SPEC.items() if k != "ros2_control"}
    assert robot_of(spec).ros2_control is None


def test_the_model_is_frozen(robot):
    with pytest.raises(dataclasses.FrozenInstanceError):
        robot.name = "other"  # type: ignore[misc]
    assert all(math.isfinite(v) for joint in robot.joints for v in joint.origin.xyz)


def limit() -> dict:
    return {"limit": {"lower": -1.0, "upper": 1.0, "effort": 10.0, "velocity": 1.0}}


def test_a_wheel_and_a_dh_rows_body_get_their_inertia_in_the_model():
    """The model is the single source of every inertia: a wheel's (a solid cylinder about its axle) and a DH row's
    body (a cylinder from its link frame to the next joint, or a sphere where they meet) are computed in resolve,
    here checked against the closed forms written out."""
    robot = robot_of(
        {
            "robot": "r",
            "links": {"base": {"shape": {"box": {"size": [0.4, 0.3, 0.1]}}, "mass": 5.0}},
            "wheels": {"w": {"parent": "base", "radius": 0.1, "width": 0.04, "mass": 0.8, "axis": "x"}},
            "arms": {
                "arm": {
                    "parent": "base",
                    "joints": [
                        {
                            "name": "j1",
                            "link": "l1",
                            "a": 0.0,
                            "d": 0.3,
                            "alpha": 0.0,
                            "mass": 2.0,
                            "radius": 0.05,
                            **limit(),
                        },
                        {
                            "name": "j2",
                            "link": "l2",
                            "a": 0.5,
                            "d": 0.0,
                            "alpha": 0.0,
                            "mass": 1.0,
                            "radius": 0.04,
                            **limit(),
                        },
                    ],
                }
            },
        }
    )
    (wheel,) = robot.wheels
    axial, transverse = 0.8 * 0.1**2 / 2, 0.8 * (3 * 0.1**2 + 0.04**2) / 12
    assert wheel.inertia is not None
    assert (wheel.inertia.ixx, wheel.inertia.iyy, wheel.inertia.izz) == pytest.approx((axial, transverse, transverse))
    first, second = robot.arms[0].rows
    # standard DH: row 1 (a = 0) ends where it starts: a sphere; row 2 runs 0.5 m along x: a cylinder of that length
    assert first.body is not None and isinstance(first.body.shape, Sphere)
    assert first.body.inertia.ixx == pytest.approx(2 / 5 * 2.0 * 0.05**2)
    assert second.body is not None and isinstance(second.body.shape, Cylinder)
    assert second.body.shape.length == pytest.approx(0.5) and second.body.origin.xyz == pytest.approx((0.25, 0, 0))
    assert second.body.origin.rpy == pytest.approx((0, math.pi / 2, 0))  # (its axis along x)
    assert second.body.inertia.izz == pytest.approx(1.0 * 0.04**2 / 2)
    assert second.body.inertia.ixx == pytest.approx(1.0 * (3 * 0.04**2 + 0.5**2) / 12)
