"""Validation: every class of mistake in a spec is reported at its place, all at once, with what would be right."""

from __future__ import annotations

import copy
import math
from pathlib import Path

import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st

from xacrokit.errors import SpecErrors
from xacrokit.load import load_text
from xacrokit.scene import scene_validator
from xacrokit.testing import valid_specs
from xacrokit.validate import robot_validator, validate

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

BASE = {
    "robot": "r",
    "materials": {"gray": [0.5, 0.5, 0.5, 1.0]},
    "links": {
        "base_link": {"shape": {"box": {"size": [0.4, 0.3, 0.1]}}, "mass": 2.0, "material": "gray"},
        "arm": {"shape": {"cylinder": {"radius": 0.05, "length": 0.3}}, "origin": {"xyz": [0, 0, 0.15]}, "mass": 1.0},
    },
    "joints": {
        "shoulder": {
            "type": "revolute",
            "parent": "base_link",
            "child": "arm",
            "axis": [0, 1, 0],
            "limit": {"lower": -1.0, "upper": 1.0, "effort": 5.0, "velocity": 1.0},
        },
    },
    "arms": {
        "dh": {
            "parent": "base_link",
            "joints": [
                {
                    "name": "j1",
                    "link": "l1",
                    "a": 0.1,
                    "d": 0.1,
                    "alpha": "pi/2",
                    "mass": 0.5,
                    "limit": {"lower": -1.0, "upper": 1.0, "effort": 5.0, "velocity": 1.0},
                }
            ],
        }
    },
    "wheels": {"left_wheel": {"parent": "base_link", "radius": 0.05, "width": 0.02, "mass": 0.2}},
    "frames": {"camera_link": {"parent": "base_link", "origin": {"xyz": [0.2, 0, 0.1]}}},
}


def errors_of(data) -> list:
    text = yaml.safe_dump(data, sort_keys=False)
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(text, "spec.yaml"))
    for error in caught.value.errors:
        assert error.file == "spec.yaml" and error.line is not None and error.column is not None
        assert str(error).startswith(f"spec.yaml:{error.line}:{error.column}: {error.path}: ")
    return caught.value.errors


def mutated(path: str, value=None, *, delete: bool = False):
    data = copy.deepcopy(BASE)
    *parents, last = [int(p) if p.isdigit() else p for p in path.split(".")]
    holder = data
    for part in parents:
        holder = holder[part]
    if delete:
        del holder[last]
    else:
        holder[last] = value
    return data


def test_the_base_spec_is_valid():
    spec = validate(load_text(yaml.safe_dump(BASE, sort_keys=False), "spec.yaml"))
    assert spec.data["arms"]["dh"]["joints"][0]["alpha"] == pytest.approx(1.5707963267948966, rel=1e-15)


