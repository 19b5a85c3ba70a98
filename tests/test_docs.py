"""Documentation that cannot drift: macro banners vs. the macros, the README's reference and its two commands."""

from __future__ import annotations

import json
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest
from lxml import etree

import xacrokit
from conftest import REPO
from xacrokit.macrodoc import XACRO_NS, read_macro_docs, render_reference
from xacrokit.resources import PUBLIC_MACRO_FILES, PUBLIC_MACROS

_PARAM = re.compile(r"""(\*{0,2}\w+)(?::=(?:'([^']*)'|"([^"]*)"|(\S+)))?""")


def declared_params(text: str) -> list[tuple[str, str | None]]:
    """Parse a xacro params="..." attribute into (name, default-or-None) pairs."""
    result = []
    for match in _PARAM.finditer(text):
        name, *defaults = match.groups()
        given = [d for d in defaults if d is not None]
        result.append((name, given[0] if given else None))
    return result


def test_every_public_macro_file_is_listed_and_has_a_header():
    on_disk = sorted(p.name for p in xacrokit.macros_dir().glob("*.xacro"))
    assert on_disk == sorted(PUBLIC_MACRO_FILES)
    for name in PUBLIC_MACRO_FILES:
        text = (xacrokit.macros_dir() / name).read_text(encoding="utf-8")
        assert f"xacrokit macro library (public API v1): {name}" in text


def test_banners_document_exactly_the_real_parameters():
    docs = read_macro_docs()
    assert {d.name for d in docs} == set(PUBLIC_MACROS)
    for doc in docs:
        documented = [(p.name, None if p.default is None else p.default.strip("'")) for p in doc.params]
        assert documented == declared_params(doc.declared_params), doc.name
        assert doc.makes and doc.creates and all(p.unit and p.description for p in doc.params), doc.name


def test_private_macros_are_marked_private():
    for path in xacrokit.macros_dir().rglob("*.xacro"):
        for macro in etree.parse(str(path)).getroot().iter(f"{{{XACRO_NS}}}macro"):
            name = macro.get("name")
            public = path.parent == xacrokit.macros_dir() and not name.startswith("_")
            assert public or name.startswith("_xacrokit"), f"{path.name}: {name}"


def test_readme_macro_reference_is_current():
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    block = readme.split("<!-- macro-reference:start -->\n", 1)[1].split("<!-- macro-reference:end -->", 1)[0]
    assert block == render_reference(), "run: gen-robot macros --reference, and paste it between the markers"


def readme_commands() -> list[str]:
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    return re.findall(r"```sh\n(.*?)\n```", readme, flags=re.S)[:2]


def test_readme_starts_with_the_two_commands_and_ci_runs_the_second():
    main_job, tests = readme_commands()
    assert "pip install" in main_job and "gen-robot" in main_job
    assert tests.endswith("python -m pytest")
    assert tests in (REPO / ".ci" / "run").read_text(encoding="utf-8")


def test_readme_main_job_runs(tmp_path):
    """Run the README's first command after its install step, with this environment's tools."""
    main_job, _ = readme_commands()
    steps = [shlex.split(step) for step in main_job.split("&&")]
    bin_dir = Path(sys.executable).parent
    ran = 0
    for words in steps:
        if words[0].startswith(".venv/bin/") and words[0] != ".venv/bin/pip":
            words[0] = str(bin_dir / words[0].removeprefix(".venv/bin/"))
            words = [str(REPO / w) if w.startswith("examples/") else w for w in words]
            result = subprocess.run(words, cwd=tmp_path, capture_output=True, text=True, timeout=300)
            assert result.returncode == 0, (words, result.stdout, result.stderr)
            ran += 1
    assert ran == 2
    assert "Successfully Parsed XML" in result.stdout  # check_urdf's verdict on the expanded example


@pytest.mark.parametrize("snippet", ["box_inertial", "dh_arm"])
def test_readme_documents_the_include_path(snippet):
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    assert "$(find xacrokit)/macros/" in readme and f"`{snippet}`" in readme


