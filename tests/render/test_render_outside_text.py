"""Text from outside (the spec's file name) in every generated file: whatever the name holds (newlines, quotes, --,
$, control characters), every file parses with its own parser and says what it says for a plain name. A newline in
the name once put a Python statement into the launch file and a CMake command into CMakeLists.txt; a -- made
package.xml and every xacro file ill-formed."""

from __future__ import annotations

import ast
import re

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from lxml import etree

from conftest import ROBOT_EXAMPLES, SCENE_EXAMPLES
from xacrokit.load import load_file
from xacrokit.pipeline import build_robot
from xacrokit.render import render_package, render_scene
from xacrokit.scene import build_scene
from xacrokit.testing import HOSTILE_FILE_NAMES, hostile_file_names

NASTY = HOSTILE_FILE_NAMES
names = hostile_file_names()


def cmake_commands(text: str) -> list[str]:
    """CMake's command invocations with comments (line and bracket) removed: what cmake would run."""
    text = re.sub(r"#\[(=*)\[.*?\]\1\]", "", text, flags=re.S)  # bracket comments
    text = re.sub(r"#[^\n]*", "", text)  # line comments (our files quote no #)
    return re.findall(r"(?m)^\s*([A-Za-z_][A-Za-z0-9_]*)\s*\(", text)


def parsed(path: str, content: str) -> object:
    """The file read by its own parser, with the parts a spec's name may fill (comments, the README) left out."""
    if path.endswith(".py"):
        return ast.dump(ast.parse(content))  # (comments are not in the tree)
    if path.endswith("CMakeLists.txt"):
        return cmake_commands(content)
    if path.endswith((".xml", ".xacro", ".urdf")):
        parser = etree.XMLParser(remove_comments=True, resolve_entities=False, no_network=True)
        return etree.tostring(etree.fromstring(content.encode("utf-8"), parser))
    if path.endswith((".yaml", ".rviz")):
        return yaml.safe_load(content)
    assert path.endswith(".md"), path
    return None  # Markdown: anything parses


@pytest.fixture(scope="module")
def models():
    robot = build_robot(next(p for p in ROBOT_EXAMPLES if p.stem == "diff_drive"))
    scene = build_scene(load_file(next(p for p in SCENE_EXAMPLES if p.stem == "two_arm_cell")))
    plain = {
        "robot": {f.path: parsed(f.path, f.content) for f in render_package(robot, spec_name="plain.yaml")},
        "scene": {f.path: parsed(f.path, f.content) for f in render_scene(scene, spec_name="plain.yaml")},
    }
    return robot, scene, plain


@settings(max_examples=40, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(name=names)
def test_any_file_name_leaves_every_generated_file_as_a_plain_name_does(models, name):
    robot, scene, plain = models
    for kind, files in (
        ("robot", render_package(robot, spec_name=name)),
        ("scene", render_scene(scene, spec_name=name)),
    ):
        assert {f.path for f in files} == set(plain[kind])
        for file in files:
            assert file.content.encode("utf-8")  # (a lone surrogate would not encode)
            assert parsed(file.path, file.content) == plain[kind][file.path], (kind, file.path)


def test_the_published_injections_stay_comments():
    """The two injections the fuzzing run found, written out: the statement and the command are not code."""
    robot = build_robot(next(p for p in ROBOT_EXAMPLES if p.stem == "diff_drive"))
    files = {f.path: f.content for f in render_package(robot, spec_name="x.yaml\nimport os; os.system('id')")}
    launch = ast.parse(files["launch/display.launch.py"])
    assert not any(isinstance(node, ast.Import) and node.names[0].name == "os" for node in ast.walk(launch))
    files = {f.path: f.content for f in render_package(robot, spec_name="x.yaml\nmessage(FATAL_ERROR boom)")}
    assert "message" not in cmake_commands(files["CMakeLists.txt"])
