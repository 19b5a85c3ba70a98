"""Hostile orientations (issue 41): every rotation form at its extremes is a located error, never a warning printed
by numpy, never a URDF written with an angle no double can say; the command line exits 2 and writes nothing."""

from __future__ import annotations

import math
import re
import warnings

import pytest
import yaml

from conftest import gen_robot
from xacrokit.errors import SpecErrors
from xacrokit.load import load_text
from xacrokit.validate import validate

SPEC = {
    "robot": "rot",
    "links": {
        "base_link": {"shape": {"box": {"size": [0.2, 0.2, 0.1]}}, "mass": 2.0},
        "camera": {"shape": {"box": {"size": [0.02, 0.08, 0.02]}}, "mass": 0.1},
    },
    "joints": {"camera_joint": {"type": "fixed", "parent": "base_link", "child": "camera", "origin": {}}},
}
PRINTED = re.compile(r"^(?P<file>.+?):(?P<line>\d+):(?P<column>\d+): (?P<path>\$\S*): (?P<message>.*)$")

CASES = [
    # (origin, where the error stands under the origin, words of its message)
    ({"quat": [0, 0, 0, 0]}, "quat", "has length 0:"),
    ({"quat": [1e308, 0, 0, 1e308]}, "quat", "has length 1.41e+308:"),  # (its length said, not inf)
    ({"quat": [1e-300, 0, 0, 0]}, "quat", "has length 1e-300:"),
    ({"quat_wxyz": [1e308, 1e308, 1e308, 1e308]}, "quat_wxyz", "has length inf:"),  # (beyond any double)
    ({"axis_angle": {"axis": [0, 0, 0], "angle": 1}}, "axis_angle.axis", "has length 0;"),
    ({"axis_angle": {"axis": [0, 0, 1], "angle": 1e308}}, "axis_angle.angle", "beyond the 1000 turns"),
    ({"axis_angle": {"axis": [0, 0, 1], "angle": "1e308 deg"}}, "axis_angle.angle", "'1e308 deg' is 1.745"),
    ({"matrix": [[1, 2, 3], [4, 5, 6], [7, 8, 9]]}, "matrix", "it holds 9.0, and a rotation's entries"),
    ({"matrix": [[1e308, 0, 0], [0, 1e308, 0], [0, 0, 1e308]]}, "matrix", "it holds 1e+308"),
    ({"matrix": [[1, 0.01, 0], [0, 1, 0], [0, 0, 1]]}, "matrix", "R^T R is 0.01 from the identity"),
    ({"matrix": [[0, 0, 0], [0, 0, 0], [0, 0, 0]]}, "matrix", "R^T R is 1 from the identity"),
    ({"matrix": [[float("nan"), 0, 0], [0, 1, 0], [0, 0, 1]]}, "matrix[0][0]", "not a finite number"),
    ({"euler": {"sequence": "xyz", "angles": [1e308, 0, 0]}}, "euler.angles[0]", "beyond the 1000 turns"),
    ({"euler": {"sequence": "ZYX", "angles": [0, "1e300 deg", 0]}}, "euler.angles[1]", "beyond the 1000 turns"),
    ({"rpy": [0, 0, 1e308]}, "rpy[2]", "beyond the 1000 turns"),
    ({"rotvec": [1e308, 1e308, 1e308]}, "rotvec", "an angle of 1.73e+308 rad"),
]


def _text(origin) -> str:
    spec = yaml.safe_load(yaml.safe_dump(SPEC))
    spec["joints"]["camera_joint"]["origin"] = origin
    return yaml.safe_dump(spec, sort_keys=False, default_flow_style=None)


@pytest.mark.parametrize(("origin", "where", "words"), CASES, ids=[c[1] + ":" + str(c[0])[:40] for c in CASES])
def test_an_orientation_at_its_extremes_is_a_located_error(origin, where, words):
    text = _text(origin)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # (numpy's RuntimeWarning on an overflow is a message the user would see)
        with pytest.raises(SpecErrors) as caught:
            validate(load_text(text, "rot.yaml"))
    (error,) = caught.value.errors
    assert error.path == f"$.joints.camera_joint.origin.{where}" and words in error.message, error
    assert error.line is not None and error.column is not None
    key = re.sub(r"\[\d+\]", "", where).rsplit(".", 1)[-1]
    lines = text.splitlines()  # (a value on its key's line; a block list on the lines below its key)
    assert any(f"{key}:" in line for line in lines[error.line - 2 : error.line]), (error.line, text)


def test_an_angle_of_many_turns_within_the_bound_is_still_a_warning():
    spec = validate(load_text(_text({"rpy": [0, 0, 90]}), "rot.yaml"))  # (degrees written without deg?)
    (warning,) = spec.warnings
    assert warning.path == "$.joints.camera_joint.origin.rpy[2]" and "if you meant degrees" in warning.message
    assert spec.data["joints"]["camera_joint"]["origin"]["rpy"] == [0, 0, 90]
    limit = 1000 * math.tau
    validate(load_text(_text({"rpy": [0, 0, limit]}), "rot.yaml"))  # (the bound itself is taken)
    with pytest.raises(SpecErrors):
        validate(load_text(_text({"rpy": [0, 0, math.nextafter(limit, math.inf)]}), "rot.yaml"))


def test_generate_refuses_them_with_exit_2_writing_nothing(tmp_path):
    """The forms that once went through (exit 0, rpy of 1e308 written) or printed numpy's RuntimeWarning."""
    for index, (origin, where) in enumerate(
        [
            ({"euler": {"sequence": "xyz", "angles": [1e308, 1e308, 1e308]}}, "euler.angles[0]"),
            ({"matrix": [[1e308, 0, 0], [0, 1e308, 0], [0, 0, 1e308]]}, "matrix"),
            ({"axis_angle": {"axis": [0, 0, 1], "angle": 1e308}}, "axis_angle.angle"),
        ]
    ):
        spec = tmp_path / f"rot{index}.yaml"
        spec.write_text(_text(origin), encoding="utf-8")
        result = gen_robot("generate", spec, "-o", tmp_path / f"pkg{index}")
        assert result.returncode == 2 and not (tmp_path / f"pkg{index}").exists(), result.stderr
        assert "Traceback" not in result.stderr and "Warning" not in result.stderr, result.stderr
        printed = [m for m in map(PRINTED.match, (line.strip() for line in result.stderr.splitlines())) if m]
        assert printed and printed[0]["path"] == f"$.joints.camera_joint.origin.{where}", result.stderr
        assert all(m["file"] == str(spec) for m in printed)
