"""Scene mistakes: clashing names, wrong parents, bad instance specs; each located, nothing written."""

from __future__ import annotations

import pytest
from scene_helpers import THIRD_PARTY, scene_file

import xacrokit
from conftest import REPO, gen_robot
from xacrokit.check import check
from xacrokit.errors import SpecErrors


def test_a_clash_names_both_instances_before_writing(tmp_path):
    (tmp_path / "acme.xacro").write_text(THIRD_PARTY, encoding="utf-8")
    macro = {"file": "acme.xacro", "macro": "acme_arm"}
    path = scene_file(
        tmp_path,
        {
            "one": {"xacro": dict(macro), "prefix": "x_", "parent": "world"},
            "two": {"xacro": dict(macro), "prefix": "x_", "parent": "world"},
        },
    )
    with pytest.raises(xacrokit.SpecErrors) as caught:
        xacrokit.generate(path, tmp_path / "pkg")
    (error,) = caught.value.errors
    assert "instances one and two would both have link x_acme_base" in error.message
    assert error.path == "$.instances.two" and error.line is not None
    assert not (tmp_path / "pkg").exists()


def test_a_clash_between_our_robots(tmp_path):
    arm = REPO / "examples" / "robots" / "two_dof_arm.yaml"
    path = scene_file(
        tmp_path,
        {
            "a": {"spec": str(arm), "prefix": "r_", "parent": "world"},
            "b": {"spec": str(arm), "prefix": "r_", "parent": "world"},
        },
    )
    with pytest.raises(xacrokit.SpecErrors, match="instances a and b would both have link r_base_link"):
        xacrokit.generate(path, tmp_path / "pkg")


@pytest.mark.parametrize(
    ("instances", "path", "words"),
    [
        (
            {"a": {"spec": "ARM", "prefix": "a_", "parent": "b/base_link"}},
            "$.instances.a.parent",
            "instance 'b' is not",
        ),
        (
            {
                "a": {"spec": "ARM", "prefix": "a_", "parent": "world"},
                "b": {"spec": "ARM", "prefix": "b_", "parent": "a/nope"},
            },
            "$.instances.b.parent",
            "'nope' is not a link",
        ),
        (
            {
                "a": {"spec": "ARM", "prefix": "a_", "parent": "b/base_link"},
                "b": {"spec": "ARM", "prefix": "b_", "parent": "a/base_link"},
            },
            "$.instances.a.parent",
            "in a loop",
        ),
        ({"a": {"spec": "ARM", "prefix": "bad prefix", "parent": "world"}}, "$.instances.a.prefix", "not a valid name"),
        ({"a": {"spec": "missing.yaml", "prefix": "a_", "parent": "world"}}, "$.instances.a.spec", "no robot spec"),
        ({"a": {"spec": "ARM", "prefix": "a_", "parent": "moon"}}, "$.instances.a.parent", "must be 'world'"),
        ({"a": {"prefix": "a_", "parent": "world"}}, "$.instances.a", "exactly one of spec (a robot spec) or xacro"),
        (
            {"a": {"spec": "ARM", "xacro": {"file": "x.xacro", "macro": "m"}, "prefix": "a_", "parent": "world"}},
            "$.instances.a",
            "got both spec and xacro",
        ),
    ],
)
def test_scene_mistakes_are_located(tmp_path, instances, path, words):
    arm = str(REPO / "examples" / "robots" / "two_dof_arm.yaml")
    for entry in instances.values():
        if entry.get("spec") == "ARM":
            entry["spec"] = arm
    with pytest.raises(xacrokit.SpecErrors) as caught:
        xacrokit.generate(scene_file(tmp_path, instances), tmp_path / "pkg")
    assert any(e.path == path and words in e.message for e in caught.value.errors), [
        str(e) for e in caught.value.errors
    ]


