"""Rigid transforms and the DH product, written from the textbook definitions (numpy, 4x4 homogeneous).

They take the model's records (:class:`xacrokit.model.Origin`, :class:`xacrokit.model.DHRow`) by the fields they read
(:class:`Pose`, :class:`DHScrew`): the model sits above ``shared``, which imports nothing of it."""

from __future__ import annotations

import math
import warnings
from collections.abc import Collection, Sequence
from typing import TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
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
    ca, sa = math.cos(alpha), math.sin(alpha)
    # (R(rpy) multiplied out, entry for entry as the macro writes it: rpy_rows)
    (b00, b01, b02), (b10, b11, b12), (b20, b21, b22) = rpy_rows(*rpy)
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


# A rotation at gimbal lock: cos(pitch), the length of the x, y part of the rotation matrix's first column, at or below
# this. Pitch is then +-pi/2 and roll and yaw turn about one axis, so that only their difference is fixed; the forms of
# one such rotation differ in their last bits (up to 2e-15 here), which matrixToRpy turns into any split of roll and
# yaw (issue 42: (1.671, pi/2, 1.571) from a quaternion, (0.183, pi/2, 0.083) from a matrix). At lock canonical_rpy
# writes one split, yaw 0; snapping a rotation to the lock moves it by at most this angle (rad).
GIMBAL_LOCK = 1e-13
# At lock the roll is rounded to this many decimals (at most 5e-13 rad), so that the forms of one rotation, whose
# conversions differ in the last bits, write the same digits. With the snap above, the rpy written is within 1e-12 of
# the rotation given (the tests' bound for every form).
LOCK_ROLL_DECIMALS = 12
# A triple of points is degenerate when Q is within this fraction of the points' size (their largest coordinate) of P,
# or R within it of the line through P and Q: their difference has then lost 9 of a double's 16 digits, and the
# direction made from it is good to about 1e-16 / POINTS_APART rad at worst.
POINTS_APART = 1e-9
_APART = f"{POINTS_APART:g}".replace("e-0", "e-")  # (as the docs write it: 1e-9)
Points = tuple[Sequence[float], Sequence[float], Sequence[float]]


def canonical_rpy(matrix: np.ndarray) -> tuple[float, float, float]:
    """URDF's roll, pitch, yaw (R = Rz(yaw) Ry(pitch) Rx(roll)) of a rotation matrix: pinocchio's ``matrixToRpy``
    (pitch in [-pi/2, pi/2], as URDF reads it) away from gimbal lock; at it (:data:`GIMBAL_LOCK`), one split of the
    turn that roll and yaw share: yaw 0, pitch +-pi/2 exactly, the whole turn in roll (rounded to
    :data:`LOCK_ROLL_DECIMALS` decimals, in (-pi, pi]), so that every form of one rotation writes the same URDF."""
    import numpy as np  # (heavy: numpy)

    rows = np.asarray(matrix, dtype=float)
    if math.hypot(rows[0, 0], rows[1, 0]) <= GIMBAL_LOCK:
        # (at yaw 0, R = Ry(+-pi/2) Rx(roll), whose middle row is (0, cos roll, -sin roll): the rpy definition read)
        roll = round(math.atan2(-rows[1, 2], rows[1, 1]), LOCK_ROLL_DECIMALS)
        half_turn = round(math.pi, LOCK_ROLL_DECIMALS)
        return (half_turn if roll <= -half_turn else roll + 0.0, math.copysign(math.pi / 2, -rows[2, 0]), 0.0)
    import pinocchio  # (heavy: pinocchio, loaded only for an origin given another way than rpy)

    roll, pitch, yaw = (float(v) + 0.0 for v in pinocchio.rpy.matrixToRpy(rows))
    return (roll, pitch, yaw)


def points_problem(points: Points) -> tuple[int, str] | None:
    """Why the triple of points P, Q, R (:func:`points_matrix`) gives no frame, and which point says it (0, 1, 2), or
    None: a coordinate that is not a finite number, Q at P, or R on the line through P and Q (within
    :data:`POINTS_APART` of the points' size, their largest coordinate)."""
    for index, point in enumerate(points):
        if not all(math.isfinite(v) for v in point):
            return index, f"{'PQR'[index]} {list(point)} holds a value that is not a finite number"
    (p, q, r), exponent = _scaled(points)
    size = max(abs(v) for point in points for v in point)
    least = POINTS_APART * math.ldexp(size, -exponent)  # (in the scaled points' units)
    apart = math.hypot(*_minus(q, p))
    if apart <= least:
        said = "at P" if apart == 0.0 else f"{math.ldexp(apart, exponent):.3g} m from P"
        return 1, (
            f"Q is {said}: X runs along Q - P, so Q must stand apart from P (by more than {_APART} of the "
            f"points' largest coordinate, {size:.3g} m)"
        )
    off = math.hypot(*_cross(_unit(_minus(q, p)), _minus(r, p)))
    if off <= least:
        said = "" if off == 0.0 else f" ({math.ldexp(off, exponent):.3g} m from it)"
        return 2, (
            f"R is on the line through P and Q{said}: Z runs along X x (R - P), so R must stand off that line (by "
            f"more than {_APART} of the points' largest coordinate, {size:.3g} m), on the side the frame's +Y points to"
        )
    return None


