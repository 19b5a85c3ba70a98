"""The schema pass: the spec against the robot's JSON Schema (``schemas/robot.schema.json``), every error worded for a
spec author and located.

A valid document is recognised by jsonschema-rs in a fraction of the time; the errors of an invalid one come from
jsonschema, whose ``pattern`` keyword is made to follow ECMA-262 as JSON Schema requires.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterator
from functools import cache, cached_property
from typing import TYPE_CHECKING, Any

from ..errors import SpecError
from ..load import PathKey, RawSpec
from ..shared.package_data import schemas_dir
from .quantities import euler_axes_problem, euler_kind_problem, euler_sequence_problem

if TYPE_CHECKING:
    import jsonschema


@cache
def robot_schema() -> dict[str, Any]:
    return json.loads((schemas_dir() / "robot.schema.json").read_text(encoding="utf-8"))


def inline_refs(schema: dict[str, Any]) -> dict[str, Any]:
    """The schema with every local ``#/$defs/NAME`` reference replaced by the definition itself.

    Our schemas are not recursive, so this terminates; validating against the inlined form is about twice as fast
    (no reference resolution per value) and gives the same errors.
    """
    definitions = schema.get("$defs", {})

    def inline(node: Any) -> Any:
        if isinstance(node, dict):
            if "$ref" in node:
                target = inline(definitions[node["$ref"].rsplit("/", 1)[-1]])
                rest = {k: inline(v) for k, v in node.items() if k != "$ref"}
                return {**target, **rest} if rest else target
            return {k: inline(v) for k, v in node.items()}
        if isinstance(node, list):
            return [inline(v) for v in node]
        return node

    return {key: inline(value) for key, value in schema.items() if key != "$defs"}


@cache
def _inlined_definitions() -> dict[str, Any]:
    schema = robot_schema()
    return {
        name: _without_descriptions(inline_refs({**definition, "$defs": schema["$defs"]}))
        for name, definition in schema["$defs"].items()
    }


def _ecma_pattern(
    validator: jsonschema.protocols.Validator, pattern: str, instance: Any, schema: dict[str, Any]
) -> Iterator[jsonschema.ValidationError]:
    """The ``pattern`` keyword as JSON Schema defines it (ECMA-262 regular expressions).

    The one difference that matters for our patterns: ECMA's ``$`` is the end of the text, while Python's also matches
    before a final newline, so plain jsonschema accepts ``"base\\n"`` as a name. (Our patterns use ``$`` only at their
    end.)
    """
    import jsonschema  # (start-up: jsonschema is imported only for a document jsonschema-rs rejects)

    if validator.is_type(instance, "string") and not _python_regex(pattern).search(instance):
        yield jsonschema.ValidationError(f"{instance!r} does not match {pattern!r}")


@cache
def _python_regex(pattern: str) -> re.Pattern[str]:
    anchored = pattern.endswith("$") and not pattern.endswith("\\$")
    return re.compile(pattern[:-1] + r"\Z" if anchored else pattern)


@cache
def _draft2020() -> Any:
    """jsonschema's Draft 2020-12 validator class with ECMA-262 patterns, made the first time a document needs it."""
    import jsonschema  # (heavy: jsonschema, about 80 ms: only a document jsonschema-rs rejects needs it)

    return jsonschema.validators.extend(jsonschema.Draft202012Validator, {"pattern": _ecma_pattern})


class SchemaValidator:
    """JSON Schema validation that is fast on valid documents and still reports every error in detail.

    jsonschema-rs (compiled) decides whether the document is valid at all, in about a hundredth of the time; only a
    document it rejects, or cannot take (NaN, a huge integer), goes through jsonschema, whose errors we word and
    locate. jsonschema has the last word: a document it accepts is valid. The property tests check that whatever
    jsonschema-rs accepts, jsonschema accepts too.

    ``schema`` is given with its ``$defs``: jsonschema-rs compiles that form in a quarter of the time the inlined one
    takes (1.6 against 7.1 ms for the robot schema, and no 2.5 ms inlining: a run validates one spec, so its start-up
    is what counts), and validates with either at the same speed; jsonschema gets :func:`inline_refs`' form.
    """

    def __init__(self, schema: dict[str, Any]) -> None:
        self.schema = schema

    @cached_property
    def full(self) -> Any:
        """jsonschema's validator of the schema inlined, which words the errors (made when first asked for)."""
        return _draft2020()(inline_refs(self.schema))

    @cached_property
    def fast(self) -> Any:
        try:
            import jsonschema_rs  # (heavy: jsonschema_rs)
        except ImportError:  # (a platform without its wheels: jsonschema alone gives the same verdicts, slower)
            return None
        return jsonschema_rs.validator_for(self.schema)

    def accepts_quickly(self, instance: Any) -> bool:
        """True when jsonschema-rs accepts ``instance``; False when it rejects it or cannot read it."""
        if self.fast is None:
            return False
        try:
            return bool(self.fast.is_valid(instance))
        except (ValueError, TypeError, OverflowError):
            return False

    def iter_errors(self, instance: Any) -> Iterator[jsonschema.ValidationError]:
        if self.accepts_quickly(instance):
            return iter(())
        return self.full.iter_errors(instance)


