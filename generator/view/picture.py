"""``gen-robot render``: a picture of a robot (URDF, xacro document, spec or scene) without OpenGL: yourdfpy places
every visual at the joint values asked for (its forward kinematics, primitives made meshes by trimesh), and
matplotlib's Agg backend draws the triangles, shaded by a fixed light, from a fixed view. The same input gives the
same PNG bytes (no version metadata), for docs, reports and CI artefacts.

A mesh file that cannot be found or read is an error that names it (never a picture with a hole in it).
"""

from __future__ import annotations

import copy
import io
import os
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import XacrokitError
from ..reader.mesh_copies import mesh_root, require_mesh_file
from ..shared.ros_packages import mesh_file

if TYPE_CHECKING:
    from ..reader.read_robot import ReadRobot
    from ..reader.robot_input import RobotInput
    from ..shared.urdf_view import UrdfView

LIGHT = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
VIEW = (22.0, -55.0)  # elevation and azimuth, degrees: the robot's front-left from above (x forward, z up)
GREY = (0.62, 0.64, 0.68)


def render(
    robot: ReadRobot | RobotInput | str | os.PathLike[str],
    *,
    joints: Mapping[str, float] | None = None,
    size: tuple[int, int] = (800, 600),
) -> bytes:
    """The PNG of a read robot (or what to read) at ``joints`` (name -> rad or m; the others at 0).

    Raises:
        XacrokitError: unreadable input, a mesh that cannot be found or read, or an unknown joint.
    """
    from ..reader.read_robot import read_robot  # (heavy: lxml)

    read = read_robot(robot)
    with read.mesh_packages() as packages:
        meshes = _placed_meshes(read, packages, joints or {})
    return _draw(meshes, size)


def _placed_meshes(
    robot: ReadRobot, packages: Mapping[str, str | os.PathLike[str]], joints: Mapping[str, float]
) -> list[tuple[np.ndarray, np.ndarray, tuple[float, float, float]]]:
    """(vertices, faces, colour) of every visual of the read robot, placed in the root link's frame."""
    import yourdfpy  # (heavy: yourdfpy)

    def resolve(fname: str) -> str:  # (yourdfpy passes it by this name)
        try:
            return str(mesh_file(fname, urdf.parent, packages))
        except (LookupError, ValueError) as exc:
            raise XacrokitError(f"mesh {fname!r}: {exc}") from None

    from ..reader.kinematic_model import UnknownName, require_placeable  # (heavy: lxml)

    urdf, view = robot.path, robot.view
    if len(view.links) > MAX_LINKS:
        raise XacrokitError(
            f"the robot has {len(view.links):,} links; render draws at most {MAX_LINKS:,} (yourdfpy's scene takes "
            "time that grows with the square of the links: 24 s for 5,000): gen-robot view draws any number"
        )
    try:
        require_placeable(view)  # (the same values refused in the same words as pose, size and export)
    except XacrokitError as exc:
        raise XacrokitError(f"cannot draw the robot: {exc}") from None
    for element in _mesh_names(view):  # (yourdfpy opens them itself: each checked first, as mesh_reader would)
        file = Path(resolve(element))
        if not file.is_file():
            raise XacrokitError(f"mesh {element!r} is not there ({file}); the picture would miss it")
        try:
            root = mesh_root(urdf, element, packages)
        except (LookupError, ValueError) as exc:
            raise XacrokitError(f"mesh {element!r}: {exc}") from None
        require_mesh_file(root, file, where=f"mesh {element!r}")
    try:  # (yourdfpy's own reader of the root already parsed: URDF.load would parse the text again)
        described = yourdfpy.URDF._parse_robot(xml_element=_for_yourdfpy(view.root))
        placed_robot = yourdfpy.URDF(robot=described, filename_handler=resolve, build_scene_graph=True)
    except XacrokitError:
        raise
    except Exception as exc:  # noqa: BLE001  (yourdfpy and trimesh raise what their readers raise)
        raise XacrokitError(f"cannot draw the robot: {type(exc).__name__}: {exc}") from None
    unknown = sorted(set(joints) - set(placed_robot.actuated_joint_names))
    if unknown:
        said = f"no moving joint {', '.join(map(repr, unknown))} in the robot"
        raise UnknownName(said, role="joint", name=unknown[0])
    if joints:
        placed_robot.update_cfg({name: float(value) for name, value in joints.items()})
    found = []
    placed = world_transforms(placed_robot.scene.graph)
    for name, geometry in placed_robot.scene.geometry.items():
        for node in placed_robot.scene.graph.geometry_nodes.get(name, []):
            transform = placed[node]
            vertices = np.asarray(geometry.vertices) @ transform[:3, :3].T + transform[:3, 3]
            found.append((vertices, np.asarray(geometry.faces), _colour(geometry)))
    if not found:
        raise XacrokitError("the robot has no visual geometry to draw")
    return found


