"""The reports for code scanning and CI dashboards as their readers take them: SARIF as GitHub's code scanning reads
it (a whole title per rule, help links to anchors that exist, fingerprints that survive moved lines, paths relative
to %SRCROOT%, no runner's absolute paths) and JUnit as junitparser (GitLab's and the CI actions' reading) parses it:
one failure per case, counts that match what is written, warnings in system-out."""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path
from urllib.parse import unquote, urlparse

import jsonschema
import pytest
from check_helpers import CORPUS
from junitparser import Error, Failure, JUnitXml
from test_check_many import _sarif_schema as sarif_schema

from conftest import REPO, gen_robot
from xacrokit.check import check
from xacrokit.check.file_workers import FileCheck
from xacrokit.check.rule_table import RULES, TITLES, anchor, titles_markdown
from xacrokit.check.sarif_report import sarif_log

FINGERPRINT = "xacrokitFinding/v1"  # (the key docs/check.md names)
CHECK_MD = (REPO / "docs" / "check.md").read_text(encoding="utf-8")
# words a whole title does not end on: a phrase cut before what it was saying
DANGLING = set(
    "a an the of to in on at by for with from into onto and or but nor that which as than per its their".split()
)

# two joints whose axes are not of unit length (J007 warns each); {gap} moves the first one down
TWO_AXES = """<?xml version="1.0"?>
<robot name="r">
  <link name="base_link">
    <inertial><mass value="1.0"/><inertia ixx="0.0042" ixy="0" ixz="0" iyy="0.0042" iyz="0" izz="0.0067"/></inertial>
    <visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual>
  </link>{gap}
  <joint name="shoulder" type="continuous"><parent link="base_link"/><child link="arm"/><axis xyz="0 {y} 0"/>
    <dynamics damping="0.1"/></joint>
  <link name="arm">
    <inertial><mass value="0.5"/><inertia ixx="0.0038" ixy="0" ixz="0" iyy="0.0038" iyz="0" izz="0.0001"/></inertial>
    <visual><geometry><cylinder radius="0.02" length="0.3"/></geometry></visual>
  </link>
  <joint name="elbow" type="continuous"><parent link="arm"/><child link="hand"/><axis xyz="0 0 3"/>
    <dynamics damping="0.1"/></joint>
  <link name="hand">
    <inertial><mass value="0.5"/><inertia ixx="0.0038" ixy="0" ixz="0" iyy="0.0038" iyz="0" izz="0.0001"/></inertial>
    <visual><geometry><cylinder radius="0.02" length="0.3"/></geometry></visual>
  </link>
</robot>
"""


def _sarif(*args, cwd: Path) -> tuple[int, dict]:
    result = gen_robot("check", *args, "--format", "sarif", "--consumers", "none", cwd=cwd)
    log = json.loads(result.stdout)
    jsonschema.Draft4Validator(sarif_schema()).validate(log)  # (the OASIS schema, every time)
    return result.returncode, log


# ------------------------------------------------------------------------------------------------ rules and titles
def test_every_rule_has_a_short_whole_title_as_its_short_description(tmp_path):
    """16 of 49 short descriptions were the full text cut at its first ';' or ' (': "the robot's base body" (I007),
    "a robot on wheels or feet" (G006), "every number URDF reads" (U002), "no two links of different sizes" (I009)."""
    shutil.copyfile(CORPUS / "J007_fail.urdf", tmp_path / "j007.urdf")
    code, log = _sarif("j007.urdf", cwd=tmp_path)
    rules = {rule["id"]: rule for rule in log["runs"][0]["tool"]["driver"]["rules"]}
    assert list(rules) == list(RULES) == list(TITLES) and code == 0
    for rule, (name, _severity, checks) in RULES.items():
        title = rules[rule]["shortDescription"]["text"]
        assert title == TITLES[rule] and len(title) <= 60, (rule, title)
        assert title[0].isupper() and title[-1] not in ".,;:(" and title.split()[-1].lower() not in DANGLING, title
        assert title.count("(") == title.count(")") and title.count("<") == title.count(">"), title
        cut = checks.lower().startswith(title.lower()) and title.lower() != checks.lower()
        assert not cut, f"{rule}: the title is the start of its full text, cut: {title!r}"
        assert rules[rule]["fullDescription"]["text"] == f"Checks that {checks}."[:1024] and rules[rule]["name"] == name


