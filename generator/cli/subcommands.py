"""The subcommands that live outside cli.py (each in its own module, its work imported when it runs): size and report,
graph, view and render, export, import, pose, jacobian and ik."""

from __future__ import annotations

from typing import Any

from .export_command import add_export_command
from .ik_command import add_ik_command
from .import_command import add_import_command
from .kinematics_commands import add_kinematics_commands
from .size_commands import add_report_command, add_size_command
from .view_commands import add_view_commands


def add_commands(commands: Any) -> None:
    """Add size, report, graph, view, render, export, import, pose, jacobian and ik to the CLI's subcommands (each
    module's ``add_*`` takes the subcommands alone: its robot options come from ``arguments.add_robot_options``)."""
    add_size_command(commands)
    add_report_command(commands)
    add_view_commands(commands)
    add_export_command(commands)
    add_import_command(commands)
    add_kinematics_commands(commands)
    add_ik_command(commands)