@cache
def robot_validator() -> SchemaValidator:
    """The robot spec schema's validator (built once)."""
    return SchemaValidator(robot_schema())


# ---------------------------------------------------------------- schema errors
def _bad_name(name: object, *, link_or_joint: bool = False) -> str:
    if link_or_joint:
        return (
            f"{name!r} is not a valid link or joint name: use letters, digits and _, not starting with a digit, in "
            "parts joined by single . / or -"
        )
    return f"{name!r} is not a valid name: use letters, digits and _, not starting with a digit"


def _long_name(error: jsonschema.ValidationError) -> str:
    name = error.instance
    shown = f"{name[:24]}...{name[-8:]}"
    return (
        f"the name {shown!r} is {len(name):,} characters long; a name has at most {error.validator_value} (the file "
        "names made from it must fit the file system's 255-byte limit)"
    )


_COLLECTIONS = {"links": "link", "joints": "joint", "arms": "arm", "wheels": "wheel", "frames": "frame"}


def _not_a_mapping(path: PathKey, error: jsonschema.ValidationError) -> str:
    """A scalar or a list where a mapping belongs: in a spec, nearly always a line indented too little."""
    fields = ", ".join(f"{k}:" for k in list(error.schema.get("properties", {}))[:4]) or "NAME: value"
    got = f"{error.instance!r}" if not isinstance(error.instance, list) else "a list"
    if path and path[-1] == "axis_angle" and isinstance(error.instance, list):
        return (
            "axis_angle is a mapping, {axis: [x, y, z], angle: A}; three numbers, the axis times the angle in "
            "radians, are a rotation vector: write rotvec: [rx, ry, rz]"
        )
    if len(path) == 2 and path[0] in _COLLECTIONS:
        kind = _COLLECTIONS[str(path[0])]
        return (
            f"{path[1]!r} is read as a {kind} name, with the value {got}, but a {kind} is a mapping ({fields} ...); "
            f"if `{path[1]}:` belongs to the {kind} above it, indent it as far as that {kind}'s other keys"
        )
    return (
        f"expected a mapping here ({fields} ...), got {got}; if the lines below belong to it, indent them further "
        "(YAML nests by indentation)"
    )


Message = tuple[PathKey, str, bool]  # (path, message, point-at-key)


def _schema_message(error: jsonschema.ValidationError) -> Message:
    """(path, message, point-at-key) for one schema error, in words a spec author understands: the first of the
    wordings below that knows the error (in this order: Euler sequences, names, quantities, scenes and shapes, bounds,
    types, counts), else jsonschema's own message."""
    path: PathKey = tuple(error.absolute_path)
    wordings = (_sequence_message, _name_message, _quantity_message, _structure_message, _bound_message, _type_message)
    for wording in wordings:
        said = wording(error, path)
        if said is not None:
            return said
    return _count_message(error, path)


def _sequence_message(error: jsonschema.ValidationError, path: PathKey) -> Message | None:
    """An Euler sequence that is none of scipy's (its pattern, or not a string), or none of the twelve under
    intrinsic/extrinsic: which are, not a name's rule; an euler mapping naming its sequence not exactly once."""
    if path[-2:] == ("euler", "sequence") and error.validator in ("pattern", "type"):
        return path, euler_sequence_problem(error.instance), False
    if path[-2:] in (("euler", "intrinsic"), ("euler", "extrinsic")) and error.validator in ("pattern", "type"):
        return path, euler_axes_problem(str(path[-1]), error.instance), False
    if path[-1:] == ("euler",) and error.validator == "oneOf" and isinstance(error.instance, dict):
        key, message = euler_kind_problem(error.instance)
        return (path if key is None else (*path, key)), message, key is not None
    return None


