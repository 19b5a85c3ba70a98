"""The units pass: every length, angle and mass of a schema-valid spec converted to an SI float, each value that does
not parse reported where it stands, and plain-number angles of many turns (degrees written without ``deg``) and lengths
beyond 10 m (millimetres written without ``mm``) noted."""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np

from ..errors import SpecError
from ..load import PathKey, RawSpec
from ..shared.materials import MATERIALS, find_material, material_key
from ..shared.transforms import rotation_rpy
from ..shared.units import Kind, UnitError, bound_problem, parse_quantity, plain_number
from ..shared.value_text import did_you_mean
from .bodies import bodies, geometries, joint_types, parts
from .physics import AXIS_LENGTHS, implausible

# A plain-number angle beyond this many turns is most likely degrees: one turn for an orientation, two for a joint's
# range (multi-turn joints exist; a range beyond two turns written in radians is rarer than degrees left unmarked).
_TURNS: dict[str | int, int] = {"lower": 2, "upper": 2, "soft_lower_limit": 2, "soft_upper_limit": 2}

# the ways an origin may give its orientation (one at a time; docs/spec.md's table has one rotation in each)
ORIENTATIONS = ("rpy", "quat", "quat_wxyz", "rotvec", "axis_angle", "matrix", "euler")
ROTVEC_TURNS = 1000  # the most turns a rotation vector's angle may make (more: its digits no longer say the turn)
ORTHONORMAL = 1e-6  # how far a rotation matrix's R^T R may be from the identity (a calibration's 7 digits pass)
QUATERNION_LENGTHS = (1e-6, 1e6)  # a quaternion's length that can be normalised without losing its direction

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
        sensor's range)."""
        if isinstance(container, dict) and key not in container:
            return
        value = container[key]
        if kind in ("angle", "length") and scale:
            plain = value if type(value) in (int, float) else plain_number(value) if isinstance(value, str) else None
            if plain is not None and kind == "angle" and abs(plain) > _TURNS.get(key, 1) * math.tau:
                self._turns(plain, key, (*path, key))
            elif plain is not None and kind == "length" and abs(plain) > LONGEST:
                self.warnings.append(
                    self.raw.error(
                        (*path, key),
                        f"length {plain:g} m is longer than any part of a robot ({LONGEST:g} m); if you meant "
                        f"millimetres, write '{plain:g} mm'",
                    )
                )
        if type(value) is float and math.isfinite(value) and (value != 0.0 or math.copysign(1.0, value) > 0):
            self._bound(value, kind, (*path, key))
            return  # already SI: what parse_quantity would return
        try:
            converted = parse_quantity(value, kind) + 0.0  # (+ 0.0: a -0.0 in the spec is written 0.0)
        except UnitError as exc:
            self.errors.append(self.raw.error((*path, key), str(exc)))
            return
        self._bound(converted, kind, (*path, key))
        self._changes.setdefault(path, {})[key] = converted
        self._count += 1

    def _bound(self, value: float, kind: Kind, path: PathKey) -> None:
        beyond = bound_problem(kind, value)
        if beyond is not None:
            self.errors.append(self.raw.error(path, beyond))

    def _turns(self, value: float, key: str | int, path: PathKey) -> None:
        what = "limit" if key in _TURNS else "angle"
        self.warnings.append(
            self.raw.error(
                path,
                f"{what} {value:g} rad is {abs(value) / math.tau:.3g} turns; "
                f"if you meant degrees, write '{value:g} deg'",
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

    def _rotvec(self, rotvec: list[float], path: PathKey) -> None:
        """``rotvec: [rx, ry, rz]`` (axis x angle, rad) to rpy; an angle beyond ROTVEC_TURNS turns is refused (1e300
        rad has no digits left for the turn it makes)."""
        angle = math.sqrt(math.fsum(v * v for v in rotvec))
        if not angle <= ROTVEC_TURNS * math.tau:
            self.errors.append(
                self.raw.error(
                    (*path, "rotvec"),
                    f"rotvec {rotvec}: an angle of {angle:.3g} rad is {angle / math.tau:.3g} turns; a rotation vector "
                    f"is the axis times an angle in radians, of at most {ROTVEC_TURNS} turns",
                )
            )
            return
        self._set_rpy(path, rotation_rpy(rotvec=tuple(rotvec)))

    def _matrix(self, rows: list[list[float]], path: PathKey) -> None:
        """``matrix:`` (3 rows) to rpy, when it is a rotation: R^T R = I to ORTHONORMAL and det R = +1."""

        matrix = np.array(rows, dtype=float)
        off = float(np.abs(matrix.T @ matrix - np.eye(3)).max())
        if not off <= ORTHONORMAL or not np.linalg.det(matrix) > 0:
            problem = f"R^T R is {off:.3g} from the identity" if not off <= ORTHONORMAL else "its determinant is -1"
            self.errors.append(
                self.raw.error(
                    (*path, "matrix"),
                    f"not a rotation matrix: {problem} (a rotation's rows are orthonormal to {ORTHONORMAL:g}, its "
                    "determinant +1; a mirror is no rotation)",
                )
            )
            return
        self._set_rpy(path, rotation_rpy(matrix=matrix))

    def _euler(self, given: dict[str, Any], path: PathKey) -> None:
        """``euler: {sequence, angles}`` (scipy's names: upper case intrinsic, lower case extrinsic) to rpy."""
        sequence = given["sequence"]
        if not re.fullmatch(r"[XYZ]{3}|[xyz]{3}", sequence):
            return  # (the schema says what a sequence is; the passes after it still run)
        if sequence[0] == sequence[1] or sequence[1] == sequence[2]:
            self.errors.append(
                self.raw.error(
                    (*path, "euler", "sequence"),
                    f"{sequence!r}: two turns in a row about one axis are one turn; consecutive axes must differ "
                    "(XYZ, ZYX, ZXZ ...)",
                )
            )
            return
        for index in range(3):
            self.convert(given["angles"], index, (*path, "euler", "angles"), "angle")
        angles = self._changes.get((*path, "euler", "angles"), {})
        values = [angles.get(k, given["angles"][k]) for k in range(3)]
        if all(isinstance(v, float) for v in values):
            self._set_rpy(path, rotation_rpy(euler=(given["sequence"], (values[0], values[1], values[2]))))

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
                    f"{field} {written or quat} has length {norm:.3g}: a rotation's quaternion has length 1 (the "
                    f"identity is {'[0, 0, 0, 1]' if field == 'quat' else '[1, 0, 0, 0]'})",
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
        self._set_rpy(path, rotation_rpy(quaternion=(quat[0] / norm, quat[1] / norm, quat[2] / norm, quat[3] / norm)))

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
                    f"axis {axis} has length {norm:.3g}; give a direction of length {AXIS_LENGTHS[0]:g} to "
                    f"{AXIS_LENGTHS[1]:g} (e.g. [0, 0, 1])",
                )
            )
            return
        self._set_rpy(path, rotation_rpy(axis=(axis[0] / norm, axis[1] / norm, axis[2] / norm), angle=angle))

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
        """A limit's velocity (rad/s, or m/s for a prismatic joint: 'deg/s', 'rpm', 'mm/s' ...) and effort (N*m or N:
        'kgf*cm' ...), each > 0."""
        prismatic = joint_type == "prismatic"
        speed: Kind = "linear_velocity" if prismatic else "angular_velocity"
        effort: Kind = "force" if prismatic else "torque"
        for key, kind in (("velocity", speed), ("effort", effort)):
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
