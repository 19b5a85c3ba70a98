"""The page's meshes (issue 33, item 5): each mesh file once per page, whatever the number of visuals and the URIs
that name it, with scale and colour kept per visual; the arrays decode to the mesh's own triangles (float32
positions, uint16 indices while they fit below WebGL 2's restart index, else uint32); in headless Chromium the
visuals of one file share one geometry, each at its own scale."""

from __future__ import annotations

import base64
import json
import zlib

import lxml.html
import numpy as np
import pytest
import trimesh

from browser import open_page
from xacrokit.reader.robot_input import RobotInput
from xacrokit.view.page import page
from xacrokit.view.page_meshes import drawn, mesh_arrays

SHARED = """<robot name="shared">
  <link name="a"><visual><geometry><mesh filename="meshes/part.stl"/></geometry></visual></link>
  <link name="b"><visual><origin xyz="0 0.5 0"/><geometry><mesh filename="package://kit/meshes/part.stl"
    scale="2 1 1"/></geometry><material name="red"><color rgba="1 0 0 1"/></material></visual></link>
  <link name="c"><visual><origin xyz="0 1 0"/><geometry><mesh filename="./meshes/../meshes/part.stl"/></geometry>
    </visual></link>
  <link name="d"><visual><origin xyz="0 1.5 0"/><geometry><mesh filename="meshes/other.stl"/></geometry></visual>
  </link>
  <joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="ac" type="fixed"><parent link="a"/><child link="c"/></joint>
  <joint name="ad" type="fixed"><parent link="a"/><child link="d"/></joint>
</robot>"""

PART = (0.1, 0.2, 0.3)  # the box part.stl holds: its extents in m


def shared_robot(folder):
    """SHARED in ``folder``: part.stl named three ways by three links (one of them scaled), other.stl by a fourth."""
    (folder / "meshes").mkdir()
    trimesh.creation.box(extents=PART).export(folder / "meshes" / "part.stl")
    trimesh.creation.icosphere(subdivisions=1, radius=0.1).export(folder / "meshes" / "other.stl")
    urdf = folder / "shared.urdf"
    urdf.write_text(SHARED, encoding="utf-8")
    return urdf


def embedded_robot(html: str) -> dict:
    return json.loads(lxml.html.fromstring(html).get_element_by_id("robot").text)


def unpacked(text: str, dtype: str) -> np.ndarray:
    return np.frombuffer(zlib.decompress(base64.b64decode(text)), dtype=dtype)


def triangles(vertices: np.ndarray, faces: np.ndarray) -> list[tuple]:
    """Each triangle as its three corners (sorted), the list sorted: the same surface whatever the vertex order."""
    corners = np.asarray(vertices, dtype=np.float32)[faces]
    return sorted(tuple(sorted(map(tuple, corner.tolist()))) for corner in corners)


def test_a_mesh_named_by_several_links_is_in_the_page_once(tmp_path):
    urdf = shared_robot(tmp_path)
    robot = embedded_robot(page(RobotInput(urdf, packages={"kit": str(tmp_path)})))
    assert [mesh["uri"] for mesh in robot["meshes"]] == ["meshes/part.stl", "meshes/other.stl"]
    visuals = {link["name"]: link["visuals"] for link in robot["links"]}
    assert {name: [v["mesh"] for v in found] for name, found in visuals.items()} == {
        "a": [0],
        "b": [0],
        "c": [0],
        "d": [1],
    }
    assert [visuals[name][0]["scale"] for name in "abc"] == [[1.0, 1.0, 1.0], [2.0, 1.0, 1.0], [1.0, 1.0, 1.0]]
    assert visuals["b"][0]["rgba"] == [1.0, 0.0, 0.0, 1.0] and visuals["a"][0]["rgba"] != visuals["b"][0]["rgba"]
    part = robot["meshes"][0]
    assert part["indexType"] == "uint16"
    positions = unpacked(part["positions"], "<f4").reshape(-1, 3)
    faces = unpacked(part["indices"], "<u2").reshape(-1, 3)
    box = trimesh.creation.box(extents=PART)
    assert triangles(positions, faces) == triangles(box.vertices, box.faces)  # (every triangle, nothing else)


