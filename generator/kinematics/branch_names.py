"""The names of a closed-form branch, from where the arm's parts are in it, seen in the arm's own frame: *up* is
along axis 1, pointing from axis 1's joint to the shoulder (axis 2's joint) when they are apart along it, else along
the root's z (REP 103); the arm's plane is the plane across the parallel axes 2 and 3 (the elbow's plane):

* shoulder: *left* or *right* for an arm with three parallel axes: the side, seen from axis 1 looking at the wrist,
  to which the shoulder's offset along the parallel axes points; *front* or *back* for a spherical-wrist arm: whether
  the wrist centre is ahead of axis 1 or behind it along the arm's forward direction (across up and axis 2, pointing
  the way the shoulder's offset from axis 1 points, else the way the arm reaches at its zero pose, else the root's x);
* elbow: *up* or *down*: whether the elbow is on up's side of the line from the shoulder (axis 2) to the wrist
  centre, in the arm's plane, or on the other;
* wrist: *flip* or *no flip*: the sign of joint 5's turn from where the wrist is singular (axis 6 along the parallel
  axes, or in line with axis 4): *no flip* when joint 5 is past that in its positive sense.

Each pair of a subproblem's two roots lies on the two sides of its measure (the two shoulders' wrist centres are
ahead and behind, or left and right, as the arm turns about axis 1; the two elbows mirror each other across the line
to the wrist), so two branches of one target never share a name. Where a measure has no side (the wrist centre on
axis 1, the elbow stretched, the line to the wrist along up) the branch is named by the root it took, *a* or *b*.
"""

from __future__ import annotations

import functools
import math
from typing import NamedTuple

from .arm_geometry import THREE_PARALLEL, ClosedForm
from .subproblems import Vec, add, cross, dot, norm, parts, scale, sub, subproblem_1

SLIGHT = 1e-9  # m, or a sine: a side this close to the line has no side
APART = 1e-6  # m per m of the arm's size: parts this far apart along a direction tell its sense


class _Naming(NamedTuple):
    """What naming a branch takes of the arm, made once per arm: the sides are measured in the frame joint 1 turns
    with (where the shoulder stays at axis 2's point; up and axis 2 are the same there at every q1), each measure
    written as a sum over the cosines and sines of the joints that place its parts (:func:`branch_name`)."""

    elbow: tuple[float, float, float]  # (the elbow's measure: 1, c3, s3)
    square: tuple[float, float, float]  # (the line to the wrist's squared length: 1, c3, s3)
    sky: tuple[float, ...]  # (up's side of that line: (1, c2, s2) x (1, c3, s3))
    shoulder: tuple[float, ...]  # (front or back, or the corner's part of left or right: (1, c2, s2) x (1, c3, s3))
    beyond: tuple[tuple[float, ...], ...]  # (left or right: the wrist centre's part, as shoulder's, x (1, c4, s4))
    parallel: bool  # (three parallel axes: left or right)
    singular: float | None  # (joint 5's value where the wrist is singular; None: the wrist has no such value)


def arm_up(form: ClosedForm) -> Vec:
    """Axis 1's direction pointing from its joint to the shoulder's (axis 2's point) when they are apart along it
    (a robot hung from a ceiling has its own up), else the one nearer the root's z, else axis 1 as written."""
    h, p = form.lines.axes, form.lines.points
    for sense in (dot(h[0], sub(p[1], p[0])), h[0][2]):
        if abs(sense) > APART * form.lines.size:
            return h[0] if sense > 0 else scale(-1.0, h[0])
    return h[0]


def arm_forward(form: ClosedForm, up: Vec) -> Vec:
    """The arm's forward direction at q1 = 0: across ``up`` and axis 2 (in the arm's plane), pointing the way the
    shoulder's offset from axis 1 points, else the way the wrist centre lies at the zero pose, else the root's x."""
    h, p = form.lines.axes, form.lines.points
    across = cross(h[1], up)
    length = norm(across)
    if length <= SLIGHT:  # (axis 2 along axis 1: no such arm is recognised; named a and b then)
        return (0.0, 0.0, 0.0)
    across = scale(1.0 / length, across)
    for sense in (dot(across, sub(p[1], p[0])), dot(across, sub(form.wrist, p[0])), across[0]):
        if abs(sense) > APART * form.lines.size:
            return across if sense > 0 else scale(-1.0, across)
    return across


@functools.cache
def _naming(form: ClosedForm) -> _Naming:
    """The measures' constants: with k axis 2, x the upper arm (axis 3's point from axis 2's) and f = x + f3 the
    elbow triangle's far corner from the shoulder turned by joint 3 (f3 = A + c3 B + s3 D, the corner from axis 3's
    point), the corner is w = R2 f and the elbow R2 x; a rotation about k keeps k, so the elbow's measure
    k . (w x R2 x) is k . (f3 x x), and k . (w x up) and a direction's dot with w are f . (R2^T v), R2^T v = va + c2 vb
    - s2 vd (v's parts about k); with three parallel axes, the wrist centre beyond the corner adds R2 R3 R4 (the
    wrist centre from axis 4's point), dotted the same way."""
    h, p = form.lines.axes, form.lines.points
    parallel = form.kind == THREE_PARALLEL and form.parallel is not None
    up = arm_up(form)
    k, x = h[1], sub(p[2], p[1])
    # (the elbow's triangle closes at the wrist centre, fixed to link 3 on axis 4; with three parallel axes, at axis
    # 4's point, the wrist centre (axes 5 and 6 meeting) turning about axis 4 with joint 4)
    a, b, d = parts(h[2], sub(p[3] if parallel else form.wrist, p[2]))
    near = add(a, x)  # (f's part that joint 3 does not turn)
    elbow = (dot(a, cross(x, k)), dot(b, cross(x, k)), dot(d, cross(x, k)))
    square = (dot(near, near) + dot(b, b), 2.0 * dot(b, near), 2.0 * dot(d, near))
    sky = _turned_dots((near, b, d), cross(up, k), k)
    base = sub(p[1], p[0])
    if parallel:
        assert form.parallel is not None  # (parallel says so)
        n = form.parallel
        offset = scale(dot(n, sub(form.wrist, p[0])), n)  # (the shoulder's offset along n, at q1 = 0)
        m = cross(offset, up)  # (o . (up x r) = r . (o x up))
        hand = parts(h[3], sub(form.wrist, p[3]))
        beyond = tuple(tuple(dot(c, v) for c in parts(h[2], mi) for v in hand) for mi in parts(k, m))
        shoulder = (dot(m, base), *_turned_dots((near, b, d), m, k))
    else:
        forward = arm_forward(form, up)
        shoulder, beyond = (dot(forward, base), *_turned_dots((near, b, d), forward, k)), ()
    singular = subproblem_1(h[4], h[5], form.parallel if parallel and form.parallel is not None else h[3])
    return _Naming(elbow, square, sky, shoulder, beyond, parallel, singular)


