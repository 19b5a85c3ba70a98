"""inertia.xacro: closed-form tensors, physical validity, pinocchio agreement, and argument checks."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from lxml import etree

import xacrokit
from conftest import assert_physical_tensor, budget, link_inertial, rpy_matrix, xacro_doc
from xacrokit.shared.solid_inertia import capsule_moments, tensor_problem

positive = st.floats(min_value=1e-3, max_value=1e3, allow_nan=False, allow_infinity=False)
length = st.floats(min_value=1e-3, max_value=10.0, allow_nan=False, allow_infinity=False)
coord = st.floats(min_value=-2.0, max_value=2.0, allow_nan=False, allow_infinity=False)
angle = st.floats(min_value=-math.pi, max_value=math.pi, allow_nan=False, allow_infinity=False)
axis_name = st.sampled_from(["x", "y", "z"])


def _axis_diag(axial: float, transverse: float, axis: str) -> np.ndarray:
    return np.diag([axial if a == axis else transverse for a in "xyz"])


def _closed_form(kind: str, p: dict) -> np.ndarray:
    """The textbook tensors, written out independently of the macros."""
    m = p["mass"]
    if kind == "box":
        x, y, z = p["x"], p["y"], p["z"]
        return np.diag([m * (y**2 + z**2) / 12, m * (x**2 + z**2) / 12, m * (x**2 + y**2) / 12])
    if kind == "cylinder":
        r, h = p["radius"], p["length"]
        return _axis_diag(m * r**2 / 2, m * (3 * r**2 + h**2) / 12, p["axis"])
    if kind == "hollow_cylinder":
        ri, ro, h = p["inner_radius"], p["outer_radius"], p["length"]
        return _axis_diag(m * (ri**2 + ro**2) / 2, m * (3 * (ri**2 + ro**2) + h**2) / 12, p["axis"])
    if kind == "capsule":  # pinocchio's closed form (a cylinder and two hemispheres), lying along z
        r, h = p["radius"], p["length"]
        moments = np.diag(pin.Inertia.FromCapsule(m, r, h).inertia)
        return _axis_diag(moments[2], moments[0], p["axis"])
    assert kind == "sphere"
    return np.eye(3) * (2 * m * p["radius"] ** 2 / 5)


@st.composite
def inertia_call(draw):
    kind = draw(st.sampled_from(["box", "cylinder", "hollow_cylinder", "capsule", "sphere"]))
    p: dict = {"mass": draw(positive)}
    if kind == "box":
        p.update(x=draw(length), y=draw(length), z=draw(length))
    elif kind in ("cylinder", "capsule"):
        p.update(radius=draw(length), length=draw(length), axis=draw(axis_name))
    elif kind == "hollow_cylinder":
        outer = draw(length)
        p.update(
            inner_radius=outer * draw(st.floats(0.0, 0.999)),
            outer_radius=outer,
            length=draw(length),
            axis=draw(axis_name),
        )
    else:
        p.update(radius=draw(length))
    xyz = [draw(coord) for _ in range(3)]
    rpy = [draw(angle) for _ in range(3)]
    return kind, p, xyz, rpy


def _call(kind: str, p: dict, xyz, rpy) -> str:
    attrs = " ".join(f'{k}="{v!r}"' if isinstance(v, float) else f'{k}="{v}"' for k, v in p.items())
    return f'<xacro:{kind}_inertial {attrs} xyz="{" ".join(map(repr, xyz))}" rpy="{" ".join(map(repr, rpy))}"/>'


@given(call=inertia_call())
def test_inertia_macros_match_closed_form_and_pinocchio(tmp_path_factory, call):
    kind, p, xyz, rpy = call
    body = f'<link name="body">{_call(kind, p, xyz, rpy)}</link>'
    folder = tmp_path_factory.mktemp("inertia")
    path = folder / "doc.urdf.xacro"
    path.write_text(xacro_doc(body), encoding="utf-8")
    urdf = xacrokit.expand(path)
    root = etree.fromstring(urdf.encode())

    mass, tensor, com, rot = link_inertial(root, "body")
    expected = _closed_form(kind, p)
    assert mass == pytest.approx(p["mass"], rel=1e-12)
    np.testing.assert_allclose(tensor, expected, rtol=1e-12, atol=0)
    np.testing.assert_allclose(com, xyz, rtol=1e-15, atol=0)
    assert_physical_tensor(tensor)

    # pinocchio (root link on a free-flyer so that its inertia is a body's) must see the same tensor about the COM,
    # turned into the link frame by the inertial origin's rotation.
    model = pin.buildModelFromXML(urdf, pin.JointModelFreeFlyer())
    inertia = model.inertias[model.getJointId("root_joint")]
    assert inertia.mass == pytest.approx(p["mass"], rel=1e-12)
    np.testing.assert_allclose(inertia.lever, xyz, rtol=1e-12, atol=1e-15)
    expected_link = rot @ expected @ rot.T
    np.testing.assert_allclose(inertia.inertia, expected_link, rtol=1e-9, atol=1e-12 * np.abs(expected).max())


@st.composite
def physical_tensor(draw):
    """A random valid tensor: principal moments obeying the triangle inequality, turned by a random rotation."""
    a, b = draw(positive), draw(positive)
    lo, hi = abs(a - b), a + b
    c = lo + (hi - lo) * draw(st.floats(0.01, 0.99))
    rot = rpy_matrix(draw(angle), draw(angle), draw(angle))
    tensor = rot @ np.diag([a, b, c]) @ rot.T
    return (tensor + tensor.T) / 2  # exactly symmetric, as a URDF tensor is


@given(tensor=physical_tensor(), mass=positive)
def test_explicit_inertial_accepts_physical_tensors_exactly(expand, tensor, mass):
    t = tensor.tolist()
    t = [[float(v) for v in row] for row in t]
    call = (
        f'<xacro:inertial mass="{mass!r}" ixx="{t[0][0]!r}" ixy="{t[0][1]!r}" ixz="{t[0][2]!r}" '
        f'iyy="{t[1][1]!r}" iyz="{t[1][2]!r}" izz="{t[2][2]!r}"/>'
    )
    root = expand(xacro_doc(f'<link name="body">{call}</link>'))
    got_mass, got, _, _ = link_inertial(root, "body")
    assert got_mass == mass
    np.testing.assert_array_equal(got, tensor)  # passed through unchanged, to the last digit


@given(moments=st.tuples(positive, positive), excess=st.floats(0.05, 10.0), angles=st.tuples(angle, angle, angle))
def test_explicit_inertial_rejects_triangle_violations(tmp_path_factory, moments, excess, angles):
    a, b = moments
    c = (a + b) * (1 + excess)  # one principal moment larger than the sum of the others
    rot = rpy_matrix(*angles)
    t = (rot @ np.diag([a, b, c]) @ rot.T).tolist()
    call = (
        f'<xacro:inertial mass="1.0" ixx="{t[0][0]!r}" ixy="{t[0][1]!r}" ixz="{t[0][2]!r}" '
        f'iyy="{t[1][1]!r}" iyz="{t[1][2]!r}" izz="{t[2][2]!r}"/>'
    )
    path = tmp_path_factory.mktemp("bad") / "doc.urdf.xacro"
    path.write_text(xacro_doc(f'<link name="body">{call}</link>'), encoding="utf-8")
    with pytest.raises(xacrokit.ExpandError, match="inertial: parameters ixx..izz violate the triangle inequality"):
        xacrokit.expand(path)


GOOD = {
    "box_inertial": {"mass": "1", "x": "0.1", "y": "0.2", "z": "0.3"},
    "cylinder_inertial": {"mass": "1", "radius": "0.1", "length": "0.3"},
    "hollow_cylinder_inertial": {"mass": "1", "inner_radius": "0.05", "outer_radius": "0.1", "length": "0.3"},
    "sphere_inertial": {"mass": "1", "radius": "0.1"},
    "capsule_inertial": {"mass": "1", "radius": "0.05", "length": "0.2"},
    "inertial": {"mass": "1", "ixx": "0.1", "ixy": "0", "ixz": "0", "iyy": "0.1", "iyz": "0", "izz": "0.1"},
}

BAD = [
    # (macro, param, bad value, words the message must contain)
    ("box_inertial", "mass", "0", "must be > 0"),
    ("box_inertial", "mass", "-2", "must be > 0"),
    ("box_inertial", "x", "-0.1", "must be > 0"),
    ("box_inertial", "y", "abc", "must be a finite number"),
    ("box_inertial", "z", "${float('nan')}", "must be a finite number"),
    ("cylinder_inertial", "radius", "-1", "must be > 0"),
    ("cylinder_inertial", "length", "0", "must be > 0"),
    ("cylinder_inertial", "axis", "w", "must be one of x, y, z"),
    ("cylinder_inertial", "mass", "-1", "must be > 0"),
    ("hollow_cylinder_inertial", "inner_radius", "0.2", "must be < outer_radius"),
    ("hollow_cylinder_inertial", "inner_radius", "-0.01", "must be >= 0"),
    ("hollow_cylinder_inertial", "outer_radius", "-0.1", "must be > 0"),
    ("hollow_cylinder_inertial", "axis", "q", "must be one of x, y, z"),
    ("sphere_inertial", "radius", "0", "must be > 0"),
    ("capsule_inertial", "radius", "-0.1", "must be > 0"),
    ("capsule_inertial", "length", "0", "must be > 0"),
    ("capsule_inertial", "axis", "v", "must be one of x, y, z"),
    ("sphere_inertial", "mass", "-0.5", "must be > 0"),
    ("inertial", "mass", "0", "must be > 0"),
    ("inertial", "ixx", "-0.1", "must be > 0"),
    ("inertial", "ixy", "0.5", "positive definite"),
    ("inertial", "izz", "0.3", "triangle inequality"),
]


@pytest.mark.parametrize(("macro", "param", "value", "words"), BAD)
def test_invalid_arguments_stop_expansion_naming_macro_and_parameter(expand, macro, param, value, words):
    attrs = dict(GOOD[macro], **{param: value})
    call = f"<xacro:{macro} " + " ".join(f'{k}="{v}"' for k, v in attrs.items()) + "/>"
    with pytest.raises(xacrokit.ExpandError) as caught:
        expand(xacro_doc(f'<link name="body">{call}</link>'))
    message = str(caught.value)
    assert message.count(macro + ":") >= 1 and param in message and words in message
    assert "when evaluating expression" not in message  # the macro's own words, not xacro's internals


@pytest.mark.parametrize("macro", sorted(GOOD))
def test_good_arguments_expand(expand, macro):
    call = f"<xacro:{macro} " + " ".join(f'{k}="{v}"' for k, v in GOOD[macro].items()) + "/>"
    root = expand(xacro_doc(f'<link name="body">{call}</link>'))
    assert link_inertial(root, "body")[0] == 1.0


# --- The explicit-tensor checks at the edges: the macro's tolerance is relative, and agrees with `gen-robot check`.
# A flat body (principal moments a, b, a + b) sits exactly on the triangle inequality's boundary, so a rotated copy
# written out to the last digit misses it by rounding in either direction; the macro must accept it, as
# tensor_problem (rule I003, eigenvalues, 1e-9 relative) does. Bodies past the boundary by far more than rounding
# must be rejected, also long thin ones whose second-moment matrix has two near-zero eigenvalues.

ratio = st.floats(min_value=-6.0, max_value=0.0).map(lambda e: 10.0**e)  # log-uniform: long thin bodies too


def _rotated(moments, angles) -> np.ndarray:
    rot = rpy_matrix(*angles)
    tensor = rot @ np.diag(moments) @ rot.T
    return (tensor + tensor.T) / 2  # exactly symmetric, as a URDF tensor is


def _macro_verdict(expand, tensor: np.ndarray) -> str | None:
    """None when <xacro:inertial> accepts ``tensor`` (written with every digit), else the macro's message."""
    t = [[float(v) for v in row] for row in tensor.tolist()]
    call = (
        f'<xacro:inertial mass="1.0" ixx="{t[0][0]!r}" ixy="{t[0][1]!r}" ixz="{t[0][2]!r}" '
        f'iyy="{t[1][1]!r}" iyz="{t[1][2]!r}" izz="{t[2][2]!r}"/>'
    )
    try:
        root = expand(xacro_doc(f'<link name="body">{call}</link>'))
    except xacrokit.ExpandError as error:
        return str(error)
    np.testing.assert_array_equal(link_inertial(root, "body")[1], tensor)
    return None


