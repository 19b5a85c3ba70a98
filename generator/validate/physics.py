"""The physics pass, on SI values: sizes and masses > 0, a mass wherever a body moves or has a shape, physical inertia
tensors, joint limits that suit the joint type, non-zero axes, floating joints only at the root; and the density
warnings (a mass no solid of its shape could have: grams written as kilograms, millimetres as metres)."""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from typing import Any

from ..errors import SpecError
from ..kinematics import dh_body_end
from ..load import PathKey, RawSpec
from ..model import AXIAL, DEFAULT_ROW_RADIUS, LIMITED
from ..physics import tensor, tensor_problem
from .bodies import Body, BodyKind

AXIS_LENGTHS = (1e-9, 1e9)  # what an axis may measure before it is normalised (resolve divides by its length)

DENSEST = 22_590.0  # kg/m^3: osmium, the densest element
LIGHTEST = 1.0  # kg/m^3: less than air (1.2); no solid body in a robot is lighter


def physics_errors(
    raw: RawSpec, data: dict[str, Any], bodies: Sequence[Body], children: set[str]
) -> Iterator[SpecError]:
    """Every physics error of a spec whose quantities all parsed; ``children``: the links that hang from another."""
    for kind, _, path, item in bodies:
        if kind == "link":
            yield from _link_errors(raw, item, path)
        elif kind == "row":
            yield from _row_errors(raw, item, path)
        elif kind == "wheel":
            for key in ("radius", "width"):
                if not item[key] > 0:
                    yield raw.error((*path, key), f"{key} must be > 0 m, got {item[key]!r}")
            if "mass" in item:
                yield from _mass_error(raw, item["mass"], (*path, "mass"))
            elif "density" not in item:
                yield raw.error(path, "a wheel needs a mass (kg) or a density (its cylinder's volume gives the mass)")
        elif kind == "frame":
            yield from _frame_errors(raw, item, path)
    for name, joint in data.get("joints", {}).items():
        yield from _joint_errors(raw, data, ("joints", name), joint, children)


def _link_errors(raw: RawSpec, link: dict[str, Any], path: PathKey) -> Iterator[SpecError]:
    yield from _shape_errors(raw, link, path)
    if isinstance(link.get("collision"), dict):
        yield from _shape_errors(raw, link["collision"], (*path, "collision"))
    if "shape" in link and "mass" not in link and "density" not in link:  # (a density's own error is said)
        yield raw.error(
            path,
            "a link with a shape needs a mass (kg) or a density: simulators drop bodies without one; "
            "for a pure frame, leave the shape out",
            key=True,
        )
    if "mass" in link:
        yield from _mass_error(raw, link["mass"], (*path, "mass"))
        shape = link.get("shape", {})
        if "inertia" not in link and ("mesh" in shape or not shape):
            what = "a mesh" if "mesh" in shape else "no shape"
            yield raw.error(
                (*path, "mass"),
                f"link has a mass but {what}, so its inertia cannot be computed; give inertia: {{ixx, iyy, izz, ...}}",
            )
    elif "inertia" in link:
        yield raw.error((*path, "inertia"), "inertia needs a mass")
    if "inertia" in link:
        yield from _inertia_errors(raw, link["inertia"], (*path, "inertia"))


def _row_errors(raw: RawSpec, row: dict[str, Any], path: PathKey) -> Iterator[SpecError]:
    yield from _limit_errors(raw, row, path, row.get("type", "revolute"))
    if "mass" in row:
        yield from _mass_error(raw, row["mass"], (*path, "mass"))
    elif row.get("type", "revolute") != "fixed" and "density" not in row:
        yield raw.error(
            path,
            f"row {row['name']!r} moves link {row['link']!r}, which has no mass; give the row a mass (kg) for its body",
        )
    if "radius" in row and not row["radius"] > 0:
        yield raw.error((*path, "radius"), f"radius must be > 0 m, got {row['radius']!r}")


