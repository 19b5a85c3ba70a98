"""The resolved robot and scene: plain frozen dataclasses in SI units, the single source of truth after validation.

What a package says about the robot or scene (its templates and the direct URDF emitter) comes from this model. Also
here, as the one place for them: the joint types, a simulated sensor's record (both defined in :mod:`xacrokit.shared`,
below the model, which the facts there need), the names of the links and joints xacrokit makes for a spec's arms,
wheels, frames and scene mounts, and of its materials (validate, resolve, emit, render, scenes and the spec line map
that check uses all ask these functions).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal

from .errors import SpecError
from .shared.joint_types import AXIAL, HOME_POSE, JOINT_TYPES, LIMITED, MOVING, JointType  # noqa: F401  (part of the model)
from .shared.sim_sensors import Sensor  # (part of the model: its fields are the sensor's values in sim_sensors' tables)

Vec3 = tuple[float, float, float]
ZERO: Vec3 = (0.0, 0.0, 0.0)

DHRowType = Literal["revolute", "continuous", "prismatic", "fixed"]
Convention = Literal["standard", "modified"]
InertiaKind = Literal["box", "cylinder", "sphere", "capsule", "tube", "mesh", "parts", "explicit"]
Axle = Literal["x", "y", "z"]
DEFAULT_ROW_RADIUS = 0.03  # m: a DH row's body (a cylinder between its joint frames) when the spec gives none
DEFAULT_TOOL = "tool0"  # an arm's tool frame when the spec names none (ROS-Industrial's name)


# ------------------------------------------------------------------------------------- names of generated elements
def attach_joint_name(link: str) -> str:
    """The fixed or continuous joint that attaches a generated link (arm base and tool, wheel, frame) to its parent."""
    return f"{link}_joint"


def arm_base_name(arm: str) -> str:
    """The link of an arm's DH frame 0."""
    return f"{arm}_base"


def mount_joint_name(root: str) -> str:
    """The fixed joint that mounts a robot's root link on its parent (a scene instance, a macro call with parent)."""
    return f"{root}_mount_joint"


def material_name(robot: Robot, name: str | None) -> str:
    """A material as the URDF names it, namespaced by its robot so that several robots (and instances) in one scene
    never clash; '' for none."""
    return f"{robot.name}/{name}" if name else ""


@dataclass(frozen=True)
class Origin:
    """A pose in a parent frame: xyz in m, rpy in rad (URDF fixed-axis roll-pitch-yaw)."""

    xyz: Vec3 = ZERO
    rpy: Vec3 = ZERO


@dataclass(frozen=True)
class Box:
    """A box centred on its origin, edges ``size`` (x, y, z; m) along the origin's axes."""

    size: Vec3


@dataclass(frozen=True)
class Cylinder:
    """A cylinder along the z axis of its origin."""

    radius: float
    length: float


@dataclass(frozen=True)
class Sphere:
    """A sphere centred on its origin (radius in m)."""

    radius: float


@dataclass(frozen=True)
class Mesh:
    """A mesh file (a ``package://`` or ``file://`` address, or a path), scaled per axis."""

    filename: str
    scale: Vec3 = (1.0, 1.0, 1.0)


Shape = Box | Cylinder | Sphere | Mesh


@dataclass(frozen=True)
class Inertia:
    """Mass (kg) and tensor about the centre of mass (kg*m^2) in the frame ``origin`` places in the link frame.

    ``kind`` says where the tensor came from: ``box``, ``cylinder``, ``sphere``, ``capsule``, ``tube`` (computed from
    the shape's closed form), ``mesh`` (from the mesh's surface), ``parts`` (the sum of a composite link's parts) or
    ``explicit`` (given in the spec).
    """

    mass: float
    ixx: float
    ixy: float
    ixz: float
    iyy: float
    iyz: float
    izz: float
    origin: Origin = Origin()
    kind: InertiaKind = "explicit"


@dataclass(frozen=True)
class Visual:
    """URDF <visual>: a shape placed in the link frame, and its material's name (None: none)."""

    shape: Shape
    origin: Origin = Origin()
    material: str | None = None


@dataclass(frozen=True)
class Collision:
    """URDF <collision>: a shape placed in the link frame."""

    shape: Shape
    origin: Origin = Origin()


