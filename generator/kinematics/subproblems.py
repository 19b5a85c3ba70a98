"""The Paden-Kahan subproblems on 3-vectors, the pieces closed-form inverse kinematics is made of (Murray, Li and
Sastry, *A Mathematical Introduction to Robotic Manipulation*, 1994, section 3.2.2; Elias and Wen, *IK-Geo*, 2022,
write subproblem 4 in this form).

Vectors are tuples of three floats and rotations 3x3 tuples of rows: the solvers run thousands of these per second,
and plain floats are ten times faster than numpy on three numbers. ``k`` is always a unit axis through the origin;
an angle turns right-handed about it (Rodrigues).

Each subproblem returns its angles with a flag ``exact``: False when the data admit no exact solution and the angle
returned is the nearest (a target a hair out of reach, a tangency within rounding): the caller verifies such a
branch on the robot and polishes it or drops it.
"""

from __future__ import annotations

import math

Vec = tuple[float, float, float]
Mat = tuple[Vec, Vec, Vec]

TANGENT = 1e-9  # a cosine this far beyond 1 is a tangency (one double root), not out of reach
DEGENERATE = 1e-12  # a vector this short has no direction: its subproblem has a continuum of answers


def dot(a: Vec, b: Vec) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a: Vec, b: Vec) -> Vec:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def add(a: Vec, b: Vec) -> Vec:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a: Vec, b: Vec) -> Vec:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def scale(s: float, a: Vec) -> Vec:
    return (s * a[0], s * a[1], s * a[2])


def norm(a: Vec) -> float:
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def perpendicular(a: Vec, k: Vec) -> Vec:
    """The part of ``a`` at right angles to the unit axis ``k``."""
    along = dot(a, k)
    return (a[0] - along * k[0], a[1] - along * k[1], a[2] - along * k[2])


def rotate(k: Vec, angle: float, a: Vec) -> Vec:
    """``a`` turned by ``angle`` about the unit axis ``k`` (Rodrigues)."""
    c, s = math.cos(angle), math.sin(angle)
    kxa = cross(k, a)
    along = dot(k, a) * (1.0 - c)
    return (
        a[0] * c + kxa[0] * s + k[0] * along,
        a[1] * c + kxa[1] * s + k[1] * along,
        a[2] * c + kxa[2] * s + k[2] * along,
    )


def turn(k: Vec, c: float, s: float, a: Vec) -> Vec:
    """``a`` turned about the unit axis ``k`` by the angle of cosine ``c`` and sine ``s`` (:func:`rotate` on floats,
    for an angle whose cosine and sine are already made)."""
    k0, k1, k2 = k
    a0, a1, a2 = a
    along = (k0 * a0 + k1 * a1 + k2 * a2) * (1.0 - c)
    return (
        a0 * c + (k1 * a2 - k2 * a1) * s + k0 * along,
        a1 * c + (k2 * a0 - k0 * a2) * s + k1 * along,
        a2 * c + (k0 * a1 - k1 * a0) * s + k2 * along,
    )


def rotation(k: Vec, angle: float) -> Mat:
    """The matrix of :func:`rotate` (rows)."""
    c, s = math.cos(angle), math.sin(angle)
    v = 1.0 - c
    x, y, z = k
    return (
        (c + x * x * v, x * y * v - z * s, x * z * v + y * s),
        (y * x * v + z * s, c + y * y * v, y * z * v - x * s),
        (z * x * v - y * s, z * y * v + x * s, c + z * z * v),
    )


def apply(m: Mat, a: Vec) -> Vec:
    return (dot(m[0], a), dot(m[1], a), dot(m[2], a))


def apply_transposed(m: Mat, a: Vec) -> Vec:
    return (
        m[0][0] * a[0] + m[1][0] * a[1] + m[2][0] * a[2],
        m[0][1] * a[0] + m[1][1] * a[1] + m[2][1] * a[2],
        m[0][2] * a[0] + m[1][2] * a[1] + m[2][2] * a[2],
    )


def multiply(a: Mat, b: Mat) -> Mat:
    columns = ((b[0][0], b[1][0], b[2][0]), (b[0][1], b[1][1], b[2][1]), (b[0][2], b[1][2], b[2][2]))
    return (
        (dot(a[0], columns[0]), dot(a[0], columns[1]), dot(a[0], columns[2])),
        (dot(a[1], columns[0]), dot(a[1], columns[1]), dot(a[1], columns[2])),
        (dot(a[2], columns[0]), dot(a[2], columns[1]), dot(a[2], columns[2])),
    )


def transposed(m: Mat) -> Mat:
    return ((m[0][0], m[1][0], m[2][0]), (m[0][1], m[1][1], m[2][1]), (m[0][2], m[1][2], m[2][2]))


