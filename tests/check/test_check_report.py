"""The report: its JSON form follows the documented schema, its text form groups by severity, and the exit codes of
gen-robot check (0 clean, 1 findings, 2 bad input)."""

from __future__ import annotations

import json

import jsonschema
import pytest
import yaml
from check_helpers import CORPUS

from conftest import REPO, gen_robot

SCHEMA = json.loads((REPO / "schemas" / "check-report.schema.json").read_text(encoding="utf-8"))


@pytest.mark.parametrize("fixture", ["I003_fail.urdf", "I003_pass.urdf", "C001_fail.urdf", "J009_fail.urdf"])
def test_json_report_follows_its_documented_schema(fixture):
    result = gen_robot("check", CORPUS / fixture, "--json")
    report = json.loads(result.stdout)
    jsonschema.validate(report, SCHEMA)
    assert result.returncode == (1 if report["summary"]["errors"] else 0)
    assert report["summary"]["errors"] == sum(f["severity"] == "error" for f in report["findings"])


def test_exit_codes():
    assert gen_robot("check", CORPUS / "J009_pass.urdf", "--consumers", "none").returncode == 0
    assert gen_robot("check", CORPUS / "J007_fail.urdf", "--consumers", "none").returncode == 0  # a warning
    assert gen_robot("check", CORPUS / "J007_fail.urdf", "--consumers", "none", "--strict").returncode == 1
    noted = gen_robot("check", CORPUS / "J009_fail.urdf", "--consumers", "none", "--strict")  # a note never fails
    assert noted.returncode == 0 and noted.stdout.splitlines()[-1] == "OK: 0 error(s), 0 warning(s), 1 note(s)"
    assert gen_robot("check", CORPUS / "I002_fail.urdf", "--consumers", "none").returncode == 1
    missing = gen_robot("check", CORPUS / "nothing.urdf")
    assert missing.returncode == 2 and "Traceback" not in missing.stderr
    assert gen_robot("check", CORPUS / "J009_pass.urdf", "--consumers", "pybullet").returncode == 2
    assert gen_robot("check", CORPUS / "J009_pass.urdf", "x:=1").returncode == 2  # arguments are for xacro input


def test_text_report_groups_by_severity():
    result = gen_robot("check", CORPUS / "S005_fail.urdf", "--consumers", "none")
    lines = result.stdout.splitlines()
    assert lines[1] == "1 error:" and lines[2].startswith("  S005 unique-joint-names: joint 'shoulder' (")
    assert lines[-1] == "FAILED: 1 error(s), 0 warning(s)" and "\033[" not in result.stdout  # no colour off a TTY


def test_invalid_specs_are_findings_and_unreadable_ones_exit_2(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(yaml.safe_dump({"robot": "r", "links": {"a": {"mass": -1}}}), encoding="utf-8")
    result = gen_robot("check", bad, "--json")  # located errors: a report, as for a URDF that is not XML (U001)
    assert result.returncode == 1, result.stderr
    report = json.loads(result.stdout)
    jsonschema.validate(report, SCHEMA)
    assert {(f["rule"], f["element"]["name"], f["line"]) for f in report["findings"]} >= {("V002", "$.links.a.mass", 3)}
    assert any("mass must be > 0" in f["message"] for f in report["findings"])
    text = gen_robot("check", bad)
    assert text.returncode == 1 and "V002 spec-valid" in text.stdout and f"{bad}:3" in text.stdout
    missing = gen_robot("check", tmp_path / "missing.yaml")  # nothing to report on
    assert missing.returncode == 2 and "cannot read the spec" in missing.stderr and not missing.stdout


def test_the_schema_names_every_rule_of_the_table():
    """The report schema's rule ids are the rule table's, in its order (a rule added to the table and not to the
    schema made every report naming it invalid: G002-G006, I008 and I009 were missing until 2026-11-27)."""
    from xacrokit.check import RULES

    assert SCHEMA["$defs"]["finding"]["properties"]["rule"]["enum"] == list(RULES)
