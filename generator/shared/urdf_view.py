"""One typed, read-only view of a URDF document that every command walks instead of lxml (yourdfpy's shape: one
dataclass per element, but lossless and located).

Lossless: every attribute is kept as the text the file gives (``None`` when absent), so that each reader decides how
strictly to read a number (check reports a number that does not read; the viewer draws a default and goes on; the
MJCF export refuses it): :func:`number` and :func:`numbers` read them. Every element keeps its source line and its lxml
element (``element``) for what the view does not model. Located: ``line`` is the element's line in the text parsed
(the file's own for a URDF; an expansion's for xacro and specs).

Only the document's top-level ``<link>``, ``<joint>``, ``<material>``, ``<gazebo>`` and ``<ros2_control>`` elements
are robot parts, as for urdfdom; anything else is in ``root``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from lxml import etree

from ..shared.units import INPUT_BOUNDS
from .kinematic_tree import Tree
from .xml_parse import read_urdf_root

Attributes = Mapping[str, str]


@dataclass(frozen=True)
class Part:
    """What every element of the view has: its lxml element and its line in the text parsed."""

    element: Any = field(repr=False, compare=False)
    line: int | None


@dataclass(frozen=True)
class Origin(Part):
    xyz: str | None = None
    rpy: str | None = None


@dataclass(frozen=True)
class Shape(Part):
    """The first element inside a ``<geometry>`` (comments skipped): ``kind`` is its tag (box, cylinder, sphere,
    mesh, capsule, or anything else a file writes), ``attributes`` its attributes (size, radius, length, filename,
    scale)."""

    kind: str = ""
    attributes: Attributes = field(default_factory=dict)

    def get(self, name: str) -> str | None:
        return self.attributes.get(name)


@dataclass(frozen=True)
class MaterialRef(Part):
    """A visual's ``<material>``: by name, with its own colour or texture when it gives one."""

    name: str | None = None
    rgba: str | None = None  # (None without <color>, or a <color> without rgba: color_given tells them apart)
    texture: str | None = None
    color_given: bool = False  # a <color> element (urdfdom reads one without rgba as white)
    texture_given: bool = False

    @property
    def defines(self) -> bool:
        """Whether it gives its own colour or texture (urdfdom then registers it for the whole robot by name)."""
        return self.color_given or self.texture_given


@dataclass(frozen=True)
class Geometry(Part):
    """A ``<visual>`` or ``<collision>``: its origin, shape and (visuals) material."""

    name: str | None = None
    origin: Origin | None = None
    shape: Shape | None = None
    material: MaterialRef | None = None


@dataclass(frozen=True)
class Inertial(Part):
    origin: Origin | None = None
    mass: str | None = None
    mass_line: int | None = None
    inertia: Attributes | None = None  # ixx, ixy, ixz, iyy, iyz, izz as the file gives them; None without <inertia>


@dataclass(frozen=True)
class Link(Part):
    name: str = ""
    inertial: Inertial | None = None
    visuals: tuple[Geometry, ...] = ()
    collisions: tuple[Geometry, ...] = ()


@dataclass(frozen=True)
class Mimic(Part):
    joint: str | None = None
    multiplier: str | None = None
    offset: str | None = None


@dataclass(frozen=True)
class Joint(Part):
    """A ``<joint>``; ``limit``, ``dynamics``, ``safety_controller`` and ``calibration`` are their elements'
    attributes (None when the element is absent)."""

    name: str = ""
    type: str | None = None
    parent: str | None = None
    child: str | None = None
    origin: Origin | None = None
    axis: str | None = None  # the <axis> xyz; None without <axis> (URDF's default is 1 0 0)
    limit: Attributes | None = None
    dynamics: Attributes | None = None
    mimic: Mimic | None = None
    safety_controller: Attributes | None = None
    calibration: Attributes | None = None


@dataclass(frozen=True)
class Material(Part):
    """A robot-level ``<material>``: its name and colour (rgba text) or texture."""

    name: str = ""
    rgba: str | None = None
    texture: str | None = None
    color_given: bool = False
    texture_given: bool = False


