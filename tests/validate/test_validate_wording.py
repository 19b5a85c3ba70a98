"""Structural YAML mistakes in words a spec author understands: a key indented too little, a line whose indentation
PyYAML cannot follow, a vector where a wheel takes x/y/z (one error, not two)."""

from __future__ import annotations

import pytest

import xacrokit
from conftest import REPO

ARM = (REPO / "examples" / "robots" / "two_dof_arm.yaml").read_text(encoding="utf-8")
DIFF = (REPO / "examples" / "robots" / "diff_drive.yaml").read_text(encoding="utf-8")

CASES = {
    "material indented too little": (
        ARM.replace("    material: gray\n", "  material: gray\n", 1),
        "$.links.material",
        "'material' is read as a link name, with the value 'gray', but a link is a mapping (shape:, origin:, mass:, "
        "material: ...); if `material:` belongs to the link above it, indent it as far as that link's other keys",
    ),
    "a scalar for an origin": (
        ARM.replace("    origin: {xyz: [0, 0, 0.15]}", "    origin: 5", 1),
        "$.links.upper_arm.origin",
        "expected a mapping here (xyz:, rpy:, quat:, axis_angle: ...), got 5; if the lines below belong to it, indent "
        "them further",
    ),
    "a key indented too far": (
        ARM.replace("    mass: 1.0\n", "     mass: 1.0\n", 1),
        "$",
        "not valid YAML: did not find expected key; check the indentation of this line and of the line above it",
    ),
    "a missing colon": (
        ARM.replace("    type: revolute\n", "    type revolute\n", 1),
        "$",
        "mapping values are not allowed in this context; check the indentation",
    ),
    "a wheel axis as a vector": (
        DIFF.replace(
            "    limit: {effort: 5, velocity: 15}", "    limit: {effort: 5, velocity: 15}\n    axis: [0, 1, 0]", 1
        ),
        "$.wheels.left_wheel.axis",
        "must be x, y or z, got [0, 1, 0] (the axle's direction in the wheel's frame: write axis: y, not a vector)",
    ),
}


@pytest.mark.parametrize("case", CASES)
def test_structural_mistakes_are_worded(tmp_path, case):
    text, path, words = CASES[case]
    assert text not in (ARM, DIFF)
    spec = tmp_path / "robot.yaml"
    spec.write_text(text, encoding="utf-8")
    with pytest.raises(xacrokit.SpecErrors) as caught:
        xacrokit.generate(spec, tmp_path / "pkg", dry_run=True)
    (error,) = caught.value.errors
    assert error.path == path and words in error.message and error.line is not None, str(error)
