"""The load stage: YAML read safely into plain data with the position of every value and key; whatever cannot be read
is one located error."""

from __future__ import annotations

import re

import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st

from conftest import REPO
from xacrokit.errors import SpecErrors
from xacrokit.load import load_file, load_text


def test_load_keeps_positions_and_reads_exponents_as_numbers():
    raw = load_text("robot: r\nlinks:\n  a:\n    mass: 1e-3\n    name: '1e-3'\n", "s.yaml")
    assert raw.data == {"robot": "r", "links": {"a": {"mass": 1e-3, "name": "1e-3"}}}
    assert raw.positions[("links", "a", "mass")] == (4, 11)
    assert raw.key_positions[("links", "a")] == (3, 3)
    error = raw.error(("links", "a", "nothing", "deeper"), "x")
    assert (error.line, error.column, error.path) == (4, 5, "$.links.a.nothing.deeper")  # where a's mapping starts


@pytest.mark.parametrize(
    ("text", "line", "words"),
    [
        ("a: 1\nb: 2\na: 3\n", 3, "duplicate key 'a' (first given on line 1)"),
        ("a: &x [1, 2]\nb: *x\n", 2, "aliases"),
        ("a: {<<: {b: 1}}\n", 1, "merge keys"),
        ("a: [1\n", 2, "not valid YAML"),
        ("a: 1\n---\nb: 2\n", 2, "not valid YAML"),
        ("", 1, "empty"),
        ("a: !!python/object:os.system x\n", 1, "YAML tag !!python/object:os.system is not allowed"),
        ("a: !custom [1]\n", 1, "YAML tag !custom is not allowed"),
        ("? [1, 2]\n: x\n", 1, "plain names"),
        ("a: &k b\n*k : 1\n", 2, "aliases (*name) are not supported in specs; write the key out (anchored on line 1)"),
        ("a: &k 1\nb: &k 2\n", 2, "duplicate anchor 'k' (first on line 1)"),
        ("a: [1, *nowhere]\n", 1, "undefined alias 'nowhere'"),
        ("a: 1\n...\n---\nb: 2\n", 3, "one YAML document"),
    ],
)
def test_unreadable_yaml_gives_one_located_error(text, line, words):
    with pytest.raises(SpecErrors) as caught:
        load_text(text, "s.yaml")
    (error,) = caught.value.errors
    assert error.file == "s.yaml" and error.line == line and words in error.message


def test_explicit_tags_and_merge_text_as_values():
    raw = load_text("a: !!str 3\nb: <<\nc: !!float 2\nd: 010\ne: yes\nf: ~\ng: '1e-3'\nh: 1e-3\n", "s.yaml")
    # 010 is ten (YAML 1.2, and what a robot's number means), not YAML 1.1's octal eight
    assert raw.data == {"a": "3", "b": "<<", "c": 2.0, "d": 10, "e": True, "f": None, "g": "1e-3", "h": 1e-3}
    assert [type(raw.data[key]) for key in "acd"] == [str, float, int]


_NAMES = st.from_regex(r"[a-z_][a-z0-9_]{0,8}", fullmatch=True)
_JSON_LIKE = st.recursive(
    st.none()
    | st.booleans()
    | st.integers(-(10**6), 10**6)
    | st.floats(allow_nan=False, allow_infinity=False, width=64)
    | st.text(st.characters(codec="utf-8", exclude_categories=("Cs", "Cc")), max_size=12).filter(
        lambda text: not re.fullmatch(r"\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?\s*", text)
    ),  # (text that reads as a number is a number: the documented rule)
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(_NAMES, inner, max_size=4),
    max_leaves=12,
)


def _paths(data, path=()):
    yield path
    if isinstance(data, dict):
        for key, value in data.items():
            yield from _paths(value, (*path, key))
    elif isinstance(data, list):
        for index, value in enumerate(data):
            yield from _paths(value, (*path, index))


