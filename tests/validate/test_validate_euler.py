"""Euler sequences (issue 41): a sequence none of scipy's is refused for what it is, not as a bad name, where it
stands; the schemas take exactly the sequences scipy takes with three angles."""

from __future__ import annotations

import itertools
import json
import re

import pytest
import yaml
from scipy.spatial.transform import Rotation

from conftest import REPO, gen_robot
from xacrokit.errors import SpecErrors
from xacrokit.load import load_file, load_text
from xacrokit.scene import build_scene
from xacrokit.validate import validate
from xacrokit.validate.quantities import EULER_SEQUENCES

SPEC = {
    "robot": "rot",
    "links": {
        "base_link": {"shape": {"box": {"size": [0.2, 0.2, 0.1]}}, "mass": 2.0},
        "camera": {"shape": {"box": {"size": [0.02, 0.08, 0.02]}}, "mass": 0.1},
    },
    "joints": {"camera_joint": {"type": "fixed", "parent": "base_link", "child": "camera", "origin": {}}},
}
WRONG = ["ABC", "xxy", "XXY", "xy", "xyzx", "XyZ", "", "x y z", 123, ["x", "y", "z"]]
PRINTED = re.compile(r"^(?P<file>.+?):(?P<line>\d+):(?P<column>\d+): (?P<path>\$\S*): (?P<message>.*)$")


def _spec_text(sequence) -> str:
    spec = yaml.safe_load(yaml.safe_dump(SPEC))
    spec["joints"]["camera_joint"]["origin"] = {"euler": {"sequence": sequence, "angles": [0.1, 0.2, 0.3]}}
    return yaml.safe_dump(spec, sort_keys=False)


def _sequence_place(text: str) -> tuple[int, int]:
    """(line, column) of the sequence's value in ``text`` (a block-style dump: the key's line, after the key; a list
    value on the lines below, at its first item)."""
    lines = text.splitlines()
    number = next(i for i, line in enumerate(lines) if line.strip().startswith("sequence:"))
    line = lines[number]
    rest = line.split("sequence:", 1)[1]
    if rest.strip():
        return number + 1, len(line) - len(rest.lstrip()) + 1
    following = lines[number + 1]
    return number + 2, len(following) - len(following.lstrip()) + 1


@pytest.mark.parametrize("sequence", WRONG, ids=repr)
def test_a_sequence_none_of_scipys_is_refused_for_what_it_is_where_it_stands(sequence):
    text = _spec_text(sequence)
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(text, "rot.yaml"))
    (error,) = caught.value.errors
    assert error.path == "$.joints.camera_joint.origin.euler.sequence"
    assert (error.line, error.column) == _sequence_place(text)
    assert error.message.startswith(f"{sequence!r} is not an Euler sequence (")
    assert "not a valid name" not in error.message and "is not of type" not in error.message
    # what is right: the rule and scipy's examples, which the schema takes
    assert "three of the axes x, y, z, no two consecutive alike" in error.message
    examples = re.search(r"e\.g\. (.*)$", error.message).group(1).split(", ")
    assert examples and set(examples) <= set(EULER_SEQUENCES)


@pytest.mark.parametrize(
    ("sequence", "why"),
    [
        ("ABC", "'A' is no axis"),
        ("xxy", "consecutive axes must differ"),
        ("xy", "2 characters"),
        ("xyzx", "4 characters"),
        ("XyZ", "mixes upper and lower case"),
        ("", "0 characters"),
        ("x y z", "5 characters"),
        (123, "a number"),
        (["x", "y", "z"], "a list"),
    ],
    ids=repr,
)
def test_the_reason_is_the_sequences_own(sequence, why):
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(_spec_text(sequence), "rot.yaml"))
    (error,) = caught.value.errors
    reason = re.match(r".* is not an Euler sequence \((.*?)\); give", error.message).group(1)
    assert why in reason, error.message


def test_generate_refuses_it_with_exit_2_and_writes_nothing(tmp_path):
    for index, sequence in enumerate(["ABC", "xyzx", "x y z"]):
        spec = tmp_path / f"rot{index}.yaml"
        text = _spec_text(sequence)
        spec.write_text(text, encoding="utf-8")
        result = gen_robot("generate", spec, "-o", tmp_path / f"pkg{index}")
        assert result.returncode == 2 and "Traceback" not in result.stderr, result.stderr
        assert not (tmp_path / f"pkg{index}").exists()
        printed = [m for m in map(PRINTED.match, (line.strip() for line in result.stderr.splitlines())) if m]
        (found,) = printed
        assert found["file"] == str(spec) and found["path"] == "$.joints.camera_joint.origin.euler.sequence"
        assert (int(found["line"]), int(found["column"])) == _sequence_place(text)
        assert found["message"].startswith(f"{sequence!r} is not an Euler sequence")


def test_a_scene_instance_says_the_same(tmp_path):
    arm = REPO / "examples" / "robots" / "two_dof_arm.yaml"
    scene = tmp_path / "cell.yaml"
    scene.write_text(
        f"scene: cell\ninstances:\n  a: {{spec: {arm}, prefix: a_, parent: world,\n"
        "      origin: {euler: {sequence: ABC, angles: [0, 0, 0]}}}\n",
        encoding="utf-8",
    )
    with pytest.raises(SpecErrors) as caught:
        build_scene(load_file(scene))
    (error,) = caught.value.errors
    line = scene.read_text(encoding="utf-8").splitlines()[3]
    assert error.path == "$.instances.a.origin.euler.sequence" and (error.line, error.column) == (
        4,
        line.index("ABC") + 1,
    )
    assert error.message.startswith("'ABC' is not an Euler sequence ('A' is no axis)")


def test_the_schemas_take_exactly_the_sequences_scipy_takes_with_three_angles():
    """Every word of up to four of x, y, z, X, Y, Z: the schemas' pattern matches it exactly when scipy's
    Rotation.from_euler takes it with three angles (the independent oracle), and EULER_SEQUENCES lists those."""
    words = ["".join(w) for n in range(5) for w in itertools.product("xyzXYZ", repeat=n)]

    def scipy_takes(word: str) -> bool:
        try:
            Rotation.from_euler(word, [0.1, 0.2, 0.3])
        except ValueError:
            return False
        return True

    taken = {w for w in words if scipy_takes(w)}
    assert taken == set(EULER_SEQUENCES) and len(taken) == 24
    for name in ("robot", "scene"):
        schema = json.loads((REPO / "schemas" / f"{name}.schema.json").read_text(encoding="utf-8"))
        pattern = next(n["properties"]["sequence"]["pattern"] for n in _nodes(schema) if _is_euler(n))
        regex = re.compile(pattern[:-1] + r"\Z")  # (ECMA's $: the end of the text)
        assert {w for w in words if regex.search(w)} == taken, name


def _is_euler(node) -> bool:
    return isinstance(node, dict) and "sequence" in node.get("properties", {}) and "angles" in node["properties"]


def _nodes(node):
    yield node
    children = node.values() if isinstance(node, dict) else node if isinstance(node, list) else ()
    for child in children:
        yield from _nodes(child)


def test_every_sequence_the_schema_takes_validates():
    for sequence in EULER_SEQUENCES:
        spec = validate(load_text(_spec_text(sequence), "rot.yaml"))
        assert spec.data["joints"]["camera_joint"]["origin"]["rpy"]
