"""The physics pass, on SI values: sizes and masses > 0, a mass wherever a body moves or has a shape, physical inertia
tensors, composite links whose parts each have a shape and a mass, joint limits that suit the joint type, non-zero
axes, floating joints only at the root. (What follows from a shape's volume, densities and meshes, is in
:mod:`.solids`.)"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from typing import Any

from ..errors import SpecError
from ..load import PathKey, RawSpec
from ..model import AXIAL, LIMITED
from ..shared.solid_inertia import entries_problem
from .bodies import Body, geometries

AXIS_LENGTHS = (1e-9, 1e9)  # what an axis may measure before it is normalised (resolve divides by its length)


class Implausible(SpecError):
    """An error about a value no real body has but a real robot's file may hold (a mass of 0, an impossible tensor, a
    moving link without mass, a continuous joint without limit): a warning instead under the spec's ``strict: false``,
    which gen-robot import writes so that such a robot comes back as its file describes it."""


def implausible(error: SpecError) -> Implausible:
    return Implausible(error.message, file=error.file, path=error.path, line=error.line, column=error.column)


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
    if "parts" in link:
        yield from _composite_errors(raw, link, path)
        return
    yield from _shape_errors(raw, link, path)
    for where, geometry in geometries(path, link):
        yield from _shape_errors(raw, geometry, where)
    if link.get("collision") == "same" and "shape" not in link:
        yield raw.error((*path, "collision"), "collision: same needs the link's shape; give the collision's own shape")
    if "shape" in link and "mass" not in link and "density" not in link:  # (a density's own error is said)
        yield implausible(
            raw.error(
                path,
                "a link with a shape needs a mass (kg) or a density: simulators drop bodies without one; "
                "for a pure frame, leave the shape out",
                key=True,
            )
        )
    computed = isinstance(link.get("inertia"), dict) and link["inertia"].get("kind") == "mesh"
    if "mass" in link:
        said = list(_mass_error(raw, link["mass"], (*path, "mass"), link=True))
        yield from said
        if not said and "inertia" not in link and not link.get("shape"):  # (a mass of 0 is said once, above)
            yield raw.error(
                (*path, "mass"),
                "link has a mass but no shape, so its inertia cannot be computed; give inertia: {ixx, iyy, izz, ...}",
            )
        if computed and "com" in link:
            yield raw.error(
                (*path, "com"),
                "a mesh's centre of mass is computed from its surface; leave com out, or give inertia: (with its "
                "origin) to state both",
            )
    elif "inertia" in link:
        yield raw.error((*path, "inertia"), "inertia needs a mass")
    if "inertia" in link and not computed:
        yield from _inertia_errors(raw, link["inertia"], (*path, "inertia"))


# What a composite link takes from its parts instead of giving it itself.
_PART_KEYS = ("shape", "origin", "mass", "density", "inertia", "com", "collision", "visuals")


def _composite_errors(raw: RawSpec, link: dict[str, Any], path: PathKey) -> Iterator[SpecError]:
    for key in _PART_KEYS:
        if key in link:
            yield raw.error(
                (*path, key),
                f"a link with parts takes its shape, mass and inertia from them: move {key} into a part (each part "
                "gives its own shape, origin and mass or density)",
                key=True,
            )
    for index, part in enumerate(link["parts"]):
        where = (*path, "parts", index)
        yield from _shape_errors(raw, part, where)
        if "mass" in part:
            yield from _mass_error(raw, part["mass"], (*path, "parts", index, "mass"))
        elif "density" not in part:
            yield raw.error(where, "a part needs a mass (kg) or a density (its shape's volume gives the mass)")
        inertia = part.get("inertia")
        if isinstance(inertia, dict) and inertia.get("kind") != "mesh":
            yield from _inertia_errors(raw, inertia, (*where, "inertia"))


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
    if "inertia" in row:
        if "mass" not in row:
            yield raw.error(
                (*path, "inertia"), "inertia needs the row's mass (kg): a published tensor comes with its mass"
            )
        yield from _inertia_errors(raw, row["inertia"], (*path, "inertia"))


def _frame_errors(raw: RawSpec, frame: dict[str, Any], path: PathKey) -> Iterator[SpecError]:
    yield from _shape_errors(raw, frame, path)
    if "shape" in frame and "mass" not in frame and "density" not in frame:
        yield raw.error(
            path, "a frame with a shape needs a mass (kg) or a density; for a bare frame, leave the shape out", key=True
        )
    if "mass" in frame:
        yield from _mass_error(raw, frame["mass"], (*path, "mass"))
        if "shape" not in frame:
            yield raw.error((*path, "mass"), "a frame's mass needs a shape (its inertia is computed from it)")


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
    massless = isinstance(child, dict) and not {"mass", "density", "parts"} & set(child)
    if joint["type"] != "fixed" and massless:
        yield implausible(
            raw.error(
                (*path, "child"),
                f"link {joint['child']!r} is moved by this {joint['type']} joint but "
                "has no mass; give it a mass (and a shape or an inertia)",
            )
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
        yield implausible(
            raw.error(path, "a continuous joint needs limit: {effort, velocity} (controllers and simulators read them)")
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
    for name in ("cylinder", "sphere", "capsule", "tube"):
        if name in shape:
            values = [((*path, "shape", name, k), v) for k, v in shape[name].items()]
    for where, value in values:
        if isinstance(value, float) and not value > 0:
            yield raw.error(where, f"sizes must be > 0 m, got {value!r}")
    tube = shape.get("tube")
    if isinstance(tube, dict) and all(isinstance(tube[k], float) for k in ("inner_radius", "outer_radius")):
        if tube["inner_radius"] > 0 and not tube["inner_radius"] < tube["outer_radius"]:
            yield raw.error(
                (*path, "shape", "tube", "inner_radius"),
                f"inner_radius ({tube['inner_radius']!r} m) must be less than outer_radius "
                f"({tube['outer_radius']!r} m); for a solid bar use cylinder",
            )
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
    problem = entries_problem(
        inertia["ixx"],
        inertia.get("ixy", 0.0),
        inertia.get("ixz", 0.0),
        inertia["iyy"],
        inertia.get("iyz", 0.0),
        inertia["izz"],
    )
    if problem:
        yield implausible(raw.error(path, problem))


def _mass_error(raw: RawSpec, mass: float, path: PathKey, *, link: bool = False) -> Iterator[SpecError]:
    """``link``: a link's own mass, whose 0 strict: false keeps (a part's, a wheel's, a row's or a frame's stays an
    error: a composite of parts that weigh nothing has no centre of mass)."""
    if not (isinstance(mass, float) and mass > 0 and math.isfinite(mass)):
        if mass == 0 and link:  # (one message for it, whatever else the link gives: its shape, its inertia)
            message = (
                "mass is 0 kg: leave `mass` out for a link that weighs nothing (a frame), else give its mass (> 0)"
            )
            yield implausible(raw.error(path, message))
            return
        yield raw.error(path, f"mass must be > 0 kg, got {mass!r}")
