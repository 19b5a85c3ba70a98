"""The one walk over a spec's bodies that every pass reads: each body once, in the order the name and tree checks
rely on (an arm's base, its rows, its tool)."""

from __future__ import annotations

from validate_cases import BASE

from xacrokit.validate.bodies import bodies


def test_every_body_once_in_the_spec_order_an_arm_along_its_chain():
    data = {**BASE, "arms": {"dh": {**BASE["arms"]["dh"], "tool": {"name": "flange"}}, "dh2": BASE["arms"]["dh"]}}
    found = [(kind, name, path) for kind, name, path, _ in bodies(data)]
    assert found == [
        ("link", "base_link", ("links", "base_link")),
        ("link", "arm", ("links", "arm")),
        ("arm", "dh_base", ("arms", "dh")),
        ("row", "l1", ("arms", "dh", "joints", 0)),
        ("tool", "flange", ("arms", "dh", "tool")),
        ("arm", "dh2_base", ("arms", "dh2")),
        ("row", "l1", ("arms", "dh2", "joints", 0)),
        ("tool", "tool0", ("arms", "dh2", "tool")),
        ("wheel", "left_wheel", ("wheels", "left_wheel")),
        ("frame", "camera_link", ("frames", "camera_link")),
    ]
    mappings = {path: mapping for _, _, path, mapping in bodies(data)}
    assert mappings[("arms", "dh", "tool")] == {"name": "flange"} and mappings[("arms", "dh2", "tool")] == {}
    assert mappings[("arms", "dh", "joints", 0)] is BASE["arms"]["dh"]["joints"][0]