def test_help_links_lead_to_anchors_that_exist_in_docs_check_md(tmp_path):
    shutil.copyfile(CORPUS / "J007_fail.urdf", tmp_path / "j007.urdf")
    _, log = _sarif("j007.urdf", cwd=tmp_path)
    driver = log["runs"][0]["tool"]["driver"]
    anchors = set(re.findall(r'<a id="([^"]+)"></a>', CHECK_MD))
    info = urlparse(driver["informationUri"])
    assert info.scheme == "https" and info.path.endswith("/docs/check.md") and not info.fragment
    for rule in driver["rules"]:
        link = urlparse(rule["helpUri"])
        assert link.scheme == "https" and link.path == info.path and link.fragment == anchor(rule["id"])
        assert link.fragment in anchors, f"{rule['id']}: #{link.fragment} is no anchor of docs/check.md"
        assert rule["helpUri"] in rule["help"]["text"] and f"]({rule['helpUri']})" in rule["help"]["markdown"]
    assert len(anchors) == len(RULES)


def test_docs_check_md_rule_titles_are_current():
    block = CHECK_MD.split("<!-- check-titles:start -->\n", 1)[1].split("<!-- check-titles:end -->", 1)[0]
    assert block == titles_markdown(), (
        "run: python -c 'from xacrokit.check.rule_table import titles_markdown; print(titles_markdown(), end=\"\")' "
        "and paste it between the markers in docs/check.md"
    )


# ---------------------------------------------------------------------------------------------------- fingerprints
def _fingerprints(folder: Path, text: str) -> dict[tuple[str, str], tuple[str, int]]:
    (folder / "arm.urdf").write_text(text, encoding="utf-8")
    _, log = _sarif("arm.urdf", cwd=folder)
    said = {}
    for result in log["runs"][0]["results"]:
        element = result["message"]["text"].split(":", 1)[0]  # ("joint 'elbow'")
        line = result["locations"][0]["physicalLocation"]["region"]["startLine"]
        said[(result["ruleId"], element)] = (result["partialFingerprints"][FINGERPRINT], line)
    return said


def test_a_fingerprint_stays_when_lines_move_and_names_its_element(tmp_path):
    before = _fingerprints(tmp_path, TWO_AXES.format(gap="", y=2))
    after = _fingerprints(tmp_path, TWO_AXES.format(gap="\n" * 7, y=5))  # (moved down, another wrong length)
    shoulder, elbow = ("J007", "joint 'shoulder'"), ("J007", "joint 'elbow'")
    assert {shoulder, elbow} <= before.keys() and before.keys() == after.keys()
    for key in before:
        assert after[key][0] == before[key][0], key  # the same alert
        assert after[key][1] == before[key][1] + 7 or key[1] == "robot", key  # (at its new line)
    assert before[shoulder][0] != before[elbow][0]  # another element, another alert
    renamed = _fingerprints(tmp_path, TWO_AXES.format(gap="", y=2).replace('"shoulder"', '"hip"'))
    assert renamed[("J007", "joint 'hip'")][0] != before[shoulder][0]
    assert renamed[elbow][0] == before[elbow][0]


# ------------------------------------------------------------------------------------------------------- places
def test_paths_are_relative_to_srcroot_percent_encoded_and_elsewhere_absolute(tmp_path):
    work, elsewhere = tmp_path / "work", tmp_path / "elsewhere"
    (work / "my robots").mkdir(parents=True)
    elsewhere.mkdir()
    inside = work / "my robots" / "arm #1 ü.urdf"
    outside = elsewhere / "arm%.urdf"
    for path in (inside, outside):
        shutil.copyfile(CORPUS / "J007_fail.urdf", path)
    code, log = _sarif(inside, outside, cwd=work)  # (absolute paths given, as $GITHUB_WORKSPACE/... would be)
    (run,) = log["runs"]
    assert "%SRCROOT%" in run["originalUriBaseIds"] and code == 0
    places = {
        r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"]: r["locations"][0]["physicalLocation"]
        for r in run["results"]
    }
    relative = places["my%20robots/arm%20%231%20%C3%BC.urdf"]["artifactLocation"]
    assert relative["uriBaseId"] == "%SRCROOT%" and Path(work, unquote(relative["uri"])) == inside
    (absolute,) = [place["artifactLocation"] for uri, place in places.items() if uri.startswith("file:")]
    assert "uriBaseId" not in absolute and Path(unquote(urlparse(absolute["uri"]).path)) == outside


