"""What the validate tests share: a valid spec using every section, one change to it, and the located errors of a
changed one. (A module of its own, not a conftest: tests/conftest.py is the one every folder imports as conftest.)"""

from __future__ import annotations

import copy

import pytest
import yaml

from xacrokit.errors import SpecError, SpecErrors
from xacrokit.load import load_text
from xacrokit.validate import validate

BASE = {
    "robot": "r",
    "materials": {"gray": [0.5, 0.5, 0.5, 1.0]},
    "links": {
        "base_link": {"shape": {"box": {"size": [0.4, 0.3, 0.1]}}, "mass": 2.0, "material": "gray"},
        "arm": {"shape": {"cylinder": {"radius": 0.05, "length": 0.3}}, "origin": {"xyz": [0, 0, 0.15]}, "mass": 1.0},
    },
    "joints": {
        "shoulder": {
            "type": "revolute",
            "parent": "base_link",
            "child": "arm",
            "axis": [0, 1, 0],
            "limit": {"lower": -1.0, "upper": 1.0, "effort": 5.0, "velocity": 1.0},
        },
    },
    "arms": {
        "dh": {
            "parent": "base_link",
            "joints": [
                {
                    "name": "j1",
                    "link": "l1",
                    "a": 0.1,
                    "d": 0.1,
                    "alpha": "pi/2",
                    "mass": 0.5,
                    "limit": {"lower": -1.0, "upper": 1.0, "effort": 5.0, "velocity": 1.0},
                }
            ],
        }
    },
    "wheels": {"left_wheel": {"parent": "base_link", "radius": 0.05, "width": 0.02, "mass": 0.2}},
    "frames": {"camera_link": {"parent": "base_link", "origin": {"xyz": [0.2, 0, 0.1]}}},
}


def errors_of(data) -> list[SpecError]:
    """The errors validate reports for ``data``, each checked to be located and printed with its place."""
    text = yaml.safe_dump(data, sort_keys=False)
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(text, "spec.yaml"))
    for error in caught.value.errors:
        assert error.file == "spec.yaml" and error.line is not None and error.column is not None
        assert str(error).startswith(f"spec.yaml:{error.line}:{error.column}: {error.path}: ")
    return caught.value.errors


def mutated(path: str, value=None, *, delete: bool = False):
    """BASE with the value at the dotted ``path`` replaced (or deleted)."""
    data = copy.deepcopy(BASE)
    *parents, last = [int(p) if p.isdigit() else p for p in path.split(".")]
    holder = data
    for part in parents:
        holder = holder[part]
    if delete:
        del holder[last]
    else:
        holder[last] = value
    return data


def case_ids(cases: list[tuple]) -> list[str]:
    return [c[0] + ":" + str(c[1])[:20] for c in cases]


def assert_mistake_located(change: str, value, path: str, words: str) -> None:
    """BASE with one change (value "DELETE" deletes) gives an error at ``path`` whose message holds ``words``."""
    data = mutated(change, delete=True) if value == "DELETE" else mutated(change, value)
    errors = errors_of(data)
    matching = [e for e in errors if e.path == path and words in e.message]
    assert matching, "\n".join(str(e) for e in errors)
