"""The units pass: every length, angle and mass of a schema-valid spec converted to an SI float, each value that does
not parse reported where it stands, and plain-number angles of many turns (degrees written without ``deg``) and lengths
beyond 10 m (millimetres written without ``mm``) noted."""

from __future__ import annotations

import itertools
import math
from typing import TYPE_CHECKING, Any

from ..errors import SpecError
from ..load import PathKey, RawSpec
from ..shared.materials import MATERIALS, find_material, material_key
from ..shared.transforms import euler_sequence, points_problem, rotation_rpy
from ..shared.units import Kind, UnitError, bound_problem, parse_quantity, plain_number
from ..shared.value_text import did_you_mean
from .bodies import bodies, geometries, joint_types, parts
from .physics import AXIS_LENGTHS, implausible

if TYPE_CHECKING:
    pass

# A plain-number angle beyond this many turns is most likely degrees: one turn for an orientation or a position, two
# for a joint's range (multi-turn joints exist; a range beyond two turns written in radians is rarer than degrees left
# unmarked).
_TURNS = {"position": 1, "range": 2}

# the ways an origin may give its orientation (one at a time; docs/spec.md's table has one rotation in each)
ORIENTATIONS = ("rpy", "quat", "quat_wxyz", "rotvec", "axis_angle", "matrix", "euler", "points")
# The most turns an orientation's angle, a pose's position or a mimic's offset may make: beyond, a double's digits no
# longer say where it points (the next double after 1e300 rad is 1e284 rad further) and a value in the wrong unit is
# the likelier story. A joint's range is not bounded so (a limit of 1e16 stands for none in some URDFs).
ANGLE_TURNS = 1000
ORTHONORMAL = 1e-6  # how far a rotation matrix's R^T R may be from the identity (a calibration's 7 digits pass)
QUATERNION_LENGTHS = (1e-6, 1e6)  # a quaternion's length that can be normalised without losing its direction
# The Euler sequences an origin takes: scipy's Rotation.from_euler with three angles, three of x, y, z with no two
# consecutive alike (two turns in a row about one axis are one turn), all upper case (intrinsic, about the turning
# frame's axes) or all lower case (extrinsic, about the fixed axes). The schemas' `sequence` patterns list the same
# (tests/validate/test_validate_euler.py holds them equal).
EULER_SEQUENCES = tuple(
    "".join(axes).lower() if lower else "".join(axes)
    for lower in (False, True)
    for axes in itertools.product("XYZ", repeat=3)
    if axes[0] != axes[1] != axes[2]
)
# The twelve sequences of axes (six Tait-Bryan, three axes; six proper Euler, the first axis again last), as
# `euler: {intrinsic: ZYZ}` and `euler: {extrinsic: xyz}` name them, in either case: the key says the kind.
EULER_AXES = tuple(sequence for sequence in EULER_SEQUENCES if sequence.isupper())
EULER_KINDS = ("sequence", "intrinsic", "extrinsic")  # (the keys of an euler mapping that name its sequence: one)

# A plain-number length beyond this is most likely millimetres: no link, offset or DH length of a robot is 10 m (a
# length written with a unit, '12 m', is taken as meant).
LONGEST = 10.0

# The quantities held directly in the mapping of an arm row and of a wheel.
_ROW: tuple[tuple[str, Kind], ...] = (
    ("a", "length"),
    ("d", "length"),
    ("alpha", "angle"),
    ("theta", "angle"),
    ("mass", "mass"),
    ("radius", "length"),
)
_WHEEL: tuple[tuple[str, Kind], ...] = (("radius", "length"), ("width", "length"), ("mass", "mass"))
# The lengths of the shapes other than a box (whose size is a list) and a mesh (whose scale is a plain factor).
_SHAPE_LENGTHS = (
    ("cylinder", ("radius", "length")),
    ("sphere", ("radius",)),
    ("capsule", ("radius", "length")),
    ("tube", ("inner_radius", "outer_radius", "length")),
)


def _is_range(path: PathKey) -> bool:
    """Whether ``path`` (to a value) is a joint's limit or soft limit: a range, not a position or an orientation."""
    return path[0] != "poses" and len(path) >= 2 and path[-2] in ("limit", "safety_controller")


