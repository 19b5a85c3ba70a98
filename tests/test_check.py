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


SPEC_ONLY = ("K001", "V001", "V002")  # rules about a spec, which a URDF fixture cannot show


def rules_of(report: CheckReport) -> set[str]:
    return {f.rule for f in report.findings}


def corpus_check(path: Path) -> CheckReport:
    rule = path.name[:4]
    return check(path, consumers=None if rule == "C001" else [], prefix="r1_" if rule == "P001" else None)


def test_every_rule_has_a_failing_and_a_passing_fixture():
    fixtures = {p.name for p in CORPUS.glob("*.urdf")}
    for rule in RULES:
        if rule in SPEC_ONLY:
            continue  # needs a spec; see test_k001_*, test_v001_* and test_invalid_specs_*
        assert {f"{rule}_fail.urdf", f"{rule}_pass.urdf"} <= fixtures, rule


@pytest.mark.parametrize("rule", sorted(r for r in RULES if r not in SPEC_ONLY))
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


MOVED_MASSLESS = """<robot name="r">
  <link name="base_link"/>
  <joint name="j1" type="revolute"><parent link="base_link"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/><dynamics damping="0.1"/></joint>
  <link name="l1"/>
  <joint name="f1" type="fixed"><parent link="l1"/><child link="flange"/></joint>
  <link name="flange"/>
  <joint name="f2" type="fixed"><parent link="flange"/><child link="body"/></joint>
  <link name="body">BODY</link>
</robot>"""
BODY = (
    '<inertial><mass value="1"/><inertia ixx="0.011" iyy="0.012" izz="0.013" ixy="0" ixz="0" iyz="0"/></inertial>'
    '<visual><geometry><box size="0.1 0.2 0.3"/></geometry></visual>'
)


def test_a_moved_link_may_leave_its_mass_to_links_fixed_to_it(tmp_path):
    """Consumers merge fixed children into their parent: the body j1 moves has mass through 'body', two fixed joints
    down. Without that mass anywhere in the body, I001 names the moved link."""
    good = tmp_path / "good.urdf"
    good.write_text(MOVED_MASSLESS.replace("BODY", BODY), encoding="utf-8")
    report = check(good)
    assert "I001" not in rules_of(report), [str(f) for f in report.findings]
    assert [c.status for c in report.consumers] == ["accepted"] * len(report.consumers)  # they agree
    bad = tmp_path / "bad.urdf"
    bad.write_text(MOVED_MASSLESS.replace("BODY", ""), encoding="utf-8")
    (finding,) = [f for f in check(bad, consumers=[]).findings if f.rule == "I001"]
    assert finding.element == "l1" and "nor any link fixed to it" in finding.message


ROWS_SPEC = """robot: rows
links:
  base_link: {shape: {box: {size: [0.1, 0.1, 0.1]}}, mass: 1.0}
arms:
  arm:
    parent: base_link
    joints:
      - {name: j1, link: l1, a: 0, d: 0.1, alpha: pi/2, mass: 1.0,
         limit: {lower: -1, upper: 1, effort: 1, velocity: 1}}
      - {name: j2, link: l2, a: 0.2, d: 0, alpha: 0, mass: 1.0, limit: {lower: -1, upper: 1, effort: 1, velocity: 1}}
      - name: j3
        link: l3
        a: 0.2
        d: 0
        alpha: 0
        mass: 1.0
        limit: {lower: -1, upper: 1, effort: 1, velocity: 1}
"""


def test_dh_row_findings_point_at_their_own_row(tmp_path):
    spec = tmp_path / "rows.yaml"
    spec.write_text(ROWS_SPEC, encoding="utf-8")
    lines = ROWS_SPEC.splitlines()
    rows = {f.element: f.line for f in check(spec, consumers=[]).findings if f.rule == "J009"}  # no dynamics
    assert set(rows) == {"j1", "j2", "j3"}
    for joint, line in rows.items():
        assert f"name: {joint}" in lines[line - 1], (joint, line)


def test_consumers_asked_for_by_name_must_be_installed(monkeypatch, tmp_path):
    import xacrokit.check as check_module

    monkeypatch.setattr(check_module, "available", lambda name: name != "mujoco")
    with pytest.raises(xacrokit.XacrokitError, match="mujoco asked for but not installed"):
        check(CORPUS / "I001_pass.urdf", consumers=["check_urdf", "mujoco"])
    with pytest.raises(xacrokit.XacrokitError, match="unknown consumer"):
        check(CORPUS / "I001_pass.urdf", consumers=["nosuch"])
    report = check(CORPUS / "I001_pass.urdf")  # 'all' means those installed: mujoco left out, not an error
    assert "mujoco" not in {c.name for c in report.consumers} and not report.errors


