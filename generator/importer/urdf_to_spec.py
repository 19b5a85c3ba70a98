"""``gen-robot import``: a URDF or xacro document read back as a robot spec that generates the same robot.

What the spec says, the spec keeps, with its numbers written exactly (YAML floats are Python's shortest repr):

- each link's first visual as its ``shape`` (box, cylinder, sphere, mesh with its URI and scale, a negative factor
  mirroring it) at its ``origin``, its colour as a named ``material`` (the URDF's material name when it is an
  identifier, else ``colour_N``), its other visuals as ``visuals:``; its collisions as ``same`` (one, the first
  visual's geometry and origin), ``none``, one shape or a list of them (also on a link without a visual);
- its inertial as ``mass`` and an explicit ``inertia`` tensor with its frame, as the file says it; or as ``mass``
  alone when the tensor is the one the spec computes from the shape (a uniform solid in the shape's axes, to 1e-12);
- each joint with its type, parent, child, origin, axis, limit, dynamics, mimic, safety controller and calibration;
- wheels that are exactly what ``wheels:`` writes (:mod:`.wheel_match`);
- values no real body has under ``strict: false`` (:attr:`Imported.as_given`).

What the spec cannot say is reported at its element's line, not dropped silently (:attr:`Imported.unsupported`): a
name the spec does not take, a relative mesh that is not there, and whatever
else the spec would refuse. Attributes URDF does not define are named (:attr:`Imported.ignored`). Every element URDF
readers do not model (``<gazebo>``, ``<transmission>``, ``<ros2_control>``, others) is kept verbatim in
:attr:`Imported.extension`, which ``gen-robot import -o SPEC`` writes beside the spec as ``SPEC_extension.xacro`` and
names in the spec's ``extension``: the generated package starts its user-owned ``urdf/NAME_extension.xacro`` with them.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from typing import Any

from lxml import etree

from ..errors import SpecErrors
from ..model import Origin as SpecOrigin
from ..reader.mesh_copies import mesh_to_copy, robot_folder
from ..reader.read_robot import ReadRobot, read_robot
from ..reader.robot_input import RobotInput
from ..reader.robot_source import urdf_floats
from ..shared.input_files import CopiedFile
from ..shared.mesh_solids import MESH_SUFFIXES, is_relative
from ..shared.ros_packages import mesh_file
from ..shared.urdf_view import Inertial, Joint, Link, Material, MaterialRef, Origin, Shape, UrdfView, read_view
from .wheel_match import wheels

IDENTIFIER = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*(?:[./-][A-Za-z0-9_]+)*$")  # (a link's or joint's: the schema's urdf_name)
SPEC_ITEM = re.compile(r"^\$\.(links|joints)(?:\.([A-Za-z_][A-Za-z0-9_]*)|\['([^']*)'\])")  # (a JSON path's item)
MODELLED = ("link", "joint", "material")  # what the spec holds of a <robot>'s children
URDF_JOINT_ATTRIBUTES = {  # (urdfdom's joint parser: what it reads of each element)
    "limit": {"lower", "upper", "effort", "velocity"},
    "dynamics": {"damping", "friction"},
    "mimic": {"joint", "multiplier", "offset"},
    "safety_controller": {"soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"},
    "calibration": {"rising", "falling"},
}


@dataclass
class Imported:
    """The spec (a mapping ready for YAML), what could not be imported (one line each), and the elements kept
    for the extension file (their tags and names)."""

    spec: dict[str, Any]
    unsupported: list[str] = field(default_factory=list)
    leftovers: list[str] = field(default_factory=list)
    meshes: dict[str, CopiedFile] = field(default_factory=dict)  # a relative mesh path in the spec -> the file copied
    extension: str = ""  # the left-out elements as a <robot> document: the spec's `extension` file, verbatim
    as_given: list[str] = field(default_factory=list)  # values no real body has, kept under `strict: false`
    ignored: list[str] = field(default_factory=list)  # attributes URDF does not define (its readers ignore them)
    wheels: list[str] = field(default_factory=list)  # the links recognised as wheels (the spec's `wheels:`)
    renamed: str = ""  # the robot's name made a spec name, said
    refused: list[str] = field(default_factory=list)  # what the spec refuses of the robot: the spec would not generate
    lines: dict[tuple[str, str], int] = field(default_factory=dict)  # (links or joints, name) -> its line in the file


def _floats(text: str | None, count: int, default: float, where: str) -> list[float]:
    return urdf_floats(text, count, default, where=where)


def _origin(origin: Origin | None, where: str) -> dict[str, list[float]] | None:
    """A URDF <origin> as the spec's (None for the identity or no origin)."""
    if origin is None:
        return None
    xyz = _floats(origin.xyz, 3, 0.0, f"{where} origin xyz")
    rpy = _floats(origin.rpy, 3, 0.0, f"{where} origin rpy")
    found: dict[str, list[float]] = {}
    if any(xyz):
        found["xyz"] = xyz
    if any(rpy):
        found["rpy"] = rpy
    return found or None


