"""``gen-robot``: a thin command-line shell over the public Python API.

Exit codes (the same words in ``gen-robot --help``, one list: :data:`EXIT_CODES`): 0 success; 1 errors found by
``check`` (its warnings too with --strict), files refused because they were edited since generated (generate, fleet), a
margin below 1 (size) or parts not imported (import); 2 bad input or usage; 70 internal error (a bug; reported in two
lines); 130 interrupted; 141 output closed.
Errors are one located message, never a traceback.
Imports stay light here: heavy libraries load inside the commands that use them.
"""

from __future__ import annotations

import argparse
import contextlib
import difflib
import os
import re
import sys
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

from .. import __version__
from ..errors import XacrokitError
from ..shared.progress_line import Progress
from ..shared.terminal_text import controls_escaped, printable
from .arguments import (
    add_force_option,
    add_robot_options,
    add_trust_option,
    fleet_count,
    require_plain_output,
    robot_input,
    spacing,
)
from .json_output import print_json
from .subcommands import GROUPS, add_commands

if TYPE_CHECKING:
    from ..check.file_workers import CheckOptions
    from ..pipeline import GenerateResult


def _cmd_expand(args: argparse.Namespace) -> int:
    from ..expansion.xacro_expand import expand_file  # (heavy: xacro)

    given = robot_input(args, args.file)
    urdf = expand_file(given.path, given.mappings, package_paths=given.packages, trust=given.trust)
    if args.output is not None:
        from ..write.outputs import output_file  # (start-up: a command's work loads when it runs)

        output_file(Path(args.output), urdf, force=args.force)
    else:
        sys.stdout.write(urdf)
    return 0


@contextlib.contextmanager
def _progress() -> Iterator[Progress]:
    """A progress line on stderr while the work runs (on a terminal only), cleared before the command's output."""
    progress = Progress()
    try:
        yield progress
    finally:
        progress.done()


def _cmd_generate(args: argparse.Namespace) -> int:
    from ..check.document_rules import generation_warnings  # (heavy: lxml)
    from ..pipeline import generate  # (heavy: jinja2)

    if args.output is not None:
        require_plain_output(args.output, folder=True)

    with _progress() as progress:
        result = generate(
            args.spec,
            args.output,
            dry_run=args.dry_run,
            force=args.force,
            macros=args.macros,
            via_xacro=args.via_xacro,
            trust=args.trust,  # (a scene's third-party macros: --trust reaches them as the argument, nothing else)
            progress=progress,
        )
        progress("judging the URDF with check's rules")  # (the command composes: generation imports no check)
        warnings = generation_warnings(result)
    _say_warnings(warnings)
    width = max(len(a.action) for a in result.actions)
    for action in result.actions:
        note = f"  ({action.reason})" if action.reason else ""
        print(f"{action.action:<{width}}  {action.path}{note}")
    print(
        f"{result.package}: {_written(result, args.dry_run)}" + (" (dry run: nothing written)" if args.dry_run else "")
    )
    return _conflicts_exit(result)


def _print_warnings(result: GenerateResult) -> None:
    """The result's warnings (valid values that look like a units mistake, located), as :func:`_say_warnings` says
    them."""
    _say_warnings(result.warnings)


def _say_warnings(warnings: Sequence[XacrokitError]) -> None:
    """Located warnings, before the plan, so that a long plan does not hide them."""
    for warning in warnings:
        print(f"gen-robot: warning: {warning}", file=sys.stderr)


def _conflicts_exit(result: GenerateResult) -> int:
    """A dry run plans conflicts instead of stopping at them: say what the real run would refuse (exit code 1)."""
    from ..write.package_writer import ConflictError  # (start-up: a command's work loads when it runs)

    conflicts = [a for a in result.actions if a.action == "conflict"]
    if not conflicts:
        return 0
    print(f"gen-robot: error: {ConflictError(result.output, conflicts, planned=True)}", file=sys.stderr)
    return ConflictError.exit_code


