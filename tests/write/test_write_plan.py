"""The write stage: plan then write; a second run changes nothing; edits are conflicts, kept unless forced; a dry
run writes nothing; nothing lands outside the package."""

from __future__ import annotations

import contextlib
import json
import os

import pytest
from write_helpers import contents, two_specs

import xacrokit
from conftest import REPO, gen_robot, gen_robot_process, snapshot
from xacrokit.errors import XacrokitError
from xacrokit.render import RenderedFile
from xacrokit.write.package_writer import MANIFEST, ConflictError, plan, write

SPEC = REPO / "examples" / "robots" / "two_dof_arm.yaml"


def test_first_run_creates_everything_and_a_second_changes_nothing(tmp_path):
    out = tmp_path / "pkg"
    first = xacrokit.generate(SPEC, out)
    assert {a.action for a in first.actions} == {"create"}
    before = snapshot(out)
    second = xacrokit.generate(SPEC, out)
    assert {a.action for a in second.actions} == {"identical"}
    assert snapshot(out) == before  # same bytes and same mtimes: nothing was rewritten


def test_an_edited_file_is_a_conflict_kept_and_nothing_is_written(tmp_path):
    out = tmp_path / "pkg"
    xacrokit.generate(SPEC, out)
    edited = out / "README.md"
    edited.write_text("my notes\n", encoding="utf-8")
    spec = tmp_path / "two_dof_arm.yaml"
    spec.write_text(SPEC.read_text(encoding="utf-8").replace("mass: 0.3", "mass: 0.35"), encoding="utf-8")
    before = snapshot(out)
    with pytest.raises(ConflictError) as caught:
        xacrokit.generate(spec, out)
    assert [c.path for c in caught.value.conflicts] == ["README.md"]
    assert "edited since it was generated" in str(caught.value)
    assert str(caught.value).splitlines()[-1].startswith("Keep your edits by moving them into the spec")
    assert snapshot(out) == before  # not even the files that would merely have been updated


def test_updates_replace_only_what_changed_and_force_overwrites_edits(tmp_path):
    out = tmp_path / "pkg"
    xacrokit.generate(SPEC, out)
    spec = tmp_path / "two_dof_arm.yaml"
    spec.write_text(SPEC.read_text(encoding="utf-8").replace("mass: 0.3", "mass: 0.35"), encoding="utf-8")
    (out / "README.md").write_text("my notes\n", encoding="utf-8")
    result = xacrokit.generate(spec, out, force=True)
    actions = {a.path: a.action for a in result.actions}
    assert actions["README.md"] == "overwrite"
    assert actions["urdf/two_dof_arm_macro.xacro"] == actions["urdf/two_dof_arm.urdf"] == "update"
    assert actions["package.xml"] == "identical"
    assert "0.35" in (out / "urdf" / "two_dof_arm.urdf").read_text(encoding="utf-8")


def test_dry_run_writes_nothing(tmp_path):
    out = tmp_path / "pkg"
    result = xacrokit.generate(SPEC, out, dry_run=True)
    assert {a.action for a in result.actions} == {"create"} and not out.exists()


def test_files_not_written_by_us_are_conflicts(tmp_path):
    out = tmp_path / "pkg"
    (out / "urdf").mkdir(parents=True)
    (out / "package.xml").write_text("<package/>", encoding="utf-8")
    with pytest.raises(ConflictError, match="not written by xacrokit") as caught:
        xacrokit.generate(SPEC, out)
    assert sorted(p.name for p in out.rglob("*")) == ["package.xml", "urdf"]
    advice = str(caught.value).splitlines()[-1]  # (not "move your edits into the spec": it was never ours)
    assert advice.startswith("A file not written by xacrokit is not ours to replace: write the package into another")
    assert "into the spec" not in str(caught.value)


def test_writes_never_leave_the_output_folder(tmp_path):
    with pytest.raises(xacrokit.XacrokitError, match="outside"):
        plan([RenderedFile("../escape.txt", "x")], tmp_path / "pkg")
    (tmp_path / "pkg").mkdir()
    (tmp_path / "elsewhere").mkdir()
    (tmp_path / "pkg" / "link").symlink_to(tmp_path / "elsewhere")
    with pytest.raises(xacrokit.XacrokitError, match="outside"):
        write([RenderedFile("link/file.txt", "x")], tmp_path / "pkg")
    assert not any((tmp_path / "elsewhere").iterdir())


