"""The one view of a URDF (xacrokit.shared.urdf_view) and its hardened parse (xacrokit.shared.xml_parse): every part
read as the file gives it, with its line; the same robot as an independent reader (yourdfpy) sees; no entity, DTD or
network ever followed."""

from __future__ import annotations

import math

import pytest
import yourdfpy

import xacrokit
from conftest import ROBOT_EXAMPLES
from xacrokit.errors import XacrokitError
from xacrokit.shared.urdf_view import number, numbers, read_view
from xacrokit.shared.xml_parse import parse_urdf

URDF = """<?xml version="1.0"?>
<robot name="demo">
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <link name="base_link">
    <inertial>
      <origin xyz="0 0 0.05" rpy="0 0 0"/>
      <mass value="2.5"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.3"/>
    </inertial>
    <visual name="body">
      <origin xyz="0 0 0.05"/>
      <geometry><!-- <box size="9 9 9"/> --><box size="0.4 0.3 0.1"/></geometry>
      <material name="blue"/>
    </visual>
    <collision><geometry><cylinder radius="0.2" length="0.1"/></geometry></collision>
  </link>
  <joint name="wheel_joint" type="continuous">
    <parent link="base_link"/><child link="wheel"/>
    <origin xyz="0 0.2 0" rpy="-1.5708 0 0"/>
    <axis xyz="0 0 1"/>
    <limit effort="5" velocity="10"/>
    <dynamics damping="0.01" friction="0.1"/>
  </joint>
  <link name="wheel">
    <visual><geometry><mesh filename="package://demo/meshes/wheel.stl" scale="1 1 -1"/></geometry>
      <material name="rubber"><color rgba="0.1 0.1 0.1 1"/></material></visual>
  </link>
  <joint name="follower" type="revolute">
    <parent link="wheel"/><child link="tip"/>
    <limit lower="-1" upper="not-a-number" effort="1" velocity="1"/>
    <mimic joint="wheel_joint" multiplier="-2"/>
  </joint>
  <link name="tip"/>
  <gazebo reference="wheel"><mu1>1.0</mu1></gazebo>
  <ros2_control name="Demo" type="system"><joint name="wheel_joint"/><joint name="follower"/></ros2_control>
</robot>
"""


def test_every_part_is_read_as_written_with_its_line():
    view = read_view(URDF)
    assert view.name == "demo"
    assert [link.name for link in view.links] == ["base_link", "wheel", "tip"]
    assert [joint.name for joint in view.joints] == ["wheel_joint", "follower"]
    base = view.link("base_link")
    assert base is not None and base.line == 4
    assert base.inertial is not None and base.inertial.mass == "2.5" and base.inertial.inertia["iyy"] == "0.2"
    assert base.inertial.origin is not None and base.inertial.origin.xyz == "0 0 0.05"
    (visual,) = base.visuals
    assert visual.name == "body" and visual.line == 10
    assert visual.shape is not None and visual.shape.kind == "box" and visual.shape.get("size") == "0.4 0.3 0.1"
    assert visual.material is not None and visual.material.name == "blue" and visual.material.rgba is None
    assert not visual.material.defines and view.materials[0].color_given
    assert base.collisions[0].shape is not None and base.collisions[0].shape.attributes == {
        "radius": "0.2",
        "length": "0.1",
    }
    wheel = view.joint("wheel_joint")
    assert wheel is not None and (wheel.type, wheel.parent, wheel.child, wheel.axis) == (
        "continuous",
        "base_link",
        "wheel",
        "0 0 1",
    )
    assert wheel.limit == {"effort": "5", "velocity": "10"} and wheel.dynamics == {"damping": "0.01", "friction": "0.1"}
    follower = view.joint("follower")
    assert follower is not None and follower.mimic is not None
    assert (follower.mimic.joint, follower.mimic.multiplier, follower.mimic.offset) == ("wheel_joint", "-2", None)
    assert follower.limit is not None and follower.limit["upper"] == "not-a-number"  # (kept: each reader decides)
    assert follower.axis is None and follower.origin is None
    assert view.colours() == {"blue": "0 0 1 1", "rubber": "0.1 0.1 0.1 1"}
    wheel_visual = view.links[1].visuals[0].material
    assert wheel_visual is not None and wheel_visual.color_given and wheel_visual.defines
    assert [(g.reference, g.line) for g in view.gazebo] == [("wheel", 34)]
    assert [(c.reference, c.joints) for c in view.ros2_control] == [("Demo", ("wheel_joint", "follower"))]