def _written(result: GenerateResult, dry_run: bool) -> str:
    """'wrote 3 of 12 files in DIR', and what was removed or kept of the files no longer generated."""
    counts = {name: sum(a.action == name for a in result.actions) for name in ("remove", "keep")}
    written = sum(a.action in ("create", "update", "overwrite") for a in result.actions)
    generated = len(result.actions) - counts["remove"] - counts["keep"]
    text = f"{'would write' if dry_run else 'wrote'} {written} of {generated} files in {result.output}"
    if counts["remove"]:
        text += f"; {'would remove' if dry_run else 'removed'} {counts['remove']} no longer generated"
    if counts["keep"]:
        text += (
            f"; {'would keep' if dry_run else 'kept'} {counts['keep']} no longer generated (edited, or not removable)"
        )
    return text


def _cmd_fleet(args: argparse.Namespace) -> int:
    from ..pipeline import generate_scene  # (heavy: jinja2)
    from ..scene import fleet_scene  # (heavy: jinja2)

    if args.output is not None:
        require_plain_output(args.output, folder=True)
    columns = None
    if args.grid:
        grid = re.fullmatch(r"([0-9]{1,6})x([0-9]{1,6})", args.grid.strip().lower())  # (ASCII digits: not ²x²)
        if not grid or int(grid[1]) * int(grid[2]) < 1:
            raise XacrokitError(f"--grid expects ROWSxCOLUMNS such as 2x5, got {args.grid!r}")
        rows_text, columns_text = grid[1], grid[2]
        if int(rows_text) * int(columns_text) < args.count:
            raise XacrokitError(
                f"--grid {args.grid} has {int(rows_text) * int(columns_text)} places for {args.count} robots"
            )
        columns = int(columns_text)
    with _progress() as progress:
        progress(f"checking {args.count} copies of {Path(args.spec).name}")
        scene = fleet_scene(args.spec, args.count, columns=columns, spacing=args.spacing)
        result = generate_scene(
            scene,
            args.output,
            dry_run=args.dry_run,
            force=args.force,
            spec_name=Path(args.spec).name,
            macros=args.macros,
            via_xacro=args.via_xacro,
            progress=progress,
        )
    _print_warnings(result)
    print(
        f"{scene.package}: {len(scene.instances)} robots r0_ .. r{len(scene.instances) - 1}_; "
        + _written(result, args.dry_run)
    )
    return _conflicts_exit(result)


def _cmd_new(args: argparse.Namespace) -> int:
    from .starter import write_starter  # (heavy: jinja2)

    path = write_starter(args.name, kind=args.kind, output=args.output)
    print(f"wrote {path}; generate its package with: gen-robot {path}")
    return 0


def _cmd_check(args: argparse.Namespace) -> int:
    from ..check.consumers import chosen, warm_consumers  # (start-up: a command's work loads when it runs)

    form = "json" if args.json else args.format
    if args.jobs is not None and args.jobs < 1:
        raise XacrokitError(f"-j/--jobs {args.jobs}: give the number of worker processes, 1 or more")
    consumers = _consumers_asked(args.consumers)
    # (the paths and the name:=value words come as one list of positionals: a word with ':=' is a mapping, as xacro
    # reads its own command line)
    paths = [word for word in args.paths if ":=" not in word]
    if not paths:
        raise XacrokitError("check: give a file or folder to check (name:=value words are xacro arguments)")
    single = len(paths) == 1 and not args.robots_only and form in ("text", "json") and not Path(paths[0]).is_dir()
    # (one file: the Python consumers' children start before the rest of check loads, each importing its library
    # while this process imports ours; the check then finds them started)
    with warm_consumers(chosen(consumers) if single else []):
        from ..check.file_workers import CheckOptions  # (heavy: concurrent)

        # (one robot input's arguments, packages and trust for every file checked)
        given = robot_input(args, paths[0], mappings=[word for word in args.paths if ":=" in word] + args.mappings)
        packages = {name: Path(folder) for name, folder in given.packages.items()}
        options = CheckOptions(
            dict(given.mappings), args.prefix, consumers, packages, bool(given.trust), _srdf(args, paths)
        )
        if single:
            return _check_single(Path(paths[0]), options, form, args.strict)  # (one file: its report as before)
    return _check_many(args, paths, options, form)


