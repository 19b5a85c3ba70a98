"""A scene has at most as many instances as a fleet has robots (scene.schema.json, scene/fleet.MAX_FLEET): the limit
is said, with its reason, as a located error; a scene at the limit is accepted."""

from __future__ import annotations

import pytest

import xacrokit
from xacrokit.scene.fleet import MAX_FLEET


def big_scene(folder, count):
    """A scene of ``count`` instances of a robot of one bare link. The limit is on the instances; what an instance of
    a robot with joints and geometry adds is its files (1,000 two-DOF arms took 14 s: their controllers' file read
    again for each, an SRDF of half a million Adjacent pairs), which tests/scene/test_fleets.py proves on fleets and
    benchmarks/bench.py times for 1,000 links."""
    (folder / "r.yaml").write_text("robot: dot\nlinks:\n  base_link: {}\n", encoding="utf-8")
    rows = [f"  a{i}: {{spec: r.yaml, prefix: a{i}_, parent: world}}" for i in range(count)]
    path = folder / "big.yaml"
    path.write_text("scene: big\ninstances:\n" + "\n".join(rows) + "\n", encoding="utf-8")
    return path


def test_a_scene_beyond_the_limit_is_a_located_error(tmp_path):
    with pytest.raises(xacrokit.SpecErrors) as caught:
        xacrokit.generate(big_scene(tmp_path, MAX_FLEET + 1), tmp_path / "pkg", dry_run=True)
    (error,) = caught.value.errors
    assert (error.path, error.line, error.column) == ("$.instances", 3, 3)
    assert f"a scene has at most {MAX_FLEET:,} instances, got {MAX_FLEET + 1:,} (as for fleets" in error.message


def test_a_scene_at_the_limit_is_accepted(tmp_path):
    result = xacrokit.generate(big_scene(tmp_path, MAX_FLEET), tmp_path / "pkg", dry_run=True)
    assert len(result.model.instances) == MAX_FLEET