@pytest.mark.parametrize("angles", [(0.3, 0.7, -0.4), (1.1, -0.2, 2.5), (-2.9, 1.4, 0.05), (0.0, math.pi / 2, 0.0)])
def test_explicit_inertial_accepts_a_rotated_flat_plate(expand, angles):
    """The reviewer's case: diag(0.02, 0.03, 0.05), 0.02 + 0.03 = 0.05, turned by rpy and written with repr."""
    tensor = _rotated([0.02, 0.03, 0.05], angles)
    assert tensor_problem(tensor) is None
    assert _macro_verdict(expand, tensor) is None


@given(
    a=positive,
    b_over_a=ratio,
    shape=st.sampled_from(["flat", "ordinary"]),
    where=st.floats(0.01, 0.99),
    angles=st.tuples(angle, angle, angle),
)
@example(a=0.03, b_over_a=2 / 3, shape="flat", where=0.5, angles=(0.3, 0.7, -0.4))
def test_explicit_inertial_accepts_rotated_flat_and_ordinary_tensors(expand, a, b_over_a, shape, where, angles):
    b = a * b_over_a
    c = a + b if shape == "flat" else (a - b) + where * 2 * b  # ordinary: strictly between a - b and a + b
    tensor = _rotated([a, b, c], angles)
    assert tensor_problem(tensor) is None
    assert _macro_verdict(expand, tensor) is None


