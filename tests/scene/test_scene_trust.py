"""A scene's third-party macro is a document from elsewhere: its expressions are guarded unless trusted, through
``gen-robot --trust`` and ``xacrokit.generate(..., trust=True)`` alike."""

from __future__ import annotations

import pytest

import xacrokit
from conftest import XACRO_HEADER, gen_robot

# reaches Python's object graph (harmlessly): refused when untrusted, evaluated (to True) when trusted
MACRO = XACRO_HEADER + (
    '<xacro:macro name="probe_bot" params="prefix parent *origin">'
    "<link name=\"${prefix}base_${python.vars(python.type)['__subclasses__'] is not None}\"/>"
    '<joint name="${prefix}mount" type="fixed"><parent link="${parent}"/>'
    "<child link=\"${prefix}base_${python.vars(python.type)['__subclasses__'] is not None}\"/>"
    '<xacro:insert_block name="origin"/></joint>'
    "</xacro:macro></robot>\n"
)


@pytest.fixture
def scene(tmp_path):
    (tmp_path / "probe_bot.xacro").write_text(MACRO, encoding="utf-8")
    path = tmp_path / "cell.yaml"
    path.write_text(
        "scene: cell\ninstances:\n  p: {xacro: {file: probe_bot.xacro, macro: probe_bot}, prefix: p_, parent: world}\n",
        encoding="utf-8",
    )
    return path


def test_untrusted_by_default_trusted_on_request(scene, tmp_path):
    with pytest.raises(xacrokit.SpecErrors, match="refused to evaluate"):
        xacrokit.generate(scene, tmp_path / "pkg", dry_run=True)
    result = xacrokit.generate(scene, tmp_path / "pkg", trust=True)
    urdf = (tmp_path / "pkg" / "urdf" / "cell.urdf").read_text(encoding="utf-8")
    assert 'link name="p_base_True"' in urdf and result.model.name == "cell"


def test_the_command_line_alike(scene, tmp_path):
    refused = gen_robot(scene, "-o", tmp_path / "a", "--dry-run")
    assert refused.returncode == 2 and "refused to evaluate" in refused.stderr, refused.stderr
    trusted = gen_robot(scene, "-o", tmp_path / "b", "--trust")
    assert trusted.returncode == 0, trusted.stderr
    assert 'link name="p_base_True"' in (tmp_path / "b" / "urdf" / "cell.urdf").read_text(encoding="utf-8")
