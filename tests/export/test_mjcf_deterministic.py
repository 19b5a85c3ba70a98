"""The MJCF export is the same bytes on every run: its contact exclusions once followed a set's order, which Python's
string hashing changes from process to process (seen on the bin-sorting cell's scene)."""

from __future__ import annotations

import os
import subprocess
import sys

from conftest import REPO

SCENE = REPO / "examples" / "scenes" / "bin_sorting_cell.yaml"


def test_two_processes_with_other_hash_seeds_write_the_same_model(tmp_path):
    models = []
    for seed in ("1", "2", "3"):
        target = tmp_path / seed / "cell.xml"
        done = subprocess.run(
            [sys.executable, "-m", "xacrokit.cli", "export", str(SCENE), "--mjcf", "-o", str(target)],
            env={**os.environ, "PYTHONHASHSEED": seed},
            capture_output=True,
            text=True,
            check=False,
        )
        assert done.returncode == 0, done.stderr
        models.append(target.read_bytes())
    assert b"<exclude" in models[0]
    assert models[0] == models[1] == models[2]