@given(a=positive, b_over_a=ratio, angles=st.tuples(angle, angle, angle))
def test_explicit_inertial_rejects_a_rotated_triangle_violation_of_1e_6(expand, a, b_over_a, angles):
    b = a * b_over_a
    excess = 1e-6  # (c - (a + b)) / trace: far above rounding, far below any visible error in a diagonal entry
    c = (a + b) * (1 + excess) / (1 - excess)
    tensor = _rotated([a, b, c], angles)
    assert "triangle inequality" in tensor_problem(tensor)
    message = _macro_verdict(expand, tensor)
    assert message is not None and "inertial: parameters ixx..izz violate the triangle inequality" in message


@given(
    b=positive,
    c_over_b=st.floats(0.5, 1.0),
    negative_over_b=st.sampled_from([0.0, 1e-6, 1e-3, 0.2]),
    angles=st.tuples(angle, angle, angle),
)
def test_explicit_inertial_rejects_rotated_singular_and_indefinite_tensors(
    expand, b, c_over_b, negative_over_b, angles
):
    tensor = _rotated([-negative_over_b * b, b, b * c_over_b], angles)
    assert "not positive definite" in tensor_problem(tensor)
    message = _macro_verdict(expand, tensor)
    assert message is not None
    if np.diag(tensor).min() > 0:  # otherwise the moment's own check (> 0) speaks first
        assert "inertial: parameters ixx..izz must form a positive definite tensor" in message
    else:
        assert "inertial: parameter" in message and "must be > 0" in message


