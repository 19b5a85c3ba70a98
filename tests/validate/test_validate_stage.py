"""The validate stage as a whole: every pass's problems reported together, in file order."""

from __future__ import annotations

import copy

from validate_cases import BASE, errors_of


def test_all_problems_are_reported_together_in_file_order():
    data = copy.deepcopy(BASE)
    data["links"]["base_link"]["material"] = "grey"
    data["joints"]["shoulder"]["parent"] = "nowhere"
    data["wheels"]["left_wheel"]["mass"] = "-1 kg"
    errors = errors_of(data)
    assert [e.path for e in errors] == [
        "$.links.base_link.material",  # names pass
        "$.joints.shoulder.parent",  # references
        "$.wheels.left_wheel.mass",  # physics, after the units pass made it -1.0
    ]
    assert [e.line for e in errors] == sorted(e.line for e in errors)
