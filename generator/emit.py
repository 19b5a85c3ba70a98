"""The direct URDF emitter: the resolved model to URDF with lxml, no xacro in the loop.

It describes exactly the robot that expanding the generated package with xacro (default arguments) describes: the
same elements, names and numbers. Every computed number follows the macro library's arithmetic operation for
operation (same formulas, same order), so the two agree to the last bit in practice; ``urdf_differences`` is the
tolerant comparison the differential tests use (numbers to 1e-12, attribute order and comments ignored).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Iterator

from lxml import etree

from .model import (
    Arm,
    Box,
    Cylinder,
    DHRow,
    Inertia,
    Joint,
    Link,
    Mesh,
    Origin,
    Robot,
    Scene,
    Shape,
    Sphere,
    Vec3,
    Wheel,
    attach_joint_name,
    material_name,
)
from .shared.gc_pause import collector_paused
from .shared.sim_sensors import sensor_element, topic_namespace
from .shared.transforms import screw_pose
from .shared.value_text import num, vec
from .shared.xml_parse import parse_xml

AXIS_VECTORS = {"x": "1 0 0", "y": "0 1 0", "z": "0 0 1"}
AXLE_GEOMETRY_RPY = {"x": "0 " + str(math.pi / 2) + " 0", "y": str(math.pi / 2) + " 0 0", "z": "0 0 0"}


def _sub(parent: etree._Element, tag: str, **attributes: str) -> etree._Element:
    return etree.SubElement(parent, tag, attributes)


def _origin(parent: etree._Element, origin: Origin) -> None:
    _sub(parent, "origin", xyz=vec(origin.xyz), rpy=vec(origin.rpy))


def _geometry(parent: etree._Element, shape: Shape) -> None:
    geometry = _sub(parent, "geometry")
    if isinstance(shape, Box):
        _sub(geometry, "box", size=vec(shape.size))
    elif isinstance(shape, Cylinder):
        _sub(geometry, "cylinder", radius=num(shape.radius), length=num(shape.length))
    elif isinstance(shape, Sphere):
        _sub(geometry, "sphere", radius=num(shape.radius))
    else:
        assert isinstance(shape, Mesh)
        _sub(geometry, "mesh", filename=shape.filename, scale=vec(shape.scale))


TENSOR = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")  # an <inertia>'s attributes, in the order they are written


def _inertial(parent: etree._Element, inertia: Inertia, xyz: str, rpy: str) -> None:
    """``<inertial>`` of ``inertia``'s mass and tensor, its origin written as given (``xyz``, ``rpy``: as the macro
    that makes the same element writes them)."""
    i = inertia
    inertial = _sub(parent, "inertial")
    _sub(inertial, "origin", xyz=xyz, rpy=rpy)
    _sub(inertial, "mass", value=num(i.mass))
    _sub(inertial, "inertia", **{name: num(getattr(i, name)) for name in TENSOR})


def _stored_inertial(parent: etree._Element, inertia: Inertia) -> None:
    """The model's tensor: resolve computed a shape's with the formulas the library's *_inertial macros use."""
    _inertial(parent, inertia, vec(inertia.origin.xyz), vec(inertia.origin.rpy))


def link_element(robot: Robot, prefix: str, link: Link) -> etree._Element:
    """A spec link (or frame) as URDF, its name glued to ``prefix``."""
    element = etree.Element("link", name=prefix + link.name)
    for drawn in link.visuals:
        visual = _sub(element, "visual")
        _origin(visual, drawn.origin)
        _geometry(visual, drawn.shape)
        if drawn.material:
            _sub(visual, "material", name=material_name(robot, drawn.material))
    for touched in link.collisions:
        collision = _sub(element, "collision")
        _origin(collision, touched.origin)
        _geometry(collision, touched.shape)
    if link.inertial is not None:
        _stored_inertial(element, link.inertial)
    return element


def joint_element(prefix: str, joint: Joint) -> etree._Element:
    """A spec joint as URDF, the names it holds glued to ``prefix``."""
    element = etree.Element("joint", name=prefix + joint.name, type=joint.type)
    _sub(element, "parent", link=prefix + joint.parent)
    _sub(element, "child", link=prefix + joint.child)
    _origin(element, joint.origin)
    if joint.axis is not None:
        _sub(element, "axis", xyz=vec(joint.axis))
    if joint.limit is not None:
        bounds = joint.limit.bounds
        limit = {} if bounds is None else {"lower": num(bounds[0]), "upper": num(bounds[1])}
        _sub(element, "limit", **limit, effort=num(joint.limit.effort), velocity=num(joint.limit.velocity))
    if joint.dynamics is not None:
        _sub(element, "dynamics", damping=num(joint.dynamics.damping), friction=num(joint.dynamics.friction))
    if joint.mimic is not None:
        _sub(
            element,
            "mimic",
            joint=prefix + joint.mimic.joint,
            multiplier=num(joint.mimic.multiplier),
            offset=num(joint.mimic.offset),
        )
    if joint.safety_controller is not None:
        s = joint.safety_controller
        values = {
            "k_velocity": s.k_velocity,
            "k_position": s.k_position,
            "soft_lower_limit": s.soft_lower_limit,
            "soft_upper_limit": s.soft_upper_limit,
        }
        _sub(element, "safety_controller", **{k: num(v) for k, v in values.items() if v is not None})
    if joint.calibration is not None:
        edges = {"rising": joint.calibration.rising, "falling": joint.calibration.falling}
        _sub(element, "calibration", **{k: num(v) for k, v in edges.items() if v is not None})
    return element


