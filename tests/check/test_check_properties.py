"""The end-to-end property suite: random valid robots check clean with every consumer accepting, and every single
fault injected into one is caught by the rule meant for it."""

from __future__ import annotations

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import xacrokit
from conftest import REPO, budget, gen_robot, mesh_package_at
from xacrokit.check import RULES, check, generation_warnings
from xacrokit.pipeline import build_robot, expand_package
from xacrokit.reader.robot_input import RobotInput
from xacrokit.render import render_package
from xacrokit.testing import URDF_FAULTS, inject_urdf_fault, valid_specs

# a dangling parent leaves the injected link without a parent: a second root is a true finding too
# a fault may bring a second rule with it: a dangling parent leaves two roots (S001); a Gazebo block naming no link
# makes the file one written for Gazebo, where a wheel or foot without friction of its own is a warning (G006), not
# the note it is in a file without any <gazebo> (drawn in a local run: a continuous joint's child was the lowest)
ALSO_EXPECTED = {"dangling_parent": {"S001"}, "missing_gazebo_reference": {"G006"}}


def urdf_of(spec, folder, macros="inline"):
    path = folder / "spec.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    robot = build_robot(path)
    return robot, expand_package(robot, render_package(robot, macros=macros)).content, path


@pytest.fixture(scope="module")
def mesh_package(tmp_path_factory):
    """The package the random specs' meshes live in (package://some_pkg/meshes/NAME.stl), names with $ { ( & < too."""
    return mesh_package_at(tmp_path_factory.mktemp("some_pkg"))


