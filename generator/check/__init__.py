"""The check stage: a strict verifier for any URDF, xacro document or spec (see :func:`check`).

Modules: ``run`` (check, input_kind), ``document`` (the URDF reader), one module per rule family holding its rules and
their rows of the table (``numbers``, ``structure``, ``joints``, ``inertia``, ``references``, ``spec``), ``consumers``
(the independent consumers), ``rules`` (the whole table, RULES), ``findings`` (Finding, CheckReport) and ``report``
(the text form).

The names below load on first use: ``python -m xacrokit.check.consumers`` runs in a subprocess per consumer, and
importing this package must not load that module (nor the rules) before it runs.
"""

from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .findings import CheckReport, Finding
    from .rules import RULES
    from .run import check, input_kind

__all__ = ["RULES", "CheckReport", "Finding", "check", "input_kind"]

_LAZY = {
    "check": "run",
    "input_kind": "run",
    "RULES": "rules",
    "CheckReport": "findings",
    "Finding": "findings",
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        import_module(f"{__name__}.rules")  # (every rule's row entered before a finding is made or named)
        value = getattr(import_module(f"{__name__}.{_LAZY[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