def _consumers_asked(asked: str | None) -> list[str] | None:
    """--consumers: None for every installed one (all, or not given), [] for none, else the names given."""
    if asked in ("all", None):
        return None
    if asked == "none":
        return []
    return [c.strip() for c in asked.split(",") if c.strip()]


def _check_many(args: argparse.Namespace, paths: list[str], options: CheckOptions, form: str) -> int:
    """``gen-robot check PATH...``: the robot files found, checked side by side, one report of them all."""
    from ..check.file_workers import check_files, run_dict  # (heavy: concurrent)
    from ..check.robot_files import robot_files  # (heavy: lxml)

    files = robot_files(paths, exclude=args.exclude, robots_only=args.robots_only)
    if not files:
        print(f"no robot file found in {', '.join(map(printable, paths))}", file=sys.stderr)
    with _progress() as progress:
        checks = list(check_files(files, options, jobs=args.jobs, progress=progress))
    if form == "json":
        print_json(run_dict(checks, strict=args.strict))
    elif form == "sarif":
        from ..check.sarif_report import sarif_log  # (heavy: concurrent)

        print_json(sarif_log(checks))
    elif form == "junit":
        from ..check.junit_report import junit_xml  # (heavy: concurrent)

        sys.stdout.write(junit_xml(checks, strict=args.strict))
    else:
        from ..check.text_report import format_files  # (heavy: lxml)

        sys.stdout.write(format_files(checks, colour=_colour(), strict=args.strict))
    return max((check.exit_code(args.strict) for check in checks), default=0)


def _srdf(args: argparse.Namespace, paths: list[str]) -> Path | None:
    """--srdf FILE, checked: one robot file to go with it, and a file that is there."""
    if args.srdf is None:
        return None
    srdf = Path(args.srdf)
    if len(paths) != 1 or Path(paths[0]).is_dir():
        raise XacrokitError(f"--srdf {printable(args.srdf)}: an SRDF is one robot's: give it with one robot file")
    if not srdf.is_file():
        raise XacrokitError(f"--srdf {printable(args.srdf)}: no such file")
    return srdf


def _check_single(path: Path, options: CheckOptions, form: str, strict: bool) -> int:
    """``gen-robot check FILE`` (text or JSON): the file's whole report; a file that cannot be read is the command's
    error (exit 2), as it always was."""

    from ..check.text_report import format_text  # (heavy: lxml)

    with _progress() as progress:
        report = options.check(path, progress)
    if form == "json":
        print_json(report.to_dict())
    else:
        sys.stdout.write(format_text(report, colour=_colour(), strict=strict))
    return report.exit_code(strict=strict)


def _colour() -> bool:
    return sys.stdout.isatty() and "NO_COLOR" not in os.environ


def _cmd_schema(args: argparse.Namespace) -> int:
    from ..shared.package_data import schemas_dir  # (start-up: a command's work loads when it runs)

    sys.stdout.write((schemas_dir() / f"{args.kind}.schema.json").read_text(encoding="utf-8"))
    return 0


def _cmd_materials(args: argparse.Namespace) -> int:
    from ..shared.materials import ALIASES, MATERIALS  # (start-up: a command's work loads when it runs)

    width = max(len(name) for name in MATERIALS)
    for name, material in MATERIALS.items():
        print(f"{name:<{width}}  {material.density:>7g} kg/m^3  {material.grade}; {material.source}")
    if ALIASES:
        print("also: " + ", ".join(f"{alias} = {name}" for alias, name in ALIASES.items()))
    return 0