def _shape(shape: Shape | None, where: str, problems: list[str]) -> dict[str, Any] | None:
    if shape is None:
        problems.append(f"{where}: no geometry")
        return None
    if shape.kind == "box":
        return {"box": {"size": _floats(shape.get("size"), 3, 0.0, f"{where} box size")}}
    if shape.kind == "cylinder":
        radius = _floats(shape.get("radius"), 1, 0.0, f"{where} cylinder radius")[0]
        length = _floats(shape.get("length"), 1, 0.0, f"{where} cylinder length")[0]
        return {"cylinder": {"radius": radius, "length": length}}
    if shape.kind == "sphere":
        return {"sphere": {"radius": _floats(shape.get("radius"), 1, 0.0, f"{where} sphere radius")[0]}}
    if shape.kind == "mesh":
        mesh: dict[str, Any] = {"filename": shape.get("filename") or ""}
        if shape.get("scale") is not None:
            scale = _floats(shape.get("scale"), 3, 1.0, f"{where} mesh scale")
            if 0.0 in scale:
                problems.append(f"{where}: mesh scale {scale} flattens it (0), which the spec refuses")
                return None
            if scale != [1.0, 1.0, 1.0]:
                mesh["scale"] = scale
        return {"mesh": mesh}
    problems.append(f"{where}: geometry <{shape.kind}> is not one the spec has")
    return None


def import_text(text: str, name_hint: str = "robot", source: str = "") -> Imported:
    """The spec of a URDF text (:func:`import_view` of its view, parsed here)."""

    return import_view(read_view(text, source or "<robot>"), name_hint, source)


def import_view(view: UrdfView, name_hint: str = "robot", source: str = "") -> Imported:
    """The spec of a robot's view (see the module's notes); ``source``: the file it was read from, which locates
    what is reported (``FILE:LINE: link 'x': ...``; a xacro document's lines are its expansion's)."""
    result = Imported(spec={})
    result.spec["robot"] = _robot_name(view.name or name_hint, result)
    for link in view.links:
        result.lines.setdefault(("links", link.name), link.line or 0)
    for joint in view.joints:
        result.lines.setdefault(("joints", joint.name), joint.line or 0)
    located = _Locator(result.lines, source)
    colours = _Colours(view)
    for material in view.materials:  # (every colour the file defines, used or not, in its order)
        colours.name_of(material, f"material {material.name!r}")
    links: dict[str, Any] = {}
    for link in view.links:
        entry = _import_link(link, located, colours, result.unsupported)
        if entry is not None:
            links[link.name] = entry
    joints = _import_joints(view, located, result)
    found = {"links": links, "joints": joints}
    result.wheels, absorbed = wheels(found, view)
    result.extension = _extension(view.root, absorbed, result.leftovers)
    if colours.colours:
        result.spec["materials"] = colours.colours
    result.spec["links"] = links
    if joints:
        result.spec["joints"] = joints
    if "wheels" in found:
        result.spec["wheels"] = found["wheels"]
    _strictness(result, located)
    return result