@dataclass(frozen=True)
class Link:
    """A link with its visuals and collisions (one each for a shape; several for a capsule, written as a cylinder and
    two spheres, or for a composite link's parts)."""

    name: str
    visuals: tuple[Visual, ...] = ()
    collisions: tuple[Collision, ...] = ()
    inertial: Inertia | None = None


@dataclass(frozen=True)
class PackageFile:
    """A file the package carries besides what the templates write: a mesh copied from the spec's folder (bytes) or
    made from a shape URDF has no element for (a tube's OBJ text). ``path`` is relative to the package root."""

    path: str
    content: bytes | str


@dataclass(frozen=True)
class Limit:
    """lower/upper in rad or m (None for continuous joints), effort in N*m or N, velocity in rad/s or m/s."""

    effort: float
    velocity: float
    lower: float | None = None
    upper: float | None = None
    acceleration: float | None = None  # (MoveIt's joint_limits.yaml only: a URDF has no place for it)

    @property
    def bounds(self) -> tuple[float, float] | None:
        """(lower, upper), or None for a continuous joint's limit (effort and velocity only)."""
        if self.lower is None or self.upper is None:
            return None
        return self.lower, self.upper


@dataclass(frozen=True)
class Dynamics:
    """URDF <dynamics>: viscous damping (N*m*s/rad or N*s/m) and Coulomb friction (N*m or N)."""

    damping: float = 0.0
    friction: float = 0.0
    armature: float = 0.0  # (reflected rotor inertia: MuJoCo's; a URDF has no place for it)


@dataclass(frozen=True)
class Mimic:
    """URDF <mimic>: this joint's position is ``multiplier`` times ``joint``'s plus ``offset``."""

    joint: str
    multiplier: float = 1.0
    offset: float = 0.0


@dataclass(frozen=True)
class SafetyController:
    """URDF <safety_controller>: the velocity and position gains and the soft limits (rad or m) of a joint."""

    k_velocity: float
    k_position: float | None = None
    soft_lower_limit: float | None = None
    soft_upper_limit: float | None = None


@dataclass(frozen=True)
class Calibration:
    """URDF <calibration>: the joint positions of a calibration switch's rising and falling edges (rad or m)."""

    rising: float | None = None
    falling: float | None = None


@dataclass(frozen=True)
class Joint:
    """A URDF joint: ``child`` placed in ``parent`` at ``origin``, moving about or along ``axis``."""

    name: str
    type: JointType
    parent: str
    child: str
    origin: Origin = Origin()
    axis: Vec3 | None = None
    limit: Limit | None = None
    dynamics: Dynamics | None = None
    mimic: Mimic | None = None
    safety_controller: SafetyController | None = None
    calibration: Calibration | None = None


@dataclass(frozen=True)
class DHRow:
    """One DH row; a, d in m, alpha, theta in rad. ``mass``/``radius`` give the link a cylinder body."""

    name: str
    link: str
    a: float
    d: float
    alpha: float
    theta: float = 0.0
    type: DHRowType = "revolute"
    limit: Limit | None = None
    dynamics: Dynamics | None = None
    mass: float | None = None
    radius: float = DEFAULT_ROW_RADIUS
    material: str | None = None
    inertia: Inertia | None = None  # (the row's own tensor, its origin in DH frame i; the body carries it moved)
    body: DHBody | None = None  # (resolve's, from the mass, radius and the next row: None without a mass)


@dataclass(frozen=True)
class DHBody:
    """A DH row's body: a cylinder from the row's link frame to where the next joint is (a sphere when they meet),
    drawn, touched and weighed as that solid (resolve computes it; the macro dh_arm computes the same)."""

    shape: Cylinder | Sphere
    origin: Origin
    inertia: Inertia


