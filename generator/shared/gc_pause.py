"""Pause Python's cyclic garbage collector around allocation-heavy stages.

Loading, validating, rendering, emitting and checking a large robot allocate millions of small objects and create no
reference cycles that must be collected during the stage; the cyclic collector would rescan the growing heap again
and again, which made these stages super-linear (loading 3,000 links took 3.7x as long as 1,000). Reference counting
still frees everything as usual; the collector's previous state is restored afterwards.
"""

from __future__ import annotations

import contextlib
import gc


class collector_paused(contextlib.ContextDecorator):  # noqa: N801 - reads as a statement: with collector_paused()
    """``with collector_paused():`` or ``@collector_paused()``."""

    def __enter__(self) -> None:
        self._was_enabled = gc.isenabled()
        gc.disable()

    def __exit__(self, *exc: object) -> None:
        if self._was_enabled:
            gc.enable()
