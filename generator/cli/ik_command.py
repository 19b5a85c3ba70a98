"""``gen-robot ik``: its options and what it prints (a shell over :mod:`xacrokit.kinematics`, imported when the
command runs: the CLI starts without numpy)."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING, Any

from ..errors import XacrokitError
from ..shared.value_text import comment_text
from .arguments import add_robot_options
from .ik_targets import forms_said, header_names, target_pose
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
        "--targets",
        metavar="FILE",
        help="many targets, one a row: a CSV (an optional header x,y,z then the orientation's names: roll,pitch,yaw; "
        "qx,qy,qz,qw; qw,qx,qy,qz; rx,ry,rz; ax,ay,az,angle; r11..r33; px..rz; a1,a2,a3) or YAML (a list of lists, or "
        "of mappings with those names); each solved on the robot read once, one solution set per row",
    )
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

    if (args.to is None) == (args.targets is None):
        raise XacrokitError("ik: give the target with --to X,Y,Z[,...], or many with --targets FILE (one of the two)")
    given: list[tuple[int | None, tuple[Any, bool]]] = []
    if args.to is not None:
        given.append((None, (target_pose(args.to, args.rotation), len(args.to.split(",")) > 3)))
    else:
        given.extend(_rows(args))
    robot = read_robot_of(args)
    out: list[dict[str, Any]] = []
    texts: list[str] = []
    reached = True
    with kinematics_flags(args):
        solver = ik_solver(robot, args.frame, in_frame=args.in_frame)
        for line, (target, oriented) in given:
            position_only = args.position_only or not oriented
            found = solver.solve(target, every=args.every, position_only=position_only)
            reached = reached and bool(found.solutions)
            said = solutions_dict(found, solver if args.equivalents else None)
            require_finite(said, "the search")  # (in text too: never inf or NaN as an answer)
            out.append({"line": line, **said} if line is not None else said)
            text = solutions_text(found, solver if args.equivalents else None)
            texts.append(text if line is None else f"target {len(texts) + 1} (line {line}):\n{text}")
    if args.json:
        print_json(out[0] if args.to is not None else {"targets": out})
    else:
        sys.stdout.write("".join(texts))
    return 0 if reached else 1


def _rows(args: argparse.Namespace) -> list[tuple[int, tuple[Any, bool]]]:
    """The targets of --targets FILE, each with its line: the row's values read as --to reads them, a header's
    names checked against the orientation's form."""
    from .rows_file import read_rows  # (start-up: a command's work loads when it runs)

    names = header_names(args.rotation)
    targets = []
    for row in read_rows(args.targets):
        where = f"{args.targets}:{row.line}:"
        values = list(row.values)
        if row.names is not None:
            given = [n.strip().lower() for n in row.names]
            if given not in (names[:3], names):
                raise XacrokitError(
                    f"{where} the columns are {', '.join(row.names)}; give {', '.join(names)} "
                    f"(or x, y, z alone) for --rotation {args.rotation}"
                )
        targets.append((row.line, (target_pose(",".join(values), args.rotation, flag=where), len(values) > 3)))
    return targets


def solutions_dict(found: Solutions, solver: IkSolver | None) -> dict[str, Any]:
    """What --json prints of one target's search; each solution's equivalents listed when ``solver`` is given."""
    out: dict[str, Any] = {"frame": found.frame, "in": found.in_frame, "method": found.method}
    out |= {"complete": found.complete, "starts": found.starts, "outside_limits": found.outside_limits}
    if found.branches:
        out["branches"] = found.branches
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
        about.append("error < 1e-10" if solution.error < 1e-10 else f"error {solution.error:.3g}")  # (--json: exact)
        if solution.branch:
            about.append(_equivalents(solution.equivalents))
        lines.append(f"solution {index} ({'; '.join(about)}):")
        if solution.singular:  # (a continuum's words name the frame: escaped as the names are)
            lines.append(f"  ({comment_text(solution.singular)})")
        lines.append(listed_values(solution.values).rstrip("\n"))
        if solver is not None and solution.branch:
            for other in solver.equivalent_values(solution):
                lines.append("  or " + ", ".join(f"{comment_text(k)} = {v:.9f}" for k, v in other.items()))
    return "\n".join(lines) + "\n"


def _how(found: Solutions) -> str:
    if found.branches:
        left = f"; {found.outside_limits} more outside the joints' limits" if found.outside_limits else ""
        if len(found.solutions) < found.branches:
            return f"{found.method}: {found.branches} branches{left}; the one nearest the rest pose (--all: every one)"
        return f"{found.method}: every branch{left}"
    starts = "1 start" if found.starts == 1 else f"{found.starts} starts"
    left = f" (the closed form's {found.outside_limits} branches are outside the joints' limits)"
    return f"{found.method}, {starts}: the list may be incomplete{left if found.outside_limits else ''}"


def _equivalents(count: int) -> str:
    if count == 0:
        return "endless equivalents: a continuous joint"
    return "no other value within the limits" if count == 1 else f"{count} equivalents within the limits"
