"""The subcommands that live outside cli.py (each in its own module, its work imported when it runs): size and report,
graph, view and render, export, import, pose, jacobian and ik. A run of one command builds (and imports) that
command's group alone; help builds them all."""

from __future__ import annotations

from typing import Any

# (the commands each group's module adds, in the order help lists them)
GROUPS = (
    ("size", "report"),
    ("graph", "view", "render"),
    ("export",),
    ("import",),
    ("pose", "jacobian"),
    ("ik",),
)


def add_commands(commands: Any, command: str | None = None) -> None:
    """Add size, report, graph, view, render, export, import, pose, jacobian and ik to the CLI's subcommands (each
    module's ``add_*`` takes the subcommands alone: its robot options come from ``arguments.add_robot_options``);
    only ``command``'s group when one is named (None: all of them)."""
    wanted = [group for group in GROUPS if command is None or command in group]
    for group in wanted:
        _add_group(commands, group)


def _add_group(commands: Any, group: tuple[str, ...]) -> None:
    if group == ("size", "report"):
        from .size_commands import add_report_command, add_size_command  # (start-up: units, sizing's options)

        add_size_command(commands)
        add_report_command(commands)
    elif group == ("graph", "view", "render"):
        from .view_commands import add_view_commands  # (start-up: a group's options load when it runs)

        add_view_commands(commands)
    elif group == ("export",):
        from .export_command import add_export_command  # (start-up: a group's options load when it runs)

        add_export_command(commands)
    elif group == ("import",):
        from .import_command import add_import_command  # (start-up: a group's options load when it runs)

        add_import_command(commands)
    elif group == ("pose", "jacobian"):
        from .kinematics_commands import add_kinematics_commands  # (start-up: joint values' parsers)

        add_kinematics_commands(commands)
    else:
        from .ik_command import add_ik_command  # (start-up: the targets' readers)

        add_ik_command(commands)
