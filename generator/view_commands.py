"""The commands that show a robot: ``gen-robot graph`` (its kinematic tree) and ``gen-robot render`` (a picture);
their options and outputs (the work is :mod:`xacrokit.graph` and :mod:`xacrokit.render_png`, imported when a command
runs)."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from .cliargs import parse_mappings, parse_packages


def add_view_commands(commands: Any, add_xacro_options: Callable[[argparse.ArgumentParser], None]) -> None:
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
    add_xacro_options(graph)
    graph.set_defaults(handler=_cmd_graph)


def _cmd_graph(args: argparse.Namespace) -> int:
    from .errors import XacrokitError
    from .fileio import write_text_atomic
    from .graph import graph, svg

    dot = graph(args.path, parse_mappings(args.mappings), package_paths=parse_packages(args.package))
    if not args.output:
        sys.stdout.write(dot)
        return 0
    output = Path(args.output)
    if output.suffix.lower() == ".svg":
        write_text_atomic(output, svg(dot))
    elif output.suffix.lower() in (".dot", ".gv"):
        write_text_atomic(output, dot)
    else:
        raise XacrokitError(f"-o {args.output}: write FILE.dot (or .gv) or FILE.svg")
    return 0
