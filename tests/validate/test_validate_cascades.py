"""One mistake, one error: a mistyped child is not also reported as separate trees, and a name given twice is not
also a second parent or a cycle."""

from __future__ import annotations

import pytest

import xacrokit
from conftest import REPO

ARM = (REPO / "examples" / "robots" / "two_dof_arm.yaml").read_text(encoding="utf-8")
ROW = (
    "{{name: {joint}, link: {link}, a: 0.1, d: 0, alpha: 0, mass: 0.2, "
    "limit: {{lower: -1, upper: 1, effort: 1, velocity: 1}}}}"
)

CASES = {
    "mistyped child": (
        ARM.replace("child: forearm", "child: forarm", 1),
        [("$.joints.elbow_joint.child", "child 'forarm' is not in links (did you mean 'forearm'?)")],
    ),
    "frame named like a link": (
        ARM + "frames:\n  forearm: {parent: upper_arm}\n",
        [("$.frames.forearm", "link name 'forearm' is already used by $.links.forearm")],
    ),
    "frame named like the root, hung below it": (
        ARM + "frames:\n  base_link: {parent: forearm}\n",
        [("$.frames.base_link", "link name 'base_link' is already used by $.links.base_link")],
    ),
    "wheel named like a link": (
        ARM + "wheels:\n  upper_arm: {parent: forearm, radius: 0.1, width: 0.05, mass: 1.0}\n",
        [("$.wheels.upper_arm", "link name 'upper_arm' is already used by $.links.upper_arm")],
    ),
    "arm row named like a link": (
        ARM
        + "arms:\n  a:\n    parent: forearm\n    joints:\n      - "
        + ROW.format(joint="j1", link="upper_arm")
        + "\n      - "
        + ROW.format(joint="j2", link="hand")
        + "\n",
        [("$.arms.a.joints[0].link", "link name 'upper_arm' is already used by $.links.upper_arm")],
    ),
}


@pytest.mark.parametrize("case", CASES)
def test_one_mistake_is_one_error(tmp_path, case):
    text, expected = CASES[case]
    spec = tmp_path / "robot.yaml"
    spec.write_text(text, encoding="utf-8")
    with pytest.raises(xacrokit.SpecErrors) as caught:
        xacrokit.generate(spec, tmp_path / "pkg", dry_run=True)
    got = [(e.path, e.message) for e in caught.value.errors]
    assert len(got) == len(expected), got
    for (path, message), (want_path, words) in zip(got, expected, strict=True):
        assert path == want_path and words in message, got
