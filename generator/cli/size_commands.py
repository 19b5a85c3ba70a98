"""The digital-twin commands, ``gen-robot size`` and ``gen-robot report``: their options and what they print (shells
over :func:`xacrokit.sizing.size` and :func:`xacrokit.sizing.design_report.design_report`, imported when the command
runs: the CLI starts without numpy)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import XacrokitError
from ..shared.units import UnitError, bound_problem, parse_quantity
from .arguments import add_force_option, add_robot_options, robot_input
from .json_output import print_json

if TYPE_CHECKING:
    from ..sizing import Load, Payload


def add_size_command(commands: Any) -> None:
    """Add ``size`` to the CLI's subcommands."""
    sz = commands.add_parser(
        "size",
        help="size the joints' motors: the worst static torque of each over its range, with payloads and loads",
        description="Size PATH (a URDF, xacro document or spec) with pinocchio: for every moving joint, the largest "
        "torque its motor must produce to hold the robot still anywhere in the joints' ranges (a search; the pose "
        "is shown), with payloads on named frames and forces the environment applies at named frames; margins "
        "against the URDF's effort limits (a peak torque is printed by magnitude, the need; --json keeps its sign "
        "about the joint's axis). Gravity is 9.80665 m/s^2 along -z of the root link unless --gravity or the "
        "sizing file's gravity says otherwise. Exit code 0 when "
        "every margin holds, 1 when a joint needs more than its effort limit, 2 bad input.",
    )
    sz.add_argument("path", help="a .urdf, .xacro or .yaml spec")
    sz.add_argument(
        "--payload",
        action="append",
        default=[],
        metavar="MASS@FRAME",
        help="a point mass at a frame's origin, e.g. '5 kg@tool0'; repeatable",
    )
    sz.add_argument(
        "--load",
        action="append",
        default=[],
        metavar="FX,FY,FZ@FRAME",
        help="a force (N, world axes) the "
        "environment applies at a frame's origin, e.g. '0,0,-50@tool0' (pressing down on the tool); repeatable",
    )
    # (size's loads were --force until 0.2, while --force elsewhere overwrites: kept one release, said deprecated)
    sz.add_argument("--force", action="append", default=[], metavar="FX,FY,FZ@FRAME", help="deprecated: --load")
    sz.add_argument(
        "--sizing",
        metavar="FILE",
        help="a sizing file (YAML, schemas/sizing.schema.json): payloads, loads, a motion through waypoints, drives",
    )
    sz.add_argument(
        "--gravity",
        metavar="G",
        help="gravity along -z of the root link, m/s^2 or with a unit ('9.81', '9.81 m/s2'); default the sizing "
        "file's gravity, else standard gravity 9.80665",
    )
    sz.add_argument(
        "--no-joint-friction",
        action="store_true",
        help="leave the joints' <dynamics> damping and friction out of the motion's torques (counted by default)",
    )
    sz.add_argument("--json", action="store_true", help="print the report as JSON (schemas/size-report.schema.json)")
    sz.add_argument(
        "--report", metavar="DIR", help="also write DIR/size_report.md with PNG plots of the motion and the drives"
    )
    add_force_option(sz, "--overwrite")
    add_robot_options(sz)
    sz.set_defaults(handler=_cmd_size)


def _cmd_size(args: argparse.Namespace) -> int:
    from ..reader.kinematic_model import UnknownName  # (heavy: lxml)
    from ..sizing import format_text, size  # (heavy: numpy, pinocchio)

    if args.force:
        print("gen-robot size: warning: --force is deprecated for a load: use --load", file=sys.stderr)
    payloads = [parse_payload(text) for text in args.payload]
    loads = [parse_load(text) for text in [*args.load, *args.force]]
    gravity = parse_gravity(args.gravity) if args.gravity is not None else None
    try:
        report = size(
            robot_input(args, args.path),
            payloads=payloads,
            loads=loads,
            sizing=args.sizing,
            gravity=gravity,
            joint_friction=not args.no_joint_friction,
        )
    except UnknownName as exc:
        flag = "--payload" if any(p.frame == exc.name for p in payloads) else "--load"
        raise XacrokitError(f"{flag}: {exc.detail}") from None
    if args.report:
        from ..sizing.report_document import write_report  # (heavy: jsonschema)

        write_report(report, args.report, force=args.overwrite)
    if args.json:
        print_json(report.to_dict())
    else:
        sys.stdout.write(format_text(report))
    return report.exit_code


def parse_payload(text: str) -> Payload:
    """``MASS@FRAME`` ('5 kg@tool0', '500 g@tool0'): a point mass at the frame's origin."""
    from ..sizing import Payload  # (heavy: numpy)

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
    from ..sizing.sizing_file import gravity_problem  # (heavy: numpy)

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
    from ..sizing import Load  # (heavy: numpy)

    vector, frame = _at(text, "--load", "FX,FY,FZ@FRAME in N, world axes, e.g. '0,0,-50@tool0'")
    parts = [p.strip() for p in vector.split(",")]
    unit = parts[-1].split()[-1] if parts and len(parts[-1].split()) == 2 else ""
    if len(parts) != 3:
        raise XacrokitError(f"--load {text!r}: give three components FX,FY,FZ (N, world axes), e.g. '0,0,-50@tool0'")
    try:
        force = tuple(parse_quantity(p if len(p.split()) == 2 or not unit else f"{p} {unit}", "force") for p in parts)
    except UnitError as exc:
        raise XacrokitError(f"--load {text!r}: {exc}") from None
    beyond = next((p for p in (bound_problem("force", f) for f in force) if p is not None), None)
    if beyond is not None:
        raise XacrokitError(f"--load {text!r}: {beyond}")
    return Load(frame=frame, force=(force[0], force[1], force[2]))


def _at(text: str, option: str, form: str) -> tuple[str, str]:
    value, sep, frame = text.rpartition("@")
    if not sep or not value.strip() or not frame.strip():
        raise XacrokitError(f"{option} {text!r}: expected {form}")
    return value.strip(), frame.strip()


def add_report_command(commands: Any) -> None:
    """Add ``report`` to the CLI's subcommands."""
    report = commands.add_parser(
        "report",
        help="the design report of a spec: per link shapes, volume, density, mass, centre of mass, inertia, formula",
        description="Print (or write with -o) the design report of SPEC as Markdown: per link its shapes and "
        "dimensions, volume, density, mass, centre of mass and inertia tensor with its principal moments and the "
        "formula it comes from (primitive, composite, mesh or given), and the robot's mass and centre of mass.",
    )
    report.add_argument("spec", help="the robot spec (.yaml)")
    report.add_argument("-o", "--output", help="write the Markdown here (atomically) instead of to standard output")
    add_force_option(report)
    report.set_defaults(handler=_cmd_report)


def _cmd_report(args: argparse.Namespace) -> int:
    from ..reader.read_robot import read_robot  # (heavy: lxml)
    from ..sizing.design_report import design_report, to_markdown  # (heavy: jsonschema)
    from ..write.outputs import output_file  # (start-up: a command's work loads when it runs)

    text = to_markdown(design_report(read_robot(robot_input(args, args.spec))))
    if args.output:
        output_file(Path(args.output), text, force=args.force)
    else:
        sys.stdout.write(text)
    return 0
