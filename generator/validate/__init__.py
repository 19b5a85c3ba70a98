"""The validate stage: JSON Schema first, then units and semantic checks; every problem located, all reported at once.

``validate(raw) -> Spec`` where ``Spec.data`` is the spec with every length, angle and mass converted to an SI float.
Nothing here writes or prints; failure is one :class:`SpecErrors` holding the list. One module per pass, in the order
they run: :mod:`.schema` (the JSON Schema and the wording of its errors), :mod:`.quantities` (units to SI),
:mod:`.names` (names, references, the tree), :mod:`.physics` (sizes, masses, inertia, limits, axes, densities) and
:mod:`.poses` (named poses within the limits, their mimic joints too); :mod:`.bodies` walks a spec's links, arm rows,
wheels and frames for all of them.

Units are converted here rather than in resolve (where the stage list of the style notes puts them) because a value
that does not parse must be reported at its line and column, and the physics checks compare SI numbers while they
still have the spec's positions beside them; resolve takes SI floats and never sees a unit.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from ..errors import SpecError, SpecErrors
from ..load import PathKey, RawSpec
from ..shared.gc_pause import collector_paused
from ..shared.sim_sensors import PRESETS, preset_body, resolve_sensor, sensor_problems
from .bodies import Body, bodies, joint_types, parts
from .extension import extension_body
from .mirror import copies_said, mirrored
from .names import (
    duplicate_errors,
    edges,
    link_and_joint_names,
    reference_errors,
    repeated_paths,
    robot_name_errors,
    tree_errors,
)
from .physics import Implausible, physics_errors
from .poses import pose_errors
from .quantities import Quantities, with_values
from .schema import (
    SchemaValidator,
    inline_refs,
    located,
    robot_schema,
    robot_validator,
    schema_errors,
    structure_intact,
)
from .solids import (
    body_solids,
    density_warnings,
    hull_errors,
    masses_from_density,
    mesh_files_errors,
    mesh_inertias,
)

__all__ = [
    "Quantities",
    "SchemaValidator",
    "Spec",
    "inline_refs",
    "robot_schema",
    "robot_validator",
    "schema_errors",
    "validate",
]


@dataclass(frozen=True)
class Spec:
    """A valid spec: ``data`` has SI floats for every quantity; ``raw`` keeps the file positions. ``warnings``: located
    notes on values that are valid but look like a units mistake (degrees written as radians, grams as kilograms)."""

    raw: RawSpec
    data: dict[str, Any]
    warnings: tuple[SpecError, ...] = ()
    extension: str = ""  # the `extension` file's <robot> children, escaped for xacro (validate/extension.py)


def semantic_errors(
    raw: RawSpec, data: dict[str, Any], every: Sequence[Body], *, physics: bool = True
) -> list[SpecError]:
    """Names, references and the tree always; physics only when every quantity parsed (it compares numbers).

    ``every``: ``list(bodies(data))``, walked once for all the passes (measurably faster on big robots than a walk
    per pass).
    """
    link_named, joint_named = link_and_joint_names(data, every)
    errors = list(duplicate_errors(raw, link_named, "link")) + list(duplicate_errors(raw, joint_named, "joint"))
    errors += robot_name_errors(raw, data)
    link_names = {item.name for item in link_named}
    errors += reference_errors(raw, data, every, link_names, joint_types(data, every))
    relations = edges(data, every)
    again = repeated_paths(link_named)  # (a link named twice is said once, not again as a second parent or a cycle)
    kept = [r for r in relations if not any(r[2][: len(p)] == p[: len(r[2])] for p in again)]  # (either holds other)
    errors += tree_errors(raw, kept, link_names)
    if physics:
        errors += physics_errors(raw, data, every, {child for _, child, _ in relations})
        errors += pose_errors(raw, data, every)
        errors += sensor_errors(raw, data)
    return errors


def sensor_errors(raw: RawSpec, data: dict[str, Any]) -> list[SpecError]:
    """Each frame sensor's impossible values (a range that ends before it starts, a scan wider than a turn, a field
    of view of pi or more), at the key that says it."""
    errors = []
    for name, frame in data.get("frames", {}).items():
        if isinstance(frame.get("sensor"), dict):
            given = frame["sensor"]
            preset = PRESETS.get(given.get("preset", ""))
            if preset is not None and given.get("type", preset[0]) != preset[0]:
                message = f"preset {given['preset']!r} is a {preset[0]}, not a {given['type']}: give one or the other"
                errors.append(raw.error(("frames", name, "sensor", "preset"), message))
                continue
            sensor = resolve_sensor(name, given)
            for keys, message in sensor_problems(name, sensor):
                path = ("frames", name, "sensor", *keys)
                errors.append(raw.error(path if _has(frame["sensor"], keys) else ("frames", name, "sensor"), message))
    return errors


def _has(holder: Any, keys: Sequence[str]) -> bool:
    for key in keys:
        if not isinstance(holder, dict) or key not in holder:
            return False
        holder = holder[key]
    return True


def _unique(errors: list[SpecError]) -> list[SpecError]:
    seen: set[tuple[str, str]] = set()
    result = []
    for error in errors:
        if (error.path, error.message) not in seen:
            seen.add((error.path, error.message))
            result.append(error)
    return result


@collector_paused()
def validate(raw: RawSpec) -> Spec:
    """Check a loaded spec against the schema and the rules a robot must obey.

    Raises:
        SpecErrors: every problem found, each with file, JSON path, line and column.
    """
    found = list(robot_validator().iter_errors(raw.data))  # one pass over the document
    errors = located(raw, found)
    if not structure_intact(found):  # the later checks rely on the shapes the schema guarantees
        raise SpecErrors(errors)
    quantities = Quantities(raw)
    data, unit_errors = quantities.run()
    parsed = all(isinstance(e, Implausible) for e in unit_errors)  # (a limit of 0 is a number the checks compare)
    notes = quantities.warnings
    del quantities  # (its table of changes is garbage now: not kept through the checks below)
    data, aliases, mirror_errors = mirrored(raw, data, parsed=parsed)
    if aliases:  # (every later problem of a copy is located at what it was copied from)
        raw = dataclasses.replace(raw, aliases=aliases)
    bodied: dict[PathKey, dict[str | int, Any]] = {
        ("frames", n): preset_body(f) for n, f in data.get("frames", {}).items() if preset_body(f)
    }
    data = with_values(data, bodied)  # (a sensor preset's shape and mass, for a frame that gives none)
    every = list(bodies(data))
    items = every + list(parts(data))  # (a composite link's parts are bodies too, though not links)
    solids, solid_errors, solid_notes = body_solids(raw, data, items) if parsed else ({}, [], [])
    masses, density_errors, density_notes = masses_from_density(raw, items, solids) if parsed else ({}, [], [])
    if masses:  # (the bodies that gave a density: their mass, before the checks that want one)
        data = with_values(data, {path: {"mass": mass} for path, mass in masses.items()})
        every = list(bodies(data))
        items = every + list(parts(data))
    inertias = mesh_inertias(items, solids)
    if inertias:  # (a mesh body's tensor, computed from its surface, as an explicit one)
        data = with_values(data, inertias)
        every = list(bodies(data))
        items = every + list(parts(data))
    extension, extension_errors = extension_body(raw, data)
    errors += (
        unit_errors
        + mirror_errors
        + mesh_files_errors(raw, data)
        + hull_errors(raw, data)
        + solid_errors
        + density_errors
        + extension_errors
    )
    errors += semantic_errors(raw, data, every, physics=parsed)
    lenient = data.get("strict") is False
    doubts: list[SpecError] = [e for e in errors if lenient and isinstance(e, Implausible)]
    errors = [e for e in errors if not (lenient and isinstance(e, Implausible))]
    if errors:
        raise SpecErrors(_unique(list(copies_said(errors, aliases))))
    dense = list(density_warnings(raw, items, solids))
    # a shape whose mass gives an impossible density says so once, at its mass, not also at each long size
    said = tuple(w.path.removesuffix(".mass") + ".shape." for w in dense)
    warnings = [n for n in notes if not n.path.startswith(said)] + dense + density_notes + solid_notes
    warnings += _unique(doubts)  # (strict: false: the values no real body has, written as given)
    ordered = tuple(sorted(copies_said(warnings, aliases), key=lambda w: (w.line or 0, w.column or 0)))
    return Spec(raw=raw, data=data, warnings=ordered, extension=extension)
