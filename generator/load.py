"""The load stage: read a spec file into plain data, remembering where every value came from.

Safe YAML only (no tags that build objects). Duplicate keys, anchors/aliases (and so alias bombs), several documents
and non-UTF-8 bytes are rejected with a located error. An unquoted scalar that reads as a number in JSON or YAML 1.2
(``1e-3``, which PyYAML's YAML 1.1 rules leave a string) is a number; a quoted one stays a string.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml
from yaml.constructor import SafeConstructor

from .errors import SpecError, SpecErrors
from .gcpause import collector_paused

PathKey = tuple[str | int, ...]
# libyaml's composer (same nodes, same line/column marks) is several times faster than PyYAML's pure-Python one
_COMPOSER = yaml.CSafeLoader if getattr(yaml, "__with_libyaml__", False) else yaml.SafeLoader
_PLAIN_TAGS = {
    f"tag:yaml.org,2002:{name}"
    for name in ("str", "int", "float", "bool", "null", "map", "seq", "timestamp", "binary", "merge")
}
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
MAX_SPEC_BYTES = 16 * 1024 * 1024


@dataclass(frozen=True)
class RawSpec:
    """A spec as read: plain data plus the 1-based (line, column) of every value and of every mapping key."""

    file: str
    data: Any
    positions: dict[PathKey, tuple[int, int]] = field(default_factory=dict)
    key_positions: dict[PathKey, tuple[int, int]] = field(default_factory=dict)

    def locate(self, path: PathKey, *, key: bool = False) -> tuple[int | None, int | None]:
        """Position of ``path`` (its key when ``key``), or of the nearest enclosing value that has one."""
        table = self.key_positions if key else self.positions
        probe = tuple(path)
        while probe:
            if probe in table:
                return table[probe]
            probe = probe[:-1]
            table = self.positions
        return self.positions.get((), (None, None))

    def error(self, path: PathKey, message: str, *, key: bool = False) -> SpecError:
        line, column = self.locate(path, key=key)
        return SpecError(message, file=self.file, path=json_path(path), line=line, column=column)


def json_path(path: PathKey) -> str:
    out = "$"
    for part in path:
        if isinstance(part, int):
            out += f"[{part}]"
        elif re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", part):
            out += f".{part}"
        else:
            out += f"[{part!r}]"
    return out


def _mark(node: yaml.Node) -> tuple[int, int]:
    return node.start_mark.line + 1, node.start_mark.column + 1


class _Builder:
    def __init__(self, file: str) -> None:
        self.file = file
        self.positions: dict[PathKey, tuple[int, int]] = {}
        self.key_positions: dict[PathKey, tuple[int, int]] = {}
        self.errors: list[SpecError] = []
        self.seen: set[int] = set()
        self.scalars = SafeConstructor()

    def fail(self, node: yaml.Node, path: PathKey, message: str) -> None:
        line, column = _mark(node)
        self.errors.append(SpecError(message, file=self.file, path=json_path(path), line=line, column=column))

    def build(self, node: yaml.Node, path: PathKey) -> Any:
        if id(node) in self.seen:
            # PyYAML hands back the anchored node itself; point at the key that used the alias instead.
            anchor_line, _ = _mark(node)
            line, column = self.key_positions.get(path, _mark(node))
            message = (
                f"YAML aliases (*name) are not supported in specs; write the value out (anchored on line {anchor_line})"
            )
            self.errors.append(SpecError(message, file=self.file, path=json_path(path), line=line, column=column))
            return None
        self.seen.add(id(node))
        self.positions[path] = _mark(node)
        if node.tag not in _PLAIN_TAGS:
            shown = node.tag.replace("tag:yaml.org,2002:", "!!")
            self.fail(node, path, f"YAML tag {shown} is not allowed in specs; write a plain value")
            return None
        if isinstance(node, yaml.MappingNode):
            return self.mapping(node, path)
        if isinstance(node, yaml.SequenceNode):
            return [self.build(item, (*path, index)) for index, item in enumerate(node.value)]
        return self.scalar(node, path)

    def mapping(self, node: yaml.MappingNode, path: PathKey) -> dict[str, Any]:
        result: dict[str, Any] = {}
        first_seen: dict[str, yaml.Node] = {}
        for key_node, value_node in node.value:
            if key_node.tag == "tag:yaml.org,2002:merge":
                self.fail(key_node, path, "YAML merge keys (<<) are not supported in specs; write the keys out")
                continue
            if not isinstance(key_node, yaml.ScalarNode):
                self.fail(key_node, path, "mapping keys must be plain names, not lists or mappings")
                continue
            key = str(key_node.value)
            if key in first_seen:
                line, _ = _mark(first_seen[key])
                self.fail(key_node, (*path, key), f"duplicate key {key!r} (first given on line {line})")
                continue
            first_seen[key] = key_node
            self.key_positions[(*path, key)] = _mark(key_node)
            result[key] = self.build(value_node, (*path, key))
        return result

    def scalar(self, node: yaml.ScalarNode, path: PathKey) -> Any:
        plain = not node.style  # PyYAML says None for a plain scalar, libyaml says ""
        if node.tag == "tag:yaml.org,2002:str" and plain and _NUMBER.fullmatch(node.value):
            return float(node.value)
        if node.tag in ("tag:yaml.org,2002:timestamp", "tag:yaml.org,2002:binary"):
            return node.value
        try:
            return self.scalars.construct_object(node)
        except yaml.YAMLError as exc:
            self.fail(node, path, f"cannot read this value: {exc}")
            return None


def _yaml_error(file: str, exc: yaml.YAMLError) -> SpecError:
    mark = getattr(exc, "problem_mark", None) or getattr(exc, "context_mark", None)
    problem = getattr(exc, "problem", None) or str(exc)
    line, column = (mark.line + 1, mark.column + 1) if mark else (None, None)
    return SpecError(f"not valid YAML: {problem}", file=file, line=line, column=column)


def load_text(text: str, file: str = "<spec>") -> RawSpec:
    """Read spec text (already decoded). Raises :class:`SpecErrors` on anything unreadable."""
    with collector_paused():
        return _load_text(text, file)


def _load_text(text: str, file: str) -> RawSpec:
    try:
        node = yaml.compose(text, Loader=_COMPOSER)
    except yaml.YAMLError as exc:
        raise SpecErrors([_yaml_error(file, exc)]) from None
    if node is None:
        raise SpecErrors([SpecError("the spec is empty; start from `gen-robot new NAME`", file=file, line=1, column=1)])
    builder = _Builder(file)
    data = builder.build(node, ())
    if builder.errors:
        raise SpecErrors(builder.errors)
    return RawSpec(file=file, data=data, positions=builder.positions, key_positions=builder.key_positions)


def load_file(path: str | Path) -> RawSpec:
    """Read a spec file: UTF-8, at most 16 MiB. Raises :class:`SpecErrors` with a located message."""
    file = str(path)
    try:
        raw = Path(path).read_bytes()
    except OSError as exc:
        raise SpecErrors([SpecError(f"cannot read the spec: {exc.strerror}", file=file)]) from None
    if len(raw) > MAX_SPEC_BYTES:
        raise SpecErrors([SpecError(f"the spec is larger than {MAX_SPEC_BYTES} bytes", file=file)])
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        column = exc.start - (raw.rfind(b"\n", 0, exc.start) + 1) + 1
        raise SpecErrors(
            [SpecError(f"the spec is not UTF-8 text (byte {raw[exc.start]:#04x})", file=file, line=line, column=column)]
        ) from None
    return load_text(text.removeprefix("\ufeff"), file)
