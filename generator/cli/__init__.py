"""``gen-robot``, the command line: a thin shell over the public Python API (``app`` parses and dispatches;
``arguments`` holds the option types; one module per group of subcommands)."""

from .app import main

__all__ = ["main"]
