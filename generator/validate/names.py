"""The names pass: the link and joint names a spec creates (with where each comes from) are unique and not reserved,
every reference (parents, children, materials, mimic joints, Gazebo and ros2_control entries) names something that
exists, and the links form one tree."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

from ..errors import SpecError
from ..load import PathKey, RawSpec, json_path
from ..model import MOVING, arm_base_name, attach_joint_name
from ..shared.kinematic_tree import Tree, cycles
from ..shared.package_data import PUBLIC_MACROS, XACRO_KEYWORDS
from ..shared.sim_sensors import CAMERAS, optical_name, sensor_kind
from ..shared.value_text import did_you_mean
from .bodies import Body, geometries, has_base_link, tool_joint_name

# The robot name becomes a xacro macro name: it must not shadow a library macro or a xacro keyword.
RESERVED_ROBOT_NAMES = frozenset({*PUBLIC_MACROS, *XACRO_KEYWORDS})


@dataclass(frozen=True)
class Named:
    """A link or joint name the spec creates; ``path`` (its key when ``at_key``) is where the spec gives it."""

    name: str
    path: PathKey
    at_key: bool


def link_and_joint_names(data: dict[str, Any], bodies: Sequence[Body]) -> tuple[list[Named], list[Named]]:
    """Every link and joint name the spec will create, with where each comes from, in the spec's order."""
    links: list[Named] = []
    joints = [Named(n, ("joints", n), True) for n in data.get("joints", {})]
    for kind, name, path, item in bodies:
        if kind == "link":
            links.append(Named(name, path, True))
        elif kind == "row":
            links.append(Named(name, (*path, "link"), False))
            joints.append(Named(item["name"], (*path, "name"), False))
        elif kind == "tool":  # named in the spec, or tool0 made for the arm
            named = "name" in item
            where = (*path, "name") if named else path[:2]
            links.append(Named(name, where, not named))
            if "joint" in item:
                joints.append(Named(item["joint"], (*path, "joint"), False))
            else:
                joints.append(Named(tool_joint_name(item), where, not named))
        elif kind == "arm" and not has_base_link(item):  # (base: false: the arm makes no link of its own)
            continue
        elif kind in ("wheel", "frame") and "joint" in item:  # its joint named in the spec (joint: NAME)
            links.append(Named(name, path, True))
            joints.append(Named(item["joint"], (*path, "joint"), False))
        else:  # an arm's base, a wheel, a frame: a link and the joint that attaches it
            links.append(Named(name, path, True))
            joints.append(Named(attach_joint_name(name), path, True))
        if kind == "frame" and isinstance(item.get("sensor"), dict) and sensor_kind(item["sensor"]) in CAMERAS:
            optical = optical_name(name, item["sensor"])  # (a camera's optical frame: a link and its joint)
            where = (*path, "sensor", "optical_frame") if "optical_frame" in item["sensor"] else (*path, "sensor")
            links.append(Named(optical, where, "optical_frame" not in item["sensor"]))
            joints.append(Named(attach_joint_name(optical), where, "optical_frame" not in item["sensor"]))
    if "mount_joint" in data:  # (the root's mount, made where the robot is mounted: named in the spec)
        joints.append(Named(data["mount_joint"], ("mount_joint",), False))
    return links, joints


def duplicate_errors(raw: RawSpec, named: list[Named], what: str) -> Iterator[SpecError]:
    """A name given again after its first use, pointing at both."""
    first: dict[str, Named] = {}
    for item in named:
        if item.name in first:
            other = first[item.name]
            line, _ = raw.locate(other.path, key=other.at_key)
            yield raw.error(
                item.path,
                f"{what} name {item.name!r} is already used by {json_path(other.path)} "
                f"(line {line}); names must be unique",
                key=item.at_key,
            )
        else:
            first[item.name] = item


def repeated_paths(named: list[Named]) -> list[PathKey]:
    """Where a name is given again after its first use (the places :func:`duplicate_errors` reports)."""
    seen: set[str] = set()
    again = []
    for item in named:
        if item.name in seen:
            again.append(item.path)
        seen.add(item.name)
    return again


def robot_name_problem(name: str) -> str | None:
    """Why xacro cannot take ``name`` as a robot's (its macro, and properties such as NAME_materials_defined, are
    named after it), None when it can: the schema has already checked it is an identifier of at most 200 characters.
    Asked by validate, by ``gen-robot new`` and by the importer, so that all three accept the same names."""
    if name in RESERVED_ROBOT_NAMES or name.startswith("_xacrokit"):
        return "is taken by a xacrokit macro or a xacro keyword (the robot's macro is named after it)"
    if name.startswith("__"):
        return (
            "starts with two underscores, which xacro refuses in the macro and property names made from it "
            "(names of Python's internals)"
        )
    return None


