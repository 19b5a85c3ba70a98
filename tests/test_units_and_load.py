"""The unit parser and the located YAML loader."""

from __future__ import annotations

import math
import re
from fractions import Fraction

import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st

from conftest import REPO
from xacrokit.errors import SpecErrors
from xacrokit.load import load_file, load_text
from xacrokit.units import UnitError, parse_quantity


@pytest.mark.parametrize(
    ("text", "kind", "value"),
    [
        (0.3, "length", 0.3),
        (2, "length", 2.0),
        ("150 mm", "length", 0.15),
        ("15 cm", "length", 0.15),
        ("1e-3", "length", 1e-3),
        ("2 in", "length", 0.0508),
        ("0.1*2", "length", 0.2),
        ("-0.5 m", "length", -0.5),
        ("90 deg", "angle", math.pi / 2),
        ("pi/2", "angle", math.pi / 2),
        ("-2*pi", "angle", -2 * math.pi),
        ("pi", "angle", math.pi),
        ("(1 + 1) * pi / 4 rad", "angle", math.pi / 2),
        ("45deg", "angle", math.pi / 4),
        ("500 g", "mass", 0.5),
        ("1.5 kg", "mass", 1.5),
        ("-pi", "angle", -math.pi),
    ],
)
def test_quantities_parse_to_si(text, kind, value):
    assert parse_quantity(text, kind) == pytest.approx(value, rel=1e-15)


@pytest.mark.parametrize(
    ("text", "kind", "words"),
    [
        ("150 mm", "angle", "is a length, expected an angle"),
        ("90 deg", "length", "is an angle, expected a length"),
        ("3 parsecs", "length", "unknown unit 'parsecs'"),
        ("__import__('os')", "length", "unexpected"),
        ("1/0", "length", "division by zero"),
        ("2 pi", "angle", "unexpected 'pi'"),
        ("", "length", "empty"),
        ("(1", "length", "ends too early"),
        ("1e999", "length", "not a finite number"),
        (True, "length", "expected"),
        ([1], "length", "expected a number"),
        ("${x}", "length", "unexpected '$'"),
        ("1 kg", "length", "is a mass"),
        # refused on the one-number fast path too: it leaves them to the parser
        ("1e999999999999999999999 mm", "length", "not a finite number"),
        ("5 g", "length", "is a mass, expected a length"),
    ],
)
def test_bad_quantities_say_what_is_wrong(text, kind, words):
    with pytest.raises(UnitError, match=None) as caught:
        parse_quantity(text, kind)
    assert words in str(caught.value)


@given(st.floats(allow_nan=False, allow_infinity=False, min_value=-1e9, max_value=1e9))
def test_numbers_pass_through_exactly_and_as_text(value):
    assert parse_quantity(value, "length") == value
    assert parse_quantity(repr(value), "length") == value
    assert parse_quantity(f"{value!r} mm", "length") == float(Fraction(repr(value)) / 1000)


@given(
    st.decimals(min_value=-(10**6), max_value=10**6, places=4, allow_nan=False, allow_infinity=False),
    st.sampled_from(
        [
            ("mm", "length"),
            ("cm", "length"),
            ("km", "length"),
            ("in", "length"),
            ("ft", "length"),
            ("g", "mass"),
            ("m", "length"),
            ("kg", "mass"),
        ]
    ),
)
def test_metric_and_imperial_units_give_the_nearest_double(number, unit):
    """'9 mm' is 0.009, not 9 * 1e-3 = 0.009000000000000001: the number and the factor are exact decimals."""
    name, kind = unit
    factor = {"mm": "0.001", "cm": "0.01", "km": "1000", "in": "0.0254", "ft": "0.3048", "g": "0.001"}.get(name, "1")
    assert parse_quantity(f"{number} {name}", kind) == float(Fraction(number) * Fraction(factor))


@pytest.mark.parametrize(
    ("text", "kind", "value"),
    [
        ("9 mm", "length", 0.009),
        ("350 g", "mass", 0.35),
        ("1.5 in", "length", 0.0381),
        ("3 ft", "length", 0.9144),
        ("0.1 + 0.2", "length", 0.3),
        ("1/3", "length", 1 / 3),
        ("1e-400 * 1e400", "length", 1.0),
    ],
)
def test_exact_arithmetic_cases(text, kind, value):
    assert parse_quantity(text, kind) == value  # exactly, not approximately


def test_huge_exact_products_stay_cheap_and_are_not_finite():
    with pytest.raises(UnitError, match="not a finite number"):
        parse_quantity("*".join(["1e400"] * 5000), "length")
    assert parse_quantity("*".join(["1e-400"] * 5000), "length") == 0.0


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
    assert raw.data == {"a": "3", "b": "<<", "c": 2.0, "d": 8, "e": True, "f": None, "g": "1e-3", "h": 1e-3}
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

    text = (REPO / "examples" / "two_dof_arm.yaml").read_text(encoding="utf-8")
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
        ("links:\n  base: {mass: !!int abc}\n", [(2, "cannot read this value: invalid literal for int()")]),
        ("x: !!bool foo\n", [(1, "cannot read this value: 'foo' is not a bool")]),
        ("x: 0x_\n", [(1, "cannot read this value")]),
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


def test_numbers_of_thousands_of_digits_are_read_not_a_traceback():
    """Python refuses to turn more than 4,300 digits into an int; such a number is read as a float instead."""
    assert parse_quantity("0.0" + "0" * 4400 + "25 m", "length") == 0.0
    assert parse_quantity("1" + "0" * 5000 + "e-5000", "length") == 1.0
    with pytest.raises(UnitError, match="not a finite number"):
        parse_quantity("1e" + "9" * 5000, "length")


@given(
    st.one_of(
        st.decimals(allow_nan=False, allow_infinity=False).map(str),
        st.from_regex(r"[-+]?(\d{1,30}\.?\d{0,30}|\.\d{1,30})([eE][-+]?\d{1,3})?", fullmatch=True),
    ),
    st.sampled_from(
        [
            ("", "length"),
            ("mm", "length"),
            ("cm", "length"),
            ("km", "length"),
            ("in", "length"),
            ("ft", "length"),
            ("m", "length"),
            ("g", "mass"),
            ("kg", "mass"),
            ("deg", "angle"),
            ("rad", "angle"),
            ("degrees", "angle"),
        ]
    ),
)
def test_the_one_number_fast_path_reads_what_the_parser_reads(number, unit):
    """'150 mm' skips the parser (decimal arithmetic instead of fractions): both must give the same double, or the
    same refusal."""
    from xacrokit.units import _parsed

    name, kind = unit
    text = f"{number} {name}".strip()
    try:
        expected = _parsed(text, kind)
    except UnitError:
        with pytest.raises(UnitError):
            parse_quantity(text, kind)
        return
    if not math.isfinite(expected):
        with pytest.raises(UnitError, match="not a finite number"):
            parse_quantity(text, kind)
    else:
        assert parse_quantity(text, kind) == expected