def test_errors_inside_an_instance_spec_point_into_that_spec(tmp_path):
    bad = tmp_path / "bad_robot.yaml"
    bad.write_text(
        (REPO / "examples" / "robots" / "two_dof_arm.yaml")
        .read_text(encoding="utf-8")
        .replace("mass: 0.5", "mass: -1"),
        encoding="utf-8",
    )
    with pytest.raises(xacrokit.SpecErrors) as caught:
        xacrokit.generate(scene_file(tmp_path, {"a": {"spec": "bad_robot.yaml", "parent": "world"}}), tmp_path / "o")
    assert [e.file for e in caught.value.errors] == [str(bad)]


def test_a_scene_passes_on_its_robots_warnings(tmp_path):
    robot = tmp_path / "heavy.yaml"
    robot.write_text(
        "robot: heavy\nlinks:\n  base_link: {shape: {box: {size: [0.1, 0.1, 0.1]}}, mass: 500}\n", encoding="utf-8"
    )
    scene = tmp_path / "cell.yaml"
    scene.write_text(
        "scene: cell\ninstances:\n  a: {spec: heavy.yaml, prefix: a_, parent: world, origin: {rpy: [0, 0, 45]}}\n"
        "  b: {spec: heavy.yaml, prefix: b_, parent: world}\n",
        encoding="utf-8",
    )
    result = xacrokit.generate(scene, tmp_path / "out")
    assert [(w.file, w.path) for w in result.warnings] == [
        (str(scene), "$.instances.a.origin.rpy[2]"),  # 45 rad: degrees without their unit
        (str(robot), "$.links.base_link.mass"),  # 500 kg in a litre: once, however many instances use it
    ]
    notes = [f for f in check(scene, consumers=[]).findings if f.rule == "V001"]
    assert sorted(f.element for f in notes) == ["$.instances.a.origin.rpy[2]", "$.links.base_link.mass"]
    fleet = gen_robot("fleet", robot, "--count", 2, "-o", tmp_path / "fleet")
    assert fleet.returncode == 0 and fleet.stderr.count("gen-robot: warning:") == 1, fleet.stderr


def test_a_missing_robot_spec_is_reported_once_where_the_scene_names_it(tmp_path):
    scene = tmp_path / "cell.yaml"
    scene.write_text("scene: cell\ninstances:\n  a: {spec: griper.yaml, prefix: a_, parent: world}\n")
    with pytest.raises(SpecErrors) as caught:
        xacrokit.generate(scene, tmp_path / "out")
    (error,) = caught.value.errors
    assert (error.file, error.path, error.line) == (str(scene), "$.instances.a.spec", 3)
    assert "no robot spec at" in error.message and "No such file or directory" in error.message


def test_a_name_taken_by_the_world_link_is_said_so(tmp_path):
    robot = tmp_path / "r.yaml"
    robot.write_text("robot: r\nlinks:\n  world: {}\n", encoding="utf-8")
    scene = tmp_path / "cell.yaml"
    scene.write_text("scene: cell\ninstances:\n  a: {spec: r.yaml, prefix: '', parent: world}\n", encoding="utf-8")
    with pytest.raises(SpecErrors) as caught:
        xacrokit.generate(scene, tmp_path / "out")
    messages = [e.message for e in caught.value.errors]
    assert any("instance a would have link world, the scene's world link" in m for m in messages), messages


@pytest.mark.parametrize(
    "content",
    ["root:$6$SECRETHASH:19000:0:99999:7:::\n", "SECRET words on one line\n", "- SECRET\n- more\n", "{x: SECRET}\n"],
)
def test_an_instance_naming_a_file_that_is_no_spec_is_refused_without_quoting_it(tmp_path, content):
    """A scene from elsewhere may name any file as an instance's spec (/etc/shadow): the error says what it is not,
    where the scene names it, and never quotes what the file holds."""
    (tmp_path / "shadow").write_text(content, encoding="utf-8")
    path = scene_file(tmp_path, {"a": {"spec": "shadow", "prefix": "a_", "parent": "world"}})
    result = gen_robot(path, "--dry-run")
    assert result.returncode == 2, result.stderr
    assert "is not a robot spec" in result.stderr and "$.instances.a.spec" in result.stderr
    assert "SECRET" not in result.stderr + result.stdout
