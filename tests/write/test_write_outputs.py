"""The write stage for command outputs (xacrokit.write.outputs): planned then written or nothing is; never through a
link, a device, a FIFO or a socket; a file gen-robot did not write is a conflict unless forced; its own files are
updated."""

from __future__ import annotations

import hashlib
import json
import os
import stat

import pytest

from xacrokit.write.outputs import RECORD, OutputConflict, OutputFile, OutputRefused, output_file, write_outputs


def test_a_new_file_is_created_and_recorded(tmp_path):
    actions = output_file(tmp_path / "page.html", "<html/>")
    assert [(a.path, a.action) for a in actions] == [("page.html", "create")]
    assert (tmp_path / "page.html").read_text() == "<html/>"
    record = json.loads((tmp_path / RECORD).read_text())
    assert list(record["files"]) == ["page.html"]


def test_our_own_file_is_updated_and_the_same_content_left_alone(tmp_path):
    output_file(tmp_path / "a.txt", "one")
    before = (tmp_path / "a.txt").stat().st_mtime_ns
    assert output_file(tmp_path / "a.txt", "one")[0].action == "identical"
    assert (tmp_path / "a.txt").stat().st_mtime_ns == before
    assert output_file(tmp_path / "a.txt", "two")[0].action == "update"
    assert (tmp_path / "a.txt").read_text() == "two"
    assert output_file(tmp_path / "a.txt", b"three")[0].action == "update"  # (the digest of "two" recorded)


def test_a_file_we_did_not_write_is_a_conflict_and_nothing_at_all_is_written(tmp_path):
    (tmp_path / "spec.yaml").write_text("hand-written")
    files = [OutputFile("meshes/a.stl", b"mesh"), OutputFile("spec.yaml", "imported")]
    with pytest.raises(OutputConflict, match=r"(?s)spec\.yaml: it exists and was not written by gen-robot.*--force"):
        write_outputs(tmp_path, files)
    assert (tmp_path / "spec.yaml").read_text() == "hand-written"
    assert not (tmp_path / "meshes").exists() and not (tmp_path / RECORD).exists()
    actions = write_outputs(tmp_path, files, force=True)
    assert [a.action for a in actions] == ["create", "overwrite"]
    assert (tmp_path / "spec.yaml").read_text() == "imported"
    assert write_outputs(tmp_path, [OutputFile("spec.yaml", "again")])[0].action == "update"  # ours now


def test_a_file_edited_since_we_wrote_it_is_a_conflict(tmp_path):
    output_file(tmp_path / "a.txt", "ours")
    (tmp_path / "a.txt").write_text("edited")
    with pytest.raises(OutputConflict):
        output_file(tmp_path / "a.txt", "ours again")
    assert (tmp_path / "a.txt").read_text() == "edited"


def test_a_symbolic_link_is_refused_and_neither_it_nor_its_target_changes(tmp_path):
    target = tmp_path / "elsewhere.txt"
    target.write_text("precious")
    (tmp_path / "out.html").symlink_to(target)
    with pytest.raises(OutputRefused, match="out.html: it is a symbolic link"):
        output_file(tmp_path / "out.html", "page", force=True)
    assert (tmp_path / "out.html").is_symlink() and target.read_text() == "precious"


def test_a_folder_on_the_way_that_is_a_link_is_refused(tmp_path):
    (tmp_path / "real").mkdir()
    (tmp_path / "meshes").symlink_to(tmp_path / "real")
    with pytest.raises(OutputRefused, match="meshes: it is a symbolic link"):
        write_outputs(tmp_path, [OutputFile("model.xml", "<mujoco/>"), OutputFile("meshes/a.obj", "v 0 0 0")])
    assert not (tmp_path / "model.xml").exists() and not any((tmp_path / "real").iterdir())


def test_a_fifo_is_refused_without_blocking(tmp_path):
    os.mkfifo(tmp_path / "pipe")
    with pytest.raises(OutputRefused, match="device, FIFO or socket"):
        output_file(tmp_path / "pipe", "text", force=True)
    assert stat.S_ISFIFO(os.lstat(tmp_path / "pipe").st_mode)


def test_a_device_is_never_replaced():
    with pytest.raises(OutputRefused, match="/dev/full: it is a device, FIFO or socket"):
        output_file("/dev/full", "text", force=True)
    assert stat.S_ISCHR(os.lstat("/dev/full").st_mode)


@pytest.mark.parametrize("relative", ["../escape.txt", "/abs.txt", "a/./b.txt", ""])
def test_a_path_out_of_the_folder_is_refused(tmp_path, relative):
    with pytest.raises(OutputRefused, match="not a path inside"):
        write_outputs(tmp_path / "out", [OutputFile(relative, "x")])
    assert not (tmp_path / "escape.txt").exists() and not (tmp_path / "out").exists()


def test_a_record_that_is_a_link_is_refused(tmp_path):
    (tmp_path / "other.json").write_text("{}")
    (tmp_path / RECORD).symlink_to(tmp_path / "other.json")
    with pytest.raises(OutputRefused, match="symbolic link"):
        output_file(tmp_path / "a.txt", "x")
    assert (tmp_path / "other.json").read_text() == "{}"


def test_a_run_killed_among_its_writes_is_taken_over_by_the_next(tmp_path, monkeypatch):
    """The record holds both digests while files are written: whatever a killed run left (the old file or its new
    one), the next run, with new content again, updates it without a false conflict."""
    import xacrokit.write.outputs as outputs

    write_outputs(tmp_path, [OutputFile("model.xml", "v1"), OutputFile("meshes/a.obj", "mesh v1")])
    real = outputs.write_text_atomic
    calls = []

    def dying(path, content):
        if path.name != RECORD:
            calls.append(path)
        if len(calls) == 2:
            raise KeyboardInterrupt  # (killed after the first file of the run)
        real(path, content)

    monkeypatch.setattr(outputs, "write_text_atomic", dying)
    with pytest.raises(KeyboardInterrupt):
        write_outputs(tmp_path, [OutputFile("model.xml", "v2"), OutputFile("meshes/a.obj", "mesh v2")])
    monkeypatch.setattr(outputs, "write_text_atomic", real)
    assert (tmp_path / "model.xml").read_text() == "v2" and (tmp_path / "meshes/a.obj").read_text() == "mesh v1"
    actions = write_outputs(tmp_path, [OutputFile("model.xml", "v3"), OutputFile("meshes/a.obj", "mesh v3")])
    assert [a.action for a in actions] == ["update", "update"]
    assert json.loads((tmp_path / RECORD).read_text())["files"]["model.xml"] == [hashlib.sha256(b"v3").hexdigest()]


def test_a_large_file_of_someone_elses_is_compared_without_reading_it_whole(tmp_path):
    big = tmp_path / "big.bin"
    with big.open("wb") as handle:  # (sparse: 64 MiB on the file system's word, nothing on disk)
        handle.seek(64 * 2**20)
        handle.write(b"\0")
    with pytest.raises(OutputConflict):
        output_file(big, "page")
    assert big.stat().st_size == 64 * 2**20 + 1


def test_a_staged_package_is_known_as_one_and_a_folder_of_yours_is_not(tmp_path):
    """export reads a spec's staged meshes while they last (is_staged); anything else is streamed at write time."""
    from xacrokit.write.atomic import is_staged, staged_packages

    class Item:
        path, content = "meshes/a.stl", b"solid"

    with staged_packages({"p_description": [Item()]}) as staged:
        assert is_staged(staged["p_description"])
    assert not is_staged(tmp_path) and not is_staged(tmp_path / "xacrokit-staged-x" / "p")
