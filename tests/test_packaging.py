"""The wheel carries the macro library, templates and schemas, and an installed wheel finds them."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import zipfile

import pytest

from conftest import REPO


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    out = tmp_path_factory.mktemp("wheel")
    # built from a copy of the sources: an in-tree build would package what an earlier build left in build/. A
    # symbolic link is copied as a link, not followed: a checkout's link to a virtual environment elsewhere (1.8 GB,
    # 90,000 files) took a minute to copy and as long to delete, and the wheel packages the package folders alone
    source = tmp_path_factory.mktemp("source") / "xacrokit"
    leftovers = shutil.ignore_patterns(
        "build", "dist", ".venv", ".git", "*.egg-info", "__pycache__", ".*_cache", ".hypothesis"
    )
    shutil.copytree(REPO, source, symlinks=True, ignore=leftovers)
    result = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q", "-w", str(out), str(source)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert result.returncode == 0, result.stderr
    (path,) = out.glob("xacrokit-*.whl")
    return path


def test_wheel_contains_the_macro_library_and_data_packages(wheel):
    names = set(zipfile.ZipFile(wheel).namelist())
    for macro in ("inertia", "links", "materials", "wheel", "dh"):
        assert f"xacrokit/macros/{macro}.xacro" in names
    assert "xacrokit/macros/_inc/checks.xacro" in names
    assert "xacrokit/macros/_inc/frames.xacro" in names
    assert "xacrokit/macros/_inc/helpers.xacro" not in names  # (a dead stub, removed)
    assert {"xacrokit/templates/__init__.py", "xacrokit/schemas/__init__.py", "xacrokit/py.typed"} <= names
    assert not any(n.startswith(("generator/", "tests/")) for n in names)
    # every module of every feature folder (a folder left out of pyproject's package list would be missing)
    modules = {"xacrokit/" + p.relative_to(REPO / "generator").as_posix() for p in (REPO / "generator").rglob("*.py")}
    assert len(modules) > 90 and modules <= names, sorted(modules - names)
    assert {"xacrokit/cli/__main__.py", "xacrokit/check/checker.py", "xacrokit/write/outputs.py"} <= names
    three = {f"xacrokit/view/three/{n}" for n in ("three.module.min.js", "OrbitControls.js", "LICENSE")}
    assert three <= names  # (the viewer's three.js, shipped with its licence: no download at run time)
    entry_points = next(n for n in names if n.endswith("entry_points.txt"))
    assert "gen-robot = xacrokit.cli:main" in zipfile.ZipFile(wheel).read(entry_points).decode()


def test_installed_wheel_finds_its_macros_and_expands_the_demo(wheel, tmp_path):
    target = tmp_path / "site"
    subprocess.run(
        [sys.executable, "-m", "pip", "install", "-q", "--no-deps", "--target", str(target), str(wheel)],
        check=True,
        capture_output=True,
        timeout=600,
    )
    script = (
        "import sys, xacrokit; from pathlib import Path\n"
        "assert Path(xacrokit.__file__).is_relative_to(sys.argv[1]), xacrokit.__file__\n"
        "assert xacrokit.macros_dir() == Path(sys.argv[1], 'xacrokit', 'macros'), xacrokit.macros_dir()\n"
        "urdf = xacrokit.expand(sys.argv[2])\n"
        "assert 'arm_link_3' in urdf\n"
        "print('ok')\n"
    )
    env = dict(os.environ, PYTHONPATH=str(target))
    result = subprocess.run(
        [sys.executable, "-c", script, str(target), str(REPO / "examples" / "macros" / "macros_demo.urdf.xacro")],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
        timeout=300,
    )
    assert result.returncode == 0 and result.stdout.strip() == "ok", result.stderr