def _name_message(error: jsonschema.ValidationError, path: PathKey) -> Message | None:
    """Unknown keys, and names (keys or values) that are too long or not of the allowed form."""
    keyword = error.validator
    if keyword == "additionalProperties":
        allowed = sorted(error.schema.get("properties", {}))
        extra = sorted(set(error.instance) - set(allowed)) if isinstance(error.instance, dict) else []
        where = (*path, extra[0]) if extra else path
        return where, f"unknown key {extra[0]!r}" + (f"; allowed here: {', '.join(allowed)}" if allowed else ""), True
    if keyword == "propertyNames":
        return (*path, error.instance), _bad_name(error.instance), True
    in_key = "propertyNames" in error.absolute_schema_path
    if keyword == "maxLength" and isinstance(error.instance, str):
        return path + ((error.instance,) if in_key else ()), _long_name(error), in_key
    # (an empty name breaks its pattern and its minLength: the pattern's words say it, once)
    pattern = error.schema.get("pattern") if keyword in ("pattern", "minLength") else None
    if pattern is None:
        return None
    separated = "[./-]" in str(pattern)  # (link and joint names' pattern)
    if in_key:  # a mapping key that is not a valid name: point at the key itself
        return (*path, error.instance), _bad_name(error.instance, link_or_joint=separated), True
    return path, _bad_name(error.instance, link_or_joint=separated), False


def _quantity_message(error: jsonschema.ValidationError, path: PathKey) -> Message | None:
    """A length, angle or mass that is not a number or a quantity string, or a mass or rate not above 0."""
    keyword = error.validator
    kind = _ref_name(error) if keyword in ("type", "minimum", "minLength") else None
    if kind not in ("length", "angle", "quantity", "mass"):
        return None
    example = {"length": "150 mm", "angle": "90 deg", "quantity": "90 deg", "mass": "500 g"}[kind]
    if keyword == "minimum":  # a mass, or a rate (the same schema: told apart by the key); 0 is physics' to say
        key = path[-1] if path and isinstance(path[-1], str) and path[-1] != "mass" else "mass"
        if key != "mass":  # (as validate.quantities says it, so that the two are said once)
            return path, f"{key} must be > 0, got {error.instance!r}", False
        return path, f"mass must be > 0 kg, got {float(error.instance)!r}", False  # as the physics check says it
    return path, f"expected a number or a string such as {example!r}, got {error.instance!r}", False


def _structure_message(error: jsonschema.ValidationError, path: PathKey) -> Message | None:
    """A scene instance's spec or xacro, too many instances, a collision's forms, a shape's one kind."""
    keyword = error.validator
    if keyword in ("oneOf", "anyOf") and len(path) == 2 and path[0] == "instances":
        given = [k for k in ("spec", "xacro") if isinstance(error.instance, dict) and k in error.instance]
        said = f"both {' and '.join(given)}" if len(given) == 2 else (given[0] if given else "neither")
        return (
            path,
            f"an instance takes exactly one of spec (a robot spec) or xacro (a third-party macro); got {said}",
            False,
        )
    if keyword == "oneOf" and path and path[-1] == "collision":
        inner = _within_its_form(error)
        if inner is not None:  # (a mapping or a list, wrong within: say what, where, not that it is no collision)
            return _schema_message(inner)
        return path, "collision must be same, none, a mapping with a shape (and an origin), or a list of them", False
    if keyword == "maxProperties" and path == ("instances",):
        return (
            path,
            f"a scene has at most {error.validator_value:,} instances, got {len(error.instance):,} (as for fleets: "
            "every instance is written out in the URDF, and a scene that large is beyond what RViz shows usefully)",
            False,
        )
    if keyword in ("minProperties", "maxProperties") and "box" in error.schema.get("properties", {}):
        return path, "a shape needs exactly one of box, cylinder, sphere, mesh", False
    return None


def _within_its_form(error: jsonschema.ValidationError) -> jsonschema.ValidationError | None:
    """The error within the one form of a oneOf that a value has the shape of (a collision mapping with an unknown key
    or a wrong origin, a list with a wrong entry), or None when the value itself is none of the forms (a number, an
    empty list: the oneOf's own words say what would be right)."""
    import jsonschema  # (start-up: an error of jsonschema's has imported it already)

    within = [e for e in error.context or () if e.relative_path or e.validator == "additionalProperties"]
    return jsonschema.exceptions.best_match(within) if within else None


def _bound_message(error: jsonschema.ValidationError, path: PathKey) -> Message | None:
    """A value beyond its schema's bounds (a colour of 0-255, a scale factor of 0 among them)."""
    keyword = error.validator
    if keyword == "exclusiveMinimum":
        return path, f"must be > {error.validator_value}, got {error.instance!r}", False
    if keyword == "minimum":
        return path, f"must be >= {error.validator_value}, got {error.instance!r}", False
    if keyword == "not" and path[-2:-1] == ("scale",):
        return path, "a scale factor must not be 0 (it flattens the mesh; a negative one mirrors it)", False
    if keyword == "maximum":
        colour = " (colours are 0..1: divide 0-255 values by 255)" if path[:1] == ("materials",) else ""
        return path, f"must be <= {error.validator_value}, got {error.instance!r}{colour}", False
    return None