def _robot_name(robot: str, result: Imported) -> str:
    """The robot's name as the spec can take it: it names the package, the macro and the files (a name that is not
    an identifier, too long, or a xacro keyword's is made one, and that is said in ``result.renamed``)."""
    from ..validate.names import robot_name_problem  # (heavy: jsonschema)

    if not IDENTIFIER.fullmatch(robot) or len(robot) > 200:
        renamed = re.sub(r"[^A-Za-z0-9_]", "_", robot)[:200]
        renamed = renamed if IDENTIFIER.fullmatch(renamed) else f"robot_{renamed}"[:200]
    else:
        renamed = robot
    if renamed.startswith("__"):  # (xacro refuses the names made from it)
        renamed = f"robot{renamed}"[:200]
    if robot_name_problem(renamed) is not None:  # (its macro would be a xacro keyword's)
        renamed = f"{renamed[:194]}_robot"
    if renamed != robot:
        result.renamed = f"robot name {robot!r} written {renamed!r} (it names the package, the macro and the files)"
    return renamed


@dataclass(frozen=True)
class _Locator:
    """``FILE:LINE: `` of a link or joint (by its kind's plural and name), empty when it cannot be said."""

    lines: Mapping[tuple[str, str], int]
    source: str

    def __call__(self, kind: str, name: str) -> str:
        line = self.lines.get((kind, name))
        return f"{self.source}:{line}: " if self.source and line else ""


class _Colours:
    """The spec's named colours, made as the file's materials are met: a material's own name when it is an
    identifier not taken by another colour, else the name of an equal colour, else ``colour_N``."""

    def __init__(self, view: UrdfView) -> None:
        self.colours: dict[str, list[float]] = {}
        self.named = {m.name: m for m in view.materials}

    def name_of(self, material: Material | MaterialRef | None, where: str) -> str | None:
        if material is None:
            return None
        own = material.color_given  # (a <color> without rgba is white, as urdfdom reads it)
        source = material if own else self.named.get(material.name or "")
        if source is None or not source.color_given:
            return None
        rgba = _floats(source.rgba, 4, 1.0, f"{where} colour")
        name = (material.name or "").rsplit("/", 1)[-1]  # (a generated robot's 'ur5/grey': grey)
        if not IDENTIFIER.fullmatch(name) or (name in self.colours and self.colours[name] != rgba):
            name = next((n for n, c in self.colours.items() if c == rgba), f"colour_{len(self.colours)}")
        self.colours.setdefault(name, rgba)
        return name


def _import_link(link: Link, located: _Locator, colours: _Colours, problems: list[str]) -> dict[str, Any] | None:
    """A link's spec entry (None, said in ``problems``, for a name the spec does not take)."""
    name = link.name
    where = f"{located('links', name)}link {name!r}"
    if not NAME.fullmatch(name):
        problems.append(f"{where}: the name is not a spec name (letters, digits and _, in parts joined by . / -)")
        return None
    entry: dict[str, Any] = {}
    drawn = _drawn(link, where, colours, problems)
    entry.update(_visual_fields(drawn))
    touched = []
    for index, collision in enumerate(link.collisions):
        said = f"{where} collision" + (f" {index + 1}" if index else "")
        shape = _shape(collision.shape, said, problems)
        if shape is not None:
            touched.append((shape, _origin(collision.origin, said)))
    if not (drawn and touched == [drawn[0][:2]]):  # ("same", the spec's default, says nothing)
        if not touched:
            if drawn:
                entry["collision"] = "none"
        elif len(touched) == 1:
            entry["collision"] = _geometry(*touched[0])
        else:
            entry["collision"] = [_geometry(s, a) for s, a in touched]
    entry.update(_inertial(link.inertial, where))
    if "inertia" in entry and "shape" in entry and _is_the_shapes(entry):
        del entry["inertia"]  # (the shape's own: the spec computes it from the mass)
    if "inertia" in entry and "origin" in entry and "origin" not in entry["inertia"]:
        entry["inertia"]["origin"] = {"xyz": [0.0, 0.0, 0.0]}  # (else the spec takes the shape's origin for it)
    return entry


