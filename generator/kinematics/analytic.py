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
    apply_transposed,
    cross,
    dot,
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
    turn,
    turned,
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


def branches(form: ClosedForm, rotation_: Mat, position: Vec) -> list[Branch]:
    """Every branch that puts the chain's frame at (``rotation_``, ``position``) in the root's frame."""
    lines = form.lines
    r_g = multiply(rotation_, transposed(lines.home_rotation))
    p_g = sub(position, apply(r_g, lines.home_position))
    if form.kind == THREE_PARALLEL:
        return _three_parallel(form, r_g, p_g)
    return _spherical_wrist(form, r_g, p_g)


class _Shoulder(NamedTuple):
    """Subproblem 4 for q1 made once per arm: n . rotate(h1, t, f) = offset is a . f cos t + b . f sin t + c h1 . f
    = offset (f the wrist centre from a point of axis 1)."""

    a: Vec
    b: Vec
    c: float
    offset: float


def _shoulder(form: ClosedForm, n: Vec) -> _Shoulder:
    h0, p0 = form.lines.axes[0], form.lines.points[0]
    hk = dot(n, h0)
    return _Shoulder(sub(n, scale(hk, h0)), cross(n, h0), hk, dot(n, sub(form.wrist, p0)))


def _fixed(h: Vec, k: Vec, p: Vec, base: float = 0.0) -> tuple[float, float, float]:
    """Subproblem 4's phase and radius for h . rotate(k, t, p) = d when h, k and p are the arm's, and what to take
    from d (with ``base`` taken from d as well): :func:`.subproblems.subproblem_4`'s first steps, once per arm."""
    along, hk = dot(k, p), dot(h, k)
    a, b = dot(h, p) - hk * along, dot(h, cross(k, p))
    return math.atan2(b, a), math.hypot(a, b), hk * along + base


class _ThreeParallel(NamedTuple):
    """What every target of a three-parallel-axes arm shares (made once per arm: ClosedForm is frozen)."""

    shoulder: _Shoulder
    n_about_1: tuple[Vec, Vec, Vec]  # (n turned by q1 about axis 1)
    across_about_1: tuple[Vec, Vec, Vec]  # (a unit vector across n, and n x it, turned by q1: theta's frame)
    normal_about_1: tuple[Vec, Vec, Vec]
    wrist: tuple[float, float, float]  # (q5's phase, radius and constant term)
    n_about_5: tuple[Vec, Vec, Vec]  # (n turned by -q5 about axis 5)
    across_about_5: tuple[Vec, Vec, Vec]
    wrist_arm: tuple[Vec, Vec, Vec]  # (the wrist centre from axis 4, turned by theta about n)
    elbow: tuple[float, float, float]  # (q3's phase, radius and constant term, |fore|^2 + |back|^2 halved)
    forearm: tuple[Vec, Vec, Vec]  # (axis 4's point from axis 3's, turned by q3)
    upper: Vec  # (axis 3's point from axis 2's)
    signs: tuple[float, float, float]


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
        parts(h[0], n),
        parts(h[0], across),
        parts(h[0], cross(n, across)),
        _fixed(n, h[4], h[5]),
        parts(h[4], n),
        parts(h[4], across),
        parts(n, sub(form.wrist, p[3])),
        elbow,
        parts(h[2], sub(p[3], p[2])),
        sub(p[2], p[1]),
        (dot(h[1], n), dot(h[2], n), dot(h[3], n)),
    )


