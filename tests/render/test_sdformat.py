"""Debian's sdformat as a consumer (issue 32, item 4): `ign sdf -p` converts a URDF the way Gazebo does when it
spawns a robot. Every example's and scene's URDF, expanded with ros2_control:=gazebo, converts without an error; the
SDF keeps the gz_ros2_control plugin and every sensor the URDF's <gazebo> blocks declare, with its type; every mesh
URI it names is found below the installed package's share folder (model://PKG/... as GZ_SIM_RESOURCE_PATH finds it,
through the model path the package exports); and every worlds/*.sdf passes `ign sdf -k`. Skipped without the tools
(.ci/run installs ignition-tools, libsdformat-dev and sdformat-sdf as root)."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest
from lxml import etree

import xacrokit
from conftest import ROBOT_EXAMPLES, SCENE_EXAMPLES
from xacrokit.expansion.xacro_expand import expand_file

IGN = shutil.which("ign")
pytestmark = pytest.mark.skipif(IGN is None, reason="Debian's ignition-tools (ign sdf) is not installed")


def _ign(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([IGN or "ign", "sdf", *args], capture_output=True, text=True, timeout=120)


def _said(result: subprocess.CompletedProcess) -> str:
    """stderr without the library's note that it has no backtrace helper."""
    return "\n".join(line for line in result.stderr.splitlines() if "ignition-tools-backward" not in line)


@pytest.mark.parametrize("example", [*ROBOT_EXAMPLES, *SCENE_EXAMPLES], ids=lambda p: p.stem)
def test_sdformat_converts_every_example_with_its_plugin_sensors_and_meshes(example, tmp_path):
    result = xacrokit.generate(example, tmp_path / "pkg")
    name, package = result.model.name, result.model.package
    share = tmp_path / "share" / package
    share.parent.mkdir()
    (tmp_path / "pkg").rename(share)
    urdf_text = expand_file(
        share / "urdf" / f"{name}.urdf.xacro", {"ros2_control": "gazebo"}, package_paths={package: str(share)}
    )
    urdf = tmp_path / f"{name}.urdf"
    urdf.write_text(urdf_text, encoding="utf-8")
    converted = _ign("-p", str(urdf))
    assert converted.returncode == 0 and "Error" not in _said(converted), _said(converted)
    sdf, described = etree.fromstring(converted.stdout.encode("utf-8")), etree.fromstring(urdf_text.encode())
    plugins = [p.get("filename") for p in sdf.iter("plugin")]
    if described.find("ros2_control") is not None:  # (a robot with ros2_control runs it through the plugin)
        assert "gz_ros2_control-system" in plugins
    assert {p.get("filename") for p in described.iterfind("gazebo/plugin")} <= set(plugins)
    declared = {(s.get("name"), s.get("type")) for s in described.iterfind("gazebo/sensor")}
    kept = {(s.get("name"), s.get("type")) for s in sdf.iter("sensor")}
    assert declared <= kept, declared - kept
    manifest = etree.parse(str(share / "package.xml")).getroot()
    model_paths = [
        Path(e.get("gazebo_model_path").replace("${prefix}", str(share)))
        for e in manifest.iterfind("export/gazebo_ros")
    ]
    for uri in {u.text.strip() for u in sdf.iter("uri") if u.text and "://" in u.text}:
        assert uri.startswith(f"model://{package}/"), uri
        assert any((root / uri.removeprefix("model://")).is_file() for root in model_paths), uri


@pytest.mark.parametrize("example", [*ROBOT_EXAMPLES, *SCENE_EXAMPLES], ids=lambda p: p.stem)
def test_every_world_passes_sdformats_check(example, tmp_path):
    xacrokit.generate(example, tmp_path / "pkg")
    worlds = sorted((tmp_path / "pkg" / "worlds").glob("*.sdf"))
    assert worlds
    for world in worlds:
        checked = _ign("-k", str(world))
        assert checked.returncode == 0 and "Valid." in checked.stdout, _said(checked) + checked.stdout