# a kind's SI unit and a value of it with a unit, for a value that does not parse as one
_EXAMPLES = {
    "angle": ("rad", "an angle", "90 deg"),
    "length": ("m", "a length", "150 mm"),
    "mass": ("kg", "a mass", "500 g"),
}


def unit_problem(said: str, kind: Kind) -> str:
    """The units' message for a value that does not parse, with what would (when it does not say so already)."""
    if " expected " in f" {said} " or "units:" in said or kind not in _EXAMPLES:
        return said
    unit, what, example = _EXAMPLES[kind]
    return f"{said}; expected a number ({unit}) or {what} with its unit, such as {example!r}"


def euler_sequence_problem(sequence: object) -> str:
    """Why ``sequence`` is not one of :data:`EULER_SEQUENCES`, and what is: the schemas' pattern and type errors at an
    ``euler.sequence`` are said in these words."""
    shown = repr(sequence) if not isinstance(sequence, str) or len(sequence) <= 24 else f"{sequence[:16]!r}..."
    if isinstance(sequence, list):
        why = "a list: write its axes together as one word, such as XYZ"
    elif not isinstance(sequence, str):
        kind = "a number" if isinstance(sequence, (int, float)) and not isinstance(sequence, bool) else "not text"
        why = f"{kind}: a sequence is one word of three axes, such as XYZ"
    elif len(sequence) != 3:
        why = f"{len(sequence)} characters: a sequence names three axes, one per angle, written together"
    elif not set(sequence) <= set("xyzXYZ"):
        why = f"{next(c for c in sequence if c not in 'xyzXYZ')!r} is no axis"
    elif not (sequence.isupper() or sequence.islower()):
        why = "it mixes upper and lower case: a sequence is all intrinsic or all extrinsic"
    else:  # (three axes of one case: two alike in a row)
        why = "two turns in a row about one axis are one turn: consecutive axes must differ"
    return (
        f"{shown} is not an Euler sequence ({why}); give three of the axes x, y, z, no two consecutive alike, all "
        "upper case (intrinsic, about the turning frame's axes: XYZ is Rx Ry Rz) or all lower case (extrinsic, about "
        "the fixed axes: xyz is URDF's rpy), e.g. XYZ, ZYX, ZXZ, xyz"
    )


def euler_axes_problem(kind: str, axes: object) -> str:
    """Why ``axes`` under ``euler.intrinsic`` or ``euler.extrinsic`` names none of :data:`EULER_AXES`, and what
    would: the schemas' pattern and type errors there are said in these words."""
    shown = repr(axes) if not isinstance(axes, str) or len(axes) <= 24 else f"{axes[:16]!r}..."
    if not isinstance(axes, str):
        why = "a list: write its axes together as one word, such as ZYZ" if isinstance(axes, list) else "not text"
    elif len(axes) != 3:
        why = f"{len(axes)} characters: a sequence names three axes, one per angle, written together"
    elif not set(axes) <= set("xyzXYZ"):
        why = f"{next(c for c in axes if c not in 'xyzXYZ')!r} is no axis"
    else:
        why = "two turns in a row about one axis are one turn: consecutive axes must differ"
    about = "the turning frame's axes" if kind == "intrinsic" else "the fixed axes"
    return (
        f"{shown} is not an Euler sequence ({why}); {kind}: takes three of the axes x, y, z (either case), no two "
        f"consecutive alike, turned about {about} in order: one of {', '.join(EULER_AXES)}"
    )


def euler_kind_problem(given: dict[str, Any]) -> tuple[str | None, str]:
    """(the key to point at, None for the mapping itself; the message) for an euler mapping that names its sequence
    not exactly once (:data:`EULER_KINDS`)."""
    named = [key for key in given if key in EULER_KINDS]
    ways = (
        "intrinsic: XYZ (about the turning frame's axes: the tf lecture's R = Rx Ry Rz), extrinsic: xyz (about the "
        "fixed axes: URDF's rpy) or sequence: XYZ (scipy's: upper case intrinsic, lower case extrinsic)"
    )
    if not named:
        return None, f"euler needs its sequence, said one way: {ways}"
    said = " and ".join(f"{key}: {given[key]}" for key in named)
    return named[1], f"euler names its sequence once ({said} given): {ways}, not two of them"


