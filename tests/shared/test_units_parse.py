"""The unit parser: quantities in the spec's unit syntax to SI floats, exactly; a clear refusal of anything else."""

from __future__ import annotations

import math
from fractions import Fraction

import pytest
from hypothesis import given
from hypothesis import strategies as st

from xacrokit.shared.units import UnitError, parse_quantity


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
        ("nan", "length", "'nan' is not a finite number"),
        ("-inf mm", "length", "'inf' is not a finite number"),
        ("Infinity", "angle", "'Infinity' is not a finite number"),
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
            ("lb", "mass"),
            ("oz", "mass"),
            ("kgf*cm", "torque"),
            ("N*cm", "torque"),
            ("kgf", "force"),
            ("mm/s", "linear_velocity"),
        ]
    ),
)
def test_metric_and_imperial_units_give_the_nearest_double(number, unit):
    """'9 mm' is 0.009, not 9 * 1e-3 = 0.009000000000000001: the number and the factor are exact decimals. The factors
    here are the definitions (NIST SP 811): the pound is 0.45359237 kg, the ounce a 16th of it, the kilogram-force
    9.80665 N (standard gravity)."""
    name, kind = unit
    factor = {
        "mm": "0.001",
        "cm": "0.01",
        "km": "1000",
        "in": "0.0254",
        "ft": "0.3048",
        "g": "0.001",
        "lb": "0.45359237",
        "oz": "0.028349523125",
        "kgf*cm": "0.0980665",
        "N*cm": "0.01",
        "kgf": "9.80665",
        "mm/s": "0.001",
    }.get(name, "1")
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


@pytest.mark.parametrize(
    ("text", "kind", "value"),
    [
        ("60 rpm", "angular_velocity", 2 * math.pi),  # a turn a second
        ("180 deg/s", "angular_velocity", math.pi),
        ("pi/2 rad/s", "angular_velocity", math.pi / 2),
        ("15 kgf*cm", "torque", 1.4709975),  # a hobby servo's datasheet torque
        ("1.5 N*m", "torque", 1.5),
        ("1.5 N * m", "torque", 1.5),
        ("(1 + 2) Nm", "torque", 3.0),
        ("2 kN", "force", 2000.0),
        ("250 mm/s", "linear_velocity", 0.25),
        ("2*pi", "angle", 2 * math.pi),  # (no unit: 'pi' is a number)
    ],
)
def test_datasheet_units_of_speed_and_effort(text, kind, value):
    assert parse_quantity(text, kind) == value


@pytest.mark.parametrize(
    ("text", "kind", "words"),
    [
        ("10 deg/s", "torque", "'10 deg/s' is an angular velocity, expected a torque (N*m, Nm, N*cm, N*mm, kgf*cm"),
        ("3 kg*m", "torque", "unknown unit 'kg*m' in '3 kg*m'; torque units: N*m, Nm"),
        ("N*m", "torque", "'N*m' has a unit but no number"),
        ("5 m", "force", "'5 m' is a length, expected a force (N, kN, kgf)"),
        ("5 kg", "length", "'5 kg' is a mass, expected a length (m, mm, cm, km, in, ft)"),
    ],
)
def test_a_refusal_names_the_accepted_units(text, kind, words):
    with pytest.raises(UnitError) as caught:
        parse_quantity(text, kind)
    assert words in str(caught.value)


def test_huge_exact_products_stay_cheap_and_are_not_finite():
    with pytest.raises(UnitError, match="not a finite number"):
        parse_quantity("*".join(["1e400"] * 25), "length")
    assert parse_quantity("*".join(["1e-400"] * 25), "length") == 0.0


def test_long_quantities_are_refused_and_long_numbers_read():
    """A quantity is at most 200 characters (that bounds the parser's recursion too); within them a number whose
    exponent is beyond any double is read as a float, not as a huge exact fraction."""
    assert parse_quantity("0.0" + "0" * 180 + "25 m", "length") == 2.5e-182
    assert parse_quantity("1" + "0" * 90 + "e-90", "length") == 1.0
    with pytest.raises(UnitError, match="not a finite number"):
        parse_quantity("1e" + "9" * 190, "length")
    for deep in ("(" * 3000 + "1" + ")" * 3000, "-" * 5000 + "1", "0.0" + "0" * 4400 + "25 m"):
        with pytest.raises(UnitError, match="at most 200"):
            parse_quantity(deep, "length")


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
    from xacrokit.shared.units import _parsed

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


@pytest.mark.parametrize(("value", "kind"), [("pi/2", "length"), ("2*pi", "mass"), ("0.1*pi", "length")])
def test_pi_belongs_to_angles(value, kind):
    with pytest.raises(UnitError, match=f"holds pi, which belongs to angles; a {kind} is written as"):
        parse_quantity(value, kind)
    assert parse_quantity(value, "angle") > 0
