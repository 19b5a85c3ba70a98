"""The resolve stage: a validated spec becomes the frozen :class:`~xacrokit.model.Robot` (SI, defaults filled in).

No errors of its own (validation already guarantees what this relies on) and no output; its only input besides the
spec is the mesh files a spec names by a relative path, read to be carried in the model (``Robot.files``) into the
package's meshes/ (validation saw them there).
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .model import (
    AXIAL,
    DEFAULT_ROW_RADIUS,
    DEFAULT_TOOL,
    HOME_POSE,
    MOVING,
    Arm,
    Box,
    Calibration,
    Collision,
    ControlledJoint,
    Cylinder,
    DHBody,
    DHRow,
    Dynamics,
    Inertia,
    InertiaKind,
    Interfaces,
    Joint,
    Limit,
    Link,
    Mesh,
    Mimic,
    Origin,
    PackageFile,
    Planning,
    Robot,
    SafetyController,
    Shape,
    Sphere,
    Surface,
    Vec3,
    Visual,
    Wheel,
    arm_base_name,
    attach_joint_name,
)
from .shared.gc_pause import collector_paused
from .shared.joint_types import mimic_positions, rest_position
from .shared.mesh_solids import MESH_FOLDER, is_relative, mesh_hull, mesh_path, package_mesh_path, tube_obj
from .shared.sim_sensors import CAMERAS, OPTICAL_RPY, Sensor, resolve_sensor
from .shared.solid_inertia import (
    box_moments,
    capsule_moments,
    combine,
    cylinder_moments,
    sphere_moment,
    tensor,
    tube_moments,
    wheel_moments,
)
from .shared.transforms import dh_body_end, dh_body_pose, rpy_matrix, screw_pose
from .validate import Spec

if TYPE_CHECKING:
    import numpy as np

DEFAULT_INTERFACES = Interfaces(command=("position",), state=("position", "velocity"))
WHEEL_INTERFACES = Interfaces(command=("velocity",), state=("position", "velocity"))


def _vec3(values: Any, default: Vec3 = (0.0, 0.0, 0.0)) -> Vec3:
    if values is None:
        return default
    x, y, z = (float(v) for v in values)
    return (x, y, z)


def origin(data: dict[str, Any] | None) -> Origin:
    data = data or {}
    return Origin(xyz=_vec3(data.get("xyz")), rpy=_vec3(data.get("rpy")))


class _Package:
    """What resolving a robot adds to its package besides the model: the files its shapes need (copied meshes, made
    tube meshes), by path in the package, and the package's name for their ``package://`` URIs."""

    def __init__(self, robot: str, spec_file: str) -> None:
        self.name = f"{robot}_description"
        self.spec_file = spec_file
        self.spec_folder = Path(spec_file).parent
        self.files: dict[str, bytes | str] = {}


def shape(data: dict[str, Any], package: _Package) -> Shape:
    """The URDF geometry of a spec shape that has one: a box, cylinder, sphere or mesh (a relative mesh path becomes
    a copy in the package's meshes/), or, for a tube, a mesh made into the package (named by its sizes: tubes of the
    same sizes share one file)."""
    if "box" in data:
        return Box(size=_vec3(data["box"]["size"]))
    if "cylinder" in data:
        return Cylinder(radius=float(data["cylinder"]["radius"]), length=float(data["cylinder"]["length"]))
    if "sphere" in data:
        return Sphere(radius=float(data["sphere"]["radius"]))
    if "tube" in data:
        inner, outer, length = (float(data["tube"][k]) for k in ("inner_radius", "outer_radius", "length"))
        path = f"{MESH_FOLDER}/xacrokit/tube_{inner!r}_{outer!r}_{length!r}.obj"
        package.files[path] = tube_obj(inner, outer, length)
        return Mesh(filename=f"package://{package.name}/{path}")
    mesh = data["mesh"]
    filename = mesh["filename"]
    if is_relative(filename):  # (validate saw the file there)
        path = package_mesh_path(filename)
        package.files[path] = (package.spec_folder / filename).read_bytes()
        filename = f"package://{package.name}/{path}"
    return Mesh(filename=filename, scale=_vec3(mesh.get("scale"), (1.0, 1.0, 1.0)))


