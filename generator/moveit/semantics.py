"""What a robot's or scene's SRDF says besides its collision matrix, read from the model: its planning groups (one
per DH arm, the chain from its base to its tool; the spec's own; else one of all its moving joints), its gripper's
group and end effector, the virtual joint that places it in the world, its mimic joints as passive joints, and a
state per named pose (``home`` first). A scene's are its robots', prefixed, each group named after its instance."""

from __future__ import annotations

from dataclasses import dataclass

from ..model import HOME_POSE, MOVING, Robot, Scene

GRIPPER = "gripper"
VIRTUAL_JOINT = "virtual_joint"


@dataclass(frozen=True)
class Group:
    """A planning group: a chain (``base``, ``tip`` links) or its ``joints``; ``moving``, the joints its states give
    (moving joints that follow no other)."""

    name: str
    moving: tuple[str, ...]
    chain: tuple[str, str] | None = None
    joints: tuple[str, ...] = ()


@dataclass(frozen=True)
class EndEffector:
    """An SRDF end effector: its group, the link it hangs from and that link's group (None: none)."""

    name: str
    parent_link: str
    group: str
    parent_group: str | None


@dataclass(frozen=True)
class Semantics:
    """An SRDF's parts but its collision matrix. ``states``: (pose, group, ((joint, value), ...)); ``virtual_joint``:
    (type, parent frame, child link) or None; ``home``: every joint one sets, at its home value (what the collision
    matrix's ``Default`` is judged at)."""

    name: str
    groups: tuple[Group, ...] = ()
    end_effectors: tuple[EndEffector, ...] = ()
    virtual_joint: tuple[str, str, str] | None = None
    passive: tuple[str, ...] = ()
    states: tuple[tuple[str, str, tuple[tuple[str, float], ...]], ...] = ()
    home: tuple[tuple[str, float], ...] = ()


@dataclass(frozen=True)
class JointFacts:
    """A robot's joints as the SRDF needs them: each moving joint's limits (None: continuous), each joint's parent
    and child link, and who each mimic joint follows."""

    limits: dict[str, tuple[float, float] | None]
    ends: dict[str, tuple[str, str]]
    leaders: dict[str, str]

    def start(self, joint: str) -> float:
        """A joint's value when a pose leaves it out: 0, or its limit nearest 0."""
        bounds = self.limits.get(joint)
        return 0.0 if bounds is None else min(max(0.0, bounds[0]), bounds[1])

    def parent_of(self, link: str) -> str | None:
        return next((parent for parent, child in self.ends.values() if child == link), None)


def joint_facts(robot: Robot) -> JointFacts:
    """The moving joints' limits, every joint's two links and the mimic joints' leaders of ``robot``."""
    limits: dict[str, tuple[float, float] | None] = {}
    ends: dict[str, tuple[str, str]] = {}
    for joint in robot.joints:
        ends[joint.name] = (joint.parent, joint.child)
        if joint.type in MOVING:
            limits[joint.name] = joint.limit.bounds if joint.limit is not None else None
    for arm in robot.arms:
        above = arm.parent
        if arm.base is not None:
            ends[arm.joint_names[0]] = (arm.parent, arm.base)
            above = arm.base
        for row in arm.rows:
            ends[row.name] = (above, row.link)
            limits[row.name] = row.limit.bounds if row.limit is not None else None
            above = row.link
        ends[arm.tool_joint_name] = (above, arm.tool)
    for wheel in robot.wheels:
        ends[wheel.joint_name] = (wheel.parent, wheel.name)
        limits[wheel.joint_name] = None
    leaders = {joint.name: joint.mimic.joint for joint in robot.joints if joint.mimic is not None}
    return JointFacts(limits, ends, leaders)


def _groups(robot: Robot, facts: JointFacts) -> list[Group]:
    """The robot's planning groups, its gripper's last (see the module's docstring)."""
    driven = [name for name in facts.limits if name not in facts.leaders]
    gripper = robot.planning.gripper
    groups = [
        Group(arm.name, tuple(r.name for r in arm.rows if r.type in MOVING), chain=(arm.frame0, arm.tool))
        for arm in robot.arms
    ]
    if robot.planning.groups:
        groups = [Group(n, tuple(j for j in js if j in driven), joints=js) for n, js in robot.planning.groups]
    elif not groups:
        wheels = {wheel.joint_name for wheel in robot.wheels}
        rest = tuple(j for j in driven if j not in wheels and j not in gripper)
        groups = [Group(robot.name, rest, joints=rest)] if rest else []
    if gripper:
        followers = tuple(j for j, leader in facts.leaders.items() if leader in gripper and j not in gripper)
        groups.append(Group(GRIPPER, tuple(j for j in gripper if j in driven), joints=(*gripper, *followers)))
    return groups


