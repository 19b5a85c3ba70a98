"""``gen-robot view``: one self-contained HTML page that shows a robot (URDF, xacro document, spec or scene) and moves
its joints, offline from ``file://``: no request of any kind leaves the page.

three.js ships inside the package (``xacrokit/view/three/``: the pinned release's module build, OrbitControls and
licence, unchanged from the npm registry's tarball, each checked against its recorded sha512), so that a page is
made without network; its module build and OrbitControls are inlined into the page through an import map of data:
URLs. The robot is embedded as JSON (every ``<`` escaped, so that no name can close the script element); meshes are
read with trimesh (STL, OBJ, PLY, and COLLADA through pycollada) and embedded once per file, in a table the visuals
refer to (:mod:`xacrokit.view.page_meshes`: deflated float32 positions and uint16 or uint32 indices). The page's
forward kinematics are the URDF's, in double precision (fixed-axis rpy, revolute, continuous, prismatic, mimic; a
floating joint takes [x, y, z, roll, pitch, yaw], a planar one [x, y, theta] in the plane normal to its axis), and
``window.xacrokit`` exposes ``setJoints({name: value})``, ``linkPose(name)`` (the 4x4 world transform, row-major),
``joints()`` and ``multiJoints()`` for tests. With a sizing file (:mod:`xacrokit.view.page_motion`) the page plays
its motion with the torque plot beside it (``playAt(t)``)."""

from __future__ import annotations

import base64
import hashlib
import json
import os
import urllib.parse
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import XacrokitError
from ..model import HOME_POSE
from ..reader.mesh_copies import mesh_reader
from ..reader.named_poses import named_poses, spec_poses
from ..reader.read_robot import ReadRobot, read_robot
from ..shared.joint_types import rest_position
from ..shared.transforms import rpy_matrix
from ..shared.urdf_view import Geometry, Inertial, Joint, Link, Origin, Shape, UrdfView, number, numbers
from .page_meshes import PageMeshes
from .page_motion import motion_json

if TYPE_CHECKING:
    from ..reader.robot_input import RobotInput

THREE_VERSION = "0.170.0"
THREE_TARBALL = f"https://registry.npmjs.org/three/-/three-{THREE_VERSION}.tgz"  # (where the shipped files come from)
THREE_INTEGRITY = "sha512-FQK+LEpYc0fBD+J8g6oSEyyNzjp+Q7Ks1C568WWaoMRLW+TkNNWmenWeGgJjV105Gd+p/2ql1ZcjYvNiPZBhuQ=="
# The files shipped in xacrokit/view/three/, unchanged from that tarball (its member, their sha512 in base64):
# tests/view/test_three_shipped.py compares them with the tarball the registry serves.
THREE_FILES = {
    "three": (
        "three.module.min.js",
        "package/build/three.module.min.js",
        "zTnt1Hf43YVf2to5DC6GE6cPRSC/xgPJDf3PLQussTsaDak1uHdbnWtIYnOQiL40AIa2OZfFkayQXVdzL1/DqA==",
    ),
    "orbit": (
        "OrbitControls.js",
        "package/examples/jsm/controls/OrbitControls.js",
        "C/00cg5kyUalxGAr1OS+9XwRpXSAMwZVY5hqDycouZs0+syRRmXeThBqbPPvcEwDlZMaWX9X08wbRFDwI1Izdg==",
    ),
    "license": (
        "LICENSE",
        "package/LICENSE",
        "NIIxW6k/aIPXYJ49SoMB/LXLu2MnsO0sU84p3CMdbj9UqhK2rLx9vMQT8fZJ98bnLUZ/jr8DSKhBTQKr6SFIPQ==",
    ),
}


def three_folder() -> Path:
    """Where the package keeps three.js (installed with it: the page needs no network, ever)."""
    return Path(__file__).resolve().parent / "three"


def three_sources() -> dict[str, str]:
    """three.js's module build and OrbitControls, as shipped (each file checked against its recorded sha512: a file
    changed after installation is refused, not inlined into a page)."""
    found = {}
    for key, (name, _, digest) in THREE_FILES.items():
        data = (three_folder() / name).read_bytes()
        if base64.b64encode(hashlib.sha512(data).digest()).decode("ascii") != digest:
            raise XacrokitError(f"{three_folder() / name} is not three.js {THREE_VERSION}'s file: reinstall xacrokit")
        found[key] = data.decode("utf-8")
    return found


