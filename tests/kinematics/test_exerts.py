"""One load, two commands (issue 43, item 4): ``jacobian --exerts`` is the wrench the tool exerts on the environment
(tau = J^T w), ``size --load`` the force the environment applies to the robot (its reaction, -w); ``--wrench``, the
old name of ``--exerts``, still works one release with a warning that says its sign."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from conftest import REPO
from xacrokit.cli.app import main
from xacrokit.cli.size_commands import parse_load
from xacrokit.reader.read_robot import read_robot
from xacrokit.sizing.sized_robot import loaded_robot
from xacrokit.sizing.static import torques

PLANAR = str(REPO / "examples" / "robots" / "planar_2dof.yaml")
ARM = str(REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml")
L1, L2 = 0.6, 0.4


def run(capsys, *words: str) -> tuple[int, str, str]:
    code = main(list(words))
    out, err = capsys.readouterr()
    return code, out, err


def test_exerts_is_tau_equals_j_transpose_w_and_warns_of_nothing(capsys):
    code, out, err = run(capsys, "jacobian", PLANAR, "tool_link", "--q", "30deg,60deg", "--exerts", "0,-10,0", "--json")
    assert (code, err) == (0, "")
    q1, q2 = math.radians(30), math.radians(60)
    x = L1 * math.cos(q1) + L2 * math.cos(q1 + q2)  # (the force along -y: tau_i = -10 * dy/dq_i)
    expected = {"joint_1": -10 * x, "joint_2": -10 * L2 * math.cos(q1 + q2)}
    assert json.loads(out)["torques"] == pytest.approx(expected, abs=1e-12)


def test_wrench_is_exerts_old_name_with_a_warning_that_says_its_sign(capsys):
    words = ["jacobian", PLANAR, "tool_link", "--q", "30deg,60deg", "--json"]
    code, exerts, err = run(capsys, *words, "--exerts", "0,-10,0,0,0,1")
    assert (code, err) == (0, "")
    code, wrench, err = run(capsys, *words, "--wrench", "0,-10,0,0,0,1")
    assert code == 0 and json.loads(wrench) == json.loads(exerts)
    assert err == (
        "gen-robot jacobian: warning: --wrench is deprecated: use --exerts (the same values: the wrench the tool "
        "exerts on the environment, tau = J^T w; size --load takes the opposite, the force on the robot)\n"
    )
    code, out, err = run(capsys, *words, "--exerts", "0,0,1", "--wrench", "0,0,1")
    assert (code, out) == (2, "")
    assert err == "gen-robot: error: --exerts and --wrench: --wrench is --exerts' old name; give --exerts alone\n"
    code, out, err = run(capsys, *words, "--exerts", "1,2")
    assert (code, out) == (2, "") and err.startswith("gen-robot: error: --exerts '1,2': give FX,FY,FZ or FX,FY,FZ,MX")


def test_a_tool_pressing_down_is_exerts_down_and_a_load_up(capsys):
    """docs/kinematics.md, "One load, two commands": jacobian --exerts 0,0,-20 and size --load 0,0,20@tool ask the
    same torques of the motors (size's own Jacobian and sign, gravity aside)."""
    q = [0.0, math.radians(-30), math.radians(45), 0.0, math.radians(20), 0.0]
    given = ",".join(repr(v) for v in q)
    code, out, err = run(capsys, "jacobian", ARM, "tool0", "--q", given, "--exerts", "0,0,-20", "--json")
    assert code == 0, err
    said = json.loads(out)
    robot = loaded_robot(read_robot(ARM), loads=[parse_load("0,0,20@tool0")], gravity=0.0)
    _, by_size = torques(robot, np.array(q))
    assert [j.name for j in robot.joints] == said["joints"]
    assert list(said["torques"].values()) == pytest.approx(list(by_size), abs=1e-9)
    assert max(abs(t) for t in by_size) > 1.0  # (a pose where the load asks torque of the motors)
