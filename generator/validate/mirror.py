"""Mirrored limbs: a spec's ``mirror:`` entries written out as the links, joints and frames they make.

Each entry copies the subtree below a joint J (J, its child and everything under it: links, joints, frames with their
sensors, and their ``ros2_control`` and ``gazebo`` entries), renames it (FROM replaced by TO in every name) and
reflects it through a plane through the origin of J's parent link. S, the reflection, flips one axis of that frame
(the plane's normal: y for xz, x for yz, z for xy), and every placement T of the copy is S T S, a proper rotation:

- a placement (xyz, rpy): the flipped axis' coordinate negated, and the two angles about the other axes negated
  (S Rz(y) Ry(p) Rx(r) S = Rz(+-y) Ry(+-p) Rx(+-r), each factor about an axis other than the normal turning the other
  way); exact sign changes, no rounding;
- a revolute or continuous axis a becomes -S a (det S = -1: S Rot(a, q) S = Rot(-S a, q)), a prismatic one S a, so
  that equal joint values give mirror-image poses and the limits stay as written;
- a body's geometry in its own frame is reflected by the same S: boxes, cylinders, spheres, capsules and tubes are
  symmetric under it; a mesh gets the flipped axis' scale negated; an explicit tensor I becomes S I S (its two
  products with the flipped axis negate);
- a lidar's rays (angles about its frame's z) turn to the mirror image's: [-max, -min] for an xz plane,
  [pi - max, pi - min] for yz (a full turn is kept as it is), elevations negated for xy.

So pose(mirror(L)) = S pose(L) S in J's parent frame for every link L of the subtree and any joint values set equally
on each joint and its copy (tests/validate/test_mirror.py checks it with yourdfpy on random limbs).

It runs after the units pass (the numbers are SI) and before every other check, which see the copies as if the spec
had written them; a copy's problems are located at what it was copied from (:class:`~xacrokit.load.RawSpec` aliases).
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

from ..errors import SpecError
from ..load import PathKey, RawSpec, json_path
from ..shared.kinematic_tree import Tree
from ..shared.sim_sensors import FULL_TURN, resolve_sensor
from ..shared.value_text import did_you_mean
from .bodies import bodies
from .names import link_and_joint_names
from .schema import robot_schema

PLANES = {"yz": 0, "xz": 1, "xy": 2}  # the plane -> the axis of J's parent frame it flips (its normal)
DEFAULT_PLANE = "xz"  # left and right of a robot facing x (REP 103)
# The most links, joints and frames the entries of one spec may make together: copies of copies double, and 40
# entries, each mirroring a joint above the last one's, would make 2^40 (the largest robot of the real-robot corpus
# has under 400 links).
MAX_COPIES = 10_000
_PRODUCTS = (("ixy", (0, 1)), ("ixz", (0, 2)), ("iyz", (1, 2)))
_TURNING = ("revolute", "continuous")  # their axes become -S a (a prismatic one S a; a fixed joint has none)


def _negated(value: Any) -> Any:
    """-value for a number; a value the units pass could not read is left as it is (its error is said already)."""
    return -value if isinstance(value, (int, float)) and not isinstance(value, bool) else value


@dataclass(frozen=True)
class Reflection:
    """S: the reflection that flips ``axis`` (0, 1, 2: x, y, z) of J's parent frame, applied to spec mappings."""

    axis: int

    def point(self, values: Any) -> list[Any]:
        """S v: a position, a prismatic axis, a mesh's scale factors."""
        return [_negated(v) if i == self.axis else v for i, v in enumerate(values)]

    def turn(self, values: Any) -> list[Any]:
        """-S v: rpy angles (each about one axis), a revolute axis."""
        return [v if i == self.axis else _negated(v) for i, v in enumerate(values)]

    def origin(self, origin: Mapping[str, Any]) -> dict[str, Any]:
        """S T S of an origin (its rotation as the rpy the units pass computed from whichever form it was given in)."""
        return {
            "xyz": self.point(origin.get("xyz", (0.0, 0.0, 0.0))),
            "rpy": self.turn(origin.get("rpy", (0.0, 0.0, 0.0))),
        }

    def tensor(self, inertia: Mapping[str, Any]) -> dict[str, Any]:
        """S I S of an explicit inertia, in its mirrored frame."""
        result = dict(inertia)
        for key, pair in _PRODUCTS:
            if key in inertia and self.axis in pair:
                result[key] = _negated(inertia[key])
        if isinstance(inertia.get("origin"), dict):
            result["origin"] = self.origin(inertia["origin"])
        return result

    def shape(self, shape: Mapping[str, Any]) -> dict[str, Any]:
        """A shape reflected in its own frame: only a mesh changes (the primitives are symmetric under S)."""
        if "mesh" not in shape:
            return dict(shape)
        mesh = shape["mesh"]
        return {"mesh": {**mesh, "scale": self.point(mesh.get("scale", (1.0, 1.0, 1.0)))}}

    def body(self, item: Mapping[str, Any]) -> dict[str, Any]:
        """A link's, frame's, part's, visual's or collision's mapping with everything it places reflected."""
        result = dict(item)
        for key in ("origin", "com"):
            if isinstance(item.get(key), dict):
                result[key] = self.origin(item[key])
        if isinstance(item.get("inertia"), dict):
            result["inertia"] = self.tensor(item["inertia"])
        if isinstance(item.get("shape"), dict):
            result["shape"] = self.shape(item["shape"])
        collision = item.get("collision")
        if isinstance(collision, dict):
            result["collision"] = self.body(collision)
        elif isinstance(collision, list):
            result["collision"] = [self.body(c) for c in collision]
        for key in ("visuals", "parts"):
            if isinstance(item.get(key), list):
                result[key] = [self.body(v) for v in item[key]]
        return result

    def rays(self, low: float, high: float) -> tuple[float, float]:
        """A lidar's first and last ray angle (about its frame's z) in the mirror image (a full turn: as it is)."""
        if high - low >= FULL_TURN or self.axis == 2:
            return low, high
        return (-high, -low) if self.axis == 1 else (math.pi - high, math.pi - low)


