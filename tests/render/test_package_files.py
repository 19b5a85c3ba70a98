"""The ROS files of a generated package: launch arguments and nodes, dependencies, install rules."""

from __future__ import annotations

import ast
import shutil
import subprocess

import pytest
from lxml import etree

import xacrokit
from conftest import REPO
from xacrokit.model import Scene

EXAMPLES = REPO / "examples"


def launch_calls(text: str) -> list[ast.Call]:
    return [n for n in ast.walk(ast.parse(text)) if isinstance(n, ast.Call)]


def keyword(call: ast.Call, name: str):
    return next((ast.literal_eval(k.value) for k in call.keywords if k.arg == name), None)


@pytest.mark.parametrize(
    ("spec", "launch"),
    [
        (EXAMPLES / "robots" / "diff_drive.yaml", "launch/display.launch.py"),
        (EXAMPLES / "scenes" / "two_arm_cell.yaml", None),
    ],
)
def test_without_the_gui_a_joint_state_publisher_still_gives_every_joint_a_state(tmp_path, spec, launch):
    result = xacrokit.generate(spec, tmp_path / "pkg")
    text = (tmp_path / "pkg" / (launch or "launch/display.launch.py")).read_text(encoding="utf-8")
    nodes = {keyword(c, "executable"): c for c in launch_calls(text) if getattr(c.func, "id", None) == "Node"}
    for executable, condition in (("joint_state_publisher_gui", "IfCondition"), ("joint_state_publisher", "Unless")):
        guard = next(k.value for k in nodes[executable].keywords if k.arg == "condition")
        assert guard.func.id.startswith(condition), executable
    arguments = {
        keyword(c, "name") or ast.literal_eval(c.args[0]): c
        for c in launch_calls(text)
        if getattr(c.func, "id", None) == "DeclareLaunchArgument"
    }
    assert keyword(arguments["gui"], "choices") == ["true", "false"]
    hardware = keyword(arguments["ros2_control"], "choices")
    assert hardware == (["mock", "none"] if isinstance(result.model, Scene) else ["mock", "gazebo", "none"])
    package = etree.parse(str(tmp_path / "pkg" / "package.xml")).getroot()
    assert {"joint_state_publisher", "joint_state_publisher_gui"} <= {e.text for e in package.iter("exec_depend")}


@pytest.mark.skipif(shutil.which("cmake") is None, reason="cmake is not installed")
def test_meshes_added_after_the_first_build_are_installed(tmp_path):
    """install(DIRECTORY meshes ... OPTIONAL) is decided at install time; if(EXISTS) would be decided at configure."""
    xacrokit.generate(EXAMPLES / "robots" / "two_dof_arm.yaml", tmp_path / "pkg")
    text = (tmp_path / "pkg" / "CMakeLists.txt").read_text(encoding="utf-8")
    # the same install rules without ament (not installed here): configure, install, add meshes, install again
    rules = "\n".join(line for line in text.splitlines() if line.startswith("install("))
    (tmp_path / "src").mkdir()
    for folder in (tmp_path / "pkg").iterdir():  # (every folder the package has: urdf, launch, config, worlds, ...)
        if folder.is_dir():
            shutil.copytree(folder, tmp_path / "src" / folder.name)
    (tmp_path / "src" / "CMakeLists.txt").write_text(f"cmake_minimum_required(VERSION 3.8)\nproject(p NONE)\n{rules}\n")
    prefix = tmp_path / "install"

    def run(*words):
        subprocess.run(words, check=True, capture_output=True, cwd=tmp_path)

    run("cmake", "-S", "src", "-B", "build", f"-DCMAKE_INSTALL_PREFIX={prefix}")
    run("cmake", "--install", "build")
    assert not (prefix / "share" / "p" / "meshes").exists()
    (tmp_path / "src" / "meshes").mkdir()
    (tmp_path / "src" / "meshes" / "arm.stl").write_text("solid arm\nendsolid arm\n")
    run("cmake", "--install", "build")  # no new configure, as colcon would not run one
    assert (prefix / "share" / "p" / "meshes" / "arm.stl").is_file()