@given(st.dictionaries(_NAMES, _JSON_LIKE, min_size=1, max_size=5), st.sampled_from([None, True, False]))
def test_any_dumped_document_loads_back_with_every_position(data, flow):
    text = yaml.safe_dump(data, default_flow_style=flow, allow_unicode=True, width=60, sort_keys=False)
    raw = load_text(text, "s.yaml")
    assert raw.data == data and repr(raw.data) == repr(data)  # same types too (1 is not 1.0, -0.0 keeps its sign)
    lines = text.splitlines()
    for path in _paths(data):
        assert path in raw.positions, path
        if path and isinstance(path[-1], str):
            line, column = raw.key_positions[path]
            assert lines[line - 1][column - 1 :].lstrip("'\"").startswith(path[-1]), (path, line, column)


def test_alias_bomb_is_rejected_without_expanding(tmp_path):
    lines = ["a0: &a0 [x, x, x, x, x, x, x, x, x, x]"]
    lines += [
        f"a{i}: &a{i} [*a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}]"
        for i in range(1, 12)
    ]
    with pytest.raises(SpecErrors, match="aliases"):
        load_text("\n".join(lines) + "\n")


def test_non_utf8_and_missing_files_are_located(tmp_path):
    bad = tmp_path / "latin1.yaml"
    bad.write_bytes("robot: r\nlinks: {caf\xe9: {}}\n".encode("latin-1"))
    with pytest.raises(SpecErrors) as caught:
        load_file(bad)
    (error,) = caught.value.errors
    assert (error.line, error.column) == (2, 12) and "not UTF-8" in error.message
    with pytest.raises(SpecErrors, match="cannot read the spec"):
        load_file(tmp_path / "missing.yaml")


def test_positions_are_read_only_when_something_needs_locating():
    from xacrokit.resolve import resolve
    from xacrokit.validate import validate

    text = (REPO / "examples" / "robots" / "two_dof_arm.yaml").read_text(encoding="utf-8")
    raw = load_text(text, "two_dof_arm.yaml")
    resolve(validate(raw))
    assert "_position_tables" not in vars(raw)  # a valid spec never pays for recording where everything is
    line = next(number for number, row in enumerate(text.splitlines(), 1) if row.startswith("robot:"))
    assert raw.key_positions[("robot",)] == (line, 1)
    assert raw.positions[("robot",)] == (line, text.splitlines()[line - 1].index("two_dof_arm") + 1)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        # an anchor inside a rejected block is still an anchor: the alias is refused as an alias, not as "undefined"
        ("robot: r\nlinks: !custom {base: &m {mass: 1}}\njoints: *m\n", [(2, "tag !custom"), (3, "aliases")]),
        ("? [&x 1]\n: 2\nb: *x\n", [(1, "plain names"), (3, "aliases")]),
        ("links:\n  base: {mass: !!int abc}\n", [(2, "abc is not a decimal number")]),
        ("x: !!bool foo\n", [(1, "cannot read this value: 'foo' is not a bool")]),
        ("x: 0x_\n", [(1, "0x_ is not a decimal number")]),
        ("[" * 600 + "]" * 600 + "\n", [(None, "nested too deeply")]),
    ],
)
def test_odd_yaml_gives_located_errors_not_tracebacks(text, expected):
    with pytest.raises(SpecErrors) as caught:
        load_text(text, "s.yaml")
    found = [(error.line, error.message) for error in caught.value.errors]
    assert len(found) == len(expected), found
    for (line, message), (want_line, words) in zip(found, expected, strict=True):
        assert line == want_line and words in message, found


def test_a_character_yaml_forbids_is_located_with_either_parser(monkeypatch):  # (PyYAML with or without libyaml)
    import xacrokit.load

    for parser in (yaml.SafeLoader, xacrokit.load._PARSER):
        monkeypatch.setattr(xacrokit.load, "_PARSER", parser)
        with pytest.raises(SpecErrors) as caught:
            load_text("robot: r\nx: \x07\n", "s.yaml")
        (error,) = caught.value.errors
        assert (error.line, error.column) == (2, 4) and "character U+0007 is not allowed" in error.message
