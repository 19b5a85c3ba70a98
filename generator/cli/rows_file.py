"""Rows of values read from a CSV or YAML file (``pose --configurations``; ``ik --targets`` may read its targets the
same way): each row with its line and its values as text, unparsed (a unit and all: ``30deg``), either named (a CSV
header's columns, a YAML mapping's keys) or positional (a CSV without a header, a YAML list of lists).

* CSV (``.csv``): a first row with no number in it is a header of names; otherwise every row is positional. Blank
  lines are skipped; a named row has one value per column.
* YAML (``.yaml``, ``.yml``): a list whose items are mappings (name: value) or lists (values in order), read by the
  spec loader's safe reader (no tags, aliases or duplicate keys).

UTF-8 only (a byte-order mark is skipped), at most :data:`MAX_ROWS` rows and :data:`MAX_BYTES` bytes; every problem
is a :class:`~xacrokit.errors.SpecError` that names the file, the line (and column where known) and what is wrong.
"""

from __future__ import annotations

import csv
import io
import re
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import SpecError
from ..load import RawSpec, load_text
from ..shared.input_files import read_input

MAX_ROWS = 100_000  # (a trajectory of 1,000 s at 100 Hz; beyond it, a file meant for another tool)
MAX_BYTES = 64 * 1024 * 1024
SUFFIXES = {".csv": "csv", ".yaml": "yaml", ".yml": "yaml"}
_NUMBER_START = re.compile(r"[+-]?\.?[0-9]")  # (a value: 0.5, -30deg, .5; a name starts otherwise)


@dataclass(frozen=True)
class Row:
    """One row: its line (1-based), its values as text, and their names (None: positional, in the reader's order).
    ``lines`` holds each value's own line where a row spans lines (a YAML block mapping); empty: all on ``line``.
    ``header_line``: where a CSV's names are (a name that is wrong is wrong there), else None."""

    line: int
    values: tuple[str, ...]
    names: tuple[str, ...] | None = None
    lines: tuple[int, ...] = ()
    header_line: int | None = None

    def named(self) -> dict[str, str] | None:
        """The values by name, or None for a positional row."""
        return None if self.names is None else dict(zip(self.names, self.values, strict=True))

    def line_of(self, index: int) -> int:
        """The line of the ``index``-th value."""
        return self.lines[index] if self.lines else self.line


def read_rows(path: str | Path) -> list[Row]:
    """The rows of the CSV or YAML file ``path`` (its suffix says which), in the file's order.

    Raises:
        SpecError: an unreadable file (missing, a folder, too large, not UTF-8), another suffix, no rows, more than
            :data:`MAX_ROWS`, or a row that is not one (located: file, line, the column or value named).
        SpecErrors: YAML that does not parse (located).
    """
    file = str(path)
    kind = SUFFIXES.get(Path(file).suffix.lower())
    if kind is None:
        raise SpecError("give a .csv, .yaml or .yml file (its suffix says how to read it)", file=file)
    text = _text(path, file)
    rows = _csv_rows(text, file) if kind == "csv" else _yaml_rows(text, file)
    if not rows:
        raise SpecError("no rows: give one row of values a line (CSV) or a list of them (YAML)", file=file)
    return rows


def _text(path: str | Path, file: str) -> str:
    try:
        raw = read_input(path, MAX_BYTES)
    except OSError as exc:
        raise SpecError(f"cannot read it: {exc.strerror or exc}", file=file) from None
    try:
        return raw.decode("utf-8").removeprefix("\ufeff")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        column = exc.start - (raw.rfind(b"\n", 0, exc.start) + 1) + 1
        message = f"not UTF-8 text (byte {raw[exc.start]:#04x}); save it as UTF-8"
        raise SpecError(message, file=file, line=line, column=column) from None


def _too_many(file: str, line: int) -> SpecError:
    return SpecError(f"more than {MAX_ROWS:,} rows; split the file", file=file, line=line)


