"""A scene spec to a :class:`~xacrokit.model.Scene`: the scene's validate and resolve stages.

A scene spec is recognised by its top-level ``scene:`` key. Its schema and quantities are checked as a robot spec's
are (the same validator and unit conversion), each instance's robot spec is validated and resolved once however many
instances use it (its problems located in its own file), and the instances become the typed plan that
:func:`~xacrokit.scene.plan.resolve_plan` turns into the scene. Every problem is collected and raised together.
"""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path
from typing import Any

from ..errors import SpecError, SpecErrors
from ..load import PathKey, RawSpec, load_file
from ..model import Robot, Scene, ThirdPartyMacro
from ..resolve import origin as resolve_origin
from ..resolve import resolve
from ..shared.package_data import XACRO_KEYWORDS, schemas_dir
from ..validate import Quantities, SchemaValidator, schema_errors, validate
from .plan import Planned, ScenePlan, resolve_plan

Source = tuple[Robot, Path] | ThirdPartyMacro  # what an instance is: a robot of ours (and its spec file), or a macro


def is_scene(raw: RawSpec) -> bool:
    """Whether a loaded spec is a scene spec (its top-level ``scene:`` key says so)."""
    return isinstance(raw.data, dict) and "scene" in raw.data


@cache
def scene_validator() -> SchemaValidator:
    """The scene spec schema's validator (built once)."""
    schema = json.loads((schemas_dir() / "scene.schema.json").read_text("utf-8"))
    return SchemaValidator(schema)


def build_scene(raw: RawSpec) -> Scene:
    """Validate and resolve a scene spec. Raises SpecErrors with every located problem (its robots' included)."""
    errors = schema_errors(raw, scene_validator())
    if errors:
        raise SpecErrors(errors)
    quantities = Quantities(raw)
    for name, instance in quantities.data["instances"].items():
        quantities.origin(instance, "origin", ("instances", name))
    data, errors, warnings = quantities.data, list(quantities.errors), list(quantities.warnings)
    robots = RobotSpecs()
    base = Path(raw.file).resolve().parent
    sources: dict[str, Source] = {}
    failed = []
    for name, entry in data["instances"].items():
        source, problems, notes = _source(raw, ("instances", name), entry, base, robots)
        errors += problems
        warnings += notes
        if source is not None:
            sources[name] = source
        else:
            failed.append(name)
    planned = []  # (the instances that could be read: their parents and names are checked in this same round)
    for name, source in sources.items():
        entry = data["instances"][name]
        origin = resolve_origin(entry.get("origin"))
        if isinstance(source, ThirdPartyMacro):
            planned.append(Planned(name, entry.get("prefix", ""), entry["parent"], origin, macro=source))
        else:
            robot, spec_file = source
            planned.append(Planned(name, entry.get("prefix", ""), entry["parent"], origin, robot, spec_file))
    world = data.get("world", "world")
    plan = ScenePlan(data["scene"], world, tuple(planned), tuple(warnings), failed=tuple(failed), errors=tuple(errors))
    return resolve_plan(raw, plan)


def _source(
    raw: RawSpec, path: PathKey, entry: dict[str, Any], base: Path, robots: RobotSpecs
) -> tuple[Source | None, list[SpecError], list[SpecError]]:
    """What an instance entry names, its errors and its robot's warnings."""
    if "xacro" in entry:
        macro, problems = third_party(raw, entry["xacro"], base, path)
        return macro, problems, []
    robot, spec_file, errors, warnings = robots.load(raw, entry["spec"], base, path)
    if robot is None:
        return None, errors, warnings
    other = robots.by_name.setdefault(robot.name, spec_file)
    if other != spec_file:
        message = (
            f"robot {robot.name!r} from {spec_file} differs from the robot of that name from {other}; rename one "
            "(robot names name their xacro macros)"
        )
        return None, [*errors, raw.error((*path, "spec"), message)], warnings
    return (robot, spec_file), errors, warnings


class RobotSpecs:
    """The robots of a scene's instances: each spec file is read, validated and resolved once however many instances
    use it, and a spec with problems reports them once."""

    def __init__(self) -> None:
        self.loaded: dict[Path, Robot | None] = {}
        self.by_name: dict[str, Path] = {}  # robot name -> the spec file it came from first

    def load(
        self, raw: RawSpec, spec: str | Path, base: Path, path: PathKey
    ) -> tuple[Robot | None, Path, list[SpecError], list[SpecError]]:
        """(robot or None, its spec file, errors, warnings) of the spec ``spec`` (relative to ``base``) that the
        scene ``raw`` names at ``path``."""
        spec_file, problem = resolved_path(base, spec)
        if problem:
            return None, spec_file, [raw.error((*path, "spec"), f"cannot use this path: {problem}")], []
        if spec_file in self.loaded:
            return self.loaded[spec_file], spec_file, [], []
        self.loaded[spec_file] = None
        try:
            robot_raw = load_file(spec_file)
            if is_scene(robot_raw):
                message = f"{spec_file} is a scene spec, not a robot spec (scenes do not nest)"
                return None, spec_file, [raw.error((*path, "spec"), message)], []
            if not isinstance(robot_raw.data, dict) or "robot" not in robot_raw.data:
                # (a scene from elsewhere may name any file: its content is not quoted back in the error)
                message = (
                    f"{spec_file} is not a robot spec (a YAML mapping with robot: and links:); its content is not shown"
                )
                return None, spec_file, [raw.error((*path, "spec"), message)], []
            valid = validate(robot_raw)
        except SpecErrors as problems:  # the robot's own problems, located in its own file
            unreadable = [e.message for e in problems.errors if e.message.startswith("cannot read the spec")]
            if unreadable:  # said once, where the scene names the file
                return (
                    None,
                    spec_file,
                    [raw.error((*path, "spec"), f"no robot spec at {spec_file}: {unreadable[0]}")],
                    [],
                )
            return None, spec_file, list(problems.errors), []
        robot = self.loaded[spec_file] = resolve(valid)
        return robot, spec_file, [], list(valid.warnings)


def resolved_path(base: Path, text: str | Path) -> tuple[Path, str | None]:
    """``base / text`` made absolute, or the reason it cannot be (a NUL in it, a loop of symbolic links)."""
    try:
        return (base / text).resolve(), None
    except ValueError:
        return base, "it holds a NUL character"
    except (RuntimeError, OSError) as exc:  # (Python 3.11 raises RuntimeError on a link loop)
        return base, str(exc)


def third_party(
    raw: RawSpec, entry: dict[str, Any], base: Path, path: PathKey
) -> tuple[ThirdPartyMacro | None, list[SpecError]]:
    """The third-party macro an instance's ``xacro`` entry names, or the error that its file is missing."""
    file, problem = resolved_path(base, entry["file"])
    if problem:
        return None, [raw.error((*path, "xacro", "file"), f"cannot use this path: {problem}")]
    if not file.is_file():
        return None, [raw.error((*path, "xacro", "file"), f"no xacro file at {file}")]
    if entry["macro"] in XACRO_KEYWORDS:
        message = f"{entry['macro']!r} is a xacro keyword (xacro:{entry['macro']}), not a macro xacro can call by name"
        return None, [raw.error((*path, "xacro", "macro"), message)]
    params = tuple((k, _literal(v)) for k, v in entry.get("params", {}).items())
    macro = ThirdPartyMacro(
        file=file,
        macro=entry["macro"],
        params=params,
        prefix_param=entry.get("prefix_param", "prefix"),
        parent_param=entry.get("parent_param", "parent"),
    )
    return macro, []


def _literal(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(value) if isinstance(value, float) else str(value)
