"""The one kinematic model of a read robot (:attr:`xacrokit.reader.read_robot.ReadRobot.kinematics`): a pinocchio
model of its URDF fixed at its root link, built once, with the joint conventions written here and nowhere else:

* the joints one sets are the revolute, continuous and prismatic joints that mimic no moving joint, in the file's
  order; a mimic joint follows its leader, through any chain of mimics (value = multiplier x leader + offset);
* a continuous joint's position is (cos q, sin q) in pinocchio's configuration (:func:`configurations`);
* a joint's limits are its ``<limit lower upper>`` (URDF's default 0 for either one absent); a continuous joint, or
  one without ``<limit>``, has none, and a search over it takes one turn either way (:attr:`KinematicJoint.span`);
* an axis is read as a direction: scaled before its norm (an axis of 1e308 1e308 0 is the diagonal), a zero axis
  refused; an origin's or axis's number that is not finite, or a length beyond 1e4 m, refused with the element named
  (export and render refuse the same values in the same words).

Joint values are given by name with units (``30deg``, ``0.1 m``; default rad and m); a joint not given is 0.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from lxml import etree

from ..errors import XacrokitError
from ..shared.joint_types import MOVING
from ..shared.units import UnitError, parse_quantity
from ..shared.urdf_view import Joint, UrdfView, joint_tree, length_problems, number
from ..shared.value_text import did_you_mean
from .robot_source import urdf_floats

MAX_DEPTH = 1000  # links from the root to a leaf: pinocchio's URDF reader crashes on chains of thousands
MAX_DOF = 150  # degrees of freedom (TIAGo dual, the largest real robot of the corpus: about 100)


@dataclass(frozen=True)
class KinematicJoint:
    """A moving joint: its name, kind, index in pinocchio's q and v, its limits (None for a continuous joint or one
    without ``<limit>``), and its effort and velocity limits (None where not a number >= 0)."""

    name: str
    kind: str
    q_index: int
    v_index: int
    limits: tuple[float, float] | None
    effort: float | None = None
    velocity: float | None = None

    @property
    def span(self) -> tuple[float, float]:
        """The range a search over the joint covers: its limits in order, or one turn either way without them."""
        if self.limits is None:
            return -math.pi, math.pi
        lower, upper = self.limits
        return (lower, upper) if lower <= upper else (upper, lower)


@dataclass(frozen=True)
class Follower:
    """A mimic joint: its value is ``multiplier`` x the leader's + ``offset``."""

    joint: KinematicJoint
    leader: str
    multiplier: float
    offset: float


@dataclass(frozen=True)
class KinematicModel:
    """A pinocchio model (fixed at ``root``) and its scratch data; the joints one sets (the file's order), the mimic
    joints that follow them, every moving joint in pinocchio's order (``moving``: what a search over the whole
    robot's joints covers, mimic joints as joints of their own) and the names of its links and joints."""

    name: str
    root: str
    model: Any
    data: Any
    joints: tuple[KinematicJoint, ...]
    followers: tuple[Follower, ...]
    moving: tuple[KinematicJoint, ...]
    frames: tuple[str, ...]

    def configuration(self, values: Mapping[str, float]) -> np.ndarray:
        """pinocchio's q: the joints at ``values`` (by name; 0 where not given), the followers at their leaders'."""
        given = [(j, values.get(j.name, 0.0)) for j in self.joints]
        given += [(f.joint, f.multiplier * values.get(f.leader, 0.0) + f.offset) for f in self.followers]
        q: np.ndarray = configurations(self.model, [j for j, _ in given], np.array([[v for _, v in given]]))[0]
        return q

    def placed(self, q: np.ndarray) -> Any:
        """Every frame placed in the root's at pinocchio's ``q`` (pinocchio's ``oMf``, in the model's data)."""
        import pinocchio as pin  # (heavy: pinocchio)

        pin.framesForwardKinematics(self.model, self.data, q)
        return self.data.oMf

    def frame_id(self, name: str) -> int:
        """pinocchio's id of the link or joint frame ``name`` (a link before a joint of the same name).

        Raises:
            UnknownName: the robot has no link or joint of that name (the closest names said).
        """
        import pinocchio as pin  # (heavy: pinocchio)

        if name not in self.frames:
            said = f"the robot has no link or frame {name!r}{did_you_mean(name, list(self.frames))}"
            raise UnknownName(said, role="frame", name=name)
        if self.model.existFrame(name, pin.FrameType.BODY):
            return int(self.model.getFrameId(name, pin.FrameType.BODY))
        return int(self.model.getFrameId(name))


