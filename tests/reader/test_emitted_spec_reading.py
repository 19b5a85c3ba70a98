"""The kinematics commands read a spec as the URDF `gen-robot SPEC` writes (the direct emitter: no template
rendered, no xacro run; issue 45, item 2): the same robot, to the last digit, as its package expanded with xacro, on
an arm, a mobile robot and a scene, and the same answers on the command line as the expanded package's URDF gives."""

from __future__ import annotations

import pytest

import xacrokit
from conftest import REPO, ROBOT_EXAMPLES, SCENE_EXAMPLES, gen_robot
from xacrokit.emit import urdf_differences
from xacrokit.reader.read_robot import read_robot

# (tests/emit/test_emit.py expands every example and random specs both ways; here the reader's two ways, on an arm, a
# mobile robot and a scene)
READ = [p for p in [*ROBOT_EXAMPLES, *SCENE_EXAMPLES] if p.stem in ("ur10e", "diff_drive", "two_arm_cell")]


@pytest.mark.parametrize("spec", READ, ids=lambda p: p.stem)
def test_a_spec_read_as_generated_is_the_robot_its_package_expands_to(spec):
    assert len(READ) == 3  # (examples renamed: choose again)
    expanded, generated = read_robot(spec), read_robot(spec, emitted=True)
    assert urdf_differences(expanded.text, generated.text, rel=0.0) == []
    assert "expanded with xacro" not in generated.text and expanded.text != generated.text  # (read the two ways)
    assert (generated.kind, generated.lines, generated.warnings) == (expanded.kind, expanded.lines, expanded.warnings)
    assert [j.name for j in generated.view.joints] == [j.name for j in expanded.view.joints]


def test_pose_jacobian_and_ik_of_a_spec_answer_as_its_expanded_urdf(tmp_path):
    spec = REPO / "examples" / "robots" / "ur10e.yaml"
    xacrokit.generate(spec, tmp_path / "pkg", via_xacro=True)
    urdf = tmp_path / "pkg" / "urdf" / "ur10e.urdf"
    q = ["--q", "0.1,-1.2,1.3,-0.4,0.5,0.6"]
    for words in (["pose", "tool0", *q], ["jacobian", "tool0", *q], ["ik", "tool0", "--to=0.5,0.2,0.4", "--all"]):
        from_spec, from_urdf = gen_robot(words[0], spec, *words[1:]), gen_robot(words[0], urdf, *words[1:])
        assert from_spec.returncode == from_urdf.returncode == 0, from_spec.stderr + from_urdf.stderr
        assert from_spec.stdout == from_urdf.stdout and len(from_spec.stdout.splitlines()) > 3
