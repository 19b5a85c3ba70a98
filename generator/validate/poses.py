"""The named poses pass, on SI values: each position a pose gives within its joint's limits, and every mimic joint
that follows it (through any chain of mimics: position = multiplier x leader + offset) within its own, or at least
at a finite position a double can say, for a follower without limits. A mimic's position is where ros2_control's
``initial_value`` and the MuJoCo keyframe put it, so a pose that drives it beyond its limits is refused at the
leader's entry, the one the spec can change.

Numbers in these messages are the shortest text that reads back as the same double (``repr``): a value just beyond a
limit never reads as the limit itself. A value the spec gave with a unit is shown as written beside it.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

from ..errors import SpecError
from ..load import PathKey, RawSpec
from ..model import LIMITED, MOVING
from ..shared.units import bound_problem, plain_number
from .bodies import Body, joint_types
from .quantities import ANGLE_TURNS

_FOLLOWERS_AT_MOST = 10_000  # followers walked from one leader (a spec's joints are fewer; a guard, not a rule)


@dataclass(frozen=True)
class PoseJoint:
    """What a pose's check needs of a moving joint: its type, where the spec gives it, its limits (SI; None for a
    joint without) and, for a mimic joint, whom it follows and how."""

    name: str
    type: str
    path: PathKey
    limits: tuple[float, float] | None
    follows: tuple[str, float, float] | None = None  # (leader, multiplier, offset)

    @property
    def unit(self) -> str:
        return "m" if self.type == "prismatic" else "rad"


def pose_errors(raw: RawSpec, data: dict[str, Any], bodies: Sequence[Body]) -> Iterator[SpecError]:
    """Every pose position outside its joint's limits, and every mimic joint a pose's position drives outside its
    own (located at the leader's entry in the pose)."""
    joints = pose_joints(data, bodies)
    followers: dict[str, list[PoseJoint]] = {}
    for mimic in joints.values():
        if mimic.follows is not None:
            followers.setdefault(mimic.follows[0], []).append(mimic)
    for pose, values in data.get("poses", {}).items():
        for name, value in values.items():
            joint = joints.get(name)
            if joint is None or joint.follows is not None or not isinstance(value, (int, float)):
                continue  # (not a moving joint, a mimic joint, a value that did not parse: said by other passes)
            where = ("poses", pose, name)
            if joint.limits is not None and not _within(joint, float(value)):  # (one without: quantities bound it)
                said = f"{_shown(raw, where, float(value), joint.unit)} is outside its limits {_limits(raw, joint)}"
                yield raw.error(where, f"{name} = {said}")
            for driven in _driven(joint, float(value), followers):  # (its mimic joints, theirs ...)
                yield raw.error(where, _follower_problem(raw, where, joint, float(value), driven))


def pose_joints(data: dict[str, Any], bodies: Sequence[Body]) -> dict[str, PoseJoint]:
    """Every moving joint a pose may name, by name: the spec's joints (mimic joints among them), arm rows, wheels."""
    types = joint_types(data, bodies)
    found: dict[str, PoseJoint] = {}
    for name, joint in data.get("joints", {}).items():
        mimic = joint.get("mimic")
        follows = None
        if isinstance(mimic, dict) and isinstance(mimic.get("joint"), str):
            multiplier, offset = mimic.get("multiplier", 1.0), mimic.get("offset", 0.0)
            if isinstance(multiplier, (int, float)) and isinstance(offset, (int, float)):
                follows = (mimic["joint"], float(multiplier), float(offset))
        found[name] = PoseJoint(name, joint["type"], ("joints", name), _limits_of(joint, joint["type"]), follows)
    for kind, _, path, item in bodies:
        if kind == "row":
            row_type = item.get("type", "revolute")
            found[item["name"]] = PoseJoint(item["name"], row_type, path, _limits_of(item, row_type))
    for name, joint_type in types.items():  # (the wheels' joints: continuous, no limits)
        found.setdefault(name, PoseJoint(name, joint_type, (), None))
    return {name: joint for name, joint in found.items() if joint.type in MOVING}


def _limits_of(holder: dict[str, Any], joint_type: str) -> tuple[float, float] | None:
    limit = holder.get("limit")
    if joint_type not in LIMITED or not isinstance(limit, dict):
        return None
    low, high = limit.get("lower"), limit.get("upper")
    if isinstance(low, (int, float)) and isinstance(high, (int, float)):
        return float(low), float(high)
    return None


def _within(joint: PoseJoint, position: float) -> bool:
    """Whether ``position`` is one the joint can be at: within its limits; without limits, finite and within what a
    double says of a turn (an angle) or of a length."""
    if joint.limits is not None:
        return joint.limits[0] <= position <= joint.limits[1]
    if joint.type == "prismatic":
        return math.isfinite(position) and bound_problem("length", position) is None
    return abs(position) <= ANGLE_TURNS * math.tau  # (False for NaN)


Step = tuple[PoseJoint, float, float]  # a mimic joint, its multiplier and offset: one link of a chain of mimics
Chain = tuple[Step, ...]  # the mimics from a leader's follower to a joint that follows it through them
Interval = tuple[float, float]


@dataclass(frozen=True)
class Driven:
    """A mimic joint a pose's position drives where it cannot be: the chain of mimics from the leader to it, where
    it puts it, and the leader's positions that keep every mimic joint it drives within its limits (None: none do,
    or none has limits)."""

    chain: Chain
    position: float
    keeping: Interval | None

    @property
    def joint(self) -> PoseJoint:
        return self.chain[-1][0]


def _driven(leader: PoseJoint, value: float, followers: dict[str, list[PoseJoint]]) -> Iterator[Driven]:
    """Each mimic joint ``leader`` at ``value`` drives (its followers, theirs ...) that is not where it can be."""
    chains = _chains(leader, followers)
    failing = [(chain, _through(chain, value)) for chain in chains]
    failing = [(chain, position) for chain, position in failing if not _within(chain[-1][0], position)]
    if failing:
        keeping = _keeping(leader, chains)
        yield from (Driven(chain, position, keeping) for chain, position in failing)


def _chains(leader: PoseJoint, followers: dict[str, list[PoseJoint]]) -> list[Chain]:
    """Every chain of mimics that hangs from ``leader``. (A cycle of mimics never hangs from a joint that follows
    none: the walk ends; the names pass says the cycle.)"""
    waiting: list[tuple[PoseJoint, Chain]] = [(leader, ())]
    seen = {leader.name}
    found = []
    while waiting and len(seen) <= _FOLLOWERS_AT_MOST:
        joint, steps = waiting.pop()
        for follower in followers.get(joint.name, ()):
            if follower.name in seen or follower.follows is None:
                continue
            seen.add(follower.name)
            chain = (*steps, (follower, follower.follows[1], follower.follows[2]))
            found.append(chain)
            waiting.append((follower, chain))
    return found


def _through(chain: Chain, value: float) -> float:
    """Where a chain of mimics puts its last joint for the leader at ``value`` (each: offset + multiplier x its
    leader, as ros2_control's initial_value and the MuJoCo keyframe compute it)."""
    for _, multiplier, offset in chain:
        value = offset + multiplier * value
    return value


def _keeping(leader: PoseJoint, chains: list[Chain]) -> Interval | None:
    """The leader's positions, within its own limits, that keep every mimic joint with limits it drives within them
    (each checked through its chain, to the last double); None when there are none or no such mimic joint."""
    limited = [chain for chain in chains if chain[-1][0].limits is not None]
    low, high = leader.limits or (-math.inf, math.inf)
    for chain in limited:
        interval = _interval(chain)
        if interval is None:
            return None
        low, high = max(low, interval[0]), min(high, interval[1])
    return (low, high) if limited and low <= high and math.isfinite(low) and math.isfinite(high) else None


def _interval(chain: Chain) -> Interval | None:
    """The leader's positions that keep the chain's last joint within its limits: solved, then moved to the last
    double the chain itself keeps within (rounding may put the solved bounds a few doubles off either way)."""
    joint = chain[-1][0]
    scale, shift = 1.0, 0.0
    for _, multiplier, offset in chain:
        scale, shift = multiplier * scale, multiplier * shift + offset
    if scale == 0 and math.isfinite(shift):  # (the mimic stays at its offset whatever the leader does)
        return (-math.inf, math.inf) if _within(joint, _through(chain, 0.0)) else None
    if joint.limits is None or not (math.isfinite(scale) and math.isfinite(shift)):
        return None
    ends = sorted(((joint.limits[0] - shift) / scale, (joint.limits[1] - shift) / scale))
    if not all(math.isfinite(end) for end in ends):
        return None
    for index, outward in ((0, -math.inf), (1, math.inf)):
        for _ in range(64):  # (in, while the end is outside)
            if _within(joint, _through(chain, ends[index])):
                break
            ends[index] = math.nextafter(ends[index], -outward)
        for _ in range(64):  # (out, while the next double is inside)
            step = math.nextafter(ends[index], outward)
            if not _within(joint, _through(chain, step)):
                break
            ends[index] = step
    low, high = ends
    return (low, high) if low <= high and all(_within(joint, _through(chain, end)) for end in ends) else None


def _follower_problem(raw: RawSpec, where: PathKey, leader: PoseJoint, value: float, driven: Driven) -> str:
    follower = driven.joint
    rules, previous = [], leader.name
    for joint, multiplier, offset in driven.chain:
        rules.append(f"{joint.name} = {multiplier!r} x {previous} + {offset!r}")
        previous = joint.name
    if follower.limits is not None:
        beyond = f"outside its limits {_limits(raw, follower)}"
    elif follower.type == "prismatic":
        beyond = "beyond any length xacrokit takes"
    else:
        beyond = f"beyond the {ANGLE_TURNS} turns a position may make"
    if driven.keeping is not None:
        low, high = driven.keeping
        right = (
            f"give {leader.name} a position in [{low!r}, {high!r}] {leader.unit}, which keeps the mimic joints it "
            "drives within their limits"
        )
    else:
        right = f"give {leader.name} another position, or change the mimic's multiplier or offset"
    return (
        f"{leader.name} = {_shown(raw, where, value, leader.unit)} puts mimic joint {follower.name} at "
        f"{driven.position!r} {follower.unit}, {beyond} (mimic: {'; '.join(rules)}); {right}"
    )


def _written(raw: RawSpec, path: PathKey) -> Any:
    """The value at ``path`` as the spec wrote it (a mirror's copy: its source's), or None."""
    node = raw.data
    for key in raw.source(path):
        if isinstance(node, dict) and key in node:
            node = node[key]
        elif isinstance(node, list) and isinstance(key, int) and 0 <= key < len(node):
            node = node[key]
        else:
            return None
    return node


def _with_unit(raw: RawSpec, path: PathKey) -> str | None:
    """The text the spec wrote at ``path`` when it gave a unit ('90 deg', 'pi/2'), else None."""
    written = _written(raw, path)
    if isinstance(written, str) and plain_number(written.strip()) is None:
        return written.strip()
    return None


def _shown(raw: RawSpec, path: PathKey, value: float, unit: str) -> str:
    """``value`` (SI) exactly, after the spec's own text when it gave a unit: '57.2958 deg (1.0000003575641672 rad)'."""
    written = _with_unit(raw, path)
    return f"{written} ({value!r} {unit})" if written is not None else f"{value!r} {unit}"


def _limits(raw: RawSpec, joint: PoseJoint) -> str:
    """A joint's limits exactly, after the spec's own text when it gave units: '[-90 deg, 90 deg] ([-1.57..., 1.57...]
    rad)'."""
    low, high = joint.limits or (math.nan, math.nan)  # (called for a joint with limits)
    exact = f"[{low!r}, {high!r}] {joint.unit}"
    written = [_with_unit(raw, (*joint.path, "limit", key)) for key in ("lower", "upper")]
    if written == [None, None]:
        return exact
    shown = [w if w is not None else repr(v) for w, v in zip(written, (low, high), strict=True)]
    return f"[{shown[0]}, {shown[1]}] ({exact})"