class UnknownName(XacrokitError):
    """A frame or joint the robot does not have, or a mimic joint given a value (``role``: "frame" or "joint";
    ``name``: the name asked); the command line says which option named it."""

    def __init__(self, detail: str, *, role: str, name: str) -> None:
        super().__init__(f"joint {name!r}: {detail}" if role == "joint" else detail)
        self.role, self.name, self.detail = role, name, detail


class JointValueError(XacrokitError):
    """A joint value that does not read as a finite angle or length (``joint``, ``text``: what was given;
    ``reason``: why not)."""

    def __init__(self, joint: str, text: str, reason: str) -> None:
        super().__init__(f"joint {joint!r} = {text}: {reason}")
        self.joint, self.text, self.reason = joint, text, reason


@dataclass(frozen=True)
class LimitWarning:
    """A joint value outside its joint's limits (allowed: a pose may be asked anywhere)."""

    joint: str
    text: str
    value: float
    limits: tuple[float, float]

    def __str__(self) -> str:
        lower, upper = self.limits
        return f"joint {self.joint!r} = {self.text}: {self.value:g} is outside its limits [{lower:g}, {upper:g}]"


def configurations(model: Any, joints: Sequence[KinematicJoint], values: np.ndarray) -> np.ndarray:
    """pinocchio's q for each row of ``values`` (one column per joint of ``joints``; the other joints neutral): the
    one place a continuous joint's angle becomes (cos, sin)."""
    import pinocchio as pin  # (heavy: pinocchio)

    result = np.tile(pin.neutral(model), (len(values), 1))
    for column, joint in enumerate(joints):
        if joint.kind == "continuous":
            result[:, joint.q_index] = np.cos(values[:, column])
            result[:, joint.q_index + 1] = np.sin(values[:, column])
        else:
            result[:, joint.q_index] = values[:, column]
    return result


def build_kinematics(text: str, view: UrdfView, name: str) -> KinematicModel:
    """The kinematic model of the URDF ``text`` (whose view is ``view``; ``name`` for a robot without one).

    Raises:
        XacrokitError: a tree deeper than MAX_DEPTH or looped, more than MAX_DOF degrees of freedom, a joint origin
            or axis that is not finite numbers or beyond 1e4 m, a zero axis, mimic joints in a loop, or a robot
            pinocchio cannot read.
    """
    import pinocchio as pin  # (heavy: pinocchio)

    root, deepest = _root_and_depth(view)
    if deepest > MAX_DEPTH:
        raise XacrokitError(f"the robot's tree is {deepest} links deep; at most {MAX_DEPTH} are queried")
    require_placeable(view)
    try:
        model = pin.buildModelFromXML(_with_unit_axes(text, view))
    except (RuntimeError, ValueError) as exc:
        raise XacrokitError(f"pinocchio cannot read the robot: {exc}") from None
    if model.nv > MAX_DOF:  # (before createData: its memory grows with the cube of a chain's degrees of freedom)
        raise XacrokitError(
            f"{model.nv} degrees of freedom; the kinematics commands take at most {MAX_DOF} (pinocchio's data for a "
            "chain of 200 takes 0.6 GB, of 300 1.8 GB)"
        )
    moving = _moving(model, view)
    leaders = {j.name: _leader(view, j.name) for j in moving}
    order = {j.name: k for k, j in enumerate(view.joints)}  # (the file's order, not pinocchio's depth-first one)
    settable = sorted((j for j in moving if leaders[j.name] is None), key=lambda j: order[j.name])
    followers = [Follower(j, *leader) for j in moving if (leader := leaders[j.name]) is not None]
    frames = dict.fromkeys([link.name for link in view.links] + [j.name for j in view.joints if j.name])
    return KinematicModel(
        view.name or name, root, model, model.createData(), tuple(settable), tuple(followers), moving, tuple(frames)
    )


def require_placeable(view: UrdfView) -> None:
    """Refuse what no command can place a robot's parts with, in the same words for every command (pose, size,
    render, export): a joint origin that is not finite numbers, a moving joint's axis that is not or is zero, a
    length beyond 1e4 m (:func:`~xacrokit.shared.urdf_view.length_problems`).

    Raises:
        XacrokitError: the first such value, named by its joint and attribute (lengths: all of them).
    """
    for joint in view.joints:
        if joint.origin is not None:
            urdf_floats(joint.origin.xyz, 3, where=f"joint {joint.name!r} origin xyz")
            urdf_floats(joint.origin.rpy, 3, where=f"joint {joint.name!r} origin rpy")
        if joint.type in MOVING or joint.type == "planar":
            unit_axis(joint)
    problems = length_problems(view)
    if problems:
        raise XacrokitError("; ".join(problems))


