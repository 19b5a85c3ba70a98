"""A one-line progress display on stderr for long work, shown only when stderr is a terminal.

Scripts and CI (not a TTY) see nothing; a person at a terminal sees what is going on while a fleet is built or the
consumers run, and the line is cleared when the work is done.
"""

from __future__ import annotations

import sys
from typing import TextIO


class Progress:
    def __init__(self, stream: TextIO | None = None, *, enabled: bool | None = None) -> None:
        self.stream = stream or sys.stderr
        self.enabled = self.stream.isatty() if enabled is None else enabled
        self.shown = False

    def __call__(self, message: str) -> None:
        """Replace the progress line with ``message``."""
        if self.enabled:
            self.stream.write(f"\r\033[K{message}")
            self.stream.flush()
            self.shown = True

    def done(self) -> None:
        """Clear the progress line, so the command's own output starts on a clean line."""
        if self.enabled and self.shown:
            self.stream.write("\r\033[K")
            self.stream.flush()
            self.shown = False
