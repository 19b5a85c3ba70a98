"""The digital-twin commands, ``gen-robot size`` and ``gen-robot report``: their options and what they print (shells
over :func:`xacrokit.sizing.size` and :func:`xacrokit.sizing.design_report.design_report`, imported when the command
runs: the CLI starts without numpy)."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable
from typing import Any

from .arguments import add_force_option, parse_mappings, parse_packages


def add_size_command(commands: Any, add_xacro_options: Callable[[argparse.ArgumentParser], None]) -> None:
    """Add ``size`` to the CLI's subcommands (``add_xacro_options``: the name:=value, --package and --trust options
    every command that reads xacro takes)."""
    sz = commands.add_parser(
        "size",
        help="size the joints' motors: the worst static torque of each over its range, with payloads and loads",
        description="Size PATH (a URDF, xacro document or spec) with pinocchio: for every moving joint, the largest "
        "torque its motor must produce to hold the robot still anywhere in the joints' ranges (a search; the pose "
        "is shown), with payloads on named frames and forces the environment applies at named frames; margins "
        "against the URDF's effort limits. Gravity is 9.80665 m/s^2 along -z of the root link unless --gravity or the "
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
        "--force",
        action="append",
        default=[],
        metavar="FX,FY,FZ@FRAME",
        help="a force (N, world axes) the "
        "environment applies at a frame's origin, e.g. '0,0,-50@tool0' (pressing down on the tool); repeatable",
    )
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
    add_xacro_options(sz)
    sz.set_defaults(handler=_cmd_size)


def _cmd_size(args: argparse.Namespace) -> int:
    from ..sizing import format_text, parse_gravity, parse_load, parse_payload, size  # (numpy, pinocchio: here only)

    payloads = [parse_payload(text) for text in args.payload]
    loads = [parse_load(text) for text in args.force]
    gravity = parse_gravity(args.gravity) if args.gravity is not None else None
    report = size(
        args.path,
        parse_mappings(args.mappings),
        payloads=payloads,
        loads=loads,
        sizing=args.sizing,
        package_paths=parse_packages(args.package),
        gravity=gravity,
        joint_friction=not args.no_joint_friction,
    )
    if args.report:
        from ..sizing.report_document import write_report

        write_report(report, args.report, force=args.overwrite)
    if args.json:
        sys.stdout.write(json.dumps(report.to_dict(), indent=2) + "\n")
    else:
        sys.stdout.write(format_text(report))
    return report.exit_code


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
    from pathlib import Path

    from ..sizing.design_report import design_report, to_markdown
    from ..write.outputs import output_file

    text = to_markdown(design_report(args.spec))
    if args.output:
        output_file(Path(args.output), text, force=args.force)
    else:
        sys.stdout.write(text)
    return 0
