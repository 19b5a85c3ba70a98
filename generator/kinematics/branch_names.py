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
from .subproblems import Vec, cross, dot, flat_parts, norm, scale, sub, subproblem_1

SLIGHT = 1e-9  # m, or a sine: a side this close to the line has no side
APART = 1e-6  # m per m of the arm's size: parts this far apart along a direction tell its sense


class _Naming(NamedTuple):
    """What naming a branch takes of the arm, made once per arm: the sides are measured in the frame joint 1 turns
    with (where the shoulder stays at axis 2's point; up and axis 2 are the same there at every q1)."""

    up: Vec  # (along axis 1, away from the base: :func:`arm_up`)
    upper: tuple[float, ...]  # (axis 3's point from axis 2's, turned by q2)
    fore: tuple[float, ...]  # (the elbow triangle's far corner from axis 3's point, turned by q3)
    hand: tuple[float, ...] | None  # (three parallel axes: the wrist centre from axis 4's point, turned by q4)
    axis_3: Vec
    axis_2: Vec
    upper_arm: Vec  # (axis 3's point from axis 2's)
    base: Vec  # (axis 2's point from axis 1's)
    offset: Vec | None  # (three parallel axes: the shoulder's offset along n, at q1 = 0)
    forward: Vec  # (across up and axis 2: :func:`arm_forward`)
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
    h, p = form.lines.axes, form.lines.points
    offset = None
    if form.kind == THREE_PARALLEL and form.parallel is not None:
        n = form.parallel
        k = dot(n, sub(form.wrist, p[0]))
        offset = (k * n[0], k * n[1], k * n[2])
    along = form.parallel if form.kind == THREE_PARALLEL and form.parallel is not None else h[3]
    up = arm_up(form)
    # (the elbow's triangle closes at the wrist centre, fixed to link 3 on axis 4; with three parallel axes, at axis
    # 4's point, the wrist centre (axes 5 and 6 meeting) turning about axis 4 with joint 4)
    corner = p[3] if offset is not None else form.wrist
    return _Naming(
        up,
        flat_parts(h[1], sub(p[2], p[1])),
        flat_parts(h[2], sub(corner, p[2])),
        flat_parts(h[3], sub(form.wrist, p[3])) if offset is not None else None,
        h[2],
        h[1],
        sub(p[2], p[1]),
        sub(p[1], p[0]),
        offset,
        arm_forward(form, up),
        subproblem_1(h[4], h[5], along),
    )


