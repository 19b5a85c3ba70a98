"""A pose keeps the mimic joints it drives within their limits (issue 41): a home that put a gripper's mimic joint at
4.5 rad against limits of +-1 went unwarned into ros2_control's initial_value and the MuJoCo keyframe. Refused at the
leader's entry, naming the mimic joint, where it would be and its limits; through chains of mimics; a mimic joint
without limits only where no double says its position."""

from __future__ import annotations

import math
import re

import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st
from lxml import etree

from conftest import gen_robot
from xacrokit.emit import emit_urdf
from xacrokit.errors import SpecErrors
from xacrokit.load import load_text
from xacrokit.resolve import resolve
from xacrokit.validate import validate


def _box(size: float, mass: float) -> dict:
    return {"shape": {"box": {"size": [size, size, size]}}, "mass": mass}


def _spec(*, chain: bool = True) -> dict:
    """A wrist (revolute, +-1 rad) that a finger follows (x3 + 1.5, +-1 rad) and, with ``chain``, a knuckle (continuous,
    x2) whose tip follows it (+0.1 rad, -60 deg .. 180 deg): a mimic of a mimic."""
    limit = {"lower": -1, "upper": 1, "effort": 1, "velocity": 1}
    spec = {
        "robot": "gripper",
        "links": {"base": _box(0.2, 2), "palm": _box(0.05, 0.5), "finger": _box(0.01, 0.02)},
        "joints": {
            "wrist": {"type": "revolute", "parent": "base", "child": "palm", "axis": [0, 0, 1], "limit": {**limit}},
            "finger_joint": {
                "type": "revolute",
                "parent": "palm",
                "child": "finger",
                "axis": [1, 0, 0],
                "limit": {**limit},  # (a copy: yaml would write the same dict as an alias, which specs refuse)
                "mimic": {"joint": "wrist", "multiplier": 3, "offset": 1.5},
            },
        },
        "ros2_control": {},
    }
    if chain:
        spec["links"] |= {"knuckle": _box(0.01, 0.02), "tip": _box(0.01, 0.02)}
        spec["joints"]["knuckle_joint"] = {
            "type": "continuous",
            "parent": "palm",
            "child": "knuckle",
            "axis": [0, 1, 0],
            "limit": {"effort": 1, "velocity": 1},
            "mimic": {"joint": "wrist", "multiplier": 2},
        }
        spec["joints"]["tip_joint"] = {
            "type": "revolute",
            "parent": "knuckle",
            "child": "tip",
            "axis": [0, 1, 0],
            "limit": {"lower": "-60 deg", "upper": "180 deg", "effort": 1, "velocity": 1},
            "mimic": {"joint": "knuckle_joint", "offset": 0.1},
        }
    return spec


NUMBER = r"-?(?:\d+\.?\d*(?:e[-+]?\d+)?|inf|nan)"
DRIVEN = re.compile(
    rf"^(?P<leader>\w+) = (?P<value>{NUMBER}) rad puts mimic joint (?P<mimic>\w+) at (?P<at>{NUMBER}) rad, "
    rf"(?:outside its limits (?:\[[^]]*\] \()?\[(?P<low>{NUMBER}), (?P<high>{NUMBER})\] rad\)?"
    rf"|beyond the (?P<turns>\d+) turns a position may make) \(mimic: (?P<rules>[^)]*)\); give \w+ "
    rf"(?:a position in \[(?P<from>{NUMBER}), (?P<to>{NUMBER})\] rad|another position)"
)


def _text(poses: dict, spec: dict | None = None) -> str:
    return yaml.safe_dump({**(spec or _spec()), "poses": poses}, sort_keys=False, default_flow_style=None)


def _errors(poses: dict, spec: dict | None = None):
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(_text(poses, spec), "gripper.yaml"))
    return caught.value.errors


def _driven(error) -> dict:
    found = DRIVEN.match(error.message)
    assert found, error.message
    return found.groupdict()