def _type_message(error: jsonschema.ValidationError, path: PathKey) -> Message | None:
    """A value of the wrong type: a unit string where only numbers go, a choice, a mapping, the spec itself."""
    keyword = error.validator
    if keyword == "type" and error.validator_value == "number" and isinstance(error.instance, str):
        return (
            path,
            f"expected a plain number in SI units, got {error.instance!r} "
            "(only lengths, angles and masses take unit strings)",
            False,
        )
    if keyword == "enum" or (keyword == "type" and "enum" in error.schema):  # (a value of the wrong type breaks both)
        choices = error.schema["enum"]
        named = ", ".join(map(str, choices[:-1])) + f" or {choices[-1]}" if len(choices) > 1 else str(choices[0])
        axle = (
            " (the axle's direction in the wheel's frame: write axis: y, not a vector)"
            if path[-1:] == ("axis",)
            else ""
        )
        return path, f"must be {named}, got {error.instance!r}{axle}", False
    if keyword == "type" and error.validator_value == "object" and path and not isinstance(error.instance, dict):
        return path, _not_a_mapping(path, error), False
    if keyword == "type" and not path:
        return path, f"a spec is a mapping (robot:, links:, ...), got {type(error.instance).__name__}", False
    if keyword == "type" and isinstance(error.validator_value, str) and error.validator_value in _PLAIN_TYPES:
        return path, f"expected {_PLAIN_TYPES[error.validator_value](error.schema)}, got {error.instance!r}", False
    return None


def _list_of(schema: dict[str, Any]) -> str:
    low, high = schema.get("minItems"), schema.get("maxItems")
    return f"a list of {low} values" if low is not None and low == high else "a list"


# what a value of a JSON type is called where the spec wants one (a string: YAML reads 1, yes or null as no text)
_PLAIN_TYPES = {
    "string": lambda schema: "text (write it in quotes where YAML reads a number, yes/no or null)",
    "array": _list_of,
    "boolean": lambda schema: "true or false",
    "integer": lambda schema: "a whole number",
}


def _count_message(error: jsonschema.ValidationError, path: PathKey) -> Message:
    """Too few or too many entries, an empty mapping, a missing key; else jsonschema's message."""
    keyword = error.validator
    if keyword in ("minItems", "maxItems") and isinstance(error.instance, list):
        low, high = error.schema.get("minItems"), error.schema.get("maxItems")
        wanted = f"{low}" if low == high else f"{low} to {high}" if high is not None else f"at least {low}"
        rows = error.schema.get("items", {}).get("type") == "object"
        one = wanted in ("1", "at least 1")
        what = ("entry" if one else "entries") if rows else ("value" if one else "values")
        return path, f"expected {wanted} {what}, got {len(error.instance)}", False
    if keyword == "minProperties" and error.instance == {}:
        return path, "must not be empty", False
    if keyword == "required":
        return path, error.message.replace("is a required property", "is required here"), False
    if keyword == "minLength" and error.instance == "":
        return path, "must not be empty", False
    return path, error.message, False


def _ref_name(error: jsonschema.ValidationError) -> str | None:
    """Which $defs entry an error's schema is (schemas are compared by identity with the loaded definitions)."""
    wanted = _without_descriptions(error.schema)
    for name, definition in _inlined_definitions().items():
        if definition == wanted:
            return name
    return None


def _without_descriptions(node: Any) -> Any:
    """A schema with its descriptions left out: a $ref that adds its own description is still the definition."""
    if isinstance(node, dict):
        return {k: _without_descriptions(v) for k, v in node.items() if k != "description"}
    if isinstance(node, list):
        return [_without_descriptions(v) for v in node]
    return node


def schema_errors(raw: RawSpec, validator: SchemaValidator | None = None) -> list[SpecError]:
    """Every schema error of ``raw`` (against the robot schema unless another validator is given), located."""
    return located(raw, list((validator or robot_validator()).iter_errors(raw.data)))


def located(raw: RawSpec, errors: list[jsonschema.ValidationError]) -> list[SpecError]:
    """The schema's errors as located spec errors, in the words of :func:`_schema_message`."""
    result = []
    said: set[tuple[PathKey, str]] = set()
    for error in errors:
        path, message, at_key = _schema_message(error)
        if (path, message) not in said:  # (one wrong value can break two keywords, worded alike)
            said.add((path, message))
            result.append(raw.error(path, message, key=at_key))
    return result


# Schema errors that leave the spec's structure intact: the later checks can still run and report more.
_VALUE_ONLY = {"exclusiveMinimum", "minimum", "maximum", "exclusiveMaximum", "pattern", "maxLength"}


def structure_intact(errors: list[jsonschema.ValidationError]) -> bool:
    """True when every error is about a value alone (a bound, a pattern), so that the passes after the schema, which
    rely on the shapes the schema guarantees, can still run."""
    return all(error.validator in _VALUE_ONLY for error in errors)