def _turned_dots(f: tuple[Vec, Vec, Vec], v: Vec, k: Vec) -> tuple[float, ...]:
    """f . (R2^T v) for f = f[0] + c3 f[1] + s3 f[2] and R2^T v = va + c2 vb - s2 vd (v's parts about k): the nine
    dot products, v's part by f's part."""
    return tuple(dot(fi, vi) for vi in parts(k, v) for fi in f)


def branch_name(form: ClosedForm, values: tuple[float, ...], roots: tuple[int, int, int]) -> str:
    """'shoulder left, elbow up, wrist no flip' for the branch at ``values`` (the chain's six joints).

    The parts are placed by joints 2 and 3 only (dot and cross products do not change when all their vectors turn
    alike, and up and axis 2 do not turn with joint 1 in its own frame): the shoulder at axis 2's point P2, the elbow
    at P2 + R2 x, the elbow triangle's far corner at P2 + w (the wrist centre; with three parallel axes, axis 4's
    point, the wrist centre beyond it turned by joint 4 too). Each measure is a sum of :func:`_naming`'s constants
    times the joints' cosines and sines. (Written out on floats: a solve names every branch it gives.)"""
    k = _naming(form)
    c2, s2, c3, s3 = math.cos(values[1]), math.sin(values[1]), math.cos(values[2]), math.sin(values[2])
    t0, t1, t2, t3, t4, t5, t6, t7, t8 = k.sky
    sky = t0 + c3 * t1 + s3 * t2 + c2 * (t3 + c3 * t4 + s3 * t5) - s2 * (t6 + c3 * t7 + s3 * t8)
    g, t0, t1, t2, t3, t4, t5, t6, t7, t8 = k.shoulder
    measure = g + t0 + c3 * t1 + s3 * t2 + c2 * (t3 + c3 * t4 + s3 * t5) - s2 * (t6 + c3 * t7 + s3 * t8)
    if k.parallel:
        measure += _beyond(k.beyond, c2, s2, c3, s3, values[3])
        side = _side(measure, ("left", "right"), roots[0])
    else:
        side = _side(measure, ("front", "back"), roots[0])
    # (which side of the line to the wrist, in the arm's plane: the parts along axis 2 leave k . (w x e) as it is)
    e0, e1, e2 = k.elbow
    elbow = e0 + c3 * e1 + s3 * e2
    q0, q1, q2 = k.square
    square = q0 + c3 * q1 + s3 * q2
    clear = abs(sky) > SLIGHT * math.sqrt(square if square > 0.0 else 0.0)
    bend = _side((elbow if sky > 0 else -elbow) if clear else 0.0, ("up", "down"), roots[1])
    return f"shoulder {side}, elbow {bend}, wrist {_flip(k.singular, values, roots[2])}"


def _beyond(beyond: tuple[tuple[float, ...], ...], c2: float, s2: float, c3: float, s3: float, q4: float) -> float:
    """Three parallel axes: the wrist centre's part of o . (up x r) beyond the corner, R2 R3 R4 h dotted with
    m = o x up as (R3^T R2^T m) . (R4 h): R2^T m's parts (1, c2, -s2), each one's parts about axis 3 (1, c3, -s3),
    each dotted with R4 h's parts (1, c4, s4)."""
    c4, s4 = math.cos(q4), math.sin(q4)
    (a0, a1, a2, b0, b1, b2, d0, d1, d2), (e0, e1, e2, f0, f1, f2, g0, g1, g2), third = beyond
    j0, j1, j2, k0, k1, k2, l0, l1, l2 = third
    first = a0 + c4 * a1 + s4 * a2 + c3 * (b0 + c4 * b1 + s4 * b2) - s3 * (d0 + c4 * d1 + s4 * d2)
    second = e0 + c4 * e1 + s4 * e2 + c3 * (f0 + c4 * f1 + s4 * f2) - s3 * (g0 + c4 * g1 + s4 * g2)
    return (
        first
        + c2 * second
        - s2 * (j0 + c4 * j1 + s4 * j2 + c3 * (k0 + c4 * k1 + s4 * k2) - s3 * (l0 + c4 * l1 + s4 * l2))
    )


def _flip(singular: float | None, values: tuple[float, ...], root: int) -> str:
    if singular is None:
        return "a" if root == 0 else "b"
    return _side(math.sin(values[4] - singular), ("no flip", "flip"), root)


def _side(measure: float, names: tuple[str, str], root: int) -> str:
    if abs(measure) <= SLIGHT:
        return "a" if root == 0 else "b"
    return names[0] if measure > 0 else names[1]