def branch_name(form: ClosedForm, values: tuple[float, ...], roots: tuple[int, int, int]) -> str:
    """'shoulder left, elbow up, wrist no flip' for the branch at ``values`` (the chain's six joints).

    The parts are placed by joints 2 and 3 only (dot and cross products do not change when all their vectors turn
    alike, and up and axis 2 do not turn with joint 1 in its own frame): the shoulder at axis 2's point P2, the elbow
    at P2 + e, the elbow triangle's far corner at P2 + w (the wrist centre; with three parallel axes, axis 4's point,
    the wrist centre beyond it turned by joint 4 too). (Written out on floats: a solve names every branch it gives.)"""
    k = _naming(form)
    u0, u1, u2 = k.up
    c2, s2 = math.cos(values[1]), math.sin(values[1])
    a0, a1, a2, b0, b1, b2, d0, d1, d2 = k.upper
    e0, e1, e2 = a0 + c2 * b0 + s2 * d0, a1 + c2 * b1 + s2 * d1, a2 + c2 * b2 + s2 * d2
    c, s = math.cos(values[2]), math.sin(values[2])
    a0, a1, a2, b0, b1, b2, d0, d1, d2 = k.fore
    (x0, x1, x2), (k0, k1, k2) = k.upper_arm, k.axis_2
    f0, f1, f2 = a0 + c * b0 + s * d0 + x0, a1 + c * b1 + s * d1 + x1, a2 + c * b2 + s * d2 + x2
    along = (k0 * f0 + k1 * f1 + k2 * f2) * (1.0 - c2)  # (turned by q2: Rodrigues)
    w0 = f0 * c2 + (k1 * f2 - k2 * f1) * s2 + k0 * along
    w1 = f1 * c2 + (k2 * f0 - k0 * f2) * s2 + k1 * along
    w2 = f2 * c2 + (k0 * f1 - k1 * f0) * s2 + k2 * along
    b0, b1, b2 = k.base
    if k.offset is not None and k.hand is not None:  # (the wrist centre: the corner, and joint 4's turn beyond it)
        t0, t1, t2 = _beyond(k, values[3], c, s, c2, s2)
        r0, r1, r2 = w0 + t0 + b0, w1 + t1 + b1, w2 + t2 + b2  # (the wrist centre from axis 1's point)
        o0, o1, o2 = k.offset
        measure = o0 * (u1 * r2 - u2 * r1) + o1 * (u2 * r0 - u0 * r2) + o2 * (u0 * r1 - u1 * r0)
        side = _side(measure, ("left", "right"), roots[0])
    else:
        g0, g1, g2 = k.forward
        side = _side(g0 * (w0 + b0) + g1 * (w1 + b1) + g2 * (w2 + b2), ("front", "back"), roots[0])
    # (which side of the line to the wrist, in the arm's plane: the parts along axis 2 leave n . (w x v) as it is)
    elbow = k0 * (w1 * e2 - w2 * e1) + k1 * (w2 * e0 - w0 * e2) + k2 * (w0 * e1 - w1 * e0)
    sky = k0 * (w1 * u2 - w2 * u1) + k1 * (w2 * u0 - w0 * u2) + k2 * (w0 * u1 - w1 * u0)
    clear = abs(sky) > SLIGHT * math.sqrt(w0 * w0 + w1 * w1 + w2 * w2)
    bend = _side((elbow if sky > 0 else -elbow) if clear else 0.0, ("up", "down"), roots[1])
    return f"shoulder {side}, elbow {bend}, wrist {_flip(k.singular, values, roots[2])}"


def _beyond(k: _Naming, q4: float, c3: float, s3: float, c2: float, s2: float) -> Vec:
    """The wrist centre from axis 4's point, turned by joints 4, 3 and 2 (three parallel axes; ``c3``, ``s3``: joint
    3's cosine and sine, ``c2``, ``s2`` joint 2's). (Rodrigues written out twice: a solve names every branch.)"""
    assert k.hand is not None  # (only called with one)
    c, s = math.cos(q4), math.sin(q4)
    a0, a1, a2, b0, b1, b2, d0, d1, d2 = k.hand
    v0, v1, v2 = a0 + c * b0 + s * d0, a1 + c * b1 + s * d1, a2 + c * b2 + s * d2
    (h0, h1, h2), (n0, n1, n2) = k.axis_3, k.axis_2
    along = (h0 * v0 + h1 * v1 + h2 * v2) * (1.0 - c3)
    t0 = v0 * c3 + (h1 * v2 - h2 * v1) * s3 + h0 * along
    t1 = v1 * c3 + (h2 * v0 - h0 * v2) * s3 + h1 * along
    t2 = v2 * c3 + (h0 * v1 - h1 * v0) * s3 + h2 * along
    along = (n0 * t0 + n1 * t1 + n2 * t2) * (1.0 - c2)
    return (
        t0 * c2 + (n1 * t2 - n2 * t1) * s2 + n0 * along,
        t1 * c2 + (n2 * t0 - n0 * t2) * s2 + n1 * along,
        t2 * c2 + (n0 * t1 - n1 * t0) * s2 + n2 * along,
    )


def _flip(singular: float | None, values: tuple[float, ...], root: int) -> str:
    if singular is None:
        return "a" if root == 0 else "b"
    return _side(math.sin(values[4] - singular), ("no flip", "flip"), root)


def _side(measure: float, names: tuple[str, str], root: int) -> str:
    if abs(measure) <= SLIGHT:
        return "a" if root == 0 else "b"
    return names[0] if measure > 0 else names[1]