def screw_origin(a: float, alpha: float, xyz: Vec3, rpy: Vec3) -> tuple[str, str]:
    """(xyz, rpy) text of :func:`screw_pose` (the pose ``xyz``, ``rpy`` after the x screw ``a``, ``alpha``), as its
    twin _xacrokit_origin_after_x_screw writes it."""
    moved, turned = screw_pose(a, alpha, xyz, rpy)
    return " ".join(map(repr, moved)), " ".join(map(repr, turned))


def _dh_body(robot: Robot, link: etree._Element, row: DHRow) -> None:
    """The row's body as resolve made it (:attr:`DHRow.body`), written as the macro writes it: its numbers with
    ``%r`` (what :func:`vec` writes), a sphere's inertial frame unrotated ("0 0 0")."""
    body = row.body
    if body is None:
        return
    xyz, rpy = vec(body.origin.xyz), vec(body.origin.rpy)
    for tag in ("visual", "collision"):
        part = _sub(link, tag)
        _sub(part, "origin", xyz=xyz, rpy=rpy)
        _geometry(part, body.shape)
        if tag == "visual" and row.material:
            _sub(part, "material", name=material_name(robot, row.material))
    i = body.inertia
    turned = vec(i.origin.rpy) if isinstance(body.shape, Cylinder) or i.kind == "explicit" else "0 0 0"
    _inertial(link, i, vec(i.origin.xyz), turned)


def _arm(robot: Robot, prefix: str, arm: Arm) -> Iterator[etree._Element]:
    if arm.base is not None:  # (else the first joint hangs on parent, DH frame 0: base: false)
        yield etree.Element("link", name=prefix + arm.base)
        base_joint = etree.Element("joint", name=prefix + attach_joint_name(arm.base), type="fixed")
        _sub(base_joint, "parent", link=prefix + arm.parent)
        _sub(base_joint, "child", link=prefix + arm.base)
        _origin(base_joint, arm.origin)
        yield base_joint
    rows = arm.rows
    parent = prefix + arm.frame0
    for index, row in enumerate(rows):
        screw = row if arm.convention == "modified" else (rows[index - 1] if index > 0 else None)
        joint = etree.Element("joint", name=prefix + row.name, type=row.type)
        _sub(joint, "parent", link=parent)
        _sub(joint, "child", link=prefix + row.link)
        xyz, rpy = screw_origin(
            screw.a if screw else 0.0, screw.alpha if screw else 0.0, (0.0, 0.0, row.d), (0.0, 0.0, row.theta)
        )
        _sub(joint, "origin", xyz=xyz, rpy=rpy)
        if row.type != "fixed":
            _sub(joint, "axis", xyz="0 0 1")
        if row.limit is not None and row.type != "fixed":
            bounds = row.limit.bounds if row.type != "continuous" else None
            limit = {} if bounds is None else {"lower": num(bounds[0]), "upper": num(bounds[1])}
            _sub(joint, "limit", **limit, effort=num(row.limit.effort), velocity=num(row.limit.velocity))
        if row.dynamics is not None and row.type != "fixed":
            _sub(joint, "dynamics", damping=num(row.dynamics.damping), friction=num(row.dynamics.friction))
        yield joint
        link = etree.Element("link", name=prefix + row.link)
        _dh_body(robot, link, row)
        yield link
        parent = prefix + row.link
    last = rows[-1]
    yield etree.Element("link", name=prefix + arm.tool)
    tool_joint = etree.Element("joint", name=prefix + arm.tool_joint_name, type="fixed")
    _sub(tool_joint, "parent", link=prefix + last.link)
    _sub(tool_joint, "child", link=prefix + arm.tool)
    standard = arm.convention == "standard"
    xyz, rpy = screw_origin(
        last.a if standard else 0.0, last.alpha if standard else 0.0, arm.tool_origin.xyz, arm.tool_origin.rpy
    )
    _sub(tool_joint, "origin", xyz=xyz, rpy=rpy)
    yield tool_joint


