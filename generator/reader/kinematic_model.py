"""The one kinematic model of a read robot (:attr:`xacrokit.reader.read_robot.ReadRobot.kinematics`): a pinocchio
model of its URDF fixed at its root link, built once, with the joint conventions written here and nowhere else:

* the joints one sets are the revolute, continuous and prismatic joints that mimic no moving joint, in the file's
  order; a mimic joint follows its leader, through any chain of mimics (value = multiplier x leader + offset);
* a continuous joint's position is (cos q, sin q) in pinocchio's configuration (:func:`configurations`);
* a joint's limits are its ``<limit lower upper>`` (URDF's default 0 for either one absent); a continuous joint, or
  one without ``<limit>``, has none, and a search over it takes one turn either way (:attr:`KinematicJoint.span`);
* an axis is read as a direction: scaled before its norm (an axis of 1e308 1e308 0 is the diagonal), a zero axis
  refused (:mod:`.pinocchio_reading`); an origin's or axis's number that is not finite, or a length beyond 1e4 m,
  refused with the element named and its line (export and render refuse the same values in the same words); so is a
  ``<limit>`` or ``<mimic>`` number that is not a finite number (urdfdom would refuse it, in words of its own);
* a mimic joint's value must come out a finite number (and a prismatic one's within 1e4 m): one whose multiplier and
  offset overflow at the values asked is refused, named, with the numbers (:class:`FollowerValueError`); a mimic of
  a joint the robot does not have is refused by the kinematics commands (:func:`require_leaders`; urdfdom takes it,
  but nothing says what the joint does then).

Joint values are given by name with units (``30deg``, ``0.1 m``; default rad and m); a joint not given is 0; a
prismatic joint's value is at most 1e4 m either way, as every length xacrokit takes.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import XacrokitError
from ..shared.joint_types import MOVING
from ..shared.units import INPUT_BOUNDS, UnitError, bound_problem, parse_quantity
from ..shared.urdf_view import Joint, UrdfView, joint_tree, length_problems, number
from ..shared.value_text import comment_text, did_you_mean
from .pinocchio_reading import line_of, pinocchio_model, unit_axis
from .robot_source import urdf_floats

__all__ = ["unit_axis"]  # (export and sizing read an axis as the kinematics do, from here)

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
    line: int | None = None  # (its <mimic>'s, or the joint's, in the text read)

    def value(self, leader: float) -> float:
        """The follower's value with its leader at ``leader``.

        Raises:
            FollowerValueError: not a finite number, or a prismatic joint's beyond 1e4 m (the numbers said).
        """
        value = self.multiplier * leader + self.offset  # (Python's floats overflow to inf quietly: judged below)
        if math.isfinite(value) and not (self.joint.kind == "prismatic" and bound_problem("length", value)):
            return value
        raise FollowerValueError(self, leader, value)


class FollowerValueError(XacrokitError):
    """A mimic joint's value (multiplier x leader + offset) that no joint can take: not a finite number, or a
    prismatic joint's beyond 1e4 m (``follower``, the leader's value ``leader``, the ``value`` it came to)."""

    def __init__(self, follower: Follower, leader: float, value: float) -> None:
        unit = "m" if follower.joint.kind == "prismatic" else "rad"
        if not math.isfinite(value):
            why = "not a finite number"
        else:
            why = f"beyond what xacrokit takes of a length (at most {shown(INPUT_BOUNDS['length'])} m)"
        where = f" (<mimic> on line {follower.line})" if follower.line else ""
        said = (
            f"mimic joint {follower.joint.name!r}{where}: with {follower.leader!r} at {shown(leader)} it would be at "
            f"{shown(follower.multiplier)} x {shown(leader)} + {shown(follower.offset)} = {shown(value)} {unit}, "
            f"{why}: its multiplier and offset take it beyond what a joint can be"
        )
        super().__init__(said)
        self.follower, self.leader, self.value = follower, leader, value


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
    solvers: dict[tuple[str, str], object] = field(default_factory=dict, compare=False, repr=False)
    """(the inverse kinematics made for a frame and target frame, kept: :func:`xacrokit.kinematics.ik_solver`)"""

    def configuration(self, values: Mapping[str, float]) -> np.ndarray:
        """pinocchio's q: the joints at ``values`` (by name; 0 where not given), the followers at their leaders'.

        Raises:
            FollowerValueError: a follower whose value is not a finite number, or a prismatic one beyond 1e4 m.
        """
        given = [(j, values.get(j.name, 0.0)) for j in self.joints]
        given += [(f.joint, f.value(values.get(f.leader, 0.0))) for f in self.followers]
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
    """A joint value outside its joint's limits (allowed: a pose may be asked anywhere); ``unit`` rad or m."""

    joint: str
    text: str
    value: float
    limits: tuple[float, float]
    unit: str = "rad"

    def __str__(self) -> str:
        return f"joint {self.joint!r} = {comment_text(self.text)}: {self.outside}"

    @property
    def outside(self) -> str:
        """``1.0000000001 rad is outside its limits [-1, 1] rad``: the value and limits in as many digits as tell
        them apart (:func:`outside_text`)."""
        return outside_text(self.value, self.limits, self.unit)


