"""The validate stage: JSON Schema first, then units and semantic checks; every problem located, all reported at once.

``validate(raw) -> Spec`` where ``Spec.data`` is the spec with every length, angle and mass converted to an SI float.
Nothing here writes or prints; failure is one :class:`SpecErrors` holding the list.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Iterator
from dataclasses import dataclass
from functools import cache, cached_property
from typing import Any

import jsonschema

from .errors import SpecError, SpecErrors
from .gcpause import collector_paused
from .load import PathKey, RawSpec
from .model import DEFAULT_TOOL, LIMITED, MOVING, arm_base_name, attach_joint_name
from .physics import tensor, tensor_problem
from .resources import PUBLIC_MACROS, schemas_dir
from .tree import Tree
from .units import Kind, UnitError, parse_quantity, plain_number

# The robot name becomes a xacro macro name: it must not shadow a library macro or a xacro keyword.
RESERVED_ROBOT_NAMES = frozenset(
    {
        *PUBLIC_MACROS,
        "call",
        "arg",
        "property",
        "include",
        "if",
        "unless",
        "macro",
        "element",
        "attribute",
        "insert_block",
    }
)


@dataclass(frozen=True)
class Spec:
    """A valid spec: ``data`` has SI floats for every quantity; ``raw`` keeps the file positions. ``warnings``: located
    notes on values that are valid but look like a units mistake (degrees written as radians, grams as kilograms)."""

    raw: RawSpec
    data: dict[str, Any]
    warnings: tuple[SpecError, ...] = ()


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
    if validator.is_type(instance, "string") and not _python_regex(pattern).search(instance):
        yield jsonschema.ValidationError(f"{instance!r} does not match {pattern!r}")


@cache
def _python_regex(pattern: str) -> re.Pattern[str]:
    anchored = pattern.endswith("$") and not pattern.endswith("\\$")
    return re.compile(pattern[:-1] + r"\Z" if anchored else pattern)


_Draft2020 = jsonschema.validators.extend(jsonschema.Draft202012Validator, {"pattern": _ecma_pattern})


class SchemaValidator:
    """JSON Schema validation that is fast on valid documents and still reports every error in detail.

    jsonschema-rs (compiled) decides whether the document is valid at all, in about a hundredth of the time; only a
    document it rejects, or cannot take (NaN, a huge integer), goes through jsonschema, whose errors we word and
    locate. jsonschema has the last word: a document it accepts is valid. The property tests check that whatever
    jsonschema-rs accepts, jsonschema accepts too.
    """

    def __init__(self, schema: dict[str, Any]) -> None:
        self.schema = schema
        self.full = _Draft2020(schema)

    @cached_property
    def fast(self) -> Any:
        try:
            import jsonschema_rs
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
    return SchemaValidator(inline_refs(robot_schema()))


# ---------------------------------------------------------------- schema errors
def _bad_name(name: object) -> str:
    return f"{name!r} is not a valid name: use letters, digits and _, not starting with a digit"


def _schema_message(error: jsonschema.ValidationError) -> tuple[PathKey, str, bool]:
    """(path, message, point-at-key) for one schema error, in words a spec author understands."""
    path: PathKey = tuple(error.absolute_path)
    keyword = error.validator
    if keyword == "additionalProperties":
        allowed = sorted(error.schema.get("properties", {}))
        extra = sorted(set(error.instance) - set(allowed)) if isinstance(error.instance, dict) else []
        where = (*path, extra[0]) if extra else path
        return where, f"unknown key {extra[0]!r}" + (f"; allowed here: {', '.join(allowed)}" if allowed else ""), True
    if keyword == "propertyNames":
        name = error.instance
        return (
            (*path, name),
            _bad_name(name),
            True,
        )
    if keyword == "pattern" and "propertyNames" in error.absolute_schema_path:
        name = error.instance  # a mapping key that is not a valid name: point at the key itself
        return (
            (*path, name),
            _bad_name(name),
            True,
        )
    if keyword == "pattern":
        return (
            path,
            _bad_name(error.instance),
            False,
        )
    kind = _ref_name(error) if keyword in ("type", "exclusiveMinimum", "minLength") else None
    if kind in ("length", "angle", "quantity", "mass"):
        example = {"length": "150 mm", "angle": "90 deg", "quantity": "90 deg", "mass": "500 g"}[kind]
        if keyword == "exclusiveMinimum":  # only a mass has one
            return path, f"mass must be > 0 kg, got {float(error.instance)!r}", False  # as the physics check says it
        return path, f"expected a number or a string such as {example!r}, got {error.instance!r}", False
    if keyword in ("oneOf", "anyOf") and len(path) == 2 and path[0] == "instances":
        given = [k for k in ("spec", "xacro") if isinstance(error.instance, dict) and k in error.instance]
        said = f"both {' and '.join(given)}" if len(given) == 2 else (given[0] if given else "neither")
        return (
            path,
            f"an instance takes exactly one of spec (a robot spec) or xacro (a third-party macro); got {said}",
            False,
        )
    if keyword == "oneOf" and path and path[-1] == "collision":
        return path, "collision must be same, none, or a mapping with a shape (and an origin)", False
    if keyword in ("minProperties", "maxProperties") and "box" in error.schema.get("properties", {}):
        return path, "a shape needs exactly one of box, cylinder, sphere, mesh", False
    if keyword == "exclusiveMinimum":
        return path, f"must be > {error.validator_value}, got {error.instance!r}", False
    if keyword == "minimum":
        return path, f"must be >= {error.validator_value}, got {error.instance!r}", False
    if keyword == "maximum":
        colour = " (colours are 0..1: divide 0-255 values by 255)" if path[:1] == ("materials",) else ""
        return path, f"must be <= {error.validator_value}, got {error.instance!r}{colour}", False
    if keyword == "type" and error.validator_value == "number" and isinstance(error.instance, str):
        return (
            path,
            f"expected a plain number in SI units, got {error.instance!r} "
            "(only lengths, angles and masses take unit strings)",
            False,
        )
    if keyword == "type" and not path:
        return path, f"a spec is a mapping (robot:, links:, ...), got {type(error.instance).__name__}", False
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
    return _located(raw, list((validator or robot_validator()).iter_errors(raw.data)))


def _located(raw: RawSpec, errors: list[jsonschema.ValidationError]) -> list[SpecError]:
    located = []
    for error in errors:
        path, message, at_key = _schema_message(error)
        located.append(raw.error(path, message, key=at_key))
    return located


# ---------------------------------------------------------------- quantities
# A plain-number angle beyond this many turns is most likely degrees: one turn for an orientation, two for a joint's
# range (multi-turn joints exist; a range beyond two turns written in radians is rarer than degrees left unmarked).
_TURNS: dict[str | int, int] = {"lower": 2, "upper": 2, "soft_lower_limit": 2, "soft_upper_limit": 2}


class Quantities:
    """Converts every quantity of a schema-valid spec to SI, collecting located errors.

    The loaded data is only read: ``data`` is a copy in which the containers on the way to a converted value are new
    and everything else is shared with ``raw.data`` (a spec written in SI floats throughout is not copied at all).
    Nothing downstream changes the data.
    """

    def __init__(self, raw: RawSpec) -> None:
        self.raw = raw
        self.errors: list[SpecError] = []
        self.warnings: list[SpecError] = []
        self._changes: dict[PathKey, dict[str | int, float]] = {}  # container path -> key -> SI value
        self._count = 0
        self._built: tuple[int, Any] = (0, raw.data)

    @property
    def data(self) -> Any:
        """The spec with the quantities converted so far."""
        if self._built[0] != self._count:
            self._built = (self._count, _with_changes(self.raw.data, self._changes))
        return self._built[1]

    def convert(self, container: Any, key: str | int, path: PathKey, kind: Kind) -> None:
        if isinstance(container, dict) and key not in container:
            return
        value = container[key]
        if kind == "angle":
            plain = value if type(value) in (int, float) else plain_number(value) if isinstance(value, str) else None
            if plain is not None and abs(plain) > _TURNS.get(key, 1) * math.tau:
                self._turns(plain, key, (*path, key))
        if type(value) is float and math.isfinite(value) and (value != 0.0 or math.copysign(1.0, value) > 0):
            return  # already SI: what parse_quantity would return
        try:
            converted = parse_quantity(value, kind) + 0.0  # (+ 0.0: a -0.0 in the spec is written 0.0)
        except UnitError as exc:
            self.errors.append(self.raw.error((*path, key), str(exc)))
            return
        self._changes.setdefault(path, {})[key] = converted
        self._count += 1

    def _turns(self, value: float, key: str | int, path: PathKey) -> None:
        what = "limit" if key in _TURNS else "angle"
        self.warnings.append(
            self.raw.error(
                path,
                f"{what} {value:g} rad is {abs(value) / math.tau:.3g} turns; "
                f"if you meant degrees, write '{value:g} deg'",
            )
        )

    def origin(self, holder: dict[str, Any], key: str, path: PathKey) -> None:
        origin = holder.get(key)
        if not isinstance(origin, dict):
            return
        for index in range(len(origin.get("xyz", []))):
            self.convert(origin["xyz"], index, (*path, key, "xyz"), "length")
        for index in range(len(origin.get("rpy", []))):
            self.convert(origin["rpy"], index, (*path, key, "rpy"), "angle")

    def shape(self, holder: dict[str, Any], path: PathKey) -> None:
        shape = holder.get("shape")
        if not isinstance(shape, dict):
            return
        path = (*path, "shape")
        if "box" in shape:
            for index in range(3):
                self.convert(shape["box"]["size"], index, (*path, "box", "size"), "length")
        for name in ("cylinder", "sphere"):
            for key in ("radius", "length"):
                if name in shape:
                    self.convert(shape[name], key, (*path, name), "length")

    def limits(self, holder: dict[str, Any], path: PathKey, joint_type: str) -> None:
        kind: Kind = "length" if joint_type == "prismatic" else "angle"
        for key in ("lower", "upper"):
            if isinstance(holder.get("limit"), dict):
                self.convert(holder["limit"], key, (*path, "limit"), kind)
        if isinstance(holder.get("mimic"), dict):
            self.convert(holder["mimic"], "offset", (*path, "mimic"), kind)
        if isinstance(holder.get("safety_controller"), dict):
            for key in ("soft_lower_limit", "soft_upper_limit"):
                self.convert(holder["safety_controller"], key, (*path, "safety_controller"), kind)

    def run(self) -> tuple[dict[str, Any], list[SpecError]]:
        data = self.raw.data
        for name, link in data.get("links", {}).items():
            path = ("links", name)
            self.shape(link, path)
            self.origin(link, "origin", path)
            self.origin(link, "com", path)
            self.convert(link, "mass", path, "mass")
            if isinstance(link.get("collision"), dict):
                self.shape(link["collision"], (*path, "collision"))
                self.origin(link["collision"], "origin", (*path, "collision"))
            if isinstance(link.get("inertia"), dict):
                self.origin(link["inertia"], "origin", (*path, "inertia"))
        for name, joint in data.get("joints", {}).items():
            self.origin(joint, "origin", ("joints", name))
            self.limits(joint, ("joints", name), joint["type"])
        for name, arm in data.get("arms", {}).items():
            self.origin(arm, "origin", ("arms", name))
            if isinstance(arm.get("tool"), dict):
                self.origin(arm["tool"], "origin", ("arms", name, "tool"))
            for index, row in enumerate(arm["joints"]):
                path = ("arms", name, "joints", index)
                for key, kind in (
                    ("a", "length"),
                    ("d", "length"),
                    ("alpha", "angle"),
                    ("theta", "angle"),
                    ("mass", "mass"),
                    ("radius", "length"),
                ):
                    self.convert(row, key, path, kind)  # type: ignore[arg-type]
                self.limits(row, path, row.get("type", "revolute"))
        for name, wheel in data.get("wheels", {}).items():
            self.origin(wheel, "origin", ("wheels", name))
            for key, kind in (("radius", "length"), ("width", "length"), ("mass", "mass")):
                self.convert(wheel, key, ("wheels", name), kind)  # type: ignore[arg-type]
        for name, frame in data.get("frames", {}).items():
            self.origin(frame, "origin", ("frames", name))
            self.shape(frame, ("frames", name))
            self.convert(frame, "mass", ("frames", name), "mass")
        return self.data, self.errors


def _with_changes(root: Any, changes: dict[PathKey, dict[str | int, float]]) -> Any:
    """``root`` with the values set in the containers at the given paths, copying only the containers on those paths
    (``root`` itself is not changed)."""
    if not changes:
        return root
    copies: dict[int, Any] = {id(root): root.copy()}
    for path, values in changes.items():
        original, copied = root, copies[id(root)]
        for key in path:
            child = original[key]
            copy = copies.get(id(child))
            if copy is None:
                copy = copies[id(child)] = child.copy()
            copied[key] = copy  # (also when another parent reached it first)
            original, copied = child, copy
        for key, value in values.items():
            copied[key] = value
    return copies[id(root)]


# ---------------------------------------------------------------- semantic checks
@dataclass(frozen=True)
class _Named:
    name: str
    path: PathKey
    at_key: bool


def _link_and_joint_names(data: dict[str, Any]) -> tuple[list[_Named], list[_Named]]:
    """Every link and joint name the spec will create, with where each comes from."""
    links = [_Named(n, ("links", n), True) for n in data.get("links", {})]
    joints = [_Named(n, ("joints", n), True) for n in data.get("joints", {})]
    for arm_name, arm in data.get("arms", {}).items():
        base = arm_base_name(arm_name)
        links.append(_Named(base, ("arms", arm_name), True))
        joints.append(_Named(attach_joint_name(base), ("arms", arm_name), True))
        for index, row in enumerate(arm["joints"]):
            links.append(_Named(row["link"], ("arms", arm_name, "joints", index, "link"), False))
            joints.append(_Named(row["name"], ("arms", arm_name, "joints", index, "name"), False))
        tool = arm.get("tool", {}).get("name", DEFAULT_TOOL)
        tool_path = ("arms", arm_name, "tool", "name") if "name" in arm.get("tool", {}) else ("arms", arm_name)
        links.append(_Named(tool, tool_path, "name" not in arm.get("tool", {})))
        joints.append(_Named(attach_joint_name(tool), tool_path, "name" not in arm.get("tool", {})))
    for section in ("wheels", "frames"):
        for name in data.get(section, {}):
            links.append(_Named(name, (section, name), True))
            joints.append(_Named(attach_joint_name(name), (section, name), True))
    return links, joints


def _duplicates(raw: RawSpec, named: list[_Named], what: str) -> Iterator[SpecError]:
    first: dict[str, _Named] = {}
    for item in named:
        if item.name in first:
            other = first[item.name]
            line, _ = raw.locate(other.path, key=other.at_key)
            yield raw.error(
                item.path,
                f"{what} name {item.name!r} is already used by {_describe(other.path)} "
                f"(line {line}); names must be unique",
                key=item.at_key,
            )
        else:
            first[item.name] = item


def _describe(path: PathKey) -> str:
    from .load import json_path

    return json_path(path)


def _edges(data: dict[str, Any]) -> list[tuple[str, str, PathKey]]:
    """(parent, child, where) for every parent-child relation the spec creates."""
    edges = [(j["parent"], j["child"], ("joints", n)) for n, j in data.get("joints", {}).items()]
    for arm_name, arm in data.get("arms", {}).items():
        chain = [
            arm_base_name(arm_name),
            *(row["link"] for row in arm["joints"]),
            arm.get("tool", {}).get("name", DEFAULT_TOOL),
        ]
        edges.append((arm["parent"], chain[0], ("arms", arm_name, "parent")))
        edges += [(a, b, ("arms", arm_name)) for a, b in zip(chain, chain[1:], strict=False)]
    for section in ("wheels", "frames"):
        edges += [(item["parent"], name, (section, name, "parent")) for name, item in data.get(section, {}).items()]
    return edges


def _tree_errors(raw: RawSpec, data: dict[str, Any], link_names: set[str]) -> Iterator[SpecError]:
    tree: Tree[PathKey] = Tree()
    dangling: list[str] = []  # children of unknown parents: the bad reference is reported, not the tree again
    for parent, child, where in _edges(data):
        if parent == child and where[0] == "joints":
            continue  # "a joint cannot connect a link to itself" says it; not a cycle to report again
        if parent not in link_names:
            dangling.append(child)
            tree.parent_of.setdefault(child, (parent, where))
            continue
        first = tree.add(parent, child, where)
        if first is not None:
            yield raw.error(
                where,
                f"link {child!r} already has parent {first[0]!r}; a link can hang from one joint only (URDF is a tree)",
            )
    roots = tree.roots(link_names)
    stranded = sorted(link_names - tree.reachable([*roots, *dangling]))
    if stranded:
        where = tree.parent_of[stranded[0]][1]
        yield raw.error(where, f"links {', '.join(stranded)} form a cycle (each hangs from another in the loop)")
    if len(roots) > 1:
        listed = ", ".join(roots)
        yield raw.error(
            ("links",),
            f"the links form {len(roots)} separate trees (roots: {listed}); connect them with "
            "joints so that exactly one link has no parent",
            key=True,
        )
    elif not roots and not stranded:
        yield raw.error(("links",), "no root link", key=True)


def _reference_errors(
    raw: RawSpec, data: dict[str, Any], link_names: set[str], joint_types: dict[str, str]
) -> Iterator[SpecError]:
    materials = set(data.get("materials", {}))

    def link_ref(path: PathKey, name: str, role: str) -> Iterator[SpecError]:
        if name not in link_names:
            yield raw.error(path, f"{role} {name!r} is not a link of this robot{_closest(name, link_names)}")

    def material_ref(holder: dict[str, Any], path: PathKey) -> Iterator[SpecError]:
        name = holder.get("material")
        if name is not None and name not in materials:
            known = ", ".join(sorted(materials)) or "none defined"
            yield raw.error((*path, "material"), f"material {name!r} is not in materials (known: {known})")

    for name, link in data.get("links", {}).items():
        yield from material_ref(link, ("links", name))
    for name, joint in data.get("joints", {}).items():
        path = ("joints", name)
        yield from link_ref((*path, "parent"), joint["parent"], "parent")
        if joint["child"] not in data.get("links", {}):
            yield raw.error(
                (*path, "child"),
                f"child {joint['child']!r} is not in links{_closest(joint['child'], set(data.get('links', {})))}",
            )
        if joint["parent"] == joint["child"]:
            yield raw.error((*path, "child"), "a joint cannot connect a link to itself")
        mimic = joint.get("mimic")
        if mimic:
            target = mimic["joint"]
            if target not in joint_types:
                yield raw.error((*path, "mimic", "joint"), f"mimic joint {target!r} is not a joint of this robot")
            elif target == name:
                yield raw.error((*path, "mimic", "joint"), "a joint cannot mimic itself")
            elif joint_types[target] not in MOVING or joint["type"] not in MOVING:
                yield raw.error(
                    (*path, "mimic", "joint"),
                    f"mimic needs two moving joints; {target!r} is "
                    f"{joint_types[target]} and this one is {joint['type']}",
                )
    for name, arm in data.get("arms", {}).items():
        yield from link_ref(("arms", name, "parent"), arm["parent"], "parent")
        for index, row in enumerate(arm["joints"]):
            yield from material_ref(row, ("arms", name, "joints", index))
    for section in ("wheels", "frames"):
        for name, item in data.get(section, {}).items():
            yield from link_ref((section, name, "parent"), item["parent"], "parent")
            yield from material_ref(item, (section, name))
    for name in data.get("gazebo", {}).get("links", {}):
        if name not in link_names:
            yield raw.error(("gazebo", "links", name), f"gazebo settings for {name!r}, which is not a link", key=True)
    for name in data.get("ros2_control", {}).get("joints", {}):
        if joint_types.get(name) not in MOVING:
            what = "is not a joint" if name not in joint_types else f"is a {joint_types[name]} joint"
            yield raw.error(
                ("ros2_control", "joints", name), f"{name!r} {what}; only moving joints are controlled", key=True
            )


def _closest(name: str, known: set[str]) -> str:
    import difflib

    match = difflib.get_close_matches(name, sorted(known), n=1)
    return f" (did you mean {match[0]!r}?)" if match else ""


def _limit_errors(raw: RawSpec, holder: dict[str, Any], path: PathKey, joint_type: str) -> Iterator[SpecError]:
    limit = holder.get("limit")
    if joint_type in LIMITED:
        if not isinstance(limit, dict):
            yield raw.error(path, f"a {joint_type} joint needs limit: lower, upper, effort, velocity")
            return
        missing = [k for k in ("lower", "upper") if k not in limit]
        if missing:
            yield raw.error((*path, "limit"), f"a {joint_type} joint needs limit {' and '.join(missing)}")
            return
        if limit["lower"] > limit["upper"]:
            yield raw.error(
                (*path, "limit", "lower"), f"lower ({limit['lower']!r}) is greater than upper ({limit['upper']!r})"
            )
        safety = holder.get("safety_controller")
        if isinstance(safety, dict):
            low, high = safety.get("soft_lower_limit"), safety.get("soft_upper_limit")
            if low is not None and low < limit["lower"]:
                yield raw.error(
                    (*path, "safety_controller", "soft_lower_limit"),
                    f"soft lower limit {low!r} is below the hard lower limit {limit['lower']!r}",
                )
            if high is not None and high > limit["upper"]:
                yield raw.error(
                    (*path, "safety_controller", "soft_upper_limit"),
                    f"soft upper limit {high!r} is above the hard upper limit {limit['upper']!r}",
                )
    elif joint_type == "continuous" and not isinstance(limit, dict):
        yield raw.error(
            path, "a continuous joint needs limit: {effort, velocity} (controllers and simulators read them)"
        )
    elif isinstance(limit, dict) and ("lower" in limit or "upper" in limit):
        hint = "; make it revolute to limit its range" if joint_type == "continuous" else ""
        yield raw.error((*path, "limit"), f"a {joint_type} joint takes no lower/upper limits{hint}")


def _shape_errors(raw: RawSpec, holder: dict[str, Any], path: PathKey) -> Iterator[SpecError]:
    shape = holder.get("shape")
    if not isinstance(shape, dict):
        return
    values: list[tuple[PathKey, float]] = []
    if "box" in shape:
        values = [((*path, "shape", "box", "size", i), v) for i, v in enumerate(shape["box"]["size"])]
    for name in ("cylinder", "sphere"):
        if name in shape:
            values = [((*path, "shape", name, k), v) for k, v in shape[name].items()]
    for where, value in values:
        if isinstance(value, float) and not value > 0:
            yield raw.error(where, f"sizes must be > 0 m, got {value!r}")


def _inertia_errors(raw: RawSpec, inertia: dict[str, Any], path: PathKey) -> Iterator[SpecError]:
    matrix = tensor(
        inertia["ixx"],
        inertia.get("ixy", 0.0),
        inertia.get("ixz", 0.0),
        inertia["iyy"],
        inertia.get("iyz", 0.0),
        inertia["izz"],
    )
    problem = tensor_problem(matrix)
    if problem:
        yield raw.error(path, problem)


def _physics_errors(raw: RawSpec, data: dict[str, Any]) -> Iterator[SpecError]:
    for name, link in data.get("links", {}).items():
        path = ("links", name)
        yield from _shape_errors(raw, link, path)
        if isinstance(link.get("collision"), dict):
            yield from _shape_errors(raw, link["collision"], (*path, "collision"))
        if "shape" in link and "mass" not in link:
            yield raw.error(
                path,
                "a link with a shape needs a mass (kg): simulators drop bodies without one; "
                "for a pure frame, leave the shape out",
                key=True,
            )
        if "mass" in link:
            yield from _mass_error(raw, link["mass"], (*path, "mass"))
            shape = link.get("shape", {})
            if "inertia" not in link and ("mesh" in shape or not shape):
                what = "a mesh" if "mesh" in shape else "no shape"
                yield raw.error(
                    (*path, "mass"),
                    f"link has a mass but {what}, so its inertia cannot be computed; "
                    "give inertia: {ixx, iyy, izz, ...}",
                )
        elif "inertia" in link:
            yield raw.error((*path, "inertia"), "inertia needs a mass")
        if "inertia" in link:
            yield from _inertia_errors(raw, link["inertia"], (*path, "inertia"))
    children = {child for _, child, _ in _edges(data)}
    for name, joint in data.get("joints", {}).items():
        path = ("joints", name)
        yield from _limit_errors(raw, joint, path, joint["type"])
        if joint["type"] == "floating" and joint["parent"] in children:
            yield raw.error(
                (*path, "type"),
                "a floating joint may only hang from the root link (a floating base): "
                "simulators such as MuJoCo reject deeper ones",
            )
        child = data.get("links", {}).get(joint["child"])
        if joint["type"] != "fixed" and isinstance(child, dict) and "mass" not in child:
            yield raw.error(
                (*path, "child"),
                f"link {joint['child']!r} is moved by this {joint['type']} joint but "
                "has no mass; give it a mass (and a shape or an inertia)",
            )
        axis = joint.get("axis")
        if axis is not None and not any(axis):
            yield raw.error((*path, "axis"), "axis must not be zero; e.g. [0, 0, 1] for the z axis")
        if axis is not None and joint["type"] in ("fixed", "floating"):
            yield raw.error((*path, "axis"), f"a {joint['type']} joint takes no axis")
    for name, arm in data.get("arms", {}).items():
        for index, row in enumerate(arm["joints"]):
            path = ("arms", name, "joints", index)
            yield from _limit_errors(raw, row, path, row.get("type", "revolute"))
            if "mass" in row:
                yield from _mass_error(raw, row["mass"], (*path, "mass"))
            elif row.get("type", "revolute") != "fixed":
                yield raw.error(
                    path,
                    f"row {row['name']!r} moves link {row['link']!r}, which has no mass; give the "
                    "row a mass (kg) for its body",
                )
            if "radius" in row and not row["radius"] > 0:
                yield raw.error((*path, "radius"), f"radius must be > 0 m, got {row['radius']!r}")
    for name, wheel in data.get("wheels", {}).items():
        for key in ("radius", "width"):
            if not wheel[key] > 0:
                yield raw.error(("wheels", name, key), f"{key} must be > 0 m, got {wheel[key]!r}")
        yield from _mass_error(raw, wheel["mass"], ("wheels", name, "mass"))
    for name, frame in data.get("frames", {}).items():
        yield from _shape_errors(raw, frame, ("frames", name))
        if "shape" in frame and "mass" not in frame:
            yield raw.error(
                ("frames", name),
                "a frame with a shape needs a mass (kg); for a bare frame, leave the shape out",
                key=True,
            )
        if "mass" in frame:
            yield from _mass_error(raw, frame["mass"], ("frames", name, "mass"))
            if "mesh" in frame.get("shape", {"mesh": None}):
                yield raw.error(("frames", name, "mass"), "a frame's mass needs a box, cylinder or sphere shape")


DENSEST = 22_590.0  # kg/m^3: osmium, the densest element
LIGHTEST = 1.0  # kg/m^3: less than air (1.2); no solid body in a robot is lighter


def _shape_volume(shape: dict[str, Any]) -> tuple[str, float] | None:
    if "box" in shape:
        x, y, z = shape["box"]["size"]
        return "box", x * y * z
    if "cylinder" in shape:
        return "cylinder", math.pi * shape["cylinder"]["radius"] ** 2 * shape["cylinder"]["length"]
    if "sphere" in shape:
        return "sphere", 4.0 / 3.0 * math.pi * shape["sphere"]["radius"] ** 3
    return None


def _density_warnings(raw: RawSpec, data: dict[str, Any]) -> Iterator[SpecError]:
    """Masses that no solid filling their shape could have: grams written as kilograms, millimetres as metres."""
    for section in ("links", "frames", "wheels"):
        for name, body in data.get(section, {}).items():
            mass = body.get("mass")
            if mass is None:
                continue
            if section == "wheels":
                found = "cylinder", math.pi * body["radius"] ** 2 * body["width"]
            else:
                shape = body.get("shape")
                found = _shape_volume(shape) if shape else None
            if found is None or not (found[1] > 0 and mass > 0):
                continue
            density = mass / found[1]
            if LIGHTEST <= density <= DENSEST:
                continue
            hint = (
                "denser than osmium (22,590 kg/m^3); grams written as kilograms? e.g. '500 g'"
                if density > DENSEST
                else "lighter than air; a size in mm written as m? e.g. '150 mm'"
            )
            yield raw.error(
                (section, name, "mass"),
                f"mass {mass:g} kg in a {found[1]:.3g} m^3 {found[0]} is {density:.3g} kg/m^3, {hint}",
            )


def _mass_error(raw: RawSpec, mass: float, path: PathKey) -> Iterator[SpecError]:
    if not (isinstance(mass, float) and mass > 0 and math.isfinite(mass)):
        yield raw.error(path, f"mass must be > 0 kg, got {mass!r}")


def semantic_errors(raw: RawSpec, data: dict[str, Any], *, physics: bool = True) -> list[SpecError]:
    """Names, references and the tree always; physics only when every quantity parsed (it compares numbers)."""
    link_named, joint_named = _link_and_joint_names(data)
    errors = list(_duplicates(raw, link_named, "link")) + list(_duplicates(raw, joint_named, "joint"))
    if data["robot"] in RESERVED_ROBOT_NAMES or data["robot"].startswith("_xacrokit"):
        errors.append(
            raw.error(
                ("robot",),
                f"robot name {data['robot']!r} is taken by a xacrokit macro or a xacro "
                "keyword (the robot's macro is named after it); choose another name",
            )
        )
    link_names = {item.name for item in link_named}
    joint_types = {n: j["type"] for n, j in data.get("joints", {}).items()}
    for arm in data.get("arms", {}).values():
        joint_types.update({row["name"]: row.get("type", "revolute") for row in arm["joints"]})
    joint_types.update({attach_joint_name(n): "continuous" for n in data.get("wheels", {})})
    joint_types.update({attach_joint_name(n): "fixed" for n in data.get("frames", {})})
    errors += _reference_errors(raw, data, link_names, joint_types)
    errors += _tree_errors(raw, data, link_names)
    if physics:
        errors += _physics_errors(raw, data)
    return errors


# Schema errors that leave the spec's structure intact: the later checks can still run and report more.
_VALUE_ONLY = {"exclusiveMinimum", "minimum", "maximum", "exclusiveMaximum", "pattern"}


def _value_only(error: jsonschema.ValidationError) -> bool:
    return error.validator in _VALUE_ONLY


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
    errors = _located(raw, found)
    if any(not _value_only(e) for e in found):  # the later checks rely on the shapes the schema guarantees
        raise SpecErrors(errors)
    quantities = Quantities(raw)
    data, unit_errors = quantities.run()
    notes = quantities.warnings
    del quantities  # (its table of changes is garbage now: not kept through the checks below)
    errors += unit_errors + semantic_errors(raw, data, physics=not unit_errors)
    if errors:
        raise SpecErrors(_unique(errors))
    warnings = notes + list(_density_warnings(raw, data))
    return Spec(raw=raw, data=data, warnings=tuple(sorted(warnings, key=lambda w: (w.line or 0, w.column or 0))))
