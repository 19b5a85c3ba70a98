"""The pre-commit hook (.pre-commit-hooks.yaml): pre-commit's own manifest reader takes it, and its entry, given the
files its ``files`` pattern selects as pre-commit gives them, passes a clean change and fails a broken robot."""

from __future__ import annotations

import re
import shlex
import shutil

from check_helpers import CORPUS

from conftest import REPO, gen_robot


def hook() -> dict:
    from pre_commit.clientlib import load_manifest

    (found,) = [h for h in load_manifest(str(REPO / ".pre-commit-hooks.yaml")) if h["id"] == "gen-robot-check"]
    return found


def committed(files: list[str], cwd) -> tuple[int, str]:
    """What pre-commit does with a commit's files: those its pattern selects, in one call (require_serial)."""
    entry = hook()
    assert entry["language"] == "python" and entry["require_serial"] is True and entry["pass_filenames"] is True
    chosen = [name for name in files if re.search(entry["files"], name)]
    command = shlex.split(entry["entry"])
    assert command[:2] == ["gen-robot", "check"]
    result = gen_robot(*command[1:], "--consumers", "none", *chosen, cwd=cwd)
    assert "Traceback" not in result.stderr
    return result.returncode, result.stdout


def test_the_hook_checks_the_robots_of_a_commit_and_skips_the_rest(tmp_path):
    shutil.copyfile(REPO / "examples" / "robots" / "rp_arm.yaml", tmp_path / "rp_arm.yaml")
    shutil.copyfile(CORPUS / "J009_pass.urdf", tmp_path / "arm.urdf")
    (tmp_path / "controllers.yaml").write_text("controller_manager:\n  ros__parameters: {update_rate: 100}\n")
    (tmp_path / "README.md").write_text("not a robot\n")
    code, out = committed(["rp_arm.yaml", "arm.urdf", "controllers.yaml", "README.md"], tmp_path)
    assert code == 0
    assert [line.split(":")[0] for line in out.splitlines()[:-1]] == ["rp_arm.yaml", "arm.urdf"]
    shutil.copyfile(CORPUS / "I002_fail.urdf", tmp_path / "broken.urdf")
    code, out = committed(["controllers.yaml", "broken.urdf"], tmp_path)
    assert code == 1 and out.splitlines()[0].startswith("broken.urdf: FAILED")


def test_a_commit_without_robots_passes(tmp_path):
    (tmp_path / "controllers.yaml").write_text("a: 1\n")
    assert committed(["controllers.yaml"], tmp_path)[0] == 0
