"""The load stage: read a spec file into plain data, remembering where every value came from.

Safe YAML only (no tags that build objects). Duplicate keys, anchors/aliases (and so alias bombs), several documents
and non-UTF-8 bytes are rejected with a located error. An unquoted scalar that reads as a number in JSON or YAML 1.2
(``1e-3``, which PyYAML's YAML 1.1 rules leave a string) is a number; a quoted one stays a string.
"""

from __future__ import annotations

import math
import re
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

import yaml
from yaml.constructor import SafeConstructor

from .errors import SpecError, SpecErrors
from .shared.gc_pause import collector_paused
from .shared.input_files import read_input
from .shared.units import NUMBER

PathKey = tuple[str | int, ...]
# libyaml's parser (same events, same line/column marks) is several times faster than PyYAML's pure-Python one
_PARSER = yaml.CSafeLoader if getattr(yaml, "__with_libyaml__", False) else yaml.SafeLoader
_PLAIN_TAGS = {
    f"tag:yaml.org,2002:{name}"
    for name in ("str", "int", "float", "bool", "null", "map", "seq", "timestamp", "binary", "merge")
}
_NUMBER = re.compile(NUMBER)
MAX_SPEC_BYTES = 16 * 1024 * 1024


@dataclass(frozen=True)
class RawSpec:
    """A spec as read: plain data, and the 1-based (line, column) of every value and of every mapping key.

    The positions are read from ``text`` the first time they are asked for (to locate an error, say): a valid spec
    on its way to a package never needs them, and recording them took half of the loading time.
    """

    file: str
    data: Any
    text: str | None = field(default=None, repr=False, compare=False)
    # where what a spec's `mirror` made was copied from (a copy's path -> its source's): a copy is located at its source
    aliases: dict[PathKey, PathKey] = field(default_factory=dict, repr=False, compare=False)

    @cached_property
    def _position_tables(self) -> tuple[dict[PathKey, tuple[int, int]], dict[PathKey, tuple[int, int]]]:
        if self.text is None:
            return {}, {}
        with collector_paused():
            builder = _read(self.text, self.file, track=True)
        return builder.positions, builder.key_positions

    @property
    def positions(self) -> dict[PathKey, tuple[int, int]]:
        """Path of every value -> its (line, column)."""
        return self._position_tables[0]

    @property
    def key_positions(self) -> dict[PathKey, tuple[int, int]]:
        """Path of every mapping entry -> the (line, column) of its key."""
        return self._position_tables[1]

    def locate(self, path: PathKey, *, key: bool = False) -> tuple[int | None, int | None]:
        """Position of ``path`` (its key when ``key``), or of the nearest enclosing value that has one."""
        table = self.key_positions if key else self.positions
        probe = self.source(path)
        while probe:
            if probe in table:
                return table[probe]
            probe = probe[:-1]
            table = self.positions
        return self.positions.get((), (None, None))

    def source(self, path: PathKey) -> PathKey:
        """``path``, or where it was copied from when a `mirror` made it (a copy of a copy: back to the spec's own)."""
        path = tuple(path)
        for _ in range(len(self.aliases)):
            made = next((n for n in (3, 2) if path[:n] in self.aliases), None)
            if made is None:
                break
            path = self.aliases[path[:made]] + path[made:]
        return path

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


_STR = "tag:yaml.org,2002:str"
_INT = "tag:yaml.org,2002:int"
_FLOAT = "tag:yaml.org,2002:float"
_MERGE = "tag:yaml.org,2002:merge"
_TIMESTAMP = "tag:yaml.org,2002:timestamp"
_RESOLVER = yaml.resolver.Resolver()


def _at(event: Any) -> tuple[int, int]:
    return event.start_mark.line + 1, event.start_mark.column + 1