def points_matrix(points: Points) -> np.ndarray:
    """The rotation of the tf lecture's online converter's triple of points P, Q, R: X along Q - P, Z along
    X x (R - P), Y = Z x X, each normalised, the matrix's columns (the frame's axes in its parent). The points are
    first scaled by a power of two (exactly), so that neither a difference nor a cross product overflows or
    underflows. Raises ValueError with :func:`points_problem`'s reason for a degenerate triple."""
    import numpy as np  # (heavy: numpy)

    problem = points_problem(points)
    if problem is not None:
        raise ValueError(problem[1])
    (p, q, r), _ = _scaled(points)
    x = _unit(_minus(q, p))
    z = _unit(_cross(x, _minus(r, p)))
    y = _unit(_cross(z, x))
    return np.array([[x[k], y[k], z[k]] for k in range(3)])


def _scaled(points: Points) -> tuple[tuple[Vec3, Vec3, Vec3], int]:
    """The points divided by the power of two just above their largest coordinate (an exact scaling: the digits are
    kept, and differences and cross products of the scaled points neither overflow nor underflow), and its exponent."""
    size = max(abs(v) for point in points for v in point)
    exponent = math.frexp(size)[1] if size > 0.0 else 0
    p, q, r = (_vec3([math.ldexp(v, -exponent) for v in point]) for point in points)
    return (p, q, r), exponent


def _vec3(values: Sequence[float]) -> Vec3:
    return (values[0], values[1], values[2])


def _minus(a: Sequence[float], b: Sequence[float]) -> Vec3:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _cross(a: Sequence[float], b: Sequence[float]) -> Vec3:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _unit(a: Vec3) -> Vec3:
    length = math.hypot(*a)
    return (a[0] / length, a[1] / length, a[2] / length)


def rotation_matrix(form: str, value: Any) -> np.ndarray:
    """The rotation matrix of a rotation given in ``form``: ``quat`` (x, y, z, w: ROS's order, of unit length),
    ``axis_angle`` ((unit axis, angle), right-handed), ``rotvec`` (axis x angle), ``matrix``, ``euler`` ((sequence,
    angles): scipy's sequence, upper case intrinsic) or ``points`` ((P, Q, R): :func:`points_matrix`); with
    pinocchio's conversions (Eigen's quaternion and angle-axis, the exponential map) and scipy's for Euler angles."""
    import numpy as np  # (heavy: numpy)
    import pinocchio  # (heavy: pinocchio, loaded only for an origin given another way than rpy)

    if form == "quat":
        return pinocchio.Quaternion(np.array(value, dtype=float)).toRotationMatrix()
    if form == "axis_angle":
        return pinocchio.AngleAxis(value[1], np.array(value[0], dtype=float)).matrix()
    if form == "rotvec":
        return pinocchio.exp3(np.array(value, dtype=float))
    if form == "euler":
        from scipy.spatial.transform import Rotation  # (heavy: scipy)

        return Rotation.from_euler(value[0], value[1]).as_matrix()
    if form == "points":
        return points_matrix(value)
    if form == "matrix":
        return np.array(value, dtype=float)
    raise ValueError(f"no rotation form {form!r}: quat, axis_angle, rotvec, matrix, euler or points")


def rotation_rpy(form: str, value: Any) -> tuple[float, float, float]:
    """URDF's roll, pitch, yaw of a rotation given in ``form`` (:func:`rotation_matrix`), with one split of roll and
    yaw at gimbal lock (:func:`canonical_rpy`)."""
    return canonical_rpy(rotation_matrix(form, value))


def euler_sequence(kind: str, axes: str) -> str:
    """scipy's name of an Euler sequence said explicitly: ``intrinsic`` (about the turning frame's axes) in upper
    case, ``extrinsic`` (about the fixed axes) in lower case, whatever the case ``axes`` is written in."""
    if kind not in ("intrinsic", "extrinsic"):
        raise ValueError(f"an Euler sequence is intrinsic or extrinsic, not {kind!r}")
    return axes.upper() if kind == "intrinsic" else axes.lower()


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


ROTATION_FORM_NAMES = ("rpy", "quat_xyzw", "quat_wxyz", "rotvec", "axis_angle", "matrix", "euler", "points")


