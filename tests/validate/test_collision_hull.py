"""`collision: hull` (issue 30, item 3): a link collides with its mesh's convex hull, made into the package; the
full-detail mesh it replaces would be G005. The hull is checked with trimesh (an independent reading of the written
file): convex, closed, holding every vertex of the mesh, fewer triangles."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
import yaml

from xacrokit import generate
from xacrokit.check import check
from xacrokit.errors import SpecErrors
from xacrokit.load import load_file
from xacrokit.validate import validate


def _spec(tmp_path, collision, shape=None):
    ball = trimesh.creation.icosphere(subdivisions=4, radius=50.0)  # (5,120 triangles, in mm)
    ball.vertices += np.random.default_rng(3).normal(0, 0.5, ball.vertices.shape)  # (not a perfect sphere)
    ball.export(tmp_path / "ball.stl")
    spec = {
        "robot": "hullbot",
        "links": {
            "base_link": {"shape": {"box": {"size": [0.2, 0.2, 0.05]}}, "mass": 1.0},
            "head": {
                "shape": shape or {"mesh": {"filename": "ball.stl", "scale": [0.001, 0.001, 0.001]}},
                "mass": 0.4,
                "collision": collision,
            },
        },
        "joints": {
            "neck": {
                "type": "revolute",
                "parent": "base_link",
                "child": "head",
                "origin": {"xyz": [0, 0, 0.1]},
                "axis": [0, 0, 1],
                "limit": {"lower": -1, "upper": 1, "effort": 1, "velocity": 1},
            },
        },
        "gazebo": {"links": {"base_link": {"mu1": 1.0, "mu2": 1.0}}},
    }
    (tmp_path / "hull.yaml").write_text(yaml.safe_dump(spec), encoding="utf-8")
    return tmp_path / "hull.yaml", ball


def test_collision_hull_writes_the_meshs_convex_hull_and_clears_g005(tmp_path):
    spec, ball = _spec(tmp_path, "same")
    assert "G005" in {f.rule for f in check(spec, consumers=[]).findings}  # (the 5,120-triangle mesh collides)
    spec, ball = _spec(tmp_path, "hull")
    result = generate(spec, tmp_path / "pkg")
    (head,) = [link for link in result.model.links if link.name == "head"]
    (collision,) = head.collisions
    assert collision.shape.scale == (0.001, 0.001, 0.001)
    relative = collision.shape.filename.removeprefix("package://hullbot_description/")
    hull = trimesh.load(tmp_path / "pkg" / relative)
    assert hull.is_watertight and hull.is_convex and len(hull.faces) < len(ball.faces)
    assert np.allclose(hull.volume, ball.convex_hull.volume, rtol=1e-6)  # (STL stores float32: 7 digits)
    inside = hull.contains(ball.vertices * 0.999)  # (every vertex, pulled in a hair: on or inside the hull)
    assert inside.all()
    report = check(spec, consumers=[])
    assert not {"G005", "I008"} & {f.rule for f in report.findings}, [str(f) for f in report.findings]


def test_collision_hull_needs_a_mesh(tmp_path):
    spec, _ = _spec(tmp_path, "hull", shape={"box": {"size": [0.1, 0.1, 0.1]}})
    with pytest.raises(SpecErrors) as raised:
        validate(load_file(spec))
    (error,) = raised.value.errors
    assert error.path == "$.links.head.collision" and "its shape is box" in error.message and error.line is not None
