"""An ``ik`` target as the user writes it: ``X,Y,Z`` then the orientation's numbers in the form ``--rotation``
names (the forms ``pose --rotation`` prints and an origin takes: rpy by default, a quaternion as tf2_echo prints it,
a rotation vector as UR's controllers give it, axis and angle, a matrix, or Euler angles of any sequence), read into
a 4x4 pose. Each value may carry a unit (``100mm``, ``30deg``) where it is a length or an angle."""

from __future__ import annotations

import math
from typing import Any

from ..errors import XacrokitError

COUNTS = {"rpy": 3, "quat_xyzw": 4, "quat_wxyz": 4, "rotvec": 3, "axis_angle": 4, "matrix": 9, "points": 9}
ANGLES = {"rpy": (0, 1, 2), "axis_angle": (3,)}  # (which of the form's numbers are angles: units allowed)
ORTHONORMAL = 1e-6  # R^T R this close to the identity, as an origin's matrix
MAX_TURNS = 1000  # an angle of more turns has no digits left for the turn it makes


NAMES = {
    "rpy": ("roll", "pitch", "yaw"),
    "quat_xyzw": ("qx", "qy", "qz", "qw"),
    "quat_wxyz": ("qw", "qx", "qy", "qz"),
    "rotvec": ("rx", "ry", "rz"),
    "axis_angle": ("ax", "ay", "az", "angle"),
    "matrix": tuple(f"r{i}{j}" for i in (1, 2, 3) for j in (1, 2, 3)),
    "points": tuple(f"{point}{axis}" for point in "pqr" for axis in "xyz"),
}


def header_names(form: str) -> list[str]:
    """The names of a --targets file's columns for the orientation ``form``: x, y, z then the form's own (Euler
    angles: a1, a2, a3 in the sequence's order)."""
    return ["x", "y", "z", *NAMES.get(form, ("a1", "a2", "a3"))]


def forms_said() -> str:
    return f"{', '.join(COUNTS)} (P, Q, R), or Euler angles (euler:XYZ, intrinsic:ZYZ, extrinsic:xyz)"


def target_pose(text: str, form: str, *, flag: str = "--to") -> Any:
    """The 4x4 pose of ``text`` (``X,Y,Z`` or ``X,Y,Z,`` and the orientation's numbers in ``form``; a checked
    ``--rotation`` value) and whether it gives an orientation.

    Raises:
        XacrokitError: the numbers' count, a value that does not parse or is beyond what xacrokit takes, or an
            orientation that is no rotation (a quaternion or axis of length 0, a matrix not orthonormal), said with
            ``flag`` and the text.
    """
    import numpy as np  # (heavy: numpy)

    from ..shared.units import UnitError, bound_problem, parse_quantity  # (start-up: loaded when it runs)
    from .kinematics_commands import euler_sequence  # (start-up: loaded when it runs)

    parts = [p.strip() for p in text.split(",")]
    sequence = euler_sequence(form)
    count = 3 if sequence else COUNTS[form]
    if len(parts) not in (3, 3 + count):
        raise XacrokitError(
            f"{flag} {text!r}: give X,Y,Z (m), or X,Y,Z and the {count} numbers of the orientation in the form "
            f"--rotation names ({form}; forms: {forms_said()})"
        )
    angles = (0, 1, 2) if sequence else ANGLES.get(form, ())
    try:
        values = [
            parse_quantity(p, "length" if k < 3 else "angle" if k - 3 in angles else "number")
            for k, p in enumerate(parts)
        ]
    except UnitError as exc:
        raise XacrokitError(f"{flag} {text!r}: {exc}") from None
    beyond = next((b for b in (bound_problem("length", v) for v in values[:3]) if b is not None), None)
    if beyond is not None or not all(math.isfinite(v) for v in values):
        raise XacrokitError(f"{flag} {text!r}: {beyond or 'not finite numbers'}")
    pose = np.eye(4)
    pose[:3, 3] = values[:3]
    if len(values) > 3:
        problem = _rotation_problem(form, values[3:])
        if problem:
            raise XacrokitError(f"{flag} {text!r}: {problem}")
        pose[:3, :3] = _rotation(form, sequence, values[3:])
    return pose


def _number_kind(form: str) -> str:
    """The kind of an orientation's number that is no angle: the points' coordinates are lengths (units allowed)."""
    return "length" if form == "points" else "number"


def _rotation_problem(form: str, numbers: list[float]) -> str:
    """Why ``numbers`` are no rotation in ``form`` ("" when they are one)."""
    import numpy as np  # (heavy: numpy)

    from ..shared.transforms import points_problem  # (heavy: numpy)

    if form == "points":
        p, q, r = numbers[0:3], numbers[3:6], numbers[6:9]
        problem = points_problem(((p[0], p[1], p[2]), (q[0], q[1], q[2]), (r[0], r[1], r[2])))
        return f"the points P, Q, R give no frame: {problem[1]}" if problem else ""

    if form in ("quat_xyzw", "quat_wxyz", "axis_angle"):
        direction = numbers[:3] if form == "axis_angle" else numbers
        length = math.hypot(*direction)
        if not 1e-6 <= length <= 1e6:
            what = "axis" if form == "axis_angle" else "quaternion"
            return f"its {what} has length {length:.3g}: give one of length 1"
    if form in ("rotvec", "axis_angle"):  # (rpy and Euler angles of any size turn by their sine and cosine)
        largest = abs(numbers[3]) if form == "axis_angle" else math.hypot(*numbers)
        if largest > MAX_TURNS * math.tau:
            return f"an angle of {largest:.3g} rad is more than {MAX_TURNS} turns"
    if form == "matrix":
        matrix = np.array(numbers, dtype=float).reshape(3, 3)
        if np.abs(matrix).max() > 1 + ORTHONORMAL:
            return "a rotation matrix's entries are within [-1, 1]"
        off = float(np.abs(matrix.T @ matrix - np.eye(3)).max())
        if off > ORTHONORMAL:
            return f"the matrix (9 numbers, row by row) is no rotation: R^T R is {off:.3g} from the identity"
        if np.linalg.det(matrix) < 0:
            return "the matrix (9 numbers, row by row) is a reflection: its determinant is -1"
    return ""


def _rotation(form: str, sequence: str | None, numbers: list[float]) -> Any:
    import numpy as np  # (heavy: numpy)

    from ..shared.transforms import rotation_matrix, rpy_matrix  # (heavy: numpy)

    if sequence:
        return rotation_matrix("euler", (sequence, numbers))
    if form == "rpy":
        return rpy_matrix(*numbers)
    if form in ("quat_xyzw", "quat_wxyz"):
        x, y, z, w = numbers if form == "quat_xyzw" else (*numbers[1:], numbers[0])
        length = math.sqrt(x * x + y * y + z * z + w * w)
        return rotation_matrix("quat", (x / length, y / length, z / length, w / length))
    if form == "axis_angle":
        length = math.hypot(*numbers[:3])
        return rotation_matrix("axis_angle", (tuple(v / length for v in numbers[:3]), numbers[3]))
    if form == "rotvec":
        return rotation_matrix("rotvec", tuple(numbers))
    if form == "points":
        return rotation_matrix("points", (tuple(numbers[0:3]), tuple(numbers[3:6]), tuple(numbers[6:9])))
    matrix = np.array(numbers, dtype=float).reshape(3, 3)
    u, _, vt = np.linalg.svd(matrix)  # (the nearest rotation: a matrix rounded to 6 digits is 1e-7 off)
    return u @ vt