def _cmd_macros(args: argparse.Namespace) -> int:
    from ..shared.package_data import PUBLIC_MACRO_FILES, macros_dir  # (start-up: a command's work loads when it runs)

    if args.reference:
        from ..shared.macro_banners import render_reference  # (heavy: lxml)

        sys.stdout.write(render_reference())
        return 0
    folder = macros_dir()
    print(folder)
    if args.verbose:
        for name in PUBLIC_MACRO_FILES:
            print(f"  $(find xacrokit)/macros/{name}  ->  {folder / name}")
    return 0


def _add_write_options(parser: argparse.ArgumentParser, default_output: str) -> None:
    parser.add_argument("-o", "--output", help=f"package folder (default: ./{default_output})")
    parser.add_argument("--dry-run", action="store_true", help="print what would be written; write nothing")
    parser.add_argument("--force", action="store_true", help="overwrite files edited since they were generated")
    parser.add_argument(
        "--via-xacro",
        action="store_true",
        help="write urdf/NAME.urdf by expanding the package "
        "with xacro instead of emitting it directly (the same robot; slower)",
    )
    parser.add_argument(
        "--macros",
        choices=("inline", "copy", "find"),
        default="inline",
        help="how the robot macro is written: inline (default) writes the links and joints as plain XML computed by "
        "gen-robot, which xacro expands almost as fast as a plain URDF; copy calls the xacrokit library macros "
        "and copies them into the package; find calls them through $(find xacrokit) (the package then depends "
        "on xacrokit). All three describe the same robot",
    )
    add_trust_option(parser, what="every xacro expression of a scene's third-party macros")


EXIT_CODES = (
    "Exit codes: 0 success; 1 errors found (check; with --strict its warnings too), files refused because they were "
    "edited since generated (generate, fleet), a margin below 1 (size) or parts not imported (import); 2 bad input or "
    "usage; 70 internal error (a bug: please report it); "
    "130 interrupted; 141 output closed."
)


class _Parser(argparse.ArgumentParser):
    """argparse with one prefix for every error, as gen-robot's own errors have: ``gen-robot: error: ...`` (a
    command's parser said ``gen-robot fleet: error: ...`` for its option errors; its usage line still names it)."""

    def error(self, message: str) -> NoReturn:
        self.print_usage(sys.stderr)
        self.exit(2, f"gen-robot: error: {_lines(message)}\n")

    def _parse_optional(self, arg_string: str) -> Any:
        """A word that starts with '-' and then a digit, or '-.' and a digit, is a value (``--to -0.5,0.3,0.5``,
        ``--q -30deg,10deg``, ``--load -1,0,0@tool0``), never an option: argparse's own test calls only a bare
        negative number (``-1``, ``-.5``) a value, and the rest "expected one argument". No gen-robot option starts
        with a digit. (None is what argparse's classifier answers for a positional word; every command's parser is
        this class, as ``add_subparsers`` makes its parsers of its parent's class.)"""
        if _NUMBER_LIKE.match(arg_string) and arg_string not in self._option_string_actions:
            return None
        return super()._parse_optional(arg_string)