def robot_json(view: UrdfView, read: Any, poses: Mapping[str, Mapping[str, float]] | None = None) -> dict[str, Any]:
    """The robot as the page reads it: links with their visuals, joints with their origin, axis, limits, mimic,
    ``home``: where each moving joint starts (:func:`~xacrokit.reader.named_poses.named_poses` of a spec's
    ``poses``; a joint it leaves out at 0, or its limit nearest 0), ``meshes``: each mesh file once
    (:class:`~xacrokit.view.page_meshes.PageMeshes`; a visual names its entry) and ``missing``: a line for each mesh
    that cannot be found or read (``read``, a :func:`~xacrokit.reader.mesh_copies.mesh_reader`, raising
    XacrokitError for it), whose visual the page goes without and lists."""

    missing: list[str] = []  # (a mesh the page cannot show: said in the page and by the command)
    colours = view.colours()
    meshes = PageMeshes(read)
    links = [
        {
            "name": link.name,
            "visuals": [v for v in (_visual(g, colours, meshes, missing, link.name) for g in link.visuals) if v],
            "collisions": _collisions(link),
            "inertia": _inertia_box(link.inertial),
        }
        for link in view.links
    ]
    joints = [_joint(joint) for joint in view.joints if joint.parent is not None and joint.child is not None]
    given = named_poses(poses or {}, view)[HOME_POSE]
    moving = [j for j in joints if j["type"] in ("revolute", "continuous", "prismatic") and "mimic" not in j]
    home = {j["name"]: _start(j, given) for j in moving}
    return {
        "name": view.name or "robot",
        "links": links,
        "joints": joints,
        "home": home,
        "meshes": meshes.table,
        "missing": missing,
    }


def _start(joint: dict[str, Any], given: Mapping[str, float]) -> float:
    """A joint's home position: given, else 0 moved into its limits."""
    if joint["name"] in given:
        return float(given[joint["name"]])
    return rest_position(joint.get("lower"), joint.get("upper"))  # (none for continuous, or no limits given)


def _visual(
    visual: Geometry, colours: dict[str, str], meshes: PageMeshes, missing: list[str], link: str
) -> dict[str, Any] | None:
    """A visual as the page draws it, None for one it cannot (a mesh that is missing is added to ``missing``); a mesh
    by its entry in ``meshes``."""
    shape = visual.shape
    if shape is None or shape.kind not in ("box", "cylinder", "sphere", "mesh"):
        return None
    entry: dict[str, Any] = {"origin": _origin(visual.origin), "kind": shape.kind}
    material = visual.material
    rgba = None
    if material is not None:
        rgba = material.rgba if material.rgba is not None else colours.get(material.name or "")
    entry["rgba"] = numbers(rgba, [0.62, 0.64, 0.68, 1.0])
    if shape.kind != "mesh":
        entry.update(_primitive(shape))
        return entry
    try:
        entry["mesh"] = meshes.index(shape.get("filename") or "")
    except XacrokitError as exc:
        missing.append(f"link {link}: {exc}")
        return None
    entry["scale"] = numbers(shape.get("scale"), [1.0, 1.0, 1.0])
    return entry


def _joint(joint: Joint) -> dict[str, Any]:
    entry: dict[str, Any] = {
        "name": joint.name,
        "type": joint.type,
        "parent": joint.parent,
        "child": joint.child,
        "origin": _origin(joint.origin),
        "axis": numbers(joint.axis, [1.0, 0.0, 0.0]),
    }
    if joint.limit is not None and joint.type in ("revolute", "prismatic"):
        entry["lower"], entry["upper"] = number(joint.limit.get("lower"), 0.0), number(joint.limit.get("upper"), 0.0)
    if joint.mimic is not None:
        entry["mimic"] = {
            "joint": joint.mimic.joint,
            "multiplier": number(joint.mimic.multiplier, 1.0),
            "offset": number(joint.mimic.offset, 0.0),
        }
    return entry


def _collisions(link: Link) -> list[dict[str, Any]]:
    """A link's collision primitives (meshes are drawn as their visuals: the toggle shows the primitives)."""
    found = []
    for collision in link.collisions:
        shape = collision.shape
        if shape is None or shape.kind not in ("box", "cylinder", "sphere"):
            continue
        entry: dict[str, Any] = {"origin": _origin(collision.origin), "kind": shape.kind}
        entry.update(rgba=[1.0, 0.4, 0.0, 0.5], **_primitive(shape))
        found.append(entry)
    return found


