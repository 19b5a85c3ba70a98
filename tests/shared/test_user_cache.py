"""The user's cache folder (``xacrokit.shared.user_cache``): compiled templates and SRDF collision matrices are taken
from it instead of being made again, give the same files either way, and a folder that is damaged, shared with
others, or cannot be made is never trusted and never fails a run."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import jinja2
import pytest

from xacrokit import __version__
from xacrokit.moveit import collision_pairs, moveit_package
from xacrokit.pipeline import generate
from xacrokit.render.environment import environment
from xacrokit.shared.user_cache import cache_folder, read_cached, write_cached

REPO = Path(__file__).resolve().parents[2]
UR5 = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """An empty cache folder of this test's own, and fresh in-process memories (the environment, the matrices)."""
    folder = tmp_path / "cache"
    monkeypatch.setenv("XACROKIT_CACHE", str(folder))
    fresh_memories()
    yield folder
    fresh_memories()


def package_texts(out: Path) -> dict[str, bytes]:
    return {str(p.relative_to(out)): p.read_bytes() for p in sorted(out.rglob("*")) if p.is_file()}


def forbid(monkeypatch, owner, name: str) -> None:
    """Make ``owner.name`` fail if called: the run must take its result from the cache."""

    def refuse(*args, **kwargs):
        raise AssertionError(f"{name} was called: the cache was not used")

    monkeypatch.setattr(owner, name, refuse)


def fresh_memories() -> None:
    environment.cache_clear()
    moveit_package._judged.cache_clear()


def test_a_second_generation_takes_templates_and_matrix_from_the_cache_and_writes_the_same_bytes(
    cache, tmp_path, monkeypatch
):
    generate(UR5, tmp_path / "first")
    templates = sorted((cache / f"templates-{__version__}").iterdir())
    matrices = sorted((cache / f"collisions-{__version__}").glob("*.json"))
    assert len(templates) >= 10 and len(matrices) == 1
    fresh_memories()
    forbid(monkeypatch, jinja2.Environment, "_compile")  # (jinja2 compiles a template's source to code here)
    forbid(monkeypatch, collision_pairs, "disabled_pairs")
    generate(UR5, tmp_path / "second")
    assert package_texts(tmp_path / "second") == package_texts(tmp_path / "first")


@pytest.mark.parametrize(("owner", "name"), [(jinja2.Environment, "_compile"), (collision_pairs, "disabled_pairs")])
def test_with_the_cache_off_the_work_the_cache_saves_is_done(cache, tmp_path, monkeypatch, owner, name):
    """The test above can fail: with the cache off (or a run that does not use it), each refused call is made."""
    generate(UR5, tmp_path / "filled")  # (the cache is full, but off below)
    monkeypatch.setenv("XACROKIT_CACHE", "off")
    fresh_memories()
    forbid(monkeypatch, owner, name)
    with pytest.raises(AssertionError, match=f"{name} was called"):
        generate(UR5, tmp_path / "out")


