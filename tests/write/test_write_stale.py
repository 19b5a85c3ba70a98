"""The write stage on regeneration: files no longer generated are removed when still as generated, kept when
edited, behind links or not removable."""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import PurePosixPath

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import xacrokit
from conftest import REPO, gen_robot, snapshot
from xacrokit.render import RenderedFile
from xacrokit.write.package_writer import MANIFEST, ConflictError, write

SPEC = REPO / "examples" / "robots" / "two_dof_arm.yaml"


def test_switching_modes_removes_what_is_no_longer_generated_and_keeps_edits(tmp_path):
    arm = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
    out = tmp_path / "pkg"
    copied = {f.path for f in xacrokit.generate(arm, out, macros="copy").files}
    stale = sorted(p for p in copied if p.startswith("urdf/xacrokit/") or p.endswith(".dh.yaml"))
    assert "urdf/xacrokit/dh.xacro" in stale and "config/ur5.dh.yaml" in stale
    edited = out / "urdf" / "xacrokit" / "links.xacro"
    edited.write_text(edited.read_text(encoding="utf-8") + "<!-- mine -->\n", encoding="utf-8")
    before = snapshot(out)
    dry = gen_robot(arm, "-o", out, "--dry-run")
    plan_lines = {" ".join(line.split()) for line in dry.stdout.splitlines()}
    assert dry.returncode == 0 and "remove urdf/xacrokit/dh.xacro (no longer generated)" in plan_lines, dry.stdout
    assert "would remove 5 no longer generated; would keep 1" in dry.stdout
    assert snapshot(out) == before
    result = gen_robot(arm, "-o", out)
    assert result.returncode == 0, result.stderr
    assert "removed 5 no longer generated; kept 1 no longer generated (edited, or not removable)" in result.stdout, (
        result.stdout
    )
    assert "keep urdf/xacrokit/links.xacro (no longer generated, but edited since: kept)" in {
        " ".join(line.split()) for line in result.stdout.splitlines()
    }
    left = {p.relative_to(out).as_posix() for p in out.rglob("*")}
    assert [p for p in stale if p in left] == ["urdf/xacrokit/links.xacro"]
    assert "urdf/xacrokit/_inc" not in left  # the folder it emptied went too
    assert "urdf/xacrokit/links.xacro" not in json.loads((out / MANIFEST).read_text(encoding="utf-8"))["files"]
    again = xacrokit.generate(arm, out)
    assert {a.action for a in again.actions} == {"identical"}  # the kept file is no longer ours


def add_to_manifest(out, path, content: bytes):
    manifest = json.loads((out / MANIFEST).read_text(encoding="utf-8"))
    manifest["files"][path] = hashlib.sha256(content).hexdigest()
    (out / MANIFEST).write_text(json.dumps(manifest), encoding="utf-8")


def test_a_manifest_naming_files_outside_the_folder_removes_nothing_there(tmp_path):
    out = tmp_path / "pkg"
    xacrokit.generate(SPEC, out)
    victim = tmp_path / "victim.txt"
    victim.write_text("x", encoding="utf-8")
    for name in ("../victim.txt", str(victim), "urdf/../../victim.txt", "./../victim.txt", "a\0b"):
        add_to_manifest(out, name, b"x")
    result = xacrokit.generate(SPEC, out)
    assert victim.exists() and {a.action for a in result.actions} == {"identical"}


def test_stale_files_behind_links_or_written_this_run_are_never_removed(tmp_path):
    out = tmp_path / "pkg"
    xacrokit.generate(SPEC, out)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "old.xacro").write_text("x", encoding="utf-8")
    (out / "linked").symlink_to(elsewhere)  # a folder link: the file behind it is not ours to delete
    add_to_manifest(out, "linked/old.xacro", b"x")
    (out / "urdf" / "alias.xacro").symlink_to(elsewhere / "old.xacro")  # a file link
    add_to_manifest(out, "urdf/alias.xacro", b"x")
    (out / "real").mkdir()  # a link to a folder inside the package: the user's file behind it is not ours either
    (out / "real" / "f.txt").write_text("x", encoding="utf-8")
    (out / "inner").symlink_to(out / "real")
    add_to_manifest(out, "inner/f.txt", b"x")
    entry = out / "urdf" / "two_dof_arm.urdf.xacro"
    os.link(entry, out / "urdf" / "OLD.urdf.xacro")  # another name for a file this run writes
    add_to_manifest(out, "urdf/OLD.urdf.xacro", entry.read_bytes())
    result = xacrokit.generate(SPEC, out)
    assert (elsewhere / "old.xacro").exists() and (out / "urdf" / "alias.xacro").is_symlink()
    assert (out / "real" / "f.txt").exists() and entry.exists()
    stale = {a.path: a for a in result.actions if a.action in ("remove", "keep")}
    assert {p: a.action for p, a in stale.items()} == dict.fromkeys(
        ["inner/f.txt", "linked/old.xacro", "urdf/OLD.urdf.xacro", "urdf/alias.xacro"], "keep"
    )
    assert all("symbolic link" in stale[p].reason for p in ("inner/f.txt", "linked/old.xacro", "urdf/alias.xacro"))


