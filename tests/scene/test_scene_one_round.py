"""A scene's mistakes come in one round, each located, with "did you mean" for mistyped names: a missing spec file,
an unknown instance and a mistyped link once took three runs to find."""

from __future__ import annotations

import pytest
from scene_helpers import scene_file

import xacrokit
from conftest import REPO

UR5 = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
ARM = REPO / "examples" / "robots" / "two_dof_arm.yaml"


def errors_of(path, tmp_path):
    with pytest.raises(xacrokit.SpecErrors) as caught:
        xacrokit.generate(path, tmp_path / "pkg", dry_run=True)
    return {e.path: e for e in caught.value.errors}


def test_every_mistake_of_a_scene_in_one_round(tmp_path):
    path = scene_file(
        tmp_path,
        {
            "arm": {"spec": str(UR5), "prefix": "arm_", "parent": "wrld"},
            "gripper": {"spec": str(ARM), "prefix": "g_", "parent": "arm/tool_0"},
            "cam": {"spec": "missing.yaml", "prefix": "c_", "parent": "world"},
            "stand": {"spec": str(ARM), "prefix": "s_", "parent": "armm/base_link"},
            "lamp": {"spec": str(ARM), "prefix": "l_", "parent": "cam/base_link"},  # on the missing one: no cascade
        },
    )
    errors = errors_of(path, tmp_path)
    assert sorted(errors) == [
        "$.instances.arm.parent",
        "$.instances.cam.spec",
        "$.instances.gripper.parent",
        "$.instances.stand.parent",
    ]
    assert (
        "parent 'wrld' must be 'world' or INSTANCE/LINK (did you mean 'world'?)"
        in errors["$.instances.arm.parent"].message
    )
    assert (
        "'tool_0' is not a link of instance 'arm' (did you mean 'tool0'?)"
        in errors["$.instances.gripper.parent"].message
    )
    assert "instance 'armm' is not in this scene (did you mean 'arm'?)" in errors["$.instances.stand.parent"].message
    assert "no robot spec at" in errors["$.instances.cam.spec"].message
    assert all(e.line is not None and e.column is not None for e in errors.values())
    assert not (tmp_path / "pkg").exists()


def test_a_wrong_parent_and_a_clash_in_one_round(tmp_path):
    path = scene_file(
        tmp_path,
        {
            "a": {"spec": str(ARM), "prefix": "r_", "parent": "world"},
            "b": {"spec": str(ARM), "prefix": "r_", "parent": "world"},
            "c": {"spec": str(ARM), "prefix": "c_", "parent": "a/nothing"},
        },
    )
    errors = errors_of(path, tmp_path)
    assert sorted(errors) == ["$.instances.b", "$.instances.c.parent"]
