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
import math
from typing import NamedTuple

from .arm_geometry import THREE_PARALLEL, ClosedForm
from .subproblems import (
    DEGENERATE,
    TANGENT,
    Mat,
    Vec,
    add,
    angles,
    apply,
    cross,
    dot,
    flat_parts,
    multiply,
    norm,
    parts,
    perpendicular,
    rotate,
    rotation,
    scale,
    sub,
    subproblem_1,
    subproblem_2,
    subproblem_3,
    transposed,
)

BRANCH_NAMES = {
    THREE_PARALLEL: (("shoulder", ("left", "right")), ("wrist", ("up", "down")), ("elbow", ("up", "down"))),
    "spherical wrist": (("shoulder", ("front", "back")), ("elbow", ("up", "down")), ("wrist", ("no flip", "flip"))),
}


class Branch(NamedTuple):
    """One closed-form solution: the six joint values (the chain's order), which root each step took, whether
    every subproblem was solved exactly (False: the nearest, to be checked), and the singularity it lies on
    ("" when none). (A named tuple: a solve makes eight, and a frozen dataclass costs four times as much to make.)"""

    values: tuple[float, ...]
    roots: tuple[int, int, int]
    exact: bool
    singular: str = ""


_made = tuple.__new__  # (Branch(...) without its __new__'s frame: a third of the time, and a solve makes eight)


def branches(form: ClosedForm, rotation_: Mat, position: Vec, *, exact_only: bool = False) -> list[Branch]:
    """Every branch that puts the chain's frame at (``rotation_``, ``position``) in the root's frame; with
    ``exact_only``, only those whose subproblems all have exact roots (a solve keeps no other: the rest not made)."""
    (h00, h01, h02), (h10, h11, h12), (h20, h21, h22) = form.lines.home_rotation  # (G = T M^-1, on floats)
    (a0, a1, a2), (b0, b1, b2), (c0, c1, c2) = rotation_
    r0 = (a0 * h00 + a1 * h01 + a2 * h02, a0 * h10 + a1 * h11 + a2 * h12, a0 * h20 + a1 * h21 + a2 * h22)
    r1 = (b0 * h00 + b1 * h01 + b2 * h02, b0 * h10 + b1 * h11 + b2 * h12, b0 * h20 + b1 * h21 + b2 * h22)
    r2 = (c0 * h00 + c1 * h01 + c2 * h02, c0 * h10 + c1 * h11 + c2 * h12, c0 * h20 + c1 * h21 + c2 * h22)
    (x0, x1, x2), (p0, p1, p2) = form.lines.home_position, position
    p_g = (
        p0 - (r0[0] * x0 + r0[1] * x1 + r0[2] * x2),
        p1 - (r1[0] * x0 + r1[1] * x1 + r1[2] * x2),
        p2 - (r2[0] * x0 + r2[1] * x1 + r2[2] * x2),
    )
    r_g = (r0, r1, r2)
    if form.kind == THREE_PARALLEL:
        return _three_parallel(form, r_g, p_g, exact_only)
    return _spherical_wrist(form, r_g, p_g, exact_only)


class _Shoulder(NamedTuple):
    """Step 1 made once per arm, subproblem 4 for q1: n . rotate(h1, t, f) = offset is a . f cos t + b . f sin t
    + c h1 . f = offset, f the wrist centre (``wrist`` at the zero pose) from axis 1's point ``origin``."""

    wrist: Vec
    origin: Vec
    axis: Vec  # (axis 1)
    base: Vec  # (axis 1's point from axis 2's)
    a: Vec
    b: Vec
    c: float
    offset: float


def _shoulder(form: ClosedForm, n: Vec) -> _Shoulder:
    h0, p0 = form.lines.axes[0], form.lines.points[0]
    hk = dot(n, h0)
    a, b, offset = sub(n, scale(hk, h0)), cross(n, h0), dot(n, sub(form.wrist, p0))
    return _Shoulder(form.wrist, p0, h0, sub(p0, form.lines.points[1]), a, b, hk, offset)


