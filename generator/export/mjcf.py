"""``gen-robot export --mjcf``: a MuJoCo model (MJCF) written from the robot's URDF, not through MuJoCo's URDF compiler.

What it keeps that MuJoCo's URDF import loses (docs/export.md has the whole mapping):

- every link is a body with the link's name and frame (``fusestatic="false"``: tool frames do not vanish), and a link
  without mass also a site of that name at its origin (where a tool or sensor frame is looked for);
- the inertial exactly as written (``fullinertia`` in the inertial origin's frame, ``inertiafromgeom="false"``);
- visuals (group 2, no contact) and collisions (group 3) with their colours; meshes copied into ``meshes/`` next to
  the model, those MuJoCo cannot read (COLLADA, PLY, glTF, OFF, text STL, STL of more than 200,000 triangles)
  converted by trimesh (to binary STL, or to OBJ beyond 200,000 triangles); a visual mesh that cannot be found or
  read is left out with a note (a collision mesh is an error: the robot would not touch what it touches), and so is a
  flat mesh, visual or collision (MuJoCo cannot make its convex hull: it has no volume to collide with);
- mimic joints as joint equality constraints (q = offset + multiplier q_leader);
- actuators from the ``<ros2_control>`` block's command interfaces (:mod:`xacrokit.export.mjcf_actuators`);
- the parent and child of every joint excluded from colliding with each other, and so are two bodies with collision
  geometry joined through bodies without any (a tool or mounting frame between them), and a body and its
  grandparent where a zero-length link joins them at one point (a spherical wrist);
- Gazebo's ``mu1`` of a link as its collision geoms' sliding friction, with priority over what they touch;
- a free joint on each robot's root (:func:`free_bodies`: the root link, or each robot a root called ``world`` holds
  by a fixed joint; ``base="free"``, or ``auto`` for a robot with a wheel, a continuous joint whose child has a
  cylinder collision), standing on the ground, z = 0 (:mod:`.mjcf_ground`), and a floor there with ``floor=True``;
- position servos that carry the weight of what they alone hold (MuJoCo's ``gravcomp`` through the actuators,
  :func:`~xacrokit.export.mjcf_actuators.compensate_gravity`);
- every compiler and option setting explicit: radians, 9.80665 m/s^2, a 2 ms step, the implicitfast integrator.

A moving link without mass (MuJoCo refuses "moving bodies" without mass and inertia) gets ``MASSLESS`` (1e-12 kg,
1e-14 kg m^2 about each axis, at its origin): its effect on the mass matrix is ~1e-12 N m s^2, named in the model's
header comment.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from lxml import etree

from ..errors import XacrokitError
from ..model import Robot
from ..reader.kinematic_model import require_placeable, unit_axis
from ..reader.mesh_copies import MeshRead
from ..reader.named_poses import named_poses, spec_poses
from ..reader.read_robot import ReadRobot, read_robot
from ..reader.robot_input import RobotInput
from ..reader.robot_source import urdf_floats as _floats
from ..shared.input_files import CopiedFile, copied_pieces
from ..shared.kinematic_tree import Tree
from ..shared.transforms import matrix_quaternion, rpy_matrix, rpy_quaternion
from ..shared.units import MAX_MOMENT, STANDARD_GRAVITY, bound_problem
from ..shared.urdf_view import Joint, Link, Origin, UrdfView
from ..write.atomic import is_staged
from ..write.outputs import OutputFile, output_file, write_outputs
from .mjcf_actuators import actuators, commanded, compensate_gravity, gains, mimics, num
from .mjcf_ground import Ground
from .mjcf_keyframes import keyframes
from .mjcf_meshes import FlatMesh, Meshes, export_reader

MJ_MINVAL = 1e-15  # MuJoCo's mjMINVAL: the least mass and moment a moving body may have
MASSLESS = (1e-12, 1e-14)  # (kg, kg m^2): what a moving link without mass gets, MuJoCo needing more than 1e-15
GRAVITY = STANDARD_GRAVITY


@dataclass
class Export:
    """The model's XML and the mesh files it names (NAME in meshes/ -> bytes, or the robot's file, streamed when
    written), and what the writer had to say."""

    xml: str
    meshes: dict[str, bytes | CopiedFile] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    repairs: dict[str, float] = field(default_factory=dict)  # link -> |change| (2-norm, kg m^2) of its inertia
    massless: list[str] = field(default_factory=list)  # moving links given MASSLESS


def nums(values: Any) -> str:
    return " ".join(num(v) for v in values)


def _origin(origin: Origin | None, where: str) -> tuple[list[float], list[float]]:
    if origin is None:
        return [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
    return _floats(origin.xyz, 3, where=f"{where} origin xyz"), _floats(origin.rpy, 3, where=f"{where} origin rpy")


def _place(node: Any, origin: Origin | None, where: str) -> None:
    """Set ``pos`` and ``quat`` of an MJCF element from a URDF <origin> (nothing for the identity)."""
    xyz, rpy = _origin(origin, where)
    if any(xyz):
        node.set("pos", nums(xyz))
    if any(rpy):
        x, y, z, w = rpy_quaternion(rpy)
        node.set("quat", nums((w, x, y, z)))  # (MuJoCo's order)


@dataclass(frozen=True)
class _Tree:
    """The URDF's links by name, its joints (those with a parent and a child), each link's child joints, the root."""

    links: dict[str, Link]
    joints: list[Joint]
    children: dict[str, list[Joint]]
    root: str


def _tree(view: UrdfView) -> _Tree:
    """The robot as one tree (MuJoCo's bodies nest), or XacrokitError saying why it is not one (a link named world
    that is not the root is one too: MuJoCo's world body has that name)."""
    links = {link.name: link for link in view.links}
    joints = [j for j in view.joints if j.parent is not None and j.child is not None]
    by_child: dict[str, Joint] = {}
    children: dict[str, list[Joint]] = {}
    for joint in joints:
        child, parent = joint.child or "", joint.parent or ""
        if child in by_child:
            raise XacrokitError(f"link {child!r} is the child of two joints: not a tree, MuJoCo needs one")
        if child not in links or parent not in links:
            raise XacrokitError(f"joint {joint.name!r} names a link that is not in the robot")
        by_child[child] = joint
        children.setdefault(parent, []).append(joint)
    roots = [name for name in links if name not in by_child]
    if not links:
        raise XacrokitError("the robot has no link (a file of xacro macros expanded without a call?)")
    if not roots:
        raise XacrokitError("every link is the child of a joint: the joints make a loop, MuJoCo needs a tree")
    if len(roots) != 1:
        raise XacrokitError(f"the robot has {len(roots)} root links ({', '.join(roots[:5])}): MuJoCo needs one tree")
    if "world" in by_child:
        raise XacrokitError(
            f"link 'world' hangs from joint {by_child['world'].name!r}: MuJoCo's world body is called world and is "
            "the root; rename the link"
        )
    tree = _Tree(links, joints, children, roots[0])
    _require_depth(tree)
    return tree


MAX_DEPTH = 490  # links in a chain from the root: MuJoCo's XML reader (tinyxml2) takes 496 nested bodies


def _require_depth(tree: _Tree) -> None:
    """Refuse a tree MuJoCo's XML reader cannot take (deeper than MAX_DEPTH), or links a walk from the root never
    reaches (they hang in a loop of joints)."""
    walk: Tree[Joint] = Tree()
    for joint in tree.joints:
        walk.add(joint.parent or "", joint.child or "", joint)
    depth = walk.depths([tree.root])
    deepest = 1 + max(depth.values())
    unreached = [name for name in tree.links if name not in depth]
    if unreached:
        said = ", ".join(map(repr, unreached[:5]))
        raise XacrokitError(f"links {said} hang in a loop of joints, not from the root: MuJoCo needs a tree")
    if deepest > MAX_DEPTH:
        raise XacrokitError(
            f"the robot's tree is {deepest} links deep: MuJoCo's XML reader (tinyxml2) refuses elements nested about "
            f"500 deep, so the export takes at most {MAX_DEPTH} links from the root to a leaf"
        )


def _skeleton(name: str, floor: bool) -> tuple[Any, Any, Any]:
    """The ``<mujoco>`` element with every compiler and option setting explicit, the visual and collision classes,
    and its (empty) asset and worldbody: (model, asset, world)."""

    model = etree.Element("mujoco", model=name)
    etree.SubElement(
        model,
        "compiler",
        angle="radian",
        autolimits="true",
        inertiafromgeom="false",
        fusestatic="false",
        discardvisual="false",
        balanceinertia="false",
        boundmass="0",
        boundinertia="0",
        meshdir="meshes",
    )
    etree.SubElement(model, "option", gravity=f"0 0 {num(-GRAVITY)}", timestep="0.002", integrator="implicitfast")
    defaults = etree.SubElement(model, "default")
    visual = etree.SubElement(defaults, "default", {"class": "visual"})
    etree.SubElement(visual, "geom", contype="0", conaffinity="0", group="2")
    collision = etree.SubElement(defaults, "default", {"class": "collision"})
    etree.SubElement(collision, "geom", group="3")
    asset = etree.SubElement(model, "asset")
    world = etree.SubElement(model, "worldbody")
    etree.SubElement(world, "light", pos="0 0 5", dir="0 0 -1", directional="true")
    if floor:
        etree.SubElement(world, "geom", name="floor", type="plane", size="0 0 1", rgba="0.85 0.85 0.85 1")
    return model, asset, world


@dataclass
class _Bodies:
    """Writes the bodies of the tree, each inside its parent's (see :func:`mjcf`)."""

    tree: _Tree
    free: Mapping[str, str]  # a body on a free joint -> the joint's name
    taken: set[str]  # the joint names given so far (the URDF's and the free joints')
    colours: dict[str, str]
    friction: dict[str, float]
    meshes: Meshes
    export: Export

    def body(self, name: str, parent: Any, joint: Joint | None) -> None:
        link = self.tree.links[name]
        if joint is None and name == "world":
            body = parent  # (a root link called world is MuJoCo's world body)
        else:
            body = etree.SubElement(parent, "body", name=name)
            if joint is not None:
                _place(body, joint.origin, f"joint {joint.name!r}")
        if name in self.free:  # (a root, or a robot hung from world by a fixed joint: placed where that puts it)
            etree.SubElement(body, "freejoint", name=self.free[name])
        moving = name in self.free or (joint is not None and _add_joint(body, joint, self.taken))
        if body is not parent:
            _inertial(body, link, moving, self.export.massless, self.export.repairs)
        _geoms(body, link, self.colours, self.friction.get(name), self.meshes)
        if link.inertial is None and body is not parent:
            etree.SubElement(body, "site", name=name)
        for child in self.tree.children.get(name, []):
            self.body(child.child or "", body, child)


def mjcf(
    robot: ReadRobot,
    read: Callable[[str], MeshRead],
    *,
    base: str = "auto",
    floor: bool = False,
    poses: Mapping[str, Mapping[str, float]] | None = None,
    armature: Mapping[str, float] | None = None,
) -> Export:
    """The MJCF of a read ``robot``; ``read(filename)`` reads a mesh (:func:`~xacrokit.reader.mesh_copies.mesh_reader`:
    safely, below the robot's folder); ``base``: auto, fixed or free; ``poses``: named poses (joint -> value), each a
    keyframe, ``home`` first (else where the ros2_control blocks start the robot); ``armature``: joint -> reflected
    rotor inertia, a spec's (a URDF cannot hold it; none by default).

    Raises:
        XacrokitError: a URDF MuJoCo cannot take (not a tree, a mesh that cannot be found or read, bad numbers).
    """

    view = robot.view
    try:
        require_placeable(view)  # (the same values refused in the same words as pose, size and render)
    except XacrokitError as exc:
        raise XacrokitError(f"MuJoCo cannot take the robot: {exc}") from None
    tree = _tree(view)
    free = free_bodies(tree, base)
    export = Export(xml="")
    meshes = Meshes(read, export.meshes, export.notes)
    meshes.keep_points = bool(free) or any(j.type == "floating" for j in tree.joints)
    model, asset, world = _skeleton(view.name if view.name is not None else "robot", floor)
    taken = {j.name for j in tree.joints} | set(free.values())
    _Bodies(tree, free, taken, view.colours(), _frictions(view), meshes, export).body(tree.root, world, None)
    for mesh in meshes.assets:
        asset.append(mesh)
    _constraints(model, robot, tree, tree.root in free, export)
    reflected = armature or {}
    for joint in model.find("worldbody").iter("joint"):
        if reflected.get(joint.get("name"), 0.0) > 0:
            joint.set("armature", num(reflected[joint.get("name")]))
    standing = Ground(meshes.points, frozenset(free) & {tree.root})
    model.append(keyframes(model, named_poses(poses or {}, view), tree.joints, standing))
    standing.stand(world)
    for element in (asset, model.find("contact")):
        if element is not None and len(element) == 0:
            model.remove(element)
    _header(model, export)
    return export


def _constraints(model: Any, robot: ReadRobot, tree: _Tree, free: bool, export: Export) -> None:
    """Contact exclusions (every joint's parent and child), mimic equalities and actuators."""

    contact = etree.SubElement(model, "contact")
    for parent, child in _adjacent(tree):
        if parent != "world" or tree.root != "world":
            etree.SubElement(contact, "exclude", body1=parent, body2=child)
    equality = mimics(tree.joints, export.notes)
    if len(equality):
        model.append(equality)
    view = robot.view
    driven = list(commanded(view))
    inertia = gains(robot.free_floating if free else robot.kinematics.model, driven) if driven else {}
    acts = actuators(view, {j.name: j for j in tree.joints}, inertia, export.notes)
    if len(acts):
        model.append(acts)
        compensate_gravity(model.find("worldbody"), acts, model.find("equality"))


def free_bodies(tree: _Tree, base: str) -> dict[str, str]:
    """The bodies on a free joint, each with its joint's name (``base``: auto, fixed or free; see :func:`mjcf`): the
    root link, or when the root is ``world`` (a scene's, or a URDF's that fixes its robot to the world) each robot
    hung from it by a fixed joint, placed where that joint puts it; under ``auto`` only those with a wheel."""
    if base == "fixed":
        return {}
    if tree.root != "world":
        tops = [tree.root]
    else:
        tops = [j.child or "" for j in tree.children.get("world", []) if j.type == "fixed"]
    if base == "auto":
        tops = [name for name in tops if _has_wheel(_below(tree, name), tree.links)]
    taken = {j.name for j in tree.joints}
    return {name: fresh(f"{name}_free", taken) for name in tops}


def fresh(name: str, taken: set[str]) -> str:
    """``name``, or with underscores added until no joint has it (MuJoCo needs each joint's name once: a URDF joint
    may already be called what the export calls the one it adds); then taken."""
    while name in taken:
        name += "_"
    taken.add(name)
    return name


def _below(tree: _Tree, name: str) -> list[Joint]:
    """The joints of the subtree below link ``name``."""
    found, stack = [], [name]
    while stack:
        for joint in tree.children.get(stack.pop(), []):
            found.append(joint)
            stack.append(joint.child or "")
    return found


def _adjacent(tree: _Tree) -> list[tuple[str, str]]:
    """The body pairs that must not collide, as MoveIt's setup assistant disables its "adjacent" pairs: every joint's
    parent and child; a body with collision geometry and the nearest body above it that has some, past bodies without
    any (a UR's geometry-less `base` frame sits between base_link and shoulder_link, whose shapes overlap where they
    are joined); and a body and the one above its parent when its joint does not move it off its parent's origin
    (a zero-length link, as a spherical wrist's: all three meet at one joint, their shapes round it)."""
    joint_of = {joint.child or "": joint for joint in tree.joints}
    parent_of = {child: joint.parent or "" for child, joint in joint_of.items()}
    pairs = [(joint.parent or "", joint.child or "") for joint in tree.joints]
    colliding = {name for name, link in tree.links.items() if link.collisions}
    for name in (name for name in tree.links if name in colliding):  # (the links' order: a set's varies by run)
        above = parent_of.get(name)
        if above is None or above in colliding:
            continue  # (the root, or already its joint's pair)
        while above is not None and above not in colliding:
            above = parent_of.get(above)
        if above is not None:
            pairs.append((above, name))
    for name, joint in joint_of.items():
        where = joint.origin.xyz if joint.origin is not None else None
        offset = _floats(where, 3, where=f"joint {joint.name!r} origin xyz")
        grandparent = parent_of.get(parent_of[name])
        if grandparent is not None and max(map(abs, offset)) < 1e-9:
            pairs.append((grandparent, name))
    return list(dict.fromkeys(pairs))


def spec_armature(robot: Robot | None) -> dict[str, float]:
    """Joint -> armature (kg m^2, or kg sliding) of a spec's joints and arm rows (``robot``: its model; None for a URDF
    or xacro document, which has no place for it: none)."""
    if robot is None:
        return {}
    dynamics = [(j.name, j.dynamics) for j in robot.joints]
    dynamics += [(row.name, row.dynamics) for arm in robot.arms for row in arm.rows]
    return {name: d.armature for name, d in dynamics if d is not None and d.armature > 0}


def _header(model: Any, export: Export) -> None:
    """The notes on repaired inertias, the model's header comment, and the XML text."""

    for name, change in export.repairs.items():
        export.notes.append(
            f"link {name!r}: its inertia is not a rigid body's (gen-robot check says why); raised by "
            f"{change:.3g} kg m^2 (2-norm) for MuJoCo"
        )
    header = "Generated by xacrokit from the robot's URDF (gen-robot export, MJCF); see docs/export.md."
    if export.massless:
        header += (
            f" Moving links without mass given {MASSLESS[0]} kg, {MASSLESS[1]} kg m^2: {', '.join(export.massless)}."
        )
    model.insert(0, etree.Comment(" " + header.replace("--", "- -") + " "))
    export.xml = etree.tostring(model, pretty_print=True, encoding="unicode")


def _has_wheel(joints: list[Joint], links: Mapping[str, Link]) -> bool:
    return any(
        j.type == "continuous"
        and any(c.shape is not None and c.shape.kind == "cylinder" for c in links[j.child or ""].collisions)
        for j in joints
    )


def _frictions(view: UrdfView) -> dict[str, float]:
    found = {}
    for gazebo in view.gazebo:
        mu = gazebo.element.find("mu1")
        if gazebo.reference and mu is not None and mu.text:
            try:
                found[gazebo.reference] = float(mu.text)
            except ValueError:
                continue
    return found


def _add_joint(body: Any, joint: Joint, taken: set[str]) -> bool:
    """The MJCF joint(s) of a URDF joint inside its child's body; False for a fixed joint (the body is welded).
    ``taken``: the joint names given (a planar or floating joint's parts are named apart from them)."""

    kind, name = joint.type, joint.name
    if kind == "fixed":
        return False
    said = f"joint {name!r}"
    axis = unit_axis(joint)
    extra = {}
    for urdf_key, mjcf_key in (("damping", "damping"), ("friction", "frictionloss")):
        given = joint.dynamics.get(urdf_key) if joint.dynamics is not None else None
        if given:
            extra[mjcf_key] = num(_floats(given, 1, where=f"{said} dynamics {urdf_key}")[0])
    if kind == "floating":
        _floating(body, name, taken)
        return True
    if kind == "planar":  # (x along u, y along v, theta about the normal: as gen-robot view and pinocchio for z)
        u = np.array([0.0, 1.0, 0.0]) if abs(axis[0]) > 0.9 else np.array([1.0, 0.0, 0.0])
        u = u - (u @ axis) * axis
        u /= np.linalg.norm(u)
        v = np.cross(axis, u)
        etree.SubElement(body, "joint", name=fresh(f"{name}_x", taken), type="slide", axis=nums(u), **extra)
        etree.SubElement(body, "joint", name=fresh(f"{name}_y", taken), type="slide", axis=nums(v), **extra)
        etree.SubElement(body, "joint", name=fresh(f"{name}_theta", taken), type="hinge", axis=nums(axis), **extra)
        return True
    if kind not in ("revolute", "continuous", "prismatic"):
        raise XacrokitError(f"joint {name!r}: type {kind!r} is not a URDF joint type")
    element = etree.SubElement(
        body, "joint", name=name, type="slide" if kind == "prismatic" else "hinge", axis=nums(axis), **extra
    )
    limit = joint.limit
    if kind != "continuous" and limit is not None and limit.get("lower") is not None and limit.get("upper") is not None:
        lower = _floats(limit["lower"], 1, where=f"{said} limit lower")[0]
        upper = _floats(limit["upper"], 1, where=f"{said} limit upper")[0]
        if lower < upper:
            element.set("range", f"{num(lower)} {num(upper)}")
    return True


def _floating(body: Any, name: str, taken: set[str]) -> None:
    """A floating joint: a free joint on a body of the world; deeper, where MuJoCo takes no free joint, the same six
    degrees of freedom as three slides along the parent's axes and a ball joint."""
    if body.getparent().tag == "worldbody":
        etree.SubElement(body, "joint", name=name, type="free")
        return
    for letter, direction in zip("xyz", ("1 0 0", "0 1 0", "0 0 1"), strict=True):
        etree.SubElement(body, "joint", name=fresh(f"{name}_{letter}", taken), type="slide", axis=direction)
    etree.SubElement(body, "joint", name=fresh(f"{name}_ball", taken), type="ball")


def _inertial(body: Any, link: Link, moving: bool, massless: list[str], repairs: dict[str, float]) -> None:
    inertial = link.inertial
    where = f"link {link.name!r}: inertial"
    mass = _floats(inertial.mass or "0", 1, where=where)[0] if inertial is not None else 0.0
    tensor = inertial.inertia if inertial is not None else None
    keys = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")
    i = {k: _floats(tensor.get(k, "0"), 1, where=where)[0] if tensor is not None else 0.0 for k in keys}
    matrix = np.array([[i["ixx"], i["ixy"], i["ixz"]], [i["ixy"], i["iyy"], i["iyz"]], [i["ixz"], i["iyz"], i["izz"]]])
    _require_bounded(link.name, mass, matrix)
    if not mass > MJ_MINVAL and moving:  # (a mass of 1e-320 is none to MuJoCo either)
        massless.append(link.name)
        mass = MASSLESS[0]
        if not matrix.any():
            value = num(MASSLESS[1])
            etree.SubElement(body, "inertial", pos="0 0 0", mass=num(mass), diaginertia=f"{value} {value} {value}")
            return
    if not mass > 0 and not matrix.any():
        return
    element = etree.SubElement(body, "inertial", mass=num(max(mass, 0.0)))  # (no mass, moments: pinocchio keeps them)
    xyz, rpy = _origin(inertial.origin if inertial is not None else None, where)
    element.set("pos", nums(xyz))
    if any(rpy):  # (MJCF takes fullinertia in the body's axes only: R I R^T, R the inertial origin's rotation)
        rotation = rpy_matrix(*rpy)
        matrix = rotation @ matrix @ rotation.T
    fixed = physical(matrix)
    if fixed is None:
        element.set("fullinertia", nums(matrix[[0, 1, 2, 0, 0, 1], [0, 1, 2, 1, 2, 2]]))
        return
    moments, axes = fixed  # (principal moments and axes: MuJoCo's own eigensolver stumbles on near-equal tiny ones)
    repairs[link.name] = float(np.linalg.norm(axes @ np.diag(moments) @ axes.T - matrix, 2))
    x, y, z, w = matrix_quaternion(axes)
    element.set("quat", nums((w, x, y, z)))
    element.set("diaginertia", nums(moments))


def _require_bounded(link: str, mass: float, matrix: np.ndarray) -> None:
    """Refuse a mass or tensor beyond what xacrokit takes (1e6 kg; 1e14 kg m^2, that mass 1e4 m away): MuJoCo's
    and numpy's arithmetic on 1e308 overflows (an eigensolver that does not converge)."""
    beyond = bound_problem("mass", mass)
    if beyond is None and np.abs(matrix).max() > MAX_MOMENT:
        beyond = f"a moment of {np.abs(matrix).max():g} kg m^2 is beyond what xacrokit takes (at most {MAX_MOMENT:g})"
    if beyond is not None:
        raise XacrokitError(f"link {link!r}: inertial: {beyond}")


def physical(matrix: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """The principal moments and axes (a rotation) of the nearest inertia MuJoCo takes when ``matrix`` is not one
    (None when it is): moments below ``MASSLESS[1]`` raised to it, and when the two smaller ones sum to less than the
    largest (no rigid body has such moments; pinocchio reads them, MuJoCo refuses) both raised by half the shortfall
    and a margin of 1e-10 of the largest, so that MuJoCo's own eigensolver agrees."""
    moments, axes = np.linalg.eigh((matrix + matrix.T) / 2.0)
    raised = np.maximum(moments, MASSLESS[1])
    shortfall = raised[2] * (1.0 + 1e-10) - raised[0] - raised[1]
    if shortfall > 0 and raised[0] + raised[1] < raised[2]:
        raised[:2] += shortfall / 2.0
    if np.array_equal(raised, moments):
        return None
    if np.linalg.det(axes) < 0:
        axes[:, 0] = -axes[:, 0]
    return raised, axes


def _geoms(body: Any, link: Link, colours: Mapping[str, str], mu: float | None, meshes: Meshes) -> None:
    for kind, parts in (("visual", link.visuals), ("collision", link.collisions)):
        said = f"link {link.name!r} {kind}"
        for part in parts:
            shape = part.shape
            if shape is None:
                continue
            geom = etree.Element("geom", {"class": kind})
            if shape.kind == "box":
                geom.set("type", "box")
                geom.set("size", nums(v / 2.0 for v in _floats(shape.get("size"), 3, where=f"{said} box size")))
            elif shape.kind == "cylinder":
                radius = _floats(shape.get("radius"), 1, where=f"{said} cylinder radius")[0]
                length = _floats(shape.get("length"), 1, where=f"{said} cylinder length")[0]
                geom.set("type", "cylinder")
                geom.set("size", f"{num(radius)} {num(length / 2.0)}")
            elif shape.kind == "sphere":
                geom.set("type", "sphere")
                geom.set("size", num(_floats(shape.get("radius"), 1, where=f"{said} sphere radius")[0]))
            elif shape.kind == "mesh":
                geom.set("type", "mesh")
                try:
                    geom.set("mesh", meshes.name(shape.get("filename") or "", shape.get("scale")))
                except XacrokitError as exc:
                    if kind == "collision" and not isinstance(exc, FlatMesh):
                        raise XacrokitError(f"link {link.name!r}: collision {exc}") from None
                    meshes.notes.append(f"link {link.name!r}: {kind} left out: {exc}")
                    continue
            else:
                continue
            _place(geom, part.origin, said)
            if kind == "visual":
                material = part.material
                rgba = None
                if material is not None:
                    rgba = material.rgba if material.rgba is not None else colours.get(material.name or "")
                if rgba:
                    colour = np.clip(_floats(rgba, 4, where=f"{said} colour"), 0.0, 1.0)  # (as renderers do)
                    geom.set("rgba", nums(colour))
            elif mu is not None:
                geom.set("friction", f"{num(mu)} 0.005 0.0001")
                geom.set("priority", "1")  # (its friction, not the larger of the two, decides the contact)
            body.append(geom)


def write_export(export: Export, output: str | os.PathLike[str], *, force: bool = False) -> list[Path]:
    """Write the model and its meshes (meshes/ next to it) through the write stage
    (:func:`~xacrokit.write.outputs.write_outputs`: atomic; never through a link or onto a device; a file there that
    gen-robot did not write is kept and nothing is written, unless ``force``); the paths written."""

    target = Path(output)
    if not export.meshes:
        output_file(target, export.xml, force=force)
        return [target]
    files = [OutputFile(target.name, export.xml)]
    files += [OutputFile(f"meshes/{name}", data) for name, data in export.meshes.items()]
    write_outputs(target.parent, files, force=force)
    return [target.parent / item.relative for item in files]


def export_mjcf(
    robot: ReadRobot | RobotInput | str | os.PathLike[str], *, base: str = "auto", floor: bool = False
) -> Export:
    """The MJCF of a read robot (URDF, xacro document, spec or scene; or what to read; see :func:`mjcf`).

    Raises:
        XacrokitError: unreadable input, a mesh that cannot be found or read, a robot MuJoCo cannot take.
        SpecErrors: an invalid spec (located).
    """

    if base not in ("auto", "fixed", "free"):
        raise XacrokitError(f"base {base!r}: the root's joint is one of auto, fixed or free")
    read_in = read_robot(robot)
    with read_in.mesh_packages() as packages:
        read = export_reader(read_in.path, packages)
        spec = read_in.spec
        export = mjcf(read_in, read, base=base, floor=floor, poses=spec_poses(spec), armature=spec_armature(spec))
        for name, mesh in export.meshes.items():  # (a spec's meshes, staged for the block: read while they last)
            if isinstance(mesh, CopiedFile) and is_staged(mesh.root):
                export.meshes[name] = b"".join(copied_pieces(mesh))
        return export
