"""Fault injection: on real gen-robot processes, SIGKILL at chosen and at random points of a first write and of an
update, and two writers at once; with the command line run in the test's process (conftest.gen_robot), a read-only
folder and a full disk. After each: no torn file (every file is whole, as one spec or the other generates it), and the
next run succeeds and gives exactly the package a clean run gives.

The kill points are seeded (the same on every run). The read-only folder and the full disk need a small tmpfs,
which only root can mount: elsewhere those tests are skipped, with the reason."""

from __future__ import annotations

import contextlib
import json
import os
import random
import re
import signal
import subprocess
import sys
import time

import pytest
from write_helpers import contents, two_specs

import xacrokit
from conftest import gen_robot
from xacrokit.write.atomic import TEMPORARY
from xacrokit.write.package_writer import MANIFEST

SEED = 20261124

# gen-robot, killed by SIGKILL at the K-th call (from 0) of STAGE: "write" (before a file's atomic write begins) or
# "rename" (after its temporary file is written, before it replaces the file: leaves the temporary behind)
KILLER = """
import os, signal, sys
import xacrokit.write.atomic as fileio, xacrokit.write.package_writer as write
point, stage = int(os.environ["KILL_AT"]), os.environ["KILL_STAGE"]
calls = []
def maybe_die():
    calls.append(1)
    if len(calls) > point:
        os.kill(os.getpid(), signal.SIGKILL)
if stage == "write":
    original = write.write_text_atomic
    def dying(*args, **kwargs):
        maybe_die()
        return original(*args, **kwargs)
    write.write_text_atomic = dying
else:
    replace = os.replace
    def dying_replace(*args, **kwargs):
        maybe_die()
        return replace(*args, **kwargs)
    fileio.os.replace = dying_replace
from xacrokit.cli.app import main
sys.exit(main(sys.argv[1:]))
"""


@pytest.fixture(scope="module")
def specs(tmp_path_factory):
    return two_specs(tmp_path_factory.mktemp("specs"))


def gen_robot_killed(spec, out, point, stage):
    env = {**os.environ, "KILL_AT": str(point), "KILL_STAGE": stage}
    return subprocess.run(
        [sys.executable, "-c", KILLER, str(spec), "-o", str(out)], env=env, capture_output=True, text=True, timeout=120
    )


def assert_no_torn_file(out, clean):
    """Every file is whole: as spec A or spec B generates it, the manifest (in progress or done), or a temporary of
    ours that a kill left (a beginning of a file's content: the kill may come while it is written; the next run
    removes it)."""
    for path, data in contents(out).items():
        name = path.rsplit("/", 1)[-1]
        if path == MANIFEST:
            json.loads(data)  # (whole JSON)
        elif TEMPORARY.fullmatch(name):
            original = path.rsplit("/", 1)[0] + "/" + name[1:-13] if "/" in path else name[1:-13]
            if original == MANIFEST:
                json.loads(data)
            else:  # (written, whole or in part when the kill came mid-write, and never renamed: never the file)
                assert any(c.get(original, b"\0").startswith(data) for c in (clean["a"], clean["b"])), path
        else:
            assert data in (clean["a"].get(path), clean["b"].get(path)), path


def assert_repaired(out, spec, clean):
    xacrokit.generate(spec, out)  # (no ConflictError)
    assert contents(out) == clean
    assert not [p for p in out.rglob("*") if TEMPORARY.fullmatch(p.name)]


def kill_points(count, total):
    rng = random.Random(SEED + total)
    return sorted({0, total - 1, *rng.sample(range(total), min(count, total))})


@pytest.mark.parametrize("stage", ["write", "rename"])
@pytest.mark.parametrize("scenario", ["first write", "update"])
def test_sigkill_at_chosen_points_leaves_nothing_torn_and_the_next_run_repairs(tmp_path, specs, scenario, stage):
    spec, clean = specs
    files = len(clean["b"])  # (the writes of a run: its files and the manifest twice, at most)
    killed = 0
    for point in kill_points(3, files + 1):
        out = tmp_path / f"{stage}_{point}"
        if scenario == "update":
            xacrokit.generate(spec["a"], out)
        result = gen_robot_killed(spec["b"], out, point, stage)
        if result.returncode == -signal.SIGKILL:
            killed += 1
        else:  # (past the last write: the run finished)
            assert result.returncode == 0, result.stderr
        if out.exists():
            assert_no_torn_file(out, clean)
        for then in ("a", "b"):
            assert_repaired(out, spec[then], clean[then])
    assert killed >= 2