_NUMBER_LIKE = re.compile(r"-\.?[0-9]")


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """gen-robot's parser: every command's (help lists them), or ``command``'s group alone, which is all a run of it
    parses (building all 19 commands' parsers and importing their modules took about 15 ms more)."""
    parser = _Parser(
        prog="gen-robot",
        description="xacrokit: correct robot descriptions from a macro library and short YAML specs. "
        "`gen-robot SPEC.yaml [options]` is short for `gen-robot generate SPEC.yaml [options]`.",
        epilog=EXIT_CODES,
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    if command is None or command in ("generate", "fleet", "new"):
        _add_generate_commands(commands)
    if command is None or command == "check":
        _add_check_command(commands)
    if command is None or any(command in group for group in GROUPS):
        add_commands(commands, command)
    if command is None or command in ("schema", "expand", "macros", "materials"):
        _add_tool_commands(commands)
    return parser


def _add_generate_commands(commands: Any) -> None:
    """generate, fleet and new: the commands that make a package or a spec."""
    gen = commands.add_parser(
        "generate",
        help="turn a YAML robot spec into a ROS 2 description package (also: gen-robot SPEC.yaml)",
        description="Validate SPEC, render the package NAME_description (xacro macro, entry, materials, Gazebo, "
        "ros2_control, launch, RViz), write urdf/NAME.urdf (the robot expanding the package with xacro gives, "
        "emitted directly; --via-xacro runs the real xacro), and write it all. Invalid specs are reported with "
        "file:line:column and write nothing; files edited since they were generated are conflicts and stop the "
        "write unless --force; files the last run generated and this one does not are removed unless edited.",
    )
    gen.add_argument("spec", help="the robot spec (YAML; see `gen-robot schema`)")
    _add_write_options(gen, "NAME_description")
    gen.set_defaults(handler=_cmd_generate)

    fleet = commands.add_parser(
        "fleet",
        help="a scene of N copies of one robot, prefixed r0_ .. r{N-1}_, on a grid",
        description="Generate the scene package NAME_fleet_description: --count copies of the robot of SPEC with "
        "prefixes r0_, r1_, ... placed row by row on a grid in the world (x along a row, y across rows).",
    )
    fleet.add_argument("spec", help="the robot spec")
    fleet.add_argument("--count", type=fleet_count, required=True, help="how many robots (1 to 1,000)")
    fleet.add_argument("--grid", help="ROWSxCOLUMNS, e.g. 2x5 (default: a square grid)")
    fleet.add_argument(
        "--spacing",
        type=spacing,
        default=2.0,
        help="distance between neighbours: metres, or with a unit such as '150 cm' (default 2.0)",
    )
    _add_write_options(fleet, "NAME_fleet_description")
    fleet.set_defaults(handler=_cmd_fleet)

    new = commands.add_parser(
        "new", help="write a commented starter spec", description="Write NAME.yaml, a commented starter spec."
    )
    new.add_argument("name", help="robot name (letters, digits, _)")
    new.add_argument(
        "--kind", choices=("arm", "mobile", "humanoid"), default="arm", help="what to start from (default: arm)"
    )
    new.add_argument(
        "-o",
        "--output",
        help="the spec file (.yaml), or a folder for NAME.yaml (default: ./NAME.yaml); missing folders are made; an "
        "existing file is never overwritten",
    )
    new.set_defaults(handler=_cmd_new)


def _add_check_command(commands: Any) -> None:
    chk = commands.add_parser(
        "check",
        help="strictly verify a URDF, xacro document or spec (structure, joints, inertia, references, kinematics)",
        description="Check each PATH: a URDF, a xacro document (expanded with the name:=value arguments), a spec "
        "(generated in memory, never written) or a folder of them. Our rules run first, then the independent "
        "consumers check_urdf, pinocchio, yourdfpy and MuJoCo (when installed). One file gives its whole report; "
        "several give a line per file (and its errors and warnings), checked in parallel worker processes. Exit "
        "code, the worst over the files: 0 clean, 1 errors (or warnings with --strict), 2 unreadable input or usage.",
    )
    chk.add_argument(
        "paths",
        nargs="+",
        metavar="PATH",
        help="a .urdf, .xacro or .yaml spec, or a folder: searched for URDFs, xacro entries and robot and scene specs "
        "(see docs/check.md)",
    )
    form = chk.add_mutually_exclusive_group()
    form.add_argument(
        "--format",
        choices=("text", "json", "sarif", "junit"),
        default="text",
        help="the report: text (default), json (schemas/check-report.schema.json for one file, "
        "check-run.schema.json for several), sarif (SARIF 2.1.0, for code scanning) or junit (JUnit XML, a test "
        "case per file)",
    )
    form.add_argument("--json", action="store_true", help="short for --format json")
    chk.add_argument("--strict", action="store_true", help="warnings fail the check too (exit code 1)")
    _add_many_files_options(chk)
    chk.add_argument(
        "--consumers",
        metavar="LIST",
        default="all",
        help="comma list of check_urdf, pinocchio, yourdfpy, mujoco; 'all' (default: those installed) or 'none'",
    )
    chk.add_argument(
        "--prefix", help="require every link, joint, gazebo reference and ros2_control joint to start with this prefix"
    )
    chk.add_argument(
        "--srdf",
        metavar="FILE",
        help="the robot's SRDF (MoveIt's semantics): its home and disabled pairs are what G007 judges self-collision "
        "by (default: NAME.srdf beside the file, or its package's config/NAME.srdf or srdf/NAME.srdf)",
    )
    add_robot_options(chk)
    chk.set_defaults(handler=_cmd_check)


def _add_many_files_options(chk: argparse.ArgumentParser) -> None:
    chk.add_argument(
        "--exclude",
        action="append",
        default=[],
        metavar="GLOB",
        help="leave out the files found in folders whose path below the folder, or a folder's or its own name, "
        "matches GLOB (repeatable): --exclude build --exclude '*_macro.xacro'",
    )
    chk.add_argument(
        "-j",
        "--jobs",
        type=int,
        default=None,
        metavar="N",
        help="check N files at once, each in a worker process (default: the number of CPUs)",
    )
    chk.add_argument(
        "--robots-only",
        action="store_true",
        help="skip named files that are not robots, as folders do (YAML that is no robot or scene spec, xacro files "
        "of macros alone): what the pre-commit hook passes",
    )


def _add_tool_commands(commands: Any) -> None:
    """schema, expand, macros and materials."""
    schema = commands.add_parser(
        "schema",
        help="print a JSON Schema",
        description="Print the JSON Schema (2020-12) of robot specs (default), scene specs, gen-robot check's or "
        "size's JSON report, or size's sizing file.",
    )
    schema.add_argument("--kind", choices=SCHEMA_KINDS, default="robot", help="which schema")
    schema.set_defaults(handler=_cmd_schema)

    expand = commands.add_parser(
        "expand",
        help="expand a xacro file to URDF with the real xacro, $(find xacrokit) resolved without ROS",
        description="Expand FILE with the real xacro. $(find xacrokit) resolves to the installed macro library; "
        "other packages through --package, a sourced ROS workspace, or AMENT_PREFIX_PATH. "
        "Every name:=value must be declared in the document with <xacro:arg>.",
    )
    expand.add_argument("file", help="the .xacro document")
    expand.add_argument("-o", "--output", help="write the URDF here (atomically) instead of to standard output")
    add_force_option(expand)
    add_robot_options(expand)
    expand.set_defaults(handler=_cmd_expand)

    macros = commands.add_parser(
        "macros",
        help="print where the macro library is installed",
        description="Print the folder of the installed macro library (what $(find xacrokit)/macros points at).",
    )
    macros.add_argument("-v", "--verbose", action="store_true", help="also list each public macro file")
    macros.add_argument("--reference", action="store_true", help="print the Markdown macro reference instead")
    macros.set_defaults(handler=_cmd_macros)

    materials = commands.add_parser(
        "materials",
        help="list the materials a spec's density may name",
        description="Print the built-in materials a body's `density:` may name: density (kg/m^3), grade, source.",
    )
    materials.set_defaults(handler=_cmd_materials)


SCHEMA_KINDS = ("robot", "scene", "check-report", "check-run", "size-report", "sizing")
COMMANDS = tuple(
    "generate new check size report graph view render export import pose jacobian ik fleet schema expand macros "
    "materials".split()
)


def _shorthand(words: list[str]) -> bool:
    """Whether the words are `gen-robot [options] SPEC [options]`, without the word generate: no command comes first
    and a spec is named (a file that exists, or a name ending in .yaml/.yml, so that a missing one is reported)."""
    if not words or words[0] in COMMANDS or words[0] in ("-h", "--help", "--version"):
        return False

    def spec_like(word: str) -> bool:
        return not word.startswith("-") and (word.lower().endswith((".yaml", ".yml")) or Path(word).is_file())

    return spec_like(words[0]) if not words[0].startswith("-") else any(map(spec_like, words))


def _closest_options(parser: argparse.ArgumentParser, args: argparse.Namespace, unknown: list[str]) -> str:
    """'; did you mean --dry-run?' for a mistyped option of the command given (or of gen-robot itself)."""
    options = set(parser._option_string_actions)  # (argparse keeps them only there)
    for action in parser._subparsers._group_actions if parser._subparsers else ():
        chosen = getattr(action, "choices", {}).get(getattr(args, "command", None))
        if chosen is not None:
            options |= set(chosen._option_string_actions)
    close = [m for word in unknown if word.startswith("-") for m in difflib.get_close_matches(word, options, n=1)]
    return f"; did you mean {', '.join(close)}?" if close else ""


def main(argv: Sequence[str] | None = None) -> int:
    """Run ``gen-robot`` with ``argv`` (default: the process arguments); returns the exit code."""
    if sys.stdout is None or sys.stdout.closed:  # (started with its output closed: nobody reads what it says)
        return 141
    words = list(sys.argv[1:] if argv is None else argv)
    if _shorthand(words):
        words.insert(0, "generate")  # gen-robot [options] SPEC.yaml [options]
    parser = build_parser(words[0] if words and words[0] in COMMANDS else None)  # (a command's parser alone)
    if words and words[0].startswith("-") and words[0] not in ("-h", "--help", "--version"):
        parser.error(f"no spec given for {words[0]}: gen-robot SPEC.yaml [options], or gen-robot COMMAND ...")
    elif words and not words[0].startswith("-") and words[0] not in COMMANDS:
        close = difflib.get_close_matches(words[0], COMMANDS, n=1)
        hint = f"did you mean {close[0]!r}? " if close else ""
        parser.error(
            f"{words[0]!r} is neither a command nor a spec file; {hint}commands: {', '.join(COMMANDS)}, or give a "
            "spec: gen-robot SPEC.yaml"
        )
    args, unknown = parser.parse_known_args(words)
    if unknown:
        parser.error(f"unrecognized arguments: {' '.join(unknown)}{_closest_options(parser, args, unknown)}")
    if not getattr(args, "handler", None):
        parser.print_help(sys.stderr)
        return 2
    try:
        return int(args.handler(args))
    except XacrokitError as exc:
        print(f"gen-robot: error: {_lines(exc)}", file=sys.stderr)
        return exc.exit_code
    except BrokenPipeError:  # the reader went away (gen-robot schema | head): stop quietly, as other tools do
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 141
    except OSError as exc:  # the file system refused (permissions, a full disk, a missing folder): say what and where
        where = f"{exc.filename}: " if exc.filename else ""
        print(f"gen-robot: error: {printable(where)}{exc.strerror or exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 130
    except Exception as exc:  # a bug of ours, whatever the input: a short report to file, never a bare traceback
        return _internal_error(exc)


def _lines(exc: object) -> str:
    """An error's text for the terminal: its lines kept (a spec's errors, one a line), everything else outside text may
    hold escaped (an ESC or a carriage return in a file name cannot rewrite the terminal or forge a line's start)."""
    return "\n".join(controls_escaped(line) for line in str(exc).split("\n"))


INTERNAL_ERROR = 70  # EX_SOFTWARE (sysexits.h): no input may lead here; the tests feed every bad input class


def _internal_error(exc: Exception) -> int:
    """Say where a bug of ours raised: the innermost frame of the traceback (read off it, without the traceback
    module, whose import with linecache and tokenize took 5 ms of `gen-robot --help`'s start)."""
    last = exc.__traceback__
    while last is not None and last.tb_next is not None:
        last = last.tb_next
    place = f" at {Path(last.tb_frame.f_code.co_filename).name}:{last.tb_lineno}" if last else ""
    print(
        f"gen-robot: internal error (a bug in xacrokit {__version__}): {type(exc).__name__}: {exc}{place}\n"
        "gen-robot: please report it with the command you ran and the files it read",
        file=sys.stderr,
    )
    return INTERNAL_ERROR


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
