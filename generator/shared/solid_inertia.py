"""Rigid-body facts used by several stages, written once: the inertia of solid primitives and what makes a tensor
physical.

The xacro macro library mirrors the formulas (``macros/inertia.xacro``: box_inertial, cylinder_inertial,
sphere_inertial, capsule_inertial, hollow_cylinder_inertial; ``macros/_inc/checks.xacro``: the tensor checks)
operation for operation, so that the direct emitter and xacro write the same bits; a change here is a change there.
The sum of parts (:func:`combine`) has no twin: composite links are written as plain XML.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Literal

from .transforms import exact_product

if TYPE_CHECKING:
    import numpy as np

TOLERANCE = 1e-9  # relative: a principal moment <= this * the largest is zero; the triangle inequality's slack

TensorProblem = Literal["not-positive-definite", "triangle-inequality"]


def box_moments(mass: float, x: float, y: float, z: float) -> tuple[float, float, float]:
    """(Ixx, Iyy, Izz) of a solid box of edges x, y, z about its centre: m/12 (b^2 + c^2)."""
    return mass / 12.0 * (y * y + z * z), mass / 12.0 * (x * x + z * z), mass / 12.0 * (x * x + y * y)


def cylinder_moments(mass: float, radius: float, length: float) -> tuple[float, float]:
    """(axial, transverse) moments of a solid cylinder about its centre: m r^2 / 2 and m (3 r^2 + l^2) / 12."""
    return mass * radius * radius / 2.0, mass * (3.0 * radius * radius + length * length) / 12.0


def wheel_moments(mass: float, radius: float, width: float, axle: str) -> tuple[float, float, float]:
    """(Ixx, Iyy, Izz) of a wheel, a solid cylinder of ``width`` spinning about the link axis ``axle`` (x, y or z):
    the cylinder's axial moment about the axle, its transverse moment about the other two (macros/wheel.xacro writes
    the same)."""
    axial, transverse = cylinder_moments(mass, radius, width)
    xx, yy, zz = (axial if axis == axle else transverse for axis in "xyz")
    return xx, yy, zz


def sphere_moment(mass: float, radius: float) -> float:
    """The moment of a solid sphere about any axis through its centre: 2 m r^2 / 5."""
    return 2.0 * mass * radius * radius / 5.0


def capsule_volume(radius: float, length: float) -> float:
    """A capsule's volume: a cylinder of ``length`` between the centres of two hemispheres, pi r^2 l + 4/3 pi r^3."""
    return math.pi * radius * radius * length + 4.0 / 3.0 * math.pi * radius**3


def capsule_moments(mass: float, radius: float, length: float) -> tuple[float, float]:
    """(axial, transverse) moments of a solid capsule about its centre, its mass shared by volume between the
    cylinder (m_c) and the two hemispheres (m_s, a sphere's worth):
    axial m_c r^2 / 2 + 2 m_s r^2 / 5; transverse m_c (l^2 / 12 + r^2 / 4) + m_s (2 r^2 / 5 + l^2 / 4 + 3 l r / 8)
    (each hemisphere's moment about its flat face's diameter is 2 (m_s / 2) r^2 / 5; its centre of mass lies 3 r / 8
    from that face, so moving it to the capsule's centre adds (m_s / 2) ((l / 2 + 3 r / 8)^2 - (3 r / 8)^2))."""
    cylinder = math.pi * radius * radius * length
    sphere = 4.0 / 3.0 * math.pi * radius**3
    m_c = mass * cylinder / (cylinder + sphere)
    m_s = mass * sphere / (cylinder + sphere)
    r2, l2 = radius * radius, length * length  # (the macro writes (radius * radius): the same operations)
    axial = m_c * r2 / 2.0 + 2.0 * m_s * r2 / 5.0
    transverse = m_c * (l2 / 12.0 + r2 / 4.0) + m_s * (2.0 * r2 / 5.0 + l2 / 4.0 + 3.0 * length * radius / 8.0)
    return axial, transverse


def tube_volume(inner: float, outer: float, length: float) -> float:
    """A hollow cylinder's volume: pi (R^2 - r^2) l."""
    return math.pi * (outer * outer - inner * inner) * length


def tube_moments(mass: float, inner: float, outer: float, length: float) -> tuple[float, float]:
    """(axial, transverse) moments of a hollow cylinder about its centre: m (R^2 + r^2) / 2 and
    m (3 (R^2 + r^2) + l^2) / 12."""
    squares = outer * outer + inner * inner
    return mass * squares / 2.0, mass * (3.0 * squares + length * length) / 12.0


def combine(parts: Sequence[tuple[float, np.ndarray, np.ndarray, np.ndarray]]) -> tuple[float, np.ndarray, np.ndarray]:
    """The mass, centre of mass and inertia tensor (about that centre, in the common frame's axes) of rigidly joined
    parts, each (mass, centre of mass in the common frame, rotation of its tensor's axes into the common frame,
    tensor about its own centre of mass): each tensor rotated (R I R^T), then moved to the common centre of mass by
    the parallel-axis theorem (m (|d|^2 E - d d^T), d from the common centre to the part's)."""
    import numpy as np  # (heavy: numpy)

    total = math.fsum(mass for mass, _, _, _ in parts)
    center = sum((mass * np.asarray(com, dtype=float) for mass, com, _, _ in parts), np.zeros(3)) / total
    result = np.zeros((3, 3))
    for mass, com, rotation, inertia in parts:
        offset = np.asarray(com, dtype=float) - center
        # (exact_product, not @: the same bits on every machine, as the generated file must be)
        turned = exact_product(exact_product(rotation, inertia), np.asarray(rotation, dtype=float).T)
        squared = math.fsum(v * v for v in offset)
        result += turned + mass * (squared * np.eye(3) - np.outer(offset, offset))
    return total, center, (result + result.T) / 2.0


