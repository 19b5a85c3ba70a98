"""A call with the process's standard error caught: urdfdom (inside pinocchio) prints its complaints from C++ to file
descriptor 2, which Python's own redirection does not reach, and a command's output must not carry them."""

from __future__ import annotations

import os
import sys
import tempfile
from collections.abc import Callable
from typing import Any


def quietly(call: Callable[[], Any]) -> tuple[Any, Exception | None, str]:
    """``call()`` with the process's standard error (file descriptor 2, where urdfdom's C++ prints) caught: its
    result, or the RuntimeError or ValueError it raised, and what it printed."""
    try:
        sys.stderr.flush()
        kept = os.dup(2)
    except (OSError, ValueError):  # (no standard error to catch: nothing printed reaches anyone)
        kept = None
    with tempfile.TemporaryFile() as caught:
        if kept is not None:
            os.dup2(caught.fileno(), 2)
        try:
            return call(), None, ""
        except (RuntimeError, ValueError) as exc:
            caught.seek(0)
            return None, exc, caught.read(1 << 16).decode("utf-8", errors="replace")
        finally:
            if kept is not None:
                os.dup2(kept, 2)
                os.close(kept)
