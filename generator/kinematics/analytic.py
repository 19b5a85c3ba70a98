"""Closed-form inverse kinematics of the arms :func:`.arm_geometry.recognise` knows, as a chain of Paden-Kahan
subproblems (:mod:`.subproblems`) on the product of exponentials T(q) = E1 ... E6 M. With G = T M^-1 the motion the
joints must make:

*three parallel axes* (joints 2, 3, 4 along n; axes 5 and 6 meet at C), up to 8 branches:
  1. E2 E3 E4 keep a point's component along n, and E5 E6 keep C: n . E1^-1(G C) = n . C gives q1 (shoulder, 2);
  2. the rotation: n^T R5(q5) h6 = (R1 n)^T R_G h6 gives q5 (wrist, 2);
  3. R6^T R5^T n = R_G^T R1 n gives q6 (none when axis 6 is along n: the wrist singularity, a continuum);
  4. R2 R3 R4 = Rot(n, theta) = R1^T R_G R6^T R5^T gives theta = q2 + q3 + q4 (each with its axis' sign);
  5. E2 E3 P4 = E1^-1(G C) - Rot(n, theta)(C - P4) =: w: the distance of E3 P4 from axis 2 is w's, which gives q3
     (elbow, 2), then q2 turns E3 P4 onto w, and q4 = theta - q2 - q3.

*spherical wrist* (axes 4, 5, 6 meet at W), up to 8 branches:
  1. E1 E2 E3 W = G W: with joints 2 and 3 parallel, n . E1^-1(G W) = n . W gives q1 (2), the distance from axis 2
     gives q3 (2) and q2 turns it onto; with axes 1 and 2 meeting at A, |E3 W - A| = |G W - A| gives q3 (2) and
     subproblem 2 gives q1 and q2 together (2);
  2. R4 R5 R6 = (R1 R2 R3)^T R_G: subproblem 2 on h6 gives q4 and q5 (2: the wrist flip), q6 turns the rest
     (none when axes 4 and 6 line up: the wrist singularity, a continuum).

Each branch is named by which root of each subproblem it took (:data:`BRANCH_NAMES`), so that one name means one
branch across targets; docs/kinematics.md says how the names read on an arm.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any

from .arm_geometry import THREE_PARALLEL, ClosedForm
from .subproblems import (
    Mat,
    Vec,
    add,
    apply,
    apply_transposed,
    cross,
    dot,
    multiply,
    norm,
    perpendicular,
    rotate,
    rotation,
    scale,
    sub,
    subproblem_1,
    subproblem_2,
    subproblem_3,
    subproblem_4,
    transposed,
)

BRANCH_NAMES = {
    THREE_PARALLEL: (("shoulder", ("left", "right")), ("wrist", ("up", "down")), ("elbow", ("up", "down"))),
    "spherical wrist": (("shoulder", ("front", "back")), ("elbow", ("up", "down")), ("wrist", ("no flip", "flip"))),
}


@dataclass(frozen=True)
class Branch:
    """One closed-form solution: the six joint values (the chain's order), which root each step took, whether
    every subproblem was solved exactly (False: the nearest, to be checked), and the singularity it lies on
    ("" when none)."""

    values: tuple[float, ...]
    roots: tuple[int, int, int]
    exact: bool
    singular: str = ""


def branches(form: ClosedForm, rotation_: Mat, position: Vec) -> list[Branch]:
    """Every branch that puts the chain's frame at (``rotation_``, ``position``) in the root's frame."""
    lines = form.lines
    r_g = multiply(rotation_, transposed(lines.home_rotation))
    p_g = sub(position, apply(r_g, lines.home_position))
    if form.kind == THREE_PARALLEL:
        return _three_parallel(form, r_g, p_g)
    return _spherical_wrist(form, r_g, p_g)


@functools.cache
def _three_parallel_constants(form: ClosedForm) -> tuple[Any, ...]:
    """What every target of a three-parallel-axes arm shares (made once per arm: ClosedForm is frozen)."""
    h, p = form.lines.axes, form.lines.points
    n = form.parallel or h[1]
    signs = (dot(h[1], n), dot(h[2], n), dot(h[3], n))
    upper, fore = perpendicular(sub(p[2], p[1]), n), perpendicular(sub(p[3], p[2]), n)
    offset = dot(n, sub(form.wrist, p[0]))
    return n, signs, _across(n), fore, scale(-1.0, upper), sub(form.wrist, p[3]), sub(p[3], p[2]), offset


def _three_parallel(form: ClosedForm, r_g: Mat, p_g: Vec) -> list[Branch]:
    h, p = form.lines.axes, form.lines.points
    n, signs, across, fore, back, wrist_arm, forearm, offset = _three_parallel_constants(form)
    centre = add(apply(r_g, form.wrist), p_g)
    from_base = sub(centre, p[0])
    shoulder = subproblem_4(n, h[0], from_base, offset)
    g6 = apply(r_g, h[5])
    found: list[Branch] = []
    for i, t1 in enumerate(_roots(shoulder)):
        q1 = -t1
        n1 = rotate(h[0], q1, n)
        reached = add(p[0], rotate(h[0], t1, from_base))
        wrist = subproblem_4(n, h[4], h[5], dot(n1, g6))
        back_n1 = apply_transposed(r_g, n1)
        for j, q5 in enumerate(_roots(wrist)):
            t6 = subproblem_1(h[5], rotate(h[4], -q5, n), back_n1)
            q6 = -t6 if t6 is not None else 0.0
            singular = "" if t6 is not None else _UR_WRIST
            turned = rotate(h[0], t1, apply(r_g, rotate(h[5], -q6, rotate(h[4], -q5, across))))
            theta = subproblem_1(n, across, turned) or 0.0
            to_w = sub(sub(reached, rotate(n, theta, wrist_arm)), p[1])
            elbow = subproblem_3(h[2], fore, back, norm(perpendicular(to_w, n)))
            exact = _exact(shoulder) and _exact(wrist) and _exact(elbow)
            for k, q3 in enumerate(_roots(elbow)):
                e3 = add(sub(p[2], p[1]), rotate(h[2], q3, forearm))
                q2 = subproblem_1(h[1], e3, to_w) or 0.0
                q4 = signs[2] * (theta - signs[0] * q2 - signs[1] * q3)
                found.append(Branch((q1, q2, q3, q4, q5, q6), (i, j, k), exact, singular))
    return found


_UR_WRIST = (
    "wrist singularity: axis 6 is parallel to axes 2, 3 and 4, so joint 6 and the three turn the tool alike: a "
    "continuum of solutions, one given"
)
_SPHERICAL = (
    "wrist singularity: axes 4 and 6 are in line, so joints 4 and 6 turn the tool alike: a continuum of solutions, "
    "one given"
)


def _spherical_wrist(form: ClosedForm, r_g: Mat, p_g: Vec) -> list[Branch]:
    h = form.lines.axes
    centre = add(apply(r_g, form.wrist), p_g)
    found: list[Branch] = []
    for i, k, (q1, q2, q3), exact in _position(form, centre):
        turned = multiply(multiply(rotation(h[0], q1), rotation(h[1], q2)), rotation(h[2], q3))
        rest = multiply(transposed(turned), r_g)
        pairs = subproblem_2(h[3], h[4], h[5], apply(rest, h[5]))
        singular = ""
        if pairs is None:  # (axis 6 in line with axis 4: q4 is free; take 0)
            q5 = subproblem_1(h[4], h[5], apply(rest, h[5])) or 0.0
            pairs, singular = ([(0.0, q5)], True), _SPHERICAL
        for j, (q4, q5) in enumerate(pairs[0]):
            across = _across(h[5])
            image = rotate(h[4], -q5, rotate(h[3], -q4, apply(rest, across)))
            q6 = subproblem_1(h[5], across, image) or 0.0
            found.append(Branch((q1, q2, q3, q4, q5, q6), (i, k, j), exact and pairs[1], singular))
    return found


def _position(form: ClosedForm, centre: Vec) -> list[tuple[int, int, tuple[float, float, float], bool]]:
    """The first three joints' values that put the wrist centre W at ``centre``, with their roots' indices."""
    h, p = form.lines.axes, form.lines.points
    found = []
    if form.parallel is not None:
        n = form.parallel
        shoulder = subproblem_4(n, h[0], sub(centre, p[0]), dot(n, sub(form.wrist, p[0])))
        for i, t1 in enumerate(_roots(shoulder)):
            reached = add(p[0], rotate(h[0], t1, sub(centre, p[0])))
            upper, fore = perpendicular(sub(p[2], p[1]), n), perpendicular(sub(form.wrist, p[2]), n)
            elbow = subproblem_3(h[2], fore, scale(-1.0, upper), norm(perpendicular(sub(reached, p[1]), n)))
            for k, q3 in enumerate(_roots(elbow)):
                e3 = add(p[2], rotate(h[2], q3, sub(form.wrist, p[2])))
                q2 = subproblem_1(h[1], sub(e3, p[1]), sub(reached, p[1])) or 0.0
                found.append((i, k, (-t1, q2, q3), _exact(shoulder) and _exact(elbow)))
        return found
    meet = form.shoulder or p[0]
    elbow = subproblem_3(h[2], sub(form.wrist, p[2]), sub(meet, p[2]), norm(sub(centre, meet)))
    for k, q3 in enumerate(_roots(elbow)):
        x = sub(add(p[2], rotate(h[2], q3, sub(form.wrist, p[2]))), meet)
        pairs = subproblem_2(h[0], h[1], x, sub(centre, meet))
        if pairs is None:  # (the wrist centre on axis 1: a shoulder singularity; q1 free, take 0)
            q2 = subproblem_1(h[1], x, sub(centre, meet)) or 0.0
            pairs = ([(0.0, q2)], False)
        for i, (q1, q2) in enumerate(pairs[0]):
            found.append((i, k, (q1, q2, q3), _exact(elbow) and pairs[1]))
    return found


def _roots(solved: tuple[list[float], bool] | None) -> list[float]:
    return solved[0] if solved is not None else []


def _exact(solved: tuple[list[float], bool] | None) -> bool:
    return solved is not None and solved[1]


def _across(k: Vec) -> Vec:
    """A unit vector at right angles to the unit ``k``."""
    other: Vec = (1.0, 0.0, 0.0) if abs(k[0]) < 0.9 else (0.0, 1.0, 0.0)
    c = cross(k, other)
    return scale(1.0 / norm(c), c)
