"""A body's density instead of its mass: mass = density x the volume of its shape (exact closed forms for primitives, a
wheel's cylinder, a DH row's body as gen-robot draws it), checked against a mass given too, refused where no volume is
known or the material is not in the table."""

from __future__ import annotations

import math
import re

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import REPO, gen_robot
from xacrokit.errors import SpecErrors
from xacrokit.pipeline import build_robot
from xacrokit.shared.materials import MATERIALS, find_material


def robot_of(tmp_path, spec):
    path = tmp_path / "dens.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    return build_robot(path)


def masses(robot):
    return {link.name: link.inertial.mass for link in robot.links if link.inertial}


sizes = st.floats(0.001, 2.0)
densities = st.floats(1.0, 22_000.0)


@settings(max_examples=40, deadline=None)
@given(size=st.tuples(sizes, sizes, sizes), radius=sizes, length=sizes, density=densities)
def test_a_density_gives_density_times_volume(tmp_path_factory, size, radius, length, density):
    spec = {
        "robot": "d",
        "links": {
            "box": {"shape": {"box": {"size": list(size)}}, "density": density},
            "can": {"shape": {"cylinder": {"radius": radius, "length": length}}, "density": density},
            "ball": {"shape": {"sphere": {"radius": radius}}, "density": f"{density / 1000!r} g/cm3"},
        },
        "joints": {
            "a": {"type": "fixed", "parent": "box", "child": "can"},
            "b": {"type": "fixed", "parent": "box", "child": "ball"},
        },
        "wheels": {"w": {"parent": "box", "radius": radius, "width": length, "density": density}},
    }
    robot = robot_of(tmp_path_factory.mktemp("d"), spec)
    got = masses(robot)
    expected = {
        "box": density * size[0] * size[1] * size[2],
        "can": density * math.pi * radius**2 * length,
        "ball": density * 4.0 / 3.0 * math.pi * radius**3,
    }
    for name, mass in expected.items():
        assert got[name] == pytest.approx(mass, rel=1e-12), name
    (wheel,) = robot.wheels
    assert wheel.mass == pytest.approx(density * math.pi * radius**2 * length, rel=1e-12)


def test_a_dh_rows_density_fills_the_body_gen_robot_draws(tmp_path):
    row = {"a": 0.3, "d": 0, "alpha": 0, "radius": 0.02, "density": 2700}
    limit = {"limit": {"lower": -1, "upper": 1, "effort": 1, "velocity": 1}, "dynamics": {"damping": 0}}
    spec = {
        "robot": "d",
        "links": {"base_link": {"shape": {"box": {"size": [0.1, 0.1, 0.1]}}, "mass": 1.0}},
        "arms": {"arm": {"parent": "base_link", "joints": [{"name": "j1", "link": "l1", **row, **limit}]}},
    }
    (arm,) = robot_of(tmp_path, spec).arms
    # standard DH: the row's body runs along its own a (0.3 m) to the tool frame
    assert arm.rows[0].mass == pytest.approx(2700 * math.pi * 0.02**2 * 0.3, rel=1e-12)


def test_a_mass_far_from_its_density_is_a_warning(tmp_path):
    spec = {
        "robot": "d",
        "links": {"ball": {"shape": {"sphere": {"radius": 0.05}}, "mass": 5.0, "density": 1000}},
    }
    path = tmp_path / "d.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    result = gen_robot(path, "--dry-run")
    assert result.returncode == 0
    assert "$.links.ball.mass: mass 5 kg is 9.55 times that of a solid sphere of density 1000 kg/m^3" in result.stderr
    spec["links"]["ball"]["mass"] = 0.4  # 0.76 of the solid's 0.524 kg: a part with pockets, quiet
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    assert "warning" not in gen_robot(path, "--dry-run").stderr


BALL = {"sphere": {"radius": 0.1}}