CASES = [
    # (what is changed, new value or "DELETE", expected JSON path, words of the message)
    ("robot", "my robot", "$.robot", "not a valid name"),
    ("robot", "${evil}", "$.robot", "not a valid name"),
    ("robot", "wheel", "$.robot", "robot name 'wheel' is taken by a xacrokit macro"),
    ("robot", "if", "$.robot", "robot name 'if' is taken"),
    ("links.base_link.mass", -1.0, "$.links.base_link.mass", "mass must be > 0 kg, got -1.0"),
    ("links.base_link.mass", "-2 kg", "$.links.base_link.mass", "mass must be > 0 kg"),
    ("links.base_link.mass", "3 parsecs", "$.links.base_link.mass", "unknown unit 'parsecs'"),
    ("links.base_link.mass", "[1]", "$.links.base_link.mass", "unexpected '['"),
    ("links.base_link.colour", "red", "$.links.base_link.colour", "unknown key 'colour'"),
    ("links.base_link.material", "grey", "$.links.base_link.material", "material 'grey' is not in materials"),
    ("links.base_link.shape", {"box": {"size": [1, 1, 0]}}, "$.links.base_link.shape.box.size[2]", "must be > 0 m"),
    (
        "links.base_link.shape",
        {"box": {"size": [1, 1]}},
        "$.links.base_link.shape.box.size",
        "expected 3 values, got 2",
    ),
    ("arms.dh.joints", [], "$.arms.dh.joints", "expected at least 1 entry, got 0"),
    ("materials.gray", [128, 128, 128, 1], "$.materials.gray[0]", "must be <= 1, got 128 (colours are 0..1"),
    (
        "joints.shoulder.limit",
        {"lower": -1.0, "upper": 1.0, "effort": "10 Nm", "velocity": 1.0},
        "$.joints.shoulder.limit.effort",
        "expected a plain number in SI units, got '10 Nm'",
    ),
    (
        "links.base_link.shape",
        {"mesh": {"filename": "package://p/m.stl"}},
        "$.links.base_link.mass",
        "cannot be computed; give inertia",
    ),
    (
        "links.base_link.shape",
        {"box": {"size": [1, 1, 1]}, "sphere": {"radius": 1}},
        "$.links.base_link.shape",
        "exactly one of box",
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
    (
        "links.base_link.origin",
        {"xyz": [0, 0, "90 deg"]},
        "$.links.base_link.origin.xyz[2]",
        "is an angle, expected a length",
    ),
    ("links.bad-name", {}, "$.links['bad-name']", "not a valid name"),
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
    ("joints.shoulder.parent", "base_lnk", "$.joints.shoulder.parent", "did you mean 'base_link'"),
    ("joints.shoulder.child", "nothing", "$.joints.shoulder.child", "child 'nothing' is not in links"),
    ("joints.shoulder.type", "ball", "$.joints.shoulder.type", "is not one of"),
    ("joints.shoulder.axis", [0, 0, 0], "$.joints.shoulder.axis", "axis must not be zero"),
    (
        "joints.shoulder.limit",
        {"lower": 1.0, "upper": -1.0, "effort": 1.0, "velocity": 1.0},
        "$.joints.shoulder.limit.lower",
        "lower (1.0) is greater than upper (-1.0)",
    ),
    ("joints.shoulder.limit", "DELETE", "$.joints.shoulder", "a revolute joint needs limit"),
    (
        "joints.shoulder.limit",
        {"lower": -1.0, "upper": 1.0, "effort": 0, "velocity": 1.0},
        "$.joints.shoulder.limit.effort",
        "must be > 0",
    ),
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
    ("wheels.left_wheel.radius", "-5 cm", "$.wheels.left_wheel.radius", "radius must be > 0 m"),
    ("arms.dh.joints.0.alpha", "90 mm", "$.arms.dh.joints[0].alpha", "is a length, expected an angle"),
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


@pytest.mark.parametrize(("change", "value", "path", "words"), CASES, ids=[c[0] + ":" + str(c[1])[:20] for c in CASES])
def test_each_mistake_is_located_and_explained(change, value, path, words):
    data = mutated(change, delete=True) if value == "DELETE" else mutated(change, value)
    errors = errors_of(data)
    matching = [e for e in errors if e.path == path and words in e.message]
    assert matching, "\n".join(str(e) for e in errors)


def test_quantities_are_converted_in_a_copy_and_the_loaded_spec_is_left_alone():
    spec = mutated("joints.shoulder.limit.lower", "-90 deg")
    spec["links"]["arm"]["origin"]["xyz"] = ["10 mm", 0, 0.15]
    raw = load_text(yaml.safe_dump(spec, sort_keys=False), "spec.yaml")
    before = copy.deepcopy(raw.data)
    data = validate(raw).data
    assert raw.data == before  # still the text the user wrote: errors and positions are about that
    assert data["joints"]["shoulder"]["limit"]["lower"] == pytest.approx(-math.pi / 2, rel=1e-15)
    assert data["links"]["arm"]["origin"]["xyz"] == [0.01, 0.0, 0.15]
    assert all(type(v) is float for v in data["links"]["arm"]["origin"]["xyz"])  # ints become floats too
    assert data["arms"]["dh"]["joints"][0]["alpha"] == pytest.approx(math.pi / 2, rel=1e-15)
    assert data["links"]["base_link"] is raw.data["links"]["base_link"]  # nothing to convert there: shared


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


def test_all_problems_are_reported_together_in_file_order():
    data = copy.deepcopy(BASE)
    data["links"]["base_link"]["material"] = "grey"
    data["joints"]["shoulder"]["parent"] = "nowhere"
    data["wheels"]["left_wheel"]["mass"] = "-1 kg"
    errors = errors_of(data)
    assert len(errors) >= 3
    assert [e.line for e in errors] == sorted(e.line for e in errors)


def test_the_line_points_at_the_offending_value():
    text = yaml.safe_dump(mutated("joints.shoulder.parent", "base_lnk"), sort_keys=False)
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(text, "spec.yaml"))
    (error,) = caught.value.errors
    line = text.splitlines()[error.line - 1]
    assert line[error.column - 1 :].startswith("base_lnk")


def test_a_floating_joint_must_hang_from_the_root():
    data = mutated("joints.hover", {"type": "floating", "parent": "arm", "child": "hovering"})
    data["links"]["hovering"] = {"shape": {"sphere": {"radius": 0.1}}, "mass": 1.0}
    messages = [(e.path, e.message) for e in errors_of(data)]
    assert (
        "$.joints.hover.type",
        "a floating joint may only hang from the root link (a floating base): simulators "
        "such as MuJoCo reject deeper ones",
    ) in messages


def test_a_name_with_a_final_newline_is_not_a_name():
    # Python's `$` matches before a final newline; JSON Schema's patterns are ECMA-262, where it does not
    spec = copy.deepcopy(BASE)
    spec["links"]["arm\n"] = spec["links"].pop("arm")
    spec["joints"]["shoulder"]["child"] = "arm\n"
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(yaml.safe_dump(spec, sort_keys=False), "spec.yaml"))
    assert any("'arm\\n' is not a valid name" in error.message for error in caught.value.errors), caught.value.errors