def rotation_forms(
    matrix: np.ndarray, *, euler: str = "XYZ", only: Collection[str] = ROTATION_FORM_NAMES
) -> dict[str, Any]:
    """A rotation matrix in the forms an origin takes (those named in ``only``: by default every one), each as an
    origin writes it: rpy (URDF's, pitch in [-pi/2, pi/2], one split at gimbal lock: :func:`canonical_rpy`),
    quat_xyzw and quat_wxyz (w >= 0, by pinocchio: Eigen's quaternion, the twin of :func:`rotation_matrix`'s), rotvec
    (axis x angle, by scipy), axis_angle ({axis, angle}; angle in [0, pi], the axis [0, 0, 1] at angle 0), the matrix,
    euler ({intrinsic: XYZ, angles} or {extrinsic: xyz, angles} for ``euler``, scipy's sequence; scipy's angles:
    within 1e-7 rad of the sequence's own gimbal lock scipy sets the third angle to 0, and they give the rotation to
    that 1e-7 only) and points ({P, Q, R}: P the origin, Q and R one along the frame's X and Y). scipy is loaded only
    for rotvec, axis_angle and euler (a third of a second: ``gen-robot pose`` prints rpy and the quaternion)."""
    import numpy as np  # (heavy: numpy)

    rows = np.asarray(matrix, dtype=float)
    forms: dict[str, Any] = {}
    if "rpy" in only:
        forms["rpy"] = list(canonical_rpy(rows))
    if "quat_xyzw" in only or "quat_wxyz" in only:
        import pinocchio  # (heavy: pinocchio, which the kinematics commands have loaded)

        quat = np.array(pinocchio.Quaternion(rows).normalized().coeffs(), dtype=float)  # (x, y, z, w)
        quat = -quat if quat[3] < 0 else quat
        forms["quat_xyzw"] = [float(v) for v in quat]
        forms["quat_wxyz"] = [float(quat[3]), *map(float, quat[:3])]
    if "rotvec" in only or "axis_angle" in only:
        from scipy.spatial.transform import Rotation  # (heavy: scipy, loaded by the features that turn rotations)

        rotvec = [float(v) for v in Rotation.from_matrix(rows).as_rotvec()]
        angle = math.hypot(*rotvec)
        axis = [v / angle for v in rotvec] if angle > 0.0 else [0.0, 0.0, 1.0]
        forms["rotvec"], forms["axis_angle"] = rotvec, {"axis": axis, "angle": angle}
    if "matrix" in only:
        forms["matrix"] = [[float(v) for v in row] for row in rows]
    if "euler" in only:
        forms["euler"] = {"intrinsic" if euler.isupper() else "extrinsic": euler, "angles": _euler_angles(rows, euler)}
    if "points" in only:
        forms["points"] = {
            "P": [0.0, 0.0, 0.0],
            "Q": [float(v) for v in rows[:, 0]],
            "R": [float(v) for v in rows[:, 1]],
        }
    return {name: forms[name] for name in ROTATION_FORM_NAMES if name in only}


def _euler_angles(rows: np.ndarray, sequence: str) -> list[float]:
    """scipy's Euler angles of a rotation matrix in ``sequence`` (scipy's: upper case intrinsic)."""
    from scipy.spatial.transform import Rotation  # (heavy: scipy, loaded by the features that print rotations)

    with warnings.catch_warnings():  # (scipy warns at gimbal lock, where it sets the third angle to 0: said above)
        warnings.simplefilter("ignore", UserWarning)
        return [float(v) for v in Rotation.from_matrix(rows).as_euler(sequence)]


def rot_x(angle: float) -> np.ndarray:
    import numpy as np  # (heavy: numpy)

    c, s = np.cos(angle), np.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(angle: float) -> np.ndarray:
    import numpy as np  # (heavy: numpy)

    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(angle: float) -> np.ndarray:
    import numpy as np  # (heavy: numpy)

    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rpy_rows(roll: float, pitch: float, yaw: float) -> tuple[Vec3, Vec3, Vec3]:
    """URDF's fixed-axis roll-pitch-yaw: R = Rz(yaw) Ry(pitch) Rx(roll), multiplied out (as :func:`screw_pose`
    writes it), its rows as plain floats: each entry one product of sines and cosines, the same bits on every
    machine, where numpy's ``@`` calls the BLAS, whose kernels (chosen by the processor) round differently in the last
    digit. (Plain floats: generation places a DH arm's joints without loading numpy.)"""
    cr, sr, cp, sp, cy, sy = (
        math.cos(roll),
        math.sin(roll),
        math.cos(pitch),
        math.sin(pitch),
        math.cos(yaw),
        math.sin(yaw),
    )
    return (
        (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
        (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
        (-sp, cp * sr, cp * cr),
    )


def rpy_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """:func:`rpy_rows` as a 3x3 array (the same bits: numpy stores the floats as they are)."""
    import numpy as np  # (heavy: numpy)

    return np.array(rpy_rows(roll, pitch, yaw))


def exact_product(left: np.ndarray, right: np.ndarray) -> np.ndarray:
    """``left @ right`` (matrices or a matrix and a vector), each entry the correctly rounded sum of its products
    (``math.fsum``), so a number written into a generated file is the same on every machine: numpy's ``@`` calls the
    BLAS, whose kernel is chosen by the processor and rounds otherwise in the last digit (a composite link's inertia
    differed between two CI machines). For the small matrices of generation only: it is Python, not BLAS."""
    import numpy as np  # (heavy: numpy)

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
    import numpy as np  # (heavy: numpy)

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
    import numpy as np  # (heavy: numpy)

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
