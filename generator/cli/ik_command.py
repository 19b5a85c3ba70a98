"""``gen-robot ik``: its options and what it prints (a shell over :mod:`xacrokit.kinematics`, imported when the
command runs: the CLI starts without numpy)."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING, Any

from ..errors import XacrokitError
from ..shared.value_text import comment_text
from .arguments import add_robot_options
from .ik_targets import forms_said, target_pose
from .json_output import print_json, require_finite
from .kinematics_commands import kinematics_flags, listed_values, read_robot_of, rotation_form

if TYPE_CHECKING:
    from ..kinematics import IkSolver, Solutions


def add_ik_command(commands: Any) -> None:
    """Add ``ik`` to the CLI's subcommands."""
    ik = commands.add_parser(
        "ik",
        help="inverse kinematics: joint values within the limits that put a frame at a pose (every branch: --all)",
        description="Find joint values within the joints' limits that put FRAME at --to X,Y,Z[,orientation] (m, "
        "units allowed: 100mm; the orientation in the form --rotation names, default URDF's roll, pitch, yaw) in --in "
        "(default: the root link; a frame fixed to it). A six-joint arm with three parallel axes (Universal Robots) "
        "or a spherical wrist (KUKA, ABB, Fanuc, Staubli) is solved in closed form: --all lists every branch, named "
        "(shoulder, elbow, wrist), each by its values nearest 0 within the limits with the count of its 2 pi "
        "equivalents; any other robot by damped least squares from spread starts (pinocchio), the count said. "
        "--targets FILE solves many targets in one run. Exit 0 with a solution (for every target), 1 when a target "
        "is out of reach (the closest reach is said), 2 bad input.",
    )
    ik.add_argument("robot", help="a .urdf, .xacro or .yaml spec")
    ik.add_argument("frame", help="the link or frame to place")
    ik.add_argument("--to", metavar="X,Y,Z[,...]", help="the target pose in --in: X,Y,Z and the orientation's numbers")
    ik.add_argument(
        "--rotation",
        type=rotation_form,
        default="rpy",
        metavar="FORM",
        help=f"the form of the orientation's numbers in --to and --targets: {forms_said()} (default rpy; as pose "
        "--rotation prints them)",
    )
    ik.add_argument("--in", dest="in_frame", metavar="FRAME", help="the frame the target is given in (default: root)")
    ik.add_argument("--position-only", action="store_true", help="reach the position, any orientation")
    ik.add_argument("--all", dest="every", action="store_true", help="list every branch (every distinct solution)")
    ik.add_argument(
        "--equivalents",
        action="store_true",
        help="also list, for each solution, every set of values 2 pi apart within the limits (counted without it)",
    )
    ik.add_argument("--json", action="store_true", help="print JSON")
    add_robot_options(ik)
    ik.set_defaults(handler=_cmd_ik)


def _cmd_ik(args: argparse.Namespace) -> int:
    from ..kinematics import ik_solver  # (heavy: lxml)

    if args.to is None:
        raise XacrokitError("ik: give the target with --to X,Y,Z[,...]")
    target = target_pose(args.to, args.rotation)
    position_only = args.position_only or len(args.to.split(",")) == 3
    robot = read_robot_of(args)
    with kinematics_flags(args):
        solver = ik_solver(robot, args.frame, in_frame=args.in_frame)
        found = solver.solve(target, every=args.every, position_only=position_only)
    out = solutions_dict(found, solver if args.equivalents else None)
    require_finite(out, "the search")  # (in text too: never inf or NaN as an answer)
    if args.json:
        print_json(out)
    else:
        sys.stdout.write(solutions_text(found, solver if args.equivalents else None))
    return 0 if found.solutions else 1


def solutions_dict(found: Solutions, solver: IkSolver | None) -> dict[str, Any]:
    """What --json prints of one target's search; each solution's equivalents listed when ``solver`` is given."""
    out: dict[str, Any] = {"frame": found.frame, "in": found.in_frame, "method": found.method}
    out |= {"complete": found.complete, "starts": found.starts, "outside_limits": found.outside_limits}
    out["solutions"] = []
    for solution in found.solutions:
        said: dict[str, Any] = {"joints": solution.values, "error": solution.error}
        if solution.branch:
            said |= {"branch": solution.branch, "equivalents": solution.equivalents}
        if solution.singular:
            said["singular"] = solution.singular
        if solver is not None:
            said["equivalent_values"] = solver.equivalent_values(solution)
        out["solutions"].append(said)
    if found.closest is not None:
        out["closest"] = {"joints": found.closest.values, "error": found.closest.error}
    return out


def solutions_text(found: Solutions, solver: IkSolver | None) -> str:
    """What the text output says of one target's search."""
    frame = comment_text(found.frame)
    if not found.solutions and found.closest is not None:
        said = f"out of reach: the closest {frame} comes is {found.closest.error:.6g} away (m, or the pose error), at\n"
        return said + listed_values(found.closest.values) + _how(found) + "\n"
    lines = [_how(found)]
    for index, solution in enumerate(found.solutions, 1):
        about = [solution.branch] if solution.branch else []
        about.append(f"error {solution.error:.3g}")
        if solution.branch:
            about.append(_equivalents(solution.equivalents))
        lines.append(f"solution {index} ({'; '.join(about)}):")
        if solution.singular:
            lines.append(f"  ({solution.singular})")
        lines.append(listed_values(solution.values).rstrip("\n"))
        if solver is not None and solution.branch:
            for other in solver.equivalent_values(solution):
                lines.append("  or " + ", ".join(f"{comment_text(k)} = {v:.9f}" for k, v in other.items()))
    return "\n".join(lines) + "\n"


def _how(found: Solutions) -> str:
    if found.complete:
        left = f"; {found.outside_limits} more outside the joints' limits" if found.outside_limits else ""
        return f"{found.method}: every branch{left}"
    starts = "1 start" if found.starts == 1 else f"{found.starts} starts"
    return f"{found.method}, {starts}: the list may be incomplete"


def _equivalents(count: int) -> str:
    if count == 0:
        return "endless equivalents: a continuous joint"
    return "no other value within the limits" if count == 1 else f"{count} equivalents within the limits"
