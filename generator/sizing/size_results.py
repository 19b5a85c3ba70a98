"""What ``gen-robot size`` says: per joint the worst static torque, where, what the loads add; along a motion the
peak and RMS torque, speed, acceleration, power and energy; through a drive the motor's side; and every margin, as a
table or as JSON (schemas/size-report.schema.json).

A margin is a limit over what is needed times the sizing file's safety factor (default 1); >= 1 passes. The URDF's
effort limit over the static and the motion peak torque, its velocity limit over the peak speed, and a drive's motor
limits over the motor's peak torque, RMS torque and peak speed. The motor side, through a gear ratio N and
efficiency eta: torque tau / (N eta) (the gearbox's losses counted as when the motor drives, the conservative case),
speed N qdot, reflected rotor inertia J_rotor N^2, and the load-to-motor inertia ratio J_load / (J_rotor N^2) with
J_load the largest diagonal entry of the mass matrix along the motion.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from .mobile import BaseMotion, BaseSizing
from .motion import JointMotion, Trajectory
from .sized_robot import GRAVITY, Load, LoadedRobot, Payload
from .static import StaticPeak

if TYPE_CHECKING:
    from .sizing_file import Drive

SCHEMA_ID = "urn:xacrokit:schema:size-report:v1"


def ratio(limit: float | None, needed: float) -> float | None:
    """limit / |needed|, None without a limit or a need."""
    if limit is None or needed == 0.0:
        return None
    return limit / abs(needed)


@dataclass(frozen=True)
class MotionTiming:
    """How long the motion's segments last (s, in order), the dwell held at each waypoint (s) and the whole cycle;
    and the joints whose speed and acceleration limits the segments were checked against, by kind (a joint left out
    had no such limit: the durations asked set its motion)."""

    segments: tuple[float, ...]
    dwell: float
    cycle: float
    checked: tuple[tuple[str, tuple[str, ...]], ...] = ()  # (("velocity", joints), ("acceleration", joints))


@dataclass(frozen=True)
class SizeReport:
    """The analysis of one robot: its static peaks, its motion (if any), its drives, and their inputs."""

    path: str
    robot: str
    peaks: tuple[StaticPeak, ...]
    efforts: dict[str, float | None]
    velocities: dict[str, float | None] = field(default_factory=dict)
    payloads: tuple[Payload, ...] = ()
    loads: tuple[Load, ...] = ()
    massless: tuple[str, ...] = ()
    motions: tuple[JointMotion, ...] | None = None
    drives: dict[str, Drive] = field(default_factory=dict)
    base: BaseSizing | None = None
    base_motion: BaseMotion | None = None
    samples: tuple[Trajectory, np.ndarray] | None = field(default=None, compare=False)  # (for the plots)
    safety_factor: float = 1.0  # every need is multiplied by it before its margin is taken
    gravity: float = GRAVITY  # m/s^2 along -z of the root frame, as the analysis took it
    timing: MotionTiming | None = None  # (with a motion)
    joint_friction: bool = True  # the motion's torques include the joints' damping and friction

    @staticmethod
    def of(
        robot: LoadedRobot,
        peaks: list[StaticPeak],
        motions: list[JointMotion] | None = None,
        drives: dict[str, Drive] | None = None,
    ) -> SizeReport:
        """The report of ``robot`` sized (its payloads and loads as given), before the motion's and base's parts."""
        return SizeReport(
            path=str(robot.robot.path),
            robot=robot.name,
            peaks=tuple(peaks),
            efforts={j.name: j.effort for j in robot.joints},
            velocities={j.name: j.velocity for j in robot.joints},
            payloads=robot.payloads,
            loads=robot.applied,
            massless=tuple(robot.massless),
            motions=None if motions is None else tuple(motions),
            drives=dict(drives or {}),
            gravity=robot.gravity,
            joint_friction=robot.joint_friction,
        )

    def _ratio(self, limit: float | None, needed: float) -> float | None:
        """A margin: the limit over the need times the safety factor."""
        return ratio(limit, needed * self.safety_factor)

    def margin(self, peak: StaticPeak) -> float | None:
        """The URDF's effort limit over the static peak torque (>= 1 passes), None without a limit or a torque."""
        return self._ratio(self.efforts.get(peak.joint), peak.torque)

    def motion_of(self, joint: str) -> JointMotion | None:
        return next((m for m in self.motions or () if m.joint == joint), None)

    def drive_side(self, joint: str) -> dict[str, Any] | None:
        """The motor side of a joint's drive (see the module's notes), from the motion, else the static peak."""
        drive = self.drives.get(joint)
        if drive is None:
            return None
        moved = self.motion_of(joint)
        static = next(p for p in self.peaks if p.joint == joint)
        peak = max(abs(static.torque), abs(moved.peak_torque) if moved else 0.0)
        rms = moved.rms_torque if moved else abs(static.torque)  # (held still: the static torque is its RMS)
        scale = drive.gear_ratio * drive.efficiency
        reflected = drive.rotor_inertia * drive.gear_ratio * drive.gear_ratio
        side: dict[str, Any] = {
            "gear_ratio": drive.gear_ratio,
            "efficiency": drive.efficiency,
            "motor_peak_torque": peak / scale,
            "motor_rms_torque": rms / scale,
            "motor_peak_speed": (moved.peak_speed if moved else 0.0) * drive.gear_ratio,
            "reflected_inertia": reflected,
            "inertia_ratio": moved.peak_load_inertia / reflected if moved and reflected > 0 else None,
        }
        side["peak_torque_margin"] = self._ratio(drive.peak_torque, side["motor_peak_torque"])
        side["rated_torque_margin"] = self._ratio(drive.rated_torque, side["motor_rms_torque"])
        side["speed_margin"] = self._ratio(drive.max_speed, side["motor_peak_speed"])
        return side

    @property
    def failures(self) -> list[tuple[str, str]]:
        """(joint, what) for every margin below 1, and for every result that is not a finite number (a margin of NaN
        is no pass)."""
        found = []
        for peak in self.peaks:
            if not math.isfinite(peak.torque) or not math.isfinite(peak.load_torque):
                found.append((peak.joint, "static torque not a finite number"))
            checks = [("static torque over the effort limit", self.margin(peak))]
            moved = self.motion_of(peak.joint)
            if moved is not None and not all(
                map(math.isfinite, (moved.peak_torque, moved.rms_torque, moved.peak_speed, moved.energy))
            ):
                found.append((peak.joint, "motion result not a finite number"))
            if moved is not None:
                checks += [
                    (
                        "motion torque over the effort limit",
                        self._ratio(self.efforts.get(peak.joint), moved.peak_torque),
                    ),
                    ("speed over the velocity limit", self._ratio(self.velocities.get(peak.joint), moved.peak_speed)),
                ]
            side = self.drive_side(peak.joint)
            if side is not None:
                motor = ("motor_peak_torque", "motor_rms_torque", "motor_peak_speed", "reflected_inertia")
                if not all(math.isfinite(side[key]) for key in motor):
                    found.append((peak.joint, "motor-side result not a finite number"))
                checks += [
                    ("motor peak torque over the motor's peak torque", side["peak_torque_margin"]),
                    ("motor RMS torque over the motor's rated torque", side["rated_torque_margin"]),
                    ("motor speed over the motor's maximum speed", side["speed_margin"]),
                ]
            found += [(peak.joint, what) for what, margin in checks if margin is not None and not margin >= 1.0]
        if self.base is not None:
            for wheel, torque, speed in zip(self.base.wheels, self.base.torques, self.base.speeds, strict=True):
                if not (math.isfinite(torque) and math.isfinite(speed)):
                    found.append((wheel.joint, "wheel result not a finite number"))
                for what, margin in (
                    ("wheel torque over the effort limit", self._ratio(wheel.effort, torque)),
                    ("wheel speed over the velocity limit", self._ratio(wheel.velocity, speed)),
                ):
                    if margin is not None and not margin >= 1.0:
                        found.append((wheel.joint, what))
        return found

    @property
    def failed(self) -> list[str]:
        """The joints with a margin below 1, in joint order."""
        return list(dict.fromkeys(joint for joint, _ in self.failures))

    @property
    def exit_code(self) -> int:
        return 1 if self.failed else 0

    def to_dict(self) -> dict[str, Any]:
        return {
            "$schema": SCHEMA_ID,
            "path": self.path,
            "robot": self.robot,
            "gravity": self.gravity,
            "joint_friction": self.joint_friction,
            "safety_factor": self.safety_factor,
            "convention": "torque the joint's motor must produce: tau = M(q) qddot + C(q, qdot) qdot + g(q) "
            "- J(q)^T w, w the force and moment the environment applies at a load's frame origin, world axes",
            "payloads": [
                {"frame": m.frame, "mass": m.mass, "com": list(m.com), "inertia": list(m.inertia)}
                for m in self.payloads
            ],
            "loads": [{"frame": w.frame, "force": list(w.force), "moment": list(w.moment)} for w in self.loads],
            "massless_links": list(self.massless),
            "joints": [self._joint(p) for p in self.peaks],
            "failed": self.failed,
            "failures": [{"joint": joint, "what": what} for joint, what in self.failures],
            **({"mobile": self._base()} if self.base is not None and self.base_motion is not None else {}),
            **({"motion_timing": self._timing()} if self.timing is not None else {}),
        }

    def _timing(self) -> dict[str, Any]:
        timing = self.timing
        assert timing is not None  # (to_dict asks only then)
        return {
            "segments": list(timing.segments),
            "dwell": timing.dwell,
            "cycle": timing.cycle,
            "limits_checked": {kind: list(joints) for kind, joints in timing.checked},
        }

    def _base(self) -> dict[str, Any]:
        base, asked = self.base, self.base_motion
        assert base is not None and asked is not None  # (to_dict asks only then)
        return {
            "speed": asked.speed,
            "acceleration": asked.acceleration,
            "slope": asked.slope,
            "rolling_resistance": asked.rolling_resistance,
            "mass": base.mass,
            "traction_force": base.force,
            "dynamics_check": {
                "closed_form": base.mass * (asked.acceleration + self.gravity * math.sin(asked.slope)),
                "inverse_dynamics": base.dynamics_force,
            },
            "power": base.power,
            "wheels": [
                {
                    "joint": wheel.joint,
                    "radius": wheel.radius,
                    "inertia": wheel.inertia,
                    "torque": torque,
                    "speed": speed,
                    "power": power,
                    "effort_margin": self._ratio(wheel.effort, torque),
                    "velocity_margin": self._ratio(wheel.velocity, speed),
                }
                for wheel, torque, speed, power in zip(base.wheels, base.torques, base.speeds, base.powers, strict=True)
            ],
        }

    def _joint(self, peak: StaticPeak) -> dict[str, Any]:
        entry: dict[str, Any] = {
            "name": peak.joint,
            "effort_limit": self.efforts.get(peak.joint),
            "velocity_limit": self.velocities.get(peak.joint),
            "static": {
                "peak_torque": peak.torque,
                "gravity_torque": peak.gravity_torque,
                "load_torque": peak.load_torque,
                "pose": peak.pose,
                "margin": self.margin(peak),
                "pass": (m := self.margin(peak)) is None or m >= 1.0,
            },
        }
        moved = self.motion_of(peak.joint)
        if moved is not None:
            entry["motion"] = {
                "peak_torque": moved.peak_torque,
                "rms_torque": moved.rms_torque,
                "peak_speed": moved.peak_speed,
                "peak_acceleration": moved.peak_acceleration,
                "peak_power": moved.peak_power,
                "peak_regenerative_power": moved.peak_regenerative_power,
                "energy": moved.energy,
                "motoring_energy": moved.motoring_energy,
                "peak_load_inertia": moved.peak_load_inertia,
                "effort_margin": self._ratio(self.efforts.get(peak.joint), moved.peak_torque),
                "velocity_margin": self._ratio(self.velocities.get(peak.joint), moved.peak_speed),
            }
        side = self.drive_side(peak.joint)
        if side is not None:
            entry["drive"] = side
        return entry