def test_a_home_that_puts_a_mimic_joint_beyond_its_limits_is_refused_at_the_leaders_entry():
    text = _text({"home": {"wrist": 1}})  # (the finger at 4.5 rad; the knuckle at 2 rad, the tip at 2.1: within)
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(text, "gripper.yaml"))
    (error,) = caught.value.errors
    assert error.path == "$.poses.home.wrist"
    line = text.splitlines()[error.line - 1]
    assert line[: error.column - 1].endswith("{wrist: ") and line[error.column - 1 :] == "1}"  # (the leader's value)
    said = _driven(error)
    assert said["leader"] == "wrist" and float(said["value"]) == 1.0
    assert said["mimic"] == "finger_joint" and float(said["at"]) == 4.5
    assert (float(said["low"]), float(said["high"])) == (-1.0, 1.0)
    assert said["rules"] == "finger_joint = 3.0 x wrist + 1.5"


def test_the_positions_it_offers_are_taken_and_the_next_double_is_not():
    spec = _spec(chain=False)
    (error,) = _errors({"home": {"wrist": 1}}, spec)
    said = _driven(error)
    low, high = float(said["from"]), float(said["to"])
    assert (low, high) == pytest.approx((-5 / 6, -1 / 6), abs=1e-12)
    for value in (low, high, (low + high) / 2):
        validate(load_text(_text({"home": {"wrist": value}}, spec), "gripper.yaml"))
    for value in (math.nextafter(low, -math.inf), math.nextafter(high, math.inf)):
        (error,) = _errors({"home": {"wrist": value}}, spec)
        assert _driven(error)["mimic"] == "finger_joint"


def test_a_chain_of_mimics_is_followed_to_its_end():
    """wrist -0.7 keeps the finger within +-1 (-0.6) and the knuckle has no limits (-1.4), but the tip, following the
    knuckle, is at -1.3 rad, below -60 deg."""
    (error,) = _errors({"home": {"wrist": -0.7}, "other": {"wrist": -0.5}})  # (-0.5: the tip at -0.9, within)
    said = _driven(error)
    assert error.path == "$.poses.home.wrist"
    assert said["mimic"] == "tip_joint" and float(said["at"]) == pytest.approx(-1.3, abs=1e-15)
    assert (float(said["low"]), float(said["high"])) == (math.radians(-60), math.radians(180))
    assert said["rules"] == "knuckle_joint = 2.0 x wrist + 0.0; tip_joint = 1.0 x knuckle_joint + 0.1"
    assert "outside its limits [-60 deg, 180 deg] ([" in error.message  # (as the spec wrote them, then exact)
    # what keeps both the finger (wrist in [-5/6, -1/6]) and the tip (wrist >= (-pi/3 - 0.1) / 2) within theirs
    assert float(said["from"]) == pytest.approx((-math.pi / 3 - 0.1) / 2, abs=1e-12)
    assert float(said["to"]) == pytest.approx(-1 / 6, abs=1e-12)


def test_a_pose_within_every_limit_validates_and_reaches_ros2_control():
    spec = validate(load_text(_text({"home": {"wrist": -0.2}}), "gripper.yaml"))
    root = etree.fromstring(emit_urdf(resolve(spec)).encode())
    written = {
        j.get("name"): float(j.find("state_interface[@name='position']/param[@name='initial_value']").text)
        for j in root.iterfind("ros2_control/joint")
    }
    assert written["wrist"] == -0.2 and written["finger_joint"] == pytest.approx(0.9, abs=1e-15)
    assert written["knuckle_joint"] == pytest.approx(-0.4, abs=1e-15)
    # a mimic of a mimic starts where its leader's start puts it (it was written 0.1: its leader taken as 0)
    assert written["tip_joint"] == pytest.approx(-0.3, abs=1e-15)