def test_a_removal_the_file_system_refuses_is_reported_as_kept(tmp_path, monkeypatch):
    arm = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
    out = tmp_path / "pkg"
    xacrokit.generate(arm, out, macros="copy")

    def refuse(path, *, dir_fd=None):
        raise PermissionError(13, "Permission denied", str(path))

    monkeypatch.setattr(os, "unlink", refuse)
    result = xacrokit.generate(arm, out)
    kept = [a for a in result.actions if a.action == "keep"]
    assert kept and all("could not remove it: Permission denied" in a.reason for a in kept)
    assert not any(a.action == "remove" for a in result.actions)
    monkeypatch.undo()
    again = xacrokit.generate(arm, out)  # the manifest was written: the next run is not stuck on them
    assert {a.action for a in again.actions} == {"identical"}
    assert (out / "urdf" / "xacrokit" / "dh.xacro").exists()  # left for the user, no longer ours


PATHS = [f"{folder}{name}" for folder in ("", "x/", "x/y/", "z/") for name in ("a.txt", "b.txt")]


@settings(suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    old=st.dictionaries(st.sampled_from(PATHS), st.sampled_from(["1", "2"]), min_size=1),
    new=st.dictionaries(st.sampled_from(PATHS), st.sampled_from(["1", "3"]), min_size=1),
    edited=st.sets(st.sampled_from(PATHS)),
    foreign=st.sets(st.sampled_from(["x/mine.txt", "z/y/mine.txt", "mine.txt"])),
)
def test_regenerating_touches_only_what_we_generated_and_nobody_edited(tmp_path_factory, old, new, edited, foreign):
    out = tmp_path_factory.mktemp("regen") / "pkg"
    write([RenderedFile(p, c) for p, c in old.items()], out)
    edited = {p for p in edited if p in old}
    for path in edited:
        (out / path).write_text("edited", encoding="utf-8")
    for path in foreign:
        (out / path).parent.mkdir(parents=True, exist_ok=True)
        (out / path).write_text("mine", encoding="utf-8")
    files = [RenderedFile(p, c) for p, c in new.items()]
    conflicts = {p for p in edited if p in new and new[p] != "edited"}
    if conflicts:
        with pytest.raises(ConflictError):
            write(files, out)
        return
    actions = {a.path: a.action for a in write(files, out)}
    on_disk = {p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file()} - {MANIFEST}
    assert {p: (out / p).read_text(encoding="utf-8") for p in new} == new  # what we generate is there
    assert all((out / p).read_text(encoding="utf-8") == "mine" for p in foreign)  # never ours: untouched
    stale = set(old) - set(new)
    assert {p for p in stale if p in edited} <= on_disk  # edited: kept
    assert not ({p for p in stale if p not in edited} & on_disk)  # ours and unedited: removed
    assert {p: a for p, a in actions.items() if p in stale} == {p: "keep" if p in edited else "remove" for p in stale}
    assert on_disk == set(new) | set(foreign) | (stale & edited)
    emptied = {str(PurePosixPath(p).parent) for p in stale - edited} - {"."}
    for folder in emptied:  # a folder our removals emptied is gone; one with anything left stays
        left = [q for q in on_disk if q.startswith(folder + "/")]
        assert (out / folder).exists() == bool(left), folder
    assert set(json.loads((out / MANIFEST).read_text(encoding="utf-8"))["files"]) == set(new)


def test_a_folder_swapped_for_a_link_while_we_write_does_not_lead_removal_outside(tmp_path, monkeypatch):
    import xacrokit.write.package_writer as write_module

    out, outside = tmp_path / "pkg", tmp_path / "outside"
    write([RenderedFile("x/f.txt", "1"), RenderedFile("a.txt", "1")], out)
    outside.mkdir()
    (outside / "f.txt").write_text("1", encoding="utf-8")  # the same bytes as the stale file
    original = write_module.write_text_atomic

    def write_then_swap(path, text):
        original(path, text)
        if (out / "x").is_dir() and not (out / "x").is_symlink():
            (out / "x").rename(tmp_path / "moved")
            (out / "x").symlink_to(outside)

    monkeypatch.setattr(write_module, "write_text_atomic", write_then_swap)
    actions = {a.path: a for a in write([RenderedFile("a.txt", "2")], out)}
    assert (outside / "f.txt").read_text(encoding="utf-8") == "1"
    assert actions["x/f.txt"].action == "keep" and "symbolic link" in actions["x/f.txt"].reason