def _primitive(shape: Shape) -> dict[str, Any]:
    """A box's, cylinder's or sphere's sizes as the page reads them (a size that is not a number: a small default,
    so that the page still draws the rest; check says what is wrong)."""
    if shape.kind == "box":
        return {"size": numbers(shape.get("size"), [0.1, 0.1, 0.1])}
    if shape.kind == "cylinder":
        return {"radius": number(shape.get("radius"), 0.05), "length": number(shape.get("length"), 0.1)}
    return {"radius": number(shape.get("radius"), 0.05)}


def _inertia_box(inertial: Inertial | None) -> dict[str, Any] | None:
    """The box of uniform density with the link's mass and principal moments (sides sqrt(6 (I_j + I_k - I_i) / m)),
    at the centre of mass, along the principal axes: what the inertia toggle draws. None without a mass."""

    if inertial is None or inertial.mass is None or inertial.inertia is None:
        return None
    try:
        mass = float(inertial.mass)
        i = {k: float(inertial.inertia.get(k, 0.0)) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
    except ValueError:
        return None
    tensor = np.array([[i["ixx"], i["ixy"], i["ixz"]], [i["ixy"], i["iyy"], i["iyz"]], [i["ixz"], i["iyz"], i["izz"]]])
    if not mass > 0 or not np.all(np.isfinite(tensor)):
        return None
    moments, axes = np.linalg.eigh(tensor)
    total = moments.sum()
    sides = [float(np.sqrt(max(6.0 * (total - 2.0 * m) / mass, 0.0))) for m in moments]
    origin = _origin(inertial.origin)
    rotation = rpy_matrix(*origin["rpy"]) @ axes
    return {"xyz": origin["xyz"], "rotation": rotation.reshape(-1).tolist(), "size": sides}


def _origin(origin: Origin | None) -> dict[str, list[float]]:
    if origin is None:
        return {"xyz": [0.0, 0.0, 0.0], "rpy": [0.0, 0.0, 0.0]}
    return {"xyz": numbers(origin.xyz, [0.0, 0.0, 0.0]), "rpy": numbers(origin.rpy, [0.0, 0.0, 0.0])}


def page(
    robot: ReadRobot | RobotInput | str | os.PathLike[str],
    *,
    poller: str = "",
    sizing: str | os.PathLike[str] | None = None,
    missing: list[str] | None = None,
) -> str:
    """The HTML page of a read robot (or what to read; see the module's notes); ``poller``: the script ``--watch``
    adds (it may then ask its own origin, and only that); ``sizing``: a sizing file whose motion the page plays;
    ``missing``: a list the meshes the page goes without are added to (the page lists them too).

    Raises:
        XacrokitError: unreadable input, a sizing file without a motion, or three.js unavailable.
        SpecErrors: an invalid sizing file (located).
    """
    from ..render import environment  # (heavy: jinja2)

    read_in = read_robot(robot)
    with read_in.mesh_packages() as packages:
        read = mesh_reader(read_in.path, packages, process=False)  # (page_meshes merges by position alone)
        shown = robot_json(read_in.view, read, spec_poses(read_in.spec))
    if missing is not None:
        missing.extend(shown["missing"])
    if sizing is not None:
        shown["motion"] = motion_json(read_in, sizing)
    sources = three_sources()
    imports = {
        "three": _script_url(sources["three"]),
        "three/addons/controls/OrbitControls.js": _script_url(sources["orbit"]),
    }
    return (
        environment()
        .get_template("viewer/view.html.j2")
        .render(
            title=shown["name"],
            robot_json=_script_json(shown),
            import_map=_script_json({"imports": imports}),
            three_version=THREE_VERSION,
            poller=poller,
        )
    )


# What a script's data: URL keeps as it is: printable ASCII but '%' (the escape), '#' (a fragment would end the URL),
# '"' and '\\' (escaped again in JSON), '<', '>' and '&' (escaped again in the page). About 1.06 times the script's
# size, where base64 takes 1.33.
URL_PLAIN = "".join(chr(c) for c in range(0x20, 0x7F) if chr(c) not in '%#"\\<>&')


def _script_url(source: str) -> str:
    """A script as a data: URL, percent-encoded (:data:`URL_PLAIN`)."""
    return "data:text/javascript," + urllib.parse.quote(source, safe=URL_PLAIN)


def _script_json(value: Any) -> str:
    """JSON to put inside a <script> element: '<', '>' and '&' as \\u escapes (no name can end the element)."""
    return json.dumps(value).replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")