@dataclass(frozen=True)
class Extension(Part):
    """A ``<gazebo>`` block (``reference``: the link or joint it is about, None for the robot) or a
    ``<ros2_control>`` block (``reference``: its name; ``joints``: the joints it lists)."""

    reference: str | None = None
    joints: tuple[str, ...] = ()


@dataclass(frozen=True)
class UrdfView:
    """The robot: its parts in document order, and look-ups by name (the first of a duplicated name)."""

    root: Any = field(repr=False, compare=False)
    name: str | None
    links: tuple[Link, ...]
    joints: tuple[Joint, ...]
    materials: tuple[Material, ...]
    gazebo: tuple[Extension, ...]
    ros2_control: tuple[Extension, ...]

    def link(self, name: str) -> Link | None:
        return next((link for link in self.links if link.name == name), None)

    def joint(self, name: str) -> Joint | None:
        return next((joint for joint in self.joints if joint.name == name), None)

    def colours(self) -> dict[str, str]:
        """Every colour a material defines by name, robot-level or inside a visual (as urdfdom reads them)."""
        found = {m.name: m.rgba for m in self.materials if m.rgba is not None}
        for link in self.links:
            for visual in link.visuals:
                given = visual.material
                if given is not None and given.name and given.rgba is not None:
                    found.setdefault(given.name, given.rgba)
        return found


def read_view(text: str, where: str = "<robot>") -> UrdfView:
    """The view of a URDF text (parsed once, hardened: :mod:`xacrokit.shared.xml_parse`).

    Raises:
        XacrokitError: not well-formed XML, or not a ``<robot>`` (located at ``where``).
    """
    return view_of(read_urdf_root(text, where))


def view_of(root: etree._Element) -> UrdfView:
    """The view of a parsed ``<robot>`` element."""
    children = [child for child in root if isinstance(child.tag, str)]
    return UrdfView(
        root=root,
        name=root.get("name"),
        links=tuple(_link(e) for e in children if e.tag == "link"),
        joints=tuple(_joint(e) for e in children if e.tag == "joint"),
        materials=tuple(_material(e) for e in children if e.tag == "material"),
        gazebo=tuple(Extension(e, e.sourceline, e.get("reference")) for e in children if e.tag == "gazebo"),
        ros2_control=tuple(_control(e) for e in children if e.tag == "ros2_control"),
    )


def _attributes(element: etree._Element | None) -> dict[str, str] | None:
    return None if element is None else {str(k): str(v) for k, v in element.attrib.items()}


def _origin(element: etree._Element | None) -> Origin | None:
    if element is None:
        return None
    return Origin(element, element.sourceline, element.get("xyz"), element.get("rpy"))


def _shape(holder: etree._Element) -> Shape | None:
    geometry = holder.find("geometry")
    shape = None if geometry is None else next(geometry.iterchildren(etree.Element), None)
    if shape is None:
        return None
    return Shape(shape, shape.sourceline, str(shape.tag), _attributes(shape) or {})


def _material_ref(element: etree._Element | None) -> MaterialRef | None:
    if element is None:
        return None
    colour, texture = element.find("color"), element.find("texture")
    return MaterialRef(
        element,
        element.sourceline,
        element.get("name"),
        colour.get("rgba") if colour is not None else None,
        texture.get("filename") if texture is not None else None,
        colour is not None,
        texture is not None,
    )


def _geometry(element: etree._Element) -> Geometry:
    return Geometry(
        element,
        element.sourceline,
        element.get("name"),
        _origin(element.find("origin")),
        _shape(element),
        _material_ref(element.find("material")),
    )


def _inertial(element: etree._Element | None) -> Inertial | None:
    if element is None:
        return None
    mass, inertia = element.find("mass"), element.find("inertia")
    return Inertial(
        element,
        element.sourceline,
        _origin(element.find("origin")),
        mass.get("value") if mass is not None else None,
        mass.sourceline if mass is not None else None,
        _attributes(inertia),
    )


def _link(element: etree._Element) -> Link:
    return Link(
        element,
        element.sourceline,
        element.get("name", ""),
        _inertial(element.find("inertial")),
        tuple(_geometry(e) for e in element.findall("visual")),
        tuple(_geometry(e) for e in element.findall("collision")),
    )


