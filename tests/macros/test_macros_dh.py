"""dh.xacro: the expanded URDF's forward kinematics equal an independent numpy DH product; bad tables are rejected."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st
from lxml import etree

import xacrokit
from conftest import assert_physical_tensor, budget, dh_product, floats, link_inertial, xacro_doc

QUARTER_TURNS = [k * math.pi / 2 for k in range(-4, 5)]
dh_angle = st.one_of(st.sampled_from(QUARTER_TURNS), st.floats(-2 * math.pi, 2 * math.pi))
dh_length = st.one_of(st.just(0.0), st.floats(-1.0, 1.0))


@st.composite
def dh_row(draw, index: int):
    kind = draw(st.sampled_from(["revolute", "revolute", "prismatic", "continuous", "fixed"]))
    row = {
        "name": f"joint_{index}",
        "link": f"link_{index}",
        "a": draw(dh_length),
        "d": draw(dh_length),
        "alpha": draw(dh_angle),
        "type": kind,
    }
    if draw(st.booleans()):
        row["theta"] = draw(dh_angle)
    if kind in ("revolute", "prismatic"):
        row["limit"] = {"lower": -3.0, "upper": 3.0, "effort": 10.0, "velocity": 1.0}
    if draw(st.booleans()):
        row["mass"] = draw(st.floats(0.01, 10.0))
    return row


@st.composite
def dh_case(draw):
    n = draw(st.integers(1, 7))
    rows = [draw(dh_row(i)) for i in range(n)]
    vec = st.tuples(dh_length, dh_length, dh_length)
    angles = st.tuples(dh_angle, dh_angle, dh_angle)
    return {
        "rows": rows,
        "convention": draw(st.sampled_from(["standard", "modified"])),
        "prefix": draw(st.sampled_from(["", "r1_", "left_arm_"])),
        "origin": (draw(vec), draw(angles)),
        "tool": (draw(vec), draw(angles)) if draw(st.booleans()) else ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)),
        "q": [draw(st.floats(-math.pi, math.pi)) for _ in rows],
    }


def arm_document(case, table_file="table.yaml") -> str:
    (oxyz, orpy), (txyz, trpy) = case["origin"], case["tool"]
    body = f"""
  <link name="world"/>
  <xacro:dh_arm prefix="{case["prefix"]}" parent="world" convention="{case["convention"]}"
                table="${{xacro.load_yaml('{table_file}')['joints']}}"
                tool_xyz="{" ".join(map(repr, txyz))}" tool_rpy="{" ".join(map(repr, trpy))}">
    <origin xyz="{" ".join(map(repr, oxyz))}" rpy="{" ".join(map(repr, orpy))}"/>
  </xacro:dh_arm>"""
    return xacro_doc(body, includes=("dh",))


def pinocchio_tool_pose(urdf: str, case) -> np.ndarray:
    model = pin.buildModelFromXML(urdf)
    data = model.createData()
    q = pin.neutral(model)
    for row, value in zip(case["rows"], case["q"], strict=False):
        if row["type"] == "fixed":
            continue
        jid = model.getJointId(case["prefix"] + row["name"])
        start = model.idx_qs[jid]
        if model.nqs[jid] == 2:  # continuous joints are (cos, sin) in pinocchio
            q[start], q[start + 1] = math.cos(value), math.sin(value)
        else:
            q[start] = value
    pin.framesForwardKinematics(model, data, q)
    return data.oMf[model.getFrameId(case["prefix"] + "tool0")].homogeneous


# budget: an example expands an arm of up to 7 rows and builds its pinocchio model (about half a second); 15 of them
# draw each row type, both conventions and the three prefixes several times (dev and thorough raise it)
@settings(max_examples=budget(15))
@given(case=dh_case())
def test_dh_arm_forward_kinematics_equal_the_dh_product(tmp_path_factory, case):
    folder = tmp_path_factory.mktemp("dh")
    (folder / "table.yaml").write_text(yaml.safe_dump({"joints": case["rows"]}), encoding="utf-8")
    (folder / "arm.urdf.xacro").write_text(arm_document(case), encoding="utf-8")
    urdf = xacrokit.expand(folder / "arm.urdf.xacro", trust=True)  # (the test's own document: expanded in-process)

    got = pinocchio_tool_pose(urdf, case)
    q = [0.0 if r["type"] == "fixed" else v for r, v in zip(case["rows"], case["q"], strict=False)]
    want = dh_product(case["rows"], q, case["convention"], case["origin"], case["tool"])
    np.testing.assert_allclose(got[:3, 3], want[:3, 3], rtol=0, atol=1e-9)
    np.testing.assert_allclose(got[:3, :3], want[:3, :3], rtol=0, atol=1e-9)

    root = etree.fromstring(urdf.encode())
    names = {e.get("name") for e in root.iter("link", "joint")} - {"world"}
    assert names and all(n.startswith(case["prefix"]) for n in names)
    for row in case["rows"]:
        if "mass" in row:
            mass, tensor, _, _ = link_inertial(root, case["prefix"] + row["link"])
            assert mass == row["mass"]
            assert_physical_tensor(tensor)


ONE_ROW = {
    "name": "j1",
    "link": "l1",
    "a": 0.1,
    "d": 0.2,
    "alpha": 0.0,
    "limit": {"lower": -1.0, "upper": 1.0, "effort": 1.0, "velocity": 1.0},
}


def test_dh_arm_names_frames_as_documented(expand, tmp_path_factory):
    folder = tmp_path_factory.mktemp("names")
    rows = [dict(ONE_ROW)]
    (folder / "t.yaml").write_text(yaml.safe_dump({"joints": rows}), encoding="utf-8")
    doc = xacro_doc(
        f"""<link name="world"/>
        <xacro:dh_arm prefix="p_" parent="world" table="${{xacro.load_yaml('{folder / "t.yaml"}')['joints']}}">
          <origin xyz="0 0 0" rpy="0 0 0"/></xacro:dh_arm>""",
        includes=("dh",),
    )
    root = expand(doc)
    # (the default base is arm_base: 'base' would make base_joint, a mobile base's footprint joint name)
    assert sorted(e.get("name") for e in root.iter("link")) == ["p_arm_base", "p_l1", "p_tool0", "world"]
    joints = {e.get("name"): e for e in root.iter("joint")}
    assert sorted(joints) == ["p_arm_base_joint", "p_j1", "p_tool0_joint"]
    assert joints["p_j1"].get("type") == "revolute"
    assert floats(joints["p_j1"].find("axis").get("xyz")) == [0.0, 0.0, 1.0]
    limit = joints["p_j1"].find("limit")
    assert [float(limit.get(k)) for k in ("lower", "upper", "effort", "velocity")] == [-1.0, 1.0, 1.0, 1.0]
    # standard DH: the tool frame sits at DH frame 1 = link 1 moved by a along x
    assert floats(joints["p_tool0_joint"].find("origin").get("xyz")) == pytest.approx([0.1, 0.0, 0.0], abs=1e-15)


def test_dh_arm_without_a_base_hangs_its_first_joint_on_parent_and_names_the_tool_joint(expand, tmp_path_factory):
    # Universal Robots' shape: shoulder_pan_joint on base_link_inertia, flange on wrist_3-flange
    folder = tmp_path_factory.mktemp("no_base")
    (folder / "t.yaml").write_text(yaml.safe_dump({"joints": [dict(ONE_ROW)]}), encoding="utf-8")
    doc = xacro_doc(
        f"""<link name="p_base_link_inertia"/>
        <xacro:dh_arm prefix="p_" parent="p_base_link_inertia" base="" tool="flange" tool_joint="l1-flange"
                      table="${{xacro.load_yaml('{folder / "t.yaml"}')['joints']}}"><origin/></xacro:dh_arm>""",
        includes=("dh",),
    )
    root = expand(doc)
    assert sorted(e.get("name") for e in root.iter("link")) == ["p_base_link_inertia", "p_flange", "p_l1"]
    joints = {e.get("name"): (e.find("parent").get("link"), e.find("child").get("link")) for e in root.iter("joint")}
    assert joints == {"p_j1": ("p_base_link_inertia", "p_l1"), "p_l1-flange": ("p_l1", "p_flange")}
    first = root.find("joint[@name='p_j1']/origin")
    assert floats(first.get("xyz")) == [0.0, 0.0, 0.2] and floats(first.get("rpy")) == [0.0, 0.0, 0.0]


BAD_ROWS = [
    ({"alpha": None}, "table[0].alpha must be a finite number"),
    ({"alpha": "pi/2"}, "table[0].alpha must be a finite number (rad), got 'pi/2'"),
    ({"a": -1e400}, "table[0].a must be a finite number"),
    ({"type": "spherical"}, "table[0].type must be one of revolute, prismatic, continuous, fixed"),
    ({"limit": None}, "table[0] (j1) is revolute and needs a limit with lower, upper, effort and velocity"),
    ({"limit": {"lower": 1.0, "upper": -1.0, "effort": 1.0, "velocity": 1.0}}, "lower (1.0) must be at most upper"),
    ({"limit": {"lower": -1.0, "upper": 1.0, "effort": 0.0, "velocity": 1.0}}, "table[0].limit.effort must be > 0"),
    ({"name": None}, "table[0] needs text keys name"),
    ({"mass": -1.0}, "table[0].mass must be > 0"),
    ({"mas": 1.0, "offset": 0.5}, "table[0] has unknown key(s) mas, offset; a row takes name, link, a, d"),
    ({"dynamics": {"damping": -5.0}}, "table[0].dynamics.damping must be >= 0"),
    ({"dynamics": {"friction": "abc"}}, "table[0].dynamics.friction must be a finite number"),
    ({"dynamics": {"damp": 0.1}}, "table[0].dynamics must be a mapping with damping and/or friction"),
    (
        {"limit": {"lower": -1.0, "upper": 1.0, "effort": 1.0, "velocity": 1.0, "lowr": 3.0}},
        "table[0].limit has unknown key(s) lowr; a limit takes lower, upper, effort, velocity",
    ),
]


@pytest.mark.parametrize(("change", "words"), BAD_ROWS)
def test_dh_arm_rejects_bad_rows_naming_the_row_and_key(tmp_path_factory, change, words):
    folder = tmp_path_factory.mktemp("bad")
    row = dict(ONE_ROW)
    row.update(change)
    row = {k: v for k, v in row.items() if v is not None}
    (folder / "t.yaml").write_text(yaml.safe_dump({"joints": [row]}), encoding="utf-8")
    doc = xacro_doc(
        """<link name="world"/>
        <xacro:dh_arm prefix="" parent="world" table="${xacro.load_yaml('t.yaml')['joints']}">
          <origin xyz="0 0 0" rpy="0 0 0"/></xacro:dh_arm>""",
        includes=("dh",),
    )
    (folder / "arm.urdf.xacro").write_text(doc, encoding="utf-8")
    with pytest.raises(xacrokit.ExpandError) as caught:
        xacrokit.expand(folder / "arm.urdf.xacro")
    assert "dh_arm:" in str(caught.value) and words in str(caught.value)


@pytest.mark.parametrize(
    ("attrs", "words"),
    [
        ('table="${[]}"', "table must be a non-empty list"),
        ('table="${[1]}" convention="craig"', "convention must be one of standard, modified"),
        ('table="${[1]}"', "table[0] must be a mapping"),
        ('table="${[1]}" tool_xyz="1 2"', "tool_xyz and tool_rpy must each be three numbers"),
    ],
)
def test_dh_arm_rejects_bad_parameters(expand, attrs, words):
    doc = xacro_doc(
        f'<link name="w"/><xacro:dh_arm prefix="" parent="w" {attrs}><origin xyz="0 0 0"/></xacro:dh_arm>',
        includes=("dh",),
    )
    with pytest.raises(xacrokit.ExpandError, match="dh_arm") as caught:
        expand(doc)
    assert words in str(caught.value)