@dataclass
class Subtree:
    """The joints, links and frames below a joint (the joint first), in the order a walk from it meets them."""

    joints: list[str] = field(default_factory=list)
    links: list[str] = field(default_factory=list)
    frames: list[str] = field(default_factory=list)

    @property
    def bodies(self) -> set[str]:
        return set(self.links) | set(self.frames)


def subtree(data: Mapping[str, Any], joint: str) -> Subtree | None:
    """What hangs below ``joint`` (None when it loops back to its own parent: the tree check says so)."""
    joints, frames = data.get("joints", {}), data.get("frames", {})
    tree: Tree[tuple[str, str]] = Tree()
    for name, item in joints.items():
        tree.add(item["parent"], item["child"], ("joint", name))
    for name, item in frames.items():
        tree.add(item["parent"], name, ("frame", name))
    top = joints[joint]["child"]
    if tree.parent_of.get(top, (None, ("joint", joint)))[1] != ("joint", joint):
        return None  # (its child has another parent first: the tree check says so)
    edges = tree.down([top], ("joint", joint), lambda _, edge: edge)  # (each body below, by the edge that hangs it)
    if joints[joint]["parent"] in edges:
        return None
    found = Subtree()
    for body, (kind, name) in edges.items():
        if kind == "joint":
            found.joints.append(name)
            found.links += [body] if body in data.get("links", {}) else []
        else:
            found.frames.append(name)
    return found


