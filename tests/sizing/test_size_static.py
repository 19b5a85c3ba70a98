"""gen-robot size, static part: joint torques against closed forms written out here (a two-link planar arm with a
payload), the loads' J^T w against pinocchio's inverse dynamics with external forces, the worst-case search against
dense grids, and the command line's report, exit codes and errors."""

from __future__ import annotations

import json
import math
import re

import jsonschema
import numpy as np
import pinocchio as pin
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import REPO, gen_robot
from xacrokit.cli.size_commands import parse_load, parse_payload
from xacrokit.errors import SpecErrors, XacrokitError
from xacrokit.reader.read_robot import read_robot
from xacrokit.sizing import GRAVITY, Load, Payload, format_text, size
from xacrokit.sizing.sized_robot import loaded_robot
from xacrokit.sizing.static import torques

# the course's two-link arm: links of 0.6 m and 0.4 m, each a uniform bar (its centre of mass at its middle)
L1, L2, M1, M2 = 0.6, 0.4, 2.0, 1.2


def planar_arm(lower1=-math.pi, upper1=math.pi, lower2=-math.pi, upper2=math.pi, effort=100.0) -> str:
    """Two revolute joints about y in the x-z plane, the links along x at q = 0 (horizontal), a tool frame at the
    tip; inertials of thin bars (their tensors do not enter static torques)."""

    def bar(name, mass, length):
        i = mass * length**2 / 12
        return (
            f'<link name="{name}"><inertial><origin xyz="{length / 2} 0 0"/><mass value="{mass}"/>'
            f'<inertia ixx="1e-6" ixy="0" ixz="0" iyy="{i}" iyz="0" izz="{i}"/></inertial>'
            f'<visual><origin xyz="{length / 2} 0 0"/><geometry><box size="{length} 0.02 0.02"/></geometry></visual>'
            "</link>"
        )

    def joint(name, parent, child, x, lower, upper):
        return (
            f'<joint name="{name}" type="revolute"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin xyz="{x} 0 0"/><axis xyz="0 1 0"/>'
            f'<limit lower="{lower!r}" upper="{upper!r}" effort="{effort}" velocity="1"/></joint>'
        )

    return (
        '<robot name="planar"><link name="base"/>'
        + bar("upper", M1, L1)
        + bar("fore", M2, L2)
        + '<link name="tool"/>'
        + joint("shoulder", "base", "upper", 0.0, lower1, upper1)
        + joint("elbow", "upper", "fore", L1, lower2, upper2)
        + '<joint name="tool_joint" type="fixed"><parent link="fore"/><child link="tool"/>'
        + f'<origin xyz="{L2} 0 0"/></joint></robot>'
    )


def closed_form(q1, q2, payload=0.0):
    """The torques the motors produce to hold the arm: a point at distance r along a link at angle a about y sits at
    x = r cos a, so gravity's moment about y is m g r cos a, and the motor's is its opposite."""
    far = M2 * L2 / 2 + payload * L2
    near = M1 * L1 / 2 + (M2 + payload) * L1
    return (
        -GRAVITY * (near * np.cos(q1) + far * np.cos(q1 + q2)),
        -GRAVITY * far * np.cos(q1 + q2),
    )


@pytest.fixture
def arm_file(tmp_path):
    def write(**limits):
        path = tmp_path / "planar.urdf"
        path.write_text(planar_arm(**limits), encoding="utf-8")
        return path

    return write


angles = st.floats(-math.pi, math.pi)


@settings(max_examples=30, deadline=None)
@given(q1=angles, q2=angles, payload=st.floats(0.0, 10.0))
def test_torques_equal_the_closed_form_two_link_arm(tmp_path_factory, q1, q2, payload):
    path = tmp_path_factory.mktemp("arm") / "planar.urdf"
    path.write_text(planar_arm(), encoding="utf-8")
    robot = loaded_robot(read_robot(path), payloads=[Payload("tool", payload)] if payload else [])
    gravity, loads = torques(robot, np.array([q1, q2]))
    want = closed_form(q1, q2, payload)
    scale = GRAVITY * (M1 * L1 + (M2 + payload) * (L1 + L2))
    assert np.abs(gravity - want).max() <= 1e-12 * scale and not loads.any()


def test_the_worst_case_of_a_full_range_is_the_arm_stretched_out(arm_file):
    report = size(arm_file(), payloads=[Payload("tool", 3.0)])
    shoulder, elbow = report.peaks
    assert abs(shoulder.torque) == pytest.approx(-closed_form(0.0, 0.0, 3.0)[0], rel=1e-9)
    assert abs(elbow.torque) == pytest.approx(-closed_form(0.0, 0.0, 3.0)[1], rel=1e-9)
    q1, q2 = shoulder.pose["shoulder"], shoulder.pose["elbow"]
    assert abs(math.cos(q1)) == pytest.approx(1.0, abs=1e-9) and math.cos(q2) == pytest.approx(1.0, abs=1e-9)