@dataclass(frozen=True)
class Arm:
    """A DH chain: parent -> ``base`` (DH frame 0, at ``origin``) -> rows -> ``tool`` (DH frame n + ``tool_origin``)
    on the fixed joint ``tool_joint``. ``base`` None: no link of its own, DH frame 0 is ``parent``'s frame (the spec's
    ``base: false``; ``origin`` is then the identity) and the first row's joint hangs on ``parent``."""

    name: str
    parent: str
    origin: Origin
    convention: Convention
    rows: tuple[DHRow, ...]
    base: str | None
    tool: str
    tool_origin: Origin = Origin()
    tool_joint: str | None = None  # the spec's name for the tool frame's joint (``tool: {joint: ...}``)

    @property
    def frame0(self) -> str:
        """The link whose frame is DH frame 0: the base link, or ``parent`` for an arm without one."""
        return self.base if self.base is not None else self.parent

    @property
    def tool_joint_name(self) -> str:
        return self.tool_joint or attach_joint_name(self.tool)

    @property
    def link_names(self) -> tuple[str, ...]:
        base = () if self.base is None else (self.base,)
        return (*base, *(row.link for row in self.rows), self.tool)

    @property
    def joint_names(self) -> tuple[str, ...]:
        base = () if self.base is None else (attach_joint_name(self.base),)
        return (*base, *(row.name for row in self.rows), self.tool_joint_name)


@dataclass(frozen=True)
class Wheel:
    """A wheel link ``name`` on a continuous joint (``joint``, by default ``name``_joint); SI units throughout."""

    name: str
    parent: str
    origin: Origin
    radius: float
    width: float
    mass: float
    axis: Axle = "y"
    material: str | None = None
    effort: float = 10.0
    velocity: float = 10.0
    damping: float = 0.01
    friction: float = 0.0
    mu1: float = 1.0
    mu2: float = 1.0
    joint: str | None = None  # the spec's name for its joint (``joint:``), else NAME_joint
    inertia: Inertia | None = None  # (resolve's: a solid cylinder about its axle, at the link's origin)

    @property
    def joint_name(self) -> str:
        return self.joint or attach_joint_name(self.name)


@dataclass(frozen=True)
class Interfaces:
    """ros2_control's command and state interfaces of a joint (position, velocity, effort)."""

    command: tuple[str, ...]
    state: tuple[str, ...]


@dataclass(frozen=True)
class ControlledJoint:
    """A joint in ros2_control: its interfaces and its initial position (rad or m)."""

    name: str
    interfaces: Interfaces
    initial_position: float = 0.0


@dataclass(frozen=True)
class Surface:
    """Gazebo's contact parameters of a link: friction coefficients (mu1, mu2) and contact stiffness and damping."""

    link: str
    mu1: float | None = None
    mu2: float | None = None
    kp: float | None = None
    kd: float | None = None


@dataclass(frozen=True)
class Planning:
    """The spec's ``moveit`` section (docs/moveit.md): planning groups by their joints (``groups``: name -> joints;
    none given: one group per DH arm), the joints of the robot's gripper (a group and an end effector), and the
    base's virtual joint (``fixed``, ``planar`` or ``floating``; None: planar on wheels, else fixed)."""

    groups: tuple[tuple[str, tuple[str, ...]], ...] = ()
    gripper: tuple[str, ...] = ()
    base: str | None = None


