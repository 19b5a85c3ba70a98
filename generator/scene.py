"""Multi-robot scenes: several robots (our specs and third-party xacro macros) in one description.

A scene spec is recognised by its top-level ``scene:`` key. It goes through the same stages as a robot spec: load ->
validate (schema, units, every instance's own spec, parents, names) -> resolve (a frozen :class:`Scene` that knows
every link and joint name of every instance before anything is written) -> render -> expand -> write. Any name two
instances would share is an error listing the names and the instances, found before writing; a third-party macro's
names are found by expanding it alone first.
"""

from __future__ import annotations

import contextlib
import dataclasses
import io
import json
import math
import re
import tempfile
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from types import SimpleNamespace
from typing import Any

from . import __version__
from .errors import ExpandError, SpecError, SpecErrors, XacrokitError
from .load import PathKey, RawSpec, load_file
from .model import Origin, Robot, mount_joint_name
from .render import MacroMode, RenderedFile, environment, render_package
from .render import controllers as robot_controllers
from .resolve import origin as resolve_origin
from .resolve import resolve
from .resources import schemas_dir
from .text import xacro_text
from .validate import Quantities, SchemaValidator, inline_refs, schema_errors, validate

ROBOT_FILES = ("urdf/", "config/")  # what a scene carries of each robot package (no nested package.xml)


@dataclass(frozen=True)
class ThirdPartyMacro:
    """A macro with the prefix / parent / *origin interface, from a .xacro file the scene includes where it is."""

    file: Path
    macro: str
    params: tuple[tuple[str, str], ...] = ()
    prefix_param: str = "prefix"
    parent_param: str = "parent"


@dataclass(frozen=True)
class Instance:
    """One robot in the scene. ``links``/``joints`` are its full names in the scene (prefix included)."""

    name: str
    prefix: str
    parent: str  # the full name of the link it is mounted on
    origin: Origin
    links: tuple[str, ...]
    joints: tuple[str, ...]
    robot: Robot | None = None
    spec_file: Path | None = None
    macro: ThirdPartyMacro | None = None
    parent_instance: str | None = None


@dataclass(frozen=True)
class Scene:
    name: str
    world: str
    instances: tuple[Instance, ...]
    source: str = field(default="", compare=False)
    warnings: tuple[SpecError, ...] = field(default=(), compare=False)  # its robots' and its own (Spec.warnings)
    command: str = field(default="", compare=False)  # what makes it again, when not `gen-robot SPEC` (a fleet)

    @property
    def package(self) -> str:
        return f"{self.name}_description"

    @property
    def robots(self) -> tuple[Robot, ...]:
        """The distinct robots of the spec instances, in first-use order."""
        seen: dict[str, Robot] = {}
        for instance in self.instances:
            if instance.robot is not None:
                seen.setdefault(instance.robot.name, instance.robot)
        return tuple(seen.values())

    @property
    def link_names(self) -> tuple[str, ...]:
        return (self.world, *(n for i in self.instances for n in i.links))

    @property
    def joint_names(self) -> tuple[str, ...]:
        return tuple(n for i in self.instances for n in i.joints)


def is_scene(raw: RawSpec) -> bool:
    return isinstance(raw.data, dict) and "scene" in raw.data


@cache
def scene_validator() -> SchemaValidator:
    """The scene spec schema's validator (built once)."""
    schema = json.loads((schemas_dir() / "scene.schema.json").read_text("utf-8"))
    return SchemaValidator(inline_refs(schema))


