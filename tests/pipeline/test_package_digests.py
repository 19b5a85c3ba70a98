"""Every example and scene generates, file for file and byte for byte, the package recorded in package_digests.json
(recorded before issue 27's restructure; package_digests.py says when to record again)."""

from __future__ import annotations

import json

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
