"""The names pass: names unique and not reserved, every reference to something that exists, one tree."""

from __future__ import annotations

import copy

import pytest
import yaml
from validate_cases import BASE, assert_mistake_located, case_ids, errors_of, mutated

from xacrokit.errors import SpecErrors
from xacrokit.load import load_text
from xacrokit.validate import validate

CASES = [
    # (what is changed, new value or "DELETE", expected JSON path, words of the message)
    ("robot", "wheel", "$.robot", "robot name 'wheel' is taken by a xacrokit macro"),
    ("robot", "if", "$.robot", "robot name 'if' is taken"),
    ("robot", "__bot", "$.robot", "robot name '__bot' starts with two underscores, which xacro refuses"),
    ("links.base_link.material", "grey", "$.links.base_link.material", "material 'grey' is not in materials"),
    ("joints.shoulder.parent", "base_lnk", "$.joints.shoulder.parent", "did you mean 'base_link'"),
    ("joints.shoulder.child", "nothing", "$.joints.shoulder.child", "child 'nothing' is not in links"),
    ("joints.shoulder.mimic", {"joint": "shoulder"}, "$.joints.shoulder.mimic.joint", "cannot mimic itself"),
    ("joints.shoulder.mimic", {"joint": "nope"}, "$.joints.shoulder.mimic.joint", "not a joint of this robot"),
    (
        "joints.dup",
        {"type": "fixed", "parent": "base_link", "child": "arm"},
        "$.joints.dup",
        "link 'arm' already has parent 'base_link'",
    ),
    (
        "joints.left_wheel_joint",
        {"type": "fixed", "parent": "arm", "child": "arm"},
        "$.wheels.left_wheel",
        "joint name 'left_wheel_joint' is already used by $.joints.left_wheel_joint",
    ),
    (
        "wheels.arm",
        {"parent": "base_link", "radius": 0.1, "width": 0.1, "mass": 1.0},
        "$.wheels.arm",
        "link name 'arm' is already used by $.links.arm",
    ),
    ("arms.dh.joints.0.link", "arm", "$.arms.dh.joints[0].link", "link name 'arm' is already used"),
    ("arms.dh.parent", "ghost", "$.arms.dh.parent", "parent 'ghost' is not a link"),
    ("frames.camera_link.parent", "camera_link", "$.frames.camera_link.parent", "form a cycle"),
    ("gazebo", {"links": {"ghost": {"mu1": 1.0}}}, "$.gazebo.links.ghost", "not a link"),
    (
        "ros2_control",
        {"joints": {"camera_link_joint": {"command": ["position"]}}},
        "$.ros2_control.joints.camera_link_joint",
        "is a fixed joint",
    ),
]


@pytest.mark.parametrize(("change", "value", "path", "words"), CASES, ids=case_ids(CASES))
def test_each_name_or_reference_mistake_is_located_and_explained(change, value, path, words):
    assert_mistake_located(change, value, path, words)


def test_two_roots_are_reported():
    data = mutated("links.island", {"shape": {"sphere": {"radius": 0.1}}, "mass": 1.0})
    (error,) = errors_of(data)
    assert "2 separate trees" in error.message and "base_link, island" in error.message


def test_a_cycle_through_joints_is_reported():
    data = copy.deepcopy(BASE)
    data["links"]["x"] = {}
    data["links"]["y"] = {}
    data["joints"]["xy"] = {"type": "fixed", "parent": "x", "child": "y"}
    data["joints"]["yx"] = {"type": "fixed", "parent": "y", "child": "x"}
    messages = [e.message for e in errors_of(data)]
    assert any("links x, y form a cycle" in m for m in messages)


def test_the_line_points_at_the_offending_value():
    text = yaml.safe_dump(mutated("joints.shoulder.parent", "base_lnk"), sort_keys=False)
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(text, "spec.yaml"))
    (error,) = caught.value.errors
    line = text.splitlines()[error.line - 1]
    assert line[error.column - 1 :].startswith("base_lnk")


def test_a_joint_from_a_link_to_itself_is_one_error_not_also_a_cycle():
    data = mutated("joints.shoulder", {"type": "fixed", "parent": "arm", "child": "arm"})
    messages = [e.message for e in errors_of(data)]
    assert any("a joint cannot connect a link to itself" in m for m in messages)
    assert not any("cycle" in m for m in messages), messages


def test_mimic_joints_that_follow_each_other_round_a_loop_are_an_error():
    data = copy.deepcopy(BASE)
    data["links"]["finger_a"] = {"shape": {"sphere": {"radius": 0.01}}, "mass": 0.1}
    data["links"]["finger_b"] = {"shape": {"sphere": {"radius": 0.01}}, "mass": 0.1}
    for name, child, other in (("grip_a", "finger_a", "grip_b"), ("grip_b", "finger_b", "grip_a")):
        data["joints"][name] = {
            "type": "prismatic",
            "parent": "base_link",
            "child": child,
            "axis": [0, 1, 0],
            "limit": {"lower": 0.0, "upper": 0.04, "effort": 10.0, "velocity": 0.1},
            "mimic": {"joint": other},
        }
    (error,) = errors_of(data)
    assert error.path == "$.joints.grip_a.mimic.joint"
    assert "mimic joints grip_a -> grip_b -> grip_a form a cycle" in error.message
    del data["joints"]["grip_b"]["mimic"]  # one of them driven: a chain that ends, no cycle
    validate(load_text(yaml.safe_dump(data, sort_keys=False), "spec.yaml"))