@dataclass(frozen=True)
class Robot:
    """A whole robot. ``links``/``joints`` hold the spec's links, joints and frames; arms and wheels keep their own
    records (they are emitted through the dh_arm and wheel macros) and add the names listed by their properties."""

    name: str
    root: str
    materials: tuple[tuple[str, tuple[float, float, float, float]], ...] = ()
    links: tuple[Link, ...] = ()
    joints: tuple[Joint, ...] = ()
    arms: tuple[Arm, ...] = ()
    wheels: tuple[Wheel, ...] = ()
    ros2_control: tuple[ControlledJoint, ...] | None = None
    surfaces: tuple[Surface, ...] = ()
    sensors: tuple[Sensor, ...] = ()
    files: tuple[PackageFile, ...] = ()
    extension: str = ""  # the first content of urdf/NAME_extension.xacro's macro (the spec's `extension` file)
    extension_source: str = ""  # that file's name as the spec gives it
    # named poses: (name, ((joint, position in rad or m), ...)), as the spec gives them (a joint left out is at its
    # start: 0, or the limit nearest 0); `home` is where the robot starts
    poses: tuple[tuple[str, tuple[tuple[str, float], ...]], ...] = ()
    mount_joint: str | None = None  # the spec's name for the joint that mounts the root (``mount_joint:``)
    planning: Planning = Planning()  # (the spec's ``moveit`` section: the SRDF's groups, gripper and virtual joint)
    source: str = field(default="", compare=False)

    @property
    def mount_joint_name(self) -> str:
        """The fixed joint that mounts the root link on a parent (the macro's, a scene's): the spec's name or
        :func:`mount_joint_name`'s."""
        return self.mount_joint or mount_joint_name(self.root)

    @property
    def mass(self) -> float:
        """The whole robot's mass (kg): its links', its arms' bodies' and its wheels'."""
        links = sum(link.inertial.mass for link in self.links if link.inertial is not None)
        rows = sum(row.body.inertia.mass for arm in self.arms for row in arm.rows if row.body is not None)
        return links + rows + sum(wheel.mass for wheel in self.wheels)

    @property
    def has_package_meshes(self) -> bool:
        """A link draws or collides with a ``package://`` mesh (Gazebo then needs the package's model path)."""
        shapes = [g.shape for link in self.links for g in link.visuals]
        shapes += [g.shape for link in self.links for g in link.collisions]
        return any(isinstance(shape, Mesh) and shape.filename.startswith("package://") for shape in shapes)

    @property
    def link_names(self) -> tuple[str, ...]:
        names = [link.name for link in self.links]
        for arm in self.arms:
            names += arm.link_names
        names += [wheel.name for wheel in self.wheels]
        return tuple(names)

    @property
    def joint_names(self) -> tuple[str, ...]:
        names = [joint.name for joint in self.joints]
        for arm in self.arms:
            names += arm.joint_names
        names += [wheel.joint_name for wheel in self.wheels]
        return tuple(names)

    @property
    def carried_files(self) -> dict[str, tuple[PackageFile, ...]]:
        """The files (meshes) the package carries besides its templates', by the package their ``package://`` URIs
        name: what a check of the URDF before the package is written must find there."""
        return {self.package: self.files} if self.files else {}

    @property
    def mock_integrates(self) -> bool:
        """Whether mock hardware must integrate commands into states (a joint commanded by velocity or acceleration):
        mock_components/GenericSystem otherwise only mirrors each command, and the position never moves."""
        return any({"velocity", "acceleration"} & set(j.interfaces.command) for j in self.ros2_control or ())

    @property
    def package(self) -> str:
        return f"{self.name}_description"


# ------------------------------------------------------------------------------------------------------------ scenes
@dataclass(frozen=True)
class ThirdPartyMacro:
    """A macro with the prefix / parent / *origin interface, from a .xacro file the scene includes where it is."""

    file: Path
    macro: str
    params: tuple[tuple[str, str], ...] = ()
    prefix_param: str = "prefix"
    parent_param: str = "parent"


@dataclass(frozen=True)
class Instance:
    """One robot in the scene: one of ours (``robot``, from ``spec_file``) or a third-party ``macro``. ``links`` and
    ``joints`` are its full names in the scene (prefix included)."""

    name: str
    prefix: str
    parent: str  # the full name of the link it is mounted on
    origin: Origin
    links: tuple[str, ...]
    joints: tuple[str, ...]
    robot: Robot | None = None
    spec_file: Path | None = None
    macro: ThirdPartyMacro | None = None
    parent_instance: str | None = None


@dataclass(frozen=True)
class Scene:
    """Several robots in one description, every name of every instance known (and disjoint) before rendering."""

    name: str
    world: str
    instances: tuple[Instance, ...]
    source: str = field(default="", compare=False)
    warnings: tuple[SpecError, ...] = field(default=(), compare=False)  # its robots' and its own (Spec.warnings)
    command: str = field(default="", compare=False)  # what makes it again, when not `gen-robot SPEC` (a fleet)

    @property
    def package(self) -> str:
        return f"{self.name}_description"

    @property
    def robots(self) -> tuple[Robot, ...]:
        """The distinct robots of the spec instances, in first-use order."""
        seen: dict[str, Robot] = {}
        for instance in self.instances:
            if instance.robot is not None:
                seen.setdefault(instance.robot.name, instance.robot)
        return tuple(seen.values())

    @property
    def link_names(self) -> tuple[str, ...]:
        return (self.world, *(n for i in self.instances for n in i.links))

    @property
    def carried_files(self) -> dict[str, tuple[PackageFile, ...]]:
        """The meshes its robots carry (moved into this package, under robots/ROBOT_description/: resolve's
        carried_into), by the package their ``package://`` URIs name (see Robot.carried_files)."""
        files = tuple(file for robot in self.robots for file in robot.files)
        return {self.package: files} if files else {}

    @property
    def joint_names(self) -> tuple[str, ...]:
        return tuple(n for i in self.instances for n in i.joints)
