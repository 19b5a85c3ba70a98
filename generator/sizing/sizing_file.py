"""The sizing file (``gen-robot size ROBOT --sizing FILE``): payloads, loads, a motion and drives, read with the
spec's reader (positions kept), checked against schemas/sizing.schema.json, its units converted; every problem
located (file:line:col) and reported at once. Names of frames and joints are checked against the robot."""

from __future__ import annotations

import dataclasses
import json
import math
import os
from dataclasses import dataclass, field
from functools import cache
from typing import Any

import numpy as np

from ..errors import SpecError, SpecErrors
from ..load import PathKey, RawSpec, load_file
from ..shared.package_data import schemas_dir
from ..shared.solid_inertia import tensor_problem
from ..shared.units import MAX_MOMENT, Kind, UnitError, bound_problem, parse_quantity
from ..shared.value_text import did_you_mean
from ..validate.quantities import ORIENTATIONS, Quantities
from ..validate.schema import SchemaValidator, schema_errors
from .mobile import BaseMotion
from .motion import (
    DEFAULT_STEP,
    MAX_SAMPLES,
    Motion,
    SegmentTiming,
    planned_durations,
    reach,
    sample_count,
    segment_timing,
    waypoint_errors,
)
from .sized_robot import Load, LoadedRobot, Payload, frame_names


@dataclass(frozen=True)
class Drive:
    """A joint's gearbox and motor: ratio N, efficiency, rotor inertia (kg*m^2), and the motor's limits (None where
    not given): continuous and peak torque (N*m), maximum speed (rad/s)."""

    gear_ratio: float
    efficiency: float = 1.0
    rotor_inertia: float = 0.0
    rated_torque: float | None = None
    peak_torque: float | None = None
    max_speed: float | None = None


@dataclass(frozen=True)
class Sizing:
    """What a sizing file asks for, in SI, by name (the motion's waypoints still by joint name)."""

    payloads: tuple[Payload, ...] = ()
    loads: tuple[Load, ...] = ()
    motion: dict[str, Any] | None = None
    drives: dict[str, Drive] = field(default_factory=dict)
    raw: RawSpec | None = None
    mobile: BaseMotion | None = None
    safety_factor: float = 1.0
    gravity: float | None = None  # m/s^2 (None: not given, standard gravity)


@cache
def _validator() -> SchemaValidator:
    schema = json.loads((schemas_dir() / "sizing.schema.json").read_text("utf-8"))
    return SchemaValidator(schema)


class _Reader:
    def __init__(self, raw: RawSpec) -> None:
        self.raw = raw
        self.errors: list[SpecError] = []

    def quantity(self, value: Any, kind: Kind, path: PathKey, *, positive: bool = False) -> float:
        try:
            number = parse_quantity(value, kind)
        except UnitError as exc:
            self.errors.append(self.raw.error(path, str(exc)))
            return math.nan
        if positive and not number > 0:
            self.errors.append(self.raw.error(path, f"must be > 0, got {value!r}"))
        beyond = bound_problem(kind, number)
        if beyond is not None:
            self.errors.append(self.raw.error(path, beyond))
        return number

    def tensor(self, inertia: tuple[float, ...], path: PathKey) -> None:
        """A payload's tensor (ixx, ixy, ixz, iyy, iyz, izz): a rigid body's, within MAX_MOMENT."""
        xx, xy, xz, yy, yz, zz = inertia
        largest = max(map(abs, inertia))
        if largest > MAX_MOMENT:
            self.errors.append(
                self.raw.error(path, f"{largest:g} kg*m^2 is beyond what xacrokit takes (at most {MAX_MOMENT:g})")
            )
            return
        problem = tensor_problem(np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]))
        if problem is not None:
            self.errors.append(self.raw.error(path, f"{problem} (leave inertia out for a point mass)"))