@dataclass
class Copy:
    """What one entry adds: new entries by section (the path of the mapping they go into) and where each came from."""

    entries: dict[tuple[str, ...], dict[str, Any]] = field(default_factory=dict)
    aliases: dict[PathKey, PathKey] = field(default_factory=dict)

    def add(self, section: tuple[str, ...], name: str, source: str, item: dict[str, Any]) -> None:
        self.entries.setdefault(section, {})[name] = item
        self.aliases[section + (name,)] = section + (source,)

    def applied(self, data: dict[str, Any]) -> dict[str, Any]:
        """``data`` with the new entries after each section's own (new containers; ``data`` is left as it is)."""
        result = dict(data)
        for section, items in self.entries.items():
            if len(section) == 1:
                result[section[0]] = {**result.get(section[0], {}), **items}
            else:
                holder = dict(result.get(section[0], {}))
                holder[section[1]] = {**holder.get(section[1], {}), **items}
                result[section[0]] = holder
        return result


class _Entry:
    """One ``mirror`` entry being checked and copied: its problems are (path, message) pairs."""

    def __init__(self, data: dict[str, Any], entry: Mapping[str, Any], at: PathKey, *, parsed: bool) -> None:
        self.data, self.at, self.parsed = data, at, parsed
        self.joint: str = entry["joint"]
        self.old, self.new = entry["rename"]
        self.reflect = Reflection(PLANES[entry.get("plane", DEFAULT_PLANE)])
        self.problems: list[tuple[PathKey, str]] = []
        self.names: list[tuple[str, str, str]] = []  # (kind, name, its copy's): every name the copy carries
        self.missing = False  # its joint is not in the spec

    def renamed(self, name: str, kind: str) -> str:
        self.names.append((kind, name, name.replace(self.old, self.new)))
        return name.replace(self.old, self.new)

    def copy(self) -> Copy | None:
        """The entry's copy, or None with its problems listed."""
        joints = self.data.get("joints", {})
        self.missing = self.joint not in joints
        if self.missing:
            known = did_you_mean(self.joint, joints)
            self.problems.append(
                ((*self.at, "joint"), f"no joint {self.joint!r} in joints{known}: mirror copies a joint of `joints`")
            )
            return None
        tree = subtree(self.data, self.joint)
        if tree is None:
            return None  # (a loop: the tree check says where)
        self._refusals(tree)
        made = Copy()
        self._joints(tree, made)
        self._bodies(tree, made)
        self._settings(tree, made)
        self._name_problems()
        return None if self.problems else made

    def _refusals(self, tree: Subtree) -> None:
        """Arms and wheels hung below, floating and planar joints: not copied (said at the entry's joint)."""
        inside = tree.bodies
        for section in ("arms", "wheels"):
            for name, item in self.data.get(section, {}).items():
                if item["parent"] in inside:
                    what = "an arm" if section == "arms" else "a wheel"
                    self.problems.append(
                        (
                            (*self.at, "joint"),
                            f"{what} ({name}) hangs below {self.joint}, on {item['parent']}: mirror copies links, "
                            f"joints and frames only; give its mirror in `{section}`",
                        )
                    )
        for name in tree.joints:
            kind = self.data["joints"][name]["type"]
            if kind in ("floating", "planar"):
                where = "" if name == self.joint else f" below {self.joint}"
                self.problems.append(
                    ((*self.at, "joint"), f"joint {name}{where} is {kind}: mirror copies no {kind} joint")
                )

    def _joints(self, tree: Subtree, made: Copy) -> None:
        inside = tree.bodies | set(tree.joints)
        for name in tree.joints:
            item = self.data["joints"][name]
            copy = dict(item)
            copy["child"] = self.renamed(item["child"], "link")
            if item["parent"] in inside:  # (J's own parent is outside: the copy hangs from it too)
                copy["parent"] = item["parent"].replace(self.old, self.new)
            if isinstance(item.get("origin"), dict):
                copy["origin"] = self.reflect.origin(item["origin"])
            if item["type"] in _TURNING + ("prismatic",):
                axis = item.get("axis", (1.0, 0.0, 0.0))  # (URDF's default, written out: the copy's differs)
                copy["axis"] = self.reflect.turn(axis) if item["type"] in _TURNING else self.reflect.point(axis)
            if isinstance(item.get("mimic"), dict) and item["mimic"]["joint"] in inside:
                copy["mimic"] = {**item["mimic"], "joint": item["mimic"]["joint"].replace(self.old, self.new)}
            made.add(("joints",), self.renamed(name, "joint"), name, copy)

    def _bodies(self, tree: Subtree, made: Copy) -> None:
        for name in tree.links:
            made.add(("links",), name.replace(self.old, self.new), name, self.reflect.body(self.data["links"][name]))
        for name in tree.frames:
            item = self.data["frames"][name]
            copy = self.reflect.body(item)
            copy["parent"] = item["parent"].replace(self.old, self.new)
            if "joint" in item:
                copy["joint"] = self.renamed(item["joint"], "frame joint")
            if isinstance(item.get("sensor"), dict):
                copy["sensor"] = self._sensor(name, item["sensor"])
            made.add(("frames",), self.renamed(name, "frame"), name, copy)

    def _sensor(self, frame: str, sensor: dict[str, Any]) -> dict[str, Any]:
        """A frame's sensor, its names renamed (the topic, given or the type's, so that the two never share one) and
        a lidar's rays turned to the mirror image's."""
        copy = dict(sensor)
        resolved = resolve_sensor(frame, sensor)
        copy["topic"] = self.renamed(resolved.topic, "sensor topic")
        if "optical_frame" in sensor:
            copy["optical_frame"] = self.renamed(sensor["optical_frame"], "optical frame")
        if self.parsed and resolved.kind in ("lidar", "lidar_3d"):
            low, high = self.reflect.rays(resolved.min_angle, resolved.max_angle)
            if (low, high) != (resolved.min_angle, resolved.max_angle):
                copy["horizontal"] = {**sensor.get("horizontal", {}), "min_angle": low, "max_angle": high}
            if resolved.kind == "lidar_3d" and self.reflect.axis == 2:
                turned = {"min_angle": -resolved.vertical_max, "max_angle": -resolved.vertical_min}
                copy["vertical"] = {**sensor.get("vertical", {}), **turned}
        return copy

    def _settings(self, tree: Subtree, made: Copy) -> None:
        """The subtree's ros2_control joint overrides, gazebo surfaces and joints' pose values, copied under the new
        names (a pose's value as it is: equal values give mirror images)."""
        poses = [(("poses", name), tree.joints) for name in self.data.get("poses", {})]
        for section, names in ((("ros2_control", "joints"), tree.joints), (("gazebo", "links"), tree.links), *poses):
            given = self.data.get(section[0], {}).get(section[1], {})
            for name in names:  # (an entry the spec gives for the copy's name is the spec's: kept)
                if name in given and name.replace(self.old, self.new) not in given:
                    made.add(section, name.replace(self.old, self.new), name, given[name])

    def _name_problems(self) -> None:
        """Each name the copy carries must contain FROM, be a valid name, and be new."""
        links, joints = link_and_joint_names(self.data, list(bodies(self.data)))
        taken = {item.name for item in links} | {item.name for item in joints}
        patterns = _patterns()
        where = (*self.at, "rename")
        for kind, name, new in self.names:
            if self.old not in name:
                self.problems.append(
                    (
                        where,
                        f"{kind} {name!r}, which the mirror of {self.joint} copies, has no {self.old!r} in it, so "
                        f"its copy would have the same name: rename it to contain {self.old!r}"
                        + (" (give the sensor a `topic`)" if kind == "sensor topic" else ""),
                    )
                )
            elif len(new) > patterns[kind][1]:
                self.problems.append(
                    (
                        where,
                        f"the mirror of {kind} {name!r} would be named with {len(new):,} characters, beyond the "
                        f"{patterns[kind][1]} a name may have",
                    )
                )
            elif not re.fullmatch(patterns[kind][0], new):
                self.problems.append((where, f"the mirror of {kind} {name!r} would be named {new!r}, not a valid name"))
            elif kind != "sensor topic" and new in taken:
                self.problems.append(
                    (where, f"the mirror of {kind} {name!r} is named {new!r}, a name the spec already has")
                )


