"""G007's pairs in collision at home, kept in the user's cache folder (issue 45, item 2): a second check of the same
robot takes them from there without importing pinocchio and says the same; a mesh whose bytes changed, a changed
home, a damaged kept file or the cache turned off pose the robot again with pinocchio and coal."""

from __future__ import annotations

import json
import os
import subprocess
import sys

from check_helpers import CORPUS

from conftest import tetrahedron_stl

# the check run in a process of its own, which says its findings and whether it imported pinocchio
SCRIPT = """
import json, sys
from xacrokit.check import check
report = check(sys.argv[1], consumers=[])
rules = sorted(f.rule for f in report.findings if f.rule in ("G007", "G008"))  # (the rules of self-collision)
print(json.dumps({"rules": rules, "pinocchio": "pinocchio" in sys.modules}))
"""
EMPTY_SRDF = '<?xml version="1.0"?>\n<robot name="corpus"/>\n'  # (an SRDF beside the URDF: G007 poses meshes)


def planted(tmp_path, lift: float = 0.0):
    """G007's planted overlap (the hand inside the base at home) with the hand's collision a mesh beside the URDF."""
    text = (CORPUS / "G007_fail.urdf").read_text(encoding="utf-8")
    hand = text.index('<link name="hand">')
    cylinder = '<collision><origin xyz="0 0 0.15"/><geometry><cylinder radius="0.02" length="0.3"/></geometry>'
    at = text.index(cylinder, hand)
    text = text[:at] + '<collision><geometry><mesh filename="hand.stl"/></geometry>' + text[at + len(cylinder) :]
    path = tmp_path / "planted.urdf"
    path.write_text(text, encoding="utf-8")
    (tmp_path / "planted.srdf").write_text(EMPTY_SRDF, encoding="utf-8")
    (tmp_path / "hand.stl").write_bytes(tetrahedron_stl(lift))
    return path


def checked(path, cache) -> dict:
    env = {**os.environ, "XACROKIT_CACHE": str(cache)}
    command = [sys.executable, "-c", SCRIPT, str(path)]
    done = subprocess.run(command, capture_output=True, text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.splitlines()[-1])


def test_a_second_check_takes_the_pairs_kept_and_a_changed_mesh_is_posed_again(tmp_path):
    path, cache = planted(tmp_path), tmp_path / "cache"
    first = checked(path, cache)
    assert first == {"rules": ["G007", "G008"], "pinocchio": True}  # (the hand's mesh inside the base, posed)
    assert checked(path, cache) == {"rules": ["G007", "G008"], "pinocchio": False}  # (kept: pinocchio not imported)
    (tmp_path / "hand.stl").write_bytes(tetrahedron_stl(1.0))  # (the same file name, the mesh a metre up: no overlap)
    assert checked(path, cache) == {"rules": ["G008"], "pinocchio": True}
    assert checked(path, cache) == {"rules": ["G008"], "pinocchio": False}
    kept = sorted(cache.rglob("home-*.json"))
    assert len(kept) == 2  # (one per mesh content)
    for file in kept:
        file.write_text("{not json", encoding="utf-8")  # (damaged: posed again, and kept anew)
    assert checked(path, cache) == {"rules": ["G008"], "pinocchio": True}
    assert checked(path, tmp_path / "elsewhere") == {"rules": ["G008"], "pinocchio": True}
    assert checked(path, "off") == {"rules": ["G008"], "pinocchio": True}


def test_a_changed_home_is_posed_again(tmp_path):
    """The SRDF's home pose is part of what is kept: turning the shoulder at home lifts the hand out of the base."""
    path, cache = planted(tmp_path), tmp_path / "cache"
    assert checked(path, cache)["rules"] == ["G007", "G008"]
    turned = EMPTY_SRDF.replace(
        "/>\n",
        '>\n  <group name="arm"><joint name="shoulder"/></group>\n'
        '  <group_state name="home" group="arm"><joint name="shoulder" value="1.0"/></group_state>\n</robot>\n',
    )
    (tmp_path / "planted.srdf").write_text(turned, encoding="utf-8")
    again = checked(path, cache)
    assert again["pinocchio"] is True  # (a home of its own: not the kept pairs of the zero pose)
