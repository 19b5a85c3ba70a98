"""The error hierarchy: every error xacrokit raises on bad input derives from :class:`XacrokitError`."""

from __future__ import annotations


class XacrokitError(Exception):
    """Root of xacrokit's errors. The CLI turns these into a message and exit code 2, never a traceback."""

    exit_code = 2


class ResourceError(XacrokitError):
    """A file shipped with xacrokit (macros, templates, schemas) cannot be found: the install is broken."""


class ExpandError(XacrokitError):
    """Expanding a xacro document failed.

    Attributes:
        file: the document that was being expanded.
        message: what went wrong, as xacro (or our check) said it.
        macro_stack: names of the macros being instantiated when it failed, innermost first.
        file_stack: files being processed when it failed, innermost first.
    """

    def __init__(
        self,
        message: str,
        *,
        file: str,
        macro_stack: tuple[str, ...] = (),
        file_stack: tuple[str, ...] = (),
    ) -> None:
        self.file = file
        self.message = message
        self.macro_stack = macro_stack
        self.file_stack = file_stack
        super().__init__(str(self))

    def __str__(self) -> str:
        lines = [f"{self.file}: {self.message}"]
        lines += [f"  in macro {name}" for name in self.macro_stack]
        lines += [f"  in file {name}" for name in self.file_stack if name != self.file]
        return "\n".join(lines)
