"""gen-robot report: a spec's design report (per link shapes, volume, density, mass, centre of mass, inertia and its
formula; the robot's mass and centre of mass), its numbers against formulas written out here and yourdfpy's
forward kinematics."""

from __future__ import annotations

import io
import math

import numpy as np
import pytest
import yourdfpy

from conftest import REPO, gen_robot
from xacrokit.emit import emit_urdf
from xacrokit.pipeline import build_robot
from xacrokit.sizing.design_report import design_report, principal_moments, to_markdown

ROVER = REPO / "examples" / "robots" / "rover.yaml"


def test_the_rover_report_sums_its_parts():
    report = design_report(ROVER)
    base = next(link for link in report.links if link.name == "base_link")
    volume = (
        2 * 0.16 * 0.14 * 0.004  # decks
        + 4 * math.pi * (0.003**2 - 0.0015**2) * 0.056  # standoffs
        + 2 * 0.034 * 0.0465 * 0.0285  # servos
        + 0.09 * 0.035 * 0.025  # battery
        + 2 * 4.02e-6  # brackets (201 mm^2 x 20 mm)
    )
    assert base.volume == pytest.approx(volume, rel=1e-6)  # (the bracket STL's 32-bit floats)
    assert base.density == pytest.approx(base.inertial.mass / volume, rel=1e-6)
    assert base.inertial.kind == "parts" and len(base.shapes) == 11
    i = base.inertial
    tensor = np.array([[i.ixx, i.ixy, i.ixz], [i.ixy, i.iyy, i.iyz], [i.ixz, i.iyz, i.izz]])
    assert principal_moments(i) == pytest.approx(sorted(np.linalg.eigvalsh(tensor)), rel=1e-12)
    wheel = next(link for link in report.links if link.name == "wheel_left_link")
    assert wheel.density == pytest.approx(950.0, rel=1e-12)  # (natural rubber: its mass from its density)


@pytest.mark.parametrize("spec", ["rover", "industrial_arm_std_dh", "humanoid_upper_body"])
def test_the_robots_mass_and_centre_of_mass_are_the_sum_of_its_links(spec):
    path = REPO / "examples" / "robots" / f"{spec}.yaml"
    report = design_report(path)
    text = io.StringIO(emit_urdf(build_robot(path)))
    urdf = yourdfpy.URDF.load(text, build_scene_graph=True, load_meshes=False)
    total, moment = 0.0, np.zeros(3)
    for name, link in urdf.link_map.items():
        if link.inertial is None:
            continue
        place = urdf.get_transform(name, urdf.base_link) @ link.inertial.origin
        total += link.inertial.mass
        moment += link.inertial.mass * place[:3, 3]
    assert report.mass == pytest.approx(total, rel=1e-12)
    assert np.abs(np.array(report.center) - moment / total).max() <= 1e-12


def test_report_writes_markdown_and_refuses_a_bad_spec(tmp_path):
    out = tmp_path / "rover.md"
    result = gen_robot("report", ROVER, "-o", out)
    assert result.returncode == 0, result.stderr
    text = out.read_text(encoding="utf-8")
    assert text == to_markdown(design_report(ROVER))
    assert "## base_link" in text and "sum of the parts" in text and "| wheel_left_link |" in text
    bad = tmp_path / "bad.yaml"
    bad.write_text("robot: r\nlinks:\n  a: {shape: {sphere: {radius: 0.1}}, mass: -1}\n", encoding="utf-8")
    result = gen_robot("report", bad)
    assert result.returncode == 2 and "bad.yaml:3" in result.stderr and "Traceback" not in result.stderr
