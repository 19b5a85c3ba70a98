"""Every class of bad input (xacrokit.testing.hostile, re-exported by xacrokit.testing) gives its documented outcome
through the command line: exit 2 with a message (located for specs: the line of the bad value), nothing written, never
the internal-error exit 70 nor a traceback. The finite classes are tried in full; docs/development.md (Bad inputs) has
the table and the counts."""

from __future__ import annotations

import contextlib
import io
import re
import shutil
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings

import xacrokit.cli.app
from conftest import assert_refused
from xacrokit.testing import (
    HOSTILE_NUMBERS,
    HOSTILE_PATHS,
    hostile_spec_texts,
    make_hostile_path,
    spec_text,
)
from xacrokit.testing.hostile import (
    ARGUMENT_CASES,
    NUMBER_FIELDS,
    SPEC_TEMPLATE,
    STRUCTURE_CASES,
    XACRO_CASES,
    XACRO_HEAD,
)


def run(argv: list[str]) -> tuple[int, str]:
    """gen-robot in this process: (exit code, stderr)."""
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            code = xacrokit.cli.app.main([str(word) for word in argv])
        except SystemExit as exc:  # (argparse's usage errors)
            code = exc.code if isinstance(exc.code, int) else 2
    return code, err.getvalue()


# what each refusal must say (its reason, in the message's own words)
STRUCTURE_WORDS = {
    "tab_indentation": "a tab: YAML indents with spaces only",
    "duplicate_key": "duplicate key 'arm' (first given on line",
    "mis_indented_material": "indent it as far as that link's other keys",
    "unclosed_bracket": "not valid YAML: did not find expected ',' or ']'",
    "mimic_cycle": "form a cycle: none of them moves by itself",
    "mesh_name_control": "holds U+0001, a character an XML file (a URDF) cannot hold",
    "mesh_name_nul": "holds U+0000, a character an XML file (a URDF) cannot hold",
    "long_robot_name": "is 100,000 characters long; a name has at most 200",
    "name_not_a_name": "'1st-link' is not a valid link or joint name",
    "reserved_robot_name": "robot name 'include' is taken by a xacrokit macro or a xacro keyword",
    "alias_bomb": "YAML aliases (*name) are not supported in specs",
    "document_stream": "a spec is one YAML document, but another one starts here",
    "not_a_mapping": "a spec is a mapping (robot:, links:, ...), got list",
    "empty": "the spec is empty",
}
ARGUMENT_WORDS = {
    "count_huge": "must be 1 to 1,000, got 10,000,000",
    "count_digits": "expected a whole number (digits 0-9)",
    "count_superscript": "expected a whole number (digits 0-9), got '²'",
    "count_negative": "expected a whole number (digits 0-9), got '-3'",
    "count_nan": "expected a whole number (digits 0-9), got 'nan'",
    "grid_superscript": "--grid expects ROWSxCOLUMNS such as 2x5, got '²x²'",
    "grid_zero": "--grid expects ROWSxCOLUMNS such as 2x5, got '0x4'",
    "grid_too_small": "--grid 2x2 has 4 places for 9 robots",
    "grid_digits": "--grid expects ROWSxCOLUMNS such as 2x5",
    "spacing_deep": "a quantity written with 6001 characters; at most 200",
    "spacing_infinite": "'1e400' is not a finite number",
    "spacing_angle": "'90 deg' is an angle, expected a length",
    "output_device": "-o /dev/null: it exists and is not a folder",
    "output_empty": "-o needs a path",
    "misspelt_option": "unrecognized arguments: --dryrun; did you mean --dry-run?",
    "unknown_command": "'genrate' is neither a command nor a spec file; did you mean 'generate'?",
    "check_without_path": "the following arguments are required: PATH",
    "bad_mapping": "prefix=r1_: no such file or folder; give a URDF, xacro document, spec or a folder of them (a xacro "
    "argument is written name:=value)",
    "missing_spec": "cannot read the spec: No such file or directory",
}


def field_line(field: str) -> int:
    return next(i for i, row in enumerate(SPEC_TEMPLATE.splitlines(), 1) if f"@{field}@" in row)


def test_the_template_with_good_values_generates(tmp_path):
    spec = tmp_path / "s.yaml"
    spec.write_text(spec_text(), encoding="utf-8")
    code, err = run([spec, "-o", tmp_path / "out"])
    assert code == 0 and (tmp_path / "out" / "urdf" / "bot.urdf").is_file(), err


def test_every_hostile_number_in_every_number_field_is_located(tmp_path):
    spec, out = tmp_path / "s.yaml", tmp_path / "out"
    failures = []
    for field in NUMBER_FIELDS:
        for value in HOSTILE_NUMBERS:
            spec.write_text(spec_text(**{field: value}), encoding="utf-8")
            code, err = run([spec, "-o", out])
            located = re.search(rf"s\.yaml:{field_line(field)}:\d+: ", err)
            if code != 2 or not located or out.exists() or "internal error" in err:
                failures.append((field, value[:30], code, err[:300]))
    assert not failures, failures
    assert len(NUMBER_FIELDS) * len(HOSTILE_NUMBERS) >= 300