def test_vertices_are_shared_across_smooth_surfaces_and_split_at_creases():
    """A sphere as an STL file holds it (a vertex per triangle corner) is drawn with one vertex per point of it; a
    box with four per side (the sides meet at 90 degrees), so that three.js's normals keep its edges sharp."""
    sphere = trimesh.creation.icosphere(subdivisions=3)
    corners = trimesh.Trimesh(
        sphere.triangles.reshape(-1, 3), np.arange(3 * len(sphere.faces)).reshape(-1, 3), process=False
    )
    vertices, faces = drawn(corners)
    assert len(vertices) == len(sphere.vertices) and triangles(vertices, faces) == triangles(
        sphere.vertices, sphere.faces
    )
    box = trimesh.creation.box(extents=PART)
    vertices, faces = drawn(box)
    assert len(vertices) == 24 and triangles(vertices, faces) == triangles(box.vertices, box.faces)


@pytest.mark.parametrize(("largest", "kind"), [(0xFFFE, "uint16"), (0xFFFF, "uint32"), (70_000, "uint32")])
def test_indices_are_uint16_while_they_stay_below_webgl_restart_index(largest, kind):
    """0xFFFF restarts a primitive in WebGL 2 (always on there), so a uint16 index stops at 0xFFFE."""
    vertices = np.random.default_rng(1).normal(size=(largest + 1, 3))
    faces = np.array([[0, 1, largest], [largest, 2, 1]])
    found = mesh_arrays(vertices, faces)
    assert found["indexType"] == kind
    assert np.array_equal(unpacked(found["indices"], "<u2" if kind == "uint16" else "<u4").reshape(-1, 3), faces)
    assert np.array_equal(unpacked(found["positions"], "<f4").reshape(-1, 3), vertices.astype(np.float32))


def test_a_mesh_that_cannot_be_read_is_said_for_every_visual_that_names_it(tmp_path):
    urdf = shared_robot(tmp_path)
    (tmp_path / "meshes" / "part.stl").write_bytes(b"not a mesh")
    robot = embedded_robot(page(RobotInput(urdf, packages={"kit": str(tmp_path)})))
    assert [line.split(":")[0] for line in robot["missing"]] == ["link a", "link b", "link c"]
    assert [mesh["uri"] for mesh in robot["meshes"]] == ["meshes/other.stl"]
    assert [v["mesh"] for link in robot["links"] for v in link["visuals"]] == [0]


def test_visuals_of_one_file_share_one_geometry_each_at_its_scale(browser, tmp_path):
    urdf = shared_robot(tmp_path)
    html = tmp_path / "shared.html"
    html.write_text(page(RobotInput(urdf, packages={"kit": str(tmp_path)})), encoding="utf-8")
    open_page(browser, html)
    assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []
    drawn = {link: browser.execute_script("return window.xacrokit.visuals(arguments[0])", link) for link in "abcd"}
    assert len({drawn[link][0]["geometry"] for link in "abc"}) == 1
    assert drawn["d"][0]["geometry"] != drawn["a"][0]["geometry"]
    sizes = {link: np.subtract(drawn[link][0]["box"][3:], drawn[link][0]["box"][:3]) for link in "abc"}
    assert np.allclose(sizes["a"], PART, atol=1e-6) and np.allclose(sizes["c"], PART, atol=1e-6)
    assert np.allclose(sizes["b"], [2 * PART[0], PART[1], PART[2]], atol=1e-6)
    centre = np.add(drawn["b"][0]["box"][3:], drawn["b"][0]["box"][:3]) / 2
    assert np.allclose(centre, [0.0, 0.5, 0.0], atol=1e-6)  # (its origin, then its scale)
