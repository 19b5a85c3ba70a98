"""Every example and scene generates, file for file and byte for byte, the package recorded in package_digests.json
(recorded before issue 27's restructure; package_digests.py says when to record again)."""

from __future__ import annotations

import json
import os
import platform
import subprocess
import sys
from pathlib import Path

import pytest

from package_digests import CASES, RECORD, digests

RECORDED = json.loads(RECORD.read_text(encoding="utf-8"))


def test_the_record_covers_every_case():
    assert sorted(RECORDED) == sorted(f"{relative} {mode}" for relative, mode in CASES)
    assert len(CASES) >= 19


@pytest.mark.parametrize(("relative", "mode"), CASES, ids=[f"{r}-{m}" for r, m in CASES])
def test_the_package_is_byte_for_byte_as_recorded(relative, mode):
    now = digests(relative, mode)
    before = RECORDED[f"{relative} {mode}"]
    assert sorted(now) == sorted(before), "files added or gone"
    changed = [name for name in before if now[name] != before[name]]
    assert not changed, f"changed since recorded: {changed}"


# OpenBLAS picks its kernels by the processor; these run on any x86-64 (newer ones than the machine's are refused)
KERNELS = ("Prescott", "Haswell")


@pytest.mark.skipif(platform.machine() != "x86_64", reason="OpenBLAS's x86-64 kernel names")
def test_a_composite_link_is_the_same_bits_whichever_blas_kernel_the_processor_gets():
    # the rover's chassis composes rotated parts: with numpy's @ its ixx differed in the last digit between two CI
    # machines (OpenBLAS's Prescott kernel against Haswell's); every kernel must give the recorded package
    script = "import json, package_digests; print(json.dumps(package_digests.digests('robots/rover.yaml', 'inline')))"
    found = {}
    for kernel in KERNELS:
        env = {**os.environ, "OPENBLAS_CORETYPE": kernel, "PYTHONPATH": str(Path(__file__).parent)}
        done = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True)
        found[kernel] = json.loads(done.stdout)
    assert found["Prescott"] == found["Haswell"] == RECORDED["robots/rover.yaml inline"]
