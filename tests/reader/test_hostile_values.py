"""The same hostile value gets the same answer from every command that places a robot's parts (issue 40): an axis of
(1e308, 1e308, 0) is the diagonal it names (pose and the MJCF export agree, and scipy's rotation about the diagonal
says where the tool goes), while a NaN origin, an origin of 1e308 m and a zero axis are refused, exit 2, in the same
words by pose, jacobian, ik, size, render and export."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from lxml import etree
from scipy.spatial.transform import Rotation

from xacrokit.cli import main

LINK = (
    '<link name="{name}"><inertial><mass value="1"/>'
    '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>'
    '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>'
)


def robot(*, origin: str = "0 0 0", axis: str = "0 0 1") -> str:
    """A base, a revolute joint 'j' (origin, axis as given, limits ±pi) to 'arm', and a fixed tool 0.5 m along x."""
    return (
        '<robot name="hostile">'
        + LINK.format(name="base")
        + LINK.format(name="arm")
        + '<link name="tool"/>'
        + f'<joint name="j" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="{origin}"/>'
        + f'<axis xyz="{axis}"/><limit lower="-3.2" upper="3.2" effort="100" velocity="1"/></joint>'
        + '<joint name="t" type="fixed"><parent link="arm"/><child link="tool"/><origin xyz="0.5 0 0"/></joint>'
        + "</robot>"
    )


def commands(path: str, out) -> dict[str, list[str]]:
    return {
        "pose": ["pose", path, "tool"],
        "jacobian": ["jacobian", path, "tool"],
        "ik": ["ik", path, "tool", "--to", "0.3,0.3,0", "--position-only"],
        "size": ["size", path],
        "render": ["render", path, "-o", str(out / "p.png"), "--size", "160x120"],
        "export": ["export", path, "--mjcf", "-o", str(out / "m.xml")],
    }


@pytest.mark.parametrize(
    ("origin", "axis", "said"),
    [
        ("0 0 nan", "0 0 1", "joint 'j' origin xyz: '0 0 nan' is not 3 finite number(s)"),
        ("1e308 1e308 0", "0 0 1", "joint 'j': <origin xyz> '1e308 1e308 0': each must be a number of at most"),
        ("0 0 0", "0 0 0", "joint 'j': its axis is zero"),
        ("0 0 0", "0 0 inf", "joint 'j' axis: '0 0 inf' is not 3 finite number(s)"),
    ],
)
def test_every_command_refuses_a_hostile_value_in_the_same_words(origin, axis, said, tmp_path, capsys):
    path = tmp_path / "hostile.urdf"
    path.write_text(robot(origin=origin, axis=axis), encoding="utf-8")
    for command, words in commands(str(path), tmp_path).items():
        code = main(words)
        err = capsys.readouterr().err
        assert code == 2, f"{command}: exit {code}: {err}"
        assert said in err, f"{command} said: {err}"
        assert "Traceback" not in err


def test_an_axis_of_1e308_is_the_diagonal_for_pose_and_export(tmp_path, capsys):
    path = tmp_path / "diagonal.urdf"
    path.write_text(robot(axis="1e308 1e308 0"), encoding="utf-8")
    assert main(["pose", str(path), "tool", "--at", "j=90deg", "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    diagonal = np.array([1.0, 1.0, 0.0]) / math.sqrt(2.0)
    want = Rotation.from_rotvec(math.pi / 2 * diagonal).apply([0.5, 0.0, 0.0])  # (scipy: the independent oracle)
    assert np.allclose(got["xyz"], want, atol=1e-12)
    assert not np.allclose(got["xyz"], [0.5, 0.0, 0.0])  # (the joint turns: not the identity)
    assert main(["export", str(path), "--mjcf", "-o", str(tmp_path / "m.xml")]) == 0
    joint = etree.parse(str(tmp_path / "m.xml")).find(".//joint[@name='j']")
    assert np.allclose([float(v) for v in joint.get("axis").split()], diagonal, atol=1e-12)