MAX_LINKS = 5000  # links render draws (yourdfpy builds its scene in time that grows with their square)


def world_transforms(graph: Any) -> dict[str, np.ndarray]:
    """Every node of a trimesh scene graph placed in its base frame, composed down the tree once. (trimesh's
    ``graph.get`` multiplies each node's path with numpy's ``multi_dot``, whose ordering of the product is cubic in
    the path's length: 30 s for the 200 links of a chain, hours for 2,000.)"""
    forest = graph.transforms
    placed = {graph.base_frame: np.eye(4)}
    stack = [graph.base_frame]
    while stack:
        node = stack.pop()
        for child in forest.children.get(node, []):
            matrix = forest.edge_data.get((node, child), {}).get("matrix")
            placed[child] = placed[node] @ matrix if matrix is not None else placed[node]
            stack.append(child)
    return placed


def _for_yourdfpy(root: Any) -> Any:
    """A copy of the robot's root as yourdfpy's ``URDF.load`` makes it before reading it: comments stripped and
    namespaces cleaned (the view's own root is left as it is)."""

    from lxml import etree  # (heavy: lxml)

    element = copy.deepcopy(root)
    etree.strip_tags(element, etree.Comment)
    etree.cleanup_namespaces(element)
    return element


def _mesh_names(view: UrdfView) -> list[str]:
    """The mesh files the robot's visuals name (what yourdfpy will open: each must be there)."""
    return sorted(
        {
            visual.shape.get("filename") or ""
            for link in view.links
            for visual in link.visuals
            if visual.shape is not None and visual.shape.kind == "mesh"
        }
    )


def _colour(geometry: Any) -> tuple[float, float, float]:
    """A visual's colour (its material's rgb), grey when it has none."""
    try:
        rgba = np.asarray(geometry.visual.main_color, dtype=float) / 255.0
    except (AttributeError, ValueError):
        return GREY
    if rgba.shape != (4,) or np.allclose(rgba[:3], 102 / 255.0):  # (trimesh's default colour: none was given)
        return GREY
    return (float(rgba[0]), float(rgba[1]), float(rgba[2]))


def _draw(meshes: list[tuple[np.ndarray, np.ndarray, tuple[float, float, float]]], size: tuple[int, int]) -> bytes:
    import matplotlib  # (heavy: matplotlib)

    matplotlib.use("Agg")
    from matplotlib.figure import Figure  # (heavy: matplotlib)

    # (heavy: mpl_toolkits)
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # type: ignore[import-untyped]

    figure = Figure(figsize=(size[0] / 100, size[1] / 100), dpi=100)
    ax = figure.add_subplot(projection="3d")
    from trimesh.remesh import subdivide_to_size  # (heavy: trimesh)

    points = np.concatenate([vertices for vertices, _, _ in meshes])
    longest = float((points.max(axis=0) - points.min(axis=0)).max()) / 12  # (small faces: matplotlib sorts by face)
    triangles, colours = [], []
    for vertices, faces, colour in meshes:
        if len(faces) and longest > 0:
            vertices, faces = subdivide_to_size(vertices, faces, max_edge=longest, max_iter=8)
        corners = vertices[faces]
        normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        lengths = np.linalg.norm(normals, axis=1)
        keep = lengths > 0
        shade = 0.45 + 0.55 * np.abs(normals[keep] @ LIGHT) / lengths[keep]
        triangles.append(corners[keep])
        colours.append(np.clip(np.outer(shade, colour), 0.0, 1.0))
    everything = np.concatenate(triangles)
    shades = np.concatenate(colours)  # (edges in the faces' colour: no seams between the small faces)
    ax.add_collection3d(Poly3DCollection(everything, facecolors=shades, edgecolors=shades, linewidths=0.3))
    low, high = everything.reshape(-1, 3).min(axis=0), everything.reshape(-1, 3).max(axis=0)
    centre, half = (low + high) / 2, max(float((high - low).max()) / 2, 1e-3)
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_zlim(centre[2] - half, centre[2] + half)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(*VIEW)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.tick_params(labelsize=7)
    figure.tight_layout()
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", metadata={"Software": None})
    return buffer.getvalue()