def _patterns() -> dict[str, tuple[str, int]]:
    """The schema's name patterns and longest lengths, by the kind of name a copy carries."""
    definitions = robot_schema()["$defs"]
    urdf = (definitions["urdf_name"]["pattern"], definitions["urdf_name"]["maxLength"])
    identifier = (definitions["identifier"]["pattern"], definitions["identifier"]["maxLength"])
    topic_schema = definitions["sensor"]["properties"]["topic"]
    return {
        "link": urdf,
        "joint": urdf,
        "frame": identifier,
        "frame joint": identifier,
        "optical frame": urdf,
        "sensor topic": (topic_schema["pattern"], topic_schema["maxLength"]),
    }


def mirrored(
    raw: RawSpec, data: dict[str, Any], *, parsed: bool
) -> tuple[dict[str, Any], dict[PathKey, PathKey], list[SpecError]]:
    """``data`` with every ``mirror`` entry's copy added (in order: a later entry may mirror an earlier one's copy),
    the aliases (a copy's path -> its source's) and the located problems of the entries that made no copy.

    ``parsed``: every quantity read (else a lidar's rays are not turned: their values may still be text)."""
    aliases: dict[PathKey, PathKey] = {}
    errors: list[SpecError] = []
    unmade: set[str] = set()  # (the names entries that failed would have made)
    for index, given in enumerate(data.get("mirror", ())):
        entry = _Entry(data, given, ("mirror", index), parsed=parsed)
        made = entry.copy()
        if not (entry.missing and entry.joint in unmade):  # (its joint is an earlier failed copy's: said there)
            errors += [raw.error(path, message) for path, message in entry.problems]
        if entry.problems:
            unmade.update(new for _, _, new in entry.names)
        if made is not None and len(aliases) + len(made.aliases) > MAX_COPIES:
            message = (
                f"the mirrors up to this one would make {len(aliases) + len(made.aliases):,} links, joints, frames and "
                f"settings, beyond the {MAX_COPIES:,} a spec's mirrors may make (does an entry mirror a joint above "
                "an earlier one's copy?)"
            )
            errors.append(raw.error(("mirror", index), message))
            break
        if made is not None:
            data = made.applied(data)
            aliases.update(made.aliases)
    return data, aliases, errors


def copies_said(errors: list[SpecError], aliases: Mapping[PathKey, PathKey]) -> Iterator[SpecError]:
    """``errors`` without a copy's error at the position of one its source has (said once, at the source); a copy's
    other errors name what it was copied from."""
    made = {json_path(path): json_path(source) for path, source in aliases.items()}
    origins = [_made_from(error.path, made) for error in errors]
    plain = {(e.line, e.column) for e, origin in zip(errors, origins, strict=True) if origin is None}
    for error, origin in zip(errors, origins, strict=True):
        if origin is None:
            yield error
        elif (error.line, error.column) not in plain:
            note = f" (in the mirror `mirror` makes of {origin})"
            yield type(error)(
                error.message + note, file=error.file, path=error.path, line=error.line, column=error.column
            )


def _made_from(path: str, made: Mapping[str, str]) -> str | None:
    """The source of the copy ``path`` (a JSON path) lies in, or None: each of its prefixes that ends a key looked up
    once (linear in the path, whatever the number of copies)."""
    for end in [i for i, c in enumerate(path) if c in ".["] + [len(path)]:
        if path[:end] in made:
            return made[path[:end]]
    return None
