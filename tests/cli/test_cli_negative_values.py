"""A word that starts with a minus sign and a digit is a value, for every option of every command (issue 43, item 1):
argparse alone called ``--to -0.5,0.3,0.5`` "expected one argument" (only a bare ``-1`` or ``-.5`` was a value)."""

from __future__ import annotations

import json

import pytest

from conftest import REPO
from xacrokit.cli.app import main

PLANAR = str(REPO / "examples" / "robots" / "planar_2dof.yaml")


def run(capsys, *words: str) -> tuple[int, str, str]:
    code = main(list(words))
    out, err = capsys.readouterr()
    return code, out, err


def test_ik_takes_a_target_that_starts_with_a_minus_sign(capsys):
    code, out, err = run(capsys, "ik", PLANAR, "tool_link", "--to", "-0.5,0.3,0.06", "--json")
    assert code in (0, 1), err  # (the parse reached the solver: 2 was argparse's "expected one argument")
    assert "expected one argument" not in err
    assert json.loads(out)["frame"] == "tool_link"


def test_pose_takes_a_point_that_starts_with_a_minus_sign(capsys):
    code, out, err = run(capsys, "pose", PLANAR, "tool_link", "--point", "-1,0,0", "--json")
    assert code == 0, err
    # (all joints at 0: the tool at x = 1 m along the base's x, so 1 m back along its x is the base's origin in x)
    assert json.loads(out)["point"] == pytest.approx([0.0, 0.0, 0.06], abs=1e-12)


def test_jacobian_takes_a_wrench_that_starts_with_a_minus_sign(capsys):
    code, out, err = run(capsys, "jacobian", PLANAR, "tool_link", "--exerts", "-10,0,0", "--json")
    assert code == 0, err
    # (all joints at 0: the arm along x, so a force along x needs no torque of either joint)
    assert json.loads(out)["torques"] == pytest.approx({"joint_1": 0.0, "joint_2": 0.0}, abs=1e-12)


def test_size_takes_a_load_that_starts_with_a_minus_sign(capsys):
    code, out, err = run(capsys, "size", PLANAR, "--load", "-1,0,0@tool_link", "--json")
    assert code in (0, 1), err
    (load,) = json.loads(out)["loads"]
    assert load["frame"] == "tool_link" and load["force"] == [-1.0, 0.0, 0.0]


@pytest.mark.parametrize("value", ["-5", "-.5", "-0.5deg", "-1e3,2", "-30deg,10deg"])
def test_every_number_like_word_is_a_value_and_options_still_options(capsys, value):
    code, out, err = run(capsys, "pose", PLANAR, "tool_link", "--point", value, "--json")
    assert code == 2 and out == ""  # (not three lengths: pose's own words say so, not argparse's)
    assert "--point" in err and "give X,Y,Z" in err and "expected one argument" not in err
    with pytest.raises(SystemExit) as usage:  # (a mistyped option is still an option: argparse's usage error)
        main(["pose", PLANAR, "tool_link", "--point", "-1,0,0", "--jsn"])
    out, err = capsys.readouterr()
    assert usage.value.code == 2 and out == "" and "unrecognized arguments: --jsn" in err