class _Builder:
    """Builds plain data and positions straight from the parser's events (no node tree: half the time).

    Events are told apart by their exact type (``type(event) is ...``, the fastest test) and typed ``Any``: PyYAML's
    stubs give the attributes of each event class only to that class.
    """

    def __init__(self, file: str, loader: yaml.CSafeLoader | yaml.SafeLoader, track: bool) -> None:
        self.file = file
        self.track = track  # record positions (and paths): without, errors are only noticed, for a second pass
        self.next_event: Callable[[], Any] = loader.get_event
        self.positions: dict[PathKey, tuple[int, int]] = {}
        self.key_positions: dict[PathKey, tuple[int, int]] = {}
        self.errors: list[SpecError] = []
        self.anchors: dict[str, int] = {}
        self.plain: dict[str, Any] = {}  # plain scalar text -> its value
        self.data: Any = None

    def fail(self, event: Any, path: PathKey, message: str) -> None:
        line, column = _at(event)
        self.errors.append(SpecError(message, file=self.file, path=json_path(path), line=line, column=column))

    def build(self, event: Any, path: PathKey, record: bool = True) -> Any:
        """The value that starts with ``event``; ``record=False`` consumes it without positions or errors."""
        kind = type(event)
        if kind is yaml.AliasEvent:
            self.check_alias(event)
            if record:
                # point at the key that used the alias
                line, column = self.key_positions.get(path, _at(event))
                message = (
                    "YAML aliases (*name) are not supported in specs; write the value out "
                    f"(anchored on line {self.anchors[event.anchor]})"
                )
                self.errors.append(SpecError(message, file=self.file, path=json_path(path), line=line, column=column))
            return None
        if event.anchor is not None:
            self.anchor(event)
        if record and self.track:
            self.positions[path] = _at(event)
        if kind is yaml.ScalarEvent:
            return self.scalar(event, path, record)
        tag = event.tag
        if tag is not None and tag != "!" and tag not in _PLAIN_TAGS:
            if record:
                shown = tag.replace("tag:yaml.org,2002:", "!!")
                self.fail(event, path, f"YAML tag {shown} is not allowed in specs; write a plain value")
            self.skip_collection()
            return None
        if kind is yaml.MappingStartEvent:
            return self.mapping(path, record)
        return self.sequence(path, record)

    def anchor(self, event: Any) -> None:
        """Remember an anchor (&name); like PyYAML, a name used twice is an error of the YAML itself."""
        if event.anchor in self.anchors:
            problem = f"found duplicate anchor {event.anchor!r} (first on line {self.anchors[event.anchor]})"
            raise SpecErrors([_event_error(self.file, problem, event)])
        self.anchors[event.anchor] = event.start_mark.line + 1

    def check_alias(self, event: Any) -> int:
        """The line of the anchor an alias (*name) refers to; an alias to no anchor is an error of the YAML itself."""
        if event.anchor not in self.anchors:
            raise SpecErrors([_event_error(self.file, f"found undefined alias {event.anchor!r}", event)])
        return self.anchors[event.anchor]

    def skip_collection(self) -> None:
        """Read past a rejected collection, still learning its anchors (a later alias to one is not 'undefined')."""
        depth = 1
        while depth:
            event = self.next_event()
            kind = type(event)
            if kind is yaml.AliasEvent:
                self.check_alias(event)
                continue
            if kind is yaml.MappingEndEvent or kind is yaml.SequenceEndEvent:
                depth -= 1
                continue
            if event.anchor is not None:
                self.anchor(event)
            if kind is yaml.MappingStartEvent or kind is yaml.SequenceStartEvent:
                depth += 1

    def sequence(self, path: PathKey, record: bool) -> list[Any]:
        items: list[Any] = []
        event = self.next_event()
        while type(event) is not yaml.SequenceEndEvent:
            items.append(self.build(event, (*path, len(items)) if self.track else path, record))
            event = self.next_event()
        return items

    def mapping(self, path: PathKey, record: bool) -> dict[str, Any]:
        result: dict[str, Any] = {}
        first_lines: dict[str, int] = {}
        event = self.next_event()
        while type(event) is not yaml.MappingEndEvent:
            key_event = event
            key = self.key(key_event, path, record)
            event = self.next_event()  # the value's first event
            if key is None or key in first_lines:
                if key is not None and record:
                    message = f"duplicate key {key!r} (first given on line {first_lines[key]})"
                    self.fail(key_event, (*path, key), message)
                self.build(event, path, record=False)
            else:
                first_lines[key] = key_event.start_mark.line + 1
                child = (*path, key) if self.track else path
                if record and self.track:
                    self.key_positions[child] = _at(key_event)
                result[key] = self.build(event, child, record)
            event = self.next_event()
        return result

    def key(self, event: Any, path: PathKey, record: bool) -> str | None:
        """A mapping key as text, or None (with an error) for a merge key, a collection or an alias."""
        if type(event) is yaml.AliasEvent:
            anchored = self.check_alias(event)
            if record:
                message = (
                    f"YAML aliases (*name) are not supported in specs; write the key out (anchored on line {anchored})"
                )
                self.fail(event, path, message)
            return None
        if event.anchor is not None:
            self.anchor(event)
        if type(event) is not yaml.ScalarEvent:
            if record:
                self.fail(event, path, "mapping keys must be plain names, not lists or mappings")
            self.skip_collection()
            return None
        tag = event.tag
        if tag is None or tag == "!":
            tag = _MERGE if event.value == "<<" and event.implicit[0] else _STR  # YAML 1.1's only implicit key tag
        if tag == _MERGE:
            if record:
                self.fail(event, path, "YAML merge keys (<<) are not supported in specs; write the keys out")
            return None
        return event.value

    def scalar(self, event: Any, path: PathKey, record: bool) -> Any:
        try:
            if event.tag is None and not event.style:  # a plain scalar: its value depends on its text alone
                value = self.plain.get(event.value, _UNSEEN)
                if value is _UNSEEN:
                    value = self.plain[event.value] = _scalar_value(event)
                return value
            return _scalar_value(event)
        except _Unreadable as exc:
            if record:
                self.fail(event, path, str(exc))
            return None