def test_input_kind_by_content_when_the_suffix_says_nothing(tmp_path):
    from xacrokit.check import input_kind

    urdf = tmp_path / "robot.txt"
    urdf.write_text((CORPUS / "I001_pass.urdf").read_text(encoding="utf-8"), encoding="utf-8")
    xacro_doc = tmp_path / "robot.in"
    xacro_doc.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a"/></robot>')
    older = tmp_path / "robot.description"  # the older namespace address, still common
    older.write_text(
        '<robot name="r" xmlns:xacro="http://ros.org/wiki/xacro"><xacro:property name="w" value="1"/></robot>'
    )
    assert input_kind(older) == "xacro"
    spec = tmp_path / "robot.spec"
    spec.write_text((REPO / "examples" / "two_dof_arm.yaml").read_text(encoding="utf-8"), encoding="utf-8")
    assert [input_kind(p) for p in (urdf, xacro_doc, spec)] == ["urdf", "xacro", "spec"]
    assert check(spec, consumers=[]).kind == "spec" and not check(spec, consumers=[]).findings


def test_a_file_in_a_package_finds_its_package_and_siblings(tmp_path):
    src = tmp_path / "ws" / "src"
    for package in ("my_desc", "meshes_pkg"):
        (src / package / "meshes").mkdir(parents=True)
        (src / package / "package.xml").write_text(f'<package format="3"><name>{package}</name></package>')
        (src / package / "meshes" / "m.stl").write_text("solid m\nendsolid m\n")
    (src / "my_desc" / "urdf").mkdir()
    urdf = src / "my_desc" / "urdf" / "r.urdf"
    meshes = "".join(
        f'<visual><geometry><mesh filename="package://{p}/meshes/{m}"/></geometry></visual>'
        for p, m in (("my_desc", "m.stl"), ("meshes_pkg", "m.stl"), ("my_desc", "gone.stl"), ("elsewhere", "m.stl"))
    )
    urdf.write_text(f'<robot name="r"><link name="base_link">{meshes}</link></robot>', encoding="utf-8")
    findings = [f for f in check(urdf, consumers=[]).findings if f.rule == "R003"]
    assert sorted((f.severity, f.element) for f in findings) == [
        ("error", "package://my_desc/meshes/gone.stl"),  # its own package found: the missing file is an error
        ("warning", "package://elsewhere/meshes/m.stl"),  # a package nowhere near: cannot be checked
    ]
    document = src / "my_desc" / "urdf" / "r.urdf.xacro"  # $(find) in gen-robot expand uses the same search
    document.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a"><visual><geometry>'
        '<mesh filename="file://$(find meshes_pkg)/meshes/m.stl"/></geometry></visual></link></robot>'
    )
    result = gen_robot("expand", document)
    assert result.returncode == 0, result.stderr
    assert f"file://{(src / 'meshes_pkg').resolve()}/meshes/m.stl" in result.stdout


UNITS_SPEC = """robot: units
links:
  base_link: {shape: {box: {size: [0.2, 0.2, 0.1]}}, mass: 2000, origin: {rpy: [0, "90", 90]}}
  arm: {shape: {cylinder: {radius: 0.02, length: 0.3}}, mass: 0.5}
  plate: {shape: {box: {size: [100, 100, 2]}}, mass: 1.5}
joints:
  shoulder: {type: revolute, parent: base_link, child: arm, axis: [0, 1, 0],
             limit: {lower: -170, upper: "170 deg", effort: 10, velocity: 1}, dynamics: {damping: 0.1}}
  mount: {type: fixed, parent: base_link, child: plate}
"""


def test_v001_names_values_that_look_like_units_left_out(tmp_path):
    spec = tmp_path / "units.yaml"
    spec.write_text(UNITS_SPEC, encoding="utf-8")
    lines = UNITS_SPEC.splitlines()
    notes = {f.element: f for f in check(spec, consumers=[]).findings if f.rule == "V001"}
    assert set(notes) == {
        "$.links.base_link.origin.rpy[1]",  # '90' (quoted): the same
        "$.links.base_link.origin.rpy[2]",  # 90 rad: degrees without their unit
        "$.links.base_link.mass",  # 2,000 kg in a 4-litre box: grams written as kilograms
        "$.links.plate.mass",  # a 100 m plate of 1.5 kg: millimetres written as metres
        "$.joints.shoulder.limit.lower",  # -170 rad (upper, '170 deg', says its unit)
    }, sorted(notes)
    assert "'-170 deg'" in notes["$.joints.shoulder.limit.lower"].message
    assert "denser than osmium" in notes["$.links.base_link.mass"].message
    assert "lighter than air" in notes["$.links.plate.mass"].message
    for finding in notes.values():
        assert finding.severity == "warning" and finding.file == str(spec)
        key = finding.element.rsplit(".", 1)[-1].split("[")[0]
        assert key in lines[finding.line - 1], (finding.element, finding.line)
    result = gen_robot(spec, "-o", tmp_path / "pkg")  # generating says the same on stderr, and still generates
    assert result.returncode == 0, result.stderr
    assert result.stderr.count("gen-robot: warning:") == 5 and "$.links.plate.mass" in result.stderr
    clean = check(REPO / "examples" / "two_dof_arm.yaml", consumers=[])
    assert "V001" not in rules_of(clean)


