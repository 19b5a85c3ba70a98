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

import math

from .arm_geometry import THREE_PARALLEL, ClosedForm
from .subproblems import Vec, add, cross, dot, norm, perpendicular, rotate, scale, sub, subproblem_1

UP: Vec = (0.0, 0.0, 1.0)
SLIGHT = 1e-9  # m, or a sine: a side this close to the line has no side


def branch_name(form: ClosedForm, values: tuple[float, ...], roots: tuple[int, int, int]) -> str:
    """'shoulder left, elbow up, wrist no flip' for the branch at ``values`` (the chain's six joints)."""
    h, p = form.lines.axes, form.lines.points

    def placed(point: Vec, joints: int) -> Vec:  # (a point of link `joints` where the values put it)
        for k in reversed(range(joints)):
            point = add(p[k], rotate(h[k], values[k], sub(point, p[k])))
        return point

    shoulder, elbow, wrist = placed(p[1], 1), placed(p[2], 2), placed(form.wrist, 3)
    reach = perpendicular(sub(wrist, p[0]), UP)
    if form.kind == THREE_PARALLEL and form.parallel is not None:
        n = form.parallel
        offset = scale(dot(n, sub(form.wrist, p[0])), rotate(h[0], values[0], n))
        side = _side(dot(offset, cross(UP, reach)), ("left", "right"), roots[0])
    else:
        side = _side(dot(perpendicular(sub(elbow, p[0]), UP), reach), ("front", "back"), roots[0])
    line = sub(wrist, shoulder)
    across = sub(UP, scale(dot(UP, line) / max(dot(line, line), 1e-300), line))
    bend = _side(dot(sub(elbow, shoulder), across) if norm(across) > SLIGHT else 0.0, ("up", "down"), roots[1])
    return f"shoulder {side}, elbow {bend}, wrist {_flip(form, values, roots[2])}"


def _flip(form: ClosedForm, values: tuple[float, ...], root: int) -> str:
    h = form.lines.axes
    along = form.parallel if form.kind == THREE_PARALLEL and form.parallel is not None else h[3]
    singular = subproblem_1(h[4], h[5], along)
    if singular is None:
        return "a" if root == 0 else "b"
    return _side(math.sin(values[4] - singular), ("no flip", "flip"), root)


def _side(measure: float, names: tuple[str, str], root: int) -> str:
    if abs(measure) <= SLIGHT:
        return "a" if root == 0 else "b"
    return names[0] if measure > 0 else names[1]