def test_damaged_cache_files_are_made_again_and_the_package_is_the_same(cache, tmp_path):
    generate(UR5, tmp_path / "first")
    for file in (cache / f"templates-{__version__}").iterdir():
        file.write_bytes(file.read_bytes()[: len(file.read_bytes()) // 2])  # (cut short mid-code)
    (matrix,) = (cache / f"collisions-{__version__}").glob("*.json")
    matrix.write_text('{"disabled": [["a", "b", "Sometimes"]], "samples": 1, "pairs": 0, "meshes": false}')
    fresh_memories()
    generate(UR5, tmp_path / "second")
    assert package_texts(tmp_path / "second") == package_texts(tmp_path / "first")
    assert "Sometimes" not in matrix.read_text()  # (judged again, and kept)


@pytest.mark.parametrize("kind", ["group-writable", "a link", "under a file"])
def test_a_cache_folder_that_is_not_private_or_cannot_be_made_is_not_used_and_the_run_still_works(
    kind, tmp_path, monkeypatch
):
    target = tmp_path / "cache"
    if kind == "group-writable":
        target.mkdir()
        target.chmod(0o777)
    elif kind == "a link":
        (tmp_path / "elsewhere").mkdir(mode=0o700)
        target.symlink_to(tmp_path / "elsewhere")
    else:
        (tmp_path / "file").write_text("")
        target = tmp_path / "file" / "cache"
    monkeypatch.setenv("XACROKIT_CACHE", str(target))
    assert cache_folder("templates", __version__) is None
    fresh_memories()
    generate(UR5, tmp_path / "out")
    assert (tmp_path / "out" / "config" / "ur5.srdf").is_file()
    assert not any((tmp_path / "elsewhere").iterdir()) if kind == "a link" else True
    fresh_memories()


def test_the_cache_folder_is_made_private_under_xdg_cache_home_and_named_by_version(tmp_path, monkeypatch):
    monkeypatch.delenv("XACROKIT_CACHE", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    folder = cache_folder("collisions", __version__)
    assert folder == tmp_path / "xacrokit" / f"collisions-{__version__}"
    assert stat.S_IMODE(os.stat(folder).st_mode) == 0o700
    write_cached(folder, "a.json", "[1]")
    assert read_cached(folder, "a.json") == "[1]" and read_cached(folder, "b.json") is None
    assert [p.name for p in folder.iterdir()] == ["a.json"]  # (no temporary file left)


def test_runs_sharing_an_empty_cache_at_once_write_the_same_packages_and_leave_whole_files(tmp_path):
    """Four runs started together on one empty cache folder: each fills it as it goes (templates, the matrix), none
    reads another's half-written file, and every package is byte for byte the one a run alone writes."""
    import subprocess
    import sys

    env = {**os.environ, "XACROKIT_CACHE": str(tmp_path / "cache")}
    command = "import sys; from xacrokit.cli import main; sys.exit(main())"
    runs = [
        subprocess.Popen([sys.executable, "-c", command, str(UR5), "-o", str(tmp_path / f"out{k}")], env=env)
        for k in range(4)
    ]
    assert [run.wait(timeout=300) for run in runs] == [0, 0, 0, 0]
    alone = tmp_path / "alone"
    subprocess.run([sys.executable, "-c", command, str(UR5), "-o", str(alone)], env={**env, "XACROKIT_CACHE": "off"})
    assert all(package_texts(tmp_path / f"out{k}") == package_texts(alone) for k in range(4))
    left = [p.name for p in (tmp_path / "cache").rglob("*") if p.name.endswith(".tmp")]
    assert left == []


def test_a_key_holds_the_code_that_does_the_work_so_an_edited_module_is_never_answered_from_old_results(
    tmp_path, monkeypatch
):
    from xacrokit.moveit.collision_matrix import Sampling, matrix_key
    from xacrokit.shared.user_cache import source_stamp

    (tmp_path / "worker_module.py").write_text("X = 1\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    first = source_stamp("worker_module")
    os.utime(tmp_path / "worker_module.py", ns=(1, 1))  # (edited: its time changes)
    source_stamp.cache_clear()
    assert source_stamp("worker_module") != first and "worker_module.py" in first
    source_stamp.cache_clear()
    key = matrix_key("<robot/>", "p", (), (), Sampling())
    pairs = Path(collision_pairs.__file__)
    monkeypatch.setattr(
        os, "stat", lambda path, *a, **k: os.lstat(tmp_path) if str(path) == str(pairs) else os.lstat(path)
    )
    source_stamp.cache_clear()
    assert matrix_key("<robot/>", "p", (), (), Sampling()) != key
    source_stamp.cache_clear()


def test_a_compiled_templates_name_holds_jinja2s_install_and_the_environments_module(tmp_path, monkeypatch):
    """jinja2 compiles autoescape and whitespace settings into a template's code: a new jinja2 or an edit of
    render/environment.py must not take code compiled before it."""
    import importlib

    settings_module = importlib.import_module("xacrokit.render.environment")  # (the module, not its function)
    cache = settings_module._TemplateCache(str(tmp_path))
    before = cache.get_cache_key("package/package.xml.j2")
    monkeypatch.setattr(settings_module, "source_stamp", lambda *modules: "another install")
    assert cache.get_cache_key("package/package.xml.j2") != before