def _wheel(robot: Robot, prefix: str, wheel: Wheel) -> Iterator[etree._Element]:
    joint = etree.Element("joint", name=prefix + wheel.joint_name, type="continuous")
    _sub(joint, "parent", link=prefix + wheel.parent)
    _sub(joint, "child", link=prefix + wheel.name)
    _origin(joint, wheel.origin)
    _sub(joint, "axis", xyz=AXIS_VECTORS[wheel.axis])
    _sub(joint, "limit", effort=num(wheel.effort), velocity=num(wheel.velocity))
    _sub(joint, "dynamics", damping=num(wheel.damping), friction=num(wheel.friction))
    yield joint
    link = etree.Element("link", name=prefix + wheel.name)
    shape = Cylinder(wheel.radius, wheel.width)
    for tag in ("visual", "collision"):
        part = _sub(link, tag)
        _sub(part, "origin", xyz="0 0 0", rpy=AXLE_GEOMETRY_RPY[wheel.axis])
        _geometry(part, shape)
        if tag == "visual" and wheel.material:
            _sub(part, "material", name=material_name(robot, wheel.material))
    i = wheel.inertia
    assert i is not None  # (resolve gives every wheel its inertia)
    _inertial(link, i, "0 0 0", "0 0 0")
    yield link
    gazebo = etree.Element("gazebo", reference=prefix + wheel.name)
    _sub(gazebo, "mu1").text = num(wheel.mu1)
    _sub(gazebo, "mu2").text = num(wheel.mu2)
    yield gazebo


class _Copies:
    """A scene's robots' links and joints written once each without a prefix, then copied for each instance with its
    prefix glued to the names they hold (a link's name; a joint's name, parent, child and mimic leader: what
    :func:`link_element` and :func:`joint_element` glue it to): a fleet of 100 copies writes its numbers once."""

    def __init__(self) -> None:
        self.written: dict[int, tuple[Robot, list[etree._Element]]] = {}

    def of(self, robot: Robot, prefix: str) -> list[etree._Element]:
        if id(robot) not in self.written:  # (the robot is kept beside its elements: its id stays its own)
            links = [link_element(robot, "", link) for link in robot.links]
            self.written[id(robot)] = (robot, links + [joint_element("", joint) for joint in robot.joints])
        return [_prefixed(element, prefix) for element in self.written[id(robot)][1]]


def _prefixed(element: etree._Element, prefix: str) -> etree._Element:
    copied = copy.deepcopy(element)
    copied.set("name", prefix + copied.get("name", ""))
    if copied.tag == "joint":
        for tag, attribute in (("parent", "link"), ("child", "link"), ("mimic", "joint")):
            named = copied.find(tag)
            if named is not None:
                named.set(attribute, prefix + named.get(attribute, ""))
    return copied


def robot_elements(
    robot: Robot, *, prefix: str = "", ros2_control: str = "mock", extras: bool = True, copies: _Copies | None = None
) -> list[etree._Element]:
    """The robot's elements (without materials), as its macro writes them for ``prefix``.

    ``extras=False`` leaves out the Gazebo surfaces and the ros2_control block (their own macros write them);
    ``copies``: a scene's links and joints, written once per robot (:class:`_Copies`).
    """
    if copies is None:
        elements = [link_element(robot, prefix, link) for link in robot.links]
        elements += [joint_element(prefix, joint) for joint in robot.joints]
    else:
        elements = copies.of(robot, prefix)
    for arm in robot.arms:
        elements += _arm(robot, prefix, arm)
    for wheel in robot.wheels:
        elements += _wheel(robot, prefix, wheel)
    for surface in robot.surfaces if extras else ():
        gazebo = etree.Element("gazebo", reference=prefix + surface.link)
        for key in ("mu1", "mu2", "kp", "kd"):
            if getattr(surface, key) is not None:
                _sub(gazebo, key).text = num(getattr(surface, key))
        elements.append(gazebo)
    for sensor in robot.sensors if extras else ():
        elements.append(sensor_element(sensor, prefix, topic_namespace(prefix)))
    if extras and robot.ros2_control is not None and ros2_control == "mock":
        elements.append(_ros2_control(robot, prefix))
    return elements


def _ros2_control(robot: Robot, prefix: str) -> etree._Element:
    block = etree.Element("ros2_control", name=prefix + robot.name, type="system")
    hardware = _sub(block, "hardware")
    _sub(hardware, "plugin").text = "mock_components/GenericSystem"
    if robot.mock_integrates:  # (velocity commands move the position state only so)
        _sub(hardware, "param", name="calculate_dynamics").text = "true"
    for controlled in robot.ros2_control or ():
        joint = _sub(block, "joint", name=prefix + controlled.name)
        for interface in controlled.interfaces.command:
            _sub(joint, "command_interface", name=interface)
        for interface in controlled.interfaces.state:
            state = _sub(joint, "state_interface", name=interface)
            if interface == "position":
                _sub(state, "param", name="initial_value").text = num(controlled.initial_position)
    return block