def _shoulder_roots(
    shoulder: _Shoulder, h0: Vec, base: Vec, f: Vec
) -> tuple[tuple[list[float], bool] | None, tuple[Vec, Vec, Vec]]:
    """q1's subproblem for the wrist centre at ``f`` from axis 1's point, and f's parts about axis 1
    (:func:`.subproblems.parts`, its part along the axis moved by ``base``: f turned from there)."""
    a, b = shoulder.a, shoulder.b
    along = h0[0] * f[0] + h0[1] * f[1] + h0[2] * f[2]
    x = a[0] * f[0] + a[1] * f[1] + a[2] * f[2]
    y = b[0] * f[0] + b[1] * f[1] + b[2] * f[2]
    radius = math.hypot(x, y)
    f_parts = (
        (base[0] + along * h0[0], base[1] + along * h0[1], base[2] + along * h0[2]),
        (f[0] - along * h0[0], f[1] - along * h0[1], f[2] - along * h0[2]),
        (h0[1] * f[2] - h0[2] * f[1], h0[2] * f[0] - h0[0] * f[2], h0[0] * f[1] - h0[1] * f[0]),
    )
    if radius < DEGENERATE:
        return None, f_parts
    return angles(math.atan2(y, x), radius, shoulder.offset - shoulder.c * along), f_parts


def _three_parallel(form: ClosedForm, r_g: Mat, p_g: Vec) -> list[Branch]:
    """The chain of the module's docstring, its arithmetic written out on floats (a solve's hot loop): vectors the
    arm fixes are turned from their parts (:func:`.subproblems.parts`), and theta is read in a frame across n."""
    k = _three_parallel_constants(form)
    h, p = form.lines.axes, form.lines.points
    f = sub(add(apply(r_g, form.wrist), p_g), p[0])
    shoulder, f_parts = _shoulder_roots(k.shoulder, h[0], sub(p[0], p[1]), f)
    g6 = apply(r_g, h[5])
    found: list[Branch] = []
    for i, t1 in enumerate(_roots(shoulder)):
        c1, s1 = math.cos(t1), -math.sin(t1)  # (of q1 = -t1)
        n1 = turned(k.n_about_1, c1, s1)
        frame = (
            apply_transposed(r_g, turned(k.across_about_1, c1, s1)),
            apply_transposed(r_g, turned(k.normal_about_1, c1, s1)),
        )
        back_n1 = apply_transposed(r_g, n1)
        reach = turned(f_parts, c1, -s1)  # (the wrist centre turned by t1 about axis 1, from axis 2's point)
        wrist = angles(k.wrist[0], k.wrist[1], dot(n1, g6) - k.wrist[2]) if k.wrist[1] >= DEGENERATE else None
        for j, q5 in enumerate(_roots(wrist)):
            c5, s5 = math.cos(q5), -math.sin(q5)  # (of -q5)
            t6 = subproblem_1(h[5], turned(k.n_about_5, c5, s5), back_n1)
            theta, to_w = _theta(k, turned(k.across_about_5, c5, s5), h[5], t6, frame, reach)
            elbow = _elbow_of(k.elbow, to_w, form.parallel or h[1])
            exact = _exact(shoulder) and _exact(wrist) and _exact(elbow)
            q6, singular = (-t6, "") if t6 is not None else (0.0, _UR_WRIST)
            for m, q3 in enumerate(_roots(elbow)):
                e3 = turned(k.forearm, math.cos(q3), math.sin(q3))
                q2 = subproblem_1(h[1], (e3[0] + k.upper[0], e3[1] + k.upper[1], e3[2] + k.upper[2]), to_w) or 0.0
                q4 = k.signs[2] * (theta - k.signs[0] * q2 - k.signs[1] * q3)
                found.append(Branch((-t1, q2, q3, q4, q5, q6), (i, j, m), exact, singular))
    return found


def _theta(
    k: _ThreeParallel, across_5: Vec, h5: Vec, t6: float | None, frame: tuple[Vec, Vec], reach: Vec
) -> tuple[float, Vec]:
    """theta = q2 + q3 + q4 (step 4: the angle about n from a vector across n to where the wrist's turns take it,
    read in the frame made for q1) and w (step 5)."""
    v = rotate(h5, t6, across_5) if t6 is not None else across_5
    x, y = dot(v, frame[0]), dot(v, frame[1])
    theta = math.atan2(y, x) if math.hypot(x, y) >= DEGENERATE else 0.0
    arm = turned(k.wrist_arm, math.cos(theta), math.sin(theta))
    return theta, (reach[0] - arm[0], reach[1] - arm[1], reach[2] - arm[2])


