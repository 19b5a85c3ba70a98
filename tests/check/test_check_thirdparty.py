"""gen-robot check with its consumers on real third-party robots installed from PyPI (example-robot-data, which the
test extra installs). Every finding of our rules on these files and more is judged in test_check_realworld.py."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from xacrokit.check import check


def _robots_folder() -> Path | None:
    for entry in sys.path:
        folder = Path(entry, "cmeel.prefix", "share", "example-robot-data", "robots")
        if folder.is_dir():
            return folder
    return None


ROBOTS = _robots_folder()
pytestmark = pytest.mark.skipif(ROBOTS is None, reason="example-robot-data is not installed")
URDFS = sorted(ROBOTS.rglob("*.urdf")) if ROBOTS else []


@pytest.mark.parametrize("name", ["panda.urdf", "ur5_robot.urdf", "solo12.urdf"])
def test_consumers_give_verdicts_on_real_robots(name):
    (path,) = [p for p in URDFS if p.name == name]
    report = check(path)
    assert [(c.name, c.status) for c in report.consumers] == [
        ("check_urdf", "accepted"),
        ("pinocchio", "accepted"),
        ("yourdfpy", "accepted"),
        ("mujoco", "accepted"),
    ], report.consumers
    # MuJoCo cannot read .dae: it judged the robot without the .dae meshes, which these files use, and says so
    (mujoco,) = [c for c in report.consumers if c.name == "mujoco"]
    dae = path.read_text(encoding="utf-8").count('.dae"')
    assert (f"{dae} .dae meshes left out" in mujoco.message) == (dae > 0), (dae, mujoco.message)


def test_known_verdicts():
    """Findings read off the files by hand: the Panda is clean (its zero inertials are bare frames); the UR5's
    ee_link has collision geometry and mass 0, but it is fixed to wrist_3_link (0.1879 kg): as consumers fuse them, the
    body has mass, so no error (it was one, the commonest false error on real robots)."""
    (panda,) = [p for p in URDFS if p.name == "panda.urdf"]
    assert check(panda, consumers=[]).errors == []
    (ur5,) = [p for p in URDFS if p.name == "ur5_robot.urdf"]
    text = ur5.read_text(encoding="utf-8")
    assert '<joint name="ee_fixed_joint" type="fixed">' in text and '<link name="ee_link">' in text
    assert [f for f in check(ur5, consumers=[]).errors if f.element == "ee_link"] == []
