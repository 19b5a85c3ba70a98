"""pose, jacobian and ik on hostile input (issue 41): no exit 70 and no inf or NaN printed on any input (a result that
overflows is refused, exit 2, naming what overflowed), no numpy warning on the terminal; an axis of 1e308 1e308 0
turns about the diagonal in every pinocchio model of the robot; a mimic of no joint, a zero axis, a NaN limit are
refused with the joint and its line; a joint given twice is refused; a value outside its limits never reads as
inside them. The robots are small URDFs written to tmp_path; each CLI case is judged by its exit code and by its
parsed JSON or its stderr together."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import gen_robot
from xacrokit.cli import main
from xacrokit.cli.json_output import print_json
from xacrokit.errors import XacrokitError
from xacrokit.reader.kinematic_model import outside_text
from xacrokit.reader.pinocchio_reading import urdfdom_complaint
from xacrokit.reader.read_robot import read_robot

LIMIT = '<limit lower="{lower}" upper="{upper}" effort="1" velocity="1"/>'


def arm(
    *,
    axis: str = "0 0 1",
    lower: str = "-1",
    upper: str = "1",
    kind: str = "revolute",
    mimic: str = "",
    second: str = "revolute",
) -> str:
    """base -> j1 (line 4) -> a -> j2 (line 6, 1 m along x) -> b -> t (fixed, 1 m along x) -> tool."""
    return "\n".join(
        [
            '<robot name="r">',
            '<link name="base"/><link name="a"/><link name="b"/><link name="tool"/>',
            "<!-- j1 next -->",
            f'<joint name="j1" type="{kind}"><parent link="base"/><child link="a"/><axis xyz="{axis}"/>'
            + LIMIT.format(lower=lower, upper=upper)
            + "</joint>",
            "<!-- j2 next -->",
            f'<joint name="j2" type="{second}"><parent link="a"/><child link="b"/><origin xyz="1 0 0"/>'
            f'<axis xyz="0 0 1"/>{mimic}' + LIMIT.format(lower="-1", upper="1") + "</joint>",
            '<joint name="t" type="fixed"><parent link="b"/><child link="tool"/><origin xyz="1 0 0"/></joint>',
            "</robot>",
        ]
    )


def written(tmp_path, text: str, name: str = "r.urdf") -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def run(capsys, *words: str) -> tuple[int, str, str]:
    code = main(list(words))
    out, err = capsys.readouterr()
    return code, out, err


def strict_json(text: str):
    """JSON as RFC 8259 has it: Infinity and NaN refused (Python's json reads them by default)."""

    def refuse(constant: str):
        raise ValueError(f"{constant} is not JSON")

    return json.loads(text, parse_constant=refuse)


def one_error(err: str) -> str:
    """The one error line a refusal prints: no traceback, no warning, no urdfdom line around it."""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("gen-robot: error: "), err
    return lines[0]


# ------------------------------------------------------------------------------------- item 1: no exit 70, ever
MIMIC_1E308 = '<mimic joint="j1" multiplier="1e308" offset="1e308"/>'


@pytest.mark.parametrize(
    "words",
    [
        ["pose", "tool", "--at", "j1=1"],
        ["pose", "tool", "--at", "j1=1", "--json"],
        ["jacobian", "tool", "--at", "j1=1", "--json"],
        ["ik", "tool", "--to", "0.5,1.5,0", "--json"],
    ],
)
def test_a_mimic_of_1e308_is_refused_naming_the_joint_and_the_value(tmp_path, capsys, words):
    path = written(tmp_path, arm(mimic=MIMIC_1E308))
    code, out, err = run(capsys, words[0], path, *words[1:])
    said = one_error(err)
    assert code == 2 and out == ""
    assert "mimic joint 'j2' (<mimic> on line 6)" in said and "= inf rad, not a finite number" in said, said
    assert "1e+308 x " in said and "internal error" not in said


def test_a_mimic_of_1e308_at_a_value_it_can_take_is_answered(tmp_path, capsys):
    """At j1 = 0, j2 = 1e308 rad: a finite angle, so a pose (finite JSON), not an error."""
    code, out, err = run(capsys, "pose", written(tmp_path, arm(mimic=MIMIC_1E308)), "tool", "--json")
    found = strict_json(out)
    assert code == 0 and err == ""
    assert np.allclose(found["xyz"], [1 + math.cos(1e308), math.sin(1e308), 0], atol=1e-12)


def test_a_mimic_chain_whose_multipliers_overflow_is_refused(tmp_path, capsys):
    third = (
        '<link name="c"/><joint name="j3" type="revolute"><parent link="tool"/><child link="c"/><axis xyz="0 0 1"/>'
        '<mimic joint="j2" multiplier="1e200"/>' + LIMIT.format(lower="-1", upper="1") + "</joint></robot>"
    )
    text = arm(mimic='<mimic joint="j1" multiplier="1e200"/>').replace("</robot>", third)
    code, out, err = run(capsys, "pose", written(tmp_path, text), "c", "--json")
    said = one_error(err)
    assert code == 2 and out == ""
    assert "mimic joints j3 -> j2 -> j1: their multipliers and offsets together come to inf x 'j1'" in said, said


# ------------------------------------------------------------------- item 2: no inf or NaN printed, in JSON or text
def test_a_point_beyond_any_length_is_refused_not_printed_as_infinity(tmp_path, capsys):
    path = written(tmp_path, arm())
    for form in (["--json"], []):
        code, out, err = run(capsys, "pose", path, "tool", "--point", "1.7e308,1.7e308,0", *form)
        said = one_error(err)
        assert code == 2 and out == "", out
        assert said.endswith(
            "--point '1.7e308,1.7e308,0': 1.7e+308 m is beyond what xacrokit takes (at most 10000 m; "
            "a value in the wrong unit?)"
        ), said


def test_a_wrench_beyond_any_force_is_refused_without_a_numpy_warning(tmp_path):
    """(a subprocess: numpy's RuntimeWarning went to the process's stderr)"""
    path = written(tmp_path, arm())
    result = gen_robot("jacobian", path, "tool", "--exerts", "0,1.7e308,0,0,0,1.7e308", "--json")
    said = one_error(result.stderr)
    assert result.returncode == 2 and result.stdout == ""
    assert "--exerts '0,1.7e308,0,0,0,1.7e308': 1.7e+308 N is beyond what xacrokit takes (at most 1e+09 N" in said
    fine = gen_robot("jacobian", path, "tool", "--exerts", "0,1e9,0,0,0,1e9", "--json")
    torques = strict_json(fine.stdout)["torques"]
    assert fine.returncode == 0 and fine.stderr == ""
    assert torques == pytest.approx({"j1": 2e9 + 1e9, "j2": 1e9 + 1e9})  # (tau = J^T w: x of the tool 2 m, then 1 m)


@pytest.mark.parametrize("command", ["pose", "jacobian"])
def test_two_origins_of_1e308_are_refused_without_a_numpy_warning(tmp_path, command):
    """(issue 41 saw Infinity printed, and numpy's warning; today the 1e4 m bound refuses them first: a guard)"""
    path = written(tmp_path, arm().replace('<origin xyz="1 0 0"/>', '<origin xyz="1e308 0 0"/>'))
    result = gen_robot(command, path, "tool", "--json")
    said = one_error(result.stderr)
    assert result.returncode == 2 and result.stdout == ""
    assert "joint 'j2': <origin xyz> '1e308 0 0': each must be a number of at most 10000 m" in said
    assert "joint 't': <origin xyz> '1e308 0 0'" in said


def test_a_jacobian_that_overflows_is_refused_naming_the_column_and_the_mimic(tmp_path, capsys):
    text = arm(mimic='<mimic joint="j1" multiplier="1.7e308"/>')
    path = written(tmp_path, text.replace('<origin xyz="1 0 0"/></joint>', '<origin xyz="3 0 0"/></joint>'))
    code, out, err = run(capsys, "jacobian", path, "tool", "--json")  # (vy of j2's column: 1.7e308 x 3 m)
    said = one_error(err)
    assert code == 2 and out == ""
    assert "the Jacobian of 'tool' overflows: the column of joint 'j1' is beyond what a float holds" in said, said
    assert "'j2' moves 1.7e+308 times as fast" in said


def test_a_prismatic_mimic_beyond_any_length_is_refused_by_ik_without_warnings(tmp_path):
    path = written(tmp_path, arm(second="prismatic", mimic='<mimic joint="j1" multiplier="1e308"/>'))
    for form in (["--json"], []):
        result = gen_robot("ik", path, "tool", "--to", "0.5,1.5,0", *form)
        said = one_error(result.stderr)
        assert result.returncode == 2 and result.stdout == ""
        assert "mimic joint 'j2' (<mimic> on line 6): with 'j1' at " in said
        assert "beyond what xacrokit takes of a length (at most 10000 m)" in said, said


def test_a_prismatic_value_beyond_any_length_is_refused(tmp_path, capsys):
    code, out, err = run(capsys, "pose", written(tmp_path, arm(kind="prismatic")), "tool", "--at", "j1=1e308")
    assert code == 2 and out == ""
    assert one_error(err).endswith(
        "--at j1=1e308: 1e+308 m is beyond what xacrokit takes (at most 10000 m; a value in the wrong unit?)"
    )


def test_ik_over_limits_of_1e308_says_no_numpy_warning(tmp_path):
    path = written(tmp_path, arm(lower="-1e308", upper="1e308"))
    result = gen_robot("ik", path, "tool", "--to", "0,2,0", "--json")
    found = strict_json(result.stdout)
    assert result.returncode == 0 and result.stderr == "", result.stderr
    assert found["solutions"] and found["solutions"][0]["error"] <= 1e-9


def test_the_one_json_printer_refuses_a_number_json_cannot_hold(capsys):
    with pytest.raises(XacrokitError, match=r"the result overflows: \$\.torques\.j1 is inf, beyond what a float"):
        print_json({"frame": "tool", "torques": {"j2": 1.0, "j1": math.inf}})
    with pytest.raises(XacrokitError, match=r"\$\.rows\[1\]\[0\] is nan"):
        print_json({"rows": [[0.0], [math.nan]]})
    assert capsys.readouterr().out == ""  # (nothing printed)
    print_json({"rows": [[1e308, -0.0]]})
    assert strict_json(capsys.readouterr().out) == {"rows": [[1e308, 0.0]]}


# ----------------------------------------------------------------------- item 3: an axis of 1e308 is the diagonal
def _about(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues: the rotation by ``angle`` about the unit ``axis`` (the closed form)."""
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * k @ k


def test_an_axis_of_1e308_turns_the_free_floating_model_about_the_diagonal(tmp_path):
    """The model size and export take for a free base: pinocchio's own normalisation left this joint still."""
    import pinocchio as pin

    diagonal = np.array([1.0, 1.0, 0.0]) / math.sqrt(2.0)
    free = read_robot(written(tmp_path, arm(axis="1e308 1e308 0"))).free_floating
    q = pin.neutral(free)
    q[free.idx_qs[free.getJointId("j1")]] = 0.7
    data = free.createData()
    pin.forwardKinematics(free, data, q)
    placed = data.oMi[free.getJointId("j1")]
    assert np.allclose(placed.rotation, _about(diagonal, 0.7), atol=1e-12)


@pytest.mark.parametrize("axis", ["1e308 1e308 0", "5e-324 5e-324 0", "2 2 0"])
def test_an_axis_of_any_size_turns_pose_jacobian_and_ik_about_the_diagonal(tmp_path, capsys, axis):
    diagonal = np.array([1.0, 1.0, 0.0]) / math.sqrt(2.0)
    path = written(tmp_path, arm(axis=axis))
    code, out, err = run(capsys, "pose", path, "a", "--at", "j1=0.7", "--json")
    assert code == 0 and err == ""
    assert np.allclose(np.array(strict_json(out)["matrix"])[:3, :3], _about(diagonal, 0.7), atol=1e-12)
    code, out, err = run(capsys, "jacobian", path, "tool", "--json")
    column = np.array(strict_json(out)["jacobian"])[:, 0]
    assert code == 0 and np.allclose(column, [*np.cross(diagonal, [2.0, 0.0, 0.0]), *diagonal], atol=1e-12)
    target = _about(diagonal, 0.5) @ [2.0, 0.0, 0.0]
    code, out, err = run(capsys, "ik", path, "tool", "--to", ",".join(repr(float(v)) for v in target), "--json")
    assert code == 0 and strict_json(out)["solutions"][0]["joints"]["j1"] == pytest.approx(0.5, abs=1e-8)


# ------------------------------------------------------- item 4: a zero axis, a mimic of nothing: refused, located
@pytest.mark.parametrize("command", [["pose", "tool"], ["jacobian", "tool"], ["ik", "tool", "--to", "1,1,0"]])
def test_a_zero_axis_is_refused_with_its_joint_and_line(tmp_path, capsys, command):
    path = written(tmp_path, arm(axis="0 0 0"))
    code, out, err = run(capsys, command[0], path, *command[1:], "--json")
    assert code == 2 and out == ""
    assert one_error(err) == (
        f"gen-robot: error: {path}: joint 'j1': its axis is zero (line 4): it names no direction to turn or slide "
        "along; give one, such as 0 0 1"
    )


@pytest.mark.parametrize("command", [["pose", "tool"], ["jacobian", "tool"], ["ik", "tool", "--to", "1,1,0"]])
def test_a_mimic_of_no_joint_is_refused_with_its_joint_and_line(tmp_path, capsys, command):
    path = written(tmp_path, arm(mimic='<mimic joint="j1x"/>'))
    code, out, err = run(capsys, command[0], path, *command[1:], "--json")
    assert code == 2 and out == ""
    assert one_error(err) == (
        f"gen-robot: error: {path}: joint 'j2' (line 6): its <mimic> names 'j1x', which is no joint of the robot "
        "(did you mean 'j1'?): give the joint it follows, or remove the <mimic>"
    )


@pytest.mark.parametrize(("limit", "said"), [("nan", "<limit lower> 'nan'"), ("-inf", "<limit lower> '-inf'")])
def test_a_limit_that_is_no_finite_number_is_refused_without_urdfdoms_lines(tmp_path, limit, said):
    """(a subprocess: urdfdom prints from C++ on the process's stderr, with the paths of its own build)"""
    result = gen_robot("pose", written(tmp_path, arm(lower=limit)), "tool", "--json")
    assert result.returncode == 2 and result.stdout == ""
    assert one_error(result.stderr).endswith(f": joint 'j1' (line 4): {said} is not a finite number")


def test_what_urdfdom_refuses_is_said_without_its_source_places(tmp_path):
    """A revolute joint without <limit>: urdfdom's complaint is the reason, its build's path is not printed."""
    text = arm().replace(LIMIT.format(lower="-1", upper="1") + "</joint>", "</joint>", 1)
    result = gen_robot("pose", written(tmp_path, text), "tool")
    said = one_error(result.stderr)
    assert result.returncode == 2
    assert said.endswith(
        "pinocchio cannot read the robot: Joint [j1] is of type REVOLUTE but it does not specify limits"
    )
    printed = "Error:   a complaint [x]\n         at line 124 in /project/urdfdom/urdf_parser/src/joint.cpp\n"
    assert urdfdom_complaint(printed) == "a complaint [x]"


# ------------------------------------------------------------------------------ item 5: a joint given twice
def test_a_joint_given_twice_is_refused(tmp_path, capsys):
    path = written(tmp_path, arm())
    for command in ("pose", "jacobian"):
        code, out, err = run(capsys, command, path, "tool", "--at", "j1=0.5", "--at", " j1 =1", "--json")
        assert code == 2 and out == ""
        assert one_error(err) == "gen-robot: error: --at j1: the joint is given twice (0.5 and 1): give each joint once"


# ------------------------------------------------------------------ item 6: outside its limits never reads inside
_OUTSIDE = re.compile(r"(\S+) rad is outside its limits \[(\S+), (\S+)\] rad")


@pytest.mark.parametrize(
    ("given", "shown"),
    [
        ("1.0000000001", "1.0000000001 rad is outside its limits [-1, 1] rad"),
        ("1.0000000000011", "1.000000000001 rad is outside its limits [-1, 1] rad"),  # (the fewest digits that tell)
        ("-1.00001", "-1.00001 rad is outside its limits [-1, 1] rad"),
        ("2", "2 rad is outside its limits [-1, 1] rad"),
    ],
)
def test_a_value_outside_its_limits_is_printed_outside_them(tmp_path, capsys, given, shown):
    code, out, err = run(capsys, "pose", written(tmp_path, arm()), "tool", "--at", f"j1={given}", "--json")
    assert code == 0 and strict_json(out)["frame"] == "tool"
    assert err == f"gen-robot: warning: --at j1={given}: {shown}\n"
    value, lower, upper = (float(v) for v in _OUTSIDE.search(err).groups())
    assert not lower <= value <= upper


def test_limits_whose_lower_is_above_the_upper_are_said_so_and_ik_refuses_them(tmp_path, capsys):
    path = written(tmp_path, arm(lower="1", upper="-1"))
    code, out, err = run(capsys, "pose", path, "tool", "--at", "j1=0.5", "--json")
    assert code == 0 and strict_json(out)["frame"] == "tool"
    assert err == (
        "gen-robot: warning: --at j1=0.5: 0.5 rad is outside its limits [1, -1] rad (its lower limit is above its "
        "upper: no value is within them)\n"
    )
    code, out, err = run(capsys, "ik", path, "tool", "--to", "1,1,0", "--json")
    assert code == 2 and out == ""
    assert one_error(err).endswith(
        "joint 'j1': its lower limit 1 is above its upper -1, so no value is within them; ik searches within the "
        "limits: swap them in its <limit>"
    )


@settings(max_examples=200, deadline=None)
@given(
    value=st.floats(-1e6, 1e6, allow_nan=False),
    lower=st.floats(-1e6, 1e6, allow_nan=False),
    width=st.floats(0, 1e6, allow_nan=False),
    nudge=st.integers(1, 4),
)
def test_a_value_just_outside_is_never_printed_inside(value, lower, width, nudge):
    upper = lower + width
    for outside in (np.nextafter(upper, math.inf) * 1.0, upper + nudge * 1e-9, lower - nudge * 1e-13, value):
        if lower <= outside <= upper:
            continue
        printed = [float(v) for v in _OUTSIDE.search(outside_text(float(outside), (lower, upper), "rad")).groups()]
        assert not printed[1] <= printed[0] <= printed[2], printed


# ---------------------------------------------------------------------------------- other hostile input
def test_a_joint_name_with_control_characters_is_escaped_in_the_error(tmp_path, capsys):
    code, out, err = run(capsys, "pose", written(tmp_path, arm()), "tool", "--at", "j1\x1b[2J\x07=1")
    assert code == 2 and out == ""
    assert one_error(err).startswith("gen-robot: error: --at j1\\x1b[2J\\x07: no moving joint of that name")


def test_names_with_control_characters_are_escaped_in_text_outputs(tmp_path, capsys):
    """A link and a joint whose names hold a line break and a C1 control (XML allows both): the text outputs cannot
    forge a line or drive the terminal; JSON keeps the names as they are."""
    link, joint = "a\nfake\x9b2J", "j\nx"
    text = arm().replace('"a"', '"a&#10;fake&#x9B;2J"').replace('"j1"', '"j&#10;x"')
    path = written(tmp_path, text)
    outputs = {}
    for command in (["pose", link, "--point", "1,0,0"], ["jacobian", link, "--exerts", "1,1,1,0,0,2"], ["ik", link]):
        extra = ["--to", "0,0,0"] if command[0] == "ik" else ["--at", f"{joint}=0.5"]
        code, out, err = run(capsys, command[0], path, *command[1:], *extra)
        assert code in (0, 1) and err == "", err
        assert all(ch.isprintable() or ch == "\n" for ch in out)
        outputs[command[0]] = out.splitlines()
    assert outputs["pose"][0] == "pose of a\\nfake\\x9b2J in base at j\\nx = 0.5:"
    assert outputs["pose"][-1].endswith("m in base (1,0,0 in a\\nfake\\x9b2J)")
    name, tau = outputs["jacobian"][-2].split()  # (tau = J^T w for joint j\nx: a on its axis, the moment about z)
    assert name == "j\\nx" and float(tau) == 2.0
    # (a on j1's axis: no joint moves it, every value of j1 is a solution; the words name the frame, escaped)
    continuum = "on a continuum of solutions: the joints move a\\nfake\\x9b2J in only 0 of the 3 directions"
    assert outputs["ik"][1:] == [
        "solution 1 (error < 1e-10):",
        f"  ({continuum} of a position at any configuration)",
        "  j\\nx = 0.000000000",
        "  j2 = 0.000000000",
    ]
    code, out, err = run(capsys, "pose", path, link, "--at", f"{joint}=0.5", "--json")
    assert code == 0 and strict_json(out)["frame"] == link


def test_a_robot_without_joints_has_a_jacobian_without_columns(tmp_path, capsys):
    path = written(tmp_path, '<robot name="still"><link name="only"/></robot>')
    code, out, err = run(capsys, "jacobian", path, "only", "--json", "--exerts", "1,2,3")
    assert code == 0 and err == ""
    assert strict_json(out) == {"frame": "only", "in": "only", "joints": [], "jacobian": [[]] * 6, "torques": {}}
    code, out, err = run(capsys, "jacobian", path, "only")
    assert code == 0 and out == "only: the robot has no joint to move: its Jacobian has no column\n"
    code, out, err = run(capsys, "ik", path, "only", "--to", "0,0,0")
    assert code == 2 and one_error(err).endswith(": the robot has no revolute, continuous or prismatic joint to move")


@pytest.mark.parametrize(
    ("change", "words"),
    [
        ({"axis": "1e-320 0 0"}, ["pose", "tool", "--at", "j1=5e-324"]),
        ({"lower": "-5e-324", "upper": "5e-324"}, ["ik", "tool", "--to", "2,0,0"]),
        ({"lower": "-1e308", "upper": "1e308", "kind": "prismatic"}, ["ik", "tool", "--to", "3,0,0"]),
        ({}, ["pose", "tool", "--point", "5e-324,-1e4,1e4", "--at", "j1=1e308"]),
        ({}, ["ik", "tool", "--to", "1e4,1e4,1e4,1e308,-1e308,5e-324"]),
    ],
)
def test_hostile_but_valid_numbers_are_answered_in_finite_json(tmp_path, capsys, change, words):
    code, out, err = run(capsys, words[0], written(tmp_path, arm(**change)), *words[1:], "--json")
    assert code in (0, 1) and "error" not in err, err
    strict_json(out)


TURNED = np.array([[0.0, -1.0, 0.0, 0.5], [1.0, 0.0, 0.0, 0.2], [0.0, 0.0, 1.0, 0.1], [0.0, 0.0, 0.0, 1.0]])


@pytest.mark.parametrize(
    ("target", "said"),
    [
        (np.full((4, 4), np.nan), "not finite (nan or inf)"),
        (np.where(np.eye(4) == 1, np.inf, 0.0), "not finite (nan or inf)"),
        (np.diag([2.0, 2.0, 2.0, 1.0]), "no rotation (its columns' lengths and angles off by up to 3, determinant 8)"),
        (np.diag([1.0, 1.0, -1.0, 1.0]), "determinant -1"),
        (TURNED + np.r_[np.zeros((3, 4)), [[0.0, 0.0, 1.0, 0.0]]], "bottom row [0.0, 0.0, 1.0, 1.0]"),
        (np.r_[TURNED[:3], [[np.nan, 0.0, 0.0, 1.0]]], "bottom row [nan, 0.0, 0.0, 1.0]"),
        (np.r_[TURNED[:3], [[0.0, 0.0, 0.0, np.nan]]], "bottom row [0.0, 0.0, 0.0, nan]"),
        (np.eye(3), "is a 3x3 array"),
        (np.zeros(16), "is a 16 array"),
    ],
)
def test_the_api_refuses_a_target_that_is_no_pose_at_once_naming_the_file(tmp_path, target, said):
    """ik(robot, frame, target) on a target that is no pose: refused before any search (a NaN searched 256 starts
    for 1.2 s, then spoke of a pose error beyond a float; 2 I came back as a closest reach 4e-10 away), the file
    named; position_only asks nothing of the rotation part."""
    from xacrokit.kinematics import ik

    path = tmp_path / "arm.urdf"
    path.write_text(arm(lower="-3", upper="3"), encoding="utf-8")
    robot = read_robot(path)
    with pytest.raises(XacrokitError) as caught:
        ik(robot, "tool", target)
    assert str(caught.value).startswith(f"{path}: the target ") and said in str(caught.value), caught.value
    stretched = np.diag([2.0, 2.0, 2.0, 1.0])
    stretched[:3, 3] = [1.8, 0.3, 0.0]
    (found,) = ik(robot, "tool", stretched, position_only=True).solutions
    assert found.error < 1e-9
    assert ik(robot, "tool", TURNED).closest is not None or ik(robot, "tool", TURNED).solutions  # (a pose: answered)


def test_the_api_names_the_file_of_a_robot_without_the_frame_or_joint_asked(tmp_path):
    """pose, jacobian and ik through Python: a frame or joint the robot does not have is said with the robot's file
    (it was said without), the error still an UnknownName with its role, name and detail (what the command line
    words with its option)."""
    from xacrokit.kinematics import ik, jacobian, pose
    from xacrokit.reader.kinematic_model import UnknownName

    path = tmp_path / "arm.urdf"
    path.write_text(arm(), encoding="utf-8")
    robot = read_robot(path)
    for ask, role, name in [
        (lambda: pose(robot, "no_such"), "frame", "no_such"),
        (lambda: jacobian(robot, "tool", in_frame="no_base"), "frame", "no_base"),
        (lambda: pose(robot, "tool", at={"j9": "1"}), "joint", "j9"),
        (lambda: ik(robot, "no_tool", np.eye(4)), "frame", "no_tool"),
    ]:
        with pytest.raises(UnknownName) as caught:
            ask()
        assert (caught.value.role, caught.value.name) == (role, name)
        assert str(caught.value).startswith(f"{path}: ") and caught.value.detail in str(caught.value)