def _frame_errors(raw: RawSpec, frame: dict[str, Any], path: PathKey) -> Iterator[SpecError]:
    yield from _shape_errors(raw, frame, path)
    if "shape" in frame and "mass" not in frame and "density" not in frame:
        yield raw.error(
            path, "a frame with a shape needs a mass (kg) or a density; for a bare frame, leave the shape out", key=True
        )
    if "mass" in frame:
        yield from _mass_error(raw, frame["mass"], (*path, "mass"))
        if "mesh" in frame.get("shape", {"mesh": None}):
            yield raw.error((*path, "mass"), "a frame's mass needs a box, cylinder or sphere shape")


def _joint_errors(
    raw: RawSpec, data: dict[str, Any], path: PathKey, joint: dict[str, Any], children: set[str]
) -> Iterator[SpecError]:
    yield from _limit_errors(raw, joint, path, joint["type"])
    if joint["type"] == "floating" and joint["parent"] in children:
        yield raw.error(
            (*path, "type"),
            "a floating joint may only hang from the root link (a floating base): "
            "simulators such as MuJoCo reject deeper ones",
        )
    child = data.get("links", {}).get(joint["child"])
    if joint["type"] != "fixed" and isinstance(child, dict) and "mass" not in child and "density" not in child:
        yield raw.error(
            (*path, "child"),
            f"link {joint['child']!r} is moved by this {joint['type']} joint but "
            "has no mass; give it a mass (and a shape or an inertia)",
        )
    axis = joint.get("axis")
    if axis is not None and not any(axis):
        yield raw.error((*path, "axis"), "axis must not be zero; e.g. [0, 0, 1] for the z axis")
    elif axis is not None and not AXIS_LENGTHS[0] <= math.hypot(*axis) <= AXIS_LENGTHS[1]:
        yield raw.error(
            (*path, "axis"),
            f"axis {list(axis)} has length {math.hypot(*axis):.3g}; a direction is normalised, so give one of length "
            f"{AXIS_LENGTHS[0]:g} to {AXIS_LENGTHS[1]:g} (e.g. [0, 0, 1]): shorter or longer ones lose their direction "
            "to rounding",
        )
    if axis is not None and joint["type"] not in AXIAL:
        yield raw.error((*path, "axis"), f"a {joint['type']} joint takes no axis")


def _limit_errors(raw: RawSpec, holder: dict[str, Any], path: PathKey, joint_type: str) -> Iterator[SpecError]:
    limit = holder.get("limit")
    if joint_type in LIMITED:
        if not isinstance(limit, dict):
            yield raw.error(path, f"a {joint_type} joint needs limit: lower, upper, effort, velocity")
            return
        missing = [k for k in ("lower", "upper") if k not in limit]
        if missing:
            yield raw.error((*path, "limit"), f"a {joint_type} joint needs limit {' and '.join(missing)}")
            return
        if limit["lower"] > limit["upper"]:
            yield raw.error(
                (*path, "limit", "lower"), f"lower ({limit['lower']!r}) is greater than upper ({limit['upper']!r})"
            )
        safety = holder.get("safety_controller")
        if isinstance(safety, dict):
            low, high = safety.get("soft_lower_limit"), safety.get("soft_upper_limit")
            if low is not None and low < limit["lower"]:
                yield raw.error(
                    (*path, "safety_controller", "soft_lower_limit"),
                    f"soft lower limit {low!r} is below the hard lower limit {limit['lower']!r}",
                )
            if high is not None and high > limit["upper"]:
                yield raw.error(
                    (*path, "safety_controller", "soft_upper_limit"),
                    f"soft upper limit {high!r} is above the hard upper limit {limit['upper']!r}",
                )
    elif joint_type == "continuous" and not isinstance(limit, dict):
        yield raw.error(
            path, "a continuous joint needs limit: {effort, velocity} (controllers and simulators read them)"
        )
    elif isinstance(limit, dict) and ("lower" in limit or "upper" in limit):
        hint = "; make it revolute to limit its range" if joint_type == "continuous" else ""
        yield raw.error((*path, "limit"), f"a {joint_type} joint takes no lower/upper limits{hint}")


