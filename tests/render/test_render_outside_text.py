"""Text from outside (the spec's file name) in every generated file: whatever the name holds (newlines, quotes, --,
$, control characters), every file parses with its own parser and says what it says for a plain name. A newline in
the name once put a Python statement into the launch file and a CMake command into CMakeLists.txt; a -- made
package.xml and every xacro file ill-formed."""

from __future__ import annotations

import ast

import pytest
from hypothesis import HealthCheck, given, settings

from conftest import ROBOT_EXAMPLES, SCENE_EXAMPLES, budget, cmake_commands, parse_generated
from xacrokit.load import load_file
from xacrokit.pipeline import build_robot
from xacrokit.render import render_package, render_scene
from xacrokit.scene import build_scene
from xacrokit.testing import HOSTILE_FILE_NAMES, hostile_file_names

NASTY = HOSTILE_FILE_NAMES
names = hostile_file_names()


@pytest.fixture(scope="module")
def models():
    robot = build_robot(next(p for p in ROBOT_EXAMPLES if p.stem == "diff_drive"))
    scene = build_scene(load_file(next(p for p in SCENE_EXAMPLES if p.stem == "two_arm_cell")))
    plain = {
        "robot": {f.path: parse_generated(f.path, f.content) for f in render_package(robot, spec_name="plain.yaml")},
        "scene": {f.path: parse_generated(f.path, f.content) for f in render_scene(scene, spec_name="plain.yaml")},
    }
    return robot, scene, plain


# budget: 40 hostile names, more than the default: rendering two packages takes 0.2 s and the name is all that varies
@settings(max_examples=budget(40), suppress_health_check=[HealthCheck.function_scoped_fixture])
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
            assert parse_generated(file.path, file.content) == plain[kind][file.path], (kind, file.path)


def test_the_published_injections_stay_comments():
    """The two injections the fuzzing run found, written out: the statement and the command are not code."""
    robot = build_robot(next(p for p in ROBOT_EXAMPLES if p.stem == "diff_drive"))
    files = {f.path: f.content for f in render_package(robot, spec_name="x.yaml\nimport os; os.system('id')")}
    launch = ast.parse(files["launch/display.launch.py"])
    assert not any(isinstance(node, ast.Import) and node.names[0].name == "os" for node in ast.walk(launch))
    files = {f.path: f.content for f in render_package(robot, spec_name="x.yaml\nmessage(FATAL_ERROR boom)")}
    assert "message" not in cmake_commands(files["CMakeLists.txt"])


@pytest.mark.parametrize(
    ("spec_name", "command"),
    [
        ("my robot.yaml", "gen-robot 'my robot.yaml'"),
        ("a\\b.yaml", "gen-robot 'a\\b.yaml'"),  # (a backslash is written once: the command runs as shown)
        ("it's.yaml", "gen-robot 'it'\"'\"'s.yaml'"),
        ("x`y.yaml", "gen-robot 'x\\x60y.yaml'"),  # (a backtick would end the code span: escaped, not runnable)
    ],
)
def test_the_readme_command_is_the_command_to_run(spec_name, command):
    robot = build_robot(next(p for p in ROBOT_EXAMPLES if p.stem == "two_dof_arm"))
    readme = next(f.content for f in render_package(robot, spec_name=spec_name) if f.path == "README.md")
    assert f"run `{command}` again" in readme, readme[:400]
    if "`" not in spec_name:
        import shlex

        assert shlex.split(command) == ["gen-robot", spec_name]
