"""What a package's config/..._controllers.yaml sets up: a diff_drive_controller for wheels that make a differential
drive, one forward command controller per command interface for the other controlled joints, and a
JointTrajectoryController for the position-commanded ones (what MoveIt sends to); and which of them the launch files
spawn active (the trajectory controller, not the position group that claims the same joints, which is loaded
inactive)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..model import Robot
from ..shared.transforms import origin_transform
from ..shared.units import STANDARD_GRAVITY

if TYPE_CHECKING:
    pass


def controllers(robot: Robot, prefix: str = "", *, mounted: bool = False) -> dict[str, Any]:
    """What config/..._controllers.yaml sets up for ``robot`` (names with ``prefix``): ``drive``, a
    diff_drive_controller for its wheels when they make a differential drive (see :func:`_differential_drive`), and
    ``command_groups``, the other controlled joints grouped by their first command interface (one forward command
    controller per group). ``mounted``: the robot is fixed into a scene's URDF, so its drive must not publish the
    odom -> base transform (the base would have two parents in TF). ``trajectory``: the JointTrajectoryController's
    joints and state interfaces (those every one of them has, of position and velocity); ``spawned`` and
    ``inactive``: the controllers the launch files start active and load inactive."""
    drive = _differential_drive(robot, prefix)
    if drive:
        drive["odom_tf"] = not mounted
    driven = set(drive["left"] + drive["right"]) if drive else set()
    groups: dict[str, list[str]] = {}
    for joint in robot.ros2_control or ():
        if joint.interfaces.command and prefix + joint.name not in driven:
            groups.setdefault(joint.interfaces.command[0], []).append(prefix + joint.name)
    trajectory = None
    if groups.get("position"):  # (MoveIt and every trajectory sender need a JointTrajectoryController)
        states = {j.name: j.interfaces.state for j in robot.ros2_control or ()}
        names = groups["position"]
        common = [k for k in ("position", "velocity") if all(k in states[n.removeprefix(prefix)] for n in names)]
        if "position" in common:
            trajectory = {"joints": names, "state_interfaces": common}
    spawned = [prefix + "joint_state_broadcaster"]
    spawned += [prefix + "diff_drive_controller"] if drive else []
    spawned += [prefix + "joint_trajectory_controller"] if trajectory else []
    spawned += [f"{prefix}{kind}_controller" for kind in groups if not (trajectory and kind == "position")]
    inactive = [prefix + "position_controller"] if trajectory else []  # (it claims the trajectory's joints too)
    return {
        "command_groups": groups,
        "drive": drive,
        "trajectory": trajectory,
        "spawned": spawned if robot.ros2_control is not None else [],
        "inactive": inactive,
    }


def axle_offset(robot: Robot) -> tuple[float, float] | None:
    """Where the differential drive's axle midpoint is in its base frame (the root link), x and y in m, the robot at
    its zero pose; None without a drive or when a wheel's parent is not reached through the spec's joints.
    diff_drive_controller's odometry is of that midpoint and it publishes it as the base frame: off it, the odometry
    is wrong whenever the robot turns."""
    if _differential_drive(robot, "") is None:
        return None
    import numpy as np  # (heavy: numpy, for a differential drive only)

    joint_of = {joint.child: joint for joint in robot.joints}
    centres = []
    for wheel in robot.wheels:
        pose, link = origin_transform(wheel.origin), wheel.parent
        while link != robot.root:
            joint = joint_of.get(link)
            if joint is None:
                return None
            pose, link = origin_transform(joint.origin) @ pose, joint.parent
        centres.append(pose[:3, 3])
    return float(np.mean([c[0] for c in centres])), float(np.mean([c[1] for c in centres]))


def _differential_drive(robot: Robot, prefix: str) -> dict[str, Any] | None:
    """The diff_drive_controller parameters of a robot whose wheels are a differential drive: two or more wheels on
    one parent link, axles along +y unrotated (a positive speed drives forward, REP 103), velocity-commanded, of one
    radius, on both sides of the parent's x-z plane. Separation: mean left y - mean right y. Otherwise None."""
    controlled = {j.name: j for j in robot.ros2_control or ()}
    wheels = robot.wheels
    if len(wheels) < 2 or len({w.parent for w in wheels}) != 1:
        return None
    for wheel in wheels:
        joint = controlled.get(wheel.joint_name)
        if wheel.axis != "y" or any(wheel.origin.rpy) or joint is None:
            return None
        if tuple(joint.interfaces.command[:1]) != ("velocity",):
            return None
    if len({w.radius for w in wheels}) != 1:
        return None
    left = [w for w in wheels if w.origin.xyz[1] > 0]
    right = [w for w in wheels if w.origin.xyz[1] < 0]
    if not left or not right or len(left) + len(right) != len(wheels):
        return None
    separation = sum(w.origin.xyz[1] for w in left) / len(left) - sum(w.origin.xyz[1] for w in right) / len(right)
    radius = wheels[0].radius
    speed = min(w.velocity for w in wheels) * radius  # (the slowest wheel's limit, at the rim)
    # the most the wheels can accelerate the robot on flat ground: their efforts, sum(effort)/r over its mass, and
    # at most mu g, beyond which they slip (an upper bound: their own spin-up and rolling resistance take some of it)
    acceleration = None
    if robot.mass > 0:
        grip = min(w.mu1 for w in wheels) * STANDARD_GRAVITY
        acceleration = min(sum(w.effort for w in wheels) / radius / robot.mass, grip)
    return {
        "speed": speed,
        "turn_rate": 2.0 * speed / separation,  # (the wheels at +-speed, turning on the spot)
        "acceleration": acceleration,
        "turn_acceleration": 2.0 * acceleration / separation if acceleration is not None else None,
        "left": [prefix + w.joint_name for w in left],
        "right": [prefix + w.joint_name for w in right],
        "separation": separation,
        "radius": radius,
        "base_frame": prefix + robot.root,
        "odom_frame": prefix + "odom",
    }