def format_text(report: SizeReport) -> str:
    """The terminal tables: the static worst case per joint; the motion and the drives when given."""
    lines = [
        f"{report.path}: robot {report.robot!r}, static worst case over the joints' ranges (g = {report.gravity} m/s^2)"
    ]
    for held in report.payloads:
        lines.append(f"  payload {held.mass:g} kg on {held.frame} (centre of mass {_vec(held.com)} m in it)")
    for w in report.loads:
        lines.append(f"  load on {w.frame}: force {_vec(w.force)} N, moment {_vec(w.moment)} N*m (world axes)")
    lines.append(
        f"  {'joint':<24} {'peak torque':>12} {'of it loads':>12} {'effort limit':>13} {'margin':>8}  pose (of the "
        "joints that change that torque)"
    )
    for p in report.peaks:
        effort, margin = report.efforts.get(p.joint), report.margin(p)
        flag = "" if margin is None or margin >= 1.0 else "  FAIL"
        pose = ", ".join(f"{k}={p.pose[k]:.3f}" for k in p.moving_it)  # (the JSON has every joint's value)
        lines.append(
            f"  {p.joint:<24} {p.need:>12.4g} {p.loads_need:>12.4g} "
            f"{_num(effort):>13} {_num(margin, '.3g'):>8}{flag}  {pose}".rstrip()
        )
    lines += _motion_lines(report)
    lines += _base_lines(report)
    lines.append(
        "  N*m (N for prismatic joints), rad/s, rad/s^2, W, J; peak torque: what the motor must produce, |tau| "
        "(signed in --json); margin = limit / need"
    )
    if report.massless:
        massless = ", ".join(report.massless)
        lines.append(f"  note: moving links with a shape but no <inertial> (counted as massless): {massless}")
    for joint, what in report.failures:
        lines.append(f"  FAIL {joint}: {what}")
    lines.append(f"FAILED: {', '.join(report.failed)}" if report.failed else "OK: every margin >= 1")
    return "\n".join(lines) + "\n"