def _shape_errors(raw: RawSpec, holder: dict[str, Any], path: PathKey) -> Iterator[SpecError]:
    shape = holder.get("shape")
    if not isinstance(shape, dict):
        return
    values: list[tuple[PathKey, float]] = []
    if "box" in shape:
        values = [((*path, "shape", "box", "size", i), v) for i, v in enumerate(shape["box"]["size"])]
    for name in ("cylinder", "sphere"):
        if name in shape:
            values = [((*path, "shape", name, k), v) for k, v in shape[name].items()]
    for where, value in values:
        if isinstance(value, float) and not value > 0:
            yield raw.error(where, f"sizes must be > 0 m, got {value!r}")
    filename = shape.get("mesh", {}).get("filename") if isinstance(shape.get("mesh"), dict) else None
    bad = next((ch for ch in filename or "" if not _xml_character(ch)), None)
    if bad is not None:
        yield raw.error(
            (*path, "shape", "mesh", "filename"),
            f"the file name holds U+{ord(bad):04X}, a character an XML file (a URDF) cannot hold; rename the file",
        )


def _xml_character(ch: str) -> bool:
    """Whether XML 1.0 allows ``ch`` in a document (tab, newline and carriage return of the control characters)."""
    code = ord(ch)
    return code in (0x9, 0xA, 0xD) or 0x20 <= code <= 0xD7FF or 0xE000 <= code <= 0xFFFD or 0x10000 <= code <= 0x10FFFF


def _inertia_errors(raw: RawSpec, inertia: dict[str, Any], path: PathKey) -> Iterator[SpecError]:
    matrix = tensor(
        inertia["ixx"],
        inertia.get("ixy", 0.0),
        inertia.get("ixz", 0.0),
        inertia["iyy"],
        inertia.get("iyz", 0.0),
        inertia["izz"],
    )
    problem = tensor_problem(matrix)
    if problem:
        yield raw.error(path, problem)


def _mass_error(raw: RawSpec, mass: float, path: PathKey) -> Iterator[SpecError]:
    if not (isinstance(mass, float) and mass > 0 and math.isfinite(mass)):
        yield raw.error(path, f"mass must be > 0 kg, got {mass!r}")


def density_warnings(raw: RawSpec, bodies: Sequence[Body], data: dict[str, Any]) -> Iterator[SpecError]:
    """Masses that no solid filling their shape could have: grams written as kilograms, millimetres as metres. A DH
    row's body is the cylinder (a sphere when it is shorter than a micrometre) gen-robot draws from its joint's frame
    to the next one, with the row's radius."""
    segments = _row_segments(data)
    for kind, _, path, item in bodies:
        mass = item.get("mass")
        if mass is None or kind not in ("link", "wheel", "frame", "row"):
            continue
        found = _volume(kind, item) if kind != "row" else segments.get(path)
        if found is None or not (found[1] > 0 and mass > 0):
            continue
        density = mass / found[1]
        if LIGHTEST <= density <= DENSEST:
            continue
        hint = (
            "denser than osmium (22,590 kg/m^3); grams written as kilograms? e.g. '500 g'"
            if density > DENSEST
            else "lighter than air; a size in mm written as m? e.g. '150 mm'"
        )
        if kind == "row":  # (its body is drawn from the DH lengths and its radius: either may be what is off)
            radius = item.get("radius", DEFAULT_ROW_RADIUS)
            body = "a cylinder to the next joint frame" if found[0] == "cylinder" else "a sphere: its frames coincide"
            fits = "too small" if density > DENSEST else "too large"
            hint += f"; or its radius ({radius:g} m; the row's body is {body}) is {fits} for its mass"
        yield raw.error(
            (*path, "mass"),
            f"mass {mass:g} kg in a {found[1]:.3g} m^3 {found[0]} is {density:.3g} kg/m^3, {hint}",
        )