def test_a_mimic_joint_without_limits_is_refused_only_beyond_what_a_double_says():
    spec = _spec()
    spec["joints"]["finger_joint"]["mimic"] = {"joint": "wrist"}
    spec["joints"]["knuckle_joint"]["mimic"]["multiplier"] = 1e308
    errors = _errors({"home": {"wrist": 0.5}}, spec)  # (the knuckle at 5e307 rad; the tip too, beyond 180 deg)
    said = sorted((_driven(e) for e in errors), key=lambda d: d["mimic"])
    assert [d["mimic"] for d in said] == ["knuckle_joint", "tip_joint"]
    assert said[0]["turns"] == "1000" and float(said[0]["at"]) == 5e307
    offered = float(said[0]["from"]), float(said[0]["to"])  # (the tip's: wrist within about 1e-308 of 0)
    assert 0 < offered[1] - offered[0] < 1e-307
    for value in offered:
        validate(load_text(_text({"home": {"wrist": value}}, spec), "gripper.yaml"))
    spec["joints"]["knuckle_joint"]["mimic"]["multiplier"] = 100
    spec["joints"]["tip_joint"]["mimic"]["offset"] = -50
    validate(load_text(_text({"home": {"wrist": 0.5}}, spec), "gripper.yaml"))  # (50 rad: 8 turns, taken)


def test_a_continuous_leader_drives_a_limited_mimic():
    spec = _spec(chain=False)
    spec["joints"]["wrist"] = {**spec["joints"]["wrist"], "type": "continuous", "limit": {"effort": 1, "velocity": 1}}
    (error,) = _errors({"home": {"wrist": "5 deg"}, "wide": {"wrist": -0.45}}, spec)
    assert error.path == "$.poses.home.wrist"
    assert error.message.startswith("wrist = 5 deg (0.08726646259971647 rad) puts mimic joint finger_joint at ")
    said = DRIVEN.match(error.message.replace("5 deg (0.08726646259971647 rad)", "0.08726646259971647 rad"))
    assert said and float(said["from"]) == pytest.approx(-5 / 6) and float(said["to"]) == pytest.approx(-1 / 6)


@given(
    multiplier=st.floats(-10, 10, allow_nan=False).filter(lambda m: abs(m) > 1e-3),
    offset=st.floats(-2, 2, allow_nan=False),
    wrist=st.floats(-1, 1, allow_nan=False),
)
def test_refused_exactly_when_the_mimics_position_is_outside_its_limits(multiplier, offset, wrist):
    """The oracle: offset + multiplier x wrist against [-1, 1], computed here."""
    spec = _spec(chain=False)
    spec["joints"]["finger_joint"]["mimic"] = {"joint": "wrist", "multiplier": multiplier, "offset": offset}
    position = offset + multiplier * wrist
    if -1 <= position <= 1:
        validate(load_text(_text({"home": {"wrist": wrist}}, spec), "gripper.yaml"))
    else:
        (error,) = _errors({"home": {"wrist": wrist}}, spec)
        said = _driven(error)
        assert float(said["at"]) == position and said["mimic"] == "finger_joint"


def test_generate_refuses_it_with_exit_2_and_writes_nothing(tmp_path):
    spec = tmp_path / "gripper.yaml"
    spec.write_text(_text({"home": {"wrist": 1}}), encoding="utf-8")
    out = tmp_path / "pkg"
    result = gen_robot("generate", spec, "-o", out)
    assert result.returncode == 2 and not out.exists(), result.stderr
    assert "Traceback" not in result.stderr
    printed = re.findall(r"^\s*(.+?):(\d+):(\d+): (\$\S*): (.*)$", result.stderr, flags=re.M)
    (found,) = printed
    assert found[0] == str(spec) and found[3] == "$.poses.home.wrist"
    said = DRIVEN.match(found[4])
    assert said and said["mimic"] == "finger_joint" and float(said["at"]) == 4.5
