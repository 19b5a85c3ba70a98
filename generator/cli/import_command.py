"""``gen-robot import``: a URDF or xacro document as a robot spec (:mod:`xacrokit.importer.urdf_to_spec`,
imported when the command runs)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from ..errors import XacrokitError
from .arguments import add_force_option, add_robot_options, robot_input


def add_import_command(commands: Any) -> None:
    """Add ``import`` to the CLI's subcommands."""
    imported = commands.add_parser(
        "import",
        help="read a URDF or xacro document back as a robot spec (links, joints, colours, inertials, meshes)",
        description="Write the robot spec of FILE (a URDF or xacro document with its name:=value arguments): each "
        "link's shape, origin, colour, collision and inertial, each joint with its limits, dynamics, mimic and safety "
        "controller, numbers exact. What the spec cannot say is listed at the top of the spec and on standard error, "
        "and the exit code is 1; a robot the spec refuses (a cycle, a link with two parents, a mimic cycle) is an "
        "error, exit 2, and nothing is written.",
    )
    imported.add_argument("path", help="a .urdf or .xacro file")
    imported.add_argument("-o", "--output", help="the spec to write (atomically); standard output without it")
    add_force_option(imported)
    add_robot_options(imported)
    imported.set_defaults(handler=_cmd_import)


def _cmd_import(args: argparse.Namespace) -> int:
    from ..importer.urdf_to_spec import import_robot, spec_yaml  # (heavy: lxml)
    from ..reader.read_robot import read_robot  # (heavy: lxml)
    from ..write.outputs import OutputFile, write_outputs  # (start-up: a command's work loads when it runs)

    result = import_robot(read_robot(robot_input(args, args.path)))
    if result.refused:  # (the spec written would not generate: nothing is written, exit 2; every reason said)
        raise XacrokitError(
            f"{args.path}: the robot cannot be imported, the spec refuses it:\n  " + "\n  ".join(result.unsupported)
        )
    for line in result.unsupported:
        print(f"gen-robot import: not imported: {line}", file=sys.stderr)
    if result.renamed:
        print(f"gen-robot import: renamed: {result.renamed}", file=sys.stderr)
    for line in result.ignored:
        print(f"gen-robot import: not URDF, ignored by its readers: {line}", file=sys.stderr)
    for line in result.as_given:
        print(f"gen-robot import: kept as the file says it (strict: false): {line}", file=sys.stderr)
    if args.output and result.extension:  # (the left-out elements, verbatim, beside the spec)
        extension = Path(args.output).with_name(Path(args.output).stem + "_extension.xacro")
        result.spec["extension"] = extension.name
    text = spec_yaml(result, str(args.path))
    if args.output:
        target = Path(args.output)
        files = [OutputFile(target.name, text)]
        if result.extension:
            files.append(OutputFile(extension.name, result.extension))
        files += [OutputFile(relative, data) for relative, data in result.meshes.items()]  # (beside the spec)
        write_outputs(target.parent, files, force=args.force)
    else:
        if result.meshes:
            print(
                f"gen-robot import: the spec names {len(result.meshes)} mesh(es) under meshes/ that -o SPEC copies "
                "beside it",
                file=sys.stderr,
            )
        sys.stdout.write(text)
    return 1 if result.unsupported else 0  # (written, but not all of it: the list above, and in the spec's header)