_ODD_VALUES = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(-(2**70), 2**70),
    st.floats(),  # NaN and infinities too: jsonschema-rs cannot take them, so jsonschema decides
    st.text(max_size=6),
    st.sampled_from(["base\n", "", "1abc", "a b", "revolute", "150 mm", "pi/2", "a/b", "_x"]),
    st.lists(st.floats(allow_nan=False), max_size=4),
    st.dictionaries(st.sampled_from(["box", "size", "xyz", "mass", "x"]), st.integers(0, 3), max_size=2),
)


def _places(node: object, path: tuple = ()) -> list[tuple]:
    found = [path]
    if isinstance(node, dict):
        for key, value in node.items():
            found += _places(value, (*path, key))
    elif isinstance(node, list):
        for index, value in enumerate(node):
            found += _places(value, (*path, index))
    return found


@st.composite
def _perturbed(draw, documents: st.SearchStrategy[dict]) -> dict:
    """A valid document with one place changed: a value replaced, a key renamed or added, or an entry removed."""
    document = copy.deepcopy(draw(documents))
    path = draw(st.sampled_from(_places(document)[1:]))
    holder = document
    for part in path[:-1]:
        holder = holder[part]
    how = draw(st.sampled_from(["replace", "rename", "add", "remove"]))
    key = path[-1]
    if how == "replace":
        holder[key] = draw(_ODD_VALUES)
    elif isinstance(holder, dict) and how == "rename":
        holder[draw(st.sampled_from(["base\n", "x y", "extra", "9a", key + "_"]))] = holder.pop(key)
    elif isinstance(holder, dict) and how == "add":
        holder[draw(st.sampled_from(["extra", "mass", "origin", "type"]))] = draw(_ODD_VALUES)
    else:
        del holder[key]
    return document


def _scene_documents() -> list[dict]:
    return [yaml.safe_load(path.read_text()) for path in sorted((EXAMPLES / "scenes").glob("*.yaml"))]


@pytest.mark.parametrize("kind", ["robot", "scene"])
@given(data=st.data())
def test_the_fast_schema_check_accepts_only_what_jsonschema_accepts(kind, data):
    validator = robot_validator() if kind == "robot" else scene_validator()
    valid = valid_specs() if kind == "robot" else st.sampled_from(_scene_documents())
    document = data.draw(valid)
    if kind == "robot":  # a valid spec takes the fast path (or the speed is gone)
        assert validator.accepts_quickly(document)
    document = data.draw(st.one_of(_perturbed(valid), _perturbed(_perturbed(valid))))
    if validator.accepts_quickly(document):
        assert not list(validator.full.iter_errors(document)), document


def test_a_joint_from_a_link_to_itself_is_one_error_not_also_a_cycle():
    data = mutated("joints.shoulder", {"type": "fixed", "parent": "arm", "child": "arm"})
    messages = [e.message for e in errors_of(data)]
    assert any("a joint cannot connect a link to itself" in m for m in messages)
    assert not any("cycle" in m for m in messages), messages


def test_a_spec_that_is_not_a_mapping_says_so():
    with pytest.raises(SpecErrors) as caught:
        validate(load_text("- 1\n- 2\n", "spec.yaml"))
    (error,) = caught.value.errors
    assert error.message == "a spec is a mapping (robot:, links:, ...), got list"