class _Unreadable(Exception):
    """A scalar that cannot become a spec value (the message says why)."""


_UNSEEN = object()


MAX_NUMBER_TEXT = 400  # characters: more than any double needs (17 digits and an exponent), far from Python's limits


def _number(text: str, tag: str) -> float | int:
    """One number reader for every number a spec holds: decimal digits (ASCII), finite, representable as a double.
    YAML 1.1's other forms (.nan, .inf, 0x1f, 0o17, 1_000, the sexagesimal 1:30) are refused: they are mistakes in a
    robot's numbers far more often than meant."""
    if len(text) > MAX_NUMBER_TEXT:
        raise _Unreadable(f"a number written with {len(text)} characters; at most {MAX_NUMBER_TEXT}")
    if not _NUMBER.fullmatch(text):
        if text.lower().lstrip("+-") in (".nan", ".inf"):
            raise _Unreadable(f"{text} is not a finite number; every number of a spec is finite")
        if ":" in text:
            raise _Unreadable(f"{text} is a YAML 1.1 sexagesimal (base 60) number; write it in decimal, or quote text")
        raise _Unreadable(f"{text} is not a decimal number; write digits 0-9 with a point and an exponent if needed")
    if tag == _INT and not _DIGITS.fullmatch(text):  # (!!int 1.5)
        raise _Unreadable(f"{text} is not a whole number, which !!int asks for")
    if tag == _INT:  # (010 is ten, as in YAML 1.2, not YAML 1.1's octal eight)
        integer = int(text)
        if abs(integer) > _LARGEST:
            raise _Unreadable(f"{text} is beyond any double (about 1.8e308); not a finite number")
        return integer
    value = float(text)
    if not math.isfinite(value):
        raise _Unreadable(f"{text} is beyond any double (about 1.8e308); not a finite number")
    if value == 0.0 and any(digit in "123456789" for digit in text.lower().partition("e")[0]):
        raise _Unreadable(f"{text} is below any double (about 5e-324) and would read as 0")
    return value


_LARGEST = int(sys.float_info.max)
_DIGITS = re.compile(r"[-+]?[0-9]+")


def _scalar_value(event: Any) -> Any:
    value = event.value
    tag = event.tag
    if tag is None or tag == "!":
        tag = _RESOLVER.resolve(yaml.ScalarNode, value, event.implicit)
    if tag == _STR:
        # an unquoted, untagged number that YAML 1.1 leaves a string (1e-3) reads as a number, as in JSON and YAML 1.2
        return _number(value, _FLOAT) if event.tag is None and not event.style and _NUMBER.fullmatch(value) else value
    if tag in (_FLOAT, _INT):
        return _number(value, tag)
    if tag == _TIMESTAMP and (event.tag is not None or not event.style):  # (plain, or tagged !!timestamp)
        raise _Unreadable(f"{value} reads as a date in YAML; a spec has no dates: write a number, or quote text")
    if tag not in _PLAIN_TAGS:
        shown = tag.replace("tag:yaml.org,2002:", "!!")
        raise _Unreadable(f"YAML tag {shown} is not allowed in specs; write a plain value")
    if tag in ("tag:yaml.org,2002:timestamp", "tag:yaml.org,2002:binary", _MERGE):  # (<< only merges as a key)
        return value
    try:
        node = yaml.ScalarNode(tag, value, event.start_mark, event.end_mark, event.style)
        return SafeConstructor().construct_object(node)  # a fresh one: it remembers every node it built
    except (yaml.YAMLError, ValueError, KeyError) as exc:  # (!!int abc, !!bool foo, 0x_)
        kind = tag.rsplit(":", 1)[-1]
        problem = getattr(exc, "problem", None) or (f"{value!r} is not a {kind}" if isinstance(exc, KeyError) else exc)
        raise _Unreadable(f"cannot read this value: {problem}") from None


