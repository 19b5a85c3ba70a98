"""``gen-robot size``: what each joint's motor must deliver, computed on the description (pinocchio).

One module per part: :mod:`.sized_robot` (the read robot with its payloads and loads, and the conventions),
:mod:`.static` (the worst static torque of each joint over its range), :mod:`.motion` (time scaling, inverse
dynamics, inverse kinematics of pose waypoints), :mod:`.mobile` (a mobile base's wheels), :mod:`.sizing_file` (the
sizing file), :mod:`.size_results` (the table and the JSON report), :mod:`.report_document` (the Markdown report
with plots) and :mod:`.design_report` (``gen-robot report``). docs/size.md is the users' page.
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Sequence

from ..errors import SpecErrors
from ..reader.read_robot import ReadRobot
from ..reader.robot_input import RobotInput
from .mobile import base_of
from .motion import inverse_dynamics, joint_motions, planned_durations, trajectory
from .size_results import MotionTiming, SizeReport, format_text
from .sized_robot import GRAVITY, Load, Payload, loaded_robot, read_sized, require_load
from .sizing_file import Drive, Sizing, motion_of, name_errors, read_sizing
from .static import StaticPeak, static_peaks

__all__ = [
    "GRAVITY",
    "Drive",
    "Load",
    "Payload",
    "SizeReport",
    "StaticPeak",
    "format_text",
    "size",
]


def size(
    robot: ReadRobot | RobotInput | str | os.PathLike[str],
    *,
    payloads: Sequence[Payload] = (),
    loads: Sequence[Load] = (),
    sizing: str | os.PathLike[str] | None = None,
    gravity: float | None = None,
    joint_friction: bool = True,
) -> SizeReport:
    """Size the joints of a read robot (a URDF, xacro document or spec; or what to read): the worst static torque of
    each over the joints' ranges,
    with the payloads and loads given (and those of the ``sizing`` file); with the sizing file's motion, the torques,
    speeds and power along it; with its drives, the motor side. ``gravity`` (m/s^2) overrides the sizing file's
    ``gravity``; both unset, standard gravity (9.80665). ``joint_friction``: the motion's torques include the joints'
    <dynamics> damping and Coulomb friction (d qdot + f sign(qdot); the static case has qdot = 0).

    Raises:
        XacrokitError: a robot with nothing to size (and, given a path, unreadable input); UnknownName: a payload's
            or load's frame the robot lacks.
        SpecErrors: an invalid spec or sizing file (located); a spec's moving link without mass names `strict:
            false`, which sizes the robot as written.
    """
    read = read_sized(robot)
    asked = read_sizing(sizing) if sizing is not None else Sizing()
    # (gravity: the argument, else the sizing file's, else standard gravity)
    pulled = gravity if gravity is not None else asked.gravity if asked.gravity is not None else GRAVITY
    problems = name_errors(asked, loaded_robot(read, gravity=pulled))
    if problems:
        raise SpecErrors(problems)
    payloads, loads = (*payloads, *asked.payloads), (*loads, *asked.loads)
    sized = loaded_robot(read, payloads=payloads, loads=loads, gravity=pulled, joint_friction=joint_friction)
    require_load(sized, str(read.path))
    motion = motion_of(asked, sized)
    moved, samples, timing = None, None, None
    if motion is not None:
        path_samples = trajectory(motion)
        torque = inverse_dynamics(sized, path_samples)
        moved, samples = joint_motions(sized, path_samples, torque), (path_samples, torque)
        checked = tuple(
            (kind, tuple(j.name for j, limit in zip(sized.joints, limits, strict=True) if math.isfinite(limit)))
            for kind, limits in (("velocity", motion.velocity), ("acceleration", motion.acceleration))
        )
        timing = MotionTiming(tuple(planned_durations(motion)), motion.dwell, float(path_samples.t[-1]), checked)
    base = None
    if asked.mobile is not None and asked.raw is not None:
        found = base_of(sized, asked.mobile, math.fsum(p.mass for p in payloads))
        if isinstance(found, str):
            raise SpecErrors([asked.raw.error(("mobile",), found, key=True)])
        base = found
    report = SizeReport.of(sized, static_peaks(sized), moved, asked.drives)
    return dataclasses.replace(
        report, base=base, base_motion=asked.mobile, samples=samples, safety_factor=asked.safety_factor, timing=timing
    )
