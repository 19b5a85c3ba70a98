"""The bodies of a spec, in one walk that every pass reads instead of looping over each section itself: each link,
arm, arm row, arm tool, wheel and frame that makes a link of the robot, with where its mapping is.

The order is the spec's sections in a fixed order (links, arms, wheels, frames) and, within an arm, the arm itself
(its base link), its rows, then its tool: the order of the links along the arm. The name checks rely on it (the first
of two equal names is the one the second is said to clash with), and so does the tree (the first parent of a link
wins).
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from typing import Any, Literal

from ..load import PathKey
from ..model import DEFAULT_TOOL, arm_base_name, attach_joint_name

BodyKind = Literal["link", "arm", "row", "tool", "wheel", "frame", "part"]

# One body of a spec: (kind, name, path, mapping). A plain tuple, and validate lists the bodies once for all the passes
# after the units: an object per body, or a walk per pass, made validation measurably slower on big robots.
#   kind: link (an entry of links), arm (an arm, whose body is its base link), row (a row of an arm's joints), tool
#         (an arm's tool frame), wheel or frame.
#   name: the name of the link the body makes (NAME_base for an arm, tool0 for a tool named nowhere); for an arm
#         without a base link (base: false), its parent's name: the link its first row hangs on, which it does not
#         make (see :func:`has_base_link`).
#   path: where the body's mapping is in the spec (path[0] is its section; an arm's tool: arms.NAME.tool, also when
#         the spec gives none).
#   mapping: the body's mapping in the spec (an arm's tool not given: an empty one).
Body = tuple[BodyKind, str, PathKey, dict[str, Any]]


def bodies(data: dict[str, Any]) -> Iterator[Body]:
    """Every body of a spec whose sections have the shapes the schema guarantees, in the order described above."""
    for name, link in data.get("links", {}).items():
        yield ("link", name, ("links", name), link)
    for name, arm in data.get("arms", {}).items():
        yield ("arm", arm_base_name(name) if has_base_link(arm) else arm["parent"], ("arms", name), arm)
        for index, row in enumerate(arm["joints"]):
            yield ("row", row["link"], ("arms", name, "joints", index), row)
        tool = arm.get("tool", {})
        yield ("tool", tool.get("name", DEFAULT_TOOL), ("arms", name, "tool"), tool)
    for name, wheel in data.get("wheels", {}).items():
        yield ("wheel", name, ("wheels", name), wheel)
    for name, frame in data.get("frames", {}).items():
        yield ("frame", name, ("frames", name), frame)


def has_base_link(arm: dict[str, Any]) -> bool:
    """Whether an arm makes a link of its own for DH frame 0 (NAME_base; not with ``base: false``)."""
    return arm.get("base", True) is not False


def tool_joint_name(tool: dict[str, Any]) -> str:
    """The name of an arm's tool joint: the tool mapping's ``joint``, else TOOL_joint (tool0_joint by default)."""
    return str(tool.get("joint") or attach_joint_name(tool.get("name", DEFAULT_TOOL)))


def parts(data: dict[str, Any]) -> Iterator[Body]:
    """Every part of a composite link (``links.NAME.parts``), as ("part", link name, path, mapping): bodies of the
    link, not links of their own (so not among :func:`bodies`)."""
    for name, link in data.get("links", {}).items():
        for index, part in enumerate(link.get("parts", ())):
            yield ("part", name, ("links", name, "parts", index), part)


def geometries(path: PathKey, link: dict[str, Any]) -> Iterator[tuple[PathKey, dict[str, Any]]]:
    """The mappings of a link, besides the link itself, that hold a shape and an origin: its collision (one, or each
    of a list) and each of its ``visuals``, with their paths."""
    collision = link.get("collision")
    if isinstance(collision, dict):
        yield (*path, "collision"), collision
    elif isinstance(collision, list):
        yield from (((*path, "collision", i), c) for i, c in enumerate(collision) if isinstance(c, dict))
    yield from (((*path, "visuals", i), v) for i, v in enumerate(link.get("visuals", ())) if isinstance(v, dict))


def joint_types(data: dict[str, Any], bodies: Sequence[Body]) -> dict[str, str]:
    """The type of every joint a reference may name: the spec's joints, arm rows, wheels' and frames' joints. (An
    arm's base and tool joints are not among them.)"""
    types = {n: j["type"] for n, j in data.get("joints", {}).items()}
    for kind, name, _, item in bodies:
        if kind == "row":
            types[item["name"]] = item.get("type", "revolute")
        elif kind == "wheel":
            types[item.get("joint", attach_joint_name(name))] = "continuous"
        elif kind == "frame":
            types[item.get("joint", attach_joint_name(name))] = "fixed"
    return types