def _event_error(file: str, problem: str, event: Any) -> SpecError:
    line, column = _at(event)
    return SpecError(f"not valid YAML: {problem}", file=file, line=line, column=column)


# PyYAML's words for what is, in a spec, nearly always a line indented too far, too little, or a missing ': '
_INDENTATION_SIGNS = (
    "did not find expected key",
    "mapping values are not allowed",
    "could not find expected ':'",
    "expected <block end>",
    "did not find expected '-' indicator",
)


def _yaml_error(file: str, exc: yaml.YAMLError, text: str) -> SpecError:
    if isinstance(exc, yaml.reader.ReaderError):  # a character YAML does not allow: it has an offset, not a mark
        at = min(max(exc.position, 0), len(text))
        line, column = text.count("\n", 0, at) + 1, at - (text.rfind("\n", 0, at) + 1) + 1
        shown = f"U+{exc.character:04X}" if isinstance(exc.character, int) else repr(exc.character)
        message = f"not valid YAML: character {shown} is not allowed in YAML text; remove it"
        return SpecError(message, file=file, line=line, column=column)
    mark = getattr(exc, "problem_mark", None) or getattr(exc, "context_mark", None)
    problem = getattr(exc, "problem", None) or str(exc)
    if mark is not None and 0 <= mark.index < len(text) and text[mark.index] == "\t":
        problem += " (a tab: YAML indents with spaces only)"
    elif any(words in problem for words in _INDENTATION_SIGNS):
        problem += (
            "; check the indentation of this line and of the line above it: the keys of one mapping start in the "
            "same column, a key's contents further right (spaces only), and a key is followed by ': '"
        )
    return SpecError(
        f"not valid YAML: {problem}",
        file=file,
        line=mark.line + 1 if mark else None,
        column=mark.column + 1 if mark else None,
    )


def load_text(text: str, file: str = "<spec>") -> RawSpec:
    """Read spec text (already decoded). Raises :class:`SpecErrors` on anything unreadable."""
    with collector_paused():
        return _load_text(text, file)


def _load_text(text: str, file: str) -> RawSpec:
    try:
        builder = _read(text, file, track=False)
        if builder.errors:  # read it again, recording where everything is, to say where the errors are
            raise SpecErrors(_read(text, file, track=True).errors)
    except RecursionError:
        raise SpecErrors([SpecError("the spec is nested too deeply to read", file=file)]) from None
    return RawSpec(file=file, data=builder.data, text=text)


def _read(text: str, file: str, *, track: bool) -> _Builder:
    """Parse ``text`` into a builder holding the data, the errors and (``track``) the positions."""
    loader = None
    try:
        loader = _PARSER(text)  # (the pure-Python reader checks the characters here)
        loader.get_event()  # the stream's start
        event = loader.get_event()
        if type(event) is yaml.StreamEndEvent:
            message = "the spec is empty; start from `gen-robot new NAME`"
            raise SpecErrors([SpecError(message, file=file, line=1, column=1)])
        builder = _Builder(file, loader, track)
        builder.data = builder.build(loader.get_event(), ())
        loader.get_event()  # the document's end
        event = loader.get_event()
        if type(event) is not yaml.StreamEndEvent:
            raise SpecErrors([_event_error(file, "a spec is one YAML document, but another one starts here", event)])
    except yaml.YAMLError as exc:
        raise SpecErrors([_yaml_error(file, exc, text)]) from None
    finally:
        if loader is not None:
            loader.dispose()
    return builder


def load_file(path: str | Path) -> RawSpec:
    """Read a spec file: UTF-8, at most 16 MiB. Raises :class:`SpecErrors` with a located message."""
    file = str(path)
    try:
        raw = read_input(path, MAX_SPEC_BYTES)
    except OSError as exc:
        raise SpecErrors([SpecError(f"cannot read the spec: {exc.strerror}", file=file)]) from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        column = exc.start - (raw.rfind(b"\n", 0, exc.start) + 1) + 1
        raise SpecErrors(
            [SpecError(f"the spec is not UTF-8 text (byte {raw[exc.start]:#04x})", file=file, line=line, column=column)]
        ) from None
    return load_text(text.removeprefix("\ufeff"), file)
