"""docs/course.md, the course done with xacrokit (issue 42, item 5): every console block is what its command prints
today, run from the repository's root; every excerpt is in the file it names; the lecture's KUKA arm is one arm
whether written as a DH table or as KUKA writes its macro; the lecture's linkage is linkage.yaml but for Link A, whose
inertia check flags."""

from __future__ import annotations

import json
import re
import shlex
import shutil
import subprocess

import numpy as np
import pytest
from lxml import etree

import xacrokit
from conftest import REPO, check_urdf_binary, gen_robot
from xacrokit.kinematics import pose
from xacrokit.reader.read_robot import read_robot

COURSE = REPO / "docs" / "course.md"
TEXT = COURSE.read_text(encoding="utf-8")
# a console block: "```text", the command after "$ ", then its output up to the closing fence
CONSOLE = re.findall(r"^```text\n\$ ([^\n]+)\n(.*?)^```", TEXT, flags=re.S | re.M)
KUKA_SPEC = REPO / "examples" / "robots" / "kuka_kr560_r3100_2.yaml"
KUKA_PAIR = REPO / "examples" / "scenes" / "kuka_kr560_pair.urdf.xacro"
KUKA_MACRO = REPO / "examples" / "scenes" / "robots" / "kuka_kr560_r3100_2_macro.xacro"
LINKAGE = REPO / "examples" / "robots" / "linkage.yaml"
LINKAGE_LECTURE = REPO / "examples" / "robots" / "linkage_lecture.urdf"


def test_the_page_shows_a_modest_number_of_commands_each_run_here():
    assert 15 <= len(CONSOLE) <= 25, len(CONSOLE)  # (each takes a second or more)
    fences = re.findall(r"^ *```(\w*)\n(.)", TEXT, flags=re.M)
    shown = [first for language, first in fences if language == "text"]
    assert shown.count("$") == len(CONSOLE)  # no console block indented or otherwise missed by the pattern
    assert not [language for language, _ in fences if language == "console"]
    assert {command.split()[0] for command, _ in CONSOLE} == {"gen-robot", "check_urdf"}


@pytest.mark.parametrize(("command", "output"), CONSOLE, ids=[command[:60] for command, _ in CONSOLE])
def test_every_console_block_is_the_commands_output(command, output, tmp_path):
    words = shlex.split(command)
    if words[0] == "check_urdf":  # on the package the page's sh block generates before it
        (package, name) = re.fullmatch(r"(\w+)_description/urdf/(\w+)\.urdf", words[1]).groups()
        assert package == name
        xacrokit.generate(REPO / "examples" / "robots" / f"{name}.yaml", tmp_path / f"{name}_description")
        result = subprocess.run(
            [check_urdf_binary(), words[1]], cwd=tmp_path, capture_output=True, text=True, timeout=60
        )
    else:
        result = gen_robot(*words[1:], cwd=REPO)
    assert (result.returncode, result.stdout) == (0, output), result.stderr


def excerpts() -> list[tuple[str, str]]:
    """(file, text) of each YAML or XML block that opens by naming an example file in a comment."""
    found = []
    for block in re.findall(r"^```(?:yaml|xml)\n(.*?)\n```", TEXT, flags=re.S | re.M):
        first, _, rest = block.partition("\n")
        named = re.fullmatch(r"(?:# |<!-- )(examples/\S+)(?: -->)?", first)
        if named:
            found.append((named.group(1), rest))
    return found


def test_every_excerpt_is_in_the_file_it_names():
    shown = excerpts()
    assert len(shown) >= 3
    for name, text in shown:
        assert text in (REPO / name).read_text(encoding="utf-8"), name


def test_the_kuka_dh_table_and_the_vendor_macro_are_one_arm():
    """At random joint values within the limits, each prefixed arm's tool0 in its base_link (the vendor-style macro,
    called twice) is the DH spec's tool0, to 1e-12; and the page's start pose is the OPW parameters' closed form."""
    spec, pair = read_robot(KUKA_SPEC), read_robot(KUKA_PAIR)
    lower = np.radians([-185, -130, -100, -350, -120, -350])
    upper = np.radians([185, 20, 165, 350, 120, 350])
    rng = np.random.default_rng(42)
    for _ in range(10):
        q = rng.uniform(lower, upper)
        expected = pose(spec, "tool0", at={f"joint_{i}": repr(float(v)) for i, v in enumerate(q, 1)}).matrix
        for prefix in ("left_", "right_"):
            at = {f"{prefix}joint_{i}": repr(float(v)) for i, v in enumerate(q, 1)}
            found = pose(pair, f"{prefix}tool0", in_frame=f"{prefix}base_link", at=at).matrix
            assert np.allclose(found, expected, rtol=0, atol=1e-12), prefix
    home = pose(spec, "tool0", at={"joint_2": "-90deg", "joint_3": "90deg"}).matrix
    a1, a2, c1, c2, c3, c4 = 0.5, -0.18, 0.86, 1.55, 1.0345, 0.305  # KUKA's OPW parameters of the KR 560 R3100-2
    assert np.allclose(home[:3, 3], [a1 + c3 + c4, 0, c1 + c2 - a2], rtol=0, atol=1e-12)
    assert np.allclose(home[:3, 2], [1, 0, 0], rtol=0, atol=1e-12)  # the flange looks straight ahead


