"""The units pass: every length, angle and mass becomes an SI float in a copy of the spec; a value that does not parse
is reported where it stands."""

from __future__ import annotations

import copy
import math

import pytest
import yaml
from validate_cases import BASE, assert_mistake_located, case_ids, mutated

from xacrokit.load import load_text
from xacrokit.validate import validate

CASES = [
    # (what is changed, new value or "DELETE", expected JSON path, words of the message)
    ("links.base_link.mass", "3 parsecs", "$.links.base_link.mass", "unknown unit 'parsecs'"),
    ("links.base_link.mass", "[1]", "$.links.base_link.mass", "unexpected '['"),
    (
        "links.base_link.origin",
        {"xyz": [0, 0, "90 deg"]},
        "$.links.base_link.origin.xyz[2]",
        "is an angle, expected a length",
    ),
    ("arms.dh.joints.0.alpha", "90 mm", "$.arms.dh.joints[0].alpha", "is a length, expected an angle"),
    # (a box of 1e200 m wrote inf into the URDF's inertia; a mass of 1e300 kg overflows every torque)
    ("links.base_link.mass", 1e300, "$.links.base_link.mass", "1e+300 kg is beyond what xacrokit takes (at most 1e+06"),
    ("links.base_link.mass", "1e12 g", "$.links.base_link.mass", "1e+09 kg is beyond what xacrokit takes"),
    (
        "links.base_link.origin",
        {"xyz": [0, 0, 1e200]},
        "$.links.base_link.origin.xyz[2]",
        "1e+200 m is beyond what xacrokit takes (at most 10000 m",
    ),
]


@pytest.mark.parametrize(("change", "value", "path", "words"), CASES, ids=case_ids(CASES))
def test_each_unit_mistake_is_located_and_explained(change, value, path, words):
    assert_mistake_located(change, value, path, words)


def test_the_base_spec_is_valid():
    spec = validate(load_text(yaml.safe_dump(BASE, sort_keys=False), "spec.yaml"))
    assert spec.data["arms"]["dh"]["joints"][0]["alpha"] == pytest.approx(1.5707963267948966, rel=1e-15)


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
