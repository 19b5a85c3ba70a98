"""gen-robot size for a mobile base: the diff-drive example on a 10 deg slope, its figures written out here by hand
from the spec's own numbers (the closed form of docs/size.md), its JSON by the schema, and located errors."""

from __future__ import annotations

import json
import math

import jsonschema
import pytest
import yaml

from conftest import REPO, gen_robot
from xacrokit.errors import SpecErrors
from xacrokit.sizing import size

DIFF_DRIVE = REPO / "examples" / "robots" / "diff_drive.yaml"
ASKED = {"mobile": {"speed": 0.5, "acceleration": 0.5, "slope": "10 deg", "rolling_resistance": 0.02}}


def write(tmp_path, data):
    path = tmp_path / "sizing.yaml"
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    return path


def test_the_diff_drive_on_a_slope_by_hand(tmp_path):
    report = size(DIFF_DRIVE, sizing=write(tmp_path, ASKED))
    base = report.base
    # the spec: chassis 6 kg, caster 0.1 kg, two wheels of 0.35 kg (radius 65 mm), lidar 0.17 kg, camera 0.07 kg
    mass = 6.0 + 0.1 + 2 * 0.35 + 0.17 + 0.07
    slope = math.radians(10)
    force = mass * 0.5 + mass * 9.80665 * (math.sin(slope) + 0.02 * math.cos(slope))
    spin = 0.35 * 0.065**2 / 2 * 0.5 / 0.065  # a solid cylinder's m r^2 / 2 times the wheel's a / r
    torque = force / 2 * 0.065 + spin
    assert base.mass == pytest.approx(mass, rel=1e-12)
    assert base.force == pytest.approx(force, rel=1e-12)
    assert [w.joint for w in base.wheels] == ["left_wheel_joint", "right_wheel_joint"]
    assert base.torques == pytest.approx((torque, torque), rel=1e-12)
    assert base.speeds == pytest.approx((0.5 / 0.065,) * 2, rel=1e-12)
    assert base.power == pytest.approx(2 * torque * 0.5 / 0.065, rel=1e-12)
    assert report.failed == []  # (the example's wheels: 5 N*m and 15 rad/s)
    # the check beside it: pinocchio's inverse dynamics of the whole robot pushed up the slope
    assert base.dynamics_force == pytest.approx(mass * (0.5 + 9.80665 * math.sin(slope)), rel=1e-12)


def test_a_steep_slope_fails_the_wheels_and_the_json_follows_its_schema(tmp_path):
    steep = {"mobile": {**ASKED["mobile"], "slope": "45 deg", "acceleration": 2.0, "speed": 1.2}, "payloads": []}
    result = gen_robot("size", DIFF_DRIVE, "--sizing", write(tmp_path, steep), "--json")
    report = json.loads(result.stdout)
    jsonschema.validate(report, json.loads((REPO / "schemas" / "size-report.schema.json").read_text()))
    speeds = [w["speed"] for w in report["mobile"]["wheels"]]
    assert speeds == pytest.approx([1.2 / 0.065] * 2)  # 18.5 rad/s, over the example's 15
    assert result.returncode == 1
    assert {"joint": "left_wheel_joint", "what": "wheel speed over the velocity limit"} in report["failures"]


@pytest.mark.parametrize(
    ("robot", "mobile", "path", "words"),
    [
        ("industrial_arm_std_dh", {"speed": 1, "acceleration": 1}, "$.mobile", "no wheels found"),
        ("diff_drive", {"speed": 1, "acceleration": 1, "wheels": ["left_wheel"]}, "$.mobile.wheels[0]", "did you mean"),
        ("diff_drive", {"speed": "1 kg", "acceleration": 1}, "$.mobile.speed", "is a mass"),
    ],
)
def test_mobile_mistakes_are_located(tmp_path, robot, mobile, path, words):
    with pytest.raises(SpecErrors) as caught:
        size(REPO / "examples" / "robots" / f"{robot}.yaml", sizing=write(tmp_path, {"mobile": mobile}))
    assert any(e.path == path and words in e.message for e in caught.value.errors), caught.value.errors


def test_a_payload_rides_in_the_mass_and_in_the_dynamics_check(tmp_path):
    from xacrokit.sizing import Payload

    report = size(DIFF_DRIVE, payloads=[Payload("base_link", 3.0)], sizing=write(tmp_path, ASKED))
    mass = 7.04 + 3.0
    assert report.base.mass == pytest.approx(mass, rel=1e-12)
    assert report.base.dynamics_force == pytest.approx(mass * (0.5 + 9.80665 * math.sin(math.radians(10))), rel=1e-12)