def pieces(data: dict[str, Any], where: Origin, package: _Package) -> list[tuple[Shape, Origin]]:
    """The URDF geometries that draw a spec shape at ``where``: one, or for a capsule its cylinder and the two spheres
    at its ends (URDF has no capsule; every consumer reads these, as visual and as collision)."""
    if "capsule" not in data:
        return [(shape(data, package), where)]
    radius, length = float(data["capsule"]["radius"]), float(data["capsule"]["length"])
    half = rpy_matrix(*where.rpy)[:, 2] * (length / 2.0)  # (the capsule's z axis in the link frame)
    x, y, z = where.xyz
    ends = [Origin(xyz=(x + s * half[0] + 0.0, y + s * half[1] + 0.0, z + s * half[2] + 0.0)) for s in (1.0, -1.0)]
    return [(Cylinder(radius, length), where), *((Sphere(radius), end) for end in ends)]


def shape_inertia(body: dict[str, Any], mass: float, frame: Origin) -> Inertia:
    """The closed-form tensor of a spec's solid shape (box, cylinder, sphere, capsule, tube) about its centre, in the
    shape's own axes."""
    kind: InertiaKind
    if "box" in body:
        xx, yy, zz = box_moments(mass, *_vec3(body["box"]["size"]))
        kind = "box"
    elif "cylinder" in body:
        zz, xx = cylinder_moments(mass, float(body["cylinder"]["radius"]), float(body["cylinder"]["length"]))
        yy, kind = xx, "cylinder"
    elif "sphere" in body:
        xx = yy = zz = sphere_moment(mass, float(body["sphere"]["radius"]))
        kind = "sphere"
    elif "capsule" in body:
        zz, xx = capsule_moments(mass, float(body["capsule"]["radius"]), float(body["capsule"]["length"]))
        yy, kind = xx, "capsule"
    elif "tube" in body:
        tube = body["tube"]
        zz, xx = tube_moments(mass, float(tube["inner_radius"]), float(tube["outer_radius"]), float(tube["length"]))
        yy, kind = xx, "tube"
    else:  # validation guarantees a mesh comes with a tensor (given, or computed from its surface)
        raise TypeError(f"no closed-form inertia for {body!r}")
    return Inertia(mass=mass, ixx=xx, ixy=0.0, ixz=0.0, iyy=yy, iyz=0.0, izz=zz, origin=frame, kind=kind)


def _link(name: str, data: dict[str, Any], package: _Package) -> Link:
    if "parts" in data:
        return _composite(name, data, package)
    where = origin(data.get("origin"))
    drawn = pieces(data["shape"], where, package) if "shape" in data else []
    material = data.get("material")
    visuals = [Visual(shape=body, origin=at, material=material) for body, at in drawn]
    for more in data.get("visuals", ()):  # (drawn only: no collision, no mass)
        tint = more.get("material", material)  # (null: none)
        visuals += [Visual(shape=b, origin=at, material=tint) for b, at in _placed(more, package)]
    collision_spec = data.get("collision", "same")
    if collision_spec == "same":
        collisions = [Collision(shape=body, origin=at) for body, at in drawn]
    elif collision_spec == "none":
        collisions = []
    elif collision_spec == "hull":  # (validate saw the shape is a mesh whose hull has a volume)
        collisions = [Collision(shape=_hull_of(data["shape"]["mesh"], package), origin=where)]
    else:  # (one shape, or a list of them)
        listed = collision_spec if isinstance(collision_spec, list) else [collision_spec]
        collisions = [Collision(shape=b, origin=at) for one in listed for b, at in _placed(one, package)]
    if "shape" not in data:
        frame = origin(data.get("com") or data.get("origin"))
    else:
        frame = origin(data["com"]) if "com" in data else where
    inertial = _explicit_inertia(data, frame)
    if inertial is None and "mass" in data and "shape" in data:
        inertial = shape_inertia(data["shape"], float(data["mass"]), frame)
    return Link(name=name, visuals=tuple(visuals), collisions=tuple(collisions), inertial=inertial)