def unit_axis(joint: Joint) -> np.ndarray:
    """A joint's axis as a unit vector (URDF's default 1 0 0 without ``<axis>``), scaled before its norm so that an
    axis of 1e308 1e308 0 is the diagonal it names.

    Raises:
        XacrokitError: not three finite numbers, or all zero.
    """
    said = f"joint {joint.name!r} axis"
    axis = np.array(urdf_floats(joint.axis, 3, where=said)) if joint.axis is not None else np.array([1.0, 0.0, 0.0])
    largest = float(np.abs(axis).max())
    if not largest > 0:
        raise XacrokitError(f"joint {joint.name!r}: its axis is zero: it names no direction to turn or slide along")
    axis = axis / largest  # (first: the norm of an axis of 1e308 overflows)
    return np.asarray(axis / np.linalg.norm(axis))


def _with_unit_axes(text: str, view: UrdfView) -> str:
    """``text``, or, when a moving joint's axis would not survive pinocchio's own normalisation (its norm overflows
    or underflows), a copy with those axes written as unit vectors (the view stays as read; :func:`require_placeable`
    has refused the axes that are not finite numbers or zero)."""
    rewritten: dict[str, np.ndarray] = {}
    for joint in view.joints:
        if joint.axis is not None and (joint.type in MOVING or joint.type == "planar"):
            given = np.array(urdf_floats(joint.axis, 3))
            with np.errstate(over="ignore", under="ignore"):  # (as pinocchio's own norm: its square overflows)
                norm = float(np.sqrt(np.sum(given * given)))
            if not (math.isfinite(norm) and norm > 1e-150):
                rewritten[joint.name] = unit_axis(joint)
    if not rewritten:
        return text
    root = etree.fromstring(etree.tostring(view.root))
    for element in root.iterchildren("joint"):
        unit = rewritten.get(element.get("name", ""))
        found = element.find("axis")
        if unit is not None and found is not None:
            found.set("xyz", " ".join(repr(float(v)) for v in unit))
    return str(etree.tostring(root, encoding="unicode"))


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


def _moving(model: Any, view: UrdfView) -> tuple[KinematicJoint, ...]:
    """Every revolute, continuous and prismatic joint with one degree of freedom, in pinocchio's order."""
    declared = {j.name: j for j in view.joints}
    found = []
    for index in range(1, model.njoints):
        joint = declared.get(model.names[index])
        if joint is None or model.nvs[index] != 1 or joint.type not in MOVING:
            continue  # (a floating or planar joint stays at its neutral pose)
        limits = None
        if joint.type != "continuous" and joint.limit is not None:
            limits = (number(joint.limit.get("lower"), 0.0), number(joint.limit.get("upper"), 0.0))
        found.append(
            KinematicJoint(
                joint.name,
                joint.type or "",
                int(model.idx_qs[index]),
                int(model.idx_vs[index]),
                limits,
                _given(joint.limit, "effort"),
                _given(joint.limit, "velocity"),
            )
        )
    return tuple(found)


def _given(limit: Mapping[str, str] | None, key: str) -> float | None:
    """A limit's effort or velocity; None when not given or not a number >= 0 (a limit of 0 is a limit: its margin
    is 0, not "no limit")."""
    try:
        value = float((limit or {}).get(key, ""))
    except ValueError:
        return None
    return value if 0 <= value < math.inf else None


def joint_values(robot: KinematicModel, given: Mapping[str, str]) -> tuple[dict[str, float], list[LimitWarning]]:
    """The joint values ``given`` as text by name (``30deg``, ``0.1``: rad or m by the joint's kind), in SI, and a
    warning for each outside its limits.

    Raises:
        UnknownName: a name that is no joint one sets (a mimic joint is set through its leader).
        JointValueError: a value that does not parse or is not finite.
    """
    by_name = {j.name: j for j in robot.joints}
    followers = {f.joint.name: f.leader for f in robot.followers}
    values, warnings = {}, []
    for name, text in given.items():
        if name in followers:
            said = f"a mimic joint follows {followers[name]!r}; set that one"
            raise UnknownName(said, role="joint", name=name)
        joint = by_name.get(name)
        if joint is None:
            said = f"no moving joint of that name{did_you_mean(name, list(by_name))}"
            raise UnknownName(said, role="joint", name=name)
        try:
            value = parse_quantity(text, "length" if joint.kind == "prismatic" else "angle")
        except UnitError as exc:
            raise JointValueError(name, text, str(exc)) from None
        if not math.isfinite(value):
            raise JointValueError(name, text, "not a finite number")
        if joint.limits is not None and not joint.limits[0] - 1e-12 <= value <= joint.limits[1] + 1e-12:
            warnings.append(LimitWarning(name, text, value, joint.limits))
        values[name] = value
    return values, warnings