def _elbow_of(elbow: tuple[float, float, float], to_w: Vec, n: Vec) -> tuple[list[float], bool] | None:
    """q3 (step 5): subproblem 3 with the distance of w from axis 2, its constants (``elbow``) made once per arm."""
    phase, radius, constant = elbow
    if radius < DEGENERATE:
        return None
    along = dot(to_w, n)
    return angles(phase, radius, -(dot(to_w, to_w) - along * along) / 2.0 - constant)


_UR_WRIST = (
    "wrist singularity: axis 6 is parallel to axes 2, 3 and 4, so joint 6 and the three turn the tool alike: a "
    "continuum of solutions, one given"
)
_SPHERICAL = (
    "wrist singularity: axes 4 and 6 are in line, so joints 4 and 6 turn the tool alike: a continuum of solutions, "
    "one given"
)


def _spherical_wrist(form: ClosedForm, r_g: Mat, p_g: Vec) -> list[Branch]:
    """The module's chain for a spherical wrist: joints 2 and 3 parallel (:func:`_parallel_arm`, on floats), or
    axes 1 and 2 meeting (:func:`_meeting_shoulder`)."""
    if form.parallel is not None:
        return _parallel_arm(form, r_g, p_g)
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
    q6_across: tuple[Vec, Vec, Vec]  # (axis 6's across vector turned by q5, :func:`.subproblems.parts`)
    q6_normal: tuple[Vec, Vec, Vec]  # (h6 x across, turned by q5)


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
        parts(h5, across6),
        parts(h5, cross(h6, across6)),
    )


def _wrist_on_floats(w: _WristPair, v: Vec, v6: Vec) -> tuple[list[Vec], bool] | None:
    """Step 2 as :func:`_wrist` gives it (q4, q5, q6 for each middle vector, and whether exact), on floats; None
    where subproblem 1 has no direction (the wrist singularity: :func:`_wrist` answers it)."""
    c, (x4, y4, z4), (xa, ya, za), (xn, yn, zn) = w.cosine, w.h4, w.across, w.normal
    a1 = x4 * v[0] + y4 * v[1] + z4 * v[2]
    on5 = w.h5[0] * v[0] + w.h5[1] * v[1] + w.h5[2] * v[2]
    on_across, on_normal = xa * v[0] + ya * v[1] + za * v[2], xn * v[0] + yn * v[1] + zn * v[2]
    alpha = (a1 - c * w.along) / (1.0 - c * c)
    beta = (w.along - c * a1) / (1.0 - c * c)
    rest = w.square - alpha * alpha - beta * beta - 2.0 * alpha * beta * c
    square = v[0] * v[0] + v[1] * v[1] + v[2] * v[2]
    scale_ = max(w.square, square, 1e-300)
    exact = rest >= -TANGENT * scale_ and abs(w.square - square) <= TANGENT * scale_
    gamma = math.sqrt(max(rest, 0.0) / w.sine2)
    on4 = alpha + beta * c  # (the middle vector's part along h4)
    middle2 = alpha * alpha + beta * beta + 2.0 * alpha * beta * c + gamma * gamma * w.sine2
    if math.sqrt(max(middle2 - on4 * on4, 0.0)) < DEGENERATE or math.sqrt(max(square - a1 * a1, 0.0)) < DEGENERATE:
        return None
    p0, p1, p2 = parts(w.h4, v6)
    found = []
    for g in (gamma, -gamma) if gamma > 0 else (gamma,):
        q5 = math.atan2(alpha * w.q5_sine[0] + g * w.q5_sine[1], alpha * w.q5_cosine[0] + g * w.q5_cosine[1])
        q4 = math.atan2(beta * on_across + g * on_normal, alpha * a1 + beta * on5 + g * on_across - on4 * a1)
        c4, s4, c5, s5 = math.cos(q4), -math.sin(q4), math.cos(q5), math.sin(q5)
        y0, y1, y2 = turned((p0, p1, p2), c4, s4)  # (v6 turned back by q4)
        (e0, e1, e2), (f0, f1, f2) = turned(w.q6_across, c5, s5), turned(w.q6_normal, c5, s5)
        found.append((q4, q5, math.atan2(y0 * f0 + y1 * f1 + y2 * f2, y0 * e0 + y1 * e1 + y2 * e2)))
    return found, exact


