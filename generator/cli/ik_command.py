"""``gen-robot ik``: its options and what it prints (a shell over :mod:`xacrokit.kinematics`, imported when the
command runs: the CLI starts without numpy)."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from ..errors import XacrokitError
from ..shared.value_text import comment_text
from .arguments import add_robot_options
from .json_output import print_json, require_finite
from .kinematics_commands import kinematics_flags, listed_values, read_robot_of


def add_ik_command(commands: Any) -> None:
    """Add ``ik`` to the CLI's subcommands."""
    ik = commands.add_parser(
        "ik",
        help="inverse kinematics: joint values within the limits that put a frame at a pose (every branch: --all)",
        description="Find joint values within the joints' limits that put FRAME at --to X,Y,Z[,R,P,Y] (m; rad, URDF's "
        "roll, pitch, yaw; units allowed: 30deg, 100mm) in --in (default: the root link; a frame fixed to it), by "
        "damped least squares from 16 starts (pinocchio). --all lists every distinct solution (the two elbow "
        "branches of a two-link arm). Exit 0 with a solution, 1 when the target is out of reach (the closest reach "
        "is said), 2 bad input.",
    )
    ik.add_argument("robot", help="a .urdf, .xacro or .yaml spec")
    ik.add_argument("frame", help="the link or frame to place")
    ik.add_argument("--to", required=True, metavar="X,Y,Z[,R,P,Y]", help="the target pose in --in")
    ik.add_argument("--in", dest="in_frame", metavar="FRAME", help="the frame the target is given in (default: root)")
    ik.add_argument("--position-only", action="store_true", help="reach the position, any orientation")
    ik.add_argument("--all", dest="every", action="store_true", help="list every distinct solution found")
    ik.add_argument("--json", action="store_true", help="print JSON")
    add_robot_options(ik)
    ik.set_defaults(handler=_cmd_ik)


def _target(text: str) -> list[float]:
    # (start-up: a command's work loads when it runs)
    from ..shared.units import UnitError, bound_problem, parse_quantity

    parts = [p.strip() for p in text.split(",")]
    if len(parts) not in (3, 6):
        raise XacrokitError(f"--to {text!r}: give X,Y,Z or X,Y,Z,R,P,Y (m, rad)")
    try:
        values = [parse_quantity(p, "length" if k < 3 else "angle") for k, p in enumerate(parts)]
    except UnitError as exc:
        raise XacrokitError(f"--to {text!r}: {exc}") from None
    beyond = next((b for b in (bound_problem("length", v) for v in values[:3]) if b is not None), None)
    if beyond is not None:
        raise XacrokitError(f"--to {text!r}: {beyond}")
    return values


def _cmd_ik(args: argparse.Namespace) -> int:
    from ..kinematics import inverse_kinematics  # (heavy: lxml)

    target = _target(args.to)
    robot = read_robot_of(args)
    with kinematics_flags(args):
        found = inverse_kinematics(
            robot, args.frame, target, in_frame=args.in_frame, position_only=args.position_only, every=args.every
        )
    out: dict[str, Any] = {"frame": found.frame, "in": found.in_frame}
    out["solutions"] = [{"joints": values, "error": error} for values, error in found.solutions]
    if found.closest is not None:
        out["closest"] = {"joints": found.closest[0], "error": found.closest[1]}
    require_finite(out, "the search")  # (in text too: never inf or NaN as an answer)
    if args.json:
        print_json(out)
        return 0 if found.solutions else 1
    if not found.solutions and found.closest is not None:
        values, error = found.closest
        sys.stdout.write(
            f"out of reach: the closest {comment_text(found.frame)} comes is {error:.6g} away (m, or the pose error), "
            "at\n"
        )
        sys.stdout.write(listed_values(values))
        return 1
    for index, (values, error) in enumerate(found.solutions, 1):
        sys.stdout.write(f"solution {index} (error {error:.3g}):\n")
        sys.stdout.write(listed_values(values))
    return 0
