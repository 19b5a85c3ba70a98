"""A small safe parser for quantities written in specs: ``0.3``, ``"150 mm"``, ``"90 deg"``, ``"pi/2"``, ``"-2*pi"``.

Grammar (no ``eval``; nothing but these tokens is accepted)::

    quantity := expr [unit]
    expr     := term (('+' | '-') term)*
    term     := factor (('*' | '/') factor)*
    factor   := ('+' | '-') factor | NUMBER | 'pi' | '(' expr ')'

The unit must belong to the field's kind; a bare number is already in SI (m, rad, kg, rad/s, m/s, N*m, N). A unit
written with ``*`` or ``/`` (``deg/s``, ``N*m``, ``kgf*cm``) ends the text and is read as one unit, not as arithmetic.

Numbers and the metric and imperial factors are exact decimals, so the arithmetic is exact until ``pi`` or an angle
unit enters: ``"9 mm"`` is the double nearest 0.009 (``9 * 1e-3`` in floats would be 0.009000000000000001), and
``"1.5 in"`` the double nearest 0.0381.
"""

from __future__ import annotations

import math
import re
from decimal import MAX_EMAX, MIN_EMIN, Context, Decimal
from fractions import Fraction
from typing import Literal

Kind = Literal[
    "length",
    "angle",
    "mass",
    "number",
    "angular_velocity",
    "linear_velocity",
    "torque",
    "force",
    "density",
    "acceleration",
    "angular_acceleration",
    "time",
]
Value = Fraction | float  # exact while no pi is involved
STANDARD_GRAVITY = 9.80665  # m/s^2, the standard acceleration of gravity (CGPM 1901): sizing's, MJCF's, a drive's grip

# A decimal literal as specs (JSON, YAML 1.2) and URDF files write one: sign, digits, point, exponent.
UNSIGNED_NUMBER = r"(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?"  # (ASCII digits only: float() reads others too)
NUMBER = r"[-+]?" + UNSIGNED_NUMBER

UNITS: dict[str, dict[str, Value]] = {
    "length": {
        "m": Fraction(1),
        "mm": Fraction(1, 1000),
        "cm": Fraction(1, 100),
        "km": Fraction(1000),
        "in": Fraction("0.0254"),
        "ft": Fraction("0.3048"),
    },
    "angle": {"rad": Fraction(1), "deg": math.pi / 180.0, "degree": math.pi / 180.0, "degrees": math.pi / 180.0},
    "mass": {
        "kg": Fraction(1),
        "g": Fraction(1, 1000),
        "lb": Fraction("0.45359237"),  # the international avoirdupois pound (1959), exactly
        "oz": Fraction("0.45359237") / 16,
    },
    "number": {},
    # a joint's velocity limit: angular for revolute and continuous joints, linear for prismatic ones
    "angular_velocity": {"rad/s": Fraction(1), "deg/s": math.pi / 180.0, "rpm": math.pi / 30.0},
    "linear_velocity": {"m/s": Fraction(1), "mm/s": Fraction(1, 1000), "cm/s": Fraction(1, 100)},
    # a joint's effort limit: torque for revolute and continuous joints, force for prismatic ones; kgf is the
    # standard gravity's 9.80665 N (hobby servos give their torque in kgf*cm)
    "torque": {
        "N*m": Fraction(1),
        "Nm": Fraction(1),
        "N*cm": Fraction(1, 100),
        "N*mm": Fraction(1, 1000),
        "kgf*cm": Fraction("9.80665") / 100,
        "kgf*m": Fraction("9.80665"),
    },
    "force": {"N": Fraction(1), "kN": Fraction(1000), "kgf": Fraction("9.80665")},
    "density": {"kg/m3": Fraction(1), "g/cm3": Fraction(1000), "g/cc": Fraction(1000), "kg/L": Fraction(1000)},
    "acceleration": {"m/s2": Fraction(1), "m/s/s": Fraction(1)},  # (a sizing file's gravity, a prismatic joint's)
    "angular_acceleration": {  # (a sizing file's acceleration limit of a revolute joint)
        "rad/s2": Fraction(1),
        "rad/s/s": Fraction(1),
        "deg/s2": math.pi / 180.0,
        "deg/s/s": math.pi / 180.0,
    },
    "time": {"s": Fraction(1), "ms": Fraction(1, 1000), "min": Fraction(60)},  # (a motion's duration)
}
_EXACT_EXPONENT = 400  # beyond 1e±400 a number is no double anyway: read it as a float (inf or 0), not as a huge int