@pytest.mark.parametrize(
    "limits",
    [
        {"lower1": 0.3, "upper1": 1.2, "lower2": -0.5, "upper2": 0.4},
        {"lower1": -2.5, "upper1": -1.9, "lower2": 1.0, "upper2": 2.9},
        {"lower1": 1.4, "upper1": 1.7, "lower2": -0.1, "upper2": 0.1},  # (the maximum in the interior: q1 + q2 = pi/2)
    ],
)
def test_the_search_finds_the_dense_grids_maximum_within_the_limits(arm_file, limits):
    report = size(arm_file(**limits))
    grid1 = np.linspace(limits["lower1"], limits["upper1"], 801)
    grid2 = np.linspace(limits["lower2"], limits["upper2"], 801)
    a, b = np.meshgrid(grid1, grid2, indexing="ij")
    for index, peak in enumerate(report.peaks):
        values = (
            np.abs(closed_form(a, b)[index])
            if False
            else np.abs(np.vectorize(lambda x, y, k=index: closed_form(x, y)[k])(a, b))
        )
        assert abs(peak.torque) >= values.max() * (1 - 1e-9)  # (at least the grid's best)
        pose = (peak.pose["shoulder"], peak.pose["elbow"])
        assert limits["lower1"] <= pose[0] <= limits["upper1"] and limits["lower2"] <= pose[1] <= limits["upper2"]
        assert peak.torque == pytest.approx(closed_form(*pose)[index], rel=1e-12)  # (and true where it says)


@settings(max_examples=20, deadline=None)
@given(
    q=st.lists(st.floats(-3.0, 3.0), min_size=6, max_size=6),
    force=st.lists(st.floats(-100.0, 100.0), min_size=3, max_size=3),
)
def test_loads_are_pinocchios_inverse_dynamics_with_external_forces(tmp_path_factory, q, force):
    """-J^T w (the frame Jacobian in world axes) against rnea(q, 0, 0, fext): w moved to the parent joint's frame
    as a spatial force (the moment of the force about the joint's origin added)."""
    spec = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
    robot = loaded_robot(read_robot(spec), payloads=[Payload("tool0", 2.0)], loads=[Load("tool0", tuple(force))])
    values = np.array(q)
    gravity, loads = torques(robot, values)
    model, data = robot.model, robot.model.createData()
    configuration = robot.configuration(values)
    pin.forwardKinematics(model, data, configuration)
    pin.updateFramePlacements(model, data)
    frame = model.frames[model.getFrameId("tool0")]
    point = data.oMf[model.getFrameId("tool0")].translation
    world = pin.Force(np.array(force), np.cross(point, np.array(force)))  # (about the world's origin)
    fext = [pin.Force.Zero() for _ in range(model.njoints)]
    fext[frame.parentJoint] = data.oMi[frame.parentJoint].actInv(world)
    zero = np.zeros(model.nv)
    tau = pin.rnea(model, data, configuration, zero, zero, fext)[[j.v_index for j in robot.joints]]
    scale = max(np.abs(tau).max(), 1.0)
    assert np.abs(gravity + loads - tau).max() <= 1e-9 * scale