def robot_name_errors(raw: RawSpec, data: dict[str, Any]) -> Iterator[SpecError]:
    problem = robot_name_problem(data["robot"])
    if problem is not None:
        yield raw.error(("robot",), f"robot name {data['robot']!r} {problem}; choose another name")


def edges(data: dict[str, Any], bodies: Sequence[Body]) -> list[tuple[str, str, PathKey]]:
    """(parent, child, where) for every parent-child relation the spec creates: the joints', then each body's."""
    joints = data.get("joints", {})
    result: list[tuple[str, str, PathKey]] = [(j["parent"], j["child"], ("joints", n)) for n, j in joints.items()]
    above = ""  # the link before the current one along an arm: its base, then each row's link
    for kind, name, path, item in bodies:
        if kind in ("row", "tool"):
            result.append((above, name, path))
        elif kind != "link" and not (kind == "arm" and not has_base_link(item)):  # an arm's base, a wheel, a frame:
            result.append((item["parent"], name, (*path, "parent")))  # hung from the parent the spec names
        if kind == "frame" and isinstance(item.get("sensor"), dict) and sensor_kind(item["sensor"]) in CAMERAS:
            result.append((name, optical_name(name, item["sensor"]), (*path, "sensor")))  # (a camera's optical frame)
        above = name
    return result


def tree_errors(raw: RawSpec, relations: list[tuple[str, str, PathKey]], link_names: set[str]) -> Iterator[SpecError]:
    """A link with two parents, links in a cycle, and links that do not form exactly one tree, given the spec's
    :func:`edges`."""
    tree: Tree[PathKey] = Tree()
    dangling: list[str] = []  # children of unknown parents: the bad reference is reported, not the tree again
    for parent, child, where in relations:
        if parent == child and where[0] == "joints":
            continue  # "a joint cannot connect a link to itself" says it; not a cycle to report again
        if parent not in link_names:
            dangling.append(child)
            tree.parent_of.setdefault(child, (parent, where))
            continue
        first = tree.add(parent, child, where)
        if first is not None:
            yield raw.error(
                where,
                f"link {child!r} already has parent {first[0]!r}; a link can hang from one joint only (URDF is a tree)",
            )
    roots = tree.roots(link_names)
    unknown_children = [child for _, child, where in relations if child not in link_names and where[0] == "joints"]
    stranded = sorted(link_names - tree.reachable([*roots, *dangling]))
    if stranded:
        where = tree.parent_of[stranded[0]][1]
        yield raw.error(where, f"links {', '.join(stranded)} form a cycle (each hangs from another in the loop)")
    if len(roots) > 1 and len(roots) - 1 > len(unknown_children):  # (a mistyped child leaves its link a root: its
        listed = ", ".join(roots)  # reference error says so, and the trees may well be one once it is corrected)
        yield raw.error(
            ("links",),
            f"the links form {len(roots)} separate trees (roots: {listed}); connect them with "
            "joints so that exactly one link has no parent",
            key=True,
        )
    elif not roots and not stranded:
        yield raw.error(("links",), "no root link", key=True)


