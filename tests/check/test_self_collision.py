"""G007 and G008, self-collision in check (issue 44, item 3): a planted overlap at home is flagged through the command
line (exit 1 with --strict, the pair in the JSON report); an SRDF beside the URDF, or given, that disables the pair
silences it; every example spec and every example's generated package is silent, and says what its SRDF disables."""

from __future__ import annotations

import json

import pytest
from check_helpers import CORPUS

import xacrokit
from conftest import ROBOT_EXAMPLES, SCENE_EXAMPLES, gen_robot
from xacrokit.check import check

SRDF = """<?xml version="1.0"?>
<robot name="corpus">
  <disable_collisions link1="base_link" link2="hand" reason="Default"/>
</robot>
"""


def _planted(tmp_path):
    path = tmp_path / "planted.urdf"
    path.write_text((CORPUS / "G007_fail.urdf").read_text(encoding="utf-8"), encoding="utf-8")
    return path


def test_a_planted_overlap_at_home_is_flagged_on_the_command_line(tmp_path):
    path = _planted(tmp_path)
    result = gen_robot("check", path, "--consumers", "none", "--strict", "--json")
    report = json.loads(result.stdout)
    flagged = [f for f in report["findings"] if f["rule"] == "G007"]
    assert result.returncode == 1 and len(flagged) == 1
    assert flagged[0]["element"] == {"kind": "link", "name": "base_link"} and "'hand'" in flagged[0]["message"]
    assert flagged[0]["severity"] == "warning" and flagged[0]["line"] == 4


def test_an_srdf_beside_the_urdf_or_given_is_respected(tmp_path):
    path = _planted(tmp_path)
    (tmp_path / "planted.srdf").write_text(SRDF, encoding="utf-8")
    report = check(path, consumers=[])
    assert [f.rule for f in report.findings] == ["G008"] and "planted.srdf disables 1 pairs" in report.findings[
        0
    ].message
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    moved = elsewhere / "robot.urdf"
    path.rename(moved)
    assert [f.rule for f in check(moved, consumers=[]).findings] == ["G007"]  # (no SRDF beside it now)
    given = check(moved, consumers=[], srdf=tmp_path / "planted.srdf")
    assert [(f.rule, f.severity) for f in given.findings] == [("G008", "info")]
    (tmp_path / "broken.srdf").write_text("<robot>", encoding="utf-8")
    broken = check(moved, consumers=[], srdf=tmp_path / "broken.srdf")
    assert sorted(f.rule for f in broken.findings) == ["G007", "G007"]  # (the SRDF unreadable, the pair flagged)


@pytest.mark.parametrize("example", [*ROBOT_EXAMPLES, *SCENE_EXAMPLES], ids=lambda p: p.stem)
def test_every_example_spec_is_silent_and_its_note_names_its_srdf(example):
    report = check(example, consumers=[])
    assert [f for f in report.findings if f.rule == "G007"] == []
    notes = [f for f in report.findings if f.rule == "G008"]  # (only where links intersect at home: Default)
    assert all(n.severity == "info" and "disables as Default" in n.message for n in notes) and len(notes) <= 1
    named = {"industrial_arm_mod_dh", "kuka_kr560_r3100_2", "two_arm_cell", "bin_sorting_cell"}
    assert bool(notes) == (example.stem in named)  # (the examples whose SRDF has Default pairs)


@pytest.mark.parametrize("example", [*ROBOT_EXAMPLES, *SCENE_EXAMPLES], ids=lambda p: p.stem)
def test_every_generated_package_is_silent_with_its_srdf(example, tmp_path):
    result = xacrokit.generate(example, tmp_path / "pkg")
    report = check(tmp_path / "pkg" / "urdf" / f"{result.name}.urdf", consumers=[])
    assert [str(f) for f in report.findings if f.rule == "G007"] == []
    (note,) = [f for f in report.findings if f.rule == "G008"]
    assert note.message.startswith(f"{result.name}.srdf disables")


def test_srdf_on_the_command_line_is_respected_and_checked(tmp_path):
    """gen-robot check ROBOT --srdf FILE: the pair the SRDF disables is no longer a warning (a note says the SRDF);
    a missing file, or an SRDF with several robot files, is an error, exit 2."""
    import json

    from conftest import gen_robot

    path = _planted(tmp_path)
    semantics = tmp_path / "semantics" / "robot.srdf"
    semantics.parent.mkdir()
    semantics.write_text(SRDF, encoding="utf-8")
    alone = json.loads(gen_robot("check", path, "--consumers", "none", "--json").stdout)
    assert [f["rule"] for f in alone["findings"]] == ["G007"]
    given = gen_robot("check", path, "--consumers", "none", "--json", "--srdf", semantics)
    assert given.returncode == 0 and [f["rule"] for f in json.loads(given.stdout)["findings"]] == ["G008"]
    missing = gen_robot("check", path, "--srdf", tmp_path / "nowhere.srdf")
    assert missing.returncode == 2 and "--srdf" in missing.stderr and "no such file" in missing.stderr
    several = gen_robot("check", path, path, "--srdf", semantics)
    assert several.returncode == 2 and "give it with one robot file" in several.stderr


def test_a_robot_of_more_than_400_solid_links_is_not_posed(tmp_path):
    """401 links of overlapping boxes on fixed joints (every non-adjacent pair collides): beyond MAX_SOLID the
    pairs' geometry model would outgrow memory (a 3,000-link fleet was killed), so G007 does not pose it; 40 such
    links are posed and flagged."""

    def chain(count):
        box = '<collision><geometry><box size="1 1 1"/></geometry></collision>'
        links = "".join(f'<link name="l{k}">{box}</link>' for k in range(count))
        joints = "".join(
            f'<joint name="j{k}" type="fixed"><parent link="l{k - 1}"/><child link="l{k}"/>'
            '<origin xyz="0.01 0 0"/></joint>'
            for k in range(1, count)
        )
        path = tmp_path / f"chain{count}.urdf"
        path.write_text(f'<robot name="chain{count}">{links}{joints}</robot>', encoding="utf-8")
        return path

    assert any(f.rule == "G007" for f in check(chain(40), consumers=[]).findings)
    assert not any(f.rule == "G007" for f in check(chain(401), consumers=[]).findings)
