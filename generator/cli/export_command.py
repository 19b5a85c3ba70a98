"""``gen-robot export``: the robot for another program, written from its URDF (:mod:`xacrokit.export.mjcf`,
imported when the command runs). Today: MuJoCo's MJCF."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from .arguments import add_force_option, add_robot_options, robot_input


def add_export_command(commands: Any) -> None:
    """Add ``export`` to the CLI's subcommands."""
    export = commands.add_parser(
        "export",
        help="write the robot as a MuJoCo model (--mjcf): bodies named as links, actuators from ros2_control",
        description="Write PATH (a URDF, xacro document, spec or scene) as a MuJoCo MJCF model, from its URDF: every "
        "link a body of its name (massless links also sites), inertials exact, meshes copied into meshes/ next to "
        "the model (converted to binary STL, or OBJ, when MuJoCo cannot read them), mimic joints as equality "
        "constraints, actuators from the ros2_control block (position servos carrying the weight they hold), "
        "parent-child contacts excluded, every compiler setting explicit.",
    )
    export.add_argument("path", help="a .urdf, .xacro or .yaml spec")
    export.add_argument("--mjcf", action="store_true", required=True, help="write MJCF (the one format so far)")
    export.add_argument("-o", "--output", required=True, help="the model to write, e.g. robot.xml (meshes/ beside it)")
    export.add_argument(
        "--base",
        choices=["auto", "fixed", "free"],
        default="auto",
        help="each robot welded to the world (fixed) or on a free joint of its own (free: the root link, or each "
        "robot a scene hangs from world); auto (the default): free for a robot with wheels, so that it can drive",
    )
    export.add_argument(
        "--floor",
        action="store_true",
        help="add a ground plane at z = 0 (every free robot stands on z = 0 in each pose, with or without it)",
    )
    add_force_option(export)
    add_robot_options(export)
    export.set_defaults(handler=_cmd_export)


def _cmd_export(args: argparse.Namespace) -> int:
    from ..export.mjcf import export_mjcf, write_export  # (heavy: lxml)
    from ..reader.read_robot import read_robot  # (heavy: lxml)

    model = export_mjcf(read_robot(robot_input(args, args.path)), base=args.base, floor=args.floor)
    for note in model.notes:
        print(f"gen-robot export: note: {note}", file=sys.stderr)
    write_export(model, args.output, force=args.force)
    return 0
