"""The --macros modes: the default package needs no macro library; find mode includes the installed one."""

from __future__ import annotations

import xacrokit
from conftest import REPO, gen_robot

SPEC = REPO / "examples" / "robots" / "two_dof_arm.yaml"


def test_the_default_package_needs_no_macro_library(tmp_path):
    # inline by default: plain links and joints, no copied macros, no DH tables for xacro to read
    arm = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
    result = gen_robot(arm, "-o", tmp_path / "pkg")
    assert result.returncode == 0, result.stderr
    paths = {p.relative_to(tmp_path / "pkg").as_posix() for p in (tmp_path / "pkg").rglob("*") if p.is_file()}
    assert not any(p.startswith("urdf/xacrokit/") or p.endswith(".dh.yaml") for p in paths), paths
    macro = (tmp_path / "pkg" / "urdf" / "ur5_macro.xacro").read_text(encoding="utf-8")
    assert "xacrokit/" not in macro and "<xacro:dh_arm" not in macro
    assert '<link name="${prefix}shoulder_link">' in macro


def test_macros_find_includes_the_installed_library(tmp_path):
    out = tmp_path / "pkg"
    result = xacrokit.generate(SPEC, out, macros="find", via_xacro=True)  # xacro must find the installed library
    macro = (out / "urdf" / "two_dof_arm_macro.xacro").read_text(encoding="utf-8")
    assert '<xacro:include filename="$(find xacrokit)/macros/inertia.xacro"/>' in macro
    assert not (out / "urdf" / "xacrokit").exists()
    assert "<exec_depend>xacrokit</exec_depend>" in (out / "package.xml").read_text(encoding="utf-8")
    copy = xacrokit.generate(SPEC, tmp_path / "copy", macros="copy", via_xacro=True)
    urdf = {f.path: f.content for f in copy.files}["urdf/two_dof_arm.urdf"]
    assert {f.path: f.content for f in result.files}["urdf/two_dof_arm.urdf"] == urdf
