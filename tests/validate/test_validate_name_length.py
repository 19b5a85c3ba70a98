"""Names are at most 200 characters: every file name gen-robot makes from a name (the longest,
``urdf/NAME.ros2_control.xacro``, plus the 14 characters of a temporary's ``.NAME.XXXXXXXX.tmp``) then fits the
file systems' 255-byte limit, and a longer name is a located spec error before anything is written."""

from __future__ import annotations

import pytest
import yaml

import xacrokit

MAX = 200


def arm_robot(name: str, arm: str) -> dict:
    row = {"name": "j1", "link": "k1", "a": 0.1, "d": 0, "alpha": 0, "mass": 1.0}
    row["limit"] = {"lower": -1, "upper": 1, "effort": 1, "velocity": 1}
    return {
        "robot": name,
        "links": {"base": {"shape": {"box": {"size": [0.1, 0.1, 0.1]}}, "mass": 1.0}},
        "arms": {arm: {"parent": "base", "joints": [row]}},
        "ros2_control": {},
    }


def test_names_of_the_longest_length_generate_every_file(tmp_path):
    spec = tmp_path / "long.yaml"
    spec.write_text(yaml.safe_dump(arm_robot("r" * MAX, "a" * MAX)), encoding="utf-8")
    result = xacrokit.generate(spec, tmp_path / "pkg")
    written = {a.path for a in result.actions if a.action == "create"}
    longest = max(written, key=lambda path: len(path.rsplit("/", 1)[-1]))
    assert len(longest.rsplit("/", 1)[-1]) == MAX + len(".ros2_control.xacro"), longest
    assert all((tmp_path / "pkg" / path).is_file() for path in written)


@pytest.mark.parametrize("where", ["robot", "arm"])
def test_a_longer_name_is_a_located_error_and_nothing_is_written(tmp_path, where):
    long = "n" * (MAX + 1)
    spec = tmp_path / "long.yaml"
    data = arm_robot(long if where == "robot" else "bot", long if where == "arm" else "arm")
    text = yaml.safe_dump(data, width=10**6, sort_keys=False)
    spec.write_text(text, encoding="utf-8")
    line, column = next((i, row.index(long) + 1) for i, row in enumerate(text.splitlines(), 1) if long in row)
    with pytest.raises(xacrokit.SpecErrors) as caught:
        xacrokit.generate(spec, tmp_path / "pkg")
    (error,) = caught.value.errors
    assert error.path == ("$.robot" if where == "robot" else f"$.arms.{long}")
    assert (error.line, error.column) == (line, column), str(error)
    assert f"is {MAX + 1} characters long; a name has at most {MAX}" in error.message
    assert not (tmp_path / "pkg").exists()


def test_a_scene_name_too_long_is_located(tmp_path):
    robot = tmp_path / "robot.yaml"
    robot.write_text(yaml.safe_dump(arm_robot("bot", "arm")), encoding="utf-8")
    path = tmp_path / "scene.yaml"
    instances = {"a": {"spec": "robot.yaml", "prefix": "a_", "parent": "world"}}
    path.write_text(yaml.safe_dump({"scene": "s" * 300, "instances": instances}), encoding="utf-8")
    with pytest.raises(xacrokit.SpecErrors) as caught:
        xacrokit.generate(path, tmp_path / "pkg", dry_run=True)
    assert any(e.path == "$.scene" and "is 300 characters long" in e.message for e in caught.value.errors)