def test_the_command_line_reports_json_by_its_schema_and_fails_on_a_margin(arm_file, tmp_path):
    path = arm_file(effort=5.0)  # (the stretched-out shoulder needs ~ 28 N*m)
    result = gen_robot("size", path, "--payload", "1 kg@tool", "--json")
    assert result.returncode == 1, result.stderr
    report = json.loads(result.stdout)
    schema = json.loads((REPO / "schemas" / "size-report.schema.json").read_text(encoding="utf-8"))
    jsonschema.validate(report, schema)
    shoulder = report["joints"][0]
    assert shoulder["name"] == "shoulder" and not shoulder["static"]["pass"]
    # (stretched out either way: q1 = 0 or pi, the sign of the torque with it)
    assert abs(shoulder["static"]["peak_torque"]) == pytest.approx(-closed_form(0, 0, 1.0)[0], rel=1e-9)
    assert set(shoulder["static"]["pose"]) == {"shoulder", "elbow"}
    assert report["failed"] == ["shoulder", "elbow"]  # (the elbow needs 9.80665 * 0.64 = 6.3 N*m)
    table = gen_robot("size", arm_file(effort=500.0), "--payload", "1 kg@tool")
    assert table.returncode == 0 and "OK: every margin >= 1" in table.stdout


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--payload", "5 kg@toool"], "no link or frame 'toool' (did you mean 'tool'?)"),
        (["--payload", "5 parsecs@tool"], "--payload '5 parsecs@tool'"),
        (["--payload", "5 kg"], "expected MASS@FRAME"),
        (["--payload", "-1 kg@tool"], "must be > 0"),
        (["--load", "0,0@tool"], "three components"),
        (["--load", "0,0,-5 kg@tool"], "--load '0,0,-5 kg@tool'"),
        (["x:=1"], "only apply to xacro input"),
        (["--payload", "1e308 kg@tool"], "1e+308 kg is beyond what xacrokit takes (at most 1e+06 kg"),
        (["--load", "0,0,-1e300@tool"], "-1e+300 N is beyond what xacrokit takes (at most 1e+09 N"),
    ],
)
def test_bad_sizing_input_is_a_clear_error_with_exit_2(arm_file, args, words):
    result = gen_robot("size", arm_file(), *args)
    assert result.returncode == 2 and words in result.stderr, result.stderr
    assert "Traceback" not in result.stderr


def test_a_urdf_without_inertials_says_which_links(tmp_path):
    text = planar_arm()
    bare = re.sub(r"<inertial>.*?</inertial>", "", text)
    path = tmp_path / "bare.urdf"
    path.write_text(bare, encoding="utf-8")
    result = gen_robot("size", path)
    assert result.returncode == 2 and "upper, fore" in result.stderr and "<inertial>" in result.stderr


def test_flag_parsers():
    assert parse_payload("500 g@tool0") == Payload("tool0", 0.5)
    assert parse_load("0, 0, -50@tool0") == Load("tool0", (0.0, 0.0, -50.0))
    assert parse_load("1,2,3 kN@flange").force == (1000.0, 2000.0, 3000.0)
    with pytest.raises(XacrokitError):
        parse_payload("@tool0")