class Quantities:
    """Converts every quantity of a schema-valid spec to SI, collecting located errors.

    The loaded data is only read: ``data`` is a copy in which the containers on the way to a converted value are new
    and everything else is shared with ``raw.data`` (a spec written in SI floats throughout is not copied at all).
    Nothing downstream changes the data.
    """

    def __init__(self, raw: RawSpec) -> None:
        self.raw = raw
        self.errors: list[SpecError] = []
        self.warnings: list[SpecError] = []
        self._changes: dict[PathKey, dict[str | int, Any]] = {}  # container path -> key -> SI value (an rpy: a list)
        self._count = 0
        self._built: tuple[int, Any] = (0, raw.data)

    @property
    def data(self) -> Any:
        """The spec with the quantities converted so far."""
        if self._built[0] != self._count:
            self._built = (self._count, with_values(self.raw.data, self._changes))
        return self._built[1]

    def convert(self, container: Any, key: str | int, path: PathKey, kind: Kind, *, scale: bool = True) -> None:
        """Convert ``container[key]`` to SI (``scale=False``: no warning for a length beyond a robot's parts, such as a
        sensor's range, and no bound on an angle, such as a sensor's)."""
        if isinstance(container, dict) and key not in container:
            return
        value = container[key]
        given = type(value) is float and math.isfinite(value) and (value != 0.0 or math.copysign(1.0, value) > 0)
        if given:
            converted = value  # already SI: what parse_quantity would return
        else:
            try:
                converted = parse_quantity(value, kind) + 0.0  # (+ 0.0: a -0.0 in the spec is written 0.0)
            except UnitError as exc:
                self.errors.append(self.raw.error((*path, key), unit_problem(str(exc), kind)))
                return
        if self._bound(value, converted, kind, (*path, key), scale=scale) and scale:
            self._scale_note(value, kind, (*path, key))
        if not given:
            self._changes.setdefault(path, {})[key] = converted
            self._count += 1

    def _bound(self, written: Any, value: float, kind: Kind, path: PathKey, *, scale: bool) -> bool:
        """Whether ``value`` (SI; ``written`` as the spec gave it) is within what xacrokit takes; if not, the error is
        said."""
        beyond = bound_problem(kind, value)
        if beyond is None and kind == "angle" and scale and not _is_range(path) and abs(value) > ANGLE_TURNS * math.tau:
            shown = f"{written.strip()!r} is {value!r} rad, " if isinstance(written, str) else f"{value!r} rad is "
            beyond = (
                f"{shown}{abs(value) / math.tau:.3g} turns, beyond the {ANGLE_TURNS} turns an angle may make here: a "
                "double's digits no longer say where it points (a value in the wrong unit?)"
            )
        if beyond is not None:
            self.errors.append(self.raw.error(path, beyond))
        return beyond is None

    def _scale_note(self, value: Any, kind: Kind, path: PathKey) -> None:
        """A warning for a plain number that looks written in the wrong unit: an angle of many turns (degrees?), a
        length beyond a robot's parts (millimetres?)."""
        plain = value if type(value) in (int, float) else plain_number(value) if isinstance(value, str) else None
        if plain is None:
            return
        if kind == "angle" and abs(plain) > _TURNS["range" if _is_range(path) else "position"] * math.tau:
            what = "limit" if _is_range(path) else "angle"
            self.warnings.append(
                self.raw.error(
                    path,
                    f"{what} {plain:g} rad is {abs(plain) / math.tau:.3g} turns; "
                    f"if you meant degrees, write '{plain:g} deg'",
                )
            )
        elif kind == "length" and abs(plain) > LONGEST:
            self.warnings.append(
                self.raw.error(
                    path,
                    f"length {plain:g} m is longer than any part of a robot ({LONGEST:g} m); if you meant "
                    f"millimetres, write '{plain:g} mm'",
                )
            )

    def origin(self, holder: dict[str, Any], key: str, path: PathKey) -> None:
        origin = holder.get(key)
        if not isinstance(origin, dict):
            return
        for index in range(len(origin.get("xyz", []))):
            self.convert(origin["xyz"], index, (*path, key, "xyz"), "length")
        for index in range(len(origin.get("rpy", []))):
            self.convert(origin["rpy"], index, (*path, key, "rpy"), "angle")
        given = [name for name in ORIENTATIONS if name in origin]
        if len(given) > 1:
            self.errors.append(
                self.raw.error(
                    (*path, key, given[1]),
                    f"an origin gives one orientation: {given[0]} or {given[1]}, not both ({', '.join(ORIENTATIONS)} "
                    "each say it whole)",
                )
            )
        elif given == ["quat"]:
            self._quaternion(origin["quat"], (*path, key))
        elif given == ["quat_wxyz"]:
            w, x, y, z = origin["quat_wxyz"]
            self._quaternion([x, y, z, w], (*path, key), field="quat_wxyz", written=origin["quat_wxyz"])
        elif given == ["axis_angle"]:
            self._axis_angle(origin["axis_angle"], (*path, key))
        elif given == ["rotvec"]:
            self._rotvec(origin["rotvec"], (*path, key))
        elif given == ["matrix"]:
            self._matrix(origin["matrix"], (*path, key))
        elif given == ["euler"]:
            self._euler(origin["euler"], (*path, key))
        elif given == ["points"]:
            self._points(origin["points"], (*path, key))

    def _rotvec(self, rotvec: list[float], path: PathKey) -> None:
        """``rotvec: [rx, ry, rz]`` (axis x angle, rad) to rpy; an angle beyond ANGLE_TURNS turns is refused (1e300
        rad has no digits left for the turn it makes)."""
        angle = math.sqrt(math.fsum(v * v for v in rotvec))
        if not angle <= ANGLE_TURNS * math.tau:
            length = math.hypot(*rotvec)  # (its length said without overflow: fsum's squares of 1e200 are inf)
            self.errors.append(
                self.raw.error(
                    (*path, "rotvec"),
                    f"rotvec {rotvec}: an angle of {length:.3g} rad is {length / math.tau:.3g} turns; a rotation "
                    f"vector is the axis times an angle in radians, of at most {ANGLE_TURNS} turns",
                )
            )
            return
        self._set_rpy(path, rotation_rpy("rotvec", tuple(rotvec)))

    def _matrix(self, rows: list[list[float]], path: PathKey) -> None:
        """``matrix:`` (3 rows) to rpy, when it is a rotation: R^T R = I to ORTHONORMAL and det R = +1."""
        import numpy as np  # (heavy: numpy)

        matrix = np.array(rows, dtype=float)
        largest = float(np.abs(matrix).max())
        if largest > 1.0 + ORTHONORMAL:  # (said before R^T R, which a value of 1e200 overflows)
            problem = f"it holds {largest!r}, and a rotation's entries are within [-1, 1]"
        else:
            off = float(np.abs(matrix.T @ matrix - np.eye(3)).max())
            problem = (
                f"R^T R is {off:.3g} from the identity"
                if not off <= ORTHONORMAL
                else "its determinant is -1"
                if not np.linalg.det(matrix) > 0
                else ""
            )
        if problem:
            self.errors.append(
                self.raw.error(
                    (*path, "matrix"),
                    f"not a rotation matrix: {problem} (a rotation's rows are orthonormal to {ORTHONORMAL:g}, its "
                    "determinant +1; a mirror is no rotation)",
                )
            )
            return
        self._set_rpy(path, rotation_rpy("matrix", matrix))

    def _euler(self, given: dict[str, Any], path: PathKey) -> None:
        """``euler: {intrinsic | extrinsic: axes, angles}`` (the kind said, the axes in either case) or ``euler:
        {sequence, angles}`` (scipy's names: upper case intrinsic, lower case extrinsic) to rpy."""
        named = [key for key in EULER_KINDS if key in given]
        if len(named) != 1:
            return  # (the schema's oneOf refused it, in the words of euler_kind_problem)
        kind, axes = named[0], given[named[0]]
        sequence = axes if kind == "sequence" else euler_sequence(kind, axes) if isinstance(axes, str) else None
        if sequence not in EULER_SEQUENCES or (kind != "sequence" and axes.upper() not in EULER_AXES):
            return  # (the schema's pattern refused it, in the words of euler_sequence_problem; the passes after run)
        for index in range(3):
            self.convert(given["angles"], index, (*path, "euler", "angles"), "angle")
        angles = self._changes.get((*path, "euler", "angles"), {})
        values = [angles.get(k, given["angles"][k]) for k in range(3)]
        if all(isinstance(v, float) for v in values):
            self._set_rpy(path, rotation_rpy("euler", (sequence, (values[0], values[1], values[2]))))

    def _points(self, given: dict[str, Any], path: PathKey) -> None:
        """``points: {P, Q, R}`` (lengths, with units) to rpy: the tf lecture's converter's frame, X along Q - P,
        Z along X x (R - P), Y = Z x X; a degenerate triple is an error at the point that makes it so."""
        errors = len(self.errors)
        for name in "PQR":
            for index in range(3):  # (no note of a length beyond 10 m: a direction is the same in any unit)
                self.convert(given[name], index, (*path, "points", name), "length", scale=False)
        if len(self.errors) > errors:
            return
        changed = [self._changes.get((*path, "points", name), {}) for name in "PQR"]
        p, q, r = ([float(c.get(k, given[name][k])) for k in range(3)] for name, c in zip("PQR", changed, strict=True))
        problem = points_problem((p, q, r))
        if problem is not None:
            index, why = problem
            self.errors.append(self.raw.error((*path, "points", "PQR"[index]), f"not a frame: {why}"))
            return
        self._set_rpy(path, rotation_rpy("points", (p, q, r)))

    def _quaternion(
        self, quat: list[float], path: PathKey, *, field: str = "quat", written: list[float] | None = None
    ) -> None:
        """``quat: [x, y, z, w]`` (ROS's order) to the rpy URDF writes; one not of unit length is normalised, with a
        warning beyond 1e-6 (a quaternion rounded to a few digits is 1e-4 off: quiet), a zero one refused."""
        norm = math.sqrt(math.fsum(v * v for v in quat))
        if not QUATERNION_LENGTHS[0] <= norm <= QUATERNION_LENGTHS[1]:
            self.errors.append(
                self.raw.error(
                    (*path, field),
                    f"{field} {written or quat} has length {math.hypot(*quat):.3g}: a rotation's quaternion has "
                    f"length 1 (the identity is {'[0, 0, 0, 1]' if field == 'quat' else '[1, 0, 0, 0]'})",
                )
            )
            return
        if abs(norm - 1.0) > 1e-6:
            self.warnings.append(
                self.raw.error(
                    (*path, field),
                    f"{field} {written or quat} has length {norm:.9g}, not 1; normalised ("
                    + ("ROS's order is [x, y, z, w]: is w last?" if field == "quat" else "[w, x, y, z]: is w first?")
                    + ")",
                )
            )
        self._set_rpy(path, rotation_rpy("quat", (quat[0] / norm, quat[1] / norm, quat[2] / norm, quat[3] / norm)))

    def _axis_angle(self, given: dict[str, Any], path: PathKey) -> None:
        """``axis_angle: {axis, angle}`` (right-handed, about the unit axis) to rpy; the axis' length is as for a
        joint axis."""
        self.convert(given, "angle", (*path, "axis_angle"), "angle")
        angle = self._changes.get((*path, "axis_angle"), {}).get("angle", given["angle"])
        if not isinstance(angle, float):
            return  # (the angle did not parse: its error is said)
        axis = given["axis"]
        norm = math.sqrt(math.fsum(v * v for v in axis))
        if not AXIS_LENGTHS[0] <= norm <= AXIS_LENGTHS[1]:
            self.errors.append(
                self.raw.error(
                    (*path, "axis_angle", "axis"),
                    f"axis {axis} has length {math.hypot(*axis):.3g}; give a direction of length "
                    f"{AXIS_LENGTHS[0]:g} to {AXIS_LENGTHS[1]:g} (e.g. [0, 0, 1])",
                )
            )
            return
        self._set_rpy(path, rotation_rpy("axis_angle", ((axis[0] / norm, axis[1] / norm, axis[2] / norm), angle)))

    def _set_rpy(self, origin_path: PathKey, rpy: tuple[float, float, float]) -> None:
        """The origin's rpy, as URDF writes it, computed from another way of giving its orientation."""
        self._changes.setdefault(origin_path, {})["rpy"] = list(rpy)
        self._count += 1

    def shape(self, holder: dict[str, Any], path: PathKey) -> None:
        shape = holder.get("shape")
        if not isinstance(shape, dict):
            return
        path = (*path, "shape")
        if "box" in shape:
            for index in range(3):
                self.convert(shape["box"]["size"], index, (*path, "box", "size"), "length")
        for name, keys in _SHAPE_LENGTHS:
            if name in shape:
                for key in keys:
                    self.convert(shape[name], key, (*path, name), "length")

    def limits(self, holder: dict[str, Any], path: PathKey, joint_type: str) -> None:
        kind: Kind = "length" if joint_type == "prismatic" else "angle"
        for key in ("lower", "upper"):
            if isinstance(holder.get("limit"), dict):
                self.convert(holder["limit"], key, (*path, "limit"), kind)
        if isinstance(holder.get("limit"), dict):
            self.rates(holder["limit"], (*path, "limit"), joint_type)
        if isinstance(holder.get("mimic"), dict):
            self.convert(holder["mimic"], "offset", (*path, "mimic"), kind)
        if isinstance(holder.get("safety_controller"), dict):
            for key in ("soft_lower_limit", "soft_upper_limit"):
                self.convert(holder["safety_controller"], key, (*path, "safety_controller"), kind)

    def density(self, item: dict[str, Any], path: PathKey) -> None:
        """A body's ``density``: kg/m^3, a string with a unit ('2.7 g/cm3'), or the name of a material of
        :mod:`xacrokit.shared.materials` ('aluminium_6061'); > 0."""
        if "density" not in item:
            return
        value = item["density"]
        material = find_material(value) if isinstance(value, str) else None
        if material is not None:
            self._changes.setdefault(path, {})["density"] = material.density
            self._count += 1
            return
        if isinstance(value, str) and value.strip()[:1].isalpha() and not value.strip().startswith("pi"):
            near = did_you_mean(material_key(value), MATERIALS)
            self.errors.append(
                self.raw.error(
                    (*path, "density"),
                    f"unknown material {value!r}{near}; give a density in kg/m^3 ('2700', '2.7 g/cm3') or a material "
                    f"of the table (gen-robot materials lists them: {', '.join(list(MATERIALS)[:6])} ...)",
                )
            )
            return
        errors = len(self.errors)
        self.convert(item, "density", path, "density")
        converted = self._changes.get(path, {}).get("density", value)
        if len(self.errors) == errors and isinstance(converted, (int, float)) and not converted > 0:
            self.errors.append(self.raw.error((*path, "density"), f"density must be > 0 kg/m^3, got {value!r}"))

    def rates(self, limit: dict[str, Any], path: PathKey, joint_type: str) -> None:
        """A limit's velocity (rad/s, or m/s for a prismatic joint: 'deg/s', 'rpm', 'mm/s' ...), effort (N*m or N:
        'kgf*cm' ...) and acceleration when given (rad/s^2 or m/s^2: 'deg/s2'), each > 0."""
        prismatic = joint_type == "prismatic"
        speed: Kind = "linear_velocity" if prismatic else "angular_velocity"
        effort: Kind = "force" if prismatic else "torque"
        rate: Kind = "acceleration" if prismatic else "angular_acceleration"
        for key, kind in (("velocity", speed), ("effort", effort), ("acceleration", rate)):
            if key not in limit:
                continue
            errors = len(self.errors)
            self.convert(limit, key, path, kind)
            value = self._changes.get(path, {}).get(key, limit[key])
            if len(self.errors) == errors and isinstance(value, (int, float)) and not value > 0:
                error = self.raw.error((*path, key), f"{key} must be > 0, got {limit[key]!r}")
                self.errors.append(implausible(error) if value == 0 else error)

    def sensor(self, sensor: dict[str, Any], path: PathKey) -> None:
        """A frame's sensor: its range (lengths of any size), its scan angles and field of view."""
        for group, keys, kind in (
            ("range", ("min", "max", "resolution"), "length"),
            ("clip", ("near", "far"), "length"),
            ("horizontal", ("min_angle", "max_angle"), "angle"),
            ("vertical", ("min_angle", "max_angle"), "angle"),
            ("image", ("fov",), "angle"),
        ):
            if isinstance(sensor.get(group), dict):
                for key in keys:
                    self.convert(sensor[group], key, (*path, group), kind, scale=False)  # type: ignore[arg-type]

    def body(self, kind: str, path: PathKey, item: dict[str, Any]) -> None:
        """Convert one body of the spec (a link, frame, wheel, arm row or tool)."""
        if kind in ("link", "frame", "wheel", "row"):
            self.density(item, path)
        if kind == "row":  # (a row's pose is its DH parameters, not an origin)
            for key, quantity in _ROW:
                self.convert(item, key, path, quantity)
            self.limits(item, path, item.get("type", "revolute"))
            if isinstance(item.get("inertia"), dict):
                self.origin(item["inertia"], "origin", (*path, "inertia"))
            return
        self.origin(item, "origin", path)
        if kind == "wheel":
            for key, quantity in _WHEEL:
                self.convert(item, key, path, quantity)
            if isinstance(item.get("limit"), dict):
                self.rates(item["limit"], (*path, "limit"), "continuous")
        elif kind in ("link", "frame"):
            self.shape(item, path)
            self.convert(item, "mass", path, "mass")
        if kind == "frame" and isinstance(item.get("sensor"), dict):
            self.sensor(item["sensor"], (*path, "sensor"))
        if kind == "link":
            self.origin(item, "com", path)
            for where, geometry in geometries(path, item):
                self.shape(geometry, where)
                self.origin(geometry, "origin", where)
            if isinstance(item.get("inertia"), dict):
                self.origin(item["inertia"], "origin", (*path, "inertia"))

    def run(self) -> tuple[dict[str, Any], list[SpecError]]:
        """Convert the whole spec: the converted data and the errors (the warnings are in ``warnings``)."""
        data = self.raw.data
        for name, joint in data.get("joints", {}).items():
            self.origin(joint, "origin", ("joints", name))
            self.limits(joint, ("joints", name), joint["type"])
        for kind, _, path, item in bodies(data):
            self.body(kind, path, item)
        types = joint_types(data, list(bodies(data)))
        for name, pose in data.get("poses", {}).items():  # (a position is a length on a prismatic joint)
            for joint in pose:
                self.convert(pose, joint, ("poses", name), "length" if types.get(joint) == "prismatic" else "angle")
        for _, _, path, part in parts(data):
            self.density(part, path)
            self.origin(part, "origin", path)
            self.shape(part, path)
            self.convert(part, "mass", path, "mass")
            if isinstance(part.get("inertia"), dict):
                self.origin(part["inertia"], "origin", (*path, "inertia"))
        return self.data, self.errors


def with_values(root: Any, changes: dict[PathKey, dict[str | int, Any]]) -> Any:
    """``root`` with the values set in the containers at the given paths, copying only the containers on those paths
    (``root`` itself is not changed)."""
    if not changes:
        return root
    copies: dict[int, Any] = {id(root): root.copy()}
    for path, values in changes.items():
        original, copied = root, copies[id(root)]
        for key in path:
            child = original[key]
            copy = copies.get(id(child))
            if copy is None:
                copy = copies[id(child)] = child.copy()
            copied[key] = copy  # (also when another parent reached it first)
            original, copied = child, copy
        for key, value in values.items():
            copied[key] = value
    return copies[id(root)]
