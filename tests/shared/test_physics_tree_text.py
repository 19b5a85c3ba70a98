"""The facts several stages share, each against an independent oracle: primitive inertia against numerical
integration, principal moments against numpy one tensor at a time, the tree walk, and the number text that xacro and
URDF readers read back exactly."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import budget, expand_text
from xacrokit.shared.kinematic_tree import Tree, cycles
from xacrokit.shared.solid_inertia import (
    box_moments,
    cylinder_moments,
    moments_problem,
    principal_moments,
    sphere_moment,
    tensor,
    tensor_problem,
)
from xacrokit.shared.value_text import num, vec, xacro_text


def integrated_moments(inside, half: tuple[float, float, float], mass: float, cells: int = 80) -> np.ndarray:
    """(Ixx, Iyy, Izz) of a uniform body by the midpoint rule on a grid over its bounding box."""
    axes = [(np.arange(cells) + 0.5) / cells * 2 * h - h for h in half]
    x, y, z = np.meshgrid(*axes, indexing="ij")
    keep = inside(x, y, z)
    x, y, z = x[keep], y[keep], z[keep]
    dm = mass / keep.sum()
    return np.array([np.sum(y**2 + z**2), np.sum(x**2 + z**2), np.sum(x**2 + y**2)]) * dm


def test_box_moments_equal_the_integral():
    size = (0.4, 0.3, 0.1)
    got = box_moments(2.0, *size)
    want = integrated_moments(lambda x, y, z: np.ones_like(x, dtype=bool), tuple(s / 2 for s in size), 2.0)
    assert got == pytest.approx(want, rel=1e-3)


def test_cylinder_moments_equal_the_integral():
    radius, length = 0.05, 0.3
    axial, transverse = cylinder_moments(1.5, radius, length)
    want = integrated_moments(lambda x, y, z: x**2 + y**2 <= radius**2, (radius, radius, length / 2), 1.5, 120)
    assert (transverse, transverse, axial) == pytest.approx(want, rel=5e-3)


def test_sphere_moment_equals_the_integral():
    radius = 0.1
    want = integrated_moments(lambda x, y, z: x**2 + y**2 + z**2 <= radius**2, (radius,) * 3, 0.5, 120)
    assert (sphere_moment(0.5, radius),) * 3 == pytest.approx(want, rel=5e-3)


finite = st.floats(-10.0, 10.0, allow_nan=False)


@given(st.lists(st.tuples(*[finite] * 6), max_size=8))
def test_batched_principal_moments_equal_numpy_one_at_a_time(entries):
    got = principal_moments(entries)
    assert len(got) == len(entries)
    for moments, entry in zip(got, entries, strict=True):
        assert moments == pytest.approx(np.linalg.eigvalsh(tensor(*entry)).tolist(), abs=1e-12)


@pytest.mark.parametrize(
    ("moments", "problem"),
    [
        ((1.0, 1.0, 1.0), None),
        ((1.0, 1.0, 2.0), None),  # a flat plate: on the triangle inequality's boundary, allowed
        ((1.0, 1.0, 2.0 + 1e-6), "triangle-inequality"),
        ((1.0, 1.0, 0.0), "not-positive-definite"),
        ((-1.0, 2.0, 2.0), "not-positive-definite"),
        ((1e-12, 1.0, 1.0), "not-positive-definite"),  # below 1e-9 of the largest: zero
    ],
)
def test_moments_problem(moments, problem):
    assert moments_problem(moments) == problem


def test_tensor_problem_says_what_is_wrong():
    assert tensor_problem(tensor(1, 0, 0, 1, 0, 1)) is None
    assert "not finite" in (tensor_problem(tensor(math.nan, 0, 0, 1, 0, 1)) or "")
    assert "triangle inequality" in (tensor_problem(tensor(1, 0, 0, 1, 0, 3)) or "")
    assert "not positive definite" in (tensor_problem(tensor(1, 2, 0, 1, 0, 1)) or "")


def test_tree_first_parent_wins_roots_reachable_and_the_way_up():
    tree: Tree[str] = Tree()
    assert tree.add("a", "b", "ab") is None and tree.add("b", "c", "bc") is None
    assert tree.add("x", "c", "xc") == ("b", "bc")  # c has a parent already: nothing added
    assert tree.roots(["a", "b", "c", "x"]) == ["a", "x"]
    assert tree.reachable(["a"]) == {"a", "b", "c"}
    assert tree.path_up("c", "a") == ["c", "b", "a"] and tree.path_up("a", "c") == []
    tree.add("c", "d", "cd")
    tree.add("d", "c2", "dc2")
    loop: Tree[str] = Tree()
    loop.add("p", "q", "pq")
    loop.add("q", "p", "qp")
    assert loop.roots(["p", "q"]) == [] and loop.path_up("p", "nowhere") == []  # a cycle: the walk ends


@settings(max_examples=budget(200))  # (budget: a float's text takes microseconds; the doubles are many)
@given(st.floats(allow_nan=False, allow_infinity=False))
def test_numbers_read_back_exactly_and_never_as_negative_zero(value):
    text = num(value)
    assert float(text) == value and text != "-0.0"
    assert vec((value, 0.0, -0.0)) == f"{text} 0.0 0.0"


# (it found that xacro refuses "$$" before anything but { or (: xacro_text writes such runs as ${'$'}...$)
@given(st.text(alphabet="$({}) ab", max_size=12))
def test_xacro_copies_escaped_text_verbatim(tmp_path_factory, value):
    folder = tmp_path_factory.mktemp("text")
    root = expand_text(
        f'<robot name="t" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="{xacro_text(value)}"/></robot>',
        folder,
        trust=True,  # (the test's own document: in-process, as the expand fixture does; the text is xacro's alone)
    )
    assert root.find("link").get("name") == value


def test_cycles_of_a_follows_relation_each_once_from_its_smallest_name():
    assert cycles({"a": "b", "b": "a", "c": "a", "d": "e", "e": "f", "f": "d", "g": "h"}) == [
        ["a", "b"],
        ["d", "e", "f"],
    ]
    assert cycles({"x": "x"}) == [["x"]] and cycles({"p": "q", "q": "r"}) == []
