"""find_package remembers a package it found (check asks for one per mesh), but never past what changes the answer:
another AMENT_PREFIX_PATH, another sys.path, another folder given, or the folder gone."""

from __future__ import annotations

import shutil
import sys

import pytest

from xacrokit.shared.ros_packages import find_package


def _package(prefix, name="probe_pkg"):
    folder = prefix / "share" / name
    folder.mkdir(parents=True)
    (folder / "package.xml").write_text(f"<package><name>{name}</name></package>", encoding="utf-8")
    return folder


def test_a_remembered_package_follows_the_prefixes_and_its_folder(tmp_path, monkeypatch):
    first, second = _package(tmp_path / "first"), _package(tmp_path / "second")
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(tmp_path / "first"))
    assert find_package("probe_pkg") == str(first)
    assert find_package("probe_pkg") == str(first)  # (remembered)
    monkeypatch.setenv("AMENT_PREFIX_PATH", f"{tmp_path / 'second'}")
    assert find_package("probe_pkg") == str(second)
    shutil.rmtree(second)
    with pytest.raises(LookupError, match="probe_pkg"):
        find_package("probe_pkg")
    monkeypatch.delenv("AMENT_PREFIX_PATH")
    monkeypatch.setattr(sys, "path", [*sys.path, str(tmp_path / "first" / "..")])
    with pytest.raises(LookupError):  # (cmeel's prefix is ENTRY/cmeel.prefix: not this one)
        find_package("probe_pkg")


def test_a_given_folder_wins_and_is_asked_again_when_it_changes(tmp_path):
    one, two = _package(tmp_path / "one"), _package(tmp_path / "two")
    assert find_package("probe_pkg", {"probe_pkg": one}) == str(one.resolve())
    assert find_package("probe_pkg", {"probe_pkg": two}) == str(two.resolve())
    link = tmp_path / "link"
    link.symlink_to(one)
    assert find_package("probe_pkg", {"probe_pkg": link}) == str(one.resolve())


def test_a_removed_working_folder_does_not_stop_the_search(tmp_path, monkeypatch):
    folder = _package(tmp_path / "prefix")
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(tmp_path / "prefix"))
    gone = tmp_path / "gone"
    gone.mkdir()
    monkeypatch.chdir(gone)
    gone.rmdir()
    assert find_package("probe_pkg") == str(folder)
