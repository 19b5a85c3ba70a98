"""URDF's joint types and the groups the generator and check ask about (a module of its own: check reads a URDF
without loading the robot model's classes)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Literal

JointType = Literal["revolute", "continuous", "prismatic", "fixed", "floating", "planar"]
JOINT_TYPES: tuple[JointType, ...] = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")
MOVING: tuple[JointType, ...] = ("revolute", "continuous", "prismatic")  # one degree of freedom, driven by a motor
LIMITED: tuple[JointType, ...] = ("revolute", "prismatic")  # need lower and upper limits
AXIAL: tuple[JointType, ...] = ("revolute", "continuous", "prismatic", "planar")  # have an <axis> (planar: the normal)
HOME_POSE = "home"  # the named pose a robot starts in (ros2_control initial_value, the first MuJoCo keyframe)


def rest_position(lower: float | None, upper: float | None) -> float:
    """Where a joint no pose names starts: 0, moved into its limits when they exclude it (ros2_control's
    initial_value, a MuJoCo keyframe and the view page's sliders alike)."""
    if lower is None or upper is None:
        return 0.0
    return min(max(0.0, lower), upper)


def mimic_positions(positions: Mapping[str, float], mimics: Mapping[str, tuple[str, float, float]]) -> dict[str, float]:
    """``positions`` with every mimic joint's added: ``mimics`` maps a mimic joint to (leader, multiplier, offset), its
    position is offset + multiplier * the leader's, through chains (a mimic of a mimic) in any order. A leader with no
    position is at 0; a cycle (which validation and check refuse) leaves its joints out."""
    found = dict(positions)
    pending = dict(mimics)
    while pending:
        ready = [name for name, (leader, _, _) in pending.items() if leader not in pending]
        if not ready:
            break
        for name in ready:
            leader, multiplier, offset = pending.pop(name)
            found[name] = offset + multiplier * found.get(leader, 0.0)
    return found