def _parent_group(groups: list[Group], facts: JointFacts, link: str) -> str | None:
    """The group whose links hold ``link`` or one of its ancestors: the tip of a chain, a child of a group's joint."""
    held = {g.chain[1]: g.name for g in groups if g.chain} | {
        facts.ends[j][1]: g.name for g in groups for j in g.joints if j in facts.ends and g.name != GRIPPER
    }
    at: str | None = link
    while at is not None:
        if at in held:
            return held[at]
        at = facts.parent_of(at)
    return None


def robot_semantics(robot: Robot) -> Semantics:
    """A robot's SRDF parts (its matrix aside)."""
    facts = joint_facts(robot)
    groups = _groups(robot, facts)
    effectors: tuple[EndEffector, ...] = ()
    if robot.planning.gripper:
        parent = facts.ends[robot.planning.gripper[0]][0]
        effectors = (EndEffector(GRIPPER, parent, GRIPPER, _parent_group(groups[:-1], facts, parent)),)
    base = robot.planning.base or ("planar" if robot.wheels else "fixed")
    frame = "world" if base == "fixed" else "odom"
    return Semantics(
        name=robot.name,
        groups=tuple(groups),
        end_effectors=effectors,
        virtual_joint=(base, frame, robot.root),
        passive=tuple(facts.leaders),
        states=_states(robot, facts, groups),
        home=tuple((j, v) for j, v in _pose(robot, facts, HOME_POSE).items() if j not in facts.leaders),
    )


def _pose(robot: Robot, facts: JointFacts, name: str) -> dict[str, float]:
    """Every moving joint's value in the named pose (a joint it leaves out at its start)."""
    given = dict(dict(robot.poses).get(name, ()))
    return {joint: given.get(joint, facts.start(joint)) for joint in facts.limits}


def _states(robot: Robot, facts: JointFacts, groups: list[Group]) -> tuple[tuple[str, str, tuple], ...]:
    """A state per group and named pose: ``home`` for every group (given or not, the robot starts there), another
    pose for each group it gives a joint of."""
    names = [HOME_POSE, *(name for name, _ in robot.poses if name != HOME_POSE)]
    states = []
    for name in names:
        values = _pose(robot, facts, name)
        given = dict(dict(robot.poses).get(name, ()))
        for group in groups:
            if group.moving and (name == HOME_POSE or set(group.moving) & set(given)):
                states.append((name, group.name, tuple((j, values[j]) for j in group.moving)))
    return tuple(states)


def scene_semantics(scene: Scene) -> Semantics:
    """A scene's SRDF parts: each robot instance's groups, end effectors, passive joints and states, prefixed, a
    group named after its instance (``instance_group`` for a robot of several); no virtual joint (the scene's root is
    its world link)."""
    groups: list[Group] = []
    effectors: list[EndEffector] = []
    passive: list[str] = []
    states: list[tuple[str, str, tuple[tuple[str, float], ...]]] = []
    home: list[tuple[str, float]] = []
    first_group: dict[str, str] = {}
    for instance in scene.instances:
        if instance.robot is None:
            continue
        own = robot_semantics(instance.robot)
        p = instance.prefix
        named = {g.name: instance.name if len(own.groups) == 1 else f"{instance.name}_{g.name}" for g in own.groups}
        if own.groups:
            first_group[instance.name] = named[own.groups[0].name]
        for g in own.groups:
            chain = (p + g.chain[0], p + g.chain[1]) if g.chain else None
            groups.append(Group(named[g.name], tuple(p + j for j in g.moving), chain, tuple(p + j for j in g.joints)))
        for e in own.end_effectors:
            above = named.get(e.parent_group or "") or first_group.get(instance.parent_instance or "")
            effectors.append(EndEffector(named[e.group], p + e.parent_link, named[e.group], above))
        passive += [p + j for j in own.passive]
        states += [(s, named[g], tuple((p + j, v) for j, v in values)) for s, g, values in own.states]
        home += [(p + j, v) for j, v in own.home]
    return Semantics(scene.name, tuple(groups), tuple(effectors), None, tuple(passive), tuple(states), tuple(home))
