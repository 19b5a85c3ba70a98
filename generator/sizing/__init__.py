"""``gen-robot size``: what each joint's motor must deliver, computed on the description (pinocchio).

One module per part: :mod:`.robot` (the model, its moving joints and loads, and the conventions), :mod:`.static` (the
worst static torque of each joint over its range), :mod:`.motion` (time scaling, inverse dynamics, inverse
kinematics of pose waypoints), :mod:`.mobile` (a mobile base's wheels), :mod:`.file` (the sizing file),
:mod:`.report` (the table and the JSON report) and :mod:`.document` (the Markdown report with plots). docs/size.md
is the users' page.
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Mapping, Sequence

from ..errors import SpecErrors, XacrokitError
from ..shared.units import UnitError, bound_problem, parse_quantity
from .mobile import base_of
from .motion import inverse_dynamics, joint_motions, planned_durations, trajectory
from .size_results import MotionTiming, SizeReport, format_text
from .sized_robot import GRAVITY, Load, Payload, add_loads, load_robot, require_load
from .sizing_file import Drive, Sizing, gravity_problem, motion_of, name_errors, read_sizing
from .static import StaticPeak, static_peaks

__all__ = [
    "GRAVITY",
    "Drive",
    "Load",
    "Payload",
    "SizeReport",
    "StaticPeak",
    "format_text",
    "parse_gravity",
    "parse_load",
    "parse_payload",
    "size",
]


def size(
    path: str | os.PathLike[str],
    mappings: Mapping[str, str] | None = None,
    *,
    payloads: Sequence[Payload] = (),
    loads: Sequence[Load] = (),
    sizing: str | os.PathLike[str] | None = None,
    package_paths: Mapping[str, str | os.PathLike[str]] | None = None,
    gravity: float | None = None,
    joint_friction: bool = True,
) -> SizeReport:
    """Size the joints of a URDF, xacro document or spec: the worst static torque of each over the joints' ranges,
    with the payloads and loads given (and those of the ``sizing`` file); with the sizing file's motion, the torques,
    speeds and power along it; with its drives, the motor side. ``gravity`` (m/s^2) overrides the sizing file's
    ``gravity``; both unset, standard gravity (9.80665). ``joint_friction``: the motion's torques include the joints'
    <dynamics> damping and Coulomb friction (d qdot + f sign(qdot); the static case has qdot = 0).

    Raises:
        XacrokitError: unreadable input, an unknown frame, or a robot with nothing to size.
        SpecErrors: an invalid spec or sizing file (located).
    """
    asked = read_sizing(sizing) if sizing is not None else Sizing()
    # (gravity: the argument, else the sizing file's, else standard gravity)
    pulled = gravity if gravity is not None else asked.gravity if asked.gravity is not None else GRAVITY
    robot = load_robot(path, mappings, package_paths=package_paths, gravity=pulled)
    robot.joint_friction = joint_friction
    problems = name_errors(asked, robot)
    if problems:
        raise SpecErrors(problems)
    payloads, loads = (*payloads, *asked.payloads), (*loads, *asked.loads)
    add_loads(robot, payloads, loads)
    require_load(robot, str(path))
    motion = motion_of(asked, robot)
    moved, samples, timing = None, None, None
    if motion is not None:
        path_samples = trajectory(motion)
        torque = inverse_dynamics(robot, path_samples)
        moved, samples = joint_motions(robot, path_samples, torque), (path_samples, torque)
        timing = MotionTiming(tuple(planned_durations(motion)), motion.dwell, float(path_samples.t[-1]))
    base = None
    if asked.mobile is not None and asked.raw is not None:
        found = base_of(robot, asked.mobile, math.fsum(p.mass for p in payloads))
        if isinstance(found, str):
            raise SpecErrors([asked.raw.error(("mobile",), found, key=True)])
        base = found
    report = SizeReport.of(str(path), robot, static_peaks(robot), payloads, loads, moved, asked.drives)
    return dataclasses.replace(
        report, base=base, base_motion=asked.mobile, samples=samples, safety_factor=asked.safety_factor, timing=timing
    )


def parse_payload(text: str) -> Payload:
    """``MASS@FRAME`` ('5 kg@tool0', '500 g@tool0'): a point mass at the frame's origin."""
    mass_text, frame = _at(text, "--payload", "MASS@FRAME, e.g. '5 kg@tool0'")
    try:
        mass = parse_quantity(mass_text, "mass")
    except UnitError as exc:
        raise XacrokitError(f"--payload {text!r}: {exc}") from None
    if not mass > 0:
        raise XacrokitError(f"--payload {text!r}: the mass must be > 0 kg")
    beyond = bound_problem("mass", mass)
    if beyond is not None:
        raise XacrokitError(f"--payload {text!r}: {beyond}")
    return Payload(frame=frame, mass=mass)


def parse_gravity(text: str) -> float:
    """``--gravity``: m/s^2 as a number or with a unit ('9.81', '9.81 m/s2'), from 0 to MOST_GRAVITY."""
    try:
        gravity = parse_quantity(text, "acceleration")
    except UnitError as exc:
        raise XacrokitError(f"--gravity {text!r}: {exc}") from None
    problem = gravity_problem(gravity)
    if problem is not None:
        raise XacrokitError(f"--gravity {text!r}: {problem}")
    return gravity


def parse_load(text: str) -> Load:
    """``FX,FY,FZ@FRAME`` ('0,0,-50 N@tool0'; each component a force, N by default): the force the environment
    applies to the robot at the frame's origin, in world axes."""
    vector, frame = _at(text, "--force", "FX,FY,FZ@FRAME in N, world axes, e.g. '0,0,-50@tool0'")
    parts = [p.strip() for p in vector.split(",")]
    unit = parts[-1].split()[-1] if parts and len(parts[-1].split()) == 2 else ""
    if len(parts) != 3:
        raise XacrokitError(f"--force {text!r}: give three components FX,FY,FZ (N, world axes), e.g. '0,0,-50@tool0'")
    try:
        force = tuple(parse_quantity(p if len(p.split()) == 2 or not unit else f"{p} {unit}", "force") for p in parts)
    except UnitError as exc:
        raise XacrokitError(f"--force {text!r}: {exc}") from None
    beyond = next((p for p in (bound_problem("force", f) for f in force) if p is not None), None)
    if beyond is not None:
        raise XacrokitError(f"--force {text!r}: {beyond}")
    return Load(frame=frame, force=(force[0], force[1], force[2]))


def _at(text: str, option: str, form: str) -> tuple[str, str]:
    value, sep, frame = text.rpartition("@")
    if not sep or not value.strip() or not frame.strip():
        raise XacrokitError(f"{option} {text!r}: expected {form}")
    return value.strip(), frame.strip()
