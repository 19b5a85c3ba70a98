"""The direct URDF emitter describes exactly the robot that expanding the generated package with xacro describes."""

from __future__ import annotations

import re

import pytest
import yaml
from hypothesis import HealthCheck, given, settings

from conftest import ROBOT_EXAMPLES, SCENE_EXAMPLES
from xacrokit.emit import emit_scene_urdf, emit_urdf, urdf_differences
from xacrokit.load import load_file
from xacrokit.pipeline import build_robot, expand_package
from xacrokit.render import render_package, render_scene
from xacrokit.scene import build_scene
from xacrokit.testing import valid_specs

EXAMPLES = ROBOT_EXAMPLES
SCENES = SCENE_EXAMPLES


def via_library(robot):
    """The URDF xacro expands from a package whose robot macro calls the library macros."""
    return expand_package(robot, render_package(robot, macros="copy")).content


NEGATIVE_ZERO = re.compile(r"(?<![\w.])-0\.0(?![\d])")  # -0.0 as a whole number (not -0.05, not 1e-0.0)


def test_every_example_is_emitted_exactly_as_the_library_macros_expand_it():
    for spec in EXAMPLES:
        robot = build_robot(spec)
        library, emitted = via_library(robot), emit_urdf(robot)
        assert urdf_differences(library, emitted, rel=0.0) == [], spec.name
        assert not NEGATIVE_ZERO.search(library) and not NEGATIVE_ZERO.search(emitted), spec.name  # a -0.0 reads oddly


@pytest.mark.parametrize("mode", ["inline", "copy"])
def test_every_scene_example_too(mode):
    for path in SCENES:
        scene = build_scene(load_file(path))
        xacro_urdf = expand_package(scene, render_scene(scene, macros=mode)).content
        assert urdf_differences(xacro_urdf, emit_scene_urdf(scene), rel=0.0) == [], path.name


BASE = (
    '<robot name="r"><link name="a"><inertial><mass value="1.0"/></inertial></link>'
    '<joint name="j" type="fixed"/></robot>'
)


def test_the_comparator_ignores_order_whitespace_and_comments():
    same = (
        '<robot name="r">\n  <!-- note -->\n  <joint type="fixed" name="j"/>\n  <link name="a"><inertial>\n'
        '<mass value="1"/></inertial></link>\n</robot>'
    )
    assert urdf_differences(BASE, same) == []
    assert urdf_differences(BASE, BASE.replace('"1.0"', '"1.0000000000001"')) == []  # within 1e-12


def test_the_comparator_reports_what_differs():
    assert urdf_differences(BASE, BASE.replace('"1.0"', '"1.001"'))  # a number
    assert urdf_differences(BASE, BASE.replace('<joint name="j" type="fixed"/>', ""))  # a missing element
    assert urdf_differences(BASE, BASE.replace('name="a"', 'name="b"'))  # a name
    assert urdf_differences(BASE, BASE.replace('type="fixed"', 'type="fixed" extra="1"'))  # an attribute
    assert urdf_differences(BASE, BASE.replace('"1.0"', '"1.0000000000001"'), rel=0.0)


def test_inline_packages_expand_to_the_emitted_urdf_on_every_example():
    for spec in EXAMPLES:
        robot = build_robot(spec)
        files = render_package(robot, macros="inline")
        assert not any(
            f.path.startswith(("urdf/xacrokit/", "config/")) and f.path.endswith((".xacro", ".dh.yaml")) for f in files
        ), spec.name
        assert urdf_differences(expand_package(robot, files).content, emit_urdf(robot), rel=0.0) == [], spec.name


@settings(suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(spec=valid_specs())
def test_random_specs_expand_to_the_emitted_urdf_in_both_macro_modes(tmp_path_factory, spec):
    path = tmp_path_factory.mktemp("emit") / "spec.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    robot = build_robot(path)
    emitted = emit_urdf(robot)
    library = via_library(robot)
    assert urdf_differences(library, emitted) == []
    assert not NEGATIVE_ZERO.search(emitted) and not NEGATIVE_ZERO.search(library)
    inline = expand_package(robot, render_package(robot, macros="inline")).content  # ${ in mesh names stays text
    assert urdf_differences(inline, emitted) == []


def test_a_negative_zero_in_the_spec_is_written_0_0_by_both_paths(tmp_path):
    # found by hypothesis: a DH row limit of -0.0 came out as "-0.0" from the library and "0.0" from the emitter
    spec = {
        "robot": "bot",
        "links": {"base": {"shape": {"box": {"size": [1.0, 1.0, 1.0]}}, "mass": 1.0}},
        "arms": {
            "arm": {
                "parent": "base",
                "joints": [
                    {"name": "j0", "link": "l0", "a": 0.0, "d": -0.0, "alpha": "-0 deg", "mass": 1.0,
                     "limit": {"lower": -0.0, "upper": 0.0, "effort": 1.0, "velocity": 1.0}}
                ],
            }
        },
    }  # fmt: skip
    path = tmp_path / "spec.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    robot = build_robot(path)
    for urdf in (via_library(robot), emit_urdf(robot)):
        assert not NEGATIVE_ZERO.search(urdf)
        assert 'lower="0.0"' in urdf
