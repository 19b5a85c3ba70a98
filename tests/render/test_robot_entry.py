"""The robot package's xacro files: the entry is its arguments and one call of the robot macro (as UR's entry is), the
robot is written once, in NAME_macro.xacro, and its plain link/joint XML is the direct emitter's in every mode."""

from __future__ import annotations

import pytest
from lxml import etree

import xacrokit
from conftest import ROBOT_EXAMPLES
from xacrokit.emit import joint_element, link_element, urdf_differences
from xacrokit.expansion.xacro_expand import expand_file
from xacrokit.pipeline import build_robot
from xacrokit.render import render_package, simple_shape_link
from xacrokit.render.control import controllers

EXAMPLES = ROBOT_EXAMPLES
XACRO = "{http://www.ros.org/wiki/xacro}"
MODES = ("inline", "copy", "find")


@pytest.mark.parametrize("mode", MODES)
def test_the_entry_is_the_arguments_and_one_macro_call(mode):
    for spec in EXAMPLES:
        robot = build_robot(spec)
        files = {f.path: f.content for f in render_package(robot, macros=mode)}
        entry = etree.fromstring(files[f"urdf/{robot.name}.urdf.xacro"].encode())
        children = [e for e in entry if isinstance(e.tag, str)]
        driven = controllers(robot)["drive"] is not None  # (a diff drive's cmd_vel remap: one argument more)
        names = ["prefix", "ros2_control", "controllers", "world"] + ["cmd_vel"] * driven
        tags = [f"{XACRO}arg"] * len(names) + [f"{XACRO}include", f"{XACRO}if", f"{XACRO}{robot.name}"]
        assert [e.tag for e in children] == tags, spec
        assert [e.get("name") for e in children[: len(names)]] == names
        include, world, call = children[len(names) :]
        assert include.get("filename") == f"{robot.name}_macro.xacro"
        assert world.get("value") == "$(arg world)" and [e.tag for e in world] == ["link"]
        assert world[0].get("name") == "world"  # (world:=true: the link a simulator fixes the root to)
        assert call.attrib == {
            "prefix": "$(arg prefix)",
            "parent": "${'world' if '$(arg world)' in ('true', 'True', '1') else ''}",
            "ros2_control": "$(arg ros2_control)",
            "controllers": "$(arg controllers)",
            **({"cmd_vel": "$(arg cmd_vel)"} if driven else {}),
        }
        assert len(entry.findall(".//link")) == 1 and not entry.findall(".//joint") and not entry.findall(".//material")
        assert len(entry.findall(f".//{XACRO}{robot.name}")) == 1  # exactly one macro call


@pytest.mark.parametrize("mode", MODES)
def test_the_robot_is_written_once_in_its_macro_file(mode):
    for spec in EXAMPLES:
        robot = build_robot(spec)
        files = {f.path: f.content for f in render_package(robot, macros=mode)}
        macro_file = f"urdf/{robot.name}_macro.xacro"
        for path, text in files.items():
            if path.endswith(".xacro") and path != macro_file and not path.startswith("urdf/xacrokit/"):
                root = etree.fromstring(text.encode())
                body = [e for e in root.iter("link", "joint") if e.getparent().tag != "ros2_control"]
                body = [e for e in body if e.getparent().tag != f"{XACRO}if" or e.get("name") != "world"]
                assert not body, (spec.name, path)  # (a ros2_control block names its joints, it does not make them;
                # the entry's world link, with world:=true, is the simulator's, not the robot's)
        macro = etree.fromstring(files[macro_file].encode())
        (definition,) = macro.findall(f"{XACRO}macro[@name='{robot.name}']")
        mount = definition.find(f"{XACRO}if/joint")
        assert mount.get("name") == "${prefix}" + robot.mount_joint_name
        written = {e.get("name") for e in definition.iter("link", "joint")} - {mount.get("name")}
        if mode == "inline":
            assert written == {"${prefix}" + n for n in (*robot.link_names, *robot.joint_names)}, spec.name


@pytest.mark.parametrize("mode", ["copy", "find"])
def test_library_modes_take_their_plain_links_and_joints_from_the_emitter(mode):
    """Spec links no library macro makes, and the spec's joints, are the emitter's elements (with the literal prefix
    ${prefix}); the rest are calls of box_link/cylinder_link/sphere_link, dh_arm and wheel."""
    for spec in EXAMPLES:
        robot = build_robot(spec)
        text = {f.path: f.content for f in render_package(robot, macros=mode)}[f"urdf/{robot.name}_macro.xacro"]
        definition = etree.fromstring(text.encode()).find(f"{XACRO}macro[@name='{robot.name}']")
        plain = {e.get("name"): e for e in definition if isinstance(e.tag, str) and e.tag in ("link", "joint")}
        wanted = [link_element(robot, "${prefix}", link) for link in robot.links if not simple_shape_link(link)]
        wanted += [joint_element("${prefix}", joint) for joint in robot.joints]
        assert sorted(plain) == sorted(e.get("name") for e in wanted), spec.name
        for element in wanted:
            written = etree.tostring(plain[element.get("name")], encoding="unicode")
            assert urdf_differences(written, etree.tostring(element, encoding="unicode"), rel=0.0) == [], spec.name
        calls = [e.tag.removeprefix(XACRO) for e in definition if isinstance(e.tag, str) and e.tag.startswith(XACRO)]
        shape_calls = [c for c in calls if c.endswith("_link")]
        assert sorted(shape_calls) == sorted(m for link in robot.links if (m := simple_shape_link(link)))
        assert calls.count("dh_arm") == len(robot.arms) and calls.count("wheel") == len(robot.wheels)


@pytest.fixture(scope="module")
def generated(tmp_path_factory):
    """Every example's package with the inline and with the copy macro, generated once in a test process for the
    three hardware arguments below (which only expand them)."""
    folder = tmp_path_factory.mktemp("modes")
    return {
        (spec, mode): xacrokit.generate(spec, folder / spec.stem / mode, macros=mode)
        for spec in EXAMPLES
        for mode in ("inline", "copy")
    }


@pytest.mark.parametrize("hardware", ["mock", "gazebo", "none"])
def test_every_macro_mode_gives_the_same_robot_with_every_argument(generated, hardware):
    # the inline macro (plain XML computed by gen-robot) and the copy macro (library macro calls) describe the same
    # robot whatever the entry's arguments
    for spec in EXAMPLES:
        outputs = []
        for mode in ("inline", "copy"):
            result = generated[spec, mode]
            entry = result.output / "urdf" / f"{result.name}.urdf.xacro"
            packages = {result.package: result.output}
            urdf = expand_file(entry, {"prefix": "r7_", "ros2_control": hardware}, package_paths=packages)
            outputs.append(urdf.replace(str(result.output.resolve()), "PACKAGE"))  # $(find) of each package
        assert urdf_differences(*outputs, rel=0.0) == [], spec.name
        assert "r7_" in outputs[0]