def _csv_lines(text: str, file: str) -> Iterator[tuple[int, tuple[str, ...]]]:
    """Each non-blank CSV row with the line it starts on, its cells stripped."""
    reader = csv.reader(io.StringIO(text, newline=""), strict=True)
    start = 1
    try:
        for cells in reader:
            line, start = start, reader.line_num + 1
            if any(cell.strip() for cell in cells):
                yield line, tuple(cell.strip() for cell in cells)
    except csv.Error as exc:
        raise SpecError(f"not valid CSV: {exc}", file=file, line=reader.line_num) from None


def _csv_rows(text: str, file: str) -> list[Row]:
    rows: list[Row] = []
    header: tuple[str, ...] | None = None
    header_line = None
    for line, cells in _csv_lines(text, file):
        if header is None and not rows and not any(_NUMBER_START.match(cell) for cell in cells):
            header, header_line = _header(cells, file, line), line
            continue
        if len(rows) == MAX_ROWS:
            raise _too_many(file, line)
        if header is not None and len(cells) != len(header):
            values = f"{len(cells)} value{'s' if len(cells) != 1 else ''}"
            said = f"{values} for the header's {len(header)} columns ({', '.join(header)})"
            raise SpecError(said, file=file, line=line)
        for index, cell in enumerate(cells):
            if not cell:
                what = f"column {index + 1} ({header[index]})" if header is not None else f"value {index + 1}"
                raise SpecError(f"{what} is empty; give a value", file=file, line=line)
        rows.append(Row(line, cells, header, header_line=header_line))
    return rows


def _header(cells: tuple[str, ...], file: str, line: int) -> tuple[str, ...]:
    for index, name in enumerate(cells):
        if not name:
            raise SpecError(f"the header's column {index + 1} is empty; name each column", file=file, line=line)
        if name in cells[:index]:
            first = cells.index(name) + 1
            said = f"the header names {name!r} twice (columns {first} and {index + 1}); name each column once"
            raise SpecError(said, file=file, line=line)
    return cells


def _yaml_rows(text: str, file: str) -> list[Row]:
    if not any(line.strip() and not line.lstrip().startswith("#") for line in text.splitlines()):
        raise SpecError("no rows: give a list of rows (mappings name: value, or lists of values)", file=file)
    raw = load_text(text, file)
    if not isinstance(raw.data, list):
        raise raw.error((), "give a list of rows: mappings (name: value) or lists of values in order")
    if len(raw.data) > MAX_ROWS:
        line, _ = raw.locate((MAX_ROWS,))
        raise _too_many(file, line or 1)
    return [_yaml_row(raw, index, item) for index, item in enumerate(raw.data)]


def _yaml_row(raw: RawSpec, index: int, item: Any) -> Row:
    if isinstance(item, dict):
        keys = list(item)
        for key in keys:
            if not isinstance(key, str):
                raise raw.error((index, key), f"a name is {key!r}, not text; quote it", key=True)
        cells = [(key, _yaml_text(raw, (index, key), item[key])) for key in keys]
    elif isinstance(item, list):
        cells = [(position, _yaml_text(raw, (index, position), value)) for position, value in enumerate(item)]
    else:
        raise raw.error((index,), "a row is a mapping (name: value) or a list of values")
    if not cells:
        raise raw.error((index,), "an empty row; give its values")
    lines = tuple(raw.locate((index, key))[0] or 1 for key, _ in cells)
    names = tuple(str(key) for key, _ in cells) if isinstance(item, dict) else None
    return Row(raw.locate((index,))[0] or 1, tuple(text for _, text in cells), names, lines)


def _yaml_text(raw: RawSpec, path: tuple[int | str, ...], value: Any) -> str:
    """A YAML value as the text a command parses: a number as Python writes it back (shortest round trip)."""
    if isinstance(value, bool) or value is None or isinstance(value, list | dict):
        what = "not a value" if isinstance(value, list | dict) else "empty"
        what = f"{str(value).lower()}, not a number" if isinstance(value, bool) else what
        raise raw.error(path, f"{what}; give a number, with a unit or without (30deg, 0.1 m)")
    if isinstance(value, float):
        return repr(value)
    text = str(value).strip()
    if not text:
        raise raw.error(path, "empty; give a number, with a unit or without (30deg, 0.1 m)")
    return text
