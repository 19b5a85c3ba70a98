"""Properties of gen-robot over random specs: every valid spec generates, expands and loads; every single-fault spec
gives located errors (exit 2), never another exception, never a file written."""

from __future__ import annotations

import subprocess

import pinocchio as pin
import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lxml import etree

import xacrokit
from conftest import check_urdf_binary, gen_robot, parse_generated
from xacrokit.testing import FAULTS, invalid_specs, valid_specs

FAULT_WORDS = {
    "negative_mass": ["mass must be > 0"],
    "swapped_limits": ["is greater than upper"],
    "dangling_parent": ["'no_such_link' is not a link"],
    "cycle": ["form a cycle"],
    "duplicate_name": ["is already used"],
    "zero_axis": ["axis must not be zero"],
    "not_positive_definite": ["not positive definite"],
    "triangle_violation": ["triangle inequality"],
    "missing_gazebo_reference": ["'no_such_link', which is not a link"],
    "wrong_type": ["expected a number or a string"],
    "bad_unit": ["unknown unit", "expected a length", "unexpected 'x'"],
    "injected_name": ["is not a valid name", "is not a valid link or joint name"],
    "unknown_material": ["material 'no_such_colour' is not in materials"],
    "not_finite": ["is not a finite number"],
    "extreme_axis": ["has length"],
    "deep_quantity": ["at most 200"],
    "tube_inside_out": ["must be less than outer_radius"],
    "composite_with_mass": ["move mass into a part"],
}


def write_spec(tmp_path_factory, spec, label):
    folder = tmp_path_factory.mktemp(label)
    path = folder / "spec.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    return folder, path


@settings(suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(spec=valid_specs())
def test_every_valid_spec_generates_expands_and_loads(tmp_path_factory, spec):
    folder, path = write_spec(tmp_path_factory, spec, "valid")
    result = xacrokit.generate(path, folder / "pkg")
    robot = result.model
    urdf_path = folder / "pkg" / "urdf" / f"{robot.name}.urdf"
    root = etree.parse(str(urdf_path)).getroot()

    assert sorted(e.get("name") for e in root.findall("link")) == sorted(robot.link_names)
    assert sorted(e.get("name") for e in root.findall("joint")) == sorted(robot.joint_names)
    for link in spec["links"].values():  # mesh filenames (with ${ and $( in them) arrive verbatim
        if "mesh" in link.get("shape", {}):
            wanted = link["shape"]["mesh"]["filename"]
            assert wanted in {m.get("filename") for m in root.iter("mesh")}

    checked = subprocess.run([check_urdf_binary(), str(urdf_path)], capture_output=True, text=True, timeout=60)
    assert checked.returncode == 0, checked.stdout + checked.stderr
    pin.buildModelFromUrdf(str(urdf_path))
    import yourdfpy

    yourdfpy.URDF.load(str(urdf_path), build_scene_graph=False, load_meshes=False)
    for file in result.files:  # launch, CMake, package.xml, xacro, YAML: each parses with its own parser
        parse_generated(file.path, file.content)
    again = xacrokit.generate(path, folder / "pkg")
    assert {a.action for a in again.actions} == {"identical"}


@given(case=invalid_specs())
def test_every_single_fault_gives_located_errors_and_writes_nothing(tmp_path_factory, case):
    spec, fault = case
    folder, path = write_spec(tmp_path_factory, spec, "invalid")
    with pytest.raises(xacrokit.SpecErrors) as caught:
        xacrokit.generate(path, folder / "pkg")
    errors = caught.value.errors
    assert errors and all(e.line is not None and e.column is not None and e.path.startswith("$") for e in errors)
    assert any(words in e.message for e in errors for words in FAULT_WORDS[fault]), (fault, [str(e) for e in errors])
    assert not (folder / "pkg").exists()


@settings(max_examples=5)
@given(case=invalid_specs())
def test_invalid_specs_exit_2_from_the_command_line(tmp_path_factory, case):
    spec, _ = case
    folder, path = write_spec(tmp_path_factory, spec, "cli")
    result = gen_robot(path, "-o", folder / "pkg")
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert f"{path}:" in result.stderr and not (folder / "pkg").exists()


@pytest.mark.parametrize("fault", FAULTS)
@settings(max_examples=1)
@given(data=st.data())
def test_every_fault_is_made(data, fault):
    """invalid_specs makes each fault it names (its maker is in the table, and says the fault it made)."""
    _, made = data.draw(invalid_specs(faults=(fault,)))
    assert made == fault
