"""Documentation that cannot drift: macro banners vs. the macros, the README's two commands and quick starts, the
reference in docs/ (its samples, generated parts and commands), and the links between them."""

from __future__ import annotations

import json
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path
from urllib.parse import unquote

import pytest
from lxml import etree

import xacrokit
from conftest import REPO, gen_robot
from xacrokit.shared.macro_banners import XACRO_NS, read_macro_docs, render_reference
from xacrokit.shared.package_data import PUBLIC_MACRO_FILES, PUBLIC_MACROS

README = REPO / "README.md"
DOCS = REPO / "docs"
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


def text_of(path: Path) -> str:
    return path.read_text(encoding="utf-8")


def blocks(path: Path, language: str) -> list[str]:
    """The fenced code blocks of one language in a Markdown file, in order."""
    return re.findall(rf"```{language}\n(.*?)\n```", text_of(path), flags=re.S)


def doc_pages() -> list[Path]:
    return sorted(DOCS.glob("*.md"))


def test_docs_macro_reference_is_current():
    macros_md = text_of(DOCS / "macros.md")
    block = macros_md.split("<!-- macro-reference:start -->\n", 1)[1].split("<!-- macro-reference:end -->", 1)[0]
    assert block == render_reference(), (
        "run: gen-robot macros --reference, and paste it between the markers in docs/macros.md"
    )


def readme_commands() -> list[str]:
    return blocks(README, "sh")[:2]


def test_readme_starts_with_the_two_commands_and_ci_runs_the_second():
    main_job, tests = readme_commands()
    assert "pip install" in main_job and "gen-robot" in main_job
    assert tests.endswith("python -m pytest")
    assert tests in (REPO / ".ci" / "run").read_text(encoding="utf-8")
    readme = text_of(README)
    assert readme.startswith("# xacrokit\n") and readme.index(tests) < readme.index("\n## ")  # before any section


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
def test_docs_document_the_include_path(snippet):
    macros_md = text_of(DOCS / "macros.md")
    assert "$(find xacrokit)/macros/" in macros_md and f"`{snippet}`" in macros_md
    assert "$(find xacrokit)/macros/" in text_of(README)  # the quick start's first include


def test_docs_error_sample_is_real_output(tmp_path):
    sample = text_of(DOCS / "spec.md").split("$ gen-robot robot.yaml\n", 1)[1].split("```", 1)[0]
    spec = (REPO / "examples" / "robots" / "two_dof_arm.yaml").read_text(encoding="utf-8")
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


def run_shell_line(command: str, folder: Path, env: dict[str, str], shell: bool) -> subprocess.CompletedProcess:
    """A docs line run as a reader's shell runs it: the first through the shell itself (the console script on PATH),
    the others, each ``gen-robot WORDS`` with at most ``> FILE`` after it, in this process (conftest.gen_robot, the
    same words, output and exit code: tests/cli/test_cli_process.py), ``> FILE`` writing the output into the
    folder. Anything else a line may hold is the shell's."""
    words = shlex.split(command)
    redirect = words[-2:-1] == [">"]
    plain = words[:-2] if redirect else words
    if shell or plain[:1] != ["gen-robot"] or any(w in ("|", ">", "<", "&&", ";", ">>") for w in plain):
        return subprocess.run(command, shell=True, cwd=folder, env=env, capture_output=True, text=True, timeout=300)
    result = gen_robot(*plain[1:], cwd=folder)
    if redirect:
        (folder / words[-1]).write_text(result.stdout, encoding="utf-8")
        result.stdout = ""
    return result


def python_blocks() -> list[tuple[str, str]]:
    """Every Python block of the README and docs/ (by file name): (the page's stem and the block's place, its text)."""
    found = [(f"README-{k}", block) for k, block in enumerate(blocks(README, "python"))]
    for page in doc_pages():
        found += [(f"{page.stem}-{k}", block) for k, block in enumerate(blocks(page, "python"))]
    return found


def readers_env() -> dict[str, str]:
    """The environment of a reader who installed xacrokit: this interpreter's scripts (gen-robot) on PATH."""
    return dict(os.environ, PATH=f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}")