@pytest.mark.parametrize(("kind", "text"), STRUCTURE_CASES, ids=[kind for kind, _ in STRUCTURE_CASES])
def test_every_structural_fault_is_located(tmp_path, kind, text):
    spec = tmp_path / "s.yaml"
    spec.write_text(text, encoding="utf-8")
    code, err = run([spec, "-o", tmp_path / "out"])
    assert_refused(code, err, STRUCTURE_WORDS[kind])
    assert re.search(r"s\.yaml:\d+:\d+: ", err), err
    assert not (tmp_path / "out").exists()


@settings(max_examples=25, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(case=hostile_spec_texts())
def test_hostile_spec_texts_are_refused(tmp_path, case):
    text, kind = case
    folder = tmp_path / "h"
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir()
    (folder / "s.yaml").write_text(text, encoding="utf-8")
    code, err = run([folder / "s.yaml", "-o", folder / "out"])
    field = kind.partition("=")[0]
    assert_refused(code, err, STRUCTURE_WORDS.get(kind) or f"s.yaml:{field_line(field)}:")
    assert not (folder / "out").exists(), kind


EXPECTED_XACRO = {
    "recursive_macro": "macro m calls itself without end",
    "self_include": "includes itself",
    "ten_gigabytes": "needs more than 4 GiB of memory",
    "escape_subscript": "python.type is out of reach",
    "not_xml": "not well-formed XML",
    "entity": "external entity",
    "keyword_without_attribute": "xacro:include: missing attribute 'filename'",
    "undefined_property": "name 'nothing' is not defined",
    "missing_block": "Not enough blocks",
}


@pytest.mark.parametrize(("kind", "body"), XACRO_CASES, ids=[kind for kind, _ in XACRO_CASES])
@pytest.mark.parametrize("command", ["expand", "check"])
def test_every_hostile_xacro_document_is_refused_with_its_reason(tmp_path, kind, body, command):
    text = XACRO_HEAD + body + "\n</robot>\n"
    if kind == "entity":
        text = '<?xml version="1.0"?>\n' + body.replace("<link", '<robot name="t"><link') + "</robot>"
    (tmp_path / "doc.urdf.xacro").write_text(text, encoding="utf-8")
    extra = ["--consumers", "none"] if command == "check" else []
    code, err = run([command, tmp_path / "doc.urdf.xacro", *extra])
    assert_refused(code, err, EXPECTED_XACRO.get(kind, "refused to evaluate"))  # (the escapes and evals)


@pytest.mark.parametrize(("kind", "words"), ARGUMENT_CASES, ids=[kind for kind, _ in ARGUMENT_CASES])
def test_every_hostile_command_line_is_refused(tmp_path, kind, words):
    spec = tmp_path / "good.yaml"
    spec.write_text(spec_text(), encoding="utf-8")
    out = tmp_path / "out"
    code, err = run([w.format(spec=spec, out=out) for w in words])
    assert_refused(code, err, ARGUMENT_WORDS[kind])
    assert not out.exists() and not (tmp_path / "out.yaml").exists()
    said = [line for line in err.splitlines() if ": error: " in line]  # one prefix, whichever parser said it
    assert said and all(line.startswith("gen-robot: error: ") for line in said), said


@pytest.mark.parametrize("kind", HOSTILE_PATHS)
@pytest.mark.parametrize("command", ["generate", "check", "expand"])
def test_every_path_that_is_no_document_is_refused(tmp_path, kind, command):
    path = make_hostile_path(kind, tmp_path)
    words = {"generate": ["generate", path, "--dry-run"], "check": ["check", path], "expand": ["expand", path]}
    code, err = run(words[command])
    if command == "check" and kind == "binary":  # a spec that is no text is a V002 finding of check: exit 1
        assert code == 1 and "internal error" not in err
        return
    if command == "check" and kind == "folder":  # check searches a folder for robots: none in this one
        assert code == 0 and "no robot file found in" in err and "Traceback" not in err
        return
    assert_refused(code, err, "cannot read" if kind != "binary" else "not UTF-8")


def test_the_documented_counts_are_the_counts_tried():
    text = (Path(__file__).parents[2] / "docs" / "development.md").read_text(encoding="utf-8")
    tried = (
        len(NUMBER_FIELDS) * len(HOSTILE_NUMBERS)
        + len(STRUCTURE_CASES)
        + 2 * len(XACRO_CASES)
        + len(ARGUMENT_CASES)
        + 3 * len(HOSTILE_PATHS)
    )
    assert f"In all, {tried} inputs are tried in full on every run" in text
    rows = {"HOSTILE_NUMBERS` × `NUMBER_FIELDS": len(NUMBER_FIELDS) * len(HOSTILE_NUMBERS)}
    rows |= {"STRUCTURE_CASES": len(STRUCTURE_CASES), "XACRO_CASES": 2 * len(XACRO_CASES)}
    rows |= {"ARGUMENT_CASES": len(ARGUMENT_CASES), "HOSTILE_PATHS": 3 * len(HOSTILE_PATHS)}
    for name, count in rows.items():
        assert re.search(rf"`{re.escape(name)}`[^|]*\| {count}, all \|", text), name