class _ParallelArm(NamedTuple):
    """What every target of a spherical-wrist arm with joints 2 and 3 parallel shares (made once per arm)."""

    shoulder: _Shoulder
    elbow: tuple[float, float, float]  # (q3's phase, radius and constant term, as the three-parallel-axes arm's)
    forearm: tuple[Vec, Vec, Vec]  # (the wrist centre from axis 3's point, turned by q3)
    upper: Vec  # (axis 3's point from axis 2's)
    across: Vec  # (a unit vector at right angles to axis 6)
    wrist: _WristPair


@functools.cache
def _parallel_arm_constants(form: ClosedForm) -> _ParallelArm:
    h, p, n = form.lines.axes, form.lines.points, form.parallel or form.lines.axes[1]
    fore, back = perpendicular(sub(form.wrist, p[2]), n), scale(-1.0, perpendicular(sub(p[2], p[1]), n))
    phase, radius, constant = _fixed(back, h[2], fore)
    elbow = (phase, radius, constant - (dot(fore, fore) + dot(back, back)) / 2.0)
    forearm, across = parts(h[2], sub(form.wrist, p[2])), _across(h[5])
    return _ParallelArm(_shoulder(form, n), elbow, forearm, sub(p[2], p[1]), across, _wrist_pair(h, across))


def _parallel_arm(form: ClosedForm, r_g: Mat, p_g: Vec) -> list[Branch]:
    """Step 1 as the three parallel axes' shoulder and elbow (q1 from n . E1^-1(G W) = n . W, q3 from the wrist
    centre's distance from axis 2, q2 turning it onto), then step 2 on axis 6 and a vector across it turned back
    by joints 1 to 3 (Rodrigues on floats: no matrices made)."""
    k = _parallel_arm_constants(form)
    h, p = form.lines.axes, form.lines.points
    f = sub(add(apply(r_g, form.wrist), p_g), p[0])
    shoulder, f_parts = _shoulder_roots(k.shoulder, h[0], sub(p[0], p[1]), f)
    g6, a6 = parts(h[0], apply(r_g, h[5])), parts(h[0], apply(r_g, k.across))
    found: list[Branch] = []
    for i, t1 in enumerate(_roots(shoulder)):
        c1, s1 = math.cos(t1), math.sin(t1)
        reach = turned(f_parts, c1, s1)  # (the wrist centre turned by t1 = -q1 about axis 1, from axis 2's point)
        elbow = _elbow_of(k.elbow, reach, form.parallel or h[1])
        back6, back_across = turned(g6, c1, s1), turned(a6, c1, s1)
        for m, q3 in enumerate(_roots(elbow)):
            c3, s3 = math.cos(q3), math.sin(q3)
            e3 = turned(k.forearm, c3, s3)
            q2 = subproblem_1(h[1], (e3[0] + k.upper[0], e3[1] + k.upper[1], e3[2] + k.upper[2]), reach) or 0.0
            c2, s2 = math.cos(q2), -math.sin(q2)
            v = turn(h[2], c3, -s3, turn(h[1], c2, s2, back6))
            v6 = turn(h[2], c3, -s3, turn(h[1], c2, s2, back_across))
            exact = _exact(shoulder) and _exact(elbow)
            fast = _wrist_on_floats(k.wrist, v, v6)
            if fast is None:
                for j, values, wrist_exact, singular in _wrist(h, v, v6, k.across):
                    found.append(Branch((-t1, q2, q3, *values), (i, m, j), exact and wrist_exact, singular))
                continue
            for j, (q4, q5, q6) in enumerate(fast[0]):
                found.append(Branch((-t1, q2, q3, q4, q5, q6), (i, m, j), exact and fast[1]))
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
