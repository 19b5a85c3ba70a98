"""What check reads: every example clean, spec input (findings at spec lines, generated in memory), xacro input with
arguments, the kind of a file by its content, and the packages a file finds near it."""

from __future__ import annotations

import pytest
from check_helpers import CORPUS, rules_of

import xacrokit
from conftest import MACRO_DEMO, REPO, ROBOT_EXAMPLES, gen_robot
from xacrokit.check import check
from xacrokit.reader.robot_input import RobotInput

# The course's own robots keep the course's numbers, and check says where they fall short: that is the lesson
# (examples/robots/simple_humanoid.yaml's comment). Exactly these findings, nothing else, and no error.
LESSONS = {
    "simple_humanoid": {
        ("I008", n) for n in ("left_forearm", "left_shin", "right_forearm", "right_shin")
    }  # the chapter's inertias its shapes cannot hold
    | {("J009", j) for j in ("neck_joint", "left_shoulder_pitch", "left_elbow", "left_hip_pitch", "left_knee")}
    | {("J009", j) for j in ("right_shoulder_pitch", "right_elbow", "right_hip_pitch", "right_knee")},
    "humanoid_upper_body": {  # the exercise gives no <dynamics>: a note each
        ("J009", j) for j in ("neck_joint", "left_shoulder", "left_elbow", "right_shoulder", "right_elbow")
    },
    # links whose stand-in cylinders intersect at home: a note naming them (the package's SRDF disables them)
    "industrial_arm_mod_dh": {("G008", "panda")},
    "kuka_kr560_r3100_2": {("G008", "kuka_kr560_r3100_2")},
}


@pytest.mark.parametrize("spec", [*ROBOT_EXAMPLES, MACRO_DEMO], ids=lambda p: p.stem)
def test_every_example_checks_clean_strictly_with_every_consumer(spec):
    report = check(spec)
    found = {(f.rule, f.element) for f in report.findings}
    assert found == LESSONS.get(spec.stem, set()), [str(f) for f in report.findings]
    assert not [f for f in report.findings if f.severity == "error"]
    assert [c.status for c in report.consumers] == ["accepted"] * len(report.consumers)
    assert {c.name for c in report.consumers} >= {"check_urdf", "pinocchio", "yourdfpy"}


def test_spec_findings_point_at_spec_lines(tmp_path):
    text = (REPO / "examples" / "robots" / "two_dof_arm.yaml").read_text(encoding="utf-8")
    text = text.replace("    dynamics: {damping: 0.05, friction: 0.0}\n", "")
    spec = tmp_path / "arm.yaml"
    spec.write_text(text, encoding="utf-8")
    report = check(spec, consumers=[])
    (finding,) = report.findings
    assert finding.rule == "J009" and finding.element == "elbow_joint" and finding.file == str(spec)
    assert text.splitlines()[finding.line - 1].strip() == "elbow_joint:"
    assert not (tmp_path / "two_dof_arm_description").exists()  # generated in memory only


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


def test_xacro_input_takes_arguments_and_prefix_rule(tmp_path):
    out = tmp_path / "pkg"
    xacrokit.generate(REPO / "examples" / "robots" / "diff_drive.yaml", out)
    entry = out / "urdf" / "diff_drive.urdf.xacro"
    packages = {"diff_drive_description": out}
    report = check(RobotInput(entry, {"prefix": "r7_"}, packages), prefix="r7_", consumers=[])
    assert not [f for f in report.findings if f.rule != "G008"]  # (G008: a note on the package's SRDF)
    unprefixed = check(RobotInput(entry, packages=packages), prefix="r7_", consumers=[])
    assert rules_of(unprefixed) - {"G008"} == {"P001"}  # (G008: a note on the package's SRDF)
    kinds = {f.element_kind for f in unprefixed.findings if f.rule != "G008"}
    assert kinds == {"link", "joint", "gazebo", "ros2_control"}
    assert all(f.line is None for f in unprefixed.findings)  # an expanded xacro's lines are not the file's


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
    spec.write_text((REPO / "examples" / "robots" / "two_dof_arm.yaml").read_text(encoding="utf-8"), encoding="utf-8")
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


def test_xacrokit_check_is_the_function_whatever_was_imported_before(tmp_path):
    """xacrokit.check is the public function and a package: importing one of the package's modules first (which makes
    Python set the package as xacrokit.check) leaves xacrokit.check(path) working."""
    import subprocess
    import sys

    urdf = tmp_path / "r.urdf"
    urdf.write_text('<robot name="r"><link name="a"/></robot>', encoding="utf-8")
    script = (
        "import xacrokit, xacrokit.check.findings, sys\n"
        f"report = xacrokit.check({str(urdf)!r}, consumers=[])\n"
        "print(type(report).__name__, report.robot)\n"
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert done.stdout.split() == ["CheckReport", "r"], done.stderr
