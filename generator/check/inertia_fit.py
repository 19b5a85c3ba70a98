"""I008 at a glance: a link drawn by boxes, cylinders and spheres whose inertia is far inside the bounds of
:mod:`.inertia_geometry`, shown so with plain floats (a generated robot's check stage then needs no numpy).

I008 takes, along each of a few directions n, the largest of two ratios: the tensor's moment about n over the mass
times the largest squared distance of the geometry's points from that axis, and its spread along n over the mass times
the largest squared reach along n; a finding when one passes TOLERANCE. A largest value over the points is at least
their mean, so with M the mean of (p - c)(p - c)^T over the same points (c the centre of mass; each primitive's sums
taken in closed form, a sphere's from its own sample points) and S the tensor in the link frame, no direction at all
passes ``SURE * TOLERANCE`` when both

- ``SURE * TOLERANCE * m * (trace(M) I - M) - S`` (the moment against its bound) and
- ``SURE * TOLERANCE * m * M + S - trace(S) / 2 I`` (the spread against its bound)

are positive definite (their Cholesky pivots, with a margin for rounding). Then I008 says nothing, as its full
computation would; otherwise (a mesh, a shape that does not read, a tensor near or past a bound) the full computation
judges the link. So this never changes a verdict or a message: it only spares numpy where nothing is to be said.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping, Sequence

from ..shared.transforms import rpy_rows
from ..shared.urdf_view import Geometry, Link, Origin
from .inertia_geometry import RIM, SPHERE, TOLERANCE
from .urdf_document import number_of, triple_of

Vector = tuple[float, float, float]
Matrix = tuple[Vector, Vector, Vector]

SURE = 0.9  # the glance accepts ratios up to this fraction of TOLERANCE: the full computation is left the rest
PIVOT = 1e-10  # a pivot at least this times the matrix's largest diagonal entry is positive beyond rounding


def fits_at_a_glance(link: Link, origin: Origin | None, mass: float, entries: Sequence[float]) -> bool:
    """Whether I008 says nothing of ``link`` (its inertial at ``origin``, of ``mass`` and tensor ``entries``: ixx,
    ixy, ixz, iyy, iyz, izz), shown without numpy; False when that is not shown so (judge it fully)."""
    placed = [_sums(g) for g in (*link.visuals, *link.collisions) if g.shape is not None]
    if not placed or any(p is None for p in placed) or not (math.isfinite(mass) and mass > 0):
        return False
    turn, centre = _placement(origin)
    count, second = 0, _zero()
    for found in placed:
        assert found is not None
        n, total, squares = found
        # about the centre of mass: sum (p - c)(p - c)^T = sum p p^T - (s c^T + c s^T) + n c c^T, s = sum p
        about = _add(_add(squares, _scaled_m(_sym(_outer(total, centre)), -1.0)), _scaled_m(_outer(centre, centre), n))
        count, second = count + n, _add(second, about)
    mean = _scaled_m(second, 1.0 / count)
    ixx, ixy, ixz, iyy, iyz, izz = entries
    stated = _turned(turn, ((ixx, ixy, ixz), (ixy, iyy, iyz), (ixz, iyz, izz)))
    k = SURE * TOLERANCE * mass
    trace_m = mean[0][0] + mean[1][1] + mean[2][2]
    trace_s = stated[0][0] + stated[1][1] + stated[2][2]
    moment = _add(_scaled_m(_add(_identity(trace_m), _scaled_m(mean, -1.0)), k), _scaled_m(stated, -1.0))
    spread = _add(_add(_scaled_m(mean, k), stated), _identity(-trace_s / 2.0))
    return _definite(moment) and _definite(spread)


def _sums(geometry: Geometry) -> tuple[int, Vector, Matrix] | None:
    """The shape's sample points (those :func:`.inertia_geometry._primitive_solid` takes) placed in the link: their
    count, sum and sum of outer products; None for a mesh, another kind, or sizes that do not read."""
    shape = geometry.shape
    assert shape is not None
    if shape.kind == "box":
        x, y, z = triple_of(shape.get("size"))
        count, total, squares = 8, (0.0, 0.0, 0.0), _diagonal(2 * x * x, 2 * y * y, 2 * z * z)
    elif shape.kind == "cylinder":
        r, length = _number(shape.attributes, "radius"), _number(shape.attributes, "length")
        count, total, squares = 2 * RIM, (0.0, 0.0, 0.0), _diagonal(RIM * r * r, RIM * r * r, RIM * length**2 / 2)
    elif shape.kind == "sphere":
        r = _number(shape.attributes, "radius")
        unit_total, unit_squares = _unit_sphere()
        count, total, squares = SPHERE, _scaled(unit_total, r), _scaled_m(unit_squares, r * r)
    else:
        return None
    turn, shift = _placement(geometry.origin)
    if not all(math.isfinite(v) for v in (*total, *shift, *(v for row in (*squares, *turn) for v in row))):
        return None
    # p = R q + t: sum p = R sum q + n t; sum p p^T = R Q R^T + (R s) t^T + t (R s)^T + n t t^T
    moved = _turn(turn, total)
    squares = _add(_turned(turn, squares), _add(_sym(_outer(moved, shift)), _scaled_m(_outer(shift, shift), count)))
    return count, _plus(moved, _scaled(shift, count)), squares


def _number(attributes: Mapping[str, str], key: str) -> float:
    found = number_of(attributes, key, math.nan)
    return math.nan if found is None else found


@functools.cache
def _unit_sphere() -> tuple[Vector, Matrix]:
    """The sum and sum of outer products of the unit sphere's SPHERE sample points (the Fibonacci lattice of
    :func:`.inertia_geometry._primitive_solid`)."""
    total, squares = (0.0, 0.0, 0.0), _zero()
    for index in range(SPHERE):
        polar = math.acos(1.0 - 2.0 * (index + 0.5) / SPHERE)
        around = math.pi * (1.0 + math.sqrt(5.0)) * (index + 0.5)
        point = (math.cos(around) * math.sin(polar), math.sin(around) * math.sin(polar), math.cos(polar))
        total, squares = _plus(total, point), _add(squares, _outer(point, point))
    return total, squares


def _placement(origin: Origin | None) -> tuple[Matrix, Vector]:
    """An origin's turn and shift in plain floats (the twin of :func:`.inertia_geometry.placement`, which gives
    numpy arrays of the same numbers: R = Rz(yaw) Ry(pitch) Rx(roll), ``shared.transforms.rpy_rows``)."""
    if origin is None:
        return _identity(1.0), (0.0, 0.0, 0.0)
    return rpy_rows(*triple_of(origin.rpy)), triple_of(origin.xyz)


def _definite(matrix: Matrix) -> bool:
    """Whether a symmetric matrix is positive definite beyond rounding: each pivot of its Cholesky factoring at least
    PIVOT times its largest diagonal entry (False for a matrix that does not read)."""
    (a, b, c), (_, e, f), (_, _, i) = matrix
    least = PIVOT * max(abs(a), abs(e), abs(i))
    if not (math.isfinite(least) and least > 0 and a > least):
        return False
    second = e - b * b / a
    if not second > least:
        return False
    across = f - c * b / a
    third = i - c * c / a - across * across / second
    return third > least


def _zero() -> Matrix:
    return _diagonal(0.0, 0.0, 0.0)


def _identity(value: float) -> Matrix:
    return _diagonal(value, value, value)


def _diagonal(x: float, y: float, z: float) -> Matrix:
    return ((x, 0.0, 0.0), (0.0, y, 0.0), (0.0, 0.0, z))


def _plus(a: Vector, b: Vector) -> Vector:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _scaled(a: Vector, k: float) -> Vector:
    return (a[0] * k, a[1] * k, a[2] * k)


def _add(a: Matrix, b: Matrix) -> Matrix:
    return (_plus(a[0], b[0]), _plus(a[1], b[1]), _plus(a[2], b[2]))


def _scaled_m(a: Matrix, k: float) -> Matrix:
    return (_scaled(a[0], k), _scaled(a[1], k), _scaled(a[2], k))


def _outer(a: Vector, b: Vector) -> Matrix:
    return (_scaled(b, a[0]), _scaled(b, a[1]), _scaled(b, a[2]))


def _sym(a: Matrix) -> Matrix:
    """a + a^T."""
    return tuple(tuple(a[i][j] + a[j][i] for j in range(3)) for i in range(3))  # type: ignore[return-value]


def _turn(turn: Matrix, a: Vector) -> Vector:
    return tuple(sum(turn[i][j] * a[j] for j in range(3)) for i in range(3))  # type: ignore[return-value]


def _turned(turn: Matrix, a: Matrix) -> Matrix:
    """turn @ a @ turn^T."""
    left = [[sum(turn[i][k] * a[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    return tuple(  # type: ignore[return-value]
        tuple(sum(left[i][k] * turn[j][k] for k in range(3)) for j in range(3)) for i in range(3)
    )