def subproblem_1(k: Vec, p: Vec, q: Vec) -> float | None:
    """The angle about ``k`` that turns ``p`` onto ``q`` (their parts at right angles to ``k``: the nearest when
    those differ in length); None when ``p`` lies along ``k`` (every angle does). (Written out on floats: the
    closed forms call it a dozen times a target.)"""
    k0, k1, k2 = k
    p0, p1, p2 = p
    q0, q1, q2 = q
    a = k0 * p0 + k1 * p1 + k2 * p2
    b = k0 * q0 + k1 * q1 + k2 * q2
    x0, x1, x2 = p0 - a * k0, p1 - a * k1, p2 - a * k2
    y0, y1, y2 = q0 - b * k0, q1 - b * k1, q2 - b * k2
    if math.sqrt(x0 * x0 + x1 * x1 + x2 * x2) < DEGENERATE or math.sqrt(y0 * y0 + y1 * y1 + y2 * y2) < DEGENERATE:
        return None
    sine = k0 * (x1 * y2 - x2 * y1) + k1 * (x2 * y0 - x0 * y2) + k2 * (x0 * y1 - x1 * y0)
    return math.atan2(sine, x0 * y0 + x1 * y1 + x2 * y2)


def subproblem_4(h: Vec, k: Vec, p: Vec, d: float) -> tuple[list[float], bool] | None:
    """The angles t with h . rotate(k, t, p) = d: two, one (a tangency), or, out of reach, the one that comes
    nearest (``exact`` False); None when the left side does not depend on t (every t, or none, does).

    h . R p = A cos t + B sin t + C with A = h.p - (h.k)(k.p), B = h.(k x p), C = (h.k)(k.p)."""
    along = dot(k, p)
    hk = dot(h, k)
    a = dot(h, p) - hk * along
    b = dot(h, cross(k, p))
    radius = math.hypot(a, b)
    if radius < DEGENERATE:
        return None
    return angles(math.atan2(b, a), radius, d - hk * along)


def angles(phase: float, radius: float, value: float) -> tuple[list[float], bool]:
    """The angles t with ``radius`` cos(t - ``phase``) = ``value`` (``radius`` above DEGENERATE), as
    :func:`subproblem_4` gives them: its last step, apart for the solvers that make ``phase`` and ``radius`` once
    per arm."""
    cosine = value / radius
    if -1.0 <= cosine <= 1.0:
        spread = math.acos(cosine)
        return ([phase + spread, phase - spread] if spread > 0.0 else [phase]), True
    exact = abs(cosine) <= 1.0 + TANGENT
    return [phase if cosine > 0 else phase + math.pi], exact


def parts(k: Vec, a: Vec) -> tuple[Vec, Vec, Vec]:
    """``a``'s part along the unit axis ``k``, its part across it and k x a: ``a`` turned by t about ``k`` is the
    first plus cos t times the second plus sin t times the third (Rodrigues, for a vector turned many times)."""
    along = dot(k, a)
    return scale(along, k), (a[0] - along * k[0], a[1] - along * k[1], a[2] - along * k[2]), cross(k, a)


def flat_parts(k: Vec, a: Vec) -> tuple[float, ...]:
    """:func:`parts` as nine floats, for solvers that unpack them into locals (a vector turned in a hot loop)."""
    (x, y, z), (u, v, w), (r, s, t) = parts(k, a)
    return (x, y, z, u, v, w, r, s, t)


def turned(parts_: tuple[Vec, Vec, Vec], c: float, s: float) -> Vec:
    """The vector of :func:`parts` ``parts_`` turned by the angle of cosine ``c`` and sine ``s``."""
    (a0, a1, a2), (b0, b1, b2), (d0, d1, d2) = parts_
    return (a0 + c * b0 + s * d0, a1 + c * b1 + s * d1, a2 + c * b2 + s * d2)


def subproblem_3(k: Vec, p: Vec, q: Vec, distance: float) -> tuple[list[float], bool] | None:
    """The angles t with |rotate(k, t, p) - q| = ``distance`` (``p`` and ``q`` from a point on the axis), as
    :func:`subproblem_4`: |R p - q|^2 = |p|^2 + |q|^2 - 2 q . R p."""
    return subproblem_4(q, k, p, (dot(p, p) + dot(q, q) - distance * distance) / 2.0)


def subproblem_2(k1: Vec, k2: Vec, p: Vec, q: Vec) -> tuple[list[tuple[float, float]], bool] | None:
    """The angle pairs (t1, t2) with rotate(k1, t1, rotate(k2, t2, p)) = q about two axes that meet at the origin
    and are not parallel: two, one, or, when no exact pair exists, the nearest (``exact`` False); None when a
    continuum does (``p`` along ``k2`` and ``q`` along ``k1``, or the axes parallel)."""
    c = dot(k1, k2)
    across = cross(k1, k2)
    sine2 = dot(across, across)
    if sine2 < DEGENERATE:
        return None
    a1, a2 = dot(k1, q), dot(k2, p)
    alpha = (a1 - c * a2) / (1.0 - c * c)
    beta = (a2 - c * a1) / (1.0 - c * c)
    rest = dot(p, p) - alpha * alpha - beta * beta - 2.0 * alpha * beta * c
    scale_ = max(dot(p, p), dot(q, q), 1e-300)
    exact = rest >= -TANGENT * scale_ and abs(dot(p, p) - dot(q, q)) <= TANGENT * scale_
    gamma = math.sqrt(max(rest, 0.0) / sine2)
    base = add(scale(alpha, k1), scale(beta, k2))
    middles = [add(base, scale(gamma, across)), add(base, scale(-gamma, across))] if gamma > 0 else [base]
    pairs = []
    for middle in middles:
        t2 = subproblem_1(k2, p, middle)
        t1 = subproblem_1(k1, middle, q)
        if t1 is None or t2 is None:
            return None
        pairs.append((t1, t2))
    return pairs, exact