def test_manifest_records_what_was_generated(tmp_path):
    out = tmp_path / "pkg"
    result = xacrokit.generate(SPEC, out)
    manifest = json.loads((out / MANIFEST).read_text(encoding="utf-8"))
    assert sorted(manifest["files"]) == sorted(f.path for f in result.files if not f.seed)
    assert [f.path for f in result.files if f.seed] == ["urdf/two_dof_arm_extension.xacro"]  # (the user's: not ours)


def test_a_folder_that_cannot_be_written_is_an_error_not_a_traceback(tmp_path):
    blocker = tmp_path / "a_file"
    blocker.write_text("x", encoding="utf-8")
    result = gen_robot(SPEC, "-o", blocker / "pkg")
    assert result.returncode != 0 and "Traceback" not in result.stderr
    assert f"cannot write the package in {blocker / 'pkg'}" in result.stderr and "nothing was written" in result.stderr


def test_a_manifest_that_is_not_utf8_is_rewritten_without_a_traceback(tmp_path):
    out = tmp_path / "pkg"
    assert gen_robot(SPEC, "-o", out).returncode == 0
    (out / MANIFEST).write_bytes(b"\xff\xfe not json")
    again = gen_robot(SPEC, "-o", out)
    assert again.returncode == 0 and "Traceback" not in again.stderr, again.stderr
    assert json.loads((out / MANIFEST).read_text(encoding="utf-8"))["files"]


def test_files_get_the_permissions_the_umask_gives(tmp_path):
    """mkstemp makes its files 0600; a package's files are read by others (colcon, a web server): 0644 under 022."""
    old = os.umask(0o022)
    try:
        xacrokit.generate(SPEC, tmp_path / "pkg")
    finally:
        os.umask(old)
    modes = {p.stat().st_mode & 0o777 for p in (tmp_path / "pkg").rglob("*") if p.is_file()}
    assert modes == {0o644}


def test_the_next_run_removes_the_temporary_files_a_killed_run_left(tmp_path):
    out = tmp_path / "pkg"
    xacrokit.generate(SPEC, out)
    left = [out / "urdf" / ".two_dof_arm.urdf.k3j_x9q2.tmp", out / ".package.xml.abcdefgh.tmp"]
    for path in left:
        path.write_text("half a file", encoding="utf-8")
    mine = out / "urdf" / ".notes.tmp"  # not one of ours (not mkstemp's name): kept
    mine.write_text("mine", encoding="utf-8")
    other = out / "urdf" / ".editor.abcdefgh.tmp"  # another program's, beside no file of the package: kept
    other.write_text("theirs", encoding="utf-8")
    (out / "urdf" / "two_dof_arm.urdf").unlink()  # (so that the run writes something)
    xacrokit.generate(SPEC, out)
    assert not any(path.exists() for path in left) and mine.read_text(encoding="utf-8") == "mine"
    assert other.read_text(encoding="utf-8") == "theirs"


def test_a_second_writer_waits_for_the_first_then_stops_with_a_message(tmp_path, monkeypatch):
    from xacrokit.write.package_writer import package_lock

    out = tmp_path / "pkg"
    with package_lock(out):  # the first writer holds the folder
        with pytest.raises(XacrokitError, match=r"another gen-robot is writing .*pkg \(waited 0.2 s\)"):
            with package_lock(out, wait=0.2):
                pass
        monkeypatch.setenv("XACROKIT_LOCK_WAIT", "0.5")  # a whole second process: refused after its wait
        result = gen_robot_process(SPEC, "-o", out)
    assert result.returncode == 2 and "another gen-robot is writing" in result.stderr, result.stderr
    assert "(waited 0.5 s)" in result.stderr
    assert not any(out.iterdir())
    assert xacrokit.generate(SPEC, out).actions  # free again once the first is done


@pytest.fixture
def full_disk(monkeypatch):
    """Called, it makes the disk fill at the third file the write stage writes from then on; it returns the list of
    the paths the stage tried."""
    import xacrokit.write.package_writer

    def install() -> list:
        real, calls = xacrokit.write.package_writer.write_text_atomic, []

        def write_until_full(path, text):
            calls.append(path)
            if len(calls) == 3:
                raise OSError(28, "No space left on device", str(path))
            real(path, text)

        monkeypatch.setattr(xacrokit.write.package_writer, "write_text_atomic", write_until_full)
        return calls

    return install


