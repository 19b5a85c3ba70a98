"""The pre-commit hook (.pre-commit-hooks.yaml): pre-commit's own manifest reader takes it, and its entry, given the
files its ``files`` pattern selects as pre-commit gives them, passes a clean change and fails a broken robot."""

from __future__ import annotations

import json
import re
import shlex
import shutil

from check_helpers import CORPUS

from conftest import REPO, gen_robot


def hook() -> dict:
    from pre_commit.clientlib import load_manifest

    (found,) = [h for h in load_manifest(str(REPO / ".pre-commit-hooks.yaml")) if h["id"] == "gen-robot-check"]
    return found


def command(files: list[str], options: tuple[str, ...] = ("--consumers", "none")) -> list[str]:
    """What pre-commit runs for a commit's files: the entry (``options`` in it, before its ``--``, where a user of the
    hook writes them) and its args, then the files its pattern selects, in one call (require_serial)."""
    from pre_commit.lang_base import hook_cmd

    entry = hook()
    assert entry["language"] == "python" and entry["require_serial"] is True and entry["pass_filenames"] is True
    words = shlex.split(entry["entry"])
    end = words.index("--") if "--" in words else len(words)
    words[end:end] = options
    said = list(hook_cmd(shlex.join(words), entry["args"]))
    assert said[:2] == ["gen-robot", "check"]
    return said + [name for name in files if re.search(entry["files"], name)]


def committed(files: list[str], cwd) -> tuple[int, str]:
    """The hook run on a commit of ``files`` (its exit code and output)."""
    result = gen_robot(*command(files)[1:], cwd=cwd)
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


def test_files_named_like_options_are_files(tmp_path):
    """pre-commit appends the file names to the entry: a file named -j.urdf, --help.urdf or -rf.urdf was read as an
    option (-j's value '.urdf', the help, an unknown option) and the commit's robots went unchecked. The entry's --
    ends the options."""
    names = ["-j.urdf", "--help.urdf", "-rf.urdf", "--strict.urdf", "--consumers.urdf"]
    for name in names[:-1]:
        shutil.copyfile(CORPUS / "J009_pass.urdf", tmp_path / name)
    shutil.copyfile(CORPUS / "I002_fail.urdf", tmp_path / names[-1])
    result = gen_robot(*command(names, ("--consumers", "none", "--format", "json"))[1:], cwd=tmp_path)
    run = json.loads(result.stdout)
    assert result.returncode == 1 and "Traceback" not in result.stderr
    assert [(r["source"], r["summary"]["errors"] > 0) for r in run["reports"]] == [
        *((name, False) for name in names[:-1]),
        (names[-1], True),
    ]


def test_options_given_after_the_entrys_end_of_options_say_where_they_belong(tmp_path):
    """The hook's ``args`` come after its entry's --: an option there is a path, which does not exist; the message
    says to give options in the entry, before the --."""
    from pre_commit.lang_base import hook_cmd

    shutil.copyfile(CORPUS / "J009_pass.urdf", tmp_path / "arm.urdf")
    said = list(hook_cmd(hook()["entry"], ["--strict"]))
    result = gen_robot(*said[1:], "arm.urdf", cwd=tmp_path)
    assert result.returncode == 2 and result.stdout == "" and "Traceback" not in result.stderr
    assert result.stderr.startswith("gen-robot: error: --strict: no such file or folder")
    assert "before the --" in result.stderr
