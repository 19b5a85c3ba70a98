"""``gen-robot``: a thin command-line shell over the public Python API.

Exit codes: 0 success, 1 check findings, 2 bad input or usage. Errors are one located message, never a traceback.
Imports stay light here: heavy libraries load inside the commands that use them.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

from . import __version__
from .errors import XacrokitError


def _cmd_expand(args: argparse.Namespace) -> int:
    from .expand import expand_file, parse_mappings

    packages = {}
    for item in args.package:
        name, sep, folder = item.partition("=")
        if not sep or not name:
            raise XacrokitError(f"--package expects NAME=PATH, got {item!r}")
        packages[name] = folder
    urdf = expand_file(args.file, parse_mappings(args.mappings), package_paths=packages)
    if args.output:
        from .fileio import write_text_atomic

        write_text_atomic(Path(args.output), urdf)
    else:
        sys.stdout.write(urdf)
    return 0


def _cmd_macros(args: argparse.Namespace) -> int:
    from .resources import PUBLIC_MACRO_FILES, macros_dir

    if args.reference:
        from .macrodoc import render_reference

        sys.stdout.write(render_reference())
        return 0
    folder = macros_dir()
    print(folder)
    if args.verbose:
        for name in PUBLIC_MACRO_FILES:
            print(f"  $(find xacrokit)/macros/{name}  ->  {folder / name}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="gen-robot",
        description="xacrokit: correct robot descriptions from a macro library and short YAML specs.",
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")

    expand = commands.add_parser(
        "expand",
        help="expand a xacro file to URDF with the real xacro, $(find xacrokit) resolved without ROS",
        description="Expand FILE with the real xacro. $(find xacrokit) resolves to the installed macro library; "
        "other packages through --package, a sourced ROS workspace, or AMENT_PREFIX_PATH. "
        "Every name:=value must be declared in the document with <xacro:arg>.",
    )
    expand.add_argument("file", help="the .xacro document")
    expand.add_argument("mappings", nargs="*", metavar="name:=value", help="values for the document's xacro:args")
    expand.add_argument("-o", "--output", help="write the URDF here (atomically) instead of to standard output")
    expand.add_argument(
        "--package", action="append", default=[], metavar="NAME=PATH", help="folder for $(find NAME); repeatable"
    )
    expand.set_defaults(handler=_cmd_expand)

    macros = commands.add_parser(
        "macros",
        help="print where the macro library is installed",
        description="Print the folder of the installed macro library (what $(find xacrokit)/macros points at).",
    )
    macros.add_argument("-v", "--verbose", action="store_true", help="also list each public macro file")
    macros.add_argument("--reference", action="store_true", help="print the Markdown macro reference instead")
    macros.set_defaults(handler=_cmd_macros)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run ``gen-robot`` with ``argv`` (default: the process arguments); returns the exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "handler", None):
        parser.print_help(sys.stderr)
        return 2
    try:
        return args.handler(args)
    except XacrokitError as exc:
        print(f"gen-robot: error: {exc}", file=sys.stderr)
        return exc.exit_code
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