def build_scene(raw: RawSpec) -> Scene:
    """Validate and resolve a scene spec. Raises SpecErrors with every located problem (its robots' included)."""
    errors = schema_errors(raw, scene_validator())
    if errors:
        raise SpecErrors(errors)
    quantities = Quantities(raw)
    for name, instance in quantities.data["instances"].items():
        quantities.origin(instance, "origin", ("instances", name))
    data, errors, warnings = quantities.data, quantities.errors, list(quantities.warnings)
    world = data.get("world", "world")
    base = Path(raw.file).resolve().parent
    partial: dict[str, dict[str, Any]] = {}
    robots_by_name: dict[str, Path] = {}
    loaded: dict[Path, Robot | None] = {}
    for name, entry in data["instances"].items():
        path: PathKey = ("instances", name)
        prefix = entry.get("prefix", "")
        if "spec" in entry:
            robot, spec_file = _load_robot(raw, entry["spec"], base, path, errors, warnings, loaded)
            if robot is None:
                continue
            other = robots_by_name.setdefault(robot.name, spec_file)
            if other != spec_file:
                errors.append(
                    raw.error(
                        (*path, "spec"),
                        f"robot {robot.name!r} from {spec_file} differs from the robot "
                        f"of that name from {other}; rename one (robot names name "
                        "their xacro macros)",
                    )
                )
                continue
            links = tuple(prefix + n for n in robot.link_names)
            joints = (*(prefix + n for n in robot.joint_names), prefix + mount_joint_name(robot.root))
            partial[name] = {
                "prefix": prefix,
                "robot": robot,
                "spec_file": spec_file,
                "links": links,
                "joints": joints,
                "root": prefix + robot.root,
            }
        else:
            macro = _third_party(raw, entry["xacro"], base, path, errors)
            if macro is not None:
                partial[name] = {"prefix": prefix, "macro": macro}
    if errors:
        raise SpecErrors(errors)
    parents = _resolve_parents(raw, data, world, partial, errors)
    for name, info in partial.items():  # third-party names: expand each such instance alone, on its real parent
        if "macro" in info and name in parents:
            found = _probe_names(raw, name, info["macro"], info["prefix"], parents[name][0], errors)
            if found is not None:
                info["links"], info["joints"] = found
    if errors:
        raise SpecErrors(errors)
    errors += _parent_link_errors(raw, data, partial, parents, world)
    errors += _collision_errors(raw, partial, world)
    if errors:
        raise SpecErrors(errors)
    instances = tuple(
        Instance(
            name=name,
            prefix=info["prefix"],
            parent=parents[name][0],
            origin=resolve_origin(data["instances"][name].get("origin")),
            links=info["links"],
            joints=info["joints"],
            robot=info.get("robot"),
            spec_file=info.get("spec_file"),
            macro=info.get("macro"),
            parent_instance=parents[name][1],
        )
        for name, info in partial.items()
    )
    return Scene(name=data["scene"], world=world, instances=instances, source=raw.file, warnings=tuple(warnings))


def _load_robot(
    raw: RawSpec,
    spec: str,
    base: Path,
    path: PathKey,
    errors: list[SpecError],
    warnings: list[SpecError],
    loaded: dict[Path, Robot | None],
):
    """The robot of an instance's spec; each spec file is read and validated once however many instances use it."""
    spec_file = (base / spec).resolve()
    if spec_file in loaded:
        return loaded[spec_file], spec_file
    loaded[spec_file] = None  # a spec with problems reports them once
    try:
        robot_raw = load_file(spec_file)
        if is_scene(robot_raw):
            errors.append(
                raw.error((*path, "spec"), f"{spec_file} is a scene spec, not a robot spec (scenes do not nest)")
            )
            return None, spec_file
        valid = validate(robot_raw)
    except SpecErrors as problems:  # the robot's own problems, located in its own file
        unreadable = [e.message for e in problems.errors if e.message.startswith("cannot read the spec")]
        if unreadable:  # said once, where the scene names the file
            errors.append(raw.error((*path, "spec"), f"no robot spec at {spec_file}: {unreadable[0]}"))
        else:
            errors += problems.errors
        return None, spec_file
    warnings += valid.warnings
    loaded[spec_file] = resolve(valid)
    return loaded[spec_file], spec_file