@pytest.mark.parametrize(
    ("body", "where", "said"),
    [
        (
            {"shape": {"mesh": {"filename": "m.stl"}}, "density": 1000},
            "links.l.shape.mesh.filename",
            "mesh file 'm.stl' is not there",
        ),
        ({"density": 1000}, "links.l.density", "a density gives a mass only with a shape"),
        (
            {"shape": BALL, "density": "unobtainium"},
            "links.l.density",
            "unknown material 'unobtainium'",
        ),
        (
            {"shape": BALL, "density": "-5 g/cm3"},
            "links.l.density",
            "density must be > 0 kg/m^3",
        ),
        (
            {"shape": BALL, "density": "5 kg"},
            "links.l.density",
            "'5 kg' is a mass, expected a density (kg/m3",
        ),
    ],
)
def test_a_density_that_gives_no_mass_is_refused_at_its_value(tmp_path, body, where, said):
    with pytest.raises(SpecErrors) as caught:
        robot_of(tmp_path, {"robot": "d", "links": {"l": body}})
    assert [(e.path, said in e.message) for e in caught.value.errors] == [(f"$.{where}", True)], caught.value.errors


def test_a_wheel_needs_a_mass_or_a_density(tmp_path):
    spec = {
        "robot": "d",
        "links": {"base_link": {"shape": {"box": {"size": [0.1, 0.1, 0.1]}}, "mass": 1.0}},
        "wheels": {"w": {"parent": "base_link", "radius": 0.05, "width": 0.02}},
    }
    with pytest.raises(SpecErrors) as caught:
        robot_of(tmp_path, spec)
    (error,) = caught.value.errors
    assert error.path == "$.wheels.w" and "a wheel needs a mass (kg) or a density" in error.message


def test_material_names_are_read_loosely_and_have_a_source():
    for name, material in MATERIALS.items():
        assert find_material(name.upper().replace("_", " ")) is material
        assert 1.0 < material.density < 22_590.0 and material.grade and len(material.source) > 10, name


def test_a_material_name_gives_its_tabled_density(tmp_path):
    spec = {
        "robot": "d",
        "links": {
            "chassis": {"shape": {"box": {"size": [0.3, 0.2, 0.05]}}, "density": "Aluminum 6061"},
            "plate": {"shape": {"box": {"size": [0.1, 0.1, 0.01]}}, "density": "steel"},
        },
        "joints": {"j": {"type": "fixed", "parent": "chassis", "child": "plate"}},
    }
    got = masses(robot_of(tmp_path, spec))
    assert got["chassis"] == pytest.approx(2700 * 0.3 * 0.2 * 0.05, rel=1e-12)  # ASM: 6061-T6 is 2.70 g/cc
    assert got["plate"] == pytest.approx(7850 * 0.1 * 0.1 * 0.01, rel=1e-12)  # Eurocode 3: steel is 7850 kg/m^3
    with pytest.raises(SpecErrors) as caught:
        robot_of(tmp_path, {"robot": "d", "links": {"l": {"shape": BALL, "density": "aluminium 6016"}}})
    assert "unknown material 'aluminium 6016' (did you mean 'aluminium_6061'?)" in caught.value.errors[0].message


def test_the_docs_density_example_gives_the_masses_it_says(tmp_path):
    docs = (REPO / "docs" / "spec.md").read_text(encoding="utf-8")
    (block,) = [b for b in re.findall(r"```yaml\n(.*?)\n```", docs, flags=re.S) if "chassis: {shape" in b]
    path = tmp_path / "d.yaml"
    joints = "\njoints:\n  j: {type: fixed, parent: chassis, child: mast}\n"
    path.write_text("robot: d\n" + block + joints, encoding="utf-8")
    got = masses(build_robot(path))
    assert round(got["chassis"], 9) == 8.1 and round(got["mast"], 4) == 0.1558  # as its comments say


def test_gen_robot_materials_lists_the_table_with_sources():
    result = gen_robot("materials")
    assert result.returncode == 0
    lines = result.stdout.splitlines()
    for name, material in MATERIALS.items():
        (line,) = [line for line in lines if line.split()[0] == name]
        assert f"{material.density:g} kg/m^3" in line and material.source in line
