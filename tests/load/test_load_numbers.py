"""One number reader for every number a spec holds: finite doubles written in ASCII decimal digits. What YAML 1.1 reads
otherwise (.nan, .inf, 1e400, dates, sexagesimal 1:30, 0x10, 1_000, huge integers) is a located error, never a value
written into a URDF; and an axis is refused before normalising it would divide by zero or overflow."""

from __future__ import annotations

import pytest
import yaml

from conftest import ROBOT_EXAMPLES, gen_robot
from xacrokit.errors import SpecErrors
from xacrokit.load import load_text

SPEC = next(p for p in ROBOT_EXAMPLES if p.stem == "two_dof_arm")


@pytest.mark.parametrize(
    ("text", "words"),
    [
        (".nan", ".nan is not a finite number"),
        ("-.inf", "-.inf is not a finite number"),
        (".Inf", ".Inf is not a finite number"),
        ("1e400", "1e400 is beyond any double"),
        ("-1e999", "-1e999 is beyond any double"),
        ("2001-12-14", "2001-12-14 reads as a date"),
        ("1:30", "1:30 is a YAML 1.1 sexagesimal"),
        ("1:30.5", "1:30.5 is a YAML 1.1 sexagesimal"),
        ("0x10", "0x10 is not a decimal number"),
        ("1_000", "1_000 is not a decimal number"),
        ("9" * 400, "is beyond any double"),
        ("9" * 5000, "a number written with 5000 characters; at most 400"),
        ("!!float abc", "abc is not a decimal number"),
    ],
)
def test_numbers_yaml_reads_otherwise_are_located_errors(text, words):
    with pytest.raises(SpecErrors) as caught:
        load_text(f"robot: r\nlinks:\n  base: {{mass: {text}}}\n", "s.yaml")
    (error,) = caught.value.errors
    assert (error.line, error.column, error.path) == (3, 16, "$.links.base.mass")
    assert words in error.message, error.message


@pytest.mark.parametrize(
    ("text", "value"), [("1e-3", 1e-3), ("010", 10), ("-0", 0), ("2.5E2", 250.0), ("'1e400'", None)]
)
def test_decimal_numbers_read_as_numbers(text, value):
    data = load_text(f"x: {text}\n", "s.yaml").data
    assert data["x"] == (value if value is not None else "1e400")  # (quoted: text, for the unit parser to judge)


@pytest.mark.parametrize(
    ("replace", "words"),
    [
        (("velocity: 1.0}", "velocity: .nan}"), ".nan is not a finite number"),
        (("mass: 1.0", 'mass: "1e400 g"'), "'1e400 g' is not a finite number"),
        (("mass: 1.0", 'mass: "٣"'), "unexpected '٣'"),  # (float() reads Arabic-Indic digits; specs do not)
        (("mass: 1.0", 'mass: "' + "(" * 2000 + "1" + ")" * 2000 + '"'), "at most 200"),
        (("axis: [0, 1, 0]", "axis: [0, 1e-320, 0]"), "has length 1e-320"),
        (("axis: [0, 1, 0]", "axis: [1e308, 1e308, 0]"), "has length 1.41e+308"),
    ],
)
def test_generate_refuses_them_with_exit_2_and_writes_nothing(tmp_path, replace, words):
    spec = tmp_path / "spec.yaml"
    spec.write_text(SPEC.read_text(encoding="utf-8").replace(*replace, 1), encoding="utf-8")
    assert replace[1] in spec.read_text(encoding="utf-8")
    result = gen_robot(spec, "-o", tmp_path / "out")
    assert result.returncode == 2 and words in result.stderr, result.stderr
    assert "Traceback" not in result.stderr and not (tmp_path / "out").exists()


def test_a_valid_spec_still_loads_every_number_it_had():
    data = load_text(SPEC.read_text(encoding="utf-8"), "s.yaml").data
    assert data == yaml.safe_load(SPEC.read_text(encoding="utf-8"))


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("!!timestamp 2001-12-14", "reads as a date"),  # (an explicit tag once skipped the date check: 1975 kg)
        ("!!int 1.5", "1.5 is not a whole number"),
        ("1e-400", "1e-400 is below any double"),
    ],
)
def test_tagged_dates_fractional_ints_and_underflow_are_errors(text, words):
    with pytest.raises(SpecErrors, match=words):
        load_text(f"x: {text}\n", "s.yaml")
    assert load_text("x: 0e5\n", "s.yaml").data == {"x": 0.0}  # (a zero written as one is a zero)
