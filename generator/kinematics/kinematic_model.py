"""The robot the kinematics commands (``gen-robot pose``, ``jacobian``) query: a pinocchio model of any robot the one
reader reads (spec, URDF, xacro document, scene), fixed at its root link, with its moving joints, the mimic joints
that follow them, and the frames (links, and the frames a spec names, which are links in its URDF).

Joint values are given by name with units (``30deg``, ``0.1 m``; default rad and m); a joint not given is 0; a mimic
joint follows its leader (value = multiplier x leader + offset) and is not given itself.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import XacrokitError
from ..shared.joint_types import MOVING
from ..shared.units import UnitError, parse_quantity
from ..shared.urdf_view import UrdfView, joint_tree, number, read_view
from ..shared.value_text import did_you_mean

MAX_DEPTH = 1000  # links from the root to a leaf: pinocchio's URDF reader crashes on chains of thousands
MAX_DOF = 150  # degrees of freedom (TIAGo dual, the largest real robot of the corpus: about 100)


@dataclass(frozen=True)
class KinematicJoint:
    """A moving joint: its name, kind, index in pinocchio's q and v, and its limits (None for a continuous joint)."""

    name: str
    kind: str
    q_index: int
    v_index: int
    limits: tuple[float, float] | None


@dataclass(frozen=True)
class Follower:
    """A mimic joint: its value is ``multiplier`` x the leader's + ``offset``."""

    joint: KinematicJoint
    leader: str
    multiplier: float
    offset: float


@dataclass
class KinematicRobot:
    """A pinocchio model (fixed at ``root``), the joints one sets (in the file's order), the mimic joints that follow
    them, and the names of its frames."""

    name: str
    root: str
    model: Any
    joints: list[KinematicJoint]
    followers: list[Follower] = field(default_factory=list)
    frames: list[str] = field(default_factory=list)
    data: Any = None

    def configuration(self, values: Mapping[str, float]) -> np.ndarray:
        """pinocchio's q: the joints at ``values`` (by name; 0 where not given), the followers at their leaders'."""
        import pinocchio as pin

        q = pin.neutral(self.model)
        for joint in self.joints:
            _set(q, joint, values.get(joint.name, 0.0))
        for follower in self.followers:
            _set(q, follower.joint, follower.multiplier * values.get(follower.leader, 0.0) + follower.offset)
        return q

    def frame_id(self, name: str, option: str) -> int:
        """pinocchio's id of the link or frame ``name`` (a link before a joint of the same name). XacrokitError
        naming ``option`` and the closest names when the robot has none."""
        import pinocchio as pin

        if name not in self.frames:
            raise XacrokitError(f"{option}: the robot has no link or frame {name!r}{did_you_mean(name, self.frames)}")
        if self.model.existFrame(name, pin.FrameType.BODY):
            return int(self.model.getFrameId(name, pin.FrameType.BODY))
        return int(self.model.getFrameId(name))


def _set(q: np.ndarray, joint: KinematicJoint, value: float) -> None:
    if joint.kind == "continuous":
        q[joint.q_index], q[joint.q_index + 1] = math.cos(value), math.sin(value)
    else:
        q[joint.q_index] = value


def load_kinematics(
    path: str | os.PathLike[str],
    mappings: Mapping[str, str] | None = None,
    *,
    package_paths: Mapping[str, str | os.PathLike[str]] | None = None,
) -> KinematicRobot:
    """Read a spec, URDF, xacro document or scene into the model the kinematics commands query.

    Raises:
        XacrokitError: unreadable input, a tree deeper than MAX_DEPTH, or one pinocchio cannot read.
        SpecErrors: an invalid spec (located).
    """
    import pinocchio as pin

    from ..reader.robot_source import robot_text

    where = Path(path)
    with robot_text(where, mappings, package_paths, meshes=False) as (text, _):  # (no mesh is read here)
        pass
    view = read_view(text, str(where))
    root, deepest = _root_and_depth(view)
    if deepest > MAX_DEPTH:
        raise XacrokitError(f"{where}: the robot's tree is {deepest} links deep; at most {MAX_DEPTH} are queried")
    try:
        model = pin.buildModelFromXML(text)
    except (RuntimeError, ValueError) as exc:
        raise XacrokitError(f"{where}: pinocchio cannot read the robot: {exc}") from None
    if model.nv > MAX_DOF:  # (before createData: its memory grows with the cube of a chain's degrees of freedom)
        raise XacrokitError(
            f"{where}: {model.nv} degrees of freedom; the kinematics commands take at most {MAX_DOF} (pinocchio's "
            "data for a chain of 200 takes 0.6 GB, of 300 1.8 GB)"
        )
    moving, followers = _joints(model, view)
    frames = [link.name for link in view.links] + [j.name for j in view.joints if j.name]
    robot = KinematicRobot(view.name or where.stem, root, model, moving, followers, list(dict.fromkeys(frames)))
    robot.data = model.createData()
    return robot