def read_sizing(path: str | os.PathLike[str]) -> Sizing:
    """The sizing file at ``path``. Raises SpecErrors (located) when it does not follow its schema or a value does
    not parse."""
    raw = load_file(os.fspath(path))
    errors = schema_errors(raw, _validator())
    if errors:
        raise SpecErrors(errors)
    data, read = raw.data or {}, _Reader(raw)
    payloads = []
    for index, item in enumerate(data.get("payloads", [])):
        where: PathKey = ("payloads", index)
        mass = read.quantity(item["mass"], "mass", (*where, "mass"), positive=True)
        com = tuple(read.quantity(v, "length", (*where, "com", k)) for k, v in enumerate(item.get("com", [0, 0, 0])))
        tensor = item.get("inertia", {})
        inertia = tuple(float(tensor.get(k, 0.0)) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"))
        if tensor:
            read.tensor(inertia, (*where, "inertia"))
        payloads.append(Payload(item["frame"], mass, (com[0], com[1], com[2]), inertia))  # type: ignore[arg-type]
    loads = []
    for index, item in enumerate(data.get("loads", [])):
        where = ("loads", index)
        force = [read.quantity(v, "force", (*where, "force", k)) for k, v in enumerate(item.get("force", [0, 0, 0]))]
        moment = [read.quantity(v, "torque", (*where, "moment", k)) for k, v in enumerate(item.get("moment", [0] * 3))]
        loads.append(Load(item["frame"], (force[0], force[1], force[2]), (moment[0], moment[1], moment[2])))
    drives = {}
    for name, item in data.get("drives", {}).items():
        where = ("drives", name)
        drives[name] = Drive(
            gear_ratio=float(item["gear_ratio"]),
            efficiency=float(item.get("efficiency", 1.0)),
            rotor_inertia=float(item.get("rotor_inertia", 0.0)),
            rated_torque=_optional(read, item, "rated_torque", "torque", where),
            peak_torque=_optional(read, item, "peak_torque", "torque", where),
            max_speed=_optional(read, item, "max_speed", "angular_velocity", where),
        )
    mobile = None
    if "mobile" in data:
        item, where = data["mobile"], ("mobile",)
        mobile = BaseMotion(
            speed=read.quantity(item["speed"], "linear_velocity", (*where, "speed"), positive=True),
            acceleration=float(item["acceleration"]),
            slope=read.quantity(item.get("slope", 0.0), "angle", (*where, "slope")),
            rolling_resistance=float(item.get("rolling_resistance", 0.0)),
            wheels=tuple(item.get("wheels", ())),
        )
    gravity = None
    if "gravity" in data:
        gravity = read.quantity(data["gravity"], "acceleration", ("gravity",))
        problem = gravity_problem(gravity)
        if problem is not None:
            read.errors.append(raw.error(("gravity",), problem))
    if read.errors:
        raise SpecErrors(read.errors)
    factor = float(data.get("safety_factor", 1.0))
    return Sizing(tuple(payloads), tuple(loads), data.get("motion"), drives, raw, mobile, factor, gravity)


MOST_GRAVITY = 1000.0  # m/s^2: a hundred times Earth's, beyond any planet's surface (Jupiter's: 24.8)


def gravity_problem(gravity: float) -> str | None:
    """Why a gravity (m/s^2) is refused, or None: it must be at least 0 (0: weightless) and at most MOST_GRAVITY."""
    if math.isnan(gravity) or 0.0 <= gravity <= MOST_GRAVITY:
        return None  # (NaN: its parse error is said)
    return (
        f"gravity must be from 0 to {MOST_GRAVITY:g} m/s^2 (Earth's standard 9.80665, the course's 9.81), "
        f"got {gravity:g}"
    )


def _optional(read: _Reader, item: dict[str, Any], key: str, kind: Kind, where: PathKey) -> float | None:
    return read.quantity(item[key], kind, (*where, key), positive=True) if key in item else None


def motion_of(sizing: Sizing, robot: LoadedRobot) -> Motion | None:
    """The sizing file's motion for ``robot``: waypoints in the robot's joint order (a joint left out keeps its
    value), limits per joint. Raises SpecErrors (located) for an unknown joint, a missing limit, a value that does
    not parse or a waypoint outside a joint's range."""
    data, raw = sizing.motion, sizing.raw
    if data is None or raw is None:
        return None
    read = _Reader(raw)
    names = [j.name for j in robot.joints]
    current = [0.0] * len(names)
    waypoints = []
    every = (
        read.quantity(data["duration"], "time", ("motion", "duration"), positive=True) if "duration" in data else None
    )
    asked: list[float | None] = []  # (per segment: the one arriving at each waypoint after the first)
    for index, point in enumerate(data["waypoints"]):
        if "pose" in point:
            current = _reached(read, robot, point["pose"], ("motion", "waypoints", index, "pose"), current)
        if index:
            where_time: PathKey = ("motion", "waypoints", index, "duration")
            own = read.quantity(point["duration"], "time", where_time, positive=True) if "duration" in point else None
            asked.append(own if own is not None else every)
        elif "duration" in point:
            message = "the first waypoint is where the cycle starts: no segment arrives at it to last (give duration "
            read.errors.append(raw.error(("motion", "waypoints", 0, "duration"), message + "on a later waypoint)"))
        _set_joint_values(read, robot, point, index, current)
        waypoints.append(tuple(current))
    # (every segment given a duration: a quintic needs no limit, the duration fixes it; a trapezoid's ramps still
    # take the acceleration limit)
    timed = all(d is not None for d in asked)
    scaling = data.get("scaling", "quintic")
    velocity = _per_joint(read, data.get("velocity"), robot, ("motion", "velocity"), missing=_missing(timed, ""))
    missing = _missing(timed, scaling)
    acceleration = _per_joint(read, data.get("acceleration"), robot, ("motion", "acceleration"), missing=missing)
    if not read.errors:
        read.errors += [raw.error(("motion", "waypoints"), problem) for problem in waypoint_errors(robot, waypoints)]
    if read.errors:
        raise SpecErrors(read.errors)
    motion = Motion(
        waypoints=tuple(waypoints),
        velocity=tuple(velocity),
        acceleration=tuple(acceleration),
        scaling=scaling,
        dwell=float(data.get("dwell", 0.0)),
        step=float(data.get("step", DEFAULT_STEP)),
        durations=tuple(asked),
    )
    too_short = _duration_errors(raw, motion, robot, data)
    if too_short:
        raise SpecErrors(too_short)
    too_long = _sampling_error(raw, motion, robot, data)
    if too_long is not None:
        raise SpecErrors([too_long])
    return motion


def _set_joint_values(
    read: _Reader, robot: LoadedRobot, point: dict[str, Any], index: int, current: list[float]
) -> None:
    """Write a waypoint's joint values (rad or m, units read) into ``current``, in the robot's joint order; an unknown
    joint is a located error."""
    names = [j.name for j in robot.joints]
    for name, value in point.items():
        if name in ("pose", "duration"):
            continue
        where: PathKey = ("motion", "waypoints", index, name)
        if name not in names:
            read.errors.append(read.raw.error(where, f"{name!r} is not a moving joint{did_you_mean(name, names)}"))
            continue
        joint = robot.joints[names.index(name)]
        current[names.index(name)] = read.quantity(value, "length" if joint.kind == "prismatic" else "angle", where)


def _duration_errors(raw: RawSpec, motion: Motion, robot: LoadedRobot, data: dict[str, Any]) -> list[SpecError]:
    """A segment asked to last less than its joints' limits allow, at the duration that asks it, with the shortest."""
    errors = []
    points = [np.array(w, dtype=float) for w in motion.waypoints]
    for index, (start, end, asked) in enumerate(zip(points, points[1:], motion.durations, strict=False), 1):
        timing = segment_timing(motion, end - start)
        if asked is None or asked >= timing.duration * (1.0 - 1e-12):
            continue
        own = "duration" in data["waypoints"][index]
        where: PathKey = ("motion", "waypoints", index, "duration") if own else ("motion", "duration")
        message = (
            f"the segment to waypoint {index} cannot last {asked:g} s: the shortest the joints' limits allow is "
            f"{timing.duration:.6g} s, set by {robot.joints[timing.joint].name}'s {timing.limit} limit; give at least "
            "that, or raise the limit"
        )
        errors.append(raw.error(where, message))
    return errors


def _sampling_error(raw: RawSpec, motion: Motion, robot: LoadedRobot, data: dict[str, Any]) -> SpecError | None:
    """The cycle sampled beyond MAX_SAMPLES, located at what makes it long (:func:`_why_long`); None when it is
    within the cap."""
    points = [np.array(w, dtype=float) for w in motion.waypoints]
    timings = [segment_timing(motion, end - start) for start, end in zip(points, points[1:], strict=False)]
    planned = planned_durations(motion)  # (the asked ones: never shorter than the timings)
    timings = [dataclasses.replace(t, duration=d) for t, d in zip(timings, planned, strict=True)]
    needed = sample_count(motion, [t.duration for t in timings])
    if needed <= MAX_SAMPLES:
        return None
    cycle = motion.dwell * len(points) + sum(t.duration for t in timings)
    cap = f"xacrokit samples a cycle at most {MAX_SAMPLES:,} times ({MAX_SAMPLES * motion.step:g} s at this step)"
    if math.isfinite(needed):
        head = f"the cycle would take {cycle:.4g} s, {needed:,.0f} samples at a step of {motion.step:g} s; {cap}"
    else:
        head = f"the cycle would take more samples at a step of {motion.step:g} s than a number can hold; {cap}"
    where, why = _why_long(motion, robot, data, timings)
    return raw.error(where, f"{head}: {why}")


def _why_long(
    motion: Motion, robot: LoadedRobot, data: dict[str, Any], timings: list[SegmentTiming]
) -> tuple[PathKey, str]:
    """Where a cycle too long to sample comes from, and why: a step finer than the default, the dwell, the limit
    that sets its longest segment, or many segments."""
    held, moving = motion.dwell * len(motion.waypoints), sum(t.duration for t in timings)
    if "step" in data and (held + moving) / DEFAULT_STEP <= MAX_SAMPLES:
        return ("motion", "step"), f"the step of {motion.step:g} s is finer than it needs; leave it out (1 ms)"
    if held >= moving:
        why = f"the dwell of {motion.dwell:g} s is held at each of the {len(motion.waypoints)} waypoints"
        return ("motion", "dwell"), f"{why} (milliseconds typed as seconds?); shorten it or give a coarser step"
    longest = max(range(len(timings)), key=lambda k: timings[k].duration)
    timing = timings[longest]
    if not timing.duration >= moving / 2:
        why = f"its {len(timings)} segments take {moving:.4g} s together"
        return ("motion", "waypoints"), f"{why}; split the cycle or give a coarser step"
    asked = (list(motion.durations) + [None] * len(timings))[longest]
    if asked is not None:  # (the segment lasts what the file asks)
        own = "duration" in data["waypoints"][longest + 1]
        where_asked: PathKey = ("motion", "waypoints", longest + 1, "duration") if own else ("motion", "duration")
        return where_asked, f"waypoint {longest} to {longest + 1} is asked to last {asked:g} s (seconds for ms?)"
    joint = robot.joints[timing.joint]
    given = data.get(timing.limit)
    where: PathKey = ("motion",)  # (the URDF's velocity limit: the file has no field for it)
    if isinstance(given, dict) and joint.name in given:
        where = ("motion", timing.limit, joint.name)
    elif given is not None and not isinstance(given, dict):
        where = ("motion", timing.limit)
    value = getattr(motion, timing.limit)[timing.joint]
    unit = ("m" if joint.kind == "prismatic" else "rad") + ("/s" if timing.limit == "velocity" else "/s^2")
    source = "" if where != ("motion",) else " (the URDF's)"
    return where, (
        f"waypoint {longest} to {longest + 1} alone takes {timing.duration:.4g} s at {joint.name}'s "
        f"{timing.limit} limit of {value:g} {unit}{source} (a value in the wrong unit?)"
    )


IK_REACHED = 1e-6  # m / rad: a pose error left above this is "unreachable"


def _reached(
    read: _Reader, robot: LoadedRobot, pose: dict[str, Any], where: PathKey, start: list[float]
) -> list[float]:
    """The joint values inverse kinematics finds for a waypoint's pose, from the previous waypoint's."""
    raw = read.raw
    frames = frame_names(robot)
    if pose["frame"] not in frames:
        read.errors.append(
            raw.error(
                (*where, "frame"), f"the robot has no frame {pose['frame']!r}{did_you_mean(pose['frame'], frames)}"
            )
        )
        return start
    xyz = [read.quantity(v, "length", (*where, "xyz", k)) for k, v in enumerate(pose["xyz"])]
    turned = Quantities(raw)  # (the orientation in any form a robot spec's origin takes, to rpy, as validate does)
    turned.origin({"pose": {k: v for k, v in pose.items() if k != "xyz"}}, "pose", where[:-1])
    read.errors += turned.errors
    for note in turned.warnings:  # (a sizing file has no warnings: a quaternion that is not of unit length is refused)
        read.errors.append(
            SpecError(
                note.message.replace("; normalised", "; give it of length 1"),
                file=note.file,
                path=note.path,
                line=note.line,
                column=note.column,
            )
        )
    converted = turned.data
    for key in where:
        converted = converted[key]
    rpy = converted.get("rpy") if any(form in pose for form in ORIENTATIONS) else None
    if read.errors:
        return start
    values, error = reach(robot, pose["frame"], xyz, rpy, start)
    if error > IK_REACHED:
        read.errors.append(
            raw.error(
                where,
                f"inverse kinematics cannot put {pose['frame']!r} there within the joints' ranges (the pose "
                f"it ends at is {error:.3g} away); move the point in reach, or give the joint values",
            )
        )
    return values


def _per_joint(read: _Reader, given: Any, robot: LoadedRobot, where: PathKey, *, missing: str | None) -> list[float]:
    """A limit for every moving joint (``where``: the motion's velocity or acceleration): one value for all, a
    mapping by name, or (speeds) the URDF's velocity limit. A joint without one is an error ending in ``missing``
    (why the limit is needed), or with ``missing`` None unlimited: inf, nothing to check against (every segment's
    duration given)."""
    raw, what = read.raw, str(where[-1])
    values = []
    names = [j.name for j in robot.joints]
    said = len(read.errors)
    if isinstance(given, dict):
        for name in given:
            if name not in names:
                read.errors.append(
                    raw.error((*where, name), f"{name!r} is not a moving joint{did_you_mean(name, names)}")
                )
    for joint in robot.joints:
        value = given.get(joint.name) if isinstance(given, dict) else given
        if what == "velocity":
            kind: Kind = "linear_velocity" if joint.kind == "prismatic" else "angular_velocity"
        else:
            kind = "acceleration" if joint.kind == "prismatic" else "angular_acceleration"
        if value is None and what == "velocity" and joint.velocity is not None:
            values.append(joint.velocity)
        elif value is None and missing is None:
            values.append(math.inf)
        elif value is None:
            source = " and the URDF gives none" if what == "velocity" else ""
            message = f"joint {joint.name!r} needs {'an' if what[0] in 'aeiou' else 'a'} {what} limit{source}: give "
            read.errors.append(raw.error(where[:-1], f"{message}`{what}:`{missing}", key=True))
            values.append(math.nan)
        else:
            path = (*where, joint.name) if isinstance(given, dict) else where
            values.append(read.quantity(value, kind, path, positive=True))
    # one value for all joints is read once per joint: its problem is said once
    read.errors[said:] = list({str(e): e for e in read.errors[said:]}.values())
    return values


def _missing(timed: bool, scaling: str) -> str | None:
    """How a missing limit can be made up for (the end of its error), or None when the motion needs no such limit:
    every segment has a duration, which fixes a quintic (a trapezoid's ramps still take the acceleration limit)."""
    if not timed:
        return ", or a `duration:` for every segment (a quintic with a duration needs no limit)"
    if scaling == "trapezoid":
        return (
            ": a trapezoid's ramps take it even when the duration is given (or `scaling: quintic`, which the "
            "duration fixes)"
        )
    return None


def name_errors(sizing: Sizing, robot: LoadedRobot) -> list[SpecError]:
    """The frames and joints the sizing file names that the robot lacks, located, with the closest name."""
    raw = sizing.raw
    if raw is None:
        return []
    frames, joints = frame_names(robot), [j.name for j in robot.joints]
    data = raw.data or {}
    errors = []
    for section in ("payloads", "loads"):
        for index, item in enumerate(data.get(section, [])):
            if item["frame"] not in frames:
                message = f"the robot has no frame {item['frame']!r}{did_you_mean(item['frame'], frames)}"
                errors.append(raw.error((section, index, "frame"), message))
    for index, name in enumerate(data.get("mobile", {}).get("wheels", [])):
        if name not in joints:
            message = f"{name!r} is not a moving joint{did_you_mean(name, joints)}"
            errors.append(raw.error(("mobile", "wheels", index), message))
    for name in data.get("drives", {}):
        if name not in joints:
            message = f"{name!r} is not a moving joint{did_you_mean(name, joints)}"
            errors.append(raw.error(("drives", name), message, key=True))
    return errors
