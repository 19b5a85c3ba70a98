"""Our rules: every rule fires on its failing corpus fixture and not on its passing one; what single rules read and
say."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from check_helpers import BODY, CORPUS, MOVED_MASSLESS, rules_of

from conftest import REPO, gen_robot
from xacrokit.check import RULES, CheckReport, check

SPEC_ONLY = ("K001", "V001", "V002", "V003")  # rules about a spec, which a URDF fixture cannot show


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
    assert not passing.errors and failing.exit_code(strict=True) == (0 if RULES[rule][1] == "info" else 1)


def test_urdf_findings_point_at_the_element_line():
    report = check(CORPUS / "J002_fail.urdf", consumers=[])
    (finding,) = report.findings
    lines = (CORPUS / "J002_fail.urdf").read_text(encoding="utf-8").splitlines()
    assert finding.file == str(CORPUS / "J002_fail.urdf")
    assert lines[finding.line - 1].strip().startswith('<joint name="shoulder"')
    assert (finding.element_kind, finding.element) == ("joint", "shoulder")


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
    assert finding.element == "l1" and "neither it nor a link fixed to it (flange, body) has a mass" in finding.message


def test_k001_catches_a_urdf_that_does_not_follow_its_dh_table(tmp_path):
    from lxml import etree

    from xacrokit.check.spec_rules import kinematics_rules
    from xacrokit.check.urdf_document import Doc
    from xacrokit.pipeline import build_robot, expand_package
    from xacrokit.render import render_package

    spec = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
    robot = build_robot(spec)
    good = expand_package(robot, render_package(robot, macros="copy")).content  # the library's dh_arm
    doc = Doc(etree.fromstring(good.encode()), str(spec), {})
    assert list(kinematics_rules(doc, robot, good)) == []
    wrong_spec = tmp_path / "ur5.yaml"
    wrong_spec.write_text(spec.read_text(encoding="utf-8").replace("a: -0.39225", "a: -0.39"), encoding="utf-8")
    wrong = build_robot(wrong_spec)
    wrong_urdf = expand_package(wrong, render_package(wrong, macros="copy")).content
    (finding,) = kinematics_rules(doc, robot, wrong_urdf)  # robot says one table, the URDF does another
    assert finding.rule == "K001" and "differ from the DH product by up to" in finding.message


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
    clean = check(REPO / "examples" / "robots" / "two_dof_arm.yaml", consumers=[])
    assert "V001" not in rules_of(clean)


DH_UNITS_SPEC = """robot: arm
links:
  base_link: {shape: {box: {size: [0.1, 0.1, 0.1]}}, mass: 1.0}
  plate: {shape: {box: {size: [0.05, 0.05, 0.01]}}, mass: 0.1}
joints:
  mount: {type: fixed, parent: base_link, child: plate, origin: {xyz: [0, 0, 450]}}
arms:
  arm:
    parent: base_link
    joints:
      - {name: j1, link: l1, a: 0, d: 0.3, alpha: pi/2, mass: 4.0, radius: 0.06, LIMIT}
      - {name: j2, link: l2, a: 455, d: 0, alpha: 0, mass: 8.0, radius: 0.05, LIMIT}
      - {name: j3, link: l3, a: 0.4, d: 0, alpha: 0, mass: 2275, radius: 0.04, LIMIT}
      - {name: j4, link: l4, a: 0.39, d: 0, alpha: 0, mass: "2.275 kg", radius: 0.04, LIMIT}