def reference_errors(
    raw: RawSpec, data: dict[str, Any], bodies: Sequence[Body], link_names: set[str], types: dict[str, str]
) -> Iterator[SpecError]:
    """Parents, children, materials, mimic joints, Gazebo links and ros2_control joints that name nothing."""
    materials = set(data.get("materials", {}))
    for kind, _, path, item in bodies:
        if kind in ("arm", "wheel", "frame") and item["parent"] not in link_names:
            parent = item["parent"]
            yield raw.error(
                (*path, "parent"), f"parent {parent!r} is not a link of this robot{did_you_mean(parent, link_names)}"
            )
        if kind == "arm" and not has_base_link(item) and "origin" in item:
            yield raw.error(
                (*path, "origin"),
                f"an arm with base: false has DH frame 0 at its parent {item['parent']!r}, so it takes no origin; "
                f"place {item['parent']!r} there instead, or drop base: false (DH frame 0 is then a link "
                f"{arm_base_name(str(path[1]))!r} at origin)",
                key=True,
            )
        material = item.get("material")
        if material is not None and material not in materials:
            known = ", ".join(sorted(materials)) or "none defined"
            yield raw.error((*path, "material"), f"material {material!r} is not in materials (known: {known})")
    for name, link in data.get("links", {}).items():  # (a composite link's parts and a link's other visuals)
        drawn = [(("links", name, "parts", i), p) for i, p in enumerate(link.get("parts", ()))]
        for path, item in drawn + [g for g in geometries(("links", name), link) if g[0][2] == "visuals"]:
            material = item.get("material")
            if material is not None and material not in materials:
                known = ", ".join(sorted(materials)) or "none defined"
                yield raw.error((*path, "material"), f"material {material!r} is not in materials (known: {known})")
    for name, joint in data.get("joints", {}).items():
        yield from _joint_reference_errors(raw, name, joint, link_names, data.get("links", {}), types)
    mimics = {n: j["mimic"]["joint"] for n, j in data.get("joints", {}).items() if j.get("mimic")}
    for loop in cycles(mimics):
        if len(loop) > 1:  # (a joint that mimics itself is said above)
            yield raw.error(
                ("joints", loop[0], "mimic", "joint"),
                f"mimic joints {' -> '.join([*loop, loop[0]])} form a cycle: none of them moves by itself; let one "
                "of them be driven (remove its mimic)",
            )
    for name in data.get("gazebo", {}).get("links", {}):
        if name not in link_names:
            yield raw.error(("gazebo", "links", name), f"gazebo settings for {name!r}, which is not a link", key=True)
    for name in data.get("ros2_control", {}).get("joints", {}):
        if types.get(name) not in MOVING:
            what = "is not a joint" if name not in types else f"is a {types[name]} joint"
            yield raw.error(
                ("ros2_control", "joints", name), f"{name!r} {what}; only moving joints are controlled", key=True
            )
    yield from _pose_reference_errors(raw, data, types)
    yield from _planning_reference_errors(raw, data, types)


def _planning_reference_errors(raw: RawSpec, data: dict[str, Any], types: dict[str, str]) -> Iterator[SpecError]:
    """The ``moveit`` section's groups and gripper name joints of the robot (a gripper's: moving joints)."""
    section = data.get("moveit", {})
    named = [
        (("moveit", "groups", g, i), j) for g, joints in section.get("groups", {}).items() for i, j in enumerate(joints)
    ]
    gripper = [(("moveit", "gripper", i), j) for i, j in enumerate(section.get("gripper", ()))]
    moving = sorted(n for n, t in types.items() if t in MOVING)
    for where, name in named + gripper:
        if name not in types:
            yield raw.error(where, f"{name!r} is not a joint of this robot{did_you_mean(name, set(types))}")
        elif where[1] == "gripper" and types[name] not in MOVING:
            yield raw.error(where, f"{name!r} is a {types[name]} joint; a gripper's joints move ({', '.join(moving)})")


def _pose_reference_errors(raw: RawSpec, data: dict[str, Any], types: dict[str, str]) -> Iterator[SpecError]:
    """A named pose gives moving joints that move by themselves."""
    moving = sorted(n for n, t in types.items() if t in MOVING)
    for pose, values in data.get("poses", {}).items():
        for name in values:
            where = ("poses", pose, name)
            if types.get(name) not in MOVING:
                what = (
                    f"is not a joint{did_you_mean(name, moving)}" if name not in types else f"is a {types[name]} joint"
                )
                yield raw.error(where, f"{name!r} {what}; a pose gives the positions of moving joints", key=True)
            elif mimic := data.get("joints", {}).get(name, {}).get("mimic"):
                yield raw.error(
                    where, f"{name!r} follows {mimic['joint']!r} (mimic): give {mimic['joint']!r}'s position", key=True
                )


def _joint_reference_errors(
    raw: RawSpec,
    name: str,
    joint: dict[str, Any],
    link_names: set[str],
    spec_links: dict[str, Any],
    types: dict[str, str],
) -> Iterator[SpecError]:
    path = ("joints", name)
    if joint["parent"] not in link_names:
        yield raw.error(
            (*path, "parent"),
            f"parent {joint['parent']!r} is not a link of this robot{did_you_mean(joint['parent'], link_names)}",
        )
    if joint["child"] not in spec_links:
        yield raw.error(
            (*path, "child"), f"child {joint['child']!r} is not in links{did_you_mean(joint['child'], set(spec_links))}"
        )
    if joint["parent"] == joint["child"]:
        yield raw.error((*path, "child"), "a joint cannot connect a link to itself")
    mimic = joint.get("mimic")
    if mimic:
        target = mimic["joint"]
        if target not in types:
            yield raw.error((*path, "mimic", "joint"), f"mimic joint {target!r} is not a joint of this robot")
        elif target == name:
            yield raw.error((*path, "mimic", "joint"), "a joint cannot mimic itself")
        elif types[target] not in MOVING or joint["type"] not in MOVING:
            yield raw.error(
                (*path, "mimic", "joint"),
                f"mimic needs two moving joints; {target!r} is {types[target]} and this one is {joint['type']}",
            )