def _hull_of(mesh: dict[str, Any], package: _Package) -> Mesh:
    """A mesh's convex hull, made into the package (``collision: hull``), at the mesh's scale."""
    path, data = mesh_hull(mesh_path(mesh["filename"], package.spec_file))
    package.files[path] = data
    return Mesh(filename=f"package://{package.name}/{path}", scale=_vec3(mesh.get("scale"), (1.0, 1.0, 1.0)))


def _placed(geometry: dict[str, Any], package: _Package) -> list[tuple[Shape, Origin]]:
    """A `collision` or `visuals` entry's geometries (a shape at its own origin in the link frame)."""
    return pieces(geometry["shape"], origin(geometry.get("origin")), package)


def _composite(name: str, data: dict[str, Any], package: _Package) -> Link:
    """A link of parts: each part's geometries, and the exact sum of the parts' inertias (physics.combine) about the
    common centre of mass, in the link's axes."""
    import numpy as np  # (heavy: numpy)

    visuals: list[Visual] = []
    collisions: list[Collision] = []
    bodies: list[tuple[float, np.ndarray, np.ndarray, np.ndarray]] = []
    for part in data["parts"]:
        where = origin(part.get("origin"))
        drawn = pieces(part["shape"], where, package)
        material = part.get("material", data.get("material"))
        visuals += [Visual(shape=body, origin=at, material=material) for body, at in drawn]
        if part.get("collision", "same") == "same":
            collisions += [Collision(shape=body, origin=at) for body, at in drawn]
        own = _explicit_inertia(part, where) or shape_inertia(part["shape"], float(part["mass"]), where)
        matrix = tensor(own.ixx, own.ixy, own.ixz, own.iyy, own.iyz, own.izz)
        bodies.append((own.mass, np.array(own.origin.xyz), rpy_matrix(*own.origin.rpy), matrix))
    mass, center, total = combine(bodies)
    inertial = Inertia(
        mass=mass,
        ixx=float(total[0, 0]),
        ixy=float(total[0, 1]) + 0.0,
        ixz=float(total[0, 2]) + 0.0,
        iyy=float(total[1, 1]),
        iyz=float(total[1, 2]) + 0.0,
        izz=float(total[2, 2]),
        origin=Origin(xyz=(float(center[0]) + 0.0, float(center[1]) + 0.0, float(center[2]) + 0.0)),
        kind="parts",
    )
    return Link(name=name, visuals=tuple(visuals), collisions=tuple(collisions), inertial=inertial)


def _explicit_inertia(data: dict[str, Any], default_frame: Origin) -> Inertia | None:
    tensor = data.get("inertia")
    if tensor is None:
        return None
    frame = origin(tensor["origin"]) if "origin" in tensor else default_frame
    return Inertia(
        mass=float(data["mass"]),
        ixx=float(tensor["ixx"]),
        ixy=float(tensor.get("ixy", 0.0)),
        ixz=float(tensor.get("ixz", 0.0)),
        iyy=float(tensor["iyy"]),
        iyz=float(tensor.get("iyz", 0.0)),
        izz=float(tensor["izz"]),
        origin=frame,
        kind=tensor.get("kind", "explicit"),
    )


def _limit(data: dict[str, Any], joint_type: str) -> Limit | None:
    limit = data.get("limit")
    if joint_type not in MOVING or not limit:
        return None
    bounded = joint_type != "continuous"
    return Limit(
        effort=float(limit["effort"]),
        velocity=float(limit["velocity"]),
        lower=float(limit["lower"]) if bounded else None,
        upper=float(limit["upper"]) if bounded else None,
        acceleration=float(limit["acceleration"]) if "acceleration" in limit else None,
    )


def _dynamics(data: dict[str, Any]) -> Dynamics | None:
    dynamics = data.get("dynamics")
    if dynamics is None:
        return None
    return Dynamics(
        damping=float(dynamics.get("damping", 0.0)),
        friction=float(dynamics.get("friction", 0.0)),
        armature=float(dynamics.get("armature", 0.0)),
    )


