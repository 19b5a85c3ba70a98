"""A limit's error never reads as within the limit (issue 41): "1 rad is outside [-1, 1]" came of printing 1.0000001 to
six digits. Values are printed as the shortest text that reads back as the same double, beside the spec's own text
where it gave a unit; every number parsed back from a message is outside the range parsed back with it."""

from __future__ import annotations

import math
import re

import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st

from conftest import gen_robot
from xacrokit.errors import SpecErrors
from xacrokit.load import load_text
from xacrokit.validate import validate

NUMBER = r"-?\d+\.?\d*(?:e[-+]?\d+)?"
# NAME = [WRITTEN (]VALUE UNIT[)] is outside its limits [[LOW', HIGH'] (][LOW, HIGH] UNIT[)]
OUTSIDE = re.compile(
    rf"^(?P<joint>\w+) = (?:(?P<written>[^()]+) \()?(?P<value>{NUMBER}) (?P<unit>rad|m)\)? is outside its limits "
    rf"(?:\[(?P<written_low>[^],]+), (?P<written_high>[^]]+)\] \()?\[(?P<low>{NUMBER}), (?P<high>{NUMBER})\] "
    rf"(?P<limit_unit>rad|m)\)?$"
)


def _spec(limit: dict, pose: dict, joint_type: str = "revolute") -> str:
    spec = {
        "robot": "digits",
        "links": {
            "base": {"shape": {"box": {"size": [0.2, 0.2, 0.1]}}, "mass": 2},
            "arm": {"shape": {"box": {"size": [0.05, 0.05, 0.3]}}, "mass": 1},
        },
        "joints": {
            "joint_1": {
                "type": joint_type,
                "parent": "base",
                "child": "arm",
                "axis": [0, 0, 1],
                "limit": {**limit, "effort": 1, "velocity": 1},
            }
        },
        "poses": {"home": {"joint_1": pose}},
    }
    return yaml.safe_dump(spec, sort_keys=False)


def _outside(text: str) -> dict:
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(text, "digits.yaml"))
    (error,) = caught.value.errors
    assert error.path == "$.poses.home.joint_1", error
    found = OUTSIDE.match(error.message)
    assert found, error.message
    return found.groupdict()


def _reads_outside(said: dict) -> bool:
    return not float(said["low"]) <= float(said["value"]) <= float(said["high"])


def test_a_value_just_beyond_the_upper_limit_reads_beyond_it():
    said = _outside(_spec({"lower": -1, "upper": 1}, 1.0000001))
    assert float(said["value"]) == 1.0000001 and (float(said["low"]), float(said["high"])) == (-1.0, 1.0)
    assert said["unit"] == said["limit_unit"] == "rad" and said["written"] is None
    assert _reads_outside(said)


def test_a_value_in_degrees_keeps_its_words_beside_the_exact_radians():
    said = _outside(_spec({"lower": -1, "upper": 1}, "57.2958 deg"))  # (1.00000036 rad)
    assert said["written"] == "57.2958 deg" and float(said["value"]) == math.radians(57.2958)
    assert _reads_outside(said)
    said = _outside(_spec({"lower": "-90 deg", "upper": "90 deg"}, "90.0000001 deg"))
    assert (said["written"], said["written_low"], said["written_high"]) == ("90.0000001 deg", "-90 deg", "90 deg")
    assert float(said["high"]) == math.pi / 2 and _reads_outside(said)


def test_a_prismatic_joint_says_metres_as_exactly():
    said = _outside(_spec({"lower": 0, "upper": 0.2}, 0.2000000000000001, "prismatic"))
    assert said["unit"] == "m" and float(said["value"]) == 0.2000000000000001 and _reads_outside(said)
    said = _outside(_spec({"lower": "0 mm", "upper": "200 mm"}, "200.0000001 mm", "prismatic"))
    assert said["written"] == "200.0000001 mm" and said["written_high"] == "200 mm" and _reads_outside(said)


@given(
    bound=st.floats(-3, 3, allow_nan=False).filter(lambda b: b != 0),
    ulps=st.integers(1, 1000),
    above=st.booleans(),
)
def test_any_value_beyond_a_limit_reads_beyond_it(bound, ulps, above):
    low, high = (bound - 1, bound) if above else (bound, bound + 1)
    value = high if above else low
    for _ in range(ulps):  # (a few doubles beyond: what six digits printed as the limit itself)
        value = math.nextafter(value, math.inf if above else -math.inf)
    said = _outside(_spec({"lower": low, "upper": high}, value))
    assert float(said["value"]) == value and (float(said["low"]), float(said["high"])) == (low, high)
    assert _reads_outside(said)


def test_generate_says_it_so_with_exit_2_writing_nothing(tmp_path):
    spec = tmp_path / "digits.yaml"
    spec.write_text(_spec({"lower": -1, "upper": 1}, 1.0000001), encoding="utf-8")
    result = gen_robot("generate", spec, "-o", tmp_path / "pkg")
    assert result.returncode == 2 and not (tmp_path / "pkg").exists(), result.stderr
    printed = re.findall(r"^\s*(.+?):(\d+):(\d+): (\$\S*): (.*)$", result.stderr, flags=re.M)
    (found,) = printed
    assert found[3] == "$.poses.home.joint_1"
    said = OUTSIDE.match(found[4])
    assert said and float(said["value"]) == 1.0000001 and _reads_outside(said.groupdict())
