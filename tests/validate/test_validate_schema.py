"""The schema pass: what the JSON Schema rejects is worded for a spec author and located; the fast check (jsonschema-rs)
accepts only what jsonschema accepts; patterns follow ECMA-262."""

from __future__ import annotations

import copy

import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st
from validate_cases import BASE, assert_mistake_located, case_ids, errors_of, mutated

from conftest import REPO, SCENE_EXAMPLES
from xacrokit.errors import SpecErrors
from xacrokit.load import load_text
from xacrokit.scene import scene_validator
from xacrokit.testing import valid_specs
from xacrokit.validate import robot_validator, validate

EXAMPLES = REPO / "examples"

CASES = [
    # (what is changed, new value or "DELETE", expected JSON path, words of the message)
    ("robot", "my robot", "$.robot", "not a valid name"),
    ("robot", "${evil}", "$.robot", "not a valid name"),
    ("links.base_link.mass", -1.0, "$.links.base_link.mass", "mass must be > 0 kg, got -1.0"),
    ("links.base_link.colour", "red", "$.links.base_link.colour", "unknown key 'colour'"),
    (
        "links.base_link.shape",
        {"box": {"size": [1, 1]}},
        "$.links.base_link.shape.box.size",
        "expected 3 values, got 2",
    ),
    ("arms.dh.joints", [], "$.arms.dh.joints", "expected at least 1 entry, got 0"),
    ("materials.gray", [128, 128, 128, 1], "$.materials.gray[0]", "must be <= 1, got 128 (colours are 0..1"),
    (
        "joints.shoulder.dynamics",
        {"damping": "0.1 N*m*s/rad", "friction": 0.0},  # (a limit's effort takes units: '10 Nm'; damping does not)
        "$.joints.shoulder.dynamics.damping",
        "expected a plain number in SI units, got '0.1 N*m*s/rad'",
    ),
    (
        "links.base_link.shape",
        {"box": {"size": [1, 1, 1]}, "sphere": {"radius": 1}},
        "$.links.base_link.shape",
        "exactly one of box",
    ),
    ("links.bad name", {}, "$.links['bad name']", "not a valid link or joint name"),
    ("links.bad--name", {}, "$.links['bad--name']", "in parts joined by single . / or -"),
    ("materials.bad-name", [0, 0, 0, 1], "$.materials['bad-name']", "not a valid name: use letters"),
    (
        "joints.shoulder.type",
        "ball",
        "$.joints.shoulder.type",
        "must be revolute, continuous, prismatic, fixed, floating or planar, got 'ball'",
    ),
    (
        "joints.shoulder.limit",
        {"lower": -1.0, "upper": 1.0, "effort": 0, "velocity": 1.0},
        "$.joints.shoulder.limit.effort",
        "must be > 0",
    ),
]


@pytest.mark.parametrize(("change", "value", "path", "words"), CASES, ids=case_ids(CASES))
def test_each_schema_mistake_is_located_and_explained(change, value, path, words):
    assert_mistake_located(change, value, path, words)


def test_a_limit_below_zero_is_said_once_by_its_own_name():
    # (a rate's schema equals a mass's: the schema's message once said "mass must be > 0 kg" beside the right one)
    data = mutated("joints.shoulder.limit", {"lower": -1.0, "upper": 1.0, "effort": 1.0, "velocity": -2})
    said = [str(e) for e in errors_of(data) if e.path == "$.joints.shoulder.limit.velocity"]
    assert len(said) == 1 and said[0].endswith("velocity must be > 0, got -2"), said


def test_a_name_with_a_final_newline_is_not_a_name():
    # Python's `$` matches before a final newline; JSON Schema's patterns are ECMA-262, where it does not
    spec = copy.deepcopy(BASE)
    spec["links"]["arm\n"] = spec["links"].pop("arm")
    spec["joints"]["shoulder"]["child"] = "arm\n"
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(yaml.safe_dump(spec, sort_keys=False), "spec.yaml"))
    said = [error.message for error in caught.value.errors]
    assert any("'arm\\n' is not a valid link or joint name" in message for message in said), said


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
    return [yaml.safe_load(path.read_text()) for path in SCENE_EXAMPLES]


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


def test_a_spec_that_is_not_a_mapping_says_so():
    with pytest.raises(SpecErrors) as caught:
        validate(load_text("- 1\n- 2\n", "spec.yaml"))
    (error,) = caught.value.errors
    assert error.message == "a spec is a mapping (robot:, links:, ...), got list"
