"""Rigid transforms and the DH product, written from the textbook definitions (numpy, 4x4 homogeneous).

They take the model's records (:class:`xacrokit.model.Origin`, :class:`xacrokit.model.DHRow`) by the fields they read
(:class:`Pose`, :class:`DHScrew`): the model sits above ``shared``, which imports nothing of it."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Protocol

import numpy as np

Vec3 = tuple[float, float, float]


class Pose(Protocol):
    """A pose in a parent frame, as :class:`xacrokit.model.Origin` holds it: xyz in m, rpy in rad."""

    @property
    def xyz(self) -> Vec3: ...

    @property
    def rpy(self) -> Vec3: ...


class DHScrew(Protocol):
    """One DH row, as :class:`xacrokit.model.DHRow` holds it: a, d in m, alpha, theta in rad, and its joint type."""

    @property
    def a(self) -> float: ...

    @property
    def alpha(self) -> float: ...

    @property
    def d(self) -> float: ...

    @property
    def theta(self) -> float: ...

    @property
    def type(self) -> str: ...


def dh_body_end(
    convention: str, a: float, alpha: float, following: tuple[float, float, float] | None
) -> tuple[float, float, float]:
    """Where a DH row's link body ends, in the row's link frame: the next joint's frame origin (the tool frame's for
    the last row, less the tool's own offset). ``following`` is the next row's (a, alpha, d), None for the last row.
    Standard DH puts the row's own a along x; modified DH the next row's a and alpha (the next joint's screw)."""
    end_a, end_alpha = (a, alpha) if convention == "standard" else following[:2] if following else (0.0, 0.0)
    end_d = following[2] if following else 0.0
    return (end_a, -math.sin(end_alpha) * end_d, math.cos(end_alpha) * end_d)


def dh_body_pose(
    end: tuple[float, float, float],
) -> tuple[tuple[float, float, float], tuple[float, float, float], float]:
    """(xyz, rpy, length) of a DH row's body, a cylinder from the link frame's origin to ``end``
    (:func:`dh_body_end`): its centre halfway, its z axis along the segment (pitch, then yaw), its length. The macro
    ``_xacrokit_dh_body`` (macros/dh.xacro) computes the same, operation for operation."""
    end_x, end_y, end_z = end
    length = math.sqrt(end_x * end_x + end_y * end_y + end_z * end_z)
    xyz = (end_x / 2.0 + 0.0, end_y / 2.0 + 0.0, end_z / 2.0 + 0.0)  # (+ 0.0: no -0.0, as the macro)
    rpy = (0.0, math.atan2(math.hypot(end_x, end_y), end_z) + 0.0, math.atan2(end_y, end_x) + 0.0)
    return xyz, rpy, length


def screw_pose(
    a: float, alpha: float, xyz: Sequence[float], rpy: Sequence[float]
) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    """(xyz, rpy) of Tx(a) Rx(alpha) T(xyz, rpy): a pose given in DH frame i, written in the link frame of a
    standard-DH row (DH frame i is the link frame moved by Tx(a) Rx(alpha)). Its twin _xacrokit_origin_after_x_screw
    (macros/_inc/frames.xacro) computes the same: same operations, same order, each number + 0.0 (no -0.0)."""
    x, y, z = xyz
    roll, pitch, yaw = rpy
    ca, sa = math.cos(alpha), math.sin(alpha)
    cr, sr, cp, sp, cy, sy = (
        math.cos(roll),
        math.sin(roll),
        math.cos(pitch),
        math.sin(pitch),
        math.cos(yaw),
        math.sin(yaw),
    )
    b00, b01, b02 = cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr
    b10, b11, b12 = sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr
    b20, b21, b22 = -sp, cp * sr, cp * cr
    r00, r01, r02 = b00, b01, b02
    r10, r11, r12 = ca * b10 - sa * b20, ca * b11 - sa * b21, ca * b12 - sa * b22
    r20 = sa * b10 + ca * b20
    out_yaw = math.atan2(r10, r00)
    out_pitch = math.atan2(-r20, math.hypot(r00, r10))
    out_roll = math.atan2(
        math.sin(out_yaw) * r02 - math.cos(out_yaw) * r12, math.cos(out_yaw) * r11 - math.sin(out_yaw) * r01
    )
    xyz = (a + x + 0.0, ca * y - sa * z + 0.0, sa * y + ca * z + 0.0)
    return xyz, (out_roll + 0.0, out_pitch + 0.0, out_yaw + 0.0)


def rotation_rpy(
    *,
    quaternion: tuple[float, float, float, float] | None = None,
    axis: tuple[float, float, float] | None = None,
    angle: float = 0.0,
    rotvec: tuple[float, ...] | None = None,
    matrix: np.ndarray | None = None,
    euler: tuple[str, tuple[float, float, float]] | None = None,
) -> tuple[float, float, float]:
    """URDF's roll, pitch, yaw of a rotation given as a unit quaternion (x, y, z, w: ROS's order), a unit axis and an
    angle (right-handed), a rotation vector (axis x angle), a rotation matrix, or Euler angles (sequence, angles:
    scipy's names, upper case intrinsic); with pinocchio's conversions (Eigen's quaternion and angle-axis;
    ``matrixToRpy`` gives pitch in [-pi/2, pi/2], as URDF reads it) and scipy's for Euler angles."""
    import pinocchio  # (loaded only for an origin given this way: it takes a quarter of a second)

    if quaternion is not None:
        matrix = pinocchio.Quaternion(np.array(quaternion, dtype=float)).toRotationMatrix()
    elif axis is not None:
        matrix = pinocchio.AngleAxis(angle, np.array(axis, dtype=float)).matrix()
    elif rotvec is not None:
        matrix = pinocchio.exp3(np.array(rotvec, dtype=float))
    elif euler is not None:
        from scipy.spatial.transform import Rotation  # (heavy: scipy)

        matrix = Rotation.from_euler(euler[0], euler[1]).as_matrix()
    elif matrix is None:
        raise ValueError("a quaternion, an axis and an angle, a rotation vector, a matrix or Euler angles")
    roll, pitch, yaw = (float(v) + 0.0 for v in pinocchio.rpy.matrixToRpy(matrix))
    return (roll, pitch, yaw)


def matrix_quaternion(matrix: np.ndarray) -> tuple[float, float, float, float]:
    """The unit quaternion (x, y, z, w: ROS's order) of a rotation matrix, by scipy's Rotation (its sign as scipy
    gives it)."""
    from scipy.spatial.transform import Rotation  # (heavy: scipy, loaded by the features that turn rotations)

    x, y, z, w = (float(v) for v in Rotation.from_matrix(matrix).as_quat())
    return x, y, z, w


def rpy_quaternion(rpy: Sequence[float]) -> tuple[float, float, float, float]:
    """The unit quaternion (x, y, z, w) of URDF's fixed-axis roll, pitch, yaw (R = Rz(y) Ry(p) Rx(r): scipy's
    extrinsic 'xyz' Euler angles)."""
    from scipy.spatial.transform import Rotation  # (heavy: scipy)

    x, y, z, w = (float(v) for v in Rotation.from_euler("xyz", [rpy[0], rpy[1], rpy[2]]).as_quat())
    return x, y, z, w


def rotation_forms(matrix: np.ndarray) -> dict[str, list[float] | list[list[float]]]:
    """A rotation matrix in every form the commands print: rpy (URDF's, pitch in [-pi/2, pi/2]), quat_xyzw and
    quat_wxyz (w >= 0), rotvec (axis x angle) and the matrix."""
    import pinocchio  # (heavy: loaded by the features that print rotations)
    from scipy.spatial.transform import Rotation

    quat = np.array(matrix_quaternion(matrix))
    quat = -quat if quat[3] < 0 else quat
    return {
        "rpy": [float(v) for v in pinocchio.rpy.matrixToRpy(matrix)],
        "quat_xyzw": [float(v) for v in quat],
        "quat_wxyz": [float(quat[3]), *map(float, quat[:3])],
        "rotvec": [float(v) for v in Rotation.from_matrix(matrix).as_rotvec()],
        "matrix": [[float(v) for v in row] for row in matrix],
    }


def rot_x(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rpy_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """URDF's fixed-axis roll-pitch-yaw: R = Rz(yaw) Ry(pitch) Rx(roll), multiplied out (as :func:`screw_pose`
    writes it): each entry one product of sines and cosines, the same bits on every machine, where numpy's ``@``
    calls the BLAS, whose kernels (chosen by the processor) round differently in the last digit."""
    cr, sr, cp, sp, cy, sy = (
        math.cos(roll),
        math.sin(roll),
        math.cos(pitch),
        math.sin(pitch),
        math.cos(yaw),
        math.sin(yaw),
    )
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def exact_product(left: np.ndarray, right: np.ndarray) -> np.ndarray:
    """``left @ right`` (matrices or a matrix and a vector), each entry the correctly rounded sum of its products
    (``math.fsum``), so a number written into a generated file is the same on every machine: numpy's ``@`` calls the
    BLAS, whose kernel is chosen by the processor and rounds otherwise in the last digit (a composite link's inertia
    differed between two CI machines). For the small matrices of generation only: it is Python, not BLAS."""
    a, b = np.asarray(left, dtype=float), np.asarray(right, dtype=float)
    columns = b.reshape(len(b), -1)
    result = np.array(
        [
            [math.fsum(x * y for x, y in zip(row, column, strict=True)) for column in columns.T]
            for row in a.reshape(-1, len(b))
        ]
    )
    return result.reshape(*a.shape[:-1], *b.shape[1:])


def transform(rotation: np.ndarray, translation: Sequence[float]) -> np.ndarray:
    result = np.eye(4)
    result[:3, :3] = rotation
    result[:3, 3] = translation
    return result


def origin_transform(origin: Pose) -> np.ndarray:
    return transform(rpy_matrix(*origin.rpy), origin.xyz)


def dh_step(row: DHScrew, q: float, convention: str) -> np.ndarray:
    """One DH row at joint value q.

    standard: Rz(theta) Tz(d) Tx(a) Rx(alpha); modified: Rx(alpha) Tx(a) Rz(theta) Tz(d). q adds to theta (revolute,
    continuous) or d (prismatic).
    """
    theta, d = row.theta, row.d
    if row.type in ("revolute", "continuous"):
        theta += q
    elif row.type == "prismatic":
        d += q
    screw_z = transform(rot_z(theta), (0.0, 0.0, 0.0)) @ transform(np.eye(3), (0.0, 0.0, d))
    screw_x = transform(np.eye(3), (row.a, 0.0, 0.0)) @ transform(rot_x(row.alpha), (0.0, 0.0, 0.0))
    return screw_z @ screw_x if convention == "standard" else screw_x @ screw_z


def dh_chain(rows: Sequence[DHScrew], q: Sequence[float], convention: str, base: Pose, tool: Pose) -> np.ndarray:
    """Pose of the tool frame in the arm's parent: base origin, the DH rows at joint values q, the tool offset."""
    result = origin_transform(base)
    for row, value in zip(rows, q, strict=True):
        result = result @ dh_step(row, value, convention)
    return result @ origin_transform(tool)