def _joint(name: str, data: dict[str, Any]) -> Joint:
    kind = data["type"]
    axis = None
    if kind in AXIAL:
        raw_axis = _vec3(data.get("axis"), (1.0, 0.0, 0.0))
        norm = math.hypot(*raw_axis)  # (validate keeps it within 1e-9..1e9: no overflow, no division by zero)
        axis = (raw_axis[0] / norm, raw_axis[1] / norm, raw_axis[2] / norm)
    mimic = data.get("mimic")
    safety = data.get("safety_controller")
    return Joint(
        name=name,
        type=kind,
        parent=data["parent"],
        child=data["child"],
        origin=origin(data.get("origin")),
        axis=axis,
        limit=_limit(data, kind),
        dynamics=_dynamics(data) if kind in MOVING else None,
        mimic=Mimic(
            joint=mimic["joint"], multiplier=float(mimic.get("multiplier", 1.0)), offset=float(mimic.get("offset", 0.0))
        )
        if mimic
        else None,
        safety_controller=SafetyController(
            k_velocity=float(safety["k_velocity"]),
            k_position=_optional_float(safety.get("k_position")),
            soft_lower_limit=_optional_float(safety.get("soft_lower_limit")),
            soft_upper_limit=_optional_float(safety.get("soft_upper_limit")),
        )
        if safety
        else None,
        calibration=Calibration(
            rising=_optional_float(data["calibration"].get("rising")),
            falling=_optional_float(data["calibration"].get("falling")),
        )
        if data.get("calibration")
        else None,
    )


def _optional_float(value: Any) -> float | None:
    return None if value is None else float(value)


def _arm(name: str, data: dict[str, Any]) -> Arm:
    rows = []
    for row in data["joints"]:
        kind = row.get("type", "revolute")
        rows.append(
            DHRow(
                name=row["name"],
                link=row["link"],
                a=float(row["a"]),
                d=float(row["d"]),
                alpha=float(row["alpha"]),
                theta=float(row.get("theta", 0.0)),
                type=kind,
                limit=_limit(row, kind),
                dynamics=_dynamics(row) if kind != "fixed" else None,
                mass=_optional_float(row.get("mass")),
                radius=float(row.get("radius", DEFAULT_ROW_RADIUS)),
                material=row.get("material"),
                inertia=_explicit_inertia(row, Origin()),
            )
        )
    tool = data.get("tool", {})
    convention = data.get("convention", "standard")
    return Arm(
        name=name,
        parent=data["parent"],
        origin=origin(data.get("origin")),
        convention=convention,
        rows=_with_bodies(rows, convention),
        base=arm_base_name(name) if data.get("base", True) else None,
        tool=tool.get("name", DEFAULT_TOOL),
        tool_origin=origin(tool.get("origin")),
        tool_joint=tool.get("joint"),
    )


def _with_bodies(rows: list[DHRow], convention: str) -> tuple[DHRow, ...]:
    """The rows with their bodies: each row with a mass gets the solid from its link frame to the next joint."""
    bodied = []
    for index, row in enumerate(rows):
        following = rows[index + 1] if index + 1 < len(rows) else None
        end = dh_body_end(
            convention, row.a, row.alpha, (following.a, following.alpha, following.d) if following else None
        )
        body = dh_body(row, end) if row.mass is not None else None
        if body is not None and row.inertia is not None:  # (the table's own tensor, given in DH frame i)
            screw = (row.a, row.alpha) if convention == "standard" else (0.0, 0.0)
            xyz, rpy = screw_pose(*screw, row.inertia.origin.xyz, row.inertia.origin.rpy)
            body = dataclasses.replace(body, inertia=dataclasses.replace(row.inertia, origin=Origin(xyz, rpy)))
        bodied.append(dataclasses.replace(row, body=body))
    return tuple(bodied)


def dh_body(row: DHRow, end: tuple[float, float, float]) -> DHBody:
    """A row's body ending at ``end``: a cylinder along the segment, its inertia about its centre in its own axes
    (axial about z); a sphere at the link's origin when the segment is shorter than a micrometre."""
    assert row.mass is not None  # (the caller gives a row with a mass)
    xyz, rpy, length = dh_body_pose(end)
    if length >= 1e-6:
        axial, transverse = cylinder_moments(row.mass, row.radius, length)
        place = Origin(xyz, rpy)
        inertia = Inertia(row.mass, transverse, 0.0, 0.0, transverse, 0.0, axial, place, "cylinder")
        return DHBody(Cylinder(row.radius, length), place, inertia)
    moment = sphere_moment(row.mass, row.radius)
    inertia = Inertia(row.mass, moment, 0.0, 0.0, moment, 0.0, moment, Origin(xyz), "sphere")
    return DHBody(Sphere(row.radius), Origin(xyz, rpy), inertia)