def _shoulder_roots(
    k: _Shoulder, r_g: Mat, p_g: Vec, exact_only: bool
) -> tuple[list[float], bool, tuple[float, ...]] | None:
    """Step 1 on floats: the roots t1 (= -q1), whether exact, and the wrist centre's parts about axis 1 (flat, as
    :func:`.subproblems.parts` gives them, its part along the axis moved to axis 2's point: turned by t1 it is the
    wrist centre from there); None when q1 has no equation (the wrist centre's plane holds axis 1), or with
    ``exact_only`` no exact root."""
    (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = r_g
    (w0, w1, w2), (o0, o1, o2), (g0, g1, g2) = k.wrist, k.origin, p_g
    f0 = r00 * w0 + r01 * w1 + r02 * w2 + g0 - o0  # (the wrist centre from axis 1's point)
    f1 = r10 * w0 + r11 * w1 + r12 * w2 + g1 - o1
    f2 = r20 * w0 + r21 * w1 + r22 * w2 + g2 - o2
    (h0, h1, h2), (b0, b1, b2), (a0, a1, a2), (d0, d1, d2) = k.axis, k.base, k.a, k.b
    along = h0 * f0 + h1 * f1 + h2 * f2
    x, y = a0 * f0 + a1 * f1 + a2 * f2, d0 * f0 + d1 * f1 + d2 * f2
    radius = math.hypot(x, y)
    if radius < DEGENERATE:
        return None
    roots, exact = angles(math.atan2(y, x), radius, k.offset - k.c * along)
    if exact_only and not exact:
        return None
    return (
        roots,
        exact,
        (
            (b0 + along * h0, b1 + along * h1, b2 + along * h2, f0 - along * h0, f1 - along * h1, f2 - along * h2)
            + (h1 * f2 - h2 * f1, h2 * f0 - h0 * f2, h0 * f1 - h1 * f0)
        ),
    )


def _fixed(h: Vec, k: Vec, p: Vec, base: float = 0.0) -> tuple[float, float, float]:
    """Subproblem 4's phase and radius for h . rotate(k, t, p) = d when h, k and p are the arm's, and what to take
    from d (with ``base`` taken from d as well): :func:`.subproblems.subproblem_4`'s first steps, once per arm."""
    along, hk = dot(k, p), dot(h, k)
    a, b = dot(h, p) - hk * along, dot(h, cross(k, p))
    return math.atan2(b, a), math.hypot(a, b), hk * along + base


class _ThreeParallel(NamedTuple):
    """What every target of a three-parallel-axes arm shares (made once per arm: ClosedForm is frozen). A vector the
    solve turns is kept as its :func:`.subproblems.parts`, flat: nine floats, along, across and k x it."""

    shoulder: _Shoulder
    axis_6: Vec
    n_about_1: tuple[float, ...]  # (n turned by q1 about axis 1)
    across_about_1: tuple[float, ...]  # (a unit vector across n, and n x it, turned by q1: theta's frame)
    normal_about_1: tuple[float, ...]
    wrist_roots: tuple[float, float, float]  # (q5's phase, radius and constant term)
    n_about_5: tuple[float, ...]  # (n turned by -q5 about axis 5, its part across axis 6)
    across_about_5: tuple[float, ...]
    wrist_arm: tuple[float, ...]  # (the wrist centre from axis 4, turned by theta about n)
    elbow: tuple[float, float, float]  # (q3's phase, radius and constant term, |fore|^2 + |back|^2 halved)
    n: Vec
    axis_2: Vec
    elbow_turn: tuple[float, ...]  # (:func:`_elbow_turn`)
    signs: tuple[float, float, float]


def _elbow_turn(k: Vec, fore: tuple[Vec, Vec, Vec], upper: Vec) -> tuple[float, ...]:
    """Subproblem 1 for q2 made once per arm: the elbow e (axis 4's point from axis 2's, ``upper`` plus ``fore``
    turned by q3: its :func:`.subproblems.parts`) has its part across axis 2 x = A + cos q3 B + sin q3 D, so that
    q2 = atan2(k . (x X y), x . y) = atan2((k x A + ...) . y, (A + ...) . y) for y (w across the axis): A, B, D,
    k x A, k x B, k x D flat, then |x|^2's six coefficients (1, c^2, s^2, c, s, cs)."""
    a, b, d = perpendicular(add(fore[0], upper), k), perpendicular(fore[1], k), perpendicular(fore[2], k)
    squares = (dot(a, a), dot(b, b), dot(d, d), 2.0 * dot(a, b), 2.0 * dot(a, d), 2.0 * dot(b, d))
    return (*a, *b, *d, *cross(k, a), *cross(k, b), *cross(k, d), *squares)


def _across_parts(parts_: tuple[float, ...], k: Vec) -> tuple[float, ...]:
    """Flat parts (:func:`.subproblems.flat_parts`) with each part's component along the unit ``k`` taken off: the
    turned vector's part across ``k``."""
    found: list[float] = []
    for i in (0, 3, 6):
        found.extend(perpendicular((parts_[i], parts_[i + 1], parts_[i + 2]), k))
    return tuple(found)


@functools.cache
def _three_parallel_constants(form: ClosedForm) -> _ThreeParallel:
    h, p = form.lines.axes, form.lines.points
    n = form.parallel or h[1]
    across = _across(n)
    fore, back = perpendicular(sub(p[3], p[2]), n), scale(-1.0, perpendicular(sub(p[2], p[1]), n))
    phase, radius, constant = _fixed(back, h[2], fore)
    elbow = (phase, radius, constant - (dot(fore, fore) + dot(back, back)) / 2.0)
    return _ThreeParallel(
        _shoulder(form, n),
        h[5],
        flat_parts(h[0], n),
        flat_parts(h[0], across),
        flat_parts(h[0], cross(n, across)),
        _fixed(n, h[4], h[5]),
        _across_parts(flat_parts(h[4], n), h[5]),
        flat_parts(h[4], across),
        flat_parts(n, sub(form.wrist, p[3])),
        elbow,
        n,
        h[1],
        _elbow_turn(h[1], parts(h[2], sub(p[3], p[2])), sub(p[2], p[1])),
        (dot(h[1], n), dot(h[2], n), dot(h[3], n)),
    )


def _three_parallel(form: ClosedForm, r_g: Mat, p_g: Vec, exact_only: bool) -> list[Branch]:
    """The chain of the module's docstring, its arithmetic written out on floats (a solve's hot loop: no call but
    the subproblems' and math's): vectors the arm fixes are turned from their parts, and theta is read in a frame
    across n. Step 1 here, steps 2 to 4 for each root of q1 (:func:`_three_parallel_wrists`), then step 5 for every
    wrist found (:func:`_three_parallel_elbows`: the arm's constants read once a target)."""
    k = _three_parallel_constants(form)
    step = _shoulder_roots(k.shoulder, r_g, p_g, exact_only)
    if step is None:
        return []
    roots, exact, reach = step
    (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = r_g
    x6, y6, z6 = k.axis_6
    g6 = (r00 * x6 + r01 * y6 + r02 * z6, r10 * x6 + r11 * y6 + r12 * z6, r20 * x6 + r21 * y6 + r22 * z6)
    arms: list[tuple[Vec, float, tuple[float, float, float, int, int, bool, str, bool]]] = []
    for i, t1 in enumerate(roots):
        _three_parallel_wrists(k, (r_g, g6, reach), t1, (i, exact, exact_only), arms)
    found: list[Branch] = []
    _three_parallel_elbows(k, arms, found)
    return found


def _three_parallel_wrists(
    k: _ThreeParallel,
    goal: tuple[Mat, Vec, tuple[float, ...]],
    t1: float,
    root: tuple[int, bool, bool],
    arms: list[tuple[Vec, float, tuple[float, float, float, int, int, bool, str, bool]]],
) -> None:
    """Steps 2 to 4 for the root ``t1`` (-q1) of step 1, each wrist appended to ``arms`` for step 5 (w, theta and
    :func:`_three_parallel_elbows`' head); ``goal`` is R_G, R_G h6 and the wrist centre's parts about axis 1,
    ``root`` the root's index, whether it is exact and whether only exact branches are made.
    (Subproblem 1 for q6 on floats: the part of R_G^T R1 n across axis 6 made once for both roots of q5.)"""
    (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = goal[0]
    c1, s1, t = math.cos(t1), -math.sin(t1), math.sin(t1)  # (of q1 = -t1)
    n0, n1, n2, x0, x1, x2, y0, y1, y2 = _turned_by_q1(k, goal[0], c1, s1)
    a0, a1, a2, b0, b1, b2, d0, d1, d2 = goal[2]  # (the wrist centre turned by t1 about axis 1, from axis 2's point)
    u0, u1, u2 = a0 + c1 * b0 + t * d0, a1 + c1 * b1 + t * d1, a2 + c1 * b2 + t * d2
    phase, radius, constant = k.wrist_roots
    if radius < DEGENERATE:
        return
    g0, g1, g2 = goal[1]
    fifths, wrist_exact = angles(phase, radius, n0 * g0 + n1 * g1 + n2 * g2 - constant)
    if root[2] and not wrist_exact:
        return
    k0, k1, k2 = k.axis_6
    g0, g1, g2 = r00 * n0 + r10 * n1 + r20 * n2, r01 * n0 + r11 * n1 + r21 * n2, r02 * n0 + r12 * n1 + r22 * n2
    along = k0 * g0 + k1 * g1 + k2 * g2  # (R_G^T R1 n, across axis 6: q6's target)
    g0, g1, g2 = g0 - along * k0, g1 - along * k1, g2 - along * k2
    turns_6 = g0 * g0 + g1 * g1 + g2 * g2 >= _SQUARE
    e0, e1, e2 = g1 * k2 - g2 * k1, g2 * k0 - g0 * k2, g0 * k1 - g1 * k0  # (g x k: p . (g x k) = k . (p x g))
    for j, q5 in enumerate(fifths):
        c5, s5 = math.cos(q5), -math.sin(q5)  # (of -q5)
        a0, a1, a2, b0, b1, b2, d0, d1, d2 = k.n_about_5  # (its parts across axis 6: p is across it)
        p0, p1, p2 = a0 + c5 * b0 + s5 * d0, a1 + c5 * b1 + s5 * d1, a2 + c5 * b2 + s5 * d2
        a0, a1, a2, b0, b1, b2, d0, d1, d2 = k.across_about_5
        v0, v1, v2 = a0 + c5 * b0 + s5 * d0, a1 + c5 * b1 + s5 * d1, a2 + c5 * b2 + s5 * d2
        t6 = None
        if turns_6 and p0 * p0 + p1 * p1 + p2 * p2 >= _SQUARE:  # (step 3: subproblem 1; else singular)
            sine, cosine = p0 * e0 + p1 * e1 + p2 * e2, p0 * g0 + p1 * g1 + p2 * g2
            t6, length = math.atan2(sine, cosine), math.hypot(sine, cosine)  # (|p| |g|: t6's cosine and sine)
            c, s = cosine / length, sine / length  # (step 4: v turned by joint 6; Rodrigues)
            along = (k0 * v0 + k1 * v1 + k2 * v2) * (1.0 - c)
            v0, v1, v2 = (
                v0 * c + (k1 * v2 - k2 * v1) * s + k0 * along,
                v1 * c + (k2 * v0 - k0 * v2) * s + k1 * along,
                v2 * c + (k0 * v1 - k1 * v0) * s + k2 * along,
            )
        x, y = v0 * x0 + v1 * x1 + v2 * x2, v0 * y0 + v1 * y1 + v2 * y2
        length = math.hypot(x, y)
        theta, c, s = (math.atan2(y, x), x / length, y / length) if length >= DEGENERATE else (0.0, 1.0, 0.0)
        a0, a1, a2, b0, b1, b2, d0, d1, d2 = k.wrist_arm
        w = (u0 - (a0 + c * b0 + s * d0), u1 - (a1 + c * b1 + s * d1), u2 - (a2 + c * b2 + s * d2))
        q6, singular = (-t6, "") if t6 is not None else (0.0, _UR_WRIST)
        arms.append((w, theta, (-t1, q5, q6, root[0], j, root[1] and wrist_exact, singular, root[2])))


def _turned_by_q1(k: _ThreeParallel, r_g: Mat, c1: float, s1: float) -> tuple[float, ...]:
    """n turned by joint 1 (``c1``, ``s1``: the cosine and sine of -q1), and the frame across n that theta is read in
    turned by joint 1, then by R_G^T: nine floats (n, then the frame's x and y)."""
    (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = r_g
    a0, a1, a2, b0, b1, b2, d0, d1, d2 = k.n_about_1
    n0, n1, n2 = a0 + c1 * b0 + s1 * d0, a1 + c1 * b1 + s1 * d1, a2 + c1 * b2 + s1 * d2
    a0, a1, a2, b0, b1, b2, d0, d1, d2 = k.across_about_1
    e0, e1, e2 = a0 + c1 * b0 + s1 * d0, a1 + c1 * b1 + s1 * d1, a2 + c1 * b2 + s1 * d2
    x0, x1, x2 = r00 * e0 + r10 * e1 + r20 * e2, r01 * e0 + r11 * e1 + r21 * e2, r02 * e0 + r12 * e1 + r22 * e2
    a0, a1, a2, b0, b1, b2, d0, d1, d2 = k.normal_about_1
    e0, e1, e2 = a0 + c1 * b0 + s1 * d0, a1 + c1 * b1 + s1 * d1, a2 + c1 * b2 + s1 * d2
    y0, y1, y2 = r00 * e0 + r10 * e1 + r20 * e2, r01 * e0 + r11 * e1 + r21 * e2, r02 * e0 + r12 * e1 + r22 * e2
    return (n0, n1, n2, x0, x1, x2, y0, y1, y2)


def _three_parallel_elbows(
    k: _ThreeParallel,
    arms: list[tuple[Vec, float, tuple[float, float, float, int, int, bool, str, bool]]],
    found: list[Branch],
) -> None:
    """Step 5 for each wrist of ``arms`` (w, theta and a head holding q1, q5, q6, the roots of q1 and q5, whether
    exact, the singularity, and whether only exact branches are made): q3 from w's distance from axis 2, q2 turning
    the elbow onto w (subproblem 1 on floats, w's part across axis 2 made once for both roots) and
    q4 = theta - q2 - q3 (each with its axis' sign); the branches appended to ``found``."""
    phase, radius, constant = k.elbow
    if radius < DEGENERATE:
        return
    (m0, m1, m2), (k0, k1, k2), (sign2, sign3, sign4) = k.n, k.axis_2, k.signs
    a0, a1, a2, b0, b1, b2, d0, d1, d2, e0, e1, e2, f0, f1, f2, g0, g1, g2, s0, s1, s2, s3, s4, s5 = k.elbow_turn
    for (w0, w1, w2), theta, head in arms:
        along = w0 * m0 + w1 * m1 + w2 * m2
        square = w0 * w0 + w1 * w1 + w2 * w2  # (w's distance from axis 2)
        thirds, elbow_exact = angles(phase, radius, -(square - along * along) / 2.0 - constant)
        q1, q5, q6, i, j, exact, singular, exact_only = head
        if exact_only and not elbow_exact:
            continue
        exact = exact and elbow_exact
        along = k0 * w0 + k1 * w1 + k2 * w2
        y0, y1, y2 = w0 - along * k0, w1 - along * k1, w2 - along * k2
        turns_2 = math.sqrt(y0 * y0 + y1 * y1 + y2 * y2) >= DEGENERATE
        ya, yb, yd = a0 * y0 + a1 * y1 + a2 * y2, b0 * y0 + b1 * y1 + b2 * y2, d0 * y0 + d1 * y1 + d2 * y2
        za, zb, zd = e0 * y0 + e1 * y1 + e2 * y2, f0 * y0 + f1 * y1 + f2 * y2, g0 * y0 + g1 * y1 + g2 * y2
        for m, q3 in enumerate(thirds):
            c, s = math.cos(q3), math.sin(q3)
            q2 = 0.0
            if turns_2 and s0 + c * (c * s1 + s3) + s * (s * s2 + s4 + c * s5) >= _SQUARE:  # (else q2 turns nothing)
                q2 = math.atan2(za + c * zb + s * zd, ya + c * yb + s * yd) or 0.0
            q4 = sign4 * (theta - sign2 * q2 - sign3 * q3)
            found.append(_made(Branch, ((q1, q2, q3, q4, q5, q6), (i, j, m), exact, singular)))


_SQUARE = DEGENERATE * DEGENERATE  # (a squared length below it: a vector without direction)
_UR_WRIST = (
    "wrist singularity: axis 6 is parallel to axes 2, 3 and 4, so joint 6 and the three turn the tool alike: a "
    "continuum of solutions, one given"
)
_SPHERICAL = (
    "wrist singularity: axes 4 and 6 are in line, so joints 4 and 6 turn the tool alike: a continuum of solutions, "
    "one given"
)


def _spherical_wrist(form: ClosedForm, r_g: Mat, p_g: Vec, exact_only: bool) -> list[Branch]:
    """The module's chain for a spherical wrist: joints 2 and 3 parallel (:func:`_parallel_arm`, on floats), or
    axes 1 and 2 meeting (:func:`_meeting_shoulder`)."""
    if form.parallel is not None:
        return _parallel_arm(form, r_g, p_g, exact_only)
    h = form.lines.axes
    centre = add(apply(r_g, form.wrist), p_g)
    found: list[Branch] = []
    for i, k, (q1, q2, q3), exact in _meeting_shoulder(form, centre):
        turned_ = multiply(multiply(rotation(h[0], q1), rotation(h[1], q2)), rotation(h[2], q3))
        rest = multiply(transposed(turned_), r_g)
        across = _across(h[5])
        for j, (q4, q5, q6), wrist_exact, singular in _wrist(h, apply(rest, h[5]), apply(rest, across), across):
            found.append(Branch((q1, q2, q3, q4, q5, q6), (i, k, j), exact and wrist_exact, singular))
    return found


def _wrist(h: tuple[Vec, ...], v: Vec, v6: Vec, across: Vec) -> list[tuple[int, Vec, bool, str]]:
    """Step 2: joints 4, 5 and 6 that turn axis 6 onto ``v`` and ``across`` (at right angles to axis 6) onto ``v6``
    (both turned back by joints 1 to 3), with the root index, whether exact, and the singularity."""
    pairs = subproblem_2(h[3], h[4], h[5], v)
    singular = ""
    if pairs is None:  # (axis 6 in line with axis 4: q4 is free; take 0)
        q5 = subproblem_1(h[4], h[5], v) or 0.0
        pairs, singular = ([(0.0, q5)], True), _SPHERICAL
    found = []
    for j, (q4, q5) in enumerate(pairs[0]):
        image = rotate(h[4], -q5, rotate(h[3], -q4, v6))
        found.append((j, (q4, q5, subproblem_1(h[5], across, image) or 0.0), pairs[1], singular))
    return found


class _WristPair(NamedTuple):
    """Subproblem 2 about axes 4 and 5 for axis 6 (p = h6, the same every target), written for any q = v: the
    middle vector m = alpha h4 + beta h5 +- gamma (h4 x h5) with alpha, beta from q's part along each axis and the
    arm's constants, then q5 = atan2((h5 x h6) . m, (h6 - (h5.h6) h5) . m) and q4 from m to v about h4, their dot
    products taken with the constants (:func:`.subproblems.subproblem_2`, its twin, written out)."""

    h4: Vec
    h5: Vec
    cosine: float  # (h4 . h5)
    across: Vec  # (h4 x h5)
    sine2: float
    along: float  # (h5 . h6)
    square: float  # (h6 . h6)
    normal: Vec  # (h4 x across)
    q5_sine: tuple[float, float]  # ((h5 x h6) . h4, (h5 x h6) . across)
    q5_cosine: tuple[float, float]  # ((h6 - (h5.h6) h5) . h4, and . across)
    q6_across: tuple[float, ...]  # (axis 6's across vector turned by q5, :func:`.subproblems.parts`, flat)
    q6_normal: tuple[float, ...]  # (h6 x across, turned by q5)
    flips: bool  # (h5 at right angles to h4 and h6, h6 along h4: the second root is q4 + pi, -q5, q6 + pi)


def _wrist_pair(h: tuple[Vec, ...], across6: Vec) -> _WristPair:
    h4, h5, h6 = h[3], h[4], h[5]
    across = cross(h4, h5)
    sine_vector, cosine_vector = cross(h5, h6), sub(h6, scale(dot(h5, h6), h5))
    return _WristPair(
        h4,
        h5,
        dot(h4, h5),
        across,
        dot(across, across),
        dot(h5, h6),
        dot(h6, h6),
        cross(h4, across),
        (dot(sine_vector, h4), dot(sine_vector, across)),
        (dot(cosine_vector, h4), dot(cosine_vector, across)),
        flat_parts(h5, across6),
        flat_parts(h5, cross(h6, across6)),
        abs(dot(h4, h5)) < DEGENERATE and abs(dot(h5, h6)) < DEGENERATE and norm(cross(h4, h6)) < DEGENERATE,
    )


def _wrist_on_floats(w: _WristPair, v: Vec, v6: Vec) -> tuple[list[Vec], bool] | None:
    """Step 2 as :func:`_wrist` gives it (q4, q5, q6 for each middle vector, and whether exact), on floats; None
    where subproblem 1 has no direction (the wrist singularity: :func:`_wrist` answers it)."""
    c, (x4, y4, z4), (xa, ya, za), (xn, yn, zn) = w.cosine, w.h4, w.across, w.normal
    v0, v1, v2 = v
    a1 = x4 * v0 + y4 * v1 + z4 * v2
    on5 = w.h5[0] * v0 + w.h5[1] * v1 + w.h5[2] * v2
    on_across, on_normal = xa * v0 + ya * v1 + za * v2, xn * v0 + yn * v1 + zn * v2
    alpha = (a1 - c * w.along) / (1.0 - c * c)
    beta = (w.along - c * a1) / (1.0 - c * c)
    rest = w.square - alpha * alpha - beta * beta - 2.0 * alpha * beta * c
    square = v0 * v0 + v1 * v1 + v2 * v2
    # (max(w.square, square, 1e-300) and max(x, 0.0) as comparisons, the same values: no call in the hot loop)
    scale_ = square if square > w.square else w.square
    scale_ = 1e-300 if scale_ < 1e-300 else scale_
    exact = rest >= -TANGENT * scale_ and abs(w.square - square) <= TANGENT * scale_
    gamma = math.sqrt((0.0 if rest < 0.0 else rest) / w.sine2)
    on4 = alpha + beta * c  # (the middle vector's part along h4)
    middle2 = alpha * alpha + beta * beta + 2.0 * alpha * beta * c + gamma * gamma * w.sine2
    off4, off_v = middle2 - on4 * on4, square - a1 * a1  # (the middle vector's and v's parts across h4, squared)
    if off4 < 0.0 or math.sqrt(off4) < DEGENERATE or off_v < 0.0 or math.sqrt(off_v) < DEGENERATE:
        return None
    u0, u1, u2 = v6  # (v6's parts about h4, :func:`.subproblems.parts`)
    along = x4 * u0 + y4 * u1 + z4 * u2
    a0, a1_, a2, b0, b1, b2 = along * x4, along * y4, along * z4, u0 - along * x4, u1 - along * y4, u2 - along * z4
    d0, d1, d2 = y4 * u2 - z4 * u1, z4 * u0 - x4 * u2, x4 * u1 - y4 * u0
    (sine_4, sine_a), (cosine_4, cosine_a) = w.q5_sine, w.q5_cosine
    ea0, ea1, ea2, eb0, eb1, eb2, ed0, ed1, ed2 = w.q6_across
    fa0, fa1, fa2, fb0, fb1, fb2, fd0, fd1, fd2 = w.q6_normal
    found = []
    for g in (gamma, -gamma) if gamma > 0 else (gamma,):
        q5 = math.atan2(alpha * sine_4 + g * sine_a, alpha * cosine_4 + g * cosine_a)
        q4 = math.atan2(beta * on_across + g * on_normal, alpha * a1 + beta * on5 + g * on_across - on4 * a1)
        c4, s4, c5, s5 = math.cos(q4), -math.sin(q4), math.cos(q5), math.sin(q5)
        y0, y1, y2 = a0 + c4 * b0 + s4 * d0, a1_ + c4 * b1 + s4 * d1, a2 + c4 * b2 + s4 * d2  # (v6 turned back by q4)
        e0, e1, e2 = ea0 + c5 * eb0 + s5 * ed0, ea1 + c5 * eb1 + s5 * ed1, ea2 + c5 * eb2 + s5 * ed2
        f0, f1, f2 = fa0 + c5 * fb0 + s5 * fd0, fa1 + c5 * fb1 + s5 * fd1, fa2 + c5 * fb2 + s5 * fd2
        q6 = math.atan2(y0 * f0 + y1 * f1 + y2 * f2, y0 * e0 + y1 * e1 + y2 * e2)
        found.append((q4, q5, q6))
        if w.flips and g > _FLIPPED and abs(q4) > _SIDED and abs(q6) > _SIDED:
            found.append((q4 - math.pi if q4 > 0 else q4 + math.pi, -q5, q6 - math.pi if q6 > 0 else q6 + math.pi))
            break  # (the flip, R4(q4 + pi) R5(-q5) R6(q6 + pi) = R4(q4) R5(q5) R6(q6), in atan2's range)
    return found, exact


_FLIPPED = 1e-3  # (gamma, about sin q5: above it the flip's values are the second root's to 1e-13)
_SIDED = 1e-9  # (q4 and q6 this far from 0: their flips are clear of atan2's cut at pi, as the second root's)


class _ParallelArm(NamedTuple):
    """What every target of a spherical-wrist arm with joints 2 and 3 parallel shares (made once per arm)."""

    shoulder: _Shoulder
    elbow: tuple[float, float, float]  # (q3's phase, radius and constant term, as the three-parallel-axes arm's)
    n: Vec
    forearm: tuple[float, ...]  # (the wrist centre from axis 3's point, turned by q3; flat parts)
    upper: Vec  # (axis 3's point from axis 2's)
    axis_2: Vec
    axis_3: Vec
    across: Vec  # (a unit vector at right angles to axis 6)
    wrist: _WristPair
    axes: tuple[Vec, ...]
    same: float  # (1 or -1: axis 3 is axis 2 or its opposite to the last bit, R2 R3 one turn about it; 0: not)


@functools.cache
def _parallel_arm_constants(form: ClosedForm) -> _ParallelArm:
    h, p, n = form.lines.axes, form.lines.points, form.parallel or form.lines.axes[1]
    fore, back = perpendicular(sub(form.wrist, p[2]), n), scale(-1.0, perpendicular(sub(p[2], p[1]), n))
    phase, radius, constant = _fixed(back, h[2], fore)
    elbow = (phase, radius, constant - (dot(fore, fore) + dot(back, back)) / 2.0)
    forearm, across = flat_parts(h[2], sub(form.wrist, p[2])), _across(h[5])
    wrist = _wrist_pair(h, across)
    same = 1.0 if h[2] == h[1] else -1.0 if h[2] == scale(-1.0, h[1]) else 0.0
    return _ParallelArm(_shoulder(form, n), elbow, n, forearm, sub(p[2], p[1]), h[1], h[2], across, wrist, h, same)


def _parallel_arm(form: ClosedForm, r_g: Mat, p_g: Vec, exact_only: bool) -> list[Branch]:
    """Step 1 as the three parallel axes' shoulder and elbow (q1 from n . E1^-1(G W) = n . W, q3 from the wrist
    centre's distance from axis 2, q2 turning it onto), then step 2 on axis 6 and a vector across it turned back
    by joints 1 to 3 (Rodrigues on floats: no matrices made); for each root of q1, :func:`_parallel_arm_elbows`."""
    k = _parallel_arm_constants(form)
    step = _shoulder_roots(k.shoulder, r_g, p_g, exact_only)
    if step is None:
        return []
    roots, exact, reach = step
    (h0, h1, h2), (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = k.shoulder.axis, *r_g
    goal: list[tuple[float, ...]] = []
    for v0, v1, v2 in (k.axes[5], k.across):  # (flat_parts(axis 1, apply(r_g, v)), written out)
        a0, a1, a2 = r00 * v0 + r01 * v1 + r02 * v2, r10 * v0 + r11 * v1 + r12 * v2, r20 * v0 + r21 * v1 + r22 * v2
        along = h0 * a0 + h1 * a1 + h2 * a2
        goal.append(
            (along * h0, along * h1, along * h2, a0 - along * h0, a1 - along * h1, a2 - along * h2)
            + (h1 * a2 - h2 * a1, h2 * a0 - h0 * a2, h0 * a1 - h1 * a0)
        )
    goal.append(reach)
    found: list[Branch] = []
    for i, t1 in enumerate(roots):
        _parallel_arm_elbows(k, goal, t1, (i, exact, exact_only), found)
    return found


def _parallel_arm_elbows(
    k: _ParallelArm, goal: list[tuple[float, ...]], t1: float, root: tuple[int, bool, bool], found: list[Branch]
) -> None:
    """The branches of the root ``t1`` (= -q1) appended to ``found``: ``goal`` holds the parts about axis 1 of R_G h6,
    of R_G across and of the wrist centre (:func:`_shoulder_roots`), ``root`` the root's index, whether exact and
    whether only exact branches are made."""
    c1, s1 = math.cos(t1), math.sin(t1)
    a0, a1, a2, b0, b1, b2, d0, d1, d2 = goal[2]  # (the wrist centre turned by t1 about axis 1, from axis 2's point)
    u = (a0 + c1 * b0 + s1 * d0, a1 + c1 * b1 + s1 * d1, a2 + c1 * b2 + s1 * d2)
    phase, radius, constant = k.elbow
    if radius < DEGENERATE:
        return
    (m0, m1, m2), (u0, u1, u2) = k.n, u
    along = u0 * m0 + u1 * m1 + u2 * m2
    thirds, elbow_exact = angles(phase, radius, -(u0 * u0 + u1 * u1 + u2 * u2 - along * along) / 2.0 - constant)
    if root[2] and not elbow_exact:
        return
    a0, a1, a2, b0, b1, b2, d0, d1, d2 = goal[0]
    back6 = (a0 + c1 * b0 + s1 * d0, a1 + c1 * b1 + s1 * d1, a2 + c1 * b2 + s1 * d2)
    a0, a1, a2, b0, b1, b2, d0, d1, d2 = goal[1]
    back_across = (a0 + c1 * b0 + s1 * d0, a1 + c1 * b1 + s1 * d1, a2 + c1 * b2 + s1 * d2)
    a0, a1, a2, b0, b1, b2, d0, d1, d2 = k.forearm
    (p0, p1, p2), (k0, k1, k2), exact = k.upper, k.axis_2, root[1] and elbow_exact
    along = k0 * u0 + k1 * u1 + k2 * u2  # (subproblem 1 for q2 on floats: u's part across axis 2 made once)
    y0, y1, y2 = u0 - along * k0, u1 - along * k1, u2 - along * k2
    turns_2 = math.sqrt(y0 * y0 + y1 * y1 + y2 * y2) >= DEGENERATE
    pair = _parts_about(k.axis_2, back6, back_across) if k.same else ()
    for m, q3 in enumerate(thirds):
        c3, s3 = math.cos(q3), math.sin(q3)
        e0, e1, e2 = a0 + c3 * b0 + s3 * d0 + p0, a1 + c3 * b1 + s3 * d1 + p1, a2 + c3 * b2 + s3 * d2 + p2
        along = k0 * e0 + k1 * e1 + k2 * e2
        x0, x1, x2 = e0 - along * k0, e1 - along * k1, e2 - along * k2
        q2 = 0.0
        if turns_2 and math.sqrt(x0 * x0 + x1 * x1 + x2 * x2) >= DEGENERATE:
            sine = k0 * (x1 * y2 - x2 * y1) + k1 * (x2 * y0 - x0 * y2) + k2 * (x0 * y1 - x1 * y0)
            q2 = math.atan2(sine, x0 * y0 + x1 * y1 + x2 * y2) or 0.0
        if pair:  # (R2 R3 = R(axis 2, q2 +- q3): both vectors turned back once, from their parts)
            v, v6 = _turned_back(pair, q2 + k.same * q3)
        else:
            v, v6 = _turned_twice(k, (math.cos(q2), -math.sin(q2), c3, -s3), (back6, back_across))
        fast = _wrist_on_floats(k.wrist, v, v6)
        if fast is None:
            for j, values, wrist_exact, singular in _wrist(k.axes, v, v6, k.across):
                found.append(Branch((-t1, q2, q3, *values), (root[0], m, j), exact and wrist_exact, singular))
            continue
        for j, (q4, q5, q6) in enumerate(fast[0]):
            found.append(_made(Branch, ((-t1, q2, q3, q4, q5, q6), (root[0], m, j), exact and fast[1], "")))


def _parts_about(k: Vec, a: Vec, b: Vec) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """:func:`.subproblems.flat_parts` of ``a`` and of ``b`` about the unit ``k``, written out."""
    k0, k1, k2 = k
    found = []
    for a0, a1, a2 in (a, b):
        along = k0 * a0 + k1 * a1 + k2 * a2
        x0, x1, x2 = along * k0, along * k1, along * k2
        found.append((x0, x1, x2, a0 - x0, a1 - x1, a2 - x2, k1 * a2 - k2 * a1, k2 * a0 - k0 * a2, k0 * a1 - k1 * a0))
    return found[0], found[1]


def _turned_back(pair: tuple[tuple[float, ...], ...], angle: float) -> tuple[Vec, Vec]:
    """Two vectors, each given by its :func:`.subproblems.flat_parts` about one axis, turned by -``angle`` about it."""
    c, s = math.cos(angle), -math.sin(angle)
    (a0, a1, a2, b0, b1, b2, d0, d1, d2), (e0, e1, e2, f0, f1, f2, g0, g1, g2) = pair
    return (
        (a0 + c * b0 + s * d0, a1 + c * b1 + s * d1, a2 + c * b2 + s * d2),
        (e0 + c * f0 + s * g0, e1 + c * f1 + s * g1, e2 + c * f2 + s * g2),
    )


def _turned_twice(k: _ParallelArm, turns: tuple[float, float, float, float], pair: tuple[Vec, Vec]) -> list[Vec]:
    """Both vectors of ``pair`` turned about axis 2, then about axis 3, by the angles of cosines and sines ``turns``
    (:func:`.subproblems.turn` twice, written out)."""
    c, s, c3, s3 = turns
    (k0, k1, k2), (j0, j1, j2) = k.axis_2, k.axis_3
    found = []
    for a0, a1, a2 in pair:
        along = (k0 * a0 + k1 * a1 + k2 * a2) * (1.0 - c)
        a0, a1, a2 = (
            a0 * c + (k1 * a2 - k2 * a1) * s + k0 * along,
            a1 * c + (k2 * a0 - k0 * a2) * s + k1 * along,
            a2 * c + (k0 * a1 - k1 * a0) * s + k2 * along,
        )
        along = (j0 * a0 + j1 * a1 + j2 * a2) * (1.0 - c3)
        found.append(
            (
                a0 * c3 + (j1 * a2 - j2 * a1) * s3 + j0 * along,
                a1 * c3 + (j2 * a0 - j0 * a2) * s3 + j1 * along,
                a2 * c3 + (j0 * a1 - j1 * a0) * s3 + j2 * along,
            )
        )
    return found


def _meeting_shoulder(form: ClosedForm, centre: Vec) -> list[tuple[int, int, tuple[float, float, float], bool]]:
    """The first three joints' values that put the wrist centre W at ``centre`` when axes 1 and 2 meet at A:
    |E3 W - A| = |G W - A| gives q3, subproblem 2 q1 and q2; with their roots' indices."""
    h, p = form.lines.axes, form.lines.points
    found = []
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
