"""The error hierarchy: every error xacrokit raises on bad input derives from :class:`XacrokitError`."""

from __future__ import annotations

from pathlib import Path


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


class SpecError(XacrokitError):
    """One located problem in a spec file; prints as ``spec.yaml:12:7: $.joints.elbow.limit.lower: message`` (a
    problem of the whole document, path ``$``, without the path)."""

    def __init__(self, message: str, *, file: str, path: str = "$", line: int | None = None, column: int | None = None):
        self.file = file
        self.path = path
        self.line = line
        self.column = column
        self.message = message
        super().__init__(str(self))

    def __str__(self) -> str:
        where = self.file
        if self.line is not None:
            where += f":{self.line}" + (f":{self.column}" if self.column is not None else "")
        return f"{where}: {self.message}" if self.path == "$" else f"{where}: {self.path}: {self.message}"

    def to_dict(self) -> dict[str, object]:
        return {"file": self.file, "path": self.path, "line": self.line, "column": self.column, "message": self.message}


class SpecErrors(XacrokitError):
    """Every problem found in a spec, reported together; ``errors`` is sorted by position."""

    def __init__(self, errors: list[SpecError]):
        self.errors = sorted(errors, key=lambda e: (e.file, e.line or 0, e.column or 0, e.path, e.message))
        super().__init__(str(self))

    def __str__(self) -> str:
        count = len(self.errors)
        if count == 1 and self.errors[0].line is None:  # about the file as a whole (unreadable, missing): one line
            return str(self.errors[0])
        files = {e.file for e in self.errors}  # (a spec, a sizing file, a scene and the specs it names)
        where = Path(next(iter(files))).name if len(files) == 1 else f"{len(files)} files"
        head = f"{count} problem{'s' if count != 1 else ''} in {where}:"
        return "\n".join([head, *(f"  {e}" for e in self.errors)])
