"""The names of a closed-form branch, from where the arm's parts are in it (the root's z is up, REP 103):

* shoulder: *left* or *right* for an arm with three parallel axes: the side, seen from axis 1 looking at the wrist,
  to which the shoulder's offset along the parallel axes points; *front* or *back* for a spherical-wrist arm: whether
  the elbow is on the wrist's side of axis 1 or reaches over the back;
* elbow: *up* or *down*: whether the elbow is above or below the line from the shoulder (axis 2) to the wrist centre;
* wrist: *flip* or *no flip*: the sign of joint 5's turn from where the wrist is singular (axis 6 along the parallel
  axes, or in line with axis 4): *no flip* when joint 5 is past that in its positive sense.

Where a name has no meaning (the wrist right above the shoulder, a shoulder without offset) the branch is named by
the root it took, *a* or *b*.
"""

from __future__ import annotations

import functools
import math
from typing import NamedTuple

from .arm_geometry import THREE_PARALLEL, ClosedForm
from .subproblems import Vec, dot, flat_parts, sub, subproblem_1

UP: Vec = (0.0, 0.0, 1.0)
SLIGHT = 1e-9  # m, or a sine: a side this close to the line has no side


class _Naming(NamedTuple):
    """What naming a branch takes of the arm, made once per arm: the sides are measured in the frame joint 1 turns
    with (where the shoulder stays at axis 2's point), up turned back by q1 instead of the arm by it."""

    up: tuple[float, ...]  # (up, turned by -q1 about axis 1: its parts, flat)
    upper: tuple[float, ...]  # (axis 3's point from axis 2's, turned by q2)
    fore: tuple[float, ...]  # (the wrist centre from axis 3's point, turned by q3)
    axis_2: Vec
    upper_arm: Vec  # (axis 3's point from axis 2's)
    base: Vec  # (axis 2's point from axis 1's)
    offset: Vec | None  # (three parallel axes: the shoulder's offset along n, at q1 = 0)
    singular: float | None  # (joint 5's value where the wrist is singular; None: the wrist has no such value)


@functools.cache
def _naming(form: ClosedForm) -> _Naming:
    h, p = form.lines.axes, form.lines.points
    offset = None
    if form.kind == THREE_PARALLEL and form.parallel is not None:
        n = form.parallel
        k = dot(n, sub(form.wrist, p[0]))
        offset = (k * n[0], k * n[1], k * n[2])
    along = form.parallel if form.kind == THREE_PARALLEL and form.parallel is not None else h[3]
    return _Naming(
        flat_parts(h[0], UP),
        flat_parts(h[1], sub(p[2], p[1])),
        flat_parts(h[2], sub(form.wrist, p[2])),
        h[1],
        sub(p[2], p[1]),
        sub(p[1], p[0]),
        offset,
        subproblem_1(h[4], h[5], along),
    )


def branch_name(form: ClosedForm, values: tuple[float, ...], roots: tuple[int, int, int]) -> str:
    """'shoulder left, elbow up, wrist no flip' for the branch at ``values`` (the chain's six joints).

    The parts are placed by joints 2 and 3 only, and up turned back by joint 1 (dot and cross products do not change
    when all their vectors turn alike): the shoulder at axis 2's point P2, the elbow at P2 + e, the wrist centre at
    P2 + w. (Written out on floats: a solve names every branch it gives.)"""
    k = _naming(form)
    c, s = math.cos(values[0]), -math.sin(values[0])
    a0, a1, a2, b0, b1, b2, d0, d1, d2 = k.up
    u0, u1, u2 = a0 + c * b0 + s * d0, a1 + c * b1 + s * d1, a2 + c * b2 + s * d2
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
    r0, r1, r2 = w0 + b0, w1 + b1, w2 + b2  # (the wrist centre from axis 1's point)
    if k.offset is not None:
        o0, o1, o2 = k.offset
        measure = o0 * (u1 * r2 - u2 * r1) + o1 * (u2 * r0 - u0 * r2) + o2 * (u0 * r1 - u1 * r0)
        side = _side(measure, ("left", "right"), roots[0])
    else:
        x0, x1, x2 = e0 + b0, e1 + b1, e2 + b2  # (the elbow from axis 1's point)
        measure = x0 * r0 + x1 * r1 + x2 * r2 - (x0 * u0 + x1 * u1 + x2 * u2) * (r0 * u0 + r1 * u1 + r2 * u2)
        side = _side(measure, ("front", "back"), roots[0])
    ratio = (u0 * w0 + u1 * w1 + u2 * w2) / max(w0 * w0 + w1 * w1 + w2 * w2, 1e-300)
    c0, c1, c2 = u0 - ratio * w0, u1 - ratio * w1, u2 - ratio * w2  # (up, across the line to the wrist)
    large = math.sqrt(c0 * c0 + c1 * c1 + c2 * c2) > SLIGHT
    bend = _side(e0 * c0 + e1 * c1 + e2 * c2 if large else 0.0, ("up", "down"), roots[1])
    return f"shoulder {side}, elbow {bend}, wrist {_flip(k.singular, values, roots[2])}"


def _flip(singular: float | None, values: tuple[float, ...], root: int) -> str:
    if singular is None:
        return "a" if root == 0 else "b"
    return _side(math.sin(values[4] - singular), ("no flip", "flip"), root)


def _side(measure: float, names: tuple[str, str], root: int) -> str:
    if abs(measure) <= SLIGHT:
        return "a" if root == 0 else "b"
    return names[0] if measure > 0 else names[1]