def _motion_lines(report: SizeReport) -> list[str]:
    """The motion's table and the drives' motor side, when the report has them."""
    lines: list[str] = []
    if report.motions is not None:
        timing = report.timing
        said = (
            ""
            if timing is None
            else (
                f" segments of {', '.join(f'{d:.4g}' for d in timing.segments)} s"
                + (f", {timing.dwell:g} s held at each waypoint" if timing.dwell else "")
                + f"; the cycle takes {timing.cycle:.4g} s"
            )
        )
        lines.append(f"  along the motion:{said}")
        lines += _unchecked_lines(report)
        lines.append(
            "  (the joints' damping and friction included: tau += d qdot + f sign(qdot))"
            if report.joint_friction
            else "  (the joints' damping and friction left out)"
        )
        lines.append(
            f"  {'joint':<24} {'peak torque':>12} {'RMS torque':>11} {'peak speed':>11} {'peak accel':>11} "
            f"{'peak power':>11} {'regen':>9} {'energy':>9}"
        )
        for m in report.motions:
            lines.append(
                f"  {m.joint:<24} {abs(m.peak_torque):>12.4g} {m.rms_torque:>11.4g} {m.peak_speed:>11.4g} "
                f"{m.peak_acceleration:>11.4g} {m.peak_power:>11.4g} {m.peak_regenerative_power:>9.4g} {m.energy:>9.4g}"
            )
    if report.drives:
        lines.append("  motor side of the drives:")
        lines.append(f"  {'joint':<24} {'peak torque':>12} {'RMS torque':>11} {'speed':>9} {'inertia ratio':>14}")
        for joint in report.drives:
            side = report.drive_side(joint)
            if side is not None:
                lines.append(
                    f"  {joint:<24} {side['motor_peak_torque']:>12.4g} {side['motor_rms_torque']:>11.4g} "
                    f"{side['motor_peak_speed']:>9.4g} {_num(side['inertia_ratio'], '.3g'):>14}"
                )
    return lines