def _joint(element: etree._Element) -> Joint:
    parent, child, axis, mimic = (element.find(tag) for tag in ("parent", "child", "axis", "mimic"))
    return Joint(
        element,
        element.sourceline,
        element.get("name", ""),
        element.get("type"),
        parent.get("link") if parent is not None else None,
        child.get("link") if child is not None else None,
        _origin(element.find("origin")),
        axis.get("xyz") if axis is not None else None,
        _attributes(element.find("limit")),
        _attributes(element.find("dynamics")),
        None
        if mimic is None
        else Mimic(mimic, mimic.sourceline, mimic.get("joint"), mimic.get("multiplier"), mimic.get("offset")),
        _attributes(element.find("safety_controller")),
        _attributes(element.find("calibration")),
    )


def _material(element: etree._Element) -> Material:
    colour, texture = element.find("color"), element.find("texture")
    return Material(
        element,
        element.sourceline,
        element.get("name", ""),
        colour.get("rgba") if colour is not None else None,
        texture.get("filename") if texture is not None else None,
        colour is not None,
        texture is not None,
    )


def _control(element: etree._Element) -> Extension:
    joints = tuple(j.get("name", "") for j in element.findall("joint"))
    return Extension(element, element.sourceline, element.get("name"), joints)


def number(text: str | None, default: float) -> float:
    """A finite number from an attribute's text; ``default`` when it is absent, not a number or not finite (the
    lenient reading of the commands that show a robot: check says what is wrong)."""
    try:
        value = float(text) if text is not None else default
    except ValueError:
        return default
    return value if math.isfinite(value) else default


def numbers(text: str | None, default: list[float]) -> list[float]:
    """``len(default)`` numbers from an attribute's text; ``default`` when it does not hold that many numbers."""
    try:
        values = [float(v) for v in (text or "").split()]
    except ValueError:
        return default
    return values if len(values) == len(default) else default


SIZE_ATTRIBUTES = {
    "box": ("size",),
    "cylinder": ("radius", "length"),
    "sphere": ("radius",),
    "capsule": ("radius", "length"),
}


def length_problems(view: UrdfView) -> list[str]:
    """The lengths a command that draws or exports the robot cannot take, one line each, named by element and
    attribute: a primitive's size that is not a positive number within INPUT_BOUNDS' length (1e4 m), an origin's
    or a joint's xyz beyond it (a size of 1e308 m overflows the meshes and axes drawn for it)."""

    bound = INPUT_BOUNDS["length"]
    problems: list[str] = []

    def beyond(text: str | None, where: str, *, positive: bool = False) -> None:
        try:
            values = [float(v) for v in (text or "").split()]
        except ValueError:
            return  # (not numbers, or not finite: each reader says so in its own words)
        if all(map(math.isfinite, values)) and any(abs(v) > bound or (positive and not v > 0) for v in values):
            kind = "a positive number" if positive else "a number"
            problems.append(f"{where} {text!r}: each must be {kind} of at most {bound:g} m")

    for link in view.links:
        for kind, holders in (("visual", link.visuals), ("collision", link.collisions)):
            for index, geometry in enumerate(holders, 1):
                where = f"link {link.name!r}, {kind} {index}:"
                if geometry.origin is not None:
                    beyond(geometry.origin.xyz, f"{where} <origin xyz>")
                shape = geometry.shape
                for attribute in SIZE_ATTRIBUTES.get(shape.kind if shape else "", ()):
                    beyond(
                        shape.get(attribute) if shape else None,
                        f"{where} <{shape.kind if shape else ''} {attribute}>",
                        positive=True,
                    )
        if link.inertial is not None and link.inertial.origin is not None:
            beyond(link.inertial.origin.xyz, f"link {link.name!r}: <inertial><origin xyz>")
    for joint in view.joints:
        if joint.origin is not None:
            beyond(joint.origin.xyz, f"joint {joint.name!r}: <origin xyz>")
    return problems


def joint_tree(view: UrdfView) -> Tree[Joint]:
    """The view's joints that name a parent and a child as a :class:`~xacrokit.shared.kinematic_tree.Tree` (the
    first parent of a link wins), keyed by the joint."""
    tree: Tree[Joint] = Tree()
    for joint in view.joints:
        if joint.parent is not None and joint.child is not None:
            tree.add(joint.parent, joint.child, joint)
    return tree
