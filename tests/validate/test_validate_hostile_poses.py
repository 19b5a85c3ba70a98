"""Hostile named poses and mirrors (issue 41): each is one located error in words of its own (never jsonschema's raw
"is not of type" or "should be non-empty", never a control character printed raw), exit 2 and nothing written."""

from __future__ import annotations

import copy
import re

import pytest
import yaml

from conftest import gen_robot
from xacrokit.errors import SpecErrors
from xacrokit.load import load_text
from xacrokit.validate import validate

LIMIT = {"lower": -1, "upper": 1, "effort": 1, "velocity": 1}
BASE = {
    "robot": "posebot",
    "links": {
        "base": {"shape": {"box": {"size": [0.2, 0.2, 0.1]}}, "mass": 2},
        "left_arm": {"shape": {"box": {"size": [0.05, 0.05, 0.3]}}, "mass": 1},
        "left_finger": {"shape": {"box": {"size": [0.01, 0.01, 0.04]}}, "mass": 0.02},
        "spinner": {"shape": {"box": {"size": [0.01, 0.01, 0.04]}}, "mass": 0.02},
        "tool": {},
    },
    "joints": {
        "left_shoulder": {
            "type": "revolute",
            "parent": "base",
            "child": "left_arm",
            "axis": [0, 1, 0],
            "limit": {**LIMIT},
        },
        "left_finger_joint": {
            "type": "revolute",
            "parent": "left_arm",
            "child": "left_finger",
            "axis": [1, 0, 0],
            "limit": {**LIMIT},
            "mimic": {"joint": "left_shoulder", "multiplier": 0.5},
        },
        "spin": {
            "type": "continuous",
            "parent": "base",
            "child": "spinner",
            "axis": [0, 0, 1],
            "limit": {"effort": 1, "velocity": 1},
        },
        "tool_joint": {"type": "fixed", "parent": "base", "child": "tool"},
    },
    "ros2_control": {},
}
RAW_WORDS = ("is not of type", "should be non-empty", "is a required property", "( ...)")

CASES = [
    # (id, section: value, the path of the one error, words of its message)
    ("continuous 1e308", {"poses": {"home": {"spin": 1e308}}}, "$.poses.home.spin", "beyond the 1000 turns"),
    (
        "continuous 1e308 deg",
        {"poses": {"home": {"spin": "1e308 deg"}}},
        "$.poses.home.spin",
        "'1e308 deg' is 1.7453292519943295e+306 rad, 2.78e+305 turns, beyond the 1000 turns",
    ),
    (
        "not a number",
        {"poses": {"home": {"spin": "hello"}}},
        "$.poses.home.spin",
        "expected a number (rad) or an angle with its unit, such as '90 deg'",
    ),
    ("a list", {"poses": {"home": {"spin": [1]}}}, "$.poses.home.spin", "expected a number or a string"),
    ("unknown joint", {"poses": {"home": {"nope": 1}}}, "$.poses.home.nope", "'nope' is not a joint"),
    ("fixed joint", {"poses": {"home": {"tool_joint": 0}}}, "$.poses.home.tool_joint", "is a fixed joint"),
    (
        "mimic joint",
        {"poses": {"home": {"left_finger_joint": 0}}},
        "$.poses.home.left_finger_joint",
        "follows 'left_shoulder' (mimic): give 'left_shoulder''s position",
    ),
    (
        "control characters",
        {"poses": {"ho\x1bme\n": {"spin": 1}}},
        "$.poses['ho\\x1bme\\n']",
        "'ho\\x1bme\\n' is not a valid name",
    ),
    ("poses a list", {"poses": [1]}, "$.poses", "expected a mapping here (NAME: value ...), got a list"),
    (
        "mimic offset 1e308",
        {"joints.left_finger_joint.mimic": {"joint": "left_shoulder", "offset": 1e308}},
        "$.joints.left_finger_joint.mimic.offset",
        "beyond the 1000 turns",
    ),
    (
        "mirror rename empty",
        {"mirror": [{"joint": "left_shoulder", "rename": ["", "right_"]}]},
        "$.mirror[0].rename[0]",
        "'' is not a valid name",
    ),
    (
        "mirror rename not a list",
        {"mirror": [{"joint": "left_shoulder", "rename": "left_"}]},
        "$.mirror[0].rename",
        "expected a list of 2 values, got 'left_'",
    ),
    (
        "mirror rename a number",
        {"mirror": [{"joint": "left_shoulder", "rename": ["left_", 7]}]},
        "$.mirror[0].rename[1]",
        "expected text (write it in quotes where YAML reads a number, yes/no or null), got 7",
    ),
    (
        "mirror of an unknown joint",
        {"mirror": [{"joint": "nope", "rename": ["left_", "right_"]}]},
        "$.mirror[0].joint",
        "no joint 'nope' in joints",
    ),
    (
        "euler sequence a list",
        {"joints.spin.origin": {"euler": {"sequence": ["z", "y", "x"], "angles": [0, 0, 0]}}},
        "$.joints.spin.origin.euler.sequence",
        "is not an Euler sequence (a list",
    ),
]


def _text(change: dict) -> str:
    spec = copy.deepcopy(BASE)
    for where, value in change.items():
        *parents, last = where.split(".")
        holder = spec
        for key in parents:
            holder = holder[key]
        holder[last] = value
    return yaml.safe_dump(spec, sort_keys=False, allow_unicode=False)


@pytest.mark.parametrize(("change", "path", "words"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_each_is_one_located_error_in_its_own_words(change, path, words):
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(_text(change), "posebot.yaml"))
    (error,) = caught.value.errors
    assert error.path == path and words in error.message, str(error)
    assert error.line is not None and error.column is not None
    assert not any(raw in error.message for raw in RAW_WORDS), error.message
    assert not re.search(r"[\x00-\x1f\x7f]", str(error)), repr(str(error))  # (no control character printed raw)


def test_a_mirror_renaming_to_control_characters_names_them_escaped():
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(_text({"mirror": [{"joint": "left_shoulder", "rename": ["left_", "x\x1b\n"]}]}), "p.yaml"))
    said = [str(e) for e in caught.value.errors]
    assert said and all(not re.search(r"[\x00-\x1f\x7f]", s) for s in said), said
    assert any("$.mirror[0].rename[1]: 'x\\x1b\\n' is not a valid name" in s for s in said), said


def test_generate_refuses_the_poses_that_once_passed_with_exit_2_writing_nothing(tmp_path):
    """A continuous joint's home of 1e308 rad (or deg) went into ros2_control's initial_value with exit 0."""
    for index, value in enumerate([1e308, "1e308 deg"]):
        spec = tmp_path / f"posebot{index}.yaml"
        spec.write_text(_text({"poses": {"home": {"spin": value}}}), encoding="utf-8")
        result = gen_robot("generate", spec, "-o", tmp_path / f"pkg{index}")
        assert result.returncode == 2 and not (tmp_path / f"pkg{index}").exists(), result.stderr
        printed = re.findall(r"^\s*(.+?):(\d+):(\d+): (\$\S*): (.*)$", result.stderr, flags=re.M)
        assert [(p[0], p[3]) for p in printed] == [(str(spec), "$.poses.home.spin")], result.stderr
        assert "beyond the 1000 turns" in printed[0][4]