def _third_party(
    raw: RawSpec, entry: dict[str, Any], base: Path, path: PathKey, errors: list[SpecError]
) -> ThirdPartyMacro | None:
    file = (base / entry["file"]).resolve()
    if not file.is_file():
        errors.append(raw.error((*path, "xacro", "file"), f"no xacro file at {file}"))
        return None
    params = tuple((k, _literal(v)) for k, v in entry.get("params", {}).items())
    return ThirdPartyMacro(
        file=file,
        macro=entry["macro"],
        params=params,
        prefix_param=entry.get("prefix_param", "prefix"),
        parent_param=entry.get("parent_param", "parent"),
    )


def _literal(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(value) if isinstance(value, float) else str(value)


def _resolve_parents(
    raw: RawSpec, data: dict[str, Any], world: str, partial: dict[str, dict[str, Any]], errors: list[SpecError]
) -> dict[str, tuple[str, str | None]]:
    """instance -> (full parent link name, parent instance or None); checks references and instance cycles."""
    parents: dict[str, tuple[str, str | None]] = {}
    for name in partial:
        parent = data["instances"][name]["parent"]
        where: PathKey = ("instances", name, "parent")
        if "/" not in parent:
            if parent not in (world, "world"):
                errors.append(raw.error(where, f"parent {parent!r} must be {world!r} or INSTANCE/LINK"))
                continue
            parents[name] = (world, None)
            continue
        other, link = parent.split("/", 1)
        if other == name:
            errors.append(raw.error(where, "an instance cannot be mounted on itself"))
        elif other not in data["instances"]:
            errors.append(
                raw.error(where, f"instance {other!r} is not in this scene (instances: {', '.join(data['instances'])})")
            )
        elif other in partial:
            parents[name] = (partial[other]["prefix"] + link, other)
    for name in list(parents):  # instance cycles: following parents must reach the world
        seen, current = {name}, parents[name][1]
        while current is not None and current in parents:
            if current in seen:
                errors.append(
                    raw.error(
                        ("instances", name, "parent"),
                        f"instances {', '.join(sorted(seen))} are mounted on each other in a loop",
                    )
                )
                parents.pop(name)
                break
            seen.add(current)
            current = parents[current][1]
    return parents


def _parent_link_errors(
    raw: RawSpec,
    data: dict[str, Any],
    partial: dict[str, dict[str, Any]],
    parents: dict[str, tuple[str, str | None]],
    world: str,
) -> list[SpecError]:
    errors = []
    for name, (link, other) in parents.items():
        if other is not None and link not in partial[other].get("links", ()):
            plain = data["instances"][name]["parent"].split("/", 1)[1]
            known = [n.removeprefix(partial[other]["prefix"]) for n in partial[other].get("links", ())]
            errors.append(
                raw.error(
                    ("instances", name, "parent"),
                    f"{plain!r} is not a link of instance {other!r} (its links: {', '.join(known)})",
                )
            )
    return errors


def _collision_errors(raw: RawSpec, partial: dict[str, dict[str, Any]], world: str) -> list[SpecError]:
    owners: dict[tuple[str, str], list[str]] = {("link", world): ["the world"]}
    for name, info in partial.items():
        for kind in ("link", "joint"):
            for full in info.get(f"{kind}s", ()):
                owners.setdefault((kind, full), []).append(name)
    clashes: dict[tuple[str, ...], list[str]] = {}
    for (kind, full), who in owners.items():
        if len(who) > 1:
            clashes.setdefault(tuple(who), []).append(f"{kind} {full}")
    errors = []
    for who, names in clashes.items():
        shown = ", ".join(names[:8]) + (f" and {len(names) - 8} more" if len(names) > 8 else "")
        instance = next(w for w in reversed(who) if w in partial)
        instances = [w for w in who if w in partial]
        if len(instances) < len(who):  # the world's link is one of them
            message = (
                f"instance{'s' if len(instances) > 1 else ''} {' and '.join(instances)} would have {shown}, the "
                "scene's world link; give a prefix, or name the world otherwise (world: ...)"
            )
        else:
            message = f"instances {' and '.join(who)} would both have {shown}; give them different prefixes"
        errors.append(raw.error(("instances", instance), message, key=True))
    return errors


def _probe_names(
    raw: RawSpec, name: str, macro: ThirdPartyMacro, prefix: str, parent: str, errors: list[SpecError]
) -> tuple[tuple[str, ...], tuple[str, ...]] | None:
    """Expand one third-party instance alone (on a stand-in parent link) to learn its link and joint names."""
    from lxml import etree

    from .expansion import expand_file

    stub = SimpleNamespace(name=name, prefix=prefix, parent=parent, origin=Origin(), macro=macro)
    text = environment().get_template("scene/probe.urdf.xacro.j2").render(instance=stub)
    with tempfile.TemporaryDirectory(prefix="xacrokit-probe-") as folder:
        probe = Path(folder) / "probe.urdf.xacro"
        probe.write_text(text, encoding="utf-8")
        try:
            with contextlib.redirect_stderr(io.StringIO()):  # (xacro's warnings come once, from the real expansion)
                urdf = expand_file(probe)
        except ExpandError as exc:
            hint = ""
            invalid = re.search(r'Invalid parameter "([^"]*)"', exc.message)
            if invalid and invalid[1] in (macro.prefix_param, macro.parent_param):  # (UR's macro says tf_prefix)
                hint = (
                    f" (the scene passes {macro.prefix_param!r} and {macro.parent_param!r}: set prefix_param and "
                    "parent_param to the macro's own names for them)"
                )
            elif invalid:
                hint = f" (the macro has no parameter {invalid[1]!r}: check the names under params)"
            errors.append(
                raw.error(
                    ("instances", name, "xacro"),
                    f"expanding {macro.macro} from {macro.file} failed: {exc.message}{hint}",
                )
            )
            return None
    root = etree.fromstring(urdf.encode())
    every_link = [e.get("name", "") for e in root.findall("link")]
    links = tuple(n for n in every_link if n != parent)
    joints = tuple(e.get("name", "") for e in root.findall("joint"))
    where: PathKey = ("instances", name, "xacro")
    problems = []
    if every_link.count(parent) > 1:
        problems.append(f"it makes a link {parent!r} itself, the name of the link it is mounted on")
    unprefixed = [n for n in (*links, *joints) if prefix not in n]  # (world_to_${prefix}base carries it too)
    if unprefixed:
        shown = ", ".join(unprefixed[:6]) + (f" and {len(unprefixed) - 6} more" if len(unprefixed) > 6 else "")
        problems.append(
            f"its names {shown} do not hold the prefix {prefix!r} (if its prefix parameter is not called "
            f"{macro.prefix_param!r}, set prefix_param)"
        )
    if not any(j.find("parent") is not None and j.find("parent").get("link") == parent for j in root.findall("joint")):
        problems.append(
            f"no joint of it hangs from the link it is mounted on, {parent!r} (if its parent parameter is not called "
            f"{macro.parent_param!r}, set parent_param)"
        )
    if problems:
        errors.append(raw.error(where, f"macro {macro.macro} from {macro.file}: " + "; ".join(problems)))
        return None
    return links, joints


# ------------------------------------------------------------------------------------------------------------ render
def render_scene(scene: Scene, *, spec_name: str = "scene.yaml", macros: MacroMode = "inline") -> list[RenderedFile]:
    """Every file of the scene package except the expanded URDF; ``macros`` is how each robot's macro is written."""
    env = environment()
    files: list[RenderedFile] = []
    for robot in scene.robots:
        for file in render_package(robot, macros=macros, spec_name=spec_name):
            if file.path.startswith(ROBOT_FILES) and not file.path.endswith("_controllers.yaml"):
                files.append(RenderedFile(f"robots/{robot.package}/{file.path}", file.content))
    has_control = any(i.robot is not None and i.robot.ros2_control is not None for i in scene.instances)
    context = {
        "scene": scene,
        "version": __version__,
        "spec_name": spec_name,
        "has_control": has_control,
        "macros": macros,
        "robot": SimpleNamespace(root=scene.world),
        "xacro_text": xacro_text,
    }
    for path, template in (
        ("package.xml", "scene/package.xml.j2"),
        ("CMakeLists.txt", "scene/CMakeLists.txt.j2"),
        ("README.md", "scene/README.md.j2"),
        (f"urdf/{scene.name}.urdf.xacro", "scene/scene.urdf.xacro.j2"),
        ("launch/display.launch.py", "scene/display.launch.py.j2"),
        (f"rviz/{scene.name}.rviz", "package/rviz/robot.rviz.j2"),
    ):
        files.append(RenderedFile(path, env.get_template(template).render(context)))
    controllers = env.get_template("package/config/controllers.yaml.j2")
    for instance in scene.instances:
        robot = instance.robot
        if robot is not None and robot.ros2_control is not None:
            text = controllers.render(
                robot=robot,
                version=__version__,
                spec_name=spec_name,
                prefix=instance.prefix,
                **robot_controllers(robot, instance.prefix, mounted=True),
            )
            files.append(RenderedFile(f"config/{instance.name}_controllers.yaml", text))
    return sorted(files, key=lambda f: f.path)


def expand_scene(scene: Scene, files: list[RenderedFile]) -> RenderedFile:
    from .expansion import expand_file
    from .fileio import write_text_atomic

    with tempfile.TemporaryDirectory(prefix="xacrokit-") as scratch:
        root = Path(scratch) / scene.package
        for file in files:
            write_text_atomic(root / file.path, file.content)
        urdf = expand_file(root / "urdf" / f"{scene.name}.urdf.xacro", xacro_banner=False)
    header = (
        f"<!-- Generated by xacrokit {__version__}: urdf/{scene.name}.urdf.xacro expanded with xacro "
        "(default arguments). Do not edit: regenerate. -->\n"
    )
    declaration, _, body = urdf.partition("\n")
    return RenderedFile(f"urdf/{scene.name}.urdf", f"{declaration}\n{header}{body}")


def fleet_scene(spec_path: str | Path, count: int, *, columns: int | None = None, spacing: float = 2.0) -> Scene:
    """``count`` copies of one robot with prefixes r0_ ... r{count-1}_, on a grid in the world (row-major)."""
    if count < 1:
        raise XacrokitError(f"a fleet needs at least 1 robot, got count {count}")
    if not (spacing > 0 and math.isfinite(spacing)):
        raise XacrokitError(f"the spacing of a fleet must be > 0 m, got {spacing!r}")
    given_columns = columns
    columns = columns or math.ceil(math.sqrt(count))
    lines = [f"scene: {_fleet_name(spec_path)}", "instances:"]
    for index in range(count):
        row, column = divmod(index, columns)
        lines.append(
            f"  r{index}: {{spec: {json.dumps(str(Path(spec_path).resolve()))}, prefix: r{index}_, parent: world, "
            f"origin: {{xyz: [{column * spacing!r}, {row * spacing!r}, 0.0]}}}}"
        )
    from .load import load_text

    raw = load_text("\n".join(lines) + "\n", file=f"<fleet of {spec_path}>")
    command = f"gen-robot fleet {Path(spec_path).name} --count {count}"
    if given_columns:
        command += f" --grid {math.ceil(count / given_columns)}x{given_columns}"
    if spacing != 2.0:
        command += f" --spacing {spacing!r}"
    return dataclasses.replace(build_scene(raw), command=command)


def _fleet_name(spec_path: str | Path) -> str:
    raw = load_file(spec_path)
    if is_scene(raw):
        raise XacrokitError(f"{spec_path} is a scene spec; a fleet copies one robot spec (generate the scene itself)")
    name = raw.data.get("robot") if isinstance(raw.data, dict) else None
    return f"{name}_fleet" if isinstance(name, str) else "fleet"
