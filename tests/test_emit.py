"""The direct URDF emitter describes exactly the robot that expanding the generated package with xacro describes."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from lxml import etree

import xacrokit
from conftest import REPO, gen_robot
from xacrokit.emit import emit_scene_urdf, emit_urdf, urdf_differences
from xacrokit.expansion import expand_file
from xacrokit.load import load_file
from xacrokit.pipeline import build_robot, expand_package
from xacrokit.render import render_package, render_scene
from xacrokit.scene import build_scene
from xacrokit.testing import valid_specs

EXAMPLES = sorted(p for p in (REPO / "examples").glob("*.yaml") if "macros_demo" not in p.name)
SCENES = sorted(p for p in (REPO / "examples" / "scenes").glob("*.yaml") if "scene:" in p.read_text("utf-8"))


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


def test_generate_emits_by_default_and_expands_with_via_xacro(tmp_path):
    spec = REPO / "examples" / "industrial_arm_std_dh.yaml"
    assert gen_robot(spec, "-o", tmp_path / "direct").returncode == 0
    result = gen_robot(spec, "-o", tmp_path / "xacro", "--via-xacro")
    assert result.returncode == 0, result.stderr
    direct = (tmp_path / "direct" / "urdf" / "ur5.urdf").read_text(encoding="utf-8")
    expanded = (tmp_path / "xacro" / "urdf" / "ur5.urdf").read_text(encoding="utf-8")
    assert "emitted directly" in direct.splitlines()[1] and "expanded with xacro" in expanded.splitlines()[1]
    assert urdf_differences(direct, expanded, rel=0.0) == []
    scene = REPO / "examples" / "scenes" / "two_arm_cell.yaml"
    first = xacrokit.generate(scene, tmp_path / "s1")
    second = xacrokit.generate(scene, tmp_path / "s2", via_xacro=True)
    urdf = "urdf/two_arm_cell.urdf"
    emitted, expanded = ({f.path: f.content for f in r.files}[urdf] for r in (first, second))
    assert "emitted directly" in emitted and "expanded with xacro" in expanded
    assert urdf_differences(emitted, expanded, rel=0.0) == []


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


def test_cli_inline_mode_with_a_prefix(tmp_path):
    spec = REPO / "examples" / "diff_drive.yaml"
    assert gen_robot(spec, "-o", tmp_path / "pkg", "--macros", "inline").returncode == 0
    prefixed = xacrokit.expand(tmp_path / "pkg" / "urdf" / "diff_drive.urdf.xacro", {"prefix": "r3_"})
    from lxml import etree

    root = etree.fromstring(prefixed.encode())
    names = [e.get("name") for e in root.iter("link", "joint") if e.getparent() is root]
    assert names and all(n.startswith("r3_") for n in names)
    assert [g.get("reference") for g in root.findall("gazebo") if g.get("reference")][0].startswith("r3_")


@pytest.mark.parametrize("mode", ["copy", "inline"])
def test_the_xacro_command_run_from_the_package_root_gives_the_emitted_urdf(tmp_path, mode):
    # what a user types after generating: a relative path, from the package folder (the DH table file is found
    # relative to the file that names it, not to the working directory), and no comments leaking from macro bodies
    spec = REPO / "examples" / "industrial_arm_std_dh.yaml"
    result = xacrokit.generate(spec, tmp_path / "pkg", macros=mode)
    xacro_command = Path(sys.executable).with_name("xacro")
    expanded = subprocess.run(
        [str(xacro_command), "urdf/ur5.urdf.xacro"], cwd=tmp_path / "pkg", capture_output=True, text=True, timeout=120
    )
    assert expanded.returncode == 0, expanded.stderr
    emitted = (tmp_path / "pkg" / "urdf" / "ur5.urdf").read_text(encoding="utf-8")
    assert urdf_differences(expanded.stdout, emitted, rel=0.0) == []
    body = etree.fromstring(expanded.stdout.encode())
    comments = [c.text for c in body.iter(etree.Comment)]
    assert len(comments) <= 1 and all("Generated by xacrokit" in c for c in comments), comments
    assert result.robot.name == "ur5"


@pytest.mark.parametrize("hardware", ["mock", "gazebo", "none"])
def test_the_inline_entry_file_is_the_robot_macro_written_out(tmp_path, hardware):
    # --macros inline writes the robot out in urdf/NAME.urdf.xacro itself (cheap for xacro); with every argument it
    # must give what calling the NAME macro gives (the copy-mode entry does that)
    for spec in EXAMPLES:
        outputs = []
        for mode in ("inline", "copy"):
            result = xacrokit.generate(spec, tmp_path / spec.stem / mode, macros=mode)
            entry = result.output / "urdf" / f"{result.robot.name}.urdf.xacro"
            packages = {result.robot.package: result.output}
            urdf = expand_file(entry, {"prefix": "r7_", "ros2_control": hardware}, package_paths=packages)
            outputs.append(urdf.replace(str(result.output.resolve()), "PACKAGE"))  # $(find) of each package
        assert urdf_differences(*outputs, rel=0.0) == [], spec.name
        assert "r7_" in outputs[0]