# A body given both a mass and a density: its mass may be below the solid's (pockets, shells, a 3D print's infill) but
# a part keeping less than a quarter of its envelope's material, or weighing more than the solid (beyond 10%: the
# shape is an approximation), is more likely a wrong number than a real part.
MASS_TO_SOLID = (0.25, 1.1)


def masses_from_density(
    raw: RawSpec, data: dict[str, Any], every: Sequence[Body]
) -> tuple[dict[PathKey, float], list[SpecError], list[SpecError]]:
    """The mass of every body that gives a density and no mass (density times the volume of its shape: exact for a
    box, cylinder or sphere; a DH row's body as gen-robot draws it), by the body's path; the errors (a density with
    no volume to fill) and the warnings (a mass far from what its density gives)."""
    segments = _row_segments(data)
    masses: dict[PathKey, float] = {}
    errors: list[SpecError] = []
    warnings: list[SpecError] = []
    for kind, _, path, item in every:
        density = item.get("density")
        if density is None or kind not in ("link", "wheel", "frame", "row"):
            continue
        found = _volume(kind, item) if kind != "row" else segments.get(path)
        if found is None:
            errors.append(
                raw.error(
                    (*path, "density"),
                    "a density gives a mass only with a box, cylinder or sphere shape (a mesh's volume is not read "
                    "yet); give mass: instead",
                )
            )
            continue
        solid = density * found[1]
        if "mass" not in item:
            if found[1] > 0:
                masses[path] = solid
            continue
        if found[1] > 0 and not MASS_TO_SOLID[0] <= item["mass"] / solid <= MASS_TO_SOLID[1]:
            warnings.append(
                raw.error(
                    (*path, "mass"),
                    f"mass {item['mass']:g} kg is {item['mass'] / solid:.3g} times that of a solid {found[0]} of "
                    f"density {density:g} kg/m^3 ({solid:.3g} kg); a part keeps between a quarter and all of its "
                    "solid's mass: is the mass, the density or the size wrong?",
                )
            )
    return masses, errors, warnings


def _row_segments(data: dict[str, Any]) -> dict[PathKey, tuple[str, float]]:
    """(solid, volume) of every DH row's body, by the row's path: as emit draws it (kinematics.dh_body_end)."""
    found: dict[PathKey, tuple[str, float]] = {}
    for name, arm in data.get("arms", {}).items():
        rows = arm["joints"]
        for index, row in enumerate(rows):
            after = rows[index + 1] if index + 1 < len(rows) else None
            following = (after["a"], after["alpha"], after["d"]) if after else None
            end = dh_body_end(arm.get("convention", "standard"), row["a"], row["alpha"], following)
            length = math.dist((0.0, 0.0, 0.0), end)
            radius = row.get("radius", DEFAULT_ROW_RADIUS)
            if length >= 1e-6:
                found[("arms", name, "joints", index)] = ("cylinder", math.pi * radius**2 * length)
            else:
                found[("arms", name, "joints", index)] = ("sphere", 4.0 / 3.0 * math.pi * radius**3)
    return found


def _volume(kind: BodyKind, item: dict[str, Any]) -> tuple[str, float] | None:
    """(solid, volume in m^3) of a link's or frame's shape, or of a wheel (a cylinder); None for a mesh or no shape."""
    if kind == "wheel":
        return "cylinder", math.pi * item["radius"] ** 2 * item["width"]
    shape = item.get("shape")
    if not shape:
        return None
    if "box" in shape:
        x, y, z = shape["box"]["size"]
        return "box", x * y * z
    if "cylinder" in shape:
        return "cylinder", math.pi * shape["cylinder"]["radius"] ** 2 * shape["cylinder"]["length"]
    if "sphere" in shape:
        return "sphere", 4.0 / 3.0 * math.pi * shape["sphere"]["radius"] ** 3
    return None
