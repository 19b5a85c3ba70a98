"""What ``gen-robot size`` says: per joint the worst static torque, where, what the loads add, and the margin against
the URDF's effort limit; as a table or as JSON (schemas/size-report.schema.json)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from .robot import GRAVITY, Load, Payload, SizingRobot
from .static import StaticPeak

SCHEMA_ID = "urn:xacrokit:schema:size-report:v1"


@dataclass(frozen=True)
class SizeReport:
    """The analysis of one robot: its static peaks and the loads they were computed with."""

    path: str
    robot: str
    peaks: tuple[StaticPeak, ...]
    efforts: dict[str, float | None]
    payloads: tuple[Payload, ...] = ()
    loads: tuple[Load, ...] = ()
    massless: tuple[str, ...] = field(default=())

    @staticmethod
    def of(
        path: str, robot: SizingRobot, peaks: list[StaticPeak], payloads: tuple[Payload, ...], loads: tuple[Load, ...]
    ) -> SizeReport:
        return SizeReport(
            path=path,
            robot=robot.name,
            peaks=tuple(peaks),
            efforts={j.name: j.effort for j in robot.joints},
            payloads=payloads,
            loads=loads,
            massless=tuple(robot.massless),
        )

    def margin(self, peak: StaticPeak) -> float | None:
        """The URDF's effort limit over the peak torque (>= 1 passes), None without a limit or a torque."""
        effort = self.efforts.get(peak.joint)
        if effort is None or abs(peak.torque) == 0.0:
            return None
        return effort / abs(peak.torque)

    @property
    def failed(self) -> list[str]:
        """The joints whose peak torque exceeds their effort limit."""
        return [p.joint for p in self.peaks if (m := self.margin(p)) is not None and m < 1.0]

    @property
    def exit_code(self) -> int:
        return 1 if self.failed else 0

    def to_dict(self) -> dict[str, Any]:
        return {
            "$schema": SCHEMA_ID,
            "path": self.path,
            "robot": self.robot,
            "gravity": GRAVITY,
            "convention": "torque the joint's motor must produce to hold the robot still: tau = g(q) - J(q)^T w, "
            "w the force and moment the environment applies at a load's frame origin, world axes",
            "payloads": [
                {"frame": p.frame, "mass": p.mass, "com": list(p.com), "inertia": list(p.inertia)}
                for p in self.payloads
            ],
            "loads": [{"frame": w.frame, "force": list(w.force), "moment": list(w.moment)} for w in self.loads],
            "massless_links": list(self.massless),
            "joints": [
                {
                    "name": p.joint,
                    "effort_limit": self.efforts.get(p.joint),
                    "static": {
                        "peak_torque": p.torque,
                        "gravity_torque": p.gravity_torque,
                        "load_torque": p.load_torque,
                        "pose": p.pose,
                        "margin": self.margin(p),
                        "pass": (m := self.margin(p)) is None or m >= 1.0,
                    },
                }
                for p in self.peaks
            ],
            "failed": self.failed,
        }


def format_text(report: SizeReport) -> str:
    """The terminal table: one row per joint."""
    lines = [f"{report.path}: robot {report.robot!r}, static worst case over the joints' ranges (g = {GRAVITY} m/s^2)"]
    for held in report.payloads:
        lines.append(f"  payload {held.mass:g} kg on {held.frame} (centre of mass {_vec(held.com)} m in it)")
    for w in report.loads:
        lines.append(f"  load on {w.frame}: force {_vec(w.force)} N, moment {_vec(w.moment)} N*m (world axes)")
    header = f"  {'joint':<24} {'peak torque':>12} {'of it loads':>12} {'effort limit':>13} {'margin':>8}  pose"
    lines.append(header)
    for p in report.peaks:
        effort = report.efforts.get(p.joint)
        margin = report.margin(p)
        flag = "" if margin is None or margin >= 1.0 else "  FAIL"
        pose = ", ".join(f"{k}={v:.3f}" for k, v in p.pose.items())
        lines.append(
            f"  {p.joint:<24} {p.torque:>12.4g} {p.load_torque:>12.4g} "
            f"{'-' if effort is None else f'{effort:.4g}':>13} {'-' if margin is None else f'{margin:.3g}':>8}{flag}  "
            f"{pose}"
        )
    lines.append("  torques in N*m (N for prismatic joints); the motor produces them; margin = effort limit / |peak|")
    if report.massless:
        lines.append(
            f"  note: moving links with a shape but no <inertial> (counted as massless): {', '.join(report.massless)}"
        )
    lines.append(
        f"FAILED: {', '.join(report.failed)} above their effort limit" if report.failed else "OK: every margin >= 1"
    )
    return "\n".join(lines) + "\n"


def _vec(values: tuple[float, ...]) -> str:
    return "[" + ", ".join(f"{v:g}" for v in values) + "]"