def material_elements(robot: Robot) -> list[etree._Element]:
    result = []
    for name, rgba in robot.materials:
        material = etree.Element("material", name=material_name(robot, name))
        _sub(material, "color", rgba=vec(rgba))
        result.append(material)
    return result


@collector_paused()
def emit_urdf(robot: Robot) -> str:
    """The URDF of ``robot`` with the entry's default arguments (no prefix; ros2_control mock when the spec has it)."""
    root = etree.Element("robot", name=robot.name)
    for element in (*material_elements(robot), *robot_elements(robot)):
        root.append(element)
    etree.indent(root, space="  ")
    return '<?xml version="1.0" ?>\n' + etree.tostring(root, encoding="unicode") + "\n"


# ------------------------------------------------------------------------------------------------------ comparison
def _numbers_equal(a: str, b: str, rel: float) -> bool:
    left, right = a.split(), b.split()
    if len(left) != len(right):
        return False
    for x, y in zip(left, right, strict=True):
        if x == y:
            continue
        try:
            fx, fy = float(x), float(y)
        except ValueError:
            return False
        if not (abs(fx - fy) <= rel * max(1.0, abs(fx), abs(fy))):
            return False
    return True


def _key(element: etree._Element) -> tuple[str, str]:
    return element.tag, element.get("name") or element.get("reference") or element.get("link") or ""


def _compare(a: etree._Element, b: etree._Element, where: str, rel: float, out: list[str]) -> None:
    if a.tag != b.tag:
        out.append(f"{where}: <{a.tag}> vs <{b.tag}>")
        return
    if set(a.attrib) != set(b.attrib):
        out.append(f"{where}: attributes {sorted(a.attrib)} vs {sorted(b.attrib)}")
    for name in set(a.attrib) & set(b.attrib):
        if not _numbers_equal(a.get(name), b.get(name), rel):
            out.append(f"{where}@{name}: {a.get(name)!r} vs {b.get(name)!r}")
    text_a, text_b = (a.text or "").strip(), (b.text or "").strip()
    if not _numbers_equal(text_a, text_b, rel):
        out.append(f"{where}: text {text_a!r} vs {text_b!r}")
    children_a = sorted((c for c in a if isinstance(c.tag, str)), key=_key)
    children_b = sorted((c for c in b if isinstance(c.tag, str)), key=_key)
    if [_key(c) for c in children_a] != [_key(c) for c in children_b]:
        out.append(f"{where}: children {[_key(c) for c in children_a]} vs {[_key(c) for c in children_b]}")
        return
    for child_a, child_b in zip(children_a, children_b, strict=True):
        _compare(child_a, child_b, f"{where}/{child_a.tag}[{_key(child_a)[1]}]", rel, out)


def urdf_differences(a: str, b: str, *, rel: float = 1e-12) -> list[str]:
    """Where two URDF texts describe different robots: element sets, names and numbers (to ``rel``); attribute
    order, element order, whitespace and comments are ignored. An empty list means the same robot."""
    out: list[str] = []
    _compare(parse_xml(a, "<first>"), parse_xml(b, "<second>"), "robot", rel, out)
    return out


@collector_paused()
def emit_scene_urdf(scene: Scene) -> str:
    """The URDF of a scene made only of our robots (third-party macros need xacro), default arguments."""
    root = etree.Element("robot", name=scene.name)
    for palette_robot in scene.robots:  # each robot's palette once, however many instances
        for element in material_elements(palette_robot):
            root.append(element)
    root.append(etree.Element("link", name=scene.world))
    control = "mock" if any(r.ros2_control is not None for r in scene.robots) else "none"
    copies = _Copies()
    for instance in scene.instances:
        robot = instance.robot
        if robot is None:
            raise ValueError(f"instance {instance.name} is a third-party macro: only xacro can expand it")
        mount = etree.SubElement(root, "joint", name=instance.prefix + robot.mount_joint_name, type="fixed")
        _sub(mount, "parent", link=instance.parent)
        _sub(mount, "child", link=instance.prefix + robot.root)
        _origin(mount, instance.origin)
        for element in robot_elements(robot, prefix=instance.prefix, ros2_control=control, copies=copies):
            root.append(element)
    etree.indent(root, space="  ")
    return '<?xml version="1.0" ?>\n' + etree.tostring(root, encoding="unicode") + "\n"