""".replace("LIMIT", "limit: {lower: -pi, upper: pi, effort: 10, velocity: 1}, dynamics: {damping: 0, friction: 0}")


def test_v001_covers_dh_rows_and_origins_as_it_does_links(tmp_path):
    """A DH table in millimetres written as metres (a 455 m upper arm), a row mass in grams (2275 for 2.275 kg) and an
    origin 450 m up: each a V001 warning at its value, worded as for links; the rows written right stay quiet."""
    spec = tmp_path / "arm.yaml"
    spec.write_text(DH_UNITS_SPEC, encoding="utf-8")
    notes = {f.element: f.message for f in check(spec, consumers=[]).findings if f.rule == "V001"}
    assert set(notes) == {
        "$.joints.mount.origin.xyz[2]",
        "$.arms.arm.joints[1].a",
        "$.arms.arm.joints[2].mass",
    }, notes
    assert notes["$.arms.arm.joints[1].a"].startswith("length 455 m is longer than any part of a robot")
    assert "write '455 mm'" in notes["$.arms.arm.joints[1].a"]
    assert "write '450 mm'" in notes["$.joints.mount.origin.xyz[2]"]
    # j3's body: a cylinder from its frame to j4's, 0.39 m long (standard DH: the next row's d is 0, its own a 0.4)
    volume = math.pi * 0.04**2 * 0.4
    assert notes["$.arms.arm.joints[2].mass"].startswith(f"mass 2275 kg in a {volume:.3g} m^3 cylinder is")
    assert "grams written as kilograms? e.g. '500 g'" in notes["$.arms.arm.joints[2].mass"]
    spec.write_text(DH_UNITS_SPEC.replace("a: 455,", 'a: "455 m",'), encoding="utf-8")  # a unit says it is meant
    assert "$.arms.arm.joints[1].a" not in {f.element for f in check(spec, consumers=[]).findings}


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


def test_j008_mimic_joints_in_a_cycle(tmp_path):
    joint = (
        '<joint name="{0}" type="revolute"><parent link="base_link"/><child link="{1}"/><axis xyz="0 0 1"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/><dynamics damping="0.1"/>{2}</joint>'
        '<link name="{1}">' + BODY + "</link>"
    )
    mimic = '<mimic joint="{}"/>'
    urdf = tmp_path / "cycle.urdf"
    for mimics, cycle in (((mimic.format("b"), mimic.format("a")), True), (("", mimic.format("a")), False)):
        urdf.write_text(
            '<robot name="r"><link name="base_link">' + BODY + "</link>"
            + joint.format("a", "la", mimics[0]) + joint.format("b", "lb", mimics[1]) + "</robot>",
            encoding="utf-8",
        )  # fmt: skip
        found = [f for f in check(urdf, consumers=[]).findings if f.rule == "J008"]
        if cycle:
            (finding,) = found
            assert finding.element == "a" and "mimic joints a -> b -> a form a cycle" in finding.message
        else:
            assert not found


def test_rigid_bodies_are_judged_as_simulators_fuse_them(tmp_path):
    """A massless link with geometry fixed to a massive one (UR's ee_link), and a point mass fixed to a body with
    inertia (an IMU), are fine; the same point mass on a moved body alone is not."""
    massless_flange = '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual><inertial><mass value="0"/>'
    massless_flange += '<inertia ixx="0" iyy="0" izz="0" ixy="0" ixz="0" iyz="0"/></inertial>'
    point_mass = '<inertial><mass value="0.01"/><inertia ixx="0" iyy="0" izz="0" ixy="0" ixz="0" iyz="0"/></inertial>'
    fine = MOVED_MASSLESS.replace("BODY", BODY).replace(
        '<link name="flange"/>', f'<link name="flange">{massless_flange}</link>'
    )
    fine = fine.replace('<link name="l1"/>', f'<link name="l1">{point_mass}</link>')
    path = tmp_path / "fine.urdf"
    path.write_text(fine, encoding="utf-8")
    report = check(path)
    assert not report.errors and not report.warnings, [str(f) for f in report.findings]
    assert [c.status for c in report.consumers] == ["accepted"] * len(report.consumers)
    alone = MOVED_MASSLESS.replace("BODY", "").replace('<link name="l1"/>', f'<link name="l1">{point_mass}</link>')
    path.write_text(alone, encoding="utf-8")
    (finding,) = check(path, consumers=[]).errors
    assert (finding.rule, finding.element) == ("I002", "l1") and "no rotational inertia" in finding.message


@pytest.mark.parametrize(
    ("rule", "change", "said"),
    [  # what consumers accept but is likely a mistake: a warning of the same rule (the failing fixtures are errors)
        ("J001", ('lower="-1" upper="1" ', ""), "<limit> has no lower and upper; URDF reads a missing one as 0"),
        ("J003", ('effort="10"', 'effort="0"'), "limit effort is 0: Gazebo applies no force to the joint"),
        ("J004", ('velocity="1"', 'velocity="0"'), "limit velocity is 0: Gazebo holds the joint still"),
    ],
)
def test_limits_consumers_accept_but_mean_no_motion_are_warnings(tmp_path, rule, change, said):
    urdf = tmp_path / "robot.urdf"
    urdf.write_text((CORPUS / f"{rule}_pass.urdf").read_text(encoding="utf-8").replace(*change), encoding="utf-8")
    report = check(urdf)
    (finding,) = [f for f in report.findings if f.rule == rule]
    assert finding.severity == "warning" and finding.message.startswith(said), finding
    assert [c.status for c in report.consumers] == ["accepted"] * len(report.consumers)  # (why it is no error)


@pytest.mark.parametrize("key", ["effort", "velocity"])
def test_a_negative_effort_or_velocity_is_an_error_pinocchio_agrees(tmp_path, key):
    urdf = tmp_path / "robot.urdf"
    text = (CORPUS / "J004_pass.urdf").read_text(encoding="utf-8")
    urdf.write_text(text.replace(f'{key}="', f'{key}="-'), encoding="utf-8")
    report = check(urdf, consumers=["pinocchio"])
    assert [(f.rule, f.severity) for f in report.findings] == [
        ("J003" if key == "effort" else "J004", "error"),
        ("C001", "error"),
    ], report.findings
    assert f"min_{key} are greater than max_{key}" in report.consumers[0].message


def test_a_mimic_consumers_ignore_is_a_warning(tmp_path):
    """A fixed joint that mimics a revolute one (Talos' reduced models keep the <mimic> of the gripper joints they
    fixed): nothing follows anything, consumers accept it, an expert would remove it."""
    text = (CORPUS / "J008_pass.urdf").read_text(encoding="utf-8")
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(
        text.replace('<joint name="j2" type="revolute">', '<joint name="j2" type="fixed">'), encoding="utf-8"
    )
    report = check(urdf)
    # (and G007: arm and a2, one cylinder each on the same origin of base_link, overlap wholly where they start)
    assert [(f.rule, f.severity) for f in report.findings] == [("J008", "warning"), ("G007", "warning")]
    assert [c.status for c in report.consumers] == ["accepted"] * len(report.consumers)


def test_v003_names_what_a_spec_under_strict_false_keeps_as_given(tmp_path):
    spec = tmp_path / "given.yaml"
    text = (
        "robot: given\nstrict: false\nlinks:\n  base_link: {shape: {box: {size: [0.1, 0.1, 0.1]}}, mass: 1.0}\n"
        "  flat: {mass: 0.5, inertia: {ixx: 0.001, iyy: 0.001, izz: 0}}\n"
        "joints:\n  spin: {type: continuous, parent: base_link, child: flat}\n"
    )
    spec.write_text(text, encoding="utf-8")
    found = {f.element: f for f in check(spec, consumers=[]).findings if f.rule == "V003"}
    assert set(found) == {"$.links.flat.inertia", "$.joints.spin"}, sorted(found)
    assert all(f.severity == "warning" for f in found.values())
    assert found["$.links.flat.inertia"].line == 5 and found["$.joints.spin"].line == 7
    (tmp_path / "strict.yaml").write_text(text.replace("strict: false\n", ""), encoding="utf-8")
    refused = {f.element for f in check(tmp_path / "strict.yaml", consumers=[]).findings if f.rule == "V002"}
    assert refused == set(found)
