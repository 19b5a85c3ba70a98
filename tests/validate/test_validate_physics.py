"""The physics pass: sizes and masses > 0, a mass on every body that moves or has a shape, physical inertia tensors,
limits that suit the joint type, non-zero axes, floating joints only at the root."""

from __future__ import annotations

import copy

import pytest
from validate_cases import BASE, assert_mistake_located, case_ids, errors_of, mutated

CASES = [
    # (what is changed, new value or "DELETE", expected JSON path, words of the message)
    ("links.base_link.mass", "-2 kg", "$.links.base_link.mass", "mass must be > 0 kg"),  # (checked once in SI)
    ("links.base_link.shape", {"box": {"size": [1, 1, 0]}}, "$.links.base_link.shape.box.size[2]", "must be > 0 m"),
    (
        "links.base_link.shape",
        {"mesh": {"filename": "package://p/m.stl"}},  # (a mass and no inertia: the mesh must give it)
        "$.links.base_link.shape.mesh.filename",
        "package 'p' is not known here",
    ),
    (
        "links.base_link.inertia",
        {"ixx": 1.0, "iyy": 1.0, "izz": 3.0},
        "$.links.base_link.inertia",
        "triangle inequality",
    ),
    (
        "links.base_link.inertia",
        {"ixx": 1.0, "iyy": 1.0, "izz": 1.0, "ixy": 2.0},
        "$.links.base_link.inertia",
        "not positive definite",
    ),
    ("links.arm.mass", "DELETE", "$.links.arm", "a link with a shape needs a mass"),
    ("arms.dh.joints.0.mass", "DELETE", "$.arms.dh.joints[0]", "moves link 'l1', which has no mass"),
    (
        "frames.camera_link.shape",
        {"box": {"size": [0.1, 0.1, 0.1]}},
        "$.frames.camera_link",
        "a frame with a shape needs a mass",
    ),
    (
        "joints.shoulder",
        {"type": "continuous", "parent": "base_link", "child": "arm"},
        "$.joints.shoulder",
        "a continuous joint needs limit",
    ),
    ("joints.shoulder.axis", [0, 0, 0], "$.joints.shoulder.axis", "axis must not be zero"),
    (
        "joints.shoulder.limit",
        {"lower": 1.0, "upper": -1.0, "effort": 1.0, "velocity": 1.0},
        "$.joints.shoulder.limit.lower",
        "lower (1.0) is greater than upper (-1.0)",
    ),
    ("joints.shoulder.limit", "DELETE", "$.joints.shoulder", "a revolute joint needs limit"),
    ("wheels.left_wheel.radius", "-5 cm", "$.wheels.left_wheel.radius", "radius must be > 0 m"),
]


@pytest.mark.parametrize(("change", "value", "path", "words"), CASES, ids=case_ids(CASES))
def test_each_physics_mistake_is_located_and_explained(change, value, path, words):
    assert_mistake_located(change, value, path, words)


def test_a_floating_joint_must_hang_from_the_root():
    data = mutated("joints.hover", {"type": "floating", "parent": "arm", "child": "hovering"})
    data["links"]["hovering"] = {"shape": {"sphere": {"radius": 0.1}}, "mass": 1.0}
    messages = [(e.path, e.message) for e in errors_of(data)]
    assert (
        "$.joints.hover.type",
        "a floating joint may only hang from the root link (a floating base): simulators "
        "such as MuJoCo reject deeper ones",
    ) in messages


@pytest.mark.parametrize("character", ["\x00", "\x01", "\x1f", "\ufffe", "\uffff"])
def test_a_mesh_file_name_an_xml_file_cannot_hold_is_refused(character):
    """lxml refused such a name with a traceback once; a URDF cannot carry it at all."""
    data = copy.deepcopy(BASE)
    data["links"]["base_link"]["collision"] = {"shape": {"mesh": {"filename": f"package://p/a{character}b.stl"}}}
    (error,) = errors_of(data)
    assert error.path == "$.links.base_link.collision.shape.mesh.filename"
    assert f"U+{ord(character):04X}, a character an XML file (a URDF) cannot hold" in error.message


def test_a_mass_of_zero_is_said_once_with_what_to_do(tmp_path):
    """Issue 31: `mass: 0` used to get "has a mass but no shape" and "mass must be > 0" at once, which contradict;
    now one message, the same with a shape or without."""
    from xacrokit.errors import SpecErrors
    from xacrokit.load import load_text
    from xacrokit.validate import validate

    text = """robot: m
links:
  base: {}
  arm: {shape: {box: {size: [0.1, 0.1, 0.3]}}, mass: 0}
  tip: {mass: 0}
joints:
  j: {type: revolute, parent: base, child: arm, axis: [0, 0, 1], limit: {lower: -1, upper: 1, effort: 1, velocity: 1}}
  k: {type: fixed, parent: arm, child: tip}
"""
    with pytest.raises(SpecErrors) as raised:
        validate(load_text(text, "m.yaml"))
    said = [(e.path, e.message) for e in raised.value.errors]
    assert said == [
        (
            f"$.links.{name}.mass",
            "mass is 0 kg: leave `mass` out for a link that weighs nothing (a frame), else give its mass (> 0)",
        )
        for name in ("arm", "tip")
    ]