_TOKEN = re.compile(rf"\s*(?:(?P<number>{UNSIGNED_NUMBER})|(?P<word>[A-Za-z_]+)|(?P<op>[-+*/()]))")


class UnitError(ValueError):
    """A quantity that does not parse, has a unit of the wrong kind, or is not finite. The message says which."""


def _tokens(text: str) -> list[tuple[str, str]]:
    tokens: list[tuple[str, str]] = []
    position = 0
    text = text.rstrip()
    while position < len(text):
        match = _TOKEN.match(text, position)
        if not match or match.end() == position:
            raise UnitError(f"unexpected {text[position:].strip()[:1]!r} in {text!r}")
        kind = match.lastgroup or ""
        tokens.append((kind, match.group(kind)))
        position = match.end()
    return tokens


class _Parser:
    def __init__(self, tokens: list[tuple[str, str]], source: str) -> None:
        self.tokens, self.source, self.at = tokens, source, 0

    def peek(self) -> tuple[str, str] | None:
        return self.tokens[self.at] if self.at < len(self.tokens) else None

    def take(self) -> tuple[str, str]:
        token = self.peek()
        if token is None:
            raise UnitError(f"{self.source!r} ends too early")
        self.at += 1
        return token

    def expr(self) -> Value:
        value = self.term()
        while (token := self.peek()) and token[1] in "+-" and token[0] == "op":
            self.take()
            value = value + self.term() if token[1] == "+" else value - self.term()
        return value

    def term(self) -> Value:
        value = self.factor()
        while (token := self.peek()) and token[0] == "op" and token[1] in "*/":
            self.take()
            right = self.factor()
            if token[1] == "/" and right == 0:
                raise UnitError(f"division by zero in {self.source!r}")
            value = _bounded(value * right if token[1] == "*" else value / right)
        return value

    def factor(self) -> Value:
        kind, text = self.take()
        if kind == "op" and text in "+-":
            return self.factor() if text == "+" else -self.factor()
        if kind == "number":
            return _number(text)
        if kind == "word" and text == "pi":
            return math.pi
        if kind == "op" and text == "(":
            value = self.expr()
            if self.take() != ("op", ")"):
                raise UnitError(f"missing ')' in {self.source!r}")
            return value
        if kind == "word" and text.lower() in _NOT_FINITE:  # (what float() reads: said as 1e999 is)
            where = f" (in {self.source!r})" if self.source.strip() != text else ""
            raise UnitError(f"{text!r} is not a finite number{where}")
        raise UnitError(f"unexpected {text!r} in {self.source!r}")


_NOT_FINITE = ("nan", "inf", "infinity")


def _number(text: str) -> Value:
    """A NUMBER token, exactly (a decimal is a fraction), unless its exponent puts it beyond any double."""
    mantissa, _, exponent = text.lower().partition("e")
    try:
        if exponent and abs(int(exponent)) > _EXACT_EXPONENT:
            return float(text)
        return Fraction(text)
    except ValueError:  # thousands of digits (Python's limit on int conversion): a float reads any length
        return float(text)


def _bounded(value: Value) -> Value:
    """``value``, as a float once an exact fraction outgrows any double (so that ``1e400*1e400*...`` stays cheap)."""
    if isinstance(value, Fraction) and max(value.numerator.bit_length(), value.denominator.bit_length()) > 4096:
        try:
            return float(value)
        except OverflowError:
            return math.copysign(math.inf, value)
    return value