def test_readme_error_sample_is_real_output(tmp_path):
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    sample = readme.split("$ gen-robot robot.yaml\n", 1)[1].split("```", 1)[0]
    spec = (REPO / "examples" / "two_dof_arm.yaml").read_text(encoding="utf-8")
    for old, new in (
        ("    parent: upper_arm", "    parent: upper_ram"),
        ("limit: {lower: 0, upper: 2.8", "limit: {lower: 2.8, upper: 0"),
        ("    mass: 0.3", "    mass: -0.3"),
    ):
        assert spec.count(old) == 1
        spec = spec.replace(old, new)
    (tmp_path / "robot.yaml").write_text(spec, encoding="utf-8")
    result = subprocess.run(
        [sys.executable, "-m", "xacrokit.cli", "robot.yaml"], cwd=tmp_path, capture_output=True, text=True, timeout=120
    )
    assert result.returncode == 2
    assert result.stderr == sample


def readme_blocks(language: str) -> list[str]:
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    return re.findall(rf"```{language}\n(.*?)\n```", readme, flags=re.S)


def test_readme_command_examples_run_in_sequence(tmp_path):
    """Every sh block after the two set-up commands, then every Python block, run in one folder in order."""
    env = dict(os.environ, PATH=f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}")
    ran = []
    for block in readme_blocks("sh")[2:]:
        for line in block.splitlines():
            command = line.split("  #", 1)[0].strip()
            if not command or command.startswith("pip "):
                continue  # installing is what the README's first command shows
            result = subprocess.run(
                command, shell=True, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300
            )
            assert result.returncode == 0, (command, result.stdout, result.stderr)
            ran.append(command)
    assert any(c.startswith("gen-robot new") for c in ran) and any(c.startswith("gen-robot expand") for c in ran)
    assert (tmp_path / "my_robot.urdf").is_file() and json.loads((tmp_path / "robot.schema.json").read_text())
    assert not (tmp_path / "src").exists()  # the --dry-run line wrote nothing
    for block in readme_blocks("python"):
        cwd = REPO if "examples/" in block else tmp_path
        result = subprocess.run(
            [sys.executable, "-c", block], cwd=cwd, env=env, capture_output=True, text=True, timeout=300
        )
        assert result.returncode == 0, (block, result.stderr)


def test_readme_spec_sample_generates(tmp_path):
    (sample,) = [b for b in readme_blocks("yaml") if b.startswith("# yaml-language-server: $schema=../schemas/robot")]
    (tmp_path / "spec.yaml").write_text(sample, encoding="utf-8")
    result = xacrokit.generate(tmp_path / "spec.yaml", tmp_path / "out")
    assert {"base_link", "upper_arm", "hand", "tool0", "camera_link"} <= set(result.robot.link_names)


def test_readme_xml_sample_expands(tmp_path):
    (sample,) = readme_blocks("xml")
    (tmp_path / "my_robot.urdf.xacro").write_text(sample, encoding="utf-8")
    root = etree.fromstring(xacrokit.expand(tmp_path / "my_robot.urdf.xacro").encode())
    assert float(root.find("link/inertial/inertia").get("ixx")) == pytest.approx(8.0 * (0.35**2 + 0.12**2) / 12)


def test_readme_check_rules_table_is_current():
    from xacrokit.report import rules_markdown

    readme = (REPO / "README.md").read_text(encoding="utf-8")
    block = readme.split("<!-- check-rules:start -->\n", 1)[1].split("<!-- check-rules:end -->", 1)[0]
    assert block == rules_markdown()


def test_readme_scene_sample_is_the_example():
    (sample,) = [b for b in readme_blocks("yaml") if "scene.schema.json" in b]
    assert sample + "\n" == (REPO / "examples" / "scenes" / "bin_sorting_cell.yaml").read_text(encoding="utf-8")