def outside_text(value: float, limits: tuple[float, float], unit: str = "", *, range_name: str = "limits") -> str:
    """``V unit is outside its limits [L, U] unit``, each number in the fewest significant digits (6 at least, 17 at
    most: then it is exact) with which the value as printed is outside the limits as printed: never a value that
    reads as inside its own range ("1 rad is outside [-1, 1]"). Limits whose lower is above the upper hold no value,
    and say so."""
    lower, upper = limits
    for digits in range(6, 18):
        texts = [f"{v:.{digits}g}" for v in (value, lower, upper)]
        shown_value, shown_lower, shown_upper = (float(t) for t in texts)
        if not shown_lower <= shown_value <= shown_upper:
            break
    empty = " (its lower limit is above its upper: no value is within them)" if lower > upper else ""
    unit = f" {unit}" if unit else ""
    return f"{texts[0]}{unit} is outside its {range_name} [{texts[1]}, {texts[2]}]{unit}{empty}"


def shown(value: float) -> str:
    """A number in a message: exactly (the shortest text that reads back as the same float), ``1`` for ``1.0``."""
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text


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
    root, deepest = _root_and_depth(view)
    if deepest > MAX_DEPTH:
        raise XacrokitError(f"the robot's tree is {deepest} links deep; at most {MAX_DEPTH} are queried")
    require_placeable(view)
    _require_numbers(view)
    model = pinocchio_model(text, view)
    if model.nv > MAX_DOF:  # (before createData: its memory grows with the cube of a chain's degrees of freedom)
        raise XacrokitError(
            f"{model.nv} degrees of freedom; the kinematics commands take at most {MAX_DOF} (pinocchio's data for a "
            "chain of 200 takes 0.6 GB, of 300 1.8 GB)"
        )
    moving = _moving(model, view)
    leaders = {j.name: _leader(view, j.name) for j in moving}
    order = {j.name: k for k, j in enumerate(view.joints)}  # (the file's order, not pinocchio's depth-first one)
    settable = sorted((j for j in moving if leaders[j.name] is None), key=lambda j: order[j.name])
    lines = {j.name: _mimic_line(j) for j in view.joints}
    followers = [Follower(j, *leader, lines[j.name]) for j in moving if (leader := leaders[j.name]) is not None]
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
            try:
                urdf_floats(joint.origin.xyz, 3, where=f"joint {joint.name!r} origin xyz")
                urdf_floats(joint.origin.rpy, 3, where=f"joint {joint.name!r} origin rpy")
            except XacrokitError as exc:
                raise XacrokitError(f"{exc}{line_of(joint, 'origin')}") from None
        if joint.type in MOVING or joint.type == "planar":
            unit_axis(joint)
    problems = length_problems(view)
    if problems:
        raise XacrokitError("; ".join(problems))


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
        XacrokitError: mimic joints that follow each other in a loop, or whose chain's multipliers and offsets
            together overflow.
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
        if not (math.isfinite(multiplier) and math.isfinite(offset)):
            raise XacrokitError(
                f"mimic joints {' -> '.join(seen)}: their multipliers and offsets together come to "
                f"{shown(multiplier)} x {current!r} + {shown(offset)}{line_of(declared[name], 'mimic')}: not finite "
                "numbers (a float holds at most 1.8e308)"
            )


def _mimic_line(joint: Joint) -> int | None:
    """The line of a joint's ``<mimic>`` (the joint's when not known)."""
    mimic = joint.mimic
    return (mimic.line if mimic is not None else None) or joint.line


def _require_numbers(view: UrdfView) -> None:
    """Refuse a ``<limit>`` or ``<mimic>`` number that is not a finite number (urdfdom refuses it too, without the
    line): what a joint's limits and a mimic joint's value are read from.

    Raises:
        XacrokitError: the first such number, named by its joint, element and attribute, with its line.
    """
    for joint in view.joints:
        given = [("limit", key, (joint.limit or {}).get(key)) for key in ("lower", "upper", "effort", "velocity")]
        if joint.mimic is not None:
            given += [("mimic", "multiplier", joint.mimic.multiplier), ("mimic", "offset", joint.mimic.offset)]
        for tag, key, text in given:
            try:
                value = float(text) if text is not None else 0.0
            except ValueError:
                value = math.nan
            if not math.isfinite(value):
                raise XacrokitError(
                    f"joint {joint.name!r}{line_of(joint, tag)}: <{tag} {key}> '{comment_text(text)}' is not a "
                    "finite number"
                )


def require_leaders(view: UrdfView) -> None:
    """Refuse a mimic joint whose ``<mimic joint>`` names no joint of the robot: urdfdom takes it, but it says
    nothing of how the joint moves (followed by nothing, set by nobody); ``gen-robot check`` says it as J008.

    Raises:
        XacrokitError: the first such joint, with the name its mimic gives, the closest names and its line.
    """
    declared = [j.name for j in view.joints]
    for joint in view.joints:
        leader = joint.mimic.joint if joint.mimic is not None else None
        if joint.mimic is not None and leader not in declared:
            named = f"'{comment_text(leader)}', which is no joint of the robot" if leader else "no joint"
            raise XacrokitError(
                f"joint {joint.name!r}{line_of(joint, 'mimic')}: its <mimic> names {named}"
                f"{did_you_mean(leader or '', declared)}: give the joint it follows, or remove the <mimic>"
            )


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
        JointValueError: a value that does not parse or is not finite, or a prismatic joint's beyond 1e4 m.
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
        beyond = bound_problem("length", value) if joint.kind == "prismatic" else None
        if beyond is not None:
            raise JointValueError(name, text, beyond)
        if joint.limits is not None and not joint.limits[0] - 1e-12 <= value <= joint.limits[1] + 1e-12:
            unit = "m" if joint.kind == "prismatic" else "rad"
            warnings.append(LimitWarning(name, text, value, joint.limits, unit))
        values[name] = value
    return values, warnings