def test_a_base_axis_gravity_never_loads_is_zero_not_rounding():
    report = size(REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml", payloads=[Payload("tool0", 5.0)])
    pan = report.peaks[0]
    assert pan.joint == "shoulder_pan_joint" and pan.torque == 0.0 and report.margin(pan) is None


def test_the_docs_starter_arm_example_says_what_size_finds(tmp_path):
    """docs/size.md: the arm starter with 1 kg and 20 N pressing down fails joints 2 and 3 (margins 0.76, 0.99)."""
    assert gen_robot("new", "my_arm", "--kind", "arm", cwd=tmp_path).returncode == 0
    result = gen_robot(
        "size", "my_arm.yaml", "--payload", "1 kg@tool0", "--load", "0,0,-20@tool0", "--json", cwd=tmp_path
    )
    assert result.returncode == 1
    report = json.loads(result.stdout)
    assert report["failed"] == ["joint_2", "joint_3"]
    margins = [round(j["static"]["margin"], 2) for j in report["joints"][1:]]
    assert margins == [0.76, 0.99]
    docs = (REPO / "docs" / "size.md").read_text(encoding="utf-8")
    assert "margins 0.76 and 0.99" in docs


def test_force_is_a_deprecated_alias_of_load(arm_file):
    """size's loads were --force until 0.2: --force still applies a load, the same as --load (its torque J^T w: 50 N
    down at the tool of the stretched-out arm adds 50 (L1 + L2) N*m at the shoulder), and says it is deprecated."""
    path = arm_file()
    given = gen_robot("size", path, "--load", "0,0,-50@tool", "--json")
    old = gen_robot("size", path, "--force", "0,0,-50@tool", "--json")
    assert given.returncode == old.returncode == 0, old.stderr
    assert "deprecated" not in given.stderr
    warning = "gen-robot size: warning: --force is deprecated for a load: use --load"
    assert warning in old.stderr.splitlines(), old.stderr
    said = json.loads(old.stdout)
    assert said == json.loads(given.stdout)
    assert said["loads"] == [{"frame": "tool", "force": [0.0, 0.0, -50.0], "moment": [0.0, 0.0, 0.0]}]
    bare = json.loads(gen_robot("size", path, "--json").stdout)
    shoulder, bare_shoulder = said["joints"][0]["static"], bare["joints"][0]["static"]
    added = abs(shoulder["peak_torque"]) - abs(bare_shoulder["peak_torque"])
    assert added == pytest.approx(50.0 * (L1 + L2), rel=1e-9)


def test_a_safety_factor_divides_every_margin(arm_file, tmp_path):
    sizing = tmp_path / "safe.yaml"
    sizing.write_text("safety_factor: 1.5\n", encoding="utf-8")
    plain = size(arm_file(effort=30.0), payloads=[Payload("tool", 1.0)])
    safe = size(arm_file(effort=30.0), payloads=[Payload("tool", 1.0)], sizing=sizing)
    for peak_plain, peak_safe in zip(plain.peaks, safe.peaks, strict=True):
        assert safe.margin(peak_safe) == pytest.approx(plain.margin(peak_plain) / 1.5, rel=1e-12)
    assert plain.failed == [] and safe.failed == ["shoulder"]  # (9.80665 x 2.56 = 25.1 N*m; x 1.5 = 37.7 > 30)


def test_an_effort_limit_of_0_is_a_limit_whose_margin_is_0(tmp_path):
    """(a spec under strict: false keeps a file's effort of 0: the joint holds nothing, so it fails, rather than
    being read as "no limit" and passing)"""
    spec = tmp_path / "zero.yaml"
    spec.write_text(
        "robot: zero\nstrict: false\nlinks:\n  base_link: {shape: {box: {size: [0.4, 0.3, 0.1]}}, mass: 2}\n"
        "  arm: {shape: {box: {size: [0.4, 0.1, 0.1]}}, origin: {xyz: [0.2, 0, 0]}, mass: 1}\n"
        "joints:\n  j: {type: revolute, parent: base_link, child: arm, axis: [0, 1, 0],\n"
        "      limit: {lower: -1, upper: 1, effort: 0, velocity: 1}}\n",
        encoding="utf-8",
    )
    result = gen_robot("size", spec, "--json")
    assert result.returncode == 1, result.stderr
    (joint,) = json.loads(result.stdout)["joints"]
    assert joint["effort_limit"] == 0.0 and joint["static"]["margin"] == 0.0 and joint["static"]["pass"] is False


def test_a_result_that_is_not_a_number_fails_and_is_listed(arm_file, monkeypatch):
    """A torque that came out NaN or infinite is a failure (exit 1, in failed), never "OK: every margin >= 1"; and
    without an effort limit to compare it with, too."""
    import dataclasses

    import xacrokit.sizing as sizing

    real = sizing.static_peaks

    def broken(robot, *args, **kwargs):
        peaks = real(robot, *args, **kwargs)
        return [dataclasses.replace(peaks[0], torque=math.nan), *peaks[1:]]

    monkeypatch.setattr(sizing, "static_peaks", broken)
    report = sizing.size(arm_file(effort=100.0))
    assert report.failed == ["shoulder"] and report.exit_code == 1
    assert ("shoulder", "static torque not a finite number") in report.failures
    assert "FAILED: shoulder" in sizing.format_text(report)


def test_a_chain_longer_than_size_searches_is_refused_before_pinocchio_reads_it(tmp_path):
    """A chain of 5,000 moving joints crashed pinocchio (signal 11), 100 took 62 s: size takes at most
    MAX_MOVING_CHAIN in a chain and says so (issue 28); a tree of many short chains is not limited by it."""
    from xacrokit.shared.urdf_view import read_view
    from xacrokit.sizing.sized_robot import MAX_MOVING_CHAIN, moving_chain

    def chain(links: int, *, branches: int = 1) -> str:
        parts = ['<link name="root"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/></inertial></link>']
        for b in range(branches):
            for k in range(links):
                parent = "root" if k == 0 else f"b{b}l{k - 1}"
                parts.append(
                    f'<link name="b{b}l{k}"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01"/>'
                    f'</inertial></link><joint name="b{b}j{k}" type="revolute"><parent link="{parent}"/>'
                    f'<child link="b{b}l{k}"/><origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>'
                    '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint>'
                )
        return f'<robot name="c">{"".join(parts)}</robot>'

    assert moving_chain(read_view(chain(7, branches=20))) == 7
    long = tmp_path / "long.urdf"
    long.write_text(chain(5000), encoding="utf-8")
    assert moving_chain(read_view(long.read_text(encoding="utf-8"))) == 5000
    result = gen_robot("size", long)
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert "a chain of 5000 moving joints" in result.stderr and f"at most {MAX_MOVING_CHAIN}" in result.stderr


def test_gravity_is_the_sizing_files_or_the_command_lines(arm_file, tmp_path):
    """Issue 31: `gravity:` in a sizing file and `--gravity` (which overrides it): the stretched-out arm's peaks are the
    closed form at that gravity (m g r, here at the course's 9.81 and the Moon's 1.62), the header and the JSON say it,
    and a gravity outside 0 to 1000 m/s^2 is a located error."""
    path = arm_file()
    sizing = tmp_path / "g.yaml"
    sizing.write_text("gravity: 9.81 m/s2\n", encoding="utf-8")
    stretched = -closed_form(0.0, 0.0, 3.0)[0] / GRAVITY  # (m r of the shoulder's load: the torque per m/s^2)
    for report, g in (
        (size(path, payloads=[Payload("tool", 3.0)], sizing=sizing), 9.81),
        (size(path, payloads=[Payload("tool", 3.0)], sizing=sizing, gravity=1.62), 1.62),
        (size(path, payloads=[Payload("tool", 3.0)]), GRAVITY),
    ):
        assert abs(report.peaks[0].torque) == pytest.approx(stretched * g, rel=1e-9)
        assert report.to_dict()["gravity"] == g
    shown = gen_robot("size", path, "--payload", "3 kg@tool", "--sizing", sizing, "--gravity", "1.62")
    assert shown.returncode == 0 and shown.stdout.splitlines()[0].endswith("(g = 1.62 m/s^2)")
    sizing.write_text("gravity: -9.81\n", encoding="utf-8")
    with pytest.raises(SpecErrors) as raised:
        size(path, sizing=sizing)
    (error,) = raised.value.errors
    assert error.path == "$.gravity" and error.line == 1 and "from 0 to 1000 m/s^2" in error.message


def test_the_pose_column_names_the_joints_that_change_the_torque(arm_file):
    """Issue 31: the UR5's shoulder pan turns about the vertical and changes no gravity torque, nor does wrist 3's
    roll about its own axis: they are left out of every row's pose; a joint with no torque shows none. The JSON
    keeps every joint's value."""
    report = size(REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml", payloads=[Payload("tool0", 5.0)])
    rows = {line.split()[0]: line for line in format_text(report).splitlines()[3:9]}
    for peak in report.peaks:
        assert len(peak.pose) == 6 and report.to_dict()["joints"][0]["static"]["pose"]
        if peak.torque == 0:
            assert peak.moving_it == () and rows[peak.joint].endswith("-")
            continue
        assert "shoulder_pan_joint" not in peak.moving_it and "wrist_3_joint" not in peak.moving_it
        assert {"shoulder_lift_joint", peak.joint} <= set(peak.moving_it)
        shown = rows[peak.joint].split("  ")[-1]
        assert shown == ", ".join(f"{name}={peak.pose[name]:.3f}" for name in peak.moving_it)


MASSLESS = """<?xml version="1.0"?>
<robot name="lecture"><link name="base"/><link name="link_1"/><link name="link_2"/><link name="tool_link"/>
  <joint name="joint_1" type="revolute"><parent link="base"/><child link="link_1"/><axis xyz="0 1 0"/>
    <limit lower="-3.14" upper="3.14" effort="100" velocity="1"/></joint>
  <joint name="joint_2" type="revolute"><parent link="link_1"/><child link="link_2"/><origin xyz="0.6 0 0"/>
    <axis xyz="0 1 0"/><limit lower="-3.14" upper="3.14" effort="100" velocity="1"/></joint>
  <joint name="tool" type="fixed"><parent link="link_2"/><child link="tool_link"/><origin xyz="0.4 0 0"/></joint>
</robot>
"""


def test_a_massless_arm_is_sized_with_its_payload_or_force(tmp_path):
    """Issue 31: the lecture's tau = J^T F model (links without mass, 0.6 m and 0.4 m): a 2 kg payload at the tool
    gives m g (L1 + L2) and m g L2 stretched out; a downward force alike; with neither, an error in the spec's words
    naming only the links a joint moves (not the tool frame)."""
    path = tmp_path / "lecture.urdf"
    path.write_text(MASSLESS, encoding="utf-8")
    shoulder, elbow = size(path, payloads=[Payload("tool_link", 2.0)]).peaks
    assert abs(shoulder.torque) == pytest.approx(2.0 * GRAVITY * 1.0, rel=1e-9)
    assert abs(elbow.torque) == pytest.approx(2.0 * GRAVITY * 0.4, rel=1e-9)
    pressed = size(path, loads=[Load("tool_link", (0.0, 0.0, -50.0))]).peaks
    assert [abs(p.torque) for p in pressed] == pytest.approx([50.0 * 1.0, 50.0 * 0.4], rel=1e-9)
    with pytest.raises(XacrokitError) as raised:
        size(path)
    message = str(raised.value)
    assert "give those links a mass (link_1, link_2: `mass:` in a spec" in message and "tool_link" not in message