def joints_of(root: etree._Element) -> dict[str, tuple]:
    return {
        j.get("name"): (
            j.get("type"),
            j.find("parent").get("link"),
            j.find("child").get("link"),
            j.find("origin").attrib,
        )
        for j in root.iter("joint")
    }


def test_the_scene_form_places_the_same_two_arms_as_the_document(tmp_path):
    (scene,) = re.findall(r"^```yaml\n(scene: kuka_kr560_pair\n.*?)\n```", TEXT, flags=re.S | re.M)
    (tmp_path / "robots").mkdir()
    shutil.copy(KUKA_MACRO, tmp_path / "robots" / KUKA_MACRO.name)
    (tmp_path / "cell.yaml").write_text(scene + "\n", encoding="utf-8")
    made = xacrokit.generate(tmp_path / "cell.yaml", tmp_path / "pkg")
    from_scene = etree.parse(str(tmp_path / "pkg" / "urdf" / f"{made.name}.urdf")).getroot()
    from_document = etree.fromstring(xacrokit.expand(KUKA_PAIR).encode())
    assert {e.get("name") for e in from_scene.iter("link")} == {e.get("name") for e in from_document.iter("link")}
    scene_joints, document_joints = joints_of(from_scene), joints_of(from_document)
    assert scene_joints.keys() == document_joints.keys() and len(scene_joints) == 2 * 10
    for name, (kind, parent, child, origin) in document_joints.items():
        kind_s, parent_s, child_s, origin_s = scene_joints[name]
        assert (kind_s, parent_s, child_s) == (kind, parent, child), name
        for key in ("xyz", "rpy"):
            values = [float(v) for v in origin.get(key, "0 0 0").split()]
            assert np.allclose([float(v) for v in origin_s.get(key, "0 0 0").split()], values, atol=1e-12), name


def urdf_root(path) -> etree._Element:
    return etree.parse(str(path)).getroot()


def numbers(element: etree._Element | None, attribute: str) -> list[float]:
    return [float(v) for v in element.get(attribute, "0 0 0").split()] if element is not None else [0.0] * 3


def shape_of(link: etree._Element) -> tuple:
    shape = link.find("visual/geometry/*")
    radius_length = [float(shape.get(k, 0)) for k in ("radius", "length")]
    return shape.tag, numbers(shape, "size"), radius_length, numbers(link.find("visual/origin"), "xyz")


def test_check_flags_the_lectures_link_a_and_nothing_else():
    """Link A's inertia is the slides' (0.5 kg, 0.005 kg*m^2 about each axis): one warning, I008, and exit 0."""
    lecture = urdf_root(LINKAGE_LECTURE)
    inertia = lecture.find("link[@name='link_A']/inertial/inertia")
    assert [float(inertia.get(k)) for k in ("ixx", "iyy", "izz")] == [0.005] * 3
    assert float(lecture.find("link[@name='link_A']/inertial/mass").get("value")) == 0.5
    assert shape_of(lecture.find("link[@name='link_A']"))[:2] == ("box", [0.5, 0.5, 0.1])
    result = gen_robot("check", LINKAGE_LECTURE, "--json", cwd=REPO)
    report = json.loads(result.stdout)
    assert result.returncode == 0 and report["summary"]["errors"] == 0
    assert [(f["rule"], f["severity"], f["element"]) for f in report["findings"]] == [
        ("I008", "warning", {"kind": "link", "name": "link_A"})
    ]
    assert {c["status"] for c in report["consumers"]} == {"accepted"}


def test_the_lectures_linkage_is_linkage_yaml_but_for_link_as_inertia(tmp_path):
    """Every number the slides do not give is linkage.yaml's, as the URDF's comment says: shapes, masses, tensors,
    joints, limits and damping (the names as the slides write them: link_A for link_a)."""
    lecture = urdf_root(LINKAGE_LECTURE)
    made = xacrokit.generate(LINKAGE, tmp_path / "pkg")
    spec = urdf_root(tmp_path / "pkg" / "urdf" / f"{made.name}.urdf")
    for letter in "abcd":
        ours, theirs = lecture.find(f"link[@name='link_{letter.upper()}']"), spec.find(f"link[@name='link_{letter}']")
        assert shape_of(ours) == shape_of(theirs), letter
        if letter == "a":
            continue  # (the slides' own inertia)
        assert ours.find("inertial/mass").get("value") == theirs.find("inertial/mass").get("value"), letter
        ours_i, theirs_i = ours.find("inertial/inertia"), theirs.find("inertial/inertia")
        for key in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz"):
            assert float(ours_i.get(key)) == pytest.approx(float(theirs_i.get(key)), rel=1e-9, abs=1e-15), letter
    for letter in "abc":
        ours = lecture.find(f"joint[@name='joint_{letter.upper()}']")
        theirs = spec.find(f"joint[@name='joint_{letter}']")
        assert ours.get("type") == theirs.get("type")
        assert numbers(ours.find("origin"), "xyz") == numbers(theirs.find("origin"), "xyz")
        assert numbers(ours.find("axis"), "xyz") == numbers(theirs.find("axis"), "xyz")
        for element, keys in (
            ("limit", ("lower", "upper", "effort", "velocity")),
            ("dynamics", ("damping", "friction")),
        ):
            found = [float(ours.find(element).get(k)) for k in keys]
            assert found == [float(theirs.find(element).get(k)) for k in keys], (letter, element)