# budget: an example renders and checks a random robot twice, inline and with the library macros (half a second);
# test_each_single_fault_is_caught_by_its_rule and the generation properties draw the same robots again
@settings(max_examples=budget(15), suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(spec=valid_specs())
def test_valid_specs_check_clean_by_our_rules(tmp_path_factory, mesh_package, spec):
    folder = tmp_path_factory.mktemp("clean")
    path = folder / "spec.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    report = check(RobotInput(path, packages={"some_pkg": mesh_package}), consumers=[])  # the default (inline) package
    assert not report.errors, [str(f) for f in report.errors]
    _, library_urdf, _ = urdf_of(spec, folder, macros="copy")  # and what the library macros give
    (folder / "library.urdf").write_text(library_urdf, encoding="utf-8")
    library = check(RobotInput(folder / "library.urdf", packages={"some_pkg": mesh_package}), consumers=[])
    assert not library.errors, [str(f) for f in library.errors]


@settings(suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(spec=valid_specs(), fault=st.sampled_from(sorted(URDF_FAULTS)), macros=st.sampled_from(["inline", "copy"]))
def test_each_single_fault_is_caught_by_its_rule(tmp_path_factory, spec, fault, macros):
    folder = tmp_path_factory.mktemp("fault")
    robot, urdf, _ = urdf_of(spec, folder, macros)
    clean = folder / "clean.urdf"
    clean.write_text(urdf, encoding="utf-8")
    before = check(clean, consumers=[])
    assert not before.errors  # the fault below is the only problem (warnings the random spec has stay as they are)
    broken = folder / "broken.urdf"
    broken.write_text(inject_urdf_fault(urdf, fault, robot.root), encoding="utf-8")
    report = check(broken, consumers=[])
    intended = URDF_FAULTS[fault]
    fired = {f.rule for f in report.findings if f.severity != "info"}
    fired -= {f.rule for f in before.findings if f.severity != "info"} - {intended}
    assert intended in fired, (fault, [str(f) for f in report.findings])
    assert fired <= {intended} | ALSO_EXPECTED.get(fault, set()), (fault, fired)
    # an error fails the check; a warning (a Gazebo block naming no link, which Gazebo ignores) fails it with --strict
    assert report.exit_code() == (1 if RULES[intended][1] == "error" else 0) and report.exit_code(strict=True) == 1


# The independent consumers take about a second a robot (a process each): a quarter as many random robots as the
# profile gives the others (6 in CI; HYPOTHESIS_PROFILE raises it), our rules on all of them above.
@settings(
    max_examples=max(1, settings.default.max_examples // 4),
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
@given(spec=valid_specs())
def test_valid_specs_are_accepted_by_every_consumer(tmp_path_factory, mesh_package, spec):
    folder = tmp_path_factory.mktemp("consumers")
    path = folder / "spec.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    report = check(RobotInput(path, packages={"some_pkg": mesh_package}))
    assert not report.errors, [str(f) for f in report.errors]
    assert {c.name for c in report.consumers} >= {"check_urdf", "pinocchio", "yourdfpy"}
    assert all(c.status == "accepted" for c in report.consumers), report.consumers


@settings(suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(spec=valid_specs())
def test_generating_says_everything_check_strict_would_fail_on(tmp_path_factory, spec):
    """gen-robot SPEC writes no package that `check --strict SPEC` then fails without having said why: each warning
    and error of check (the spec's own V001 and the rules on the URDF) is one of the warnings the command says (the
    generator's and check's rules' on its URDF, composed by generation_warnings)."""
    folder = tmp_path_factory.mktemp("said")
    path = folder / "spec.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    said = [w.message for w in generation_warnings(xacrokit.generate(path, folder / "out", dry_run=True))]
    failing = [f for f in check(path, consumers=[]).findings if f.severity != "info"]
    for finding in failing:
        if finding.rule == "V001":
            assert any(finding.message in m for m in said), (finding.message, said)
        else:
            expected = f"{finding.rule} {RULES[finding.rule][0]} ({finding.severity} of gen-robot check): "
            expected += f"{finding.element_kind} {finding.element!r}: {finding.message}"
            assert expected in said, (expected, said)
    assert len(said) == len(failing), (said, [str(f) for f in failing])


def test_generating_says_a_warning_check_strict_fails_on(tmp_path):
    spec = tmp_path / "w.yaml"
    spec.write_text(
        """robot: w
links:
  base_link: {shape: {box: {size: [0.2, 0.2, 0.1]}}, mass: 2.0}
  arm: {shape: {box: {size: [0.05, 0.05, 0.3]}}, mass: 1.0, inertia: {ixx: 0.01, iyy: 0.01, izz: 0.01}}
joints:
  shoulder: {type: revolute, parent: base_link, child: arm, axis: [0, 1, 0],
             limit: {lower: 0, upper: 0, effort: 10, velocity: 1}, dynamics: {damping: 0.1}}
""",
        encoding="utf-8",
    )
    result = gen_robot(spec, "-o", tmp_path / "pkg")
    assert result.returncode == 0
    assert result.stderr.splitlines() == [
        f"gen-robot: warning: {spec}:4:3: I005 inertia-placeholder (warning of gen-robot check): link 'arm': inertia "
        "is 0.01 * identity, a common placeholder; compute it from the body (e.g. xacrokit's inertia macros)",
        f"gen-robot: warning: {spec}:4:3: I008 inertia-fits-geometry (warning of gen-robot check): link 'arm': its "
        "moments spread the mass 0.0707 m (rms) along the link's x axis from the centre of mass, but the link's "
        "geometry reaches at most 0.025 m that way (the two moments across that axis minus the one about it are "
        "2 sum(m d^2), d along it: 0.01 kg*m^2 here, at most 0.00125); a uniform box of 1 kg filling its collision "
        "geometry has ixx, iyy, izz = 0.00771, 0.00771, 0.000417 kg*m^2",
        f"gen-robot: warning: {spec}:6:3: J013 limit-range (warning of gen-robot check): joint 'shoulder': limit lower "
        "and upper are both 0.0: the joint cannot move; give it its real limits (a CAD exporter writes 0 and 0 when "
        "it knows none), make it continuous if it turns without end, or fixed if it never moves",
    ]
    assert gen_robot("check", spec, "--consumers", "none", "--strict").returncode == 1  # (what was said)
    generated = xacrokit.generate(spec, tmp_path / "again", dry_run=True)
    assert generated.warnings == ()  # generation leaves check's to check: the command composes the two
    said = [f"gen-robot: warning: {w}" for w in generation_warnings(generated)]
    assert said == result.stderr.splitlines()


def test_at_one_place_the_spec_speaks_first_then_check_then_the_generator(tmp_path, monkeypatch):
    """generation_warnings merges check's findings into generate's warnings in line order as gen-robot SPEC always
    said them: where a spec warning, a check finding and the generator's drive warning share a line and column, in
    that order (check's used to be said between the two from inside generate)."""
    from dataclasses import replace

    from xacrokit.check import document_rules
    from xacrokit.check.findings import Finding
    from xacrokit.errors import SpecError

    example = (REPO / "examples" / "robots" / "diff_drive.yaml").read_text(encoding="utf-8")
    spec = tmp_path / "drive.yaml"  # the base frame 5 cm behind the axle: the generator's drive warning
    spec.write_text(example.replace("xyz: [0, 0.18, -0.055]", "xyz: [0.05, 0.18, -0.055]"), encoding="utf-8")
    result = xacrokit.generate(spec, tmp_path / "pkg", dry_run=True)
    (drive,) = result.warnings
    assert "axle midpoint" in drive.message and result.source is not None
    ours = SpecError("the spec's", file=str(spec), path="$.wheels.left_wheel", line=drive.line, column=drive.column)
    source = replace(result.source, warnings=(ours,))
    result = replace(result, warnings=(ours, drive), source=source)
    found = [
        Finding("J013", "warning", "joint", "left_wheel_joint", "check's", line=drive.line, column=drive.column),
        Finding("I005", "info", "link", "left_wheel", "not said: an info", line=1, column=1),
        Finding("I005", "warning", "link", "base_link", "check's first", line=1, column=1),
    ]
    monkeypatch.setattr(document_rules, "generated_urdf_findings", lambda *args: found)
    said = generation_warnings(result)
    assert len(said) == 4 and said[1] is ours and said[3] is drive, [str(w) for w in said]
    assert said[0].message.endswith("link 'base_link': check's first") and said[0].line == 1
    assert said[2].message == "J013 limit-range (warning of gen-robot check): joint 'left_wheel_joint': check's"