# units written with '*' or '/' between words ('deg/s', 'N*m'): matched at the end of the text before the parser
# runs (which would read 'deg / s' as a division)
_COMPOUND_UNITS = {unit for table in UNITS.values() for unit in table if "*" in unit or "/" in unit}
_COMPOUND = re.compile(
    r"(?P<unit>(?<![A-Za-z_])(?!pi\b)[A-Za-z_][A-Za-z0-9_]*(?:\s*[*/]\s*[A-Za-z_][A-Za-z0-9_]*)+)\s*$"
)  # (a whole word first, not pi: '2*pi*rad/s' ends with the unit 'rad/s')


def _expected(kind: str) -> str:
    """'a torque (N*m, Nm, ... or a plain number in N*m)': what the field takes, with its units."""
    return f"{_article(kind)} {_said(kind)} ({_unit_list(kind)})"


def _said(kind: str) -> str:
    """A kind as a message says it: 'angular velocity', not 'angular_velocity'."""
    return kind.replace("_", " ")


def _unit_kind(word: str) -> str | None:
    return next((kind for kind, table in UNITS.items() if word in table), None)


# The common case, one number and maybe a unit ("150 mm", "0.3", "90 deg"), without the parser; decimal arithmetic
# (exact for these products) gives the same doubles as the parser's fractions, faster.
_SIMPLE = re.compile(rf"\s*({NUMBER})\s*([A-Za-z_]*)\s*")
_DECIMAL_FACTORS = {
    kind: {unit: Decimal(Fraction(f).numerator) / Decimal(Fraction(f).denominator) for unit, f in table.items()}
    for kind, table in UNITS.items()
    if kind in ("length", "mass")
}
_EXACT = Context(
    prec=60, Emax=MAX_EMAX, Emin=MIN_EMIN
)  # more digits than any spec number times a factor has: the product is exact


def plain_number(text: str) -> float | None:
    """``text`` as a float when it is a bare number (``'90'``), else None (a unit or ``pi`` says what it is)."""
    simple = _SIMPLE.fullmatch(text)
    return float(simple[1]) if simple and not simple[2] else None


def _simple(number: str, unit: str, kind: Kind, value: str) -> float:
    """``number`` (and ``unit``) as the parser would read it, for the one-number case."""
    if not unit:
        return float(number)  # (correctly rounded: what the parser's fraction gives)
    if kind == "angle" and unit in UNITS["angle"]:
        return float(number) * float(UNITS["angle"][unit])  # (as the parser: the number, then a float factor)
    factor = _DECIMAL_FACTORS.get(kind, {}).get(unit)
    if factor is None:  # pi, or a unit that is unknown or of another kind: the parser says which
        return _parsed(value, kind)
    try:
        return float(_EXACT.multiply(Decimal(number), factor))
    except (ArithmeticError, ValueError):  # (an exponent beyond even decimal's range)
        return _parsed(value, kind)


MAX_QUANTITY_TEXT = 200  # characters: '-2*pi + (150 mm)' needs a few dozen


def parse_quantity(value: object, kind: Kind) -> float:
    """Turn a spec value into a finite SI float.

    Args:
        value: a number, or a string such as ``"150 mm"``, ``"90 deg"``, ``"pi/2"``, ``"1e-3"``.
        kind: what the field measures; a unit of another kind is an error.

    Raises:
        UnitError: the value is not a number or a well-formed expression, the unit is unknown or of another kind, or
            the result is not finite.
    """
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise UnitError(f"expected a number or a string such as {_example(kind)!r}, got {value!r}")
    if isinstance(value, str):
        if len(value) > MAX_QUANTITY_TEXT:  # (also bounds the parser's recursion: one level per sign or parenthesis)
            raise UnitError(f"a quantity written with {len(value)} characters; at most {MAX_QUANTITY_TEXT}")
        simple = _SIMPLE.fullmatch(value)
        number = _simple(simple[1], simple[2], kind, value) if simple else _parsed(value, kind)
    else:
        number = float(value)
    if not math.isfinite(number):
        raise UnitError(f"{value!r} is not a finite number")
    return number


