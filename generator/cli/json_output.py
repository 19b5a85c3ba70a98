"""What every ``--json`` (and ``--format json``/``sarif``) of gen-robot prints: JSON as RFC 8259 has it, which holds
no infinity and no NaN. Python's json writes them as ``Infinity`` and ``NaN`` by default, which strict readers (jq,
JavaScript's JSON.parse, Go, Rust's serde) refuse; a result that holds one is an error instead (exit 2, nothing
printed), said with its place in the result. The commands refuse what overflows before, naming the input; this is
the one place that makes sure.
"""

from __future__ import annotations

import json
import math
import sys
from collections.abc import Mapping

from ..errors import XacrokitError


def print_json(data: object) -> None:
    """Print ``data`` as indented JSON and a newline.

    Raises:
        XacrokitError: a number in it that is not finite (:func:`require_finite`); nothing is printed then.
    """
    require_finite(data, "the result")
    sys.stdout.write(json.dumps(data, indent=2, allow_nan=False) + "\n")


def require_finite(data: object, what: str) -> None:
    """Refuse ``data`` (nested dicts, lists and numbers) holding a number that is not finite: a command prints no
    inf or NaN as an answer, in JSON or in text.

    Raises:
        XacrokitError: ``WHAT overflows: $.torques.j1 is inf, beyond what a float holds``, the first such place.
    """
    found = nonfinite_place(data)
    if found is not None:
        place, value = found
        raise XacrokitError(
            f"{what} overflows: {place} is {value!r}, beyond what a float holds (JSON has no number for it); "
            "nothing printed"
        )


def nonfinite_place(data: object, place: str = "$") -> tuple[str, float] | None:
    """The JSON path and value of the first number in ``data`` that is not finite (depth first), or None."""
    stack: list[tuple[str, object]] = [(place, data)]
    while stack:
        where, value = stack.pop()
        if isinstance(value, float) and not math.isfinite(value):
            return where, value
        if isinstance(value, Mapping):
            stack += reversed([(f"{where}.{key}", item) for key, item in value.items()])
        elif isinstance(value, list | tuple):
            stack += reversed([(f"{where}[{index}]", item) for index, item in enumerate(value)])
    return None
