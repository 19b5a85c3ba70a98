"""The package's extension file (issue 19, item 2): urdf/NAME_extension.xacro is the user's. gen-robot writes it
once, when it is missing, and then never rewrites it, never reports it as a conflict, never removes it; the robot's
macro includes it and calls its macro with the prefix, so what the user adds reaches the entry, fleets and scenes,
and urdf/NAME.urdf is expanded with it (by xacro, as soon as it holds anything)."""

from __future__ import annotations

import json

from conftest import REPO, gen_robot
from xacrokit.expansion.xacro_expand import expand_file

SPEC = REPO / "examples" / "robots" / "two_dof_arm.yaml"
ADDED = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="two_dof_arm_extension" params="prefix">
    <gazebo reference="${prefix}upper_arm"><mu1>0.3</mu1></gazebo>
  </xacro:macro>
</robot>
"""


def test_the_extension_is_written_once_and_then_left_to_its_owner(tmp_path):
    package = tmp_path / "pkg"
    assert gen_robot(SPEC, "-o", package).returncode == 0
    extension = package / "urdf" / "two_dof_arm_extension.xacro"
    assert "YOURS" in extension.read_text(encoding="utf-8")
    manifest = json.loads((package / ".xacrokit-manifest.json").read_text(encoding="utf-8"))
    assert not any("extension" in path for path in json.dumps(manifest).split('"'))  # (not ours to track)
    extension.write_text(ADDED, encoding="utf-8")
    again = gen_robot(SPEC, "-o", package)
    assert again.returncode == 0, again.stderr  # (no conflict)
    assert extension.read_text(encoding="utf-8") == ADDED
    urdf = expand_file(package / "urdf" / "two_dof_arm.urdf.xacro", {"prefix": "a_"})
    assert '<gazebo reference="a_upper_arm">' in urdf and "<mu1>0.3</mu1>" in urdf
    plain = (package / "urdf" / "two_dof_arm.urdf").read_text(encoding="utf-8")
    assert '<gazebo reference="upper_arm">' in plain  # (urdf/NAME.urdf: expanded with the owner's extension)
    extension.unlink()
    assert gen_robot(SPEC, "-o", package).returncode == 0
    assert "YOURS" in extension.read_text(encoding="utf-8")  # (missing: written again)


def test_every_instance_of_a_fleet_calls_the_extension_with_its_prefix(tmp_path):
    result = gen_robot("fleet", SPEC, "--count", "2", "-o", tmp_path / "fleet")
    assert result.returncode == 0, result.stderr
    (extension,) = (tmp_path / "fleet" / "robots").glob("*/urdf/two_dof_arm_extension.xacro")
    extension.write_text(ADDED, encoding="utf-8")
    result = gen_robot("fleet", SPEC, "--count", "2", "-o", tmp_path / "fleet")
    assert result.returncode == 0, result.stderr
    assert extension.read_text(encoding="utf-8") == ADDED
    (urdf,) = (tmp_path / "fleet" / "urdf").glob("*.urdf")
    text = urdf.read_text(encoding="utf-8")
    assert '<gazebo reference="r0_upper_arm">' in text and '<gazebo reference="r1_upper_arm">' in text


def test_a_specs_extension_is_copied_verbatim(tmp_path):
    """What gen-robot import keeps (a vendor's <gazebo>, with its own names) must not be evaluated by xacro."""
    spec = tmp_path / "arm.yaml"
    spec.write_text(SPEC.read_text(encoding="utf-8") + "extension: added.xacro\n", encoding="utf-8")
    (tmp_path / "added.xacro").write_text(
        '<robot><gazebo reference="upper_arm"><plugin name="p" filename="x"><arg>${not_ours}</arg></plugin>'
        "</gazebo></robot>",
        encoding="utf-8",
    )
    result = gen_robot(spec, "-o", tmp_path / "pkg")
    assert result.returncode == 0, result.stderr
    urdf = (tmp_path / "pkg" / "urdf" / "two_dof_arm.urdf").read_text(encoding="utf-8")
    assert "<arg>${not_ours}</arg>" in urdf and '<gazebo reference="upper_arm">' in urdf


def test_a_bad_extension_is_a_located_spec_error_and_nothing_is_written(tmp_path):
    base = SPEC.read_text(encoding="utf-8")
    (tmp_path / "bad.xacro").write_text("<robot><gazebo></robot>", encoding="utf-8")
    (tmp_path / "other.xacro").write_text("<sdf/>", encoding="utf-8")
    (tmp_path / "notes.txt").write_text("<robot/>", encoding="utf-8")
    (tmp_path / "sly.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:include filename="/etc/passwd"/></robot>',
        encoding="utf-8",
    )
    for name, said in (
        ("gone.xacro", "cannot read 'gone.xacro'"),
        ("../outside.xacro", "in the spec's folder or below"),
        ("notes.txt", "in the spec's folder or below"),
        ("bad.xacro", "bad.xacro:1:"),
        ("other.xacro", "not <robot>"),
        ("sly.xacro", "sly.xacro:1: a xacro element or attribute"),
    ):
        spec = tmp_path / "arm.yaml"
        spec.write_text(base + f"extension: {name}\n", encoding="utf-8")
        result = gen_robot(spec, "-o", tmp_path / "out")
        assert result.returncode == 2 and said in result.stderr and "arm.yaml:" in result.stderr, (name, result.stderr)
        assert not (tmp_path / "out").exists()


def test_an_extension_reached_through_a_symbolic_link_is_not_read(tmp_path):
    package = tmp_path / "pkg"
    assert gen_robot(SPEC, "-o", package).returncode == 0
    elsewhere = tmp_path / "elsewhere.xacro"
    elsewhere.write_text(ADDED, encoding="utf-8")
    extension = package / "urdf" / "two_dof_arm_extension.xacro"
    extension.unlink()
    extension.symlink_to(elsewhere)
    before = (package / "urdf" / "two_dof_arm.urdf").read_text(encoding="utf-8")
    result = gen_robot(SPEC, "-o", package)
    assert result.returncode == 2 and "refusing to write urdf/two_dof_arm_extension.xacro" in result.stderr
    assert "resolves outside" in result.stderr  # (the write stage's rule for every file of the package)
    assert (package / "urdf" / "two_dof_arm.urdf").read_text(encoding="utf-8") == before  # (nothing written)
    assert extension.is_symlink() and elsewhere.read_text(encoding="utf-8") == ADDED  # (not read, not written)