def _wheel(name: str, data: dict[str, Any]) -> Wheel:
    limit, dynamics = data.get("limit", {}), data.get("dynamics", {})
    mass, radius, width, axle = float(data["mass"]), float(data["radius"]), float(data["width"]), data.get("axis", "y")
    xx, yy, zz = wheel_moments(mass, radius, width, axle)
    return Wheel(
        name=name,
        parent=data["parent"],
        origin=origin(data.get("origin")),
        radius=radius,
        width=width,
        mass=mass,
        axis=axle,
        material=data.get("material"),
        effort=float(limit.get("effort", 10.0)),
        velocity=float(limit.get("velocity", 10.0)),
        damping=float(dynamics.get("damping", 0.01)),
        friction=float(dynamics.get("friction", 0.0)),
        mu1=float(data.get("mu1", 1.0)),
        mu2=float(data.get("mu2", 1.0)),
        joint=data.get("joint"),
        inertia=Inertia(mass, xx, 0.0, 0.0, yy, 0.0, zz, Origin(), "cylinder"),
    )


def _frame(name: str, data: dict[str, Any], package: _Package) -> tuple[Link, Joint]:
    body: dict[str, Any] = {k: data[k] for k in ("shape", "mass", "material", "inertia") if k in data}
    joint = Joint(
        name=data.get("joint", attach_joint_name(name)),
        type="fixed",
        parent=data["parent"],
        child=name,
        origin=origin(data.get("origin")),
    )
    return _link(name, body, package), joint


def _optical_joint(sensor: Sensor) -> Joint:
    """The fixed joint of a camera's optical frame on the sensor's frame (REP 103: z forward, x right, y down)."""
    name, parent, child = attach_joint_name(sensor.frame), sensor.link, sensor.frame
    return Joint(name=name, type="fixed", parent=parent, child=child, origin=Origin(rpy=OPTICAL_RPY))


def _controlled(
    data: dict[str, Any], robot_joints: list[tuple[str, Limit | None, bool]], mimics: list[tuple[str, Mimic]]
) -> tuple[ControlledJoint, ...] | None:
    """Every moving, non-mimic joint with its interfaces (per-joint override, else wheel or global default), starting
    at its `home` position; then every mimic joint with state interfaces only (gz_ros2_control holds a mimic joint to
    its leader only when it is listed so: its gripper demo), starting where its leader's start puts it."""
    control = data.get("ros2_control")
    if control is None:
        return None
    default = control.get("interfaces", {})
    overrides = control.get("joints", {})
    home = data.get("poses", {}).get(HOME_POSE, {})
    result = []
    for name, limit, is_wheel in robot_joints:
        base = WHEEL_INTERFACES if is_wheel else DEFAULT_INTERFACES
        if not is_wheel and default:
            base = Interfaces(tuple(default.get("command", base.command)), tuple(default.get("state", base.state)))
        override = overrides.get(name, {})
        chosen = Interfaces(tuple(override.get("command", base.command)), tuple(override.get("state", base.state)))
        rest = rest_position(limit.lower, limit.upper) if limit is not None else 0.0
        start = float(home.get(name, rest))
        result.append(ControlledJoint(name=name, interfaces=chosen, initial_position=start))
    starts = mimic_positions(
        {c.name: c.initial_position for c in result},
        {name: (mimic.joint, mimic.multiplier, mimic.offset) for name, mimic in mimics},
    )
    states = tuple(default.get("state", DEFAULT_INTERFACES.state))
    for name, _ in mimics:
        start = starts.get(name, 0.0)  # (0 only in a cycle, which validation refuses)
        result.append(ControlledJoint(name=name, interfaces=Interfaces((), states), initial_position=start))
    return tuple(result)