def _unchecked_lines(report: SizeReport) -> list[str]:
    """The limits the motion was not checked against (none given: the durations asked set it), said under its
    header; nothing when every joint's speed and acceleration limits were checked."""
    timing = report.timing
    if timing is None:
        return []
    joints = list(report.efforts)
    missing = {kind: [j for j in joints if j not in checked] for kind, checked in timing.checked}
    kinds = [kind for kind, names in missing.items() if names]
    if not kinds:
        return []
    names = {tuple(missing[kind]) for kind in kinds}
    partly = len(names) > 1 or len(next(iter(names))) < len(joints)
    whose = "; ".join(f"{kind}: {', '.join(missing[kind])}" for kind in kinds)
    said = " or ".join(kinds)
    if partly:
        return [f"  no {said} limit was given for some joints ({whose}): none checked there; the durations set it"]
    return [f"  no {said} limit was given, so none was checked: the durations set the motion"]


def _base_lines(report: SizeReport) -> list[str]:
    """The mobile base's traction and power, with its closed-form check, and each wheel's torque and speed."""
    lines: list[str] = []
    if report.base is not None and report.base_motion is not None:
        base, asked = report.base, report.base_motion
        lines.append(
            f"  mobile base: {base.mass:.4g} kg at {asked.speed:g} m/s, {asked.acceleration:g} m/s^2, slope "
            f"{math.degrees(asked.slope):.3g} deg, C_rr {asked.rolling_resistance:g}: traction {base.force:.4g} N, "
            f"power {base.power:.4g} W"
        )
        closed = base.mass * (asked.acceleration + report.gravity * math.sin(asked.slope))
        lines.append(
            f"  check: m a + m g sin(theta) = {closed:.6g} N closed form, {base.dynamics_force:.6g} N by pinocchio's "
            "inverse dynamics of the whole robot"
        )
        for wheel, torque, speed in zip(base.wheels, base.torques, base.speeds, strict=True):
            lines.append(
                f"  {wheel.joint:<24} torque {torque:.4g} N*m (limit {_num(wheel.effort)}), speed {speed:.4g} rad/s "
                f"(limit {_num(wheel.velocity)}), radius {wheel.radius:g} m"
            )
    return lines


def _num(value: float | None, spec: str = ".4g") -> str:
    return "-" if value is None else format(value, spec)


def _vec(values: tuple[float, ...]) -> str:
    return "[" + ", ".join(f"{v:g}" for v in values) + "]"
