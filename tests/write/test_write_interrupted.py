"""A run stopped at any point (here: an exception that, like SIGKILL, runs none of the write's cleanups, raised
before the k-th file write or removal) leaves a folder the next run takes over: the manifest is written "in progress"
first, with every file's last and next digest, and completed last. Regenerating either spec then gives no false
conflict and exactly the package a clean run gives; an edit is still never overwritten. (Real SIGKILLs of a
gen-robot process: tests/write/test_write_faults.py.)"""

from __future__ import annotations

import json
import os

import pytest
from write_helpers import contents, two_specs

import xacrokit
import xacrokit.write.package_writer as write_stage
from xacrokit.write.package_writer import MANIFEST, ConflictError


class Killed(BaseException):
    """Stands for SIGKILL: not an Exception, so no handler of ours turns it into a message or cleans up after it."""


@pytest.fixture(scope="module")
def specs(tmp_path_factory):
    return two_specs(tmp_path_factory.mktemp("specs"))


def killed_after(monkeypatch, target, function, count):
    """Make ``target.function`` raise Killed on its call number ``count`` (0: the first)."""
    original = getattr(target, function)
    calls = []

    def dying(*args, **kwargs):
        calls.append(1)
        if len(calls) > count:
            raise Killed
        return original(*args, **kwargs)

    monkeypatch.setattr(target, function, dying)


def killed_update(spec_from, spec_to, out, target, function, count):
    """Generate ``spec_from`` into ``out``, then update it to ``spec_to``, killed at call ``count`` of
    ``target.function``."""
    xacrokit.generate(spec_from, out)
    with pytest.MonkeyPatch.context() as patch:
        killed_after(patch, target, function, count)
        with pytest.raises(Killed):
            xacrokit.generate(spec_to, out)


def count_writes(spec_from, spec_to, out):
    """How many atomic writes an update from one spec to the other makes (the manifest's two included)."""
    xacrokit.generate(spec_from, out)
    calls = []
    original = write_stage.write_text_atomic

    def counting(*args, **kwargs):
        calls.append(1)
        return original(*args, **kwargs)

    write_stage.write_text_atomic = counting
    try:
        xacrokit.generate(spec_to, out)
    finally:
        write_stage.write_text_atomic = original
    return len(calls)


@pytest.mark.parametrize("then", ["a", "b"])
def test_an_update_killed_at_any_write_is_completed_by_the_next_run_of_either_spec(tmp_path, specs, then):
    spec, clean = specs
    writes = count_writes(spec["a"], spec["b"], tmp_path / "count")
    assert writes >= 10
    for k in range(writes):
        out = tmp_path / f"k{k}"
        killed_update(spec["a"], spec["b"], out, write_stage, "write_text_atomic", k)
        if k > 0:  # (killed before its first write: the folder is still A's, with A's manifest)
            assert "in_progress" in json.loads((out / MANIFEST).read_text())
        result = xacrokit.generate(spec[then], out)  # no ConflictError
        assert contents(out) == clean[then], k
        assert "in_progress" not in json.loads((out / MANIFEST).read_text())
        assert {a.action for a in xacrokit.generate(spec[then], out).actions} == {"identical"}, result.actions


def test_an_update_killed_while_removing_stale_files_is_completed(tmp_path, specs):
    spec, clean = specs
    for k in range(4):
        out = tmp_path / f"r{k}"
        killed_update(spec["a"], spec["b"], out, os, "unlink", k)
        left = contents(out).keys() - clean["b"].keys()
        assert left, "some of A's files were left, to be removed by the next run"
        xacrokit.generate(spec["b"], out)
        assert contents(out) == clean["b"], k


def test_an_edit_made_after_a_killed_run_is_still_a_conflict(tmp_path, specs):
    spec, _ = specs
    out = tmp_path / "pkg"
    killed_update(spec["a"], spec["b"], out, write_stage, "write_text_atomic", 3)
    readme = out / "README.md"
    readme.write_text(readme.read_text(encoding="utf-8") + "my notes\n", encoding="utf-8")
    with pytest.raises(ConflictError) as caught:
        xacrokit.generate(spec["a"], out)
    assert [c.path for c in caught.value.conflicts] == ["README.md"]
    assert readme.read_text(encoding="utf-8").endswith("my notes\n")


def test_a_manifest_of_the_older_form_is_read(tmp_path, specs):
    spec, clean = specs
    out = tmp_path / "pkg"
    xacrokit.generate(spec["a"], out)
    data = json.loads((out / MANIFEST).read_text())
    assert all(isinstance(v, str) for v in data["files"].values())  # done: one digest per file, as before
    xacrokit.generate(spec["b"], out)
    assert contents(out) == clean["b"]