# Tensors 2x and 0.5x the tolerance away from each threshold: the macro must decide exactly as tensor_problem does.
# Triangle: the largest moment may exceed the sum of the others by 1e-9 * trace. Positive definite: a rod
# (smallest, 1, 1) needs smallest > 1e-9; its second-moment matrix has two eigenvalues near smallest / 2, and a long
# strip (1, 1e-7, c) past the triangle boundary has one tiny negative and one tiny positive: cases where comparing the
# principal minors with tolerances decides wrongly.


def _past_flat(b: float, excess: float) -> tuple[float, float, float]:
    """Moments (1, b, c) with c - (1 + b) = excess * trace."""
    return (1.0, b, (1.0 + b) * (1 + excess) / (1 - excess))


NEAR_THRESHOLD = [
    pytest.param(_past_flat(0.6, -1e-6), True, id="plate-inside-by-1e-6"),
    pytest.param(_past_flat(0.6, 0.5e-9), True, id="plate-past-by-0.5e-9"),
    pytest.param(_past_flat(0.6, 2e-9), False, id="plate-past-by-2e-9"),
    pytest.param(_past_flat(1e-7, 0.5e-9), True, id="strip-past-by-0.5e-9"),
    pytest.param(_past_flat(1e-7, 2e-9), False, id="strip-past-by-2e-9"),
    pytest.param(_past_flat(1e-7, 1e-6), False, id="strip-past-by-1e-6"),
    pytest.param(_past_flat(1e-3, 1e-6), False, id="narrow-plate-past-by-1e-6"),
    pytest.param((2e-9, 1.0, 1.0), True, id="rod-2e-9"),
    pytest.param((0.5e-9, 1.0, 1.0), False, id="rod-0.5e-9"),
    pytest.param((1e-7, 1.0, 1.0), True, id="rod-1e-7"),
]


# budget: ten threshold cases, each at 10 drawn scales and rotations (100 expansions in all; the threshold itself is
# what the cases pin, the draws only move it around)
@pytest.mark.parametrize(("moments", "accepted"), NEAR_THRESHOLD)
@settings(max_examples=budget(10))
@given(scale=positive, angles=st.tuples(angle, angle, angle))
def test_explicit_inertial_agrees_with_check_near_the_thresholds(expand, moments, accepted, scale, angles):
    tensor = _rotated([scale * m for m in moments], angles)
    assert (tensor_problem(tensor) is None) == accepted
    assert (_macro_verdict(expand, tensor) is None) == accepted


@given(radius=st.floats(1e-3, 2.0), length=st.floats(1e-3, 2.0), mass=st.floats(1e-3, 100.0))
def test_capsule_inertial_writes_the_generators_bits(expand, radius, length, mass):
    """The macro is physics.capsule_moments' twin: the same operations, so the same doubles (gen-robot's emitter
    writes composite and capsule links from Python; a hand-written xacro gets the same numbers)."""
    call = f'<xacro:capsule_inertial mass="{mass!r}" radius="{radius!r}" length="{length!r}"/>'
    root = expand(xacro_doc(f'<link name="body">{call}</link>'))
    _, tensor, _, _ = link_inertial(root, "body")
    axial, transverse = capsule_moments(mass, radius, length)
    assert (tensor[0, 0], tensor[1, 1], tensor[2, 2]) == (transverse, transverse, axial)
