"""gen-robot check: every rule fires on its failing fixture and not on its passing one; reports, exit codes, inputs."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import jsonschema
import pytest
import yaml

import xacrokit
from conftest import REPO, gen_robot
from xacrokit.check import RULES, CheckReport, check
from xacrokit.consumers import run_consumer

CORPUS = REPO / "tests" / "check_corpus"
SCHEMA = json.loads((REPO / "schemas" / "check-report.schema.json").read_text(encoding="utf-8"))


def rules_of(report: CheckReport) -> set[str]:
    return {f.rule for f in report.findings}


def corpus_check(path: Path) -> CheckReport:
    rule = path.name[:4]
    return check(path, consumers=None if rule == "C001" else [], prefix="r1_" if rule == "P001" else None)


def test_every_rule_has_a_failing_and_a_passing_fixture():
    fixtures = {p.name for p in CORPUS.glob("*.urdf")}
    for rule in RULES:
        if rule == "K001":
            continue  # needs a spec; see test_k001_*
        assert {f"{rule}_fail.urdf", f"{rule}_pass.urdf"} <= fixtures, rule


@pytest.mark.parametrize("rule", sorted(r for r in RULES if r != "K001"))
def test_rule_fires_on_its_failing_fixture_only(rule):
    failing = corpus_check(CORPUS / f"{rule}_fail.urdf")
    assert rule in rules_of(failing), [str(f) for f in failing.findings]
    assert all(f.severity == RULES[f.rule][1] or f.rule == "R003" for f in failing.findings)
    passing = corpus_check(CORPUS / f"{rule}_pass.urdf")
    assert rule not in rules_of(passing), [str(f) for f in passing.findings]
    assert not passing.errors and failing.exit_code(strict=True) == 1


def test_urdf_findings_point_at_the_element_line():
    report = check(CORPUS / "J002_fail.urdf", consumers=[])
    (finding,) = report.findings
    lines = (CORPUS / "J002_fail.urdf").read_text(encoding="utf-8").splitlines()
    assert finding.file == str(CORPUS / "J002_fail.urdf")
    assert lines[finding.line - 1].strip().startswith('<joint name="shoulder"')
    assert (finding.element_kind, finding.element) == ("joint", "shoulder")


def test_rooted_cycle_is_reported_and_check_urdf_is_not_left_running(tmp_path):
    urdf = tmp_path / "rooted.urdf"
    urdf.write_text(
        '<robot name="rc"><link name="root"/><link name="a"/><link name="b"/>'
        '<joint name="ra" type="fixed"><parent link="root"/><child link="a"/></joint>'
        '<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>'
        '<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint></robot>',
        encoding="utf-8",
    )
    report = check(urdf)
    assert [f.message for f in report.findings if f.rule == "S002"] == [
        "joint 'ba' closes a cycle a -> b -> a; remove it"
    ]
    assert {c.status for c in report.consumers} == {"skipped"}
    # run check_urdf anyway: it prints forever on this file; the output cap stops it
    forced = run_consumer("check_urdf", urdf, timeout=20)
    assert forced.status in ("rejected", "timeout") and forced.failed


def test_consumer_that_hangs_is_stopped_and_reported(tmp_path, monkeypatch):
    import xacrokit.consumers as consumers

    monkeypatch.setattr(consumers, "_check_urdf_binary", lambda: str(tmp_path / "sleeper"))
    sleeper = tmp_path / "sleeper"
    sleeper.write_text("#!/bin/sh\nsleep 30\n", encoding="utf-8")
    sleeper.chmod(0o755)
    result = consumers.run_consumer("check_urdf", CORPUS / "J002_pass.urdf", timeout=0.5)
    assert result.status == "timeout" and result.failed


@pytest.mark.parametrize("fixture", ["I003_fail.urdf", "I003_pass.urdf", "C001_fail.urdf", "J009_fail.urdf"])
def test_json_report_follows_its_documented_schema(fixture):
    result = gen_robot("check", CORPUS / fixture, "--json")
    report = json.loads(result.stdout)
    jsonschema.validate(report, SCHEMA)
    assert result.returncode == (1 if report["summary"]["errors"] else 0)
    assert report["summary"]["errors"] == sum(f["severity"] == "error" for f in report["findings"])


def test_exit_codes():
    assert gen_robot("check", CORPUS / "J009_pass.urdf", "--consumers", "none").returncode == 0
    assert gen_robot("check", CORPUS / "J009_fail.urdf", "--consumers", "none").returncode == 0  # a warning
    assert gen_robot("check", CORPUS / "J009_fail.urdf", "--consumers", "none", "--strict").returncode == 1
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


@pytest.mark.parametrize("spec", sorted((REPO / "examples").glob("*.yaml")), ids=lambda p: p.stem)
def test_every_example_checks_clean_strictly_with_every_consumer(spec):
    if "macros_demo" in spec.name:
        spec = REPO / "examples" / "macros_demo.urdf.xacro"
    report = check(spec)
    assert not report.findings, [str(f) for f in report.findings]
    assert [c.status for c in report.consumers] == ["accepted"] * len(report.consumers)
    assert {c.name for c in report.consumers} >= {"check_urdf", "pinocchio", "yourdfpy"}


def test_spec_findings_point_at_spec_lines(tmp_path):
    text = (REPO / "examples" / "two_dof_arm.yaml").read_text(encoding="utf-8")
    text = text.replace("    dynamics: {damping: 0.05, friction: 0.0}\n", "")
    spec = tmp_path / "arm.yaml"
    spec.write_text(text, encoding="utf-8")
    report = check(spec, consumers=[])
    (finding,) = report.findings
    assert finding.rule == "J009" and finding.element == "elbow_joint" and finding.file == str(spec)
    assert text.splitlines()[finding.line - 1].strip() == "elbow_joint:"
    assert not (tmp_path / "two_dof_arm_description").exists()  # generated in memory only


def test_xacro_input_takes_arguments_and_prefix_rule(tmp_path):
    out = tmp_path / "pkg"
    xacrokit.generate(REPO / "examples" / "diff_drive.yaml", out)
    entry = out / "urdf" / "diff_drive.urdf.xacro"
    packages = {"diff_drive_description": out}
    report = check(entry, {"prefix": "r7_"}, prefix="r7_", consumers=[], package_paths=packages)
    assert not report.findings
    unprefixed = check(entry, prefix="r7_", consumers=[], package_paths=packages)
    assert rules_of(unprefixed) == {"P001"}
    kinds = {f.element_kind for f in unprefixed.findings}
    assert kinds == {"link", "joint", "gazebo", "ros2_control"}
    assert all(f.line is None for f in unprefixed.findings)  # an expanded xacro's lines are not the file's


def test_k001_catches_a_urdf_that_does_not_follow_its_dh_table(tmp_path):
    from lxml import etree

    from xacrokit.check import _Doc, kinematics_rules
    from xacrokit.pipeline import build_robot, expand_package
    from xacrokit.render import render_package

    spec = REPO / "examples" / "industrial_arm_std_dh.yaml"
    robot = build_robot(spec)
    good = expand_package(robot, render_package(robot, macros="copy")).content  # the library's dh_arm
    doc = _Doc(etree.fromstring(good.encode()), str(spec), {}, source_lines=False)
    assert list(kinematics_rules(doc, robot, good)) == []
    wrong_spec = tmp_path / "ur5.yaml"
    wrong_spec.write_text(spec.read_text(encoding="utf-8").replace("a: -0.39225", "a: -0.39"), encoding="utf-8")
    wrong = build_robot(wrong_spec)
    wrong_urdf = expand_package(wrong, render_package(wrong, macros="copy")).content
    (finding,) = kinematics_rules(doc, robot, wrong_urdf)  # robot says one table, the URDF does another
    assert finding.rule == "K001" and "differ from the DH product by up to" in finding.message


def test_unreadable_specs_exit_2(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(yaml.safe_dump({"robot": "r", "links": {"a": {"mass": -1}}}), encoding="utf-8")
    result = gen_robot("check", bad)
    assert result.returncode == 2 and "mass must be > 0" in result.stderr


@pytest.mark.skipif(not __import__("importlib").util.find_spec("mujoco"), reason="MuJoCo is not installed")
def test_mujoco_consumer_accepts_good_and_rejects_bad_inertia():
    good = check(CORPUS / "I003_pass.urdf", consumers=["mujoco"])
    assert [c.status for c in good.consumers] == ["accepted"]
    bad = check(CORPUS / "I003_fail.urdf", consumers=["mujoco"])
    (verdict,) = bad.consumers
    assert verdict.status == "rejected" and "inertia" in verdict.message and "\n" not in verdict.message
    assert {f.rule for f in bad.errors} == {"I003", "C001"}


def test_benchmark_script_runs():
    result = subprocess.run(
        [sys.executable, str(REPO / "benchmarks" / "bench.py"), "check", "cli"],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert result.returncode == 0, result.stderr
    for words in ("1000 links:", "ratio t(3000)/t(1000)", "rooted cycle reported (S002)", "gen-robot --help"):
        assert words in result.stdout


def test_consumers_leave_nothing_in_the_working_folder(tmp_path):
    result = gen_robot("check", CORPUS / "I003_fail.urdf", cwd=tmp_path)  # MuJoCo, when installed, rejects it
    assert result.returncode == 1
    assert list(tmp_path.iterdir()) == []


def test_benchmark_stage_measurement_runs(tmp_path, monkeypatch):
    monkeypatch.syspath_prepend(str(REPO / "benchmarks"))
    from bench import measure_size, touch

    row = measure_size(10, tmp_path)
    stages = {"load", "validate", "resolve", "render", "write", "emit", "xacro", "check", "full", "lxml"}
    assert set(row) == stages | {"touch"}  # (touch: the reference walk, not a stage)
    assert all(value > 0 for value in row.values())
    assert touch({"a": [1, {"b": 2.0}], "c": {}}) == 4  # it reaches every mapping and list
