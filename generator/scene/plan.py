"""The typed plan of a scene between reading its instances and resolving it, and the checks every scene passes.

A scene spec (:mod:`.build`) and a fleet (:mod:`.fleet`) both come down to a :class:`ScenePlan` of :class:`Planned`
instances; :func:`resolve_plan` then resolves their parents, learns the names of third-party macros (:mod:`.probe`),
checks that every parent link exists and that no two instances share a name, and makes the
:class:`~xacrokit.model.Scene`. Each helper returns the errors it finds; the caller decides when to stop.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from ..errors import SpecError, SpecErrors
from ..load import PathKey, RawSpec
from ..model import Instance, Origin, Robot, Scene, ThirdPartyMacro
from ..resolve import carried_into
from ..shared.value_text import did_you_mean
from .probe import probe_names


@dataclass(frozen=True)
class Planned:
    """One instance as its entry says: where it goes (``parent`` as written: the world, or INSTANCE/LINK with the
    link named without its prefix) and what it is, one of ours (``robot``) or a third-party ``macro``."""

    name: str
    prefix: str
    parent: str
    origin: Origin
    robot: Robot | None = None
    spec_file: Path | None = None
    macro: ThirdPartyMacro | None = None

    def names(self) -> tuple[tuple[str, ...], tuple[str, ...]] | None:
        """(links, joints) with the prefix, known at once for a robot of ours (None for a third-party macro)."""
        if self.robot is None:
            return None
        prefix, robot = self.prefix, self.robot
        joints = (*(prefix + n for n in robot.joint_names), prefix + robot.mount_joint_name)
        return tuple(prefix + n for n in robot.link_names), joints


@dataclass(frozen=True)
class Mount:
    """Where an instance is mounted: the full name of the link, and the instance it belongs to (None: the world)."""

    link: str
    instance: str | None


Names = dict[str, tuple[tuple[str, ...], tuple[str, ...]]]  # instance -> (links, joints)


@dataclass(frozen=True)
class ScenePlan:
    """A scene as read, before its parents and names are resolved.

    Attributes:
        name: the scene's name (it names the package).
        world: the name of its world link.
        planned: its instances, in the spec's order.
        warnings: its robots' and its own (Spec.warnings).
        command: what makes it again, when not ``gen-robot SPEC`` (a fleet).
        failed: instances that could not be planned (their errors are in ``errors``): they exist, so naming one as a
            parent is no mistake, but nothing can be checked against them.
        errors: the problems found before.
    """

    name: str
    world: str
    planned: tuple[Planned, ...]
    warnings: tuple[SpecError, ...] = ()
    command: str = ""
    failed: tuple[str, ...] = ()
    errors: tuple[SpecError, ...] = ()


def resolve_plan(raw: RawSpec, scene: ScenePlan) -> Scene:
    """The scene of ``scene`` (``raw`` locates its errors). Raises SpecErrors with every problem found, the plan's
    ``errors`` (found before) included."""
    name, world, planned = scene.name, scene.world, scene.planned
    by_name = {p.name: p for p in planned}
    mounts, found_errors = resolve_parents(raw, world, by_name, scene.failed)
    errors = [*scene.errors, *found_errors]
    names: Names = {p.name: found for p in planned if (found := p.names()) is not None}
    for plan in planned:  # third-party names: expand each such instance alone, on its real parent
        if plan.macro is not None and plan.name in mounts:
            found, problems = probe_names(raw, plan.name, plan.macro, plan.prefix, mounts[plan.name].link)
            errors += problems
            if found is not None:
                names[plan.name] = found
    names = {p.name: names[p.name] for p in planned if p.name in names}  # in the spec's order (errors name them so)
    errors += parent_link_errors(raw, by_name, mounts, names) + collision_errors(raw, world, names)
    if errors:
        raise SpecErrors(errors)
    instances = tuple(
        Instance(
            name=plan.name,
            prefix=plan.prefix,
            parent=mounts[plan.name].link,
            origin=plan.origin,
            links=names[plan.name][0],
            joints=names[plan.name][1],
            robot=None if plan.robot is None else carried_into(plan.robot, f"{name}_description"),
            spec_file=plan.spec_file,
            macro=plan.macro,
            parent_instance=mounts[plan.name].instance,
        )
        for plan in planned
    )
    return Scene(
        name=name,
        world=world,
        instances=instances,
        source=raw.file,
        warnings=scene.warnings,
        command=scene.command,
    )


def resolve_parents(
    raw: RawSpec, world: str, planned: dict[str, Planned], failed: Sequence[str] = ()
) -> tuple[dict[str, Mount], list[SpecError]]:
    """Where each instance is mounted, and the errors: unknown parents, instances mounted on themselves or in a
    loop. An instance whose parent is wrong, or is a ``failed`` instance, has no mount."""
    errors: list[SpecError] = []
    mounts: dict[str, Mount] = {}
    every = sorted([*planned, *failed])
    for name, plan in planned.items():
        where: PathKey = ("instances", name, "parent")
        if "/" not in plan.parent:
            if plan.parent not in (world, "world"):
                hint = did_you_mean(plan.parent, {world, *every})
                errors.append(raw.error(where, f"parent {plan.parent!r} must be {world!r} or INSTANCE/LINK{hint}"))
                continue
            mounts[name] = Mount(world, None)
            continue
        other, link = plan.parent.split("/", 1)
        if other == name:
            errors.append(raw.error(where, "an instance cannot be mounted on itself"))
        elif other in failed:
            continue  # (its own errors are said; its links are not known)
        elif other not in planned:
            errors.append(
                raw.error(
                    where,
                    f"instance {other!r} is not in this scene{did_you_mean(other, every)} (instances: "
                    f"{', '.join(every)})",
                )
            )
        else:
            mounts[name] = Mount(planned[other].prefix + link, other)
    for name in list(mounts):  # instance cycles: following parents must reach the world
        seen, current = {name}, mounts[name].instance
        while current is not None and current in mounts:
            if current in seen:
                errors.append(
                    raw.error(
                        ("instances", name, "parent"),
                        f"instances {', '.join(sorted(seen))} are mounted on each other in a loop",
                    )
                )
                mounts.pop(name)
                break
            seen.add(current)
            current = mounts[current].instance
    return mounts, errors


def parent_link_errors(
    raw: RawSpec, planned: dict[str, Planned], mounts: dict[str, Mount], names: Names
) -> list[SpecError]:
    """An instance mounted on a link its parent instance does not have."""
    errors = []
    for name, mount in mounts.items():
        if mount.instance is None:
            continue
        if mount.instance not in names:  # (its macro could not be expanded: said already)
            continue
        other = planned[mount.instance]
        links = names[mount.instance][0]
        if mount.link not in links:
            plain = planned[name].parent.split("/", 1)[1]
            known = [n.removeprefix(other.prefix) for n in links]
            errors.append(
                raw.error(
                    ("instances", name, "parent"),
                    f"{plain!r} is not a link of instance {mount.instance!r}{did_you_mean(plain, known)} (its links: "
                    f"{', '.join(known)})",
                )
            )
    return errors


def collision_errors(raw: RawSpec, world: str, names: Names) -> list[SpecError]:
    """Names two instances (or an instance and the world link) would share: one error per group of instances."""
    owners: dict[tuple[str, str], list[str]] = {("link", world): ["the world"]}
    for name, (links, joints) in names.items():
        for kind, full_names in (("link", links), ("joint", joints)):
            for full in full_names:
                owners.setdefault((kind, full), []).append(name)
    clashes: dict[tuple[str, ...], list[str]] = {}
    for (kind, full), owned_by in owners.items():
        if len(owned_by) > 1:
            clashes.setdefault(tuple(owned_by), []).append(f"{kind} {full}")
    errors = []
    for who, clashing in clashes.items():
        shown = ", ".join(clashing[:8]) + (f" and {len(clashing) - 8} more" if len(clashing) > 8 else "")
        instance = next(w for w in reversed(who) if w in names)
        instances = [w for w in who if w in names]
        if len(instances) < len(who):  # the world's link is one of them
            message = (
                f"instance{'s' if len(instances) > 1 else ''} {' and '.join(instances)} would have {shown}, the "
                "scene's world link; give a prefix, or name the world otherwise (world: ...)"
            )
        else:
            message = f"instances {' and '.join(who)} would both have {shown}; give them different prefixes"
        errors.append(raw.error(("instances", instance), message, key=True))
    return errors