def _drawn(link: Link, where: str, colours: _Colours, problems: list[str]) -> list[tuple[Any, Any, str | None]]:
    """(shape, origin, colour) of each visual of the link that the spec can say."""
    drawn = []
    for index, visual in enumerate(link.visuals):
        said = f"{where} visual" + (f" {index + 1}" if index else "")
        shape = _shape(visual.shape, said, problems)
        if shape is not None:
            drawn.append((shape, _origin(visual.origin, said), colours.name_of(visual.material, where)))
    return drawn


def _visual_fields(drawn: list[tuple[Any, Any, str | None]]) -> dict[str, Any]:
    """The first visual as the link's shape, origin and material; the others as ``visuals:``."""
    if not drawn:
        return {}
    shape, at, colour = drawn[0]
    entry: dict[str, Any] = {"shape": shape}
    if at:
        entry["origin"] = at
    if colour:
        entry["material"] = colour
    more = [_geometry(s, a, c if c != colour else None) for s, a, c in drawn[1:]]
    for piece, (_, _, c) in zip(more, drawn[1:], strict=True):
        if colour and c is None:
            piece["material"] = None  # (no colour, where the link's would be the default)
    if more:
        entry["visuals"] = more
    return entry


def _import_joints(view: UrdfView, located: _Locator, result: Imported) -> dict[str, Any]:
    """Every joint whose name the spec takes; the attributes URDF does not define are said in ``result.ignored``."""
    joints: dict[str, Any] = {}
    for joint in view.joints:
        name = joint.name
        if not NAME.fullmatch(name):
            result.unsupported.append(
                f"{located('joints', name)}joint {name!r}: the name is not a spec name (letters, digits and _, in "
                "parts joined by . / -)"
            )
            continue
        joints[name] = _joint(joint, f"{located('joints', name)}joint {name!r}", result.unsupported)
        if joint.mimic is not None and "mimic" not in joints[name]:
            result.ignored.append(f"joint {name!r} <mimic> (a {joint.type} joint: nothing to move)")
        for tag, known in URDF_JOINT_ATTRIBUTES.items():
            for element in joint.element.findall(tag):  # (every such element, the view's first and any other)
                extra = sorted(set(element.attrib) - known)
                if extra:
                    result.ignored.append(f"joint {name!r} <{tag}> {', '.join(extra)}")
    return joints


def _extension(root: Any, absorbed: Any, leftovers: list[str]) -> str:
    """The ``<robot>`` children the spec does not model (and no wheel absorbed), verbatim, as the extension file's
    text ('' when there are none); each is named in ``leftovers``."""

    kept = etree.Element("robot")
    for child in root.iterchildren(etree.Element):
        if child.tag not in MODELLED and child not in absorbed and _holds_xacro(child):
            leftovers.append(f"<{child.tag}{_label(child)}> left out: it holds xacro, which an extension may not")
        elif child.tag not in MODELLED and child not in absorbed:
            leftovers.append(f"<{child.tag}{_label(child)}>")
            copy = etree.fromstring(etree.tostring(child))  # (its own document: namespaces it uses come along)
            copy.tail = None
            kept.append(copy)
    if not len(kept):
        return ""
    kept.text = "\n  "
    for element in kept:
        element.tail = "\n  "
    kept[-1].tail = "\n"
    return etree.tostring(kept, encoding="unicode") + "\n"


