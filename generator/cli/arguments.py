"""What gen-robot's options take: argument types and checks that say what is wrong with a value (argparse shows
their messages), and the -o check, shared by the commands that write."""

from __future__ import annotations

import argparse
import os
import re
import stat
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import ExpandError, XacrokitError

if TYPE_CHECKING:
    from ..reader.robot_input import RobotInput


def require_plain_output(output: str, *, folder: bool) -> None:
    """-o must name a file (or a package folder) that is one, or nothing yet: never '' (the working folder), a device
    (-o /dev/null replaced the device with a file), a FIFO or a socket."""

    if not output.strip():
        raise XacrokitError("-o needs a path; an empty one would mean the working folder itself")
    try:
        mode = os.stat(output).st_mode
    except OSError:  # (not there yet, or not reachable: the write says which, and that nothing was written)
        return
    wanted, what = (stat.S_ISDIR, "a folder") if folder else (stat.S_ISREG, "a regular file")
    if not wanted(mode):
        raise XacrokitError(f"-o {output}: it exists and is not {what} (a device, FIFO or socket is never written)")


def add_force_option(parser: argparse.ArgumentParser, *flags: str) -> None:
    """--force (also --overwrite; ``flags`` instead when given: size's --force is a load) for a command that writes
    files: replace an existing file that gen-robot did not write there."""
    parser.add_argument(
        *(flags or ("--force", "--overwrite")),
        action="store_true",
        help="replace an output file that exists and was not written by gen-robot (or was edited since); without "
        "it such a file is kept and nothing is written (exit 2)",
    )


def parse_packages(items: list[str]) -> dict[str, str]:
    packages = {}
    for item in items:
        name, sep, folder = item.partition("=")
        if not sep or not name:
            raise XacrokitError(f"--package expects NAME=PATH, got {item!r}")
        packages[name] = folder
    return packages


FLEET_LIMIT_WHY = "every copy is written out in the URDF; a scene that large is beyond what RViz shows usefully"


def fleet_count(text: str) -> int:
    from ..scene.fleet import MAX_FLEET  # (heavy: jinja2)

    if not re.fullmatch(r"[0-9]{1,9}", text.strip()):
        raise argparse.ArgumentTypeError(f"expected a whole number (digits 0-9), got {text!r}")
    count = int(text)
    if not 1 <= count <= MAX_FLEET:
        why = f" (the limit: {FLEET_LIMIT_WHY})" if count > MAX_FLEET else ""
        raise argparse.ArgumentTypeError(f"must be 1 to {MAX_FLEET:,}, got {count:,}{why}")
    return count


def spacing(text: str) -> float:
    from ..shared.units import UnitError, parse_quantity  # (start-up: a command's work loads when it runs)

    try:
        spacing = parse_quantity(text, "length")
    except UnitError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    if not spacing > 0:
        raise argparse.ArgumentTypeError(f"must be > 0 m, got {text!r}")
    return spacing


def parse_mappings(words: list[str]) -> dict[str, str]:
    """Turn command-line words ``name:=value`` into a mapping; reject anything else with a clear message."""
    result: dict[str, str] = {}
    for word in words:
        name, sep, value = word.partition(":=")
        if not sep or not name.isidentifier():
            raise ExpandError(f"expected an argument as name:=value, got {word!r}", file="<command line>")
        result[name] = value
    return result


def add_trust_option(parser: argparse.ArgumentParser, *, what: str = "every xacro expression") -> None:
    """--trust: the one declaration of the option; what it reaches is the robot input's ``trust``
    (:func:`robot_input`) or a scene's third-party macros (generate)."""
    parser.add_argument(
        "--trust",
        action="store_true",
        help=f"evaluate {what}, as xacro does (for your own documents; by default, expressions that could reach "
        "Python's internals are refused: see docs/macros.md, Untrusted documents)",
    )


def add_robot_options(parser: argparse.ArgumentParser) -> None:
    """What every command that reads a robot takes besides its path: name:=value xacro arguments, --package and
    --trust (:func:`robot_input` makes the robot input of them)."""
    # (default=[]: argparse otherwise calls an optional list of positionals required when the path is missing)
    parser.add_argument(
        "mappings", nargs="*", default=[], metavar="name:=value", help="values for the document's xacro:args"
    )
    parser.add_argument(
        "--package",
        action="append",
        default=[],
        metavar="NAME=PATH",
        help="folder for $(find NAME) and package://NAME; repeatable",
    )
    add_trust_option(parser)


def robot_input(args: argparse.Namespace, path: str, *, mappings: list[str] | None = None) -> RobotInput:
    """The robot input of a command's arguments: ``path`` with the name:=value words (``mappings`` when the command
    parsed them itself), --package and --trust. The one place the command line makes one."""
    from ..expansion.expression_guard import trusted_by_default  # (start-up: a command's work loads when it runs)
    from ..reader.robot_input import RobotInput  # (start-up: a command's work loads when it runs)

    words = getattr(args, "mappings", []) if mappings is None else mappings
    trust = True if getattr(args, "trust", False) else trusted_by_default()
    return RobotInput(Path(path), parse_mappings(words), parse_packages(getattr(args, "package", [])), trust)