def test_an_unreadable_file_is_told_without_the_runners_absolute_paths(tmp_path, monkeypatch):
    (tmp_path / "robots").mkdir()
    (tmp_path / "robots" / "unreadable.urdf").write_bytes(b"\xff\xfe")
    code, log = _sarif(tmp_path / "robots", cwd=tmp_path)  # (an absolute folder, as CI passes it)
    (invocation,) = log["runs"][0]["invocations"]
    (notice,) = invocation["toolExecutionNotifications"]
    assert code == 2 and invocation["executionSuccessful"] is False
    assert str(tmp_path) not in json.dumps(log), notice["message"]["text"]
    assert "robots/unreadable.urdf" in notice["message"]["text"]
    where = notice["locations"][0]["physicalLocation"]["artifactLocation"]
    assert where == {"uri": "robots/unreadable.urdf", "uriBaseId": "%SRCROOT%"}
    # a path outside the working folder, below the home folder: said from ~
    home, work = tmp_path / "home" / "runner", tmp_path / "work"
    work.mkdir()
    monkeypatch.setenv("HOME", str(home))
    monkeypatch.chdir(work)
    told = FileCheck(str(home / "x.urdf"), None, f"cannot read {home}/x.urdf: no such file")
    (notice,) = sarif_log([told])["runs"][0]["invocations"][0]["toolExecutionNotifications"]
    assert notice["message"]["text"] == "cannot read ~/x.urdf: no such file"


# ------------------------------------------------------------------------------------------------------- JUnit
def _two_errors(folder: Path) -> Path:
    """A URDF with two errors of two rules (I002 and J002) and a warning (J007)."""
    text = (CORPUS / "I002_fail.urdf").read_text(encoding="utf-8")
    joint = '<joint name="extra" type="revolute"><parent link="base_link"/><child link="extra_link"/>'
    joint += '<axis xyz="0 0 2"/><limit lower="1" upper="-1" effort="1" velocity="1"/><dynamics damping="0"/></joint>'
    joint += '<link name="extra_link"><inertial><mass value="0.1"/>'
    joint += '<inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial></link>'
    path = folder / "two_errors.urdf"
    path.write_text(text.replace("</robot>", joint + "</robot>"), encoding="utf-8")
    return path


@pytest.mark.parametrize("strict", [False, True])
def test_junit_has_one_failure_per_case_with_every_finding_and_warnings_in_system_out(tmp_path, strict):
    two = _two_errors(tmp_path)
    shutil.copyfile(CORPUS / "J007_fail.urdf", tmp_path / "j007.urdf")  # (a warning only)
    shutil.copyfile(CORPUS / "J009_pass.urdf", tmp_path / "clean.urdf")
    (tmp_path / "unreadable.urdf").write_bytes(b"\xff")
    options = ["--consumers", "none", *(["--strict"] if strict else [])]
    result = gen_robot("check", tmp_path, "--format", "junit", *options)
    (suite,) = list(JUnitXml.fromstring(result.stdout.encode()))
    cases = {Path(case.name).name: case for case in suite}
    assert sorted(cases) == ["clean.urdf", "j007.urdf", "two_errors.urdf", "unreadable.urdf"]
    assert result.returncode == 2
    for name in ("clean.urdf", "j007.urdf", "two_errors.urdf"):
        report = check(tmp_path / name, consumers=[])
        failing = report.errors + (report.warnings if strict else [])
        results = cases[name].result
        assert len(results) == (1 if failing else 0), (name, results)  # one failure element at most
        if failing:
            (failure,) = results
            assert isinstance(failure, Failure)
            assert failure.text.splitlines() == [f.said(str(tmp_path / name)) for f in failing]
            assert failure.type == ",".join(dict.fromkeys(f.rule for f in failing))
        shown = [] if strict else [f.said(str(tmp_path / name)) for f in report.warnings]
        assert (cases[name].system_out or "").splitlines() == shown
    assert len(check(two, consumers=[]).errors) >= 2 and {"I002", "J002"} <= set(
        cases["two_errors.urdf"].result[0].type.split(",")
    )
    assert isinstance(cases["unreadable.urdf"].result[0], Error)
    kinds = [type(case.result[0]) if case.result else None for case in suite]
    said = (suite.tests, suite.failures, suite.errors, suite.skipped)
    assert said == (len(kinds), kinds.count(Failure), kinds.count(Error), 0) == (4, 2 if strict else 1, 1, 0)
