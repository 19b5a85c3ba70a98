"""gen-robot check on real robots nobody here wrote (tests/realworld.py: pinned registry packages), against
verdicts given by reading the files (realworld_verdicts.yaml): the rules find exactly what was judged, no error is
false, at least 90% of warnings are true, and every file a consumer rejects gets an error from our rules alone."""

from __future__ import annotations

import collections
import os

import pytest
import yaml

from realworld import VERDICTS, findings_of, rejected_by, robots

DATA = yaml.safe_load(VERDICTS.read_text(encoding="utf-8"))
VERDICT_IDS = DATA["verdicts"]
FILES = DATA["files"]


def judged(key: str) -> list[tuple[str, str]]:
    """(finding line, verdict id) of a file, as recorded."""
    return [tuple(line.rsplit(": ", 1)) for line in FILES[key].get("findings", [])]  # type: ignore[misc]


def test_the_corpus_is_the_recorded_one():
    assert sorted(robots()) == sorted(FILES), "re-record: python tests/realworld.py --record --consumers"
    assert len(FILES) >= 120


@pytest.mark.parametrize("key", sorted(FILES))
def test_the_rules_find_what_was_judged(key):
    """A finding nobody judged, or a judged one that is gone, fails: judge it by reading the file (or record why the
    rule changed) in realworld_verdicts.yaml."""
    robot = robots()[key]
    assert findings_of(robot) == [line for line, _ in judged(key)]


def test_every_verdict_is_given_and_explained():
    for key in FILES:
        for line, verdict in judged(key):
            assert verdict in VERDICT_IDS, f"{key}: {line}: {verdict!r} is not one of the verdicts"
    for name, verdict in VERDICT_IDS.items():
        assert isinstance(verdict["true"], bool) and len(verdict["why"]) > 40, name


def tally() -> dict[tuple[str, str], collections.Counter[bool]]:
    counts: dict[tuple[str, str], collections.Counter[bool]] = collections.defaultdict(collections.Counter)
    for key in FILES:
        for line, verdict in judged(key):
            rule, severity = line.split()[:2]
            counts[(rule, severity)][VERDICT_IDS[verdict]["true"]] += 1
    return counts


def test_no_error_is_false_and_nine_warnings_in_ten_are_true():
    counts = tally()
    false_errors = {rule: c[False] for (rule, severity), c in counts.items() if severity == "error" and c[False]}
    assert not false_errors
    warnings = collections.Counter[bool]()
    for (_, severity), c in counts.items():
        if severity == "warning":
            warnings.update(c)
    assert warnings[True] >= 0.9 * (warnings[True] + warnings[False]), warnings


def test_every_file_a_consumer_rejects_gets_an_error_from_our_rules():
    """Our rules alone (--consumers none) fail every file a consumer rejects, but for what they do not read: the
    contents of mesh files (each such file says which consumer limit it meets, and why)."""
    limits = []
    for key, entry in FILES.items():
        errors = [line for line, _ in judged(key) if line.split()[1] == "error"]
        if entry.get("rejected_by") and not errors:
            assert "mesh" in entry.get("consumer_limit", ""), f"{key}: rejected by {entry['rejected_by']}, no error"
            limits.append(key)
        elif "consumer_limit" in entry:
            raise AssertionError(f"{key}: a consumer limit is recorded, but the file gets an error anyway")
    assert len(limits) <= 2, limits


# the consumers take about two seconds a file: the verdicts recorded for the files they reject, and for every fifth
# file they accept, are checked again here (all of them with XACROKIT_CORPUS_CONSUMERS=all)
SAMPLE = [
    key
    for index, key in enumerate(sorted(FILES))
    if FILES[key].get("rejected_by") or index % 5 == 0 or os.environ.get("XACROKIT_CORPUS_CONSUMERS") == "all"
]


@pytest.mark.parametrize("key", SAMPLE)
def test_the_consumers_verdicts_are_the_recorded_ones(key):
    assert rejected_by(robots()[key]) == FILES[key].get("rejected_by", [])


def test_the_corpus_in_one_call_gives_each_file_its_judged_findings():
    """gen-robot check on the corpus' folders in one call (worker processes, the files found by the folder search):
    the same files, and each report has exactly the findings judged for its file alone."""
    import json
    import subprocess
    import sys

    from realworld import SOURCES, unpacked

    by_path = {str(robot.path): key for key, robot in robots().items()}
    folders = [str(unpacked(source) / source.urdfs) for source in SOURCES]
    packages = [f"--package={name}={unpacked(s) / folder}" for s in SOURCES for name, folder in s.packages]
    command = [sys.executable, "-m", "xacrokit.cli", "check", *folders, *packages, "--exclude", "*.xacro"]
    done = subprocess.run([*command, "--consumers", "none", "--json", "-j", "2"], capture_output=True, text=True)
    reports = json.loads(done.stdout)["reports"]
    assert sorted(r["source"] for r in reports) == sorted(by_path)
    for report in reports:
        said = sorted(
            f"{f['rule']} {f['severity']} {f['element']['kind']} {f['element']['name']}"
            for f in report["findings"]
            if f["severity"] != "info"
        )
        assert said == [line for line, _ in judged(by_path[report["source"]])], report["source"]
    assert done.returncode == 1
