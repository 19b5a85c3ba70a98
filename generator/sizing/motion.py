"""The motion part of ``gen-robot size``: a joint-space trajectory through waypoints, time-scaled within velocity and
acceleration limits, and the joint torques along it by inverse dynamics (pinocchio's rnea, payloads and loads
included): per joint the peak and RMS torque, peak speed and acceleration, peak and regenerative power, and energy.

Each segment between two waypoints is a straight line in joint space, q(t) = q_a + s(t) (q_b - q_a), at rest at both
ends, and every joint arrives together. The path parameter s follows

- ``quintic``: s = 10 u^3 - 15 u^4 + 6 u^5 (u = t / T): peak speed 15/8 |dq| / T, peak acceleration
  (10 / sqrt 3) |dq| / T^2; T the shortest that keeps every joint within its limits;
- ``trapezoid``: constant acceleration, cruise, constant deceleration (a triangle when the segment is too short to
  reach the speed limit); T likewise the shortest.

A dwell (the robot held still at each waypoint, default 0) is part of the cycle: the RMS torque counts it, as sizing
guides ask.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..kinematics import REACHED
from ..kinematics.inverse import Chain, solve, starts
from ..reader.kinematic_model import outside_text
from ..shared.transforms import rpy_matrix
from .sized_robot import LoadedRobot, joint_configurations

QUINTIC_SPEED = 15.0 / 8.0  # peak ds/du of 10u^3 - 15u^4 + 6u^5
QUINTIC_ACCELERATION = 10.0 / math.sqrt(3.0)  # peak |d2s/du2|
DEFAULT_STEP = 1e-3  # s: the sampling step when the sizing file gives none


@dataclass(frozen=True)
class Motion:
    """Waypoints (one value per moving joint, in the robot's joint order), the time scaling, the joints' speed and
    acceleration limits (rad/s, rad/s^2 or m/s, m/s^2), the dwell at each waypoint (s) and the sampling step (s)."""

    waypoints: tuple[tuple[float, ...], ...]
    velocity: tuple[float, ...]
    acceleration: tuple[float, ...]
    scaling: str = "quintic"
    dwell: float = 0.0
    step: float = DEFAULT_STEP
    durations: tuple[float | None, ...] = ()  # s, per segment: the duration asked (None, or none given: the shortest)


@dataclass(frozen=True)
class Trajectory:
    """Samples of the whole cycle: times (s), positions, velocities, accelerations (one row per sample)."""

    t: np.ndarray
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray


@dataclass(frozen=True)
class JointMotion:
    """One joint along the cycle: torques (N*m or N), speeds, accelerations, power (W), energy (J)."""

    joint: str
    peak_torque: float
    rms_torque: float
    peak_speed: float
    peak_acceleration: float
    peak_power: float  # the largest tau * qdot (motoring)
    peak_regenerative_power: float  # the most negative tau * qdot, as a positive number (0 if never)
    energy: float  # the integral of tau * qdot over the cycle (net)
    motoring_energy: float  # the integral of its positive part
    peak_load_inertia: float  # the largest diagonal entry M_ii(q) of the mass matrix along the cycle (kg*m^2 or kg)


def _quintic(duration: float, times: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """s, ds/dt, d2s/dt2 at ``times`` (0..duration) of a rest-to-rest quintic segment of length 1."""
    u = np.clip(times / duration, 0.0, 1.0)
    s = u**3 * (10 - 15 * u + 6 * u * u)
    ds = 30 * u * u * (1 - u) ** 2 / duration
    dds = 60 * u * (1 - u) * (1 - 2 * u) / duration**2
    return s, ds, dds


def _trapezoid(
    speed: float, acceleration: float, times: np.ndarray
) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
    """(duration, s, ds, dds) of a rest-to-rest trapezoid of length 1 with the path's speed and acceleration limits
    (a triangle when the cruise speed is not reached)."""
    ramp = speed / acceleration
    if ramp * speed >= 1.0:  # (a triangle: accelerate to the middle, decelerate)
        ramp = math.sqrt(1.0 / acceleration)
        speed = acceleration * ramp
        duration = 2.0 * ramp
    else:
        duration = 1.0 / speed + ramp
    t = np.clip(times, 0.0, duration)
    rising, falling = t < ramp, t > duration - ramp
    tail = duration - t
    s = np.where(rising, acceleration * t * t / 2, np.where(falling, 1.0 - acceleration * tail * tail / 2, 0.0))
    cruise = ~(rising | falling)
    s = np.where(cruise, acceleration * ramp * ramp / 2 + speed * (t - ramp), s)
    ds = np.where(rising, acceleration * t, np.where(falling, acceleration * tail, speed))
    dds = np.where(rising, acceleration, np.where(falling, -acceleration, 0.0))
    return duration, s, ds, dds


def _path_limits(motion: Motion, delta: np.ndarray) -> tuple[float, float, int, int]:
    """The path's speed and acceleration limits per unit s (the tightest joint's) and which joints set them."""
    moving = np.flatnonzero(np.abs(delta) > 0)
    with np.errstate(divide="ignore", over="ignore"):  # (a limit of 1e-320 is a path speed of 0: an endless segment)
        speeds = np.array(motion.velocity)[moving] / np.abs(delta[moving])
        accelerations = np.array(motion.acceleration)[moving] / np.abs(delta[moving])
    slow, sluggish = int(np.argmin(speeds)), int(np.argmin(accelerations))
    return float(speeds[slow]), float(accelerations[sluggish]), int(moving[slow]), int(moving[sluggish])


@dataclass(frozen=True)
class SegmentTiming:
    """A segment's shortest duration (s), and the limit that sets it: "velocity" or "acceleration" of ``joint``
    (its index in the motion's joints); duration 0 and joint -1 for a segment that does not move."""

    duration: float
    limit: str = ""
    joint: int = -1


def segment_duration(motion: Motion, delta: np.ndarray) -> float:
    """The shortest duration of a segment that keeps every joint within its speed and acceleration limits (inf when
    a limit is too small for a float to say how long)."""
    return segment_timing(motion, delta).duration


def segment_timing(motion: Motion, delta: np.ndarray) -> SegmentTiming:
    """:func:`segment_duration` with the limit and joint that set it."""
    if not (np.abs(delta) > 0).any():
        return SegmentTiming(0.0)
    speed, acceleration, slow, sluggish = _path_limits(motion, delta)
    if not (speed > 0 and acceleration > 0):
        return SegmentTiming(
            math.inf, "velocity" if not speed > 0 else "acceleration", slow if not speed > 0 else sluggish
        )
    if motion.scaling == "quintic":
        cruising, ramping = QUINTIC_SPEED / speed, math.sqrt(QUINTIC_ACCELERATION / acceleration)
        if cruising >= ramping:
            return SegmentTiming(cruising, "velocity", slow)
        return SegmentTiming(ramping, "acceleration", sluggish)
    duration = _trapezoid(speed, acceleration, np.zeros(1))[0]
    triangle = (speed / acceleration) * speed >= 1.0
    return SegmentTiming(duration, "acceleration" if triangle else "velocity", sluggish if triangle else slow)


MAX_SAMPLES = 200_000  # a cycle of 200 s at the default 1 ms step; memory and time grow with it (docs/size.md)


def sample_count(motion: Motion, durations: Sequence[float]) -> float:
    """How many samples :func:`trajectory` takes for the cycle whose segments last ``durations`` (inf when a
    duration is): the start, every dwell, every segment (at least 2 samples each)."""
    ratios = [motion.dwell / motion.step, *(d / motion.step for d in durations if d > 0)]
    if not all(math.isfinite(r) for r in ratios):
        return math.inf
    held = max(float(math.ceil(ratios[0])), 1.0) if motion.dwell > 0 else 0.0
    moving = sum(max(float(math.ceil(r)), 2.0) for r in ratios[1:])  # (floats: a sum past 1e308 is inf, not an error)
    return 1.0 + held * len(motion.waypoints) + moving


def planned_durations(motion: Motion) -> list[float]:
    """Each segment's duration (s): the one asked (the sizing file's reader checked it is not below the shortest),
    else the shortest the joints' limits allow."""
    points = [np.array(w, dtype=float) for w in motion.waypoints]
    asked = list(motion.durations) + [None] * (len(points) - 1 - len(motion.durations))
    return [
        given if given is not None else segment_duration(motion, end - start)
        for start, end, given in zip(points, points[1:], asked, strict=False)
    ]


def stretched_speed(acceleration: float, duration: float) -> float:
    """The cruise speed (per unit path) of a trapezoid of unit length that lasts ``duration`` at ``acceleration``:
    the smaller root of v^2 - a T v + a = 0 (T = 1/v + v/a); a triangle when a T^2 = 4."""
    root = max(acceleration * acceleration * duration * duration - 4.0 * acceleration, 0.0)
    return (acceleration * duration - math.sqrt(root)) / 2.0


def trajectory(motion: Motion) -> Trajectory:
    """The sampled cycle: each segment at its planned duration (:func:`planned_durations`: the one asked, else the
    shortest), every joint arriving together, a dwell at every waypoint (the first included). Raises ValueError for a
    cycle of more than MAX_SAMPLES samples (:func:`sample_count`; the sizing file's reader refuses those first,
    located)."""
    points = [np.array(w, dtype=float) for w in motion.waypoints]
    durations = planned_durations(motion)
    if not sample_count(motion, durations) <= MAX_SAMPLES:
        raise ValueError(f"the cycle needs more than {MAX_SAMPLES:,} samples")
    times: list[np.ndarray] = []
    positions: list[np.ndarray] = []
    speeds: list[np.ndarray] = []
    accelerations: list[np.ndarray] = []
    clock = 0.0
    n = len(points[0])

    def hold(point: np.ndarray, duration: float) -> None:
        nonlocal clock
        count = max(int(math.ceil(duration / motion.step)), 1) if duration > 0 else 0
        if count:
            local = np.linspace(0.0, duration, count + 1)[1:]
            times.append(clock + local)
            positions.append(np.tile(point, (count, 1)))
            speeds.append(np.zeros((count, n)))
            accelerations.append(np.zeros((count, n)))
            clock += duration

    times.append(np.zeros(1))
    positions.append(points[0][None, :])
    speeds.append(np.zeros((1, n)))
    accelerations.append(np.zeros((1, n)))
    hold(points[0], motion.dwell)
    for start, end, duration in zip(points, points[1:], durations, strict=False):
        delta = end - start
        if duration > 0 and not (np.abs(delta) > 0).any():  # (a segment asked to last, that does not move: a hold)
            hold(end, duration)
        elif duration > 0:
            count = max(int(math.ceil(duration / motion.step)), 2)
            local = np.linspace(0.0, duration, count + 1)[1:]
            if motion.scaling == "quintic":
                s, ds, dds = _quintic(duration, local)
            else:
                speed, acceleration, _, _ = _path_limits(motion, delta)
                if duration > segment_duration(motion, delta):  # (stretched: the limit's acceleration, a lower speed)
                    speed = stretched_speed(acceleration, duration)
                _, s, ds, dds = _trapezoid(speed, acceleration, local)
            times.append(clock + local)
            positions.append(start + s[:, None] * delta)
            speeds.append(ds[:, None] * delta)
            accelerations.append(dds[:, None] * delta)
            clock += duration
        hold(end, motion.dwell)
    return Trajectory(
        t=np.concatenate(times),
        q=np.concatenate(positions),
        v=np.concatenate(speeds),
        a=np.concatenate(accelerations),
    )


def inverse_dynamics(robot: LoadedRobot, path: Trajectory) -> np.ndarray:
    """The moving joints' torques at every sample: rnea(q, v, a) with the loads as external forces (each load's
    force and moment moved to its frame's parent joint), one row per sample; with ``robot.joint_friction``, plus each
    joint's viscous damping and Coulomb friction as the URDF's <dynamics> gives them (pinocchio reads them):
    d qdot + f sign(qdot), what the motor must also overcome."""
    import pinocchio as pin  # (heavy: pinocchio)

    model, data = robot.model, robot.data
    rows = [j.v_index for j in robot.joints]
    qs = joint_configurations(robot, path.q)
    vs, accelerations = np.zeros((len(path.t), model.nv)), np.zeros((len(path.t), model.nv))
    vs[:, rows], accelerations[:, rows] = path.v, path.a
    result = np.empty((len(path.t), len(rows)))
    for k in range(len(path.t)):
        if robot.loads:
            pin.forwardKinematics(model, data, qs[k])
            pin.updateFramePlacements(model, data)
            fext = [pin.Force.Zero() for _ in range(model.njoints)]
            for frame_id, force in robot.loads:
                frame = model.frames[frame_id]
                point = data.oMf[frame_id].translation
                world = pin.Force(force.linear, force.angular + np.cross(point, force.linear))
                fext[frame.parentJoint] += data.oMi[frame.parentJoint].actInv(world)
            result[k] = pin.rnea(model, data, qs[k], vs[k], accelerations[k], fext)[rows]
        else:
            result[k] = pin.rnea(model, data, qs[k], vs[k], accelerations[k])[rows]
    if robot.joint_friction:
        result += np.asarray(model.damping)[rows] * path.v + np.asarray(model.friction)[rows] * np.sign(path.v)
    return result


def joint_motions(robot: LoadedRobot, path: Trajectory, torque: np.ndarray) -> list[JointMotion]:
    """Per joint: the peaks, the RMS torque over the whole cycle and the energies (trapezoidal rule in time), and the
    largest inertia the joint moves (the mass matrix's diagonal, pinocchio's crba)."""
    import pinocchio as pin  # (heavy: pinocchio)

    rows = [j.v_index for j in robot.joints]
    qs = joint_configurations(robot, path.q)
    diagonals = np.empty((len(path.t), robot.model.nv))
    for k in range(len(path.t)):
        diagonals[k] = np.diagonal(pin.crba(robot.model, robot.data, qs[k]))
    inertia = diagonals[:, rows].max(axis=0)
    power = torque * path.v
    duration = float(path.t[-1] - path.t[0])
    result = []
    for index, joint in enumerate(robot.joints):
        squared = np.trapezoid(torque[:, index] ** 2, path.t) if duration > 0 else 0.0
        result.append(
            JointMotion(
                joint=joint.name,
                peak_torque=float(torque[np.argmax(np.abs(torque[:, index])), index]),
                rms_torque=float(math.sqrt(squared / duration)) if duration > 0 else float(abs(torque[0, index])),
                peak_speed=float(np.abs(path.v[:, index]).max()),
                peak_acceleration=float(np.abs(path.a[:, index]).max()),
                peak_power=float(max(power[:, index].max(), 0.0)) + 0.0,  # (max(-0.0, 0.0) is -0.0)
                peak_regenerative_power=float(max(-power[:, index].min(), 0.0)) + 0.0,
                energy=float(np.trapezoid(power[:, index], path.t)),
                motoring_energy=float(np.trapezoid(np.maximum(power[:, index], 0.0), path.t)),
                peak_load_inertia=float(inertia[index]),
            )
        )
    return result


def waypoint_errors(robot: LoadedRobot, waypoints: Sequence[Sequence[float]]) -> list[str]:
    """Waypoint values outside their joint's range, said as 'waypoint k: joint value outside [lower, upper]'."""
    problems = []
    for k, point in enumerate(waypoints):
        for joint, value in zip(robot.joints, point, strict=True):
            if joint.kind != "continuous" and not joint.span[0] - 1e-12 <= value <= joint.span[1] + 1e-12:
                unit = "m" if joint.kind == "prismatic" else "rad"  # (digits enough not to read as inside)
                outside = outside_text(value, joint.span, unit, range_name="range")
                problems.append(f"waypoint {k}: {joint.name} = {outside}")
    return problems


def reach(
    robot: LoadedRobot,
    frame: str,
    xyz: Sequence[float],
    rpy: Sequence[float] | None,
    start: Sequence[float],
) -> tuple[list[float], float]:
    """Joint values that put ``frame`` at the pose (``rpy`` None: the position only), from ``start``, kept within the
    joints' ranges (the solver of ``gen-robot ik``: :func:`xacrokit.kinematics.inverse.solve`); and the pose error
    left (m, and rad for the orientation). When the solver stops short from ``start`` (a joint limit between it and
    the pose), it tries the starts ``gen-robot ik`` spreads over the ranges and keeps, of those that reach the pose,
    the one nearest ``start``."""
    import pinocchio as pin  # (heavy: pinocchio)

    target = pin.SE3(rpy_matrix(*rpy) if rpy is not None else np.eye(3), np.array(xyz, dtype=float))
    lower = np.array([j.span[0] for j in robot.joints])
    upper = np.array([j.span[1] for j in robot.joints])
    columns = [[(j.v_index, 1.0)] for j in robot.joints]
    chain = Chain(robot.model, robot.model.getFrameId(frame), columns, lower, upper, robot.configuration)
    values, error = solve(chain, target, position_only=rpy is None, start=start)
    if error > REACHED:
        tried = [solve(chain, target, position_only=rpy is None, start=s) for s in starts(chain, start)[1:]]
        reached = [(v, e) for v, e in tried if e <= REACHED]
        if reached:
            values, error = min(reached, key=lambda found: float(np.abs(found[0] - np.asarray(start)).sum()))
        else:
            values, error = min([(values, error), *tried], key=lambda found: found[1])
    return [float(v) for v in values], error