PLACEHOLDERS = (1.0, 0.1, 0.01, 1e-3, 1e-4, 1e-5, 1e-6)  # kg*m^2: the round k of a k * identity placeholder tensor


def is_placeholder(ixx: float, ixy: float, ixz: float, iyy: float, iyz: float, izz: float) -> bool:
    """Whether six tensor entries are a round multiple of the identity (check's I005; I009 leaves them to it)."""
    return ixy == ixz == iyz == 0 and ixx == iyy == izz and ixx in PLACEHOLDERS


def tensor(ixx: float, ixy: float, ixz: float, iyy: float, iyz: float, izz: float) -> np.ndarray:
    """The symmetric 3x3 matrix of six inertia entries."""
    import numpy as np  # (heavy: numpy)

    return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]], dtype=float)


UNSCALED = 1e140  # LAPACK scales a matrix whose norm is beyond 1e146 or below 1e-146 (and rounds): those go to it


def principal_moments(entries: Sequence[Sequence[float]]) -> list[list[float]]:
    """The principal moments (ascending) of many tensors given as (ixx, ixy, ixz, iyy, iyz, izz). A diagonal tensor's
    are its diagonal, sorted (LAPACK's eigvalsh gives exactly those bits while it need not scale the tensor:
    tests/shared/test_solid_inertia.py); the others go in one batched eigvalsh (per-tensor numpy calls cost ten times
    more on robots with many links), so that a robot whose tensors are all diagonal, as primitives in their own axes
    are, needs no numpy. Entries must be finite."""
    moments: list[list[float]] = []
    full: list[int] = []
    for k, (ixx, ixy, ixz, iyy, iyz, izz) in enumerate(entries):
        largest = max(abs(ixx), abs(iyy), abs(izz))
        plain = ixy == ixz == iyz == 0 and 1 / UNSCALED <= largest <= UNSCALED
        moments.append(sorted((ixx, iyy, izz)) if plain else [])
        if not moments[-1]:
            full.append(k)
    if full:
        import numpy as np  # (heavy: numpy)

        rows = np.array([entries[k] for k in full], dtype=float).reshape(-1, 6)
        batch = rows[:, [0, 1, 2, 1, 3, 4, 2, 4, 5]].reshape(-1, 3, 3)
        for k, found in zip(full, np.linalg.eigvalsh(batch).tolist(), strict=True):
            moments[k] = found
    return moments


def moments_problem(moments: Iterable[float], rel: float = TOLERANCE) -> TensorProblem | None:
    """Why principal moments cannot be a rigid body's about its centre of mass: a moment not above ``rel`` times the
    largest (not positive definite), or one above the sum of the other two beyond ``rel`` of the trace (the triangle
    inequality); None when they can."""
    values = list(moments)
    scale = max(max(abs(m) for m in values), 1e-300)
    if min(values) <= rel * scale:
        return "not-positive-definite"
    total = sum(values)
    if any(m > total - m + rel * total for m in values):
        return "triangle-inequality"
    return None


def format_moments(values: Iterable[float]) -> str:
    return ", ".join(f"{v:.6g}" for v in values)


def describe_problem(problem: TensorProblem, moments: Iterable[float]) -> str:
    """The sentence that says what is wrong with principal moments (the spec's validation and check both say it)."""
    if problem == "not-positive-definite":
        return (
            f"the inertia tensor is not positive definite (principal moments {format_moments(moments)}); "
            "every principal moment must be > 0"
        )
    return (
        f"the inertia tensor violates the triangle inequality (principal moments {format_moments(moments)}); "
        "each must be at most the sum of the other two"
    )


def tensor_problem(matrix: np.ndarray, rel: float = TOLERANCE) -> str | None:
    """Why ``matrix`` cannot be a rigid body's inertia about its centre of mass (a sentence), or None when it can."""
    import numpy as np  # (heavy: numpy)

    if not np.all(np.isfinite(matrix)):
        return "the inertia tensor has entries that are not finite"
    moments = np.linalg.eigvalsh(matrix).tolist()
    problem = moments_problem(moments, rel)
    return None if problem is None else describe_problem(problem, moments)


def entries_problem(ixx: float, ixy: float, ixz: float, iyy: float, iyz: float, izz: float) -> str | None:
    """:func:`tensor_problem` of six inertia entries (numbers), without numpy when the tensor is diagonal."""
    entries = (ixx, ixy, ixz, iyy, iyz, izz)
    if not all(math.isfinite(v) for v in entries):
        return "the inertia tensor has entries that are not finite"
    moments = principal_moments([entries])[0]
    problem = moments_problem(moments)
    return None if problem is None else describe_problem(problem, moments)
