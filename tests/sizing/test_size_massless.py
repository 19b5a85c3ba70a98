"""An arm of massless links with a payload (issue 42, item 4): the lecture's tau = J^T F exercise. A URDF's links
without <inertial> are sized as they are; a spec refuses a moving link without mass, as every command does, and size's
message names the way to size it as written, `strict: false`; docs/size.md's spec with it is sized, its torques the
closed form's (the payload's weight at the tip of links of 0.6 m and 0.4 m, stretched out level)."""

from __future__ import annotations

import json
import re

import pytest

from conftest import REPO, gen_robot
from xacrokit.errors import SpecErrors
from xacrokit.sizing import GRAVITY, Payload, size

DOCS = (REPO / "docs" / "size.md").read_text(encoding="utf-8")
# the spec docs/size.md shows (its block is indented under a list item)
(SHOWN,) = [
    re.sub(r"^  ", "", block, flags=re.M)
    for block in re.findall(r"^  ```yaml\n(.*?)^  ```", DOCS, flags=re.S | re.M)
    if block.lstrip().startswith("strict: false")
]
LOCATED = re.compile(r"^  (?P<file>[^:]+):(?P<line>\d+):(?P<column>\d+): (?P<path>\$\S*): (?P<message>.*)$")


def _located(stderr: str) -> list[dict[str, str]]:
    """The located problems of an error: file, line, column, path and message of each."""
    return [m.groupdict() for m in map(LOCATED.match, stderr.splitlines()) if m]


def test_a_massless_spec_is_refused_naming_strict_false(tmp_path):
    """Without `strict: false`: exit 2, nothing on standard output, every massless link located, and the way to size
    it as written said once (it did not name strict: false before)."""
    spec = tmp_path / "lecture_arm.yaml"
    spec.write_text(SHOWN.replace("strict: false", "strict: true"), encoding="utf-8")
    result = gen_robot("size", spec.name, "--payload", "1 kg@tool_link", cwd=tmp_path)
    assert result.returncode == 2 and result.stdout == "" and "Traceback" not in result.stderr
    problems = _located(result.stderr)
    paths = {p["path"] for p in problems}
    assert {"$.joints.joint_1.child", "$.joints.joint_2.child"} <= paths
    assert all(p["file"] == "lecture_arm.yaml" and int(p["line"]) > 0 for p in problems)
    told = [p for p in problems if "write `strict: false` at the top of the spec" in p["message"]]
    assert len(told) == 1 and "tau = J^T F" in told[0]["message"]
    with pytest.raises(SpecErrors) as caught:  # (the Python API says the same)
        size(spec, payloads=[Payload("tool_link", 1.0)])
    assert sum("strict: false" in e.message for e in caught.value.errors) == 1


def test_the_docs_massless_spec_is_sized_with_its_payload(tmp_path):
    """With `strict: false` (as docs/size.md writes it): 1 kg at the tip needs g (0.6 + 0.4) at the shoulder and
    g 0.4 at the elbow, the links listed as massless; the docs' figures are these."""
    spec = tmp_path / "lecture_arm.yaml"
    spec.write_text(SHOWN, encoding="utf-8")
    result = gen_robot("size", spec, "--payload", "1 kg@tool_link", "--json", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    report = json.loads(result.stdout)
    needs = [abs(j["static"]["peak_torque"]) for j in report["joints"]]
    assert needs == pytest.approx([GRAVITY * 1.0, GRAVITY * 0.4], rel=1e-9)
    assert report["massless_links"] == ["link_1", "link_2"]
    said = f'`gen-robot size lecture_arm.yaml --payload "1 kg@tool_link"`: {needs[0]:.4g} and {needs[1]:.4g} N·m'
    assert said in DOCS


def test_a_massless_spec_with_nothing_to_load_it_says_so(tmp_path):
    """`strict: false` and no payload: every torque would be 0, an error naming the links and the payload."""
    spec = tmp_path / "lecture_arm.yaml"
    spec.write_text(SHOWN, encoding="utf-8")
    result = gen_robot("size", spec, cwd=tmp_path)
    assert result.returncode == 2 and result.stdout == ""
    assert "give those links a mass (link_1, link_2" in result.stderr and "--payload" in result.stderr
