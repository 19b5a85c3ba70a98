"""The write stage: decide what happens to every file first, then write atomically, or not at all.

Per file (copier's way):

* ``create``     the file does not exist yet;
* ``identical``  it exists with exactly this content: left alone (its mtime does not change);
* ``update``     it exists as we last generated it (its hash is in the manifest): replaced;
* ``conflict``   it exists and differs from what we last generated (someone edited it), or we never generated it:
                 kept, and nothing at all is written unless ``force``;
* ``overwrite``  a conflict replaced because ``force`` was given;
* ``remove``     we generated it last time, this run does not, and it is unchanged: deleted (with any folder
                 that leaves empty), e.g. the copied macros after switching to ``--macros inline``;
* ``keep``       the same, but someone edited it: left alone and dropped from the manifest.

The manifest ``.xacrokit-manifest.json`` in the package root records the SHA-256 of each file as generated.
Nothing is ever written outside the output folder.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from . import __version__
from .errors import XacrokitError
from .fileio import write_text_atomic
from .render import RenderedFile

MANIFEST = ".xacrokit-manifest.json"
Action = Literal["create", "identical", "update", "conflict", "overwrite", "remove", "keep"]


@dataclass(frozen=True)
class FileAction:
    path: str
    action: Action
    reason: str = ""


class ConflictError(XacrokitError):
    """Files were edited since they were generated; nothing was written."""

    exit_code = 1

    def __init__(self, root: Path, conflicts: list[FileAction]):
        self.root = root
        self.conflicts = conflicts
        lines = [f"{len(conflicts)} file(s) in {root} changed since they were generated; nothing was written:"]
        lines += [f"  {c.path}: {c.reason}" for c in conflicts]
        lines.append("Keep your edits by moving them into the spec, or run again with --force to overwrite.")
        super().__init__("\n".join(lines))


def _digest(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _read_manifest(root: Path) -> dict[str, str]:
    try:
        data = json.loads((root / MANIFEST).read_text(encoding="utf-8"))
        files = data.get("files", {})
        return {str(k): str(v) for k, v in files.items()} if isinstance(files, dict) else {}
    except (OSError, ValueError, AttributeError):
        return {}


def _inside(root: Path, relative: str) -> Path:
    target = (root / relative).resolve()
    if not target.is_relative_to(root.resolve()):
        raise XacrokitError(f"refusing to write {relative}: it resolves outside {root}")
    return target


def plan(files: list[RenderedFile], root: Path, *, force: bool = False) -> list[FileAction]:
    """Decide the action for every file, touching nothing."""
    if root.exists() and not root.is_dir():
        raise XacrokitError(f"the output {root} exists and is not a folder")
    manifest = _read_manifest(root)
    actions = []
    for file in files:
        target = _inside(root, file.path)
        if not target.exists():
            actions.append(FileAction(file.path, "create"))
            continue
        if not target.is_file():
            # even --force does not replace a folder with a file
            actions.append(FileAction(file.path, "conflict", "a folder stands in its place"))
            continue
        try:
            current = target.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError):
            current = None
        if current == file.content:
            actions.append(FileAction(file.path, "identical"))
        elif current is not None and manifest.get(file.path) == _digest(current):
            actions.append(FileAction(file.path, "update"))
        else:
            reason = "edited since it was generated" if file.path in manifest else "not written by xacrokit"
            actions.append(FileAction(file.path, "overwrite" if force else "conflict", reason))
    return actions + _stale(manifest, {f.path for f in files}, root)


def _stale(manifest: dict[str, str], paths: set[str], root: Path) -> list[FileAction]:
    """What happens to the files we generated last time that this run does not generate."""
    actions = []
    for path in sorted(manifest.keys() - paths):
        try:
            target = _inside(root, path)
            current = target.read_text(encoding="utf-8") if target.is_file() else None
        except (XacrokitError, OSError, UnicodeDecodeError):
            continue  # outside the folder (a hand-made manifest), gone, or unreadable: not ours to touch
        if current is None:
            continue
        if _digest(current) == manifest[path]:
            actions.append(FileAction(path, "remove", "no longer generated"))
        else:
            actions.append(FileAction(path, "keep", "no longer generated, but edited since: kept"))
    return actions


def write(files: list[RenderedFile], root: Path, *, force: bool = False, dry_run: bool = False) -> list[FileAction]:
    """Plan, then (unless ``dry_run``) write every created, updated or overwritten file atomically.

    Raises:
        ConflictError: some file was edited since it was generated (and ``force`` is off); nothing is written.
    """
    actions = plan(files, root, force=force)
    conflicts = [a for a in actions if a.action == "conflict"]
    if conflicts:
        raise ConflictError(root, conflicts)
    if dry_run:
        return actions
    by_path = {f.path: f for f in files}
    done = 0
    try:
        for action in actions:
            if action.action in ("create", "update", "overwrite"):
                write_text_atomic(_inside(root, action.path), by_path[action.path].content)
                done += 1
        for action in actions:
            if action.action == "remove":
                _remove(root, action.path)
        manifest = {"generator": f"xacrokit {__version__}", "files": {f.path: _digest(f.content) for f in files}}
        text = json.dumps(manifest, indent=2, sort_keys=True) + "\n"
        manifest_path = root / MANIFEST
        if not manifest_path.exists() or manifest_path.read_text(encoding="utf-8") != text:
            write_text_atomic(manifest_path, text)
    except OSError as exc:
        where = exc.filename or root
        written = f"; {done} file(s) were written before it, each whole" if done else "; nothing was written"
        raise XacrokitError(f"cannot write the package in {root}: {where}: {exc.strerror or exc}{written}") from exc
    return actions


def _remove(root: Path, relative: str) -> None:
    """Delete a file we generated, then each folder above it (up to ``root``) that this leaves empty."""
    target = _inside(root, relative)
    target.unlink(missing_ok=True)
    top = root.resolve()
    folder = target.parent
    while folder != top and folder.is_relative_to(top) and not any(folder.iterdir()):
        folder.rmdir()
        folder = folder.parent
