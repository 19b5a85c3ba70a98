"""wheel.xacro, links.xacro and materials.xacro."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import xacrokit
from conftest import assert_physical_tensor, floats, link_inertial, rpy_matrix, xacro_doc

AXES = {"x": [1.0, 0.0, 0.0], "y": [0.0, 1.0, 0.0], "z": [0.0, 0.0, 1.0]}
size = st.floats(min_value=1e-3, max_value=5.0)


def wheel_doc(axis: str, radius: float, width: float, mass: float, extra: str = "") -> str:
    return xacro_doc(
        f"""<link name="base_link"/>
        <xacro:wheel prefix="left_" parent="base_link" radius="{radius!r}" width="{width!r}" mass="{mass!r}"
                     axis="{axis}" {extra}><origin xyz="0 0.2 0" rpy="0 0 0"/></xacro:wheel>""",
        includes=("wheel",),
    )


@given(axis=st.sampled_from(sorted(AXES)), radius=size, width=size, mass=size)
def test_wheel_inertia_about_the_axle_is_half_m_r_squared(expand, axis, radius, width, mass):
    root = expand(wheel_doc(axis, radius, width, mass))
    got_mass, tensor, _, rot = link_inertial(root, "left_wheel")
    axle = np.array(AXES[axis])
    tensor_link = rot @ tensor @ rot.T
    assert got_mass == mass
    assert axle @ tensor_link @ axle == pytest.approx(mass * radius**2 / 2, rel=1e-12)
    transverse = np.cross(axle, [1.0, 1.0, 1.0])
    transverse /= np.linalg.norm(transverse)
    assert transverse @ tensor_link @ transverse == pytest.approx(mass * (3 * radius**2 + width**2) / 12, rel=1e-12)
    assert_physical_tensor(tensor_link)

    joint = root.find("joint[@name='left_wheel_joint']")
    assert joint.get("type") == "continuous"
    assert floats(joint.find("axis").get("xyz")) == AXES[axis]
    # the drawn cylinder (along its own z) lies along the axle, for visual and collision alike
    for element in ("visual", "collision"):
        origin = root.find(f"link[@name='left_wheel']/{element}/origin")
        cylinder_axis = rpy_matrix(*floats(origin.get("rpy"))) @ [0.0, 0.0, 1.0]
        assert abs(abs(cylinder_axis @ axle) - 1.0) < 1e-12
        geometry = root.find(f"link[@name='left_wheel']/{element}/geometry/cylinder")
        assert (float(geometry.get("radius")), float(geometry.get("length"))) == (radius, width)


def test_wheel_joint_limits_dynamics_and_gazebo_friction(expand):
    root = expand(
        wheel_doc("y", 0.1, 0.04, 0.5, 'effort="5" velocity="12" damping="0.2" friction="0.1" mu1="0.9" mu2="0.7"')
    )
    joint = root.find("joint[@name='left_wheel_joint']")
    assert joint.find("parent").get("link") == "base_link" and joint.find("child").get("link") == "left_wheel"
    assert floats(joint.find("origin").get("xyz")) == [0.0, 0.2, 0.0]
    limit, dynamics = joint.find("limit"), joint.find("dynamics")
    assert (float(limit.get("effort")), float(limit.get("velocity"))) == (5.0, 12.0)
    assert (float(dynamics.get("damping")), float(dynamics.get("friction"))) == (0.2, 0.1)
    gazebo = root.findall("gazebo")
    assert [g.get("reference") for g in gazebo] == ["left_wheel"]
    assert (float(gazebo[0].findtext("mu1")), float(gazebo[0].findtext("mu2"))) == (0.9, 0.7)


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        ('material="" effort="0"', "wheel: parameter effort must be > 0"),
        ('velocity="-1"', "wheel: parameter velocity must be > 0"),
        ('damping="-0.1"', "wheel: parameter damping must be >= 0"),
        ('mu1="-1"', "wheel: parameter mu1 must be >= 0"),
    ],
)
def test_wheel_rejects_bad_parameters(expand, extra, words):
    with pytest.raises(xacrokit.ExpandError, match=words):
        expand(wheel_doc("y", 0.1, 0.04, 0.5, extra))


@pytest.mark.parametrize(
    ("axis", "radius", "width", "mass", "words"),
    [
        ("w", 0.1, 0.04, 0.5, "wheel: parameter axis must be one of x, y, z"),
        ("y", -0.1, 0.04, 0.5, "wheel: parameter radius must be > 0"),
        ("y", 0.1, 0.0, 0.5, "wheel: parameter width must be > 0"),
        ("y", 0.1, 0.04, -0.5, "wheel: parameter mass must be > 0"),
    ],
)
def test_wheel_rejects_bad_shape(expand, axis, radius, width, mass, words):
    with pytest.raises(xacrokit.ExpandError, match=words):
        expand(wheel_doc(axis, radius, width, mass))


@pytest.mark.parametrize(
    ("call", "geometry", "expected"),
    [
        (
            '<xacro:box_link name="b" mass="2" x="0.1" y="0.2" z="0.3" xyz="0 0 0.15" rpy="0 0 0.5"/>',
            "box",
            np.diag([2 * (0.04 + 0.09) / 12, 2 * (0.01 + 0.09) / 12, 2 * (0.01 + 0.04) / 12]),
        ),
        (
            '<xacro:cylinder_link name="b" mass="2" radius="0.1" length="0.4" xyz="0 0 0.2" rpy="0 1.5 0"/>',
            "cylinder",
            np.diag([2 * (0.03 + 0.16) / 12, 2 * (0.03 + 0.16) / 12, 2 * 0.01 / 2]),
        ),
        ('<xacro:sphere_link name="b" mass="2" radius="0.1" xyz="0 0 0.15"/>', "sphere", np.eye(3) * 2 * 2 * 0.01 / 5),
    ],
)
def test_shape_links_put_visual_collision_and_inertial_at_one_origin(expand, call, geometry, expected):
    root = expand(
        xacro_doc(
            call.replace('name="b"', 'prefix="r1_" name="b" material="xacrokit_red"'), includes=("materials", "links")
        )
    )
    link = root.find("link[@name='r1_b']")
    assert link is not None
    origins = {e: link.find(f"{e}/origin").attrib for e in ("visual", "collision", "inertial")}
    assert origins["visual"] == origins["collision"] == origins["inertial"]
    assert (
        link.find(f"visual/geometry/{geometry}") is not None and link.find(f"collision/geometry/{geometry}") is not None
    )
    assert link.find("visual/material").get("name") == "xacrokit_red"
    mass, tensor, _, _ = link_inertial(root, "r1_b")
    assert mass == 2.0
    np.testing.assert_allclose(tensor, expected, rtol=1e-12)


def test_links_without_material_have_none(expand):
    root = expand(xacro_doc('<xacro:sphere_link name="s" mass="1" radius="0.1"/>', includes=("links",)))
    assert root.find("link[@name='s']/visual/material") is None


def test_materials_are_defined_once_however_often_included(expand):
    doc = xacro_doc(
        '<xacro:include filename="$(find xacrokit)/macros/materials.xacro"/>'
        '<xacro:macro name="robot" params="prefix">'
        '<xacro:include filename="$(find xacrokit)/macros/materials.xacro"/><link name="${prefix}a"/></xacro:macro>'
        '<xacro:robot prefix="r1_"/><xacro:robot prefix="r2_"/>',
        includes=("materials", "links", "wheel"),
    )
    root = expand(doc)
    names = [m.get("name") for m in root.findall("material")]
    assert len(names) == len(set(names)) == 13


def test_materials_palette_matches_its_banner(expand):
    root = expand(xacro_doc("", includes=("materials",)))
    defined = {m.get("name"): floats(m.find("color").get("rgba")) for m in root.findall("material")}
    banner = (xacrokit.macros_dir() / "materials.xacro").read_text(encoding="utf-8")
    documented = {}
    for line in banner.splitlines():
        if line.strip().startswith("palette:"):
            words = line.split()[1:]
            documented[words[0]] = [float(v) for v in words[1:]]
    assert documented == defined
    assert all(0.0 <= v <= 1.0 for rgba in defined.values() for v in rgba)


def test_pi_is_not_a_literal_in_the_macros():
    for path in xacrokit.macros_dir().rglob("*.xacro"):
        text = path.read_text(encoding="utf-8")
        assert "3.14159" not in text and "1.5707" not in text, path


def test_wheel_name_parameter_names_link_joint_and_gazebo_reference(expand):
    root = expand(wheel_doc("y", 0.1, 0.04, 0.5, 'name="caster_front"'))
    assert root.find("link[@name='left_caster_front']") is not None
    assert root.find("joint[@name='left_caster_front_joint']/child").get("link") == "left_caster_front"
    assert [g.get("reference") for g in root.iter("gazebo")] == ["left_caster_front"]