def test_sigkill_at_random_times_leaves_nothing_torn(tmp_path, specs):
    spec, clean = specs
    rng = random.Random(SEED)
    for attempt in range(4):
        out = tmp_path / f"t{attempt}"
        xacrokit.generate(spec["a"], out)
        process = subprocess.Popen(
            [sys.executable, "-m", "xacrokit.cli", str(spec["b"]), "-o", str(out)],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        time.sleep(rng.uniform(0.2, 1.2))  # (a run takes about 0.5 to 1 s: before, during or after its writes)
        process.send_signal(signal.SIGKILL)
        process.wait(timeout=60)
        assert_no_torn_file(out, clean)
        assert_repaired(out, spec["b" if attempt % 2 else "a"], clean["b" if attempt % 2 else "a"])


@pytest.mark.parametrize("wait", ["10", "0"])
def test_two_writers_at_once_leave_one_whole_package(tmp_path, specs, wait):
    spec, clean = specs
    env = {**os.environ, "XACROKIT_LOCK_WAIT": wait}
    for attempt in range(2):
        out = tmp_path / f"w{attempt}"
        runs = {
            name: subprocess.Popen(
                [sys.executable, "-m", "xacrokit.cli", str(spec[name]), "-o", str(out)],
                env=env,
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
                text=True,
            )
            for name in ("a", "b")
        }
        results = {name: (run.wait(timeout=120), run.stderr.read()) for name, run in runs.items()}
        for run in runs.values():
            run.stdout.close()
            run.stderr.close()
        for code, err in results.values():
            assert code == 0 or (code == 2 and "another gen-robot is writing" in err), err
        done = contents(out)
        assert done in (clean["a"], clean["b"]), sorted(done)  # one package, never a mix
        winners = [n for n in ("a", "b") if done == clean[n]]
        assert results[winners[0]][0] == 0
        if wait == "10":
            assert all(code == 0 for code, _ in results.values())


@contextlib.contextmanager
def small_tmpfs(folder, size):
    """A tmpfs of ``size`` mounted on ``folder`` (root only), unmounted after."""
    folder.mkdir(parents=True, exist_ok=True)
    if os.geteuid() != 0:
        pytest.skip("mounting a small tmpfs needs root (a full disk and a read-only folder are simulated elsewhere)")
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(folder)], capture_output=True)
    if mounted.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {mounted.stderr.decode(errors='replace').strip()}")
    try:
        yield folder
    finally:
        subprocess.run(["umount", "-l", str(folder)], capture_output=True)


def test_a_read_only_folder_is_refused_whole_and_the_next_run_writes(tmp_path, specs):
    spec, clean = specs
    with small_tmpfs(tmp_path / "mnt", "4m") as disk:
        out = disk / "pkg"
        xacrokit.generate(spec["a"], out)
        subprocess.run(["mount", "-o", "remount,ro", str(disk)], check=True)
        try:
            refused = gen_robot(spec["b"], "-o", out)
            assert refused.returncode == 2 and "Read-only file system" in refused.stderr, refused.stderr
            assert "Traceback" not in refused.stderr
            assert contents(out) == clean["a"]
        finally:
            subprocess.run(["mount", "-o", "remount,rw", str(disk)], check=True)
        assert_repaired(out, spec["b"], clean["b"])


def test_a_full_disk_leaves_no_partial_fresh_package_and_no_torn_update(tmp_path, specs):
    spec, clean = specs
    with small_tmpfs(tmp_path / "mnt", "40k") as disk:  # (the package takes about 76 kB in 4 kB pages)
        refused = gen_robot(spec["a"], "-o", disk / "pkg")
        assert refused.returncode == 2 and "No space left on device" in refused.stderr, refused.stderr
        assert "nothing was written" in refused.stderr and not (disk / "pkg").exists()
    with small_tmpfs(tmp_path / "mnt2", "1m") as disk:
        out = disk / "pkg"
        xacrokit.generate(spec["a"], out)
        filler = disk / "filler"
        with open(
            filler, "wb", buffering=0
        ) as handle:  # fill the disk to its last pages (unbuffered: nothing left to flush)
            with contextlib.suppress(OSError):
                while True:
                    handle.write(b"\0" * 4096)
        refused = gen_robot(spec["b"], "-o", out)
        assert refused.returncode == 2 and "No space left on device" in refused.stderr, refused.stderr
        assert re.search(r"(\d+ file\(s\) were written before it, each whole|nothing was written)", refused.stderr)
        assert_no_torn_file(out, clean)
        filler.unlink()
        assert_repaired(out, spec["b"], clean["b"])