@collector_paused()
def resolve(spec: Spec) -> Robot:
    """Build the model of a validated spec."""
    data = spec.data
    package = _Package(data["robot"], spec.raw.file)
    links = [_link(name, link, package) for name, link in data.get("links", {}).items()]
    joints = [_joint(name, joint) for name, joint in data.get("joints", {}).items()]
    sensors = []
    for name, frame in data.get("frames", {}).items():
        link, joint = _frame(name, frame, package)
        links.append(link)
        joints.append(joint)
        if isinstance(frame.get("sensor"), dict):
            sensor = resolve_sensor(name, frame["sensor"])
            sensors.append(sensor)
            if sensor.kind in CAMERAS:  # its optical frame (REP 103), the link its readings are stamped with
                links.append(Link(name=sensor.frame))
                joints.append(_optical_joint(sensor))
    arms = tuple(_arm(name, arm) for name, arm in data.get("arms", {}).items())
    wheels = tuple(_wheel(name, wheel) for name, wheel in data.get("wheels", {}).items())
    moving = [(j.name, j.limit, False) for j in joints if j.type in MOVING and j.mimic is None]
    moving += [(row.name, row.limit, False) for arm in arms for row in arm.rows if row.type in MOVING]
    moving += [(w.joint_name, None, True) for w in wheels]
    surfaces = tuple(
        Surface(link=name, mu1=s.get("mu1"), mu2=s.get("mu2"), kp=s.get("kp"), kd=s.get("kd"))
        for name, s in data.get("gazebo", {}).get("links", {}).items()
    )
    children = {j.child for j in joints} | {w.name for w in wheels}
    for arm in arms:
        children |= set(arm.link_names)
    root = next(link.name for link in links if link.name not in children)
    return Robot(
        name=data["robot"],
        root=root,
        materials=tuple((n, tuple(float(c) for c in rgba)) for n, rgba in data.get("materials", {}).items()),  # type: ignore[misc]
        links=tuple(links),
        joints=tuple(joints),
        arms=arms,
        wheels=wheels,
        ros2_control=_controlled(data, moving, [(j.name, j.mimic) for j in joints if j.type in MOVING and j.mimic]),
        surfaces=surfaces,
        sensors=tuple(sensors),
        extension=spec.extension,
        extension_source=data.get("extension", ""),
        poses=tuple(
            (name, tuple((joint, float(value)) for joint, value in pose.items()))
            for name, pose in data.get("poses", {}).items()
        ),
        files=tuple(PackageFile(path, content) for path, content in sorted(package.files.items())),
        mount_joint=data.get("mount_joint"),
        planning=_planning(data.get("moveit", {})),
        source=spec.raw.file,
    )


def carried_into(robot: Robot, package: str) -> Robot:
    """``robot`` with the files it carries (copied and made meshes) moved into the package ``package``, under
    ``robots/ROBOT_description/``, and the URIs that name them rewritten: a scene package carries its robots' meshes,
    so that it is the one package to build and install."""
    if not robot.files:
        return robot
    folder = f"robots/{robot.package}"
    own, carried = f"package://{robot.package}/", {file.path for file in robot.files}

    def moved(body: Shape) -> Shape:
        if isinstance(body, Mesh) and body.filename.startswith(own) and body.filename[len(own) :] in carried:
            return dataclasses.replace(body, filename=f"package://{package}/{folder}/{body.filename[len(own) :]}")
        return body

    links = tuple(
        dataclasses.replace(
            link,
            visuals=tuple(dataclasses.replace(v, shape=moved(v.shape)) for v in link.visuals),
            collisions=tuple(dataclasses.replace(c, shape=moved(c.shape)) for c in link.collisions),
        )
        for link in robot.links
    )
    files = tuple(PackageFile(f"{folder}/{file.path}", file.content) for file in robot.files)
    return dataclasses.replace(robot, links=links, files=files)


def _planning(section: dict[str, Any]) -> Planning:
    """The spec's ``moveit`` section as the model's :class:`Planning`."""
    groups = tuple((name, tuple(joints)) for name, joints in section.get("groups", {}).items())
    return Planning(groups=groups, gripper=tuple(section.get("gripper", ())), base=section.get("base"))
