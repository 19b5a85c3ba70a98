"""The commands that show a robot: ``gen-robot graph`` (its kinematic tree), ``gen-robot view`` (an offline page) and
``gen-robot render`` (a picture); their options and outputs (the work is
:mod:`xacrokit.view.tree_graph`, :mod:`xacrokit.view.page` and :mod:`xacrokit.view.picture`, imported when a command
runs)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import XacrokitError
from .arguments import add_force_option, add_robot_options, robot_input

if TYPE_CHECKING:
    from ..reader.read_robot import ReadRobot


def _read(args: argparse.Namespace) -> ReadRobot:
    from ..reader.read_robot import read_robot  # (heavy: lxml)

    return read_robot(robot_input(args, args.path))


def add_view_commands(commands: Any) -> None:
    """Add ``graph`` and ``render`` to the CLI's subcommands."""
    graph = commands.add_parser(
        "graph",
        help="the kinematic tree as Graphviz DOT (SVG with -o tree.svg when Graphviz is installed)",
        description="Write the kinematic tree of PATH (a URDF, xacro document, spec or scene) as Graphviz DOT: links "
        "with their masses, joints with type, axis and limits. Without -o it prints DOT; -o FILE.dot writes it; "
        "-o FILE.svg draws it with Graphviz's dot.",
    )
    graph.add_argument("path", help="a .urdf, .xacro or .yaml spec")
    graph.add_argument("-o", "--output", help="FILE.dot or FILE.svg (written atomically)")
    add_force_option(graph)
    add_robot_options(graph)
    graph.set_defaults(handler=_cmd_graph)

    view = commands.add_parser(
        "view",
        help="an offline HTML page of the robot with a slider per joint (three.js, no network)",
        description="Write one self-contained HTML page of PATH (a URDF, xacro document, spec or scene) that opens "
        "offline from file://: the robot, a slider per moving joint (mimic joints follow), orbit with the mouse. "
        "three.js comes from the npm registry's pinned tarball, downloaded once and cached.",
    )
    view.add_argument("path", help="a .urdf, .xacro or .yaml spec")
    view.add_argument("-o", "--output", help="the HTML page to write (atomically); required without --watch")
    add_force_option(view)
    view.add_argument(
        "--watch",
        action="store_true",
        help="serve the page on 127.0.0.1 and make it again (the browser reloads) when a file in PATH's folder changes",
    )
    view.add_argument(
        "--sizing",
        metavar="FILE",
        help="a sizing file with a motion (as gen-robot size reads it): the page plays it, its torque plot beside it",
    )
    view.add_argument("--port", type=int, default=8765, help="with --watch: the port (0: any free one; default 8765)")
    add_robot_options(view)
    view.set_defaults(handler=_cmd_view)

    render = commands.add_parser(
        "render",
        help="a picture of the robot (PNG, matplotlib: no OpenGL, the same bytes every run)",
        description="Draw PATH (a URDF, xacro document, spec or scene) at the joint values given (others at 0) into "
        "a PNG, without OpenGL: its visuals placed by yourdfpy, drawn by matplotlib's Agg backend from a fixed view.",
    )
    render.add_argument("path", help="a .urdf, .xacro or .yaml spec")
    render.add_argument("-o", "--output", required=True, help="the PNG to write (atomically)")
    add_force_option(render)
    render.add_argument(
        "--joint",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="a joint's value (rad or m, or with a unit: 'elbow_joint=90 deg'); repeatable",
    )
    render.add_argument("--size", default="800x600", metavar="WxH", help="pixels (default 800x600)")
    add_robot_options(render)
    render.set_defaults(handler=_cmd_render)


def _cmd_graph(args: argparse.Namespace) -> int:
    from ..view.tree_graph import graph, svg  # (start-up: a command's work loads when it runs)
    from ..write.outputs import output_file  # (start-up: a command's work loads when it runs)

    dot = graph(_read(args))
    if not args.output:
        sys.stdout.write(dot)
        return 0
    output = Path(args.output)
    if output.suffix.lower() == ".svg":
        output_file(output, svg(dot), force=args.force)
    elif output.suffix.lower() in (".dot", ".gv"):
        output_file(output, dot, force=args.force)
    else:
        raise XacrokitError(f"-o {args.output}: write FILE.dot (or .gv) or FILE.svg")
    return 0


def _cmd_render(args: argparse.Namespace) -> int:
    from ..shared.units import UnitError, parse_quantity  # (start-up: a command's work loads when it runs)
    from ..view.picture import render  # (heavy: numpy)
    from ..write.outputs import output_file  # (start-up: a command's work loads when it runs)

    joints = {}
    for text in args.joint:
        name, sep, value = text.partition("=")
        if not sep or not name.strip():
            raise XacrokitError(f"--joint {text!r}: expected NAME=VALUE, e.g. 'elbow_joint=90 deg'")
        try:  # (an angle, or a length for a prismatic joint: '0.1 m', '50 mm')
            joints[name.strip()] = parse_quantity(value.strip(), "angle")
        except UnitError:
            try:
                joints[name.strip()] = parse_quantity(value.strip(), "length")
            except UnitError as exc:
                raise XacrokitError(f"--joint {text!r}: {exc}; give an angle or a length") from None
    try:
        width, height = (int(v) for v in args.size.lower().split("x"))
    except ValueError:
        raise XacrokitError(f"--size {args.size!r}: expected WIDTHxHEIGHT in pixels, e.g. 800x600") from None
    if not (16 <= width <= 8000 and 16 <= height <= 8000):
        raise XacrokitError(f"--size {args.size!r}: each side must be 16 to 8000 pixels")
    from ..reader.kinematic_model import UnknownName  # (heavy: lxml)

    try:
        picture = render(_read(args), joints=joints, size=(width, height))
    except UnknownName as exc:
        raise XacrokitError(f"--joint: {exc.detail}") from None
    output_file(Path(args.output), picture, force=args.force)
    return 0


def _cmd_view(args: argparse.Namespace) -> int:
    from ..view.page import page  # (heavy: lxml)
    from ..write.outputs import output_file  # (start-up: a command's work loads when it runs)

    given = robot_input(args, args.path)
    if args.watch:
        from ..reader.read_robot import read_robot  # (heavy: lxml)
        from ..view.watch_server import POLL, POLLER, Watcher  # (heavy: http)

        def build(version: int) -> str:  # (the robot read anew each time a file changes)
            poller = POLLER.format(version=version, poll=int(POLL * 1000))
            return page(read_robot(given), poller=poller, sizing=args.sizing)

        def say(message: str) -> None:
            print(f"gen-robot view: {message}", flush=True)

        Watcher(build, Path(args.path).resolve().parent).serve(args.port, announce=say)
        return 0
    if not args.output:
        raise XacrokitError("gen-robot view needs -o PAGE.html (or --watch to serve it)")
    missing: list[str] = []
    text = page(_read(args), sizing=args.sizing, missing=missing)
    for line in missing:
        print(f"gen-robot view: warning: not shown: {line}", file=sys.stderr)
    output_file(Path(args.output), text, force=args.force)
    return 0