def _parsed(value: str, kind: Kind) -> float:
    """A quantity string through the parser: the exact value as a float."""
    tokens = _tokens(value)
    if not tokens:
        raise UnitError(f"expected a quantity such as {_example(kind)!r}, got an empty string")
    if (
        kind in ("length", "mass") and ("word", "pi") in tokens
    ):  # (radius: pi/2 is an angle written where a length goes)
        raise UnitError(f"{value!r} holds pi, which belongs to angles; a {kind} is written as {_example(kind)!r}")
    scale: Value = Fraction(1)
    compound = _COMPOUND.search(value)
    if compound:  # 'deg/s', 'N*m' end the text
        unit = re.sub(r"\s+", "", compound["unit"])
        unit_kind = _unit_kind(unit)
        if unit_kind is None:
            raise UnitError(f"unknown unit {unit!r} in {value!r}; {_said(kind)} units: {_unit_list(kind)}")
        if unit_kind != kind:
            raise UnitError(f"{value!r} is {_article(unit_kind)} {_said(unit_kind)}, expected {_expected(kind)}")
        tokens = _tokens(value[: compound.start("unit")])
        scale = UNITS[kind][unit]
    elif len(tokens) > 1 and tokens[-1][0] == "word" and tokens[-1][1] != "pi":
        unit = tokens.pop()[1]
        unit_kind = _unit_kind(unit)
        if unit_kind is None:
            raise UnitError(f"unknown unit {unit!r} in {value!r}; {_said(kind)} units: {_unit_list(kind)}")
        if unit_kind != kind:
            raise UnitError(f"{value!r} is {_article(unit_kind)} {_said(unit_kind)}, expected {_expected(kind)}")
        scale = UNITS[kind][unit]
    if not tokens:
        raise UnitError(f"{value!r} has a unit but no number; write it as {_example(kind)!r}")
    parser = _Parser(tokens, value)
    try:
        exact = parser.expr()
        if parser.peek() is not None:
            raise UnitError(f"unexpected {parser.peek()[1]!r} in {value!r}")  # type: ignore[index]
        return float(exact * scale)
    except OverflowError:  # (a fraction beyond any double met a float, or became one)
        raise UnitError(f"{value!r} is not a finite number") from None


def _article(kind: str) -> str:
    return "an" if kind[0] in "aeiou" else "a"


def _unit_list(kind: str) -> str:
    return ", ".join(UNITS[kind]) or "none (a plain number)"


def _example(kind: str) -> str:
    return {
        "length": "150 mm",
        "angle": "90 deg",
        "mass": "500 g",
        "number": "1.5",
        "angular_velocity": "60 rpm",
        "linear_velocity": "250 mm/s",
        "torque": "15 kgf*cm",
        "force": "200 N",
        "density": "2.7 g/cm3",
        "acceleration": "9.81 m/s2",
        "angular_acceleration": "180 deg/s2",
        "time": "500 ms",
    }[kind]


# The largest magnitude of each kind of quantity xacrokit takes, in specs and in sizing's payloads and loads: far
# beyond any robot (the heaviest industrial payloads are about 2.3 t, the longest arms a few metres), and small enough
# that no inertia, torque or power computed from them overflows a double (a box of 1e200 m wrote inf into the URDF;
# a payload of 1e308 kg gave inf - inf = NaN torques).
INPUT_BOUNDS = {"mass": 1e6, "length": 1e4, "force": 1e9, "torque": 1e9}  # kg, m, N, N*m
MAX_MOMENT = INPUT_BOUNDS["mass"] * INPUT_BOUNDS["length"] ** 2  # kg m^2: the largest mass at the largest distance
_BOUND_UNITS = {"mass": "kg", "length": "m", "force": "N", "torque": "N*m"}


def bound_problem(kind: str, value: float) -> str | None:
    """Why ``value`` (SI) is beyond what xacrokit takes for a quantity of ``kind``, or None."""
    bound = INPUT_BOUNDS.get(kind)
    if bound is None or not abs(value) > bound:
        return None
    unit = _BOUND_UNITS[kind]
    return f"{value:g} {unit} is beyond what xacrokit takes (at most {bound:g} {unit}; a value in the wrong unit?)"