def run_python_block(block: str, folder: Path) -> None:
    """A Python block run as a reader runs it, a process of its own: in the repository when it reads its examples/,
    else in ``folder`` (where the command examples made what it reads)."""
    cwd = REPO if "examples/" in block else folder
    command = [sys.executable, "-c", block]
    result = subprocess.run(command, cwd=cwd, env=readers_env(), capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, (block, result.stderr)


# the Python blocks that read only the repository run each in a test of its own, side by side (about half of the
# sequence's time); the others at the end of the command examples' sequence, whose files they read
OF_THE_REPOSITORY = [(name, block) for name, block in python_blocks() if "examples/" in block]


@pytest.mark.parametrize("block", [block for _, block in OF_THE_REPOSITORY], ids=[n for n, _ in OF_THE_REPOSITORY])
def test_python_examples_of_the_repository_run(block, tmp_path):
    run_python_block(block, tmp_path)


def test_command_examples_run_in_sequence(tmp_path):
    """Every sh block of the README after its two set-up commands, then every sh block of docs/ (by file name), run in
    one folder in order, as a reader would: the README's quick starts make the my_robot spec, package and xacro
    document that the reference pages' examples use. Then every Python block of the README and docs/ that reads
    them (the others: test_python_examples_of_the_repository_run)."""
    env = readers_env()
    (xml_sample,) = blocks(README, "xml")
    (tmp_path / "my_robot.urdf.xacro").write_text(xml_sample, encoding="utf-8")  # "Save this as my_robot.urdf.xacro"
    sh_blocks = blocks(README, "sh")[2:] + [block for page in doc_pages() for block in blocks(page, "sh")]
    ran = []
    for block in sh_blocks:
        for line in block.splitlines():
            command = line.split("  #", 1)[0].strip()
            if not command or command.startswith("pip "):
                continue  # installing is what the README's first command shows
            command = re.sub(r"(?<![\w/.])examples/", f"{REPO.as_posix()}/examples/", command)  # (the repository's)
            result = run_shell_line(command, tmp_path, env, shell=not ran)
            assert result.returncode == 0, (command, result.stdout, result.stderr)
            ran.append(command)
    for command in ("gen-robot new", "gen-robot check", "gen-robot expand", "gen-robot fleet"):
        assert any(c.startswith(command) for c in ran), command
    assert json.loads((tmp_path / "robot.schema.json").read_text())
    assert not (tmp_path / "src").exists()  # the --dry-run line wrote nothing
    assert json.loads((tmp_path / "report.json").read_text())["summary"]["errors"] == 0
    root = etree.parse(str(tmp_path / "my_robot.urdf")).getroot()  # the quick start's own xacro, expanded
    assert float(root.find("link/inertial/inertia").get("ixx")) == pytest.approx(8.0 * (0.35**2 + 0.12**2) / 12)
    prefixed = etree.parse(str(tmp_path / "left_my_robot.urdf")).getroot()  # the generated entry, with prefix:=left_
    names = [e.get("name") for e in prefixed.iter("link", "joint")]
    assert names and all(name.startswith("left_") for name in names)
    reading_them = [block for name, block in python_blocks() if (name, block) not in OF_THE_REPOSITORY]
    assert reading_them and OF_THE_REPOSITORY  # (none of either: the blocks moved, and this would prove nothing)
    for block in reading_them:
        run_python_block(block, tmp_path)


def test_docs_spec_sample_generates(tmp_path):
    blocks_yaml = blocks(DOCS / "spec.md", "yaml")
    (sample,) = [b for b in blocks_yaml if b.startswith("# yaml-language-server: $schema=robot.schema.json")]
    (tmp_path / "spec.yaml").write_text(sample, encoding="utf-8")
    result = xacrokit.generate(tmp_path / "spec.yaml", tmp_path / "out")
    assert {"base_link", "upper_arm", "hand", "tool0", "camera_link"} <= set(result.model.link_names)


def test_readme_xml_sample_expands(tmp_path):
    (sample,) = blocks(README, "xml")
    (tmp_path / "my_robot.urdf.xacro").write_text(sample, encoding="utf-8")
    root = etree.fromstring(xacrokit.expand(tmp_path / "my_robot.urdf.xacro").encode())
    assert float(root.find("link/inertial/inertia").get("ixx")) == pytest.approx(8.0 * (0.35**2 + 0.12**2) / 12)


def test_docs_check_rules_table_is_current():
    from xacrokit.check.text_report import rules_markdown

    check_md = text_of(DOCS / "check.md")
    block = check_md.split("<!-- check-rules:start -->\n", 1)[1].split("<!-- check-rules:end -->", 1)[0]
    assert block == rules_markdown(), (
        f"run: python -c 'from {rules_markdown.__module__} import rules_markdown; print(rules_markdown(), end=\"\")' "
        "and paste it between the markers in docs/check.md"
    )


def test_docs_scene_sample_is_the_example():
    (sample,) = [b for b in blocks(DOCS / "scenes.md", "yaml") if "scene.schema.json" in b]
    assert sample + "\n" == (REPO / "examples" / "scenes" / "bin_sorting_cell.yaml").read_text(encoding="utf-8")


_LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)|^\[[^\]]+\]:\s*(\S+)", flags=re.M)


def heading_anchors(page: Path) -> set[str]:
    """The anchors GitHub gives a page's headings: lower case, punctuation dropped, spaces as hyphens, repeats
    numbered."""
    text = re.sub(r"^```.*?^```", "", text_of(page), flags=re.S | re.M)
    anchors: set[str] = set()
    for heading in re.findall(r"^#{1,6} +(.+?) *$", text, flags=re.M):
        slug = re.sub(r"[^\w\- ]", "", heading.lower()).replace(" ", "-")
        anchor, n = slug, 0
        while anchor in anchors:
            n += 1
            anchor = f"{slug}-{n}"
        anchors.add(anchor)
    return anchors


def relative_links(page: Path) -> list[str]:
    """The targets of a page's links that are not web addresses, outside code blocks and code spans."""
    text = re.sub(r"^```.*?^```", "", text_of(page), flags=re.S | re.M)
    text = re.sub(r"`[^`\n]*`", "code", text)
    targets = [inline or reference for inline, reference in _LINK.findall(text)]
    return [t for t in targets if not re.match(r"[a-z][a-z0-9+.-]*:", t)]


@pytest.mark.parametrize("page", [README, *doc_pages()], ids=lambda p: p.relative_to(REPO).as_posix())
def test_relative_links_point_at_files_that_exist(page):
    for target in relative_links(page):
        path_part, _, anchor = target.partition("#")
        resolved = (page.parent / unquote(path_part)).resolve() if path_part else page
        assert resolved == REPO or REPO in resolved.parents, f"{page.name}: {target} leaves the repository"
        assert resolved.exists(), f"{page.name}: {target} points at nothing"
        if anchor:
            assert resolved.suffix == ".md", f"{page.name}: {target}: an anchor into a file that is not Markdown"
            assert anchor in heading_anchors(resolved), f"{page.name}: {target}: no such heading"


def test_readme_links_every_docs_page_and_pages_have_links():
    linked = {(README.parent / t.partition("#")[0]).resolve() for t in relative_links(README)}
    assert doc_pages() and set(doc_pages()) <= linked, "link every docs/*.md page from README.md"
    assert all(relative_links(page) for page in doc_pages())  # the link checker reads each page's links at all
