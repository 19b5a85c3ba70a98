"""gen-robot new: each starter spec generates a package that checks clean, names no path of this machine."""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path, PurePosixPath

import jsonschema
import pytest
import yaml
from lxml import etree

import xacrokit
from conftest import REPO, gen_robot
from xacrokit.check import check
from xacrokit.cli.starter import KINDS as STARTER_KINDS
from xacrokit.cli.starter import starter_text, write_starter
from xacrokit.reader.robot_input import RobotInput


@pytest.mark.parametrize("kind", STARTER_KINDS)
def test_new_writes_a_starter_that_generates(tmp_path, kind):
    result = gen_robot("new", f"my_{kind}", "--kind", kind, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    spec = tmp_path / f"my_{kind}.yaml"
    text = spec.read_text(encoding="utf-8")
    assert all(line.startswith("# ") for line in text.splitlines()[:3])  # opens with its comments
    generated = xacrokit.generate(spec, tmp_path / "out")
    assert generated.name == f"my_{kind}"
    again = gen_robot("new", f"my_{kind}", cwd=tmp_path)
    assert again.returncode == 2 and "already exists" in again.stderr
    assert spec.read_text(encoding="utf-8") == text
    assert gen_robot("new", "bad name", cwd=tmp_path).returncode == 2


@pytest.mark.parametrize(
    ("name", "words"),
    [("include", "is taken by a xacrokit macro or a xacro keyword"), ("__bot", "starts with two underscores")],
)
def test_new_refuses_a_name_the_spec_refuses(tmp_path, name, words):
    """gen-robot new writes no starter that gen-robot would then refuse (the same rule: validate.names)."""
    result = gen_robot("new", name, cwd=tmp_path)
    assert result.returncode == 2 and words in result.stderr, result.stderr
    assert list(tmp_path.iterdir()) == []


def test_plain_new_writes_the_arm_starter(tmp_path):
    assert gen_robot("new", "bot", cwd=tmp_path).returncode == 0
    assert (tmp_path / "bot.yaml").read_text(encoding="utf-8") == starter_text("bot", "arm")


@pytest.mark.parametrize("kind", STARTER_KINDS)
def test_every_starter_package_checks_clean_with_strict(tmp_path, kind):
    """`gen-robot new` then `gen-robot` then `gen-robot check --strict`: no errors and no warnings."""
    spec = write_starter(f"my_{kind}", kind=kind, output=tmp_path / f"my_{kind}.yaml")
    out = tmp_path / f"my_{kind}_description"
    xacrokit.generate(spec, out)
    reports = [
        check(out / "urdf" / f"my_{kind}.urdf"),
        check(spec, consumers=[]),
        # the entry xacro with a prefix, as a second instance would use it: still clean, every name prefixed
        check(
            RobotInput(out / "urdf" / f"my_{kind}.urdf.xacro", {"prefix": "left_"}, {f"my_{kind}_description": out}),
            prefix="left_",
            consumers=[],
        ),
    ]
    for report in reports:
        assert report.errors == [] and report.warnings == [], [str(f) for f in report.findings]
        assert report.exit_code(strict=True) == 0
    assert reports[0].consumers and all(c.status == "accepted" for c in reports[0].consumers)
    root = etree.parse(str(out / "urdf" / f"my_{kind}.urdf")).getroot()
    moving = [j for j in root.findall("joint") if j.get("type") in ("revolute", "continuous", "prismatic")]
    assert moving
    for joint in moving:  # every moving joint carries sensible, positive damping
        dynamics = joint.find("dynamics")
        assert dynamics is not None, joint.get("name")
        assert 0 < float(dynamics.get("damping")) <= 5 and 0 <= float(dynamics.get("friction", "0")) <= 5


@pytest.mark.parametrize("kind", STARTER_KINDS)
def test_starter_names_no_path_of_this_machine_and_says_how_to_get_the_schema(tmp_path, kind):
    text = starter_text("bot", kind)
    machine_paths = {str(REPO), sys.prefix, str(Path(xacrokit.__file__).resolve().parent), str(Path.home())}
    assert not [p for p in machine_paths if p in text]
    assert not re.search(r"(?m)^#\s*yaml-language-server", text)  # no modeline naming a file that is not there
    # ... but the comment's recipe works: the schema it writes validates the starter through the modeline it shows
    (hint,) = [line for line in text.splitlines() if "$schema=" in line]
    schema_file = hint.split("$schema=", 1)[1].strip()
    assert not PurePosixPath(schema_file).is_absolute() and "gen-robot schema > " + schema_file in text
    written = gen_robot("schema", cwd=tmp_path)
    assert written.returncode == 0
    (tmp_path / schema_file).write_text(written.stdout, encoding="utf-8")
    jsonschema.validate(yaml.safe_load(text), json.loads((tmp_path / schema_file).read_text(encoding="utf-8")))


def test_a_starter_is_never_written_through_a_link_nor_over_a_file(tmp_path):
    """gen-robot new writes with the project's writer: a dangling link where the spec would go is refused (its target
    is not made), an existing file is kept, and a spec written leaves no temporary file beside it."""
    (tmp_path / "bot.yaml").symlink_to(tmp_path / "elsewhere.yaml")
    refused = gen_robot("new", "bot", "-o", tmp_path / "bot.yaml")
    assert refused.returncode == 2 and "already exists; not overwritten" in refused.stderr
    assert not (tmp_path / "elsewhere.yaml").exists()
    written = write_starter("arm2", output=tmp_path / "specs/")
    assert written == tmp_path / "specs" / "arm2.yaml" and written.read_text(encoding="utf-8") == starter_text("arm2")
    assert sorted(p.name for p in written.parent.iterdir() if not p.name.startswith(".xacrokit")) == ["arm2.yaml"]
    assert gen_robot("new", "arm2", "-o", written).returncode == 2 and written.read_text() == starter_text("arm2")