def test_lenient_numbers_fall_back_to_the_default():
    assert number("1.5", 0.0) == 1.5 and number(None, 2.0) == 2.0
    assert number("nan", 3.0) == 3.0 and number("inf", 3.0) == 3.0 and number("x", 4.0) == 4.0
    assert numbers("1 2 3", [0.0] * 3) == [1.0, 2.0, 3.0]
    assert numbers("1 2", [0.0] * 3) == [0.0] * 3 and numbers("1 a 3", [9.0] * 3) == [9.0] * 3


@pytest.mark.parametrize("spec", ROBOT_EXAMPLES, ids=lambda p: p.stem)
def test_an_independent_reader_sees_the_same_robot(spec, tmp_path):
    """yourdfpy's own parse of each example's URDF: the same links, joints (type, parent, child, axis), masses."""
    result = xacrokit.generate(spec, tmp_path / "pkg")
    urdf = tmp_path / "pkg" / "urdf" / f"{result.name}.urdf"
    view = read_view(urdf.read_text(encoding="utf-8"), str(urdf))
    other = yourdfpy.URDF.load(str(urdf), load_meshes=False, build_scene_graph=False)
    assert [link.name for link in view.links] == [link.name for link in other.robot.links]
    for joint, theirs in zip(view.joints, other.robot.joints, strict=True):
        assert (joint.name, joint.type, joint.parent, joint.child) == (
            theirs.name,
            theirs.type,
            theirs.parent,
            theirs.child,
        )
        if theirs.axis is not None and joint.type != "fixed":
            assert numbers(joint.axis or "1 0 0", [0.0] * 3) == pytest.approx(list(theirs.axis), abs=0)
    for link, theirs in zip(view.links, other.robot.links, strict=True):
        if theirs.inertial is None:
            assert link.inertial is None
        else:
            assert link.inertial is not None and float(link.inertial.mass or "nan") == theirs.inertial.mass
        assert len(link.visuals) == len(theirs.visuals) and len(link.collisions) == len(theirs.collisions)


def test_an_external_entity_is_never_read(tmp_path):
    secret = tmp_path / "secret.txt"
    secret.write_text("TOP-SECRET", encoding="utf-8")
    doctype = f'<!DOCTYPE r [<!ENTITY e SYSTEM "file://{secret}">]>'
    text = f'<?xml version="1.0"?>{doctype}<robot name="r"><link name="&e;"/></robot>'
    parsed = parse_urdf(text)
    names = [] if parsed.root is None else [link.get("name") for link in parsed.root.iter("link")]
    assert "TOP-SECRET" not in str(names)
    if parsed.root is not None:
        view = read_view(text)
        assert all("TOP-SECRET" not in link.name for link in view.links)


def test_an_undeclared_prefix_is_read_past_and_named_with_its_line():
    parsed = parse_urdf('<robot name="r">\n<link name="a"/>\n<joint name="j" drake:x="1" type="fixed"/>\n</robot>')
    assert parsed.root is not None and parsed.undeclared == {"drake": 3}


@pytest.mark.parametrize(
    ("text", "said"),
    [
        (
            "<robot name='r'><link name='a'></robot>",
            "not-a-urdf.xml:1:40: not well-formed XML: Opening and ending tag mismatch",
        ),
        ("<sdf><model/></sdf>", "not-a-urdf.xml:1: the root element is <sdf>, not <robot>"),
    ],
)
def test_what_is_not_a_urdf_is_a_located_error(text, said):
    with pytest.raises(XacrokitError, match=said):
        read_view(text, "not-a-urdf.xml")


def test_a_view_cannot_be_changed():
    view = read_view(URDF)
    with pytest.raises(AttributeError):
        view.links[0].name = "other"  # type: ignore[misc]
    assert math.isfinite(number(view.links[0].inertial.mass, math.nan))  # type: ignore[union-attr]