def _strictness(result: Imported, located: Any) -> None:
    """``strict: false`` for a robot whose file holds values the spec refuses by default (a mass of 0, a tensor that
    is not physical, a moving link without mass, a continuous joint without limit): they are kept as the file says
    them, and listed (:attr:`Imported.as_given`)."""

    from ..load import load_text  # (heavy: yaml)
    from ..validate import validate  # (heavy: jsonschema)
    from ..validate.physics import Implausible  # (heavy: jsonschema)

    # (its relative meshes are not beside this text, which is read as in a folder that is not there: those errors are
    # not the ones asked about, and nothing of the working folder is read)
    try:
        validate(load_text(yaml_text(result.spec), "/nonexistent/xacrokit-import/spec.yaml"))
        return
    except SpecErrors as caught:
        doubts = [e for e in caught.errors if isinstance(e, Implausible)]
        for error in caught.errors:  # (what the spec would refuse besides: said now; a relative mesh is seen to)
            if not isinstance(error, Implausible) and not error.path.endswith(".filename"):
                found = SPEC_ITEM.match(error.path)  # (at the link's or joint's line in the file)
                where = located(found[1], found[2] or found[3]) if found else ""
                said = f"{where}the spec refuses {error.path.removeprefix('$.')}: {error.message}"
                result.unsupported.append(said)
                result.refused.append(said)
    if doubts:
        result.spec = {"robot": result.spec["robot"], "strict": False, **result.spec}
        result.as_given = [f"{e.path.removeprefix('$.')}: {e.message}" for e in doubts]