def _root_and_depth(view: UrdfView) -> tuple[str, int]:
    """The root link (the first link no joint has as child) and the most links on a path from it to a leaf."""
    tree = joint_tree(view)
    roots = [link.name for link in view.links if link.name not in tree.parent_of]
    if not roots:
        raise XacrokitError("every link is the child of a joint: the joints make a loop, not a tree")
    return roots[0], 1 + max(tree.depths([roots[0]]).values())


def _leader(view: UrdfView, name: str) -> tuple[str, float, float] | None:
    """The settable joint a mimic joint ``name`` follows, through any chain of mimics, with the multiplier and offset
    that give its value from that joint's; None when ``name`` is no mimic of a moving joint (it is set itself).

    Raises:
        XacrokitError: mimic joints that follow each other in a loop.
    """
    declared = {j.name: j for j in view.joints}
    multiplier, offset, seen, current = 1.0, 0.0, [name], name
    while True:
        mimic = declared[current].mimic
        if mimic is None or mimic.joint not in declared or declared[mimic.joint].type not in MOVING:
            return None if current == name else (current, multiplier, offset)
        factor = number(mimic.multiplier, 1.0)
        multiplier, offset = multiplier * factor, multiplier * number(mimic.offset, 0.0) + offset
        current = mimic.joint or ""
        if current in seen:
            raise XacrokitError(f"mimic joints {' -> '.join(seen + [current])} follow each other in a loop")
        seen.append(current)


def _joints(model: Any, view: UrdfView) -> tuple[list[KinematicJoint], list[Follower]]:
    """The moving joints one sets, and the mimic joints (whose leader, through any chain of mimics, is a moving
    joint) that follow them."""
    declared = {j.name: j for j in view.joints}
    moving, followers = [], []
    for index in range(1, model.njoints):
        name = model.names[index]
        joint = declared.get(name)
        if joint is None or model.nvs[index] != 1 or joint.type not in MOVING:
            continue
        limits = None
        if joint.type != "continuous" and joint.limit is not None:
            limits = (number(joint.limit.get("lower"), 0.0), number(joint.limit.get("upper"), 0.0))
        made = KinematicJoint(name, joint.type or "", int(model.idx_qs[index]), int(model.idx_vs[index]), limits)
        leader = _leader(view, name)
        if leader is not None:
            followers.append(Follower(made, *leader))
        else:
            moving.append(made)
    order = {j.name: k for k, j in enumerate(view.joints)}  # (the file's order, not pinocchio's depth-first one)
    return sorted(moving, key=lambda j: order[j.name]), followers


def joint_values(robot: KinematicRobot, given: Mapping[str, str]) -> tuple[dict[str, float], list[str]]:
    """The joint values ``given`` as text by name (``30deg``, ``0.1``: rad or m by the joint's kind), in SI, and a
    warning for each outside its limits.

    Raises:
        XacrokitError: a name that is no joint one sets (a mimic joint is set through its leader), or a value that
            does not parse.
    """
    by_name = {j.name: j for j in robot.joints}
    followers = {f.joint.name: f.leader for f in robot.followers}
    values, warnings = {}, []
    for name, text in given.items():
        if name in followers:
            raise XacrokitError(f"--at {name}: a mimic joint follows {followers[name]!r}; set that one")
        joint = by_name.get(name)
        if joint is None:
            raise XacrokitError(f"--at {name}: no moving joint of that name{did_you_mean(name, list(by_name))}")
        try:
            value = parse_quantity(text, "length" if joint.kind == "prismatic" else "angle")
        except UnitError as exc:
            raise XacrokitError(f"--at {name}={text}: {exc}") from None
        if not math.isfinite(value):
            raise XacrokitError(f"--at {name}={text}: not a finite number")
        if joint.limits is not None and not joint.limits[0] - 1e-12 <= value <= joint.limits[1] + 1e-12:
            lower, upper = joint.limits
            warnings.append(f"--at {name}={text}: {value:g} is outside the joint's limits [{lower:g}, {upper:g}]")
        values[name] = value
    return values, warnings