def test_check_urdf_says_what_urdfdom_found_first(tmp_path):
    """urdfdom prints the cause first and where it gave up after; the finding keeps the cause."""
    urdf = tmp_path / "no_limit.urdf"
    urdf.write_text(
        MOVED_MASSLESS.replace("BODY", BODY).replace('<limit lower="-1" upper="1" effort="1" velocity="1"/>', "")
    )
    report = check(urdf, consumers=["check_urdf"])
    (consumer,) = report.consumers
    assert consumer.status == "rejected" and "does not specify limits" in consumer.message, consumer.message
    assert "at line" not in consumer.message  # urdfdom's own source locations are left out


def test_a_spec_mesh_finding_is_given_once_at_its_link(tmp_path):
    spec = tmp_path / "meshy.yaml"
    spec.write_text(
        "robot: meshy\nlinks:\n  base_link:\n    shape: {mesh: {filename: package://nowhere_pkg/meshes/base.stl}}\n"
        "    mass: 1.0\n    inertia: {ixx: 0.011, iyy: 0.012, izz: 0.013}\n",
        encoding="utf-8",
    )
    findings = [f for f in check(spec, consumers=[]).findings if f.rule == "R003"]
    assert len(findings) == 1, findings  # the visual's and the collision's mesh: one finding
    assert findings[0].line == 3 and findings[0].file == str(spec)


def test_check_urdf_printing_an_error_is_a_rejection_even_when_it_exits_0():
    """urdfdom reports an unreadable rpy ("pi/2", left by a xacro macro) and carries on to exit 0."""
    report = check(CORPUS / "U002_fail.urdf", consumers=["check_urdf"])
    (consumer,) = report.consumers
    assert consumer.status == "rejected" and "pi/2" in consumer.message, consumer
    assert {f.rule for f in report.errors} == {"U002", "C001"}


@pytest.mark.parametrize(
    ("element", "bad"),
    [
        ('<inertia ixx="1_0" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/>', 'ixx="1_0"'),  # Python reads it; urdfdom not
        ('<inertia ixx="\uff11" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/>', 'ixx="\uff11"'),  # a full-width digit
        ('<origin xyz="0&#9;0 0"/>', 'xyz="0\t0 0"'),  # a tab between values (written as a reference: XML turns a
        # literal tab in an attribute into a space)
        ('<mass value="1.0 "/>', 'value="1.0 "'),  # urdfdom: "mass [1.0 ] is not a float"
        ('<origin rpy="0 0 nan"/>', 'rpy="0 0 nan"'),
    ],
)
def test_u002_reads_numbers_the_way_urdfdom_does(tmp_path, element, bad):
    urdf = tmp_path / "r.urdf"
    urdf.write_text(f'<robot name="r"><link name="a"><inertial>{element}</inertial></link></robot>', encoding="utf-8")
    messages = [f.message for f in check(urdf, consumers=[]).findings if f.rule == "U002"]
    assert len(messages) == 1 and bad in messages[0], messages


def test_u002_accepts_what_urdf_allows_and_refuses_colours_beyond_1(tmp_path):
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        '<robot name="r"><material name="m"><color rgba="2 0 0 1"/></material><link name="a"><visual><origin/>'
        '<geometry><mesh filename="m.stl" scale=" 1e-3  +.5 -0. "/></geometry></visual>'
        '<inertial><origin xyz="+1E-2 .01 -0." rpy="  0 0 0 "/><mass value=" 1"/>'
        '<inertia ixx="0.011" iyy="0.012" izz="0.013" ixy="0" ixz="0" iyz="0"/></inertial></link></robot>',
        encoding="utf-8",
    )
    messages = [f.message for f in check(urdf, consumers=[]).findings if f.rule == "U002"]
    assert messages == ['<color rgba="2 0 0 1">: expected 4 numbers from 0 to 1']