def _is_the_shapes(entry: dict[str, Any]) -> bool:
    """Whether a link's inertia is, bit for bit, the one the spec computes from its shape and mass (a solid of uniform
    density centred on the shape's origin, in the shape's axes): then the spec says only the mass, and writes the same
    numbers back. Not "to a tolerance": the chapter's sphere says 0.008 where 2/5 m r^2 is 0.008000000000000002, and
    dropping it would change the robot in its last digit."""
    from ..resolve import shape_inertia  # (heavy: jsonschema)

    if "mesh" in entry["shape"]:
        return False  # (a mesh's tensor comes from its surface: kept as the file says it)
    shape_at = entry.get("origin", {})
    given = entry["inertia"]
    given_at = given.get("origin", {})
    if list(given_at.get("xyz", [0.0] * 3)) != list(shape_at.get("xyz", [0.0] * 3)):
        return False
    if list(given_at.get("rpy", [0.0] * 3)) != list(shape_at.get("rpy", [0.0] * 3)):
        return False  # (the same tensor said in other axes: kept as said, so that it is written back the same)
    computed = shape_inertia(entry["shape"], entry["mass"], _zero_origin())  # (in the shape's axes: the given's too)
    said = {k: float(given.get(k, 0.0)) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
    own = {"ixx": computed.ixx, "iyy": computed.iyy, "izz": computed.izz, "ixy": 0.0, "ixz": 0.0, "iyz": 0.0}
    return said == {k: float(v) for k, v in own.items()}


def _zero_origin() -> Any:
    return SpecOrigin()


def _holds_xacro(element: Any) -> bool:
    """Whether an element holds a xacro element or attribute (an extension file is copied verbatim: no xacro)."""

    xacro = "{http://www.ros.org/wiki/xacro}"
    return any(
        str(e.tag).startswith(xacro) or any(str(k).startswith(xacro) for k in e.attrib)
        for e in element.iter(etree.Element)
    )


def _label(element: Any) -> str:
    for key in ("name", "reference"):
        if element.get(key):
            return f' {key}="{element.get(key)}"'
    return ""


def _geometry(shape: dict[str, Any], at: dict[str, Any] | None, colour: str | None = None) -> dict[str, Any]:
    """A `visuals` or `collision` entry: a shape, its origin and its colour (when they are not the defaults)."""
    found: dict[str, Any] = {"shape": shape}
    if at:
        found["origin"] = at
    if colour:
        found["material"] = colour
    return found


def _inertial(inertial: Inertial | None, where: str) -> dict[str, Any]:
    if inertial is None or inertial.mass_line is None:
        return {}
    mass = _floats(inertial.mass, 1, 0.0, f"{where} mass")[0]
    tensor = inertial.inertia
    keys = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")
    values = {k: _floats(tensor.get(k) if tensor is not None else None, 1, 0.0, f"{where} {k}")[0] for k in keys}
    if mass == 0.0 and not any(values.values()):
        return {}  # (a frame: no mass, no inertia)
    inertia: dict[str, Any] = {k: v for k, v in values.items() if v or k in ("ixx", "iyy", "izz")}
    at = _origin(inertial.origin, f"{where} inertial")
    if at:
        inertia["origin"] = at
    return {"mass": mass, "inertia": inertia}


def _joint(joint: Joint, where: str, problems: list[str]) -> dict[str, Any]:
    entry: dict[str, Any] = {"type": joint.type, "parent": joint.parent, "child": joint.child}
    at = _origin(joint.origin, where)
    if at:
        entry["origin"] = at
    if joint.axis is not None and joint.type not in ("fixed", "floating"):
        entry["axis"] = _floats(joint.axis, 3, 0.0, f"{where} axis")
    limit = joint.limit
    if limit is not None and joint.type in ("revolute", "prismatic", "continuous"):
        entry["limit"] = {
            key: _floats(limit.get(key), 1, 0.0, f"{where} limit {key}")[0]
            for key in ("lower", "upper", "effort", "velocity")
            if limit.get(key) is not None and not (joint.type == "continuous" and key in ("lower", "upper"))
        }
        if joint.type != "continuous":  # (urdfdom reads a range not given as 0: the spec says it)
            entry["limit"] = {"lower": 0.0, "upper": 0.0, **entry["limit"]}
    moving = joint.type in ("revolute", "prismatic", "continuous")
    dynamics = joint.dynamics
    if dynamics is not None and moving:  # (URDF readers ignore a fixed joint's dynamics)
        entry["dynamics"] = {
            key: _floats(dynamics.get(key), 1, 0.0, f"{where} {key}")[0]
            for key in ("damping", "friction")
            if dynamics.get(key) is not None
        }
    mimic = joint.mimic
    if mimic is not None and moving:  # (a fixed joint's mimic moves nothing: left out, said in the header)
        entry["mimic"] = {"joint": mimic.joint}
        for key, default in (("multiplier", 1.0), ("offset", 0.0)):
            value = _floats(getattr(mimic, key), 1, default, f"{where} mimic {key}")[0]
            if value != default:
                entry["mimic"][key] = value
    safety = joint.safety_controller
    if safety is not None and moving:
        entry["safety_controller"] = {
            key: _floats(safety.get(key), 1, 0.0, f"{where} {key}")[0]
            for key in ("soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity")
            if safety.get(key) is not None
        }
    calibration = joint.calibration
    if calibration is not None:
        given = [k for k in ("rising", "falling") if calibration.get(k) is not None]
        if given:
            said = {k: _floats(calibration.get(k), 1, 0.0, f"{where} calibration {k}")[0] for k in given}
            entry["calibration"] = said
    return entry


def import_robot(robot: ReadRobot | RobotInput | str | os.PathLike[str]) -> Imported:
    """The spec of a read URDF or xacro document (or what to read: a xacro document's arguments in its input).

    Raises:
        XacrokitError: unreadable input, or a robot with nothing the spec can hold.
    """

    read = read_robot(robot)
    imported = import_view(read.view, read.path.stem.split(".")[0], read.where)
    _relative_meshes(imported, read.path, read.packages, read.where)
    return imported


def _relative_meshes(imported: Imported, urdf: Any, packages: Mapping[str, Any], source: str) -> None:
    """A mesh named by a path relative to the URDF (``meshes/arm.stl``) is copied beside the spec, under
    ``meshes/``, and the spec names the copy: gen-robot then carries it into the package. The robot's folders below
    the one all its copied meshes share are kept (``visual/wrist3.obj`` and ``collision/wrist3.obj`` become
    ``meshes/visual/wrist3.obj`` and ``meshes/collision/wrist3.obj``). (A ``package://`` or ``file://`` URI stays as
    written: the package it names is the user's.) What is copied is read here, once, safely
    (:func:`~xacrokit.reader.mesh_copies.mesh_to_copy`: no link, nothing outside the robot's folder, a mesh of its
    kind) and streamed when the spec is written; a mesh that is not is a located error, and nothing is imported."""

    from ..validate.bodies import geometries  # (heavy: jsonschema)

    found: list[tuple[dict[str, Any], str, str]] = []  # (the spec's mesh, the file, where the URDF names it)
    for link_name, link in imported.spec.get("links", {}).items():
        for holder in [link, *(geometry for _, geometry in geometries((), link))]:
            mesh = holder.get("shape", {}).get("mesh")
            if not mesh or not is_relative(mesh["filename"]):
                continue
            path = mesh_file(mesh["filename"], urdf.parent, packages)
            line = imported.lines.get(("links", link_name))
            if not Path(path).is_file() and not Path(path).is_symlink():
                imported.unsupported.append(f"mesh {mesh['filename']!r}: not found (looked for {str(path)!r})")
            elif PurePosixPath(mesh["filename"]).suffix.lower() not in MESH_SUFFIXES:
                imported.unsupported.append(f"mesh {mesh['filename']!r}: not a mesh file the spec copies")
            else:
                where = f"{source}:{line}: " if line else f"{source}: "
                found.append((mesh, os.path.normpath(os.path.abspath(path)), f"{where}mesh {mesh['filename']!r}"))
    if not found:
        return
    shared = os.path.commonpath([os.path.dirname(file) for _, file, _ in found])
    for mesh, file, said in found:
        target = "meshes/" + Path(os.path.relpath(file, shared)).as_posix()
        if target not in imported.meshes:
            imported.meshes[target] = mesh_to_copy(robot_folder(urdf), Path(file), where=said)
        mesh["filename"] = target


def yaml_text(data: Any, **options: Any) -> str:
    """``data`` as YAML in its keys' order, by libyaml's emitter when PyYAML has it: the pure-Python one took 85 s of
    a 20,000-link import's 114 (the text is the same: all 129 real robots' specs compared)."""
    import yaml  # (heavy: yaml)

    text: str = yaml.dump(data, Dumper=getattr(yaml, "CSafeDumper", yaml.SafeDumper), sort_keys=False, **options)
    return text


def spec_yaml(imported: Imported, source: str) -> str:
    """The spec as YAML, with a header naming its source and what was not imported."""

    said = [f"Imported by gen-robot import from {source!r}."]
    said += [f"not imported: {line}" for line in imported.unsupported]
    said += [f"as the file says it (strict: false): {line}" for line in imported.as_given]
    said += [f"not URDF, ignored by its readers: {line}" for line in imported.ignored]
    said += [f"renamed: {imported.renamed}"] if imported.renamed else []
    if imported.wheels:
        said.append(f"wheels (exactly what the spec's wheels: write): {', '.join(imported.wheels)}")
    said += [f"kept in the extension file (not modelled by the spec): {line}" for line in imported.leftovers]
    # (one comment line each: every line break YAML knows, a carriage return among them, is made a space)
    lines = ["# " + " ".join(line.splitlines()) for line in said]
    body = yaml_text(imported.spec, default_flow_style=None, width=120, allow_unicode=True)
    return "\n".join(lines) + "\n" + body