def test_a_fresh_package_that_cannot_be_written_leaves_nothing_behind(tmp_path, full_disk):
    tried = full_disk()
    with pytest.raises(XacrokitError, match="No space left on device; nothing was written"):
        xacrokit.generate(SPEC, tmp_path / "new" / "pkg")
    assert len(tried) == 3 and not (tmp_path / "new").exists()


def test_a_failed_fresh_package_removes_only_its_own_files(tmp_path, monkeypatch, full_disk):
    """Two packages made side by side in a new folder: the one that fails leaves the other whole (the review found
    that removing the new folder wholesale deleted a sibling run's package)."""
    import xacrokit.write.package_writer

    out = tmp_path / "new"
    xacrokit.generate(SPEC, out / "a")
    (out / "a" / "mine.txt").write_text("a user's file", encoding="utf-8")
    before = snapshot(out / "a")
    monkeypatch.setattr(
        xacrokit.write.package_writer, "_first_missing", lambda root: out
    )  # as if b's run had made new/ too
    full_disk()
    with pytest.raises(XacrokitError, match="what this run wrote is removed"):
        xacrokit.generate(SPEC, out / "b")
    assert not (out / "b").exists() and snapshot(out / "a") == before


def test_a_run_that_waited_for_another_writer_of_a_new_folder_does_not_undo_its_package(
    tmp_path, monkeypatch, full_disk
):
    """B starts when the folder does not exist, waits for the lock while A writes a package there, then fails: A's
    package is updated, not B's new one, so nothing of it is removed (the files of it that B replaced, the manifest
    among them, were deleted, and the next run of B found 11 conflicts)."""
    import xacrokit.write.package_writer as write_stage

    spec, clean = two_specs(tmp_path)
    out = tmp_path / "pkg"
    real_lock = write_stage.package_lock

    @contextlib.contextmanager
    def lock_after_a(root, wait=None):
        monkeypatch.setattr(write_stage, "package_lock", real_lock)
        xacrokit.generate(spec["a"], root)  # (A, the first writer, done while B waited)
        full_disk()
        with real_lock(root, wait):
            yield

    monkeypatch.setattr(write_stage, "package_lock", lock_after_a)
    with pytest.raises(XacrokitError, match=r"No space left on device; 1 file\(s\) were written before it, each whole"):
        xacrokit.generate(spec["b"], out)
    monkeypatch.undo()
    assert (out / MANIFEST).is_file() and (out / "CMakeLists.txt").is_file()
    xacrokit.generate(spec["b"], out)  # (no conflict)
    assert contents(out) == clean["b"]


def test_a_writer_that_finds_the_folder_busy_removes_nothing_of_it(tmp_path, monkeypatch):
    """A second writer that gives up waiting never held the folder: it does not undo it as a package it made (it
    removed the empty folders the first writer had just made, the package folder too, the first writer's lock on it)."""
    import xacrokit.write.package_writer as write_stage
    from xacrokit.write.package_writer import package_lock

    out = tmp_path / "pkg"
    monkeypatch.setattr(write_stage, "_first_missing", lambda root: out)  # (missing when the second run began)
    monkeypatch.setenv("XACROKIT_LOCK_WAIT", "0")
    with package_lock(out):  # the first writer, which has just made its first folder
        (out / "urdf").mkdir()
        with pytest.raises(XacrokitError, match="another gen-robot is writing"):
            xacrokit.generate(SPEC, out)
        assert (out / "urdf").is_dir()


@pytest.mark.parametrize("value", ["abc", "nan", "-1", "1e9"])
def test_a_lock_wait_that_is_no_number_of_seconds_is_refused(tmp_path, monkeypatch, value):
    monkeypatch.setenv("XACROKIT_LOCK_WAIT", value)
    with pytest.raises(XacrokitError, match="XACROKIT_LOCK_WAIT must be a number of seconds from 0 to 3600"):
        xacrokit.generate(SPEC, tmp_path / "pkg")
    assert not (tmp_path / "pkg").exists()
