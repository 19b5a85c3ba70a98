"""three.js ships inside the package (issue 33, item 4): each shipped file is the one of the pinned npm release, its
sha512 recorded in view/page.py and checked here; the files equal the members of the registry's tarball, whose own
integrity (the registry's sha512) is checked first; a page is made with every network call refused; a changed file
is refused, not inlined."""

from __future__ import annotations

import base64
import hashlib
import io
import json
import os
import shutil
import socket
import tarfile
import urllib.parse
import urllib.request
from pathlib import Path

import lxml.html
import pytest

from conftest import REPO
from xacrokit.errors import XacrokitError
from xacrokit.view import page as view_page

CACHE = Path(os.environ.get("XACROKIT_NPM_CACHE") or Path.home() / ".cache" / "xacrokit" / "npm")


def _sha512(data: bytes) -> str:
    return base64.b64encode(hashlib.sha512(data).digest()).decode("ascii")


def test_every_shipped_file_has_its_recorded_sha512():
    folder = view_page.three_folder()
    assert sorted(p.name for p in folder.iterdir()) == sorted(name for name, _, _ in view_page.THREE_FILES.values())
    for name, _, digest in view_page.THREE_FILES.values():
        assert _sha512((folder / name).read_bytes()) == digest, name
    assert "The MIT License" in (folder / "LICENSE").read_text(encoding="utf-8")


def _tarball() -> bytes:
    """The pinned release's tarball from the npm registry (cached): skipped when the registry cannot be reached,
    unless CI asks for every download (XACROKIT_CORPUS=require, as .ci/run sets)."""
    cached = CACHE / f"three-{view_page.THREE_VERSION}.tgz"
    if not cached.is_file():
        try:
            with urllib.request.urlopen(view_page.THREE_TARBALL, timeout=120) as response:  # noqa: S310
                data = response.read()
        except OSError as exc:
            if os.environ.get("XACROKIT_CORPUS") == "require":
                raise
            pytest.skip(f"the npm registry cannot be reached: {exc}")
        cached.parent.mkdir(parents=True, exist_ok=True)
        partial = cached.with_name(f".{cached.name}.{os.getpid()}")  # (written whole: another run may read it)
        partial.write_bytes(data)
        os.replace(partial, cached)
    return cached.read_bytes()


def test_the_shipped_files_are_the_registrys_unchanged():
    data = _tarball()
    assert "sha512-" + _sha512(data) == view_page.THREE_INTEGRITY  # (the registry's integrity of the tarball)
    with tarfile.open(fileobj=io.BytesIO(data), mode="r:gz") as archive:
        for name, member, _ in view_page.THREE_FILES.values():
            handle = archive.extractfile(member)
            assert handle is not None and handle.read() == (view_page.three_folder() / name).read_bytes(), name


def test_a_page_is_made_without_any_network(monkeypatch):
    def refused(*args, **kwargs):
        raise OSError("no network in this test")

    monkeypatch.setattr(socket, "create_connection", refused)
    monkeypatch.setattr(socket.socket, "connect", refused)
    monkeypatch.setattr(urllib.request, "urlopen", refused)
    html = view_page.page(REPO / "examples" / "robots" / "two_dof_arm.yaml")
    imports = json.loads(lxml.html.fromstring(html).find(".//script[@type='importmap']").text)["imports"]
    sources = view_page.three_sources()
    for name, key in (("three", "three"), ("three/addons/controls/OrbitControls.js", "orbit")):  # (inlined, unchanged)
        kind, _, data = imports[name].partition(",")
        assert kind == "data:text/javascript" and urllib.parse.unquote(data) == sources[key], name


def test_a_changed_shipped_file_is_refused(monkeypatch, tmp_path):
    copy = tmp_path / "three"
    shutil.copytree(view_page.three_folder(), copy)
    orbit = copy / "OrbitControls.js"
    orbit.write_text(orbit.read_text(encoding="utf-8") + "\n// changed\n", encoding="utf-8")
    monkeypatch.setattr(view_page, "three_folder", lambda: copy)
    with pytest.raises(XacrokitError, match="OrbitControls.js is not three.js 0.170.0's file"):
        view_page.three_sources()
