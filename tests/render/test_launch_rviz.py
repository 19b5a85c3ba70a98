"""The generated launch file is Python that starts what it says; RViz's fixed frame follows the prefix argument."""

from __future__ import annotations

import ast
import os

import pytest
import yaml
from lxml import etree

import xacrokit
from conftest import REPO

SPEC = REPO / "examples" / "robots" / "two_dof_arm.yaml"


def test_generated_launch_file_is_python(tmp_path):
    result = xacrokit.generate(SPEC, tmp_path / "pkg")
    launch = {f.path: f.content for f in result.files}["launch/display.launch.py"]
    compile(launch, "display.launch.py", "exec")
    assert os.path.exists(tmp_path / "pkg" / "launch" / "display.launch.py")


def node_arguments(launch: str, package: str) -> list[ast.expr]:
    """The ``arguments=[...]`` elements of the one ``Node(package=PACKAGE, ...)`` call of a launch file."""
    calls = [
        node
        for node in ast.walk(ast.parse(launch))
        if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "Node"
        for keyword in node.keywords
        if keyword.arg == "package" and isinstance(keyword.value, ast.Constant) and keyword.value.value == package
    ]
    assert len(calls) == 1, f"{len(calls)} Node calls for {package}"
    (arguments,) = [k.value for k in calls[0].keywords if k.arg == "arguments"]
    assert isinstance(arguments, ast.List)
    return arguments.elts


def root_link(urdf: str) -> str:
    root = etree.fromstring(urdf.encode())
    children = {j.find("child").get("link") for j in root.findall("joint")}
    (name,) = [e.get("name") for e in root.findall("link") if e.get("name") not in children]
    return name


@pytest.mark.parametrize("example", ["two_dof_arm", "diff_drive", "humanoid_upper_body"])
def test_rviz_fixed_frame_follows_the_prefix_launch_argument(tmp_path, example):
    result = xacrokit.generate(REPO / "examples" / "robots" / f"{example}.yaml", tmp_path / "pkg")
    files = {f.path: f.content for f in result.files}
    name = result.name
    launch = files["launch/display.launch.py"]
    compile(launch, "display.launch.py", "exec")
    root = root_link(files[f"urdf/{name}.urdf"])
    assert root == result.model.root
    arguments = node_arguments(launch, "rviz2")
    flags = [a.value for a in arguments if isinstance(a, ast.Constant)]
    assert flags.count("-f") == 1 and "-d" in flags
    frame = arguments[[getattr(a, "value", None) for a in arguments].index("-f") + 1]
    # [LaunchConfiguration("prefix"), "ROOT"]: launch concatenates a list of substitutions into one argument
    assert isinstance(frame, ast.List) and len(frame.elts) == 2
    prefix, link = frame.elts
    assert isinstance(prefix, ast.Call) and prefix.func.id == "LaunchConfiguration"
    assert [a.value for a in prefix.args] == ["prefix"]
    assert isinstance(link, ast.Constant) and link.value == root
    declared = [
        node.args[0].value
        for node in ast.walk(ast.parse(launch))
        if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "DeclareLaunchArgument"
    ]
    assert "prefix" in declared
    # without a prefix the .rviz file agrees with the launch file (it is what rviz2 -d alone shows)
    rviz = yaml.safe_load(files[f"rviz/{name}.rviz"])
    assert rviz["Visualization Manager"]["Global Options"]["Fixed Frame"] == root
