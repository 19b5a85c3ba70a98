"""The check stage: a strict verifier for any URDF, xacro document or spec (see :func:`check`).

Modules: ``checker`` (check), ``urdf_document`` (the URDF as check reads it), ``document_rules`` (the rules on a URDF
alone, and ``generation_warnings``: what ``gen-robot SPEC`` says of the package it wrote), one module per rule family
holding its rules and their rows of the table (``number_rules``, ``structure_rules``, ``joint_rules``,
``inertia_rules``, ``reference_rules``, ``sensor_rules``, ``spec_rules``), ``consumers`` (the independent consumers;
``consumer_host``, their host: one a worker, or one a consumer started as a check begins), ``inertia_fit`` (I008
without numpy where a link's inertia is far inside its bounds), ``rule_table`` (the whole table, RULES), ``findings``
(Finding, CheckReport), ``robot_files`` (the robots among files and folders), ``file_workers`` (many files in worker
processes) and the reports: ``text_report``, ``sarif_report``, ``junit_report``.

The names below load on first use: ``python -m xacrokit.check.consumers`` runs in a subprocess per consumer, and
importing this package must not load that module (nor the rules) before it runs.
"""

from __future__ import annotations

import sys
import types
from importlib import import_module
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .checker import check, input_kind
    from .document_rules import generation_warnings
    from .file_workers import CheckOptions, FileCheck, check_files
    from .findings import CheckReport, Finding
    from .robot_files import robot_files
    from .rule_table import RULES

__all__ = [
    "RULES",
    "CheckOptions",
    "CheckReport",
    "FileCheck",
    "Finding",
    "check",
    "check_files",
    "generation_warnings",
    "input_kind",
    "robot_files",
]

_LAZY = {
    "check": "checker",
    "input_kind": "checker",  # (the reader's, as check sees it)
    "RULES": "rule_table",
    "CheckReport": "findings",
    "Finding": "findings",
    "check_files": "file_workers",
    "CheckOptions": "file_workers",
    "FileCheck": "file_workers",
    "robot_files": "robot_files",
    "generation_warnings": "document_rules",  # (what gen-robot SPEC says: generate's warnings and check's)
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        import_module(f"{__name__}.rule_table")  # (every rule's row entered before a finding is made or named)
        value = getattr(import_module(f"{__name__}.{_LAZY[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


class _CheckPackage(types.ModuleType):
    """This package, callable as :func:`check`: ``xacrokit.check`` is both the public function and this package, and
    once any ``xacrokit.check.X`` is imported Python sets the package as the attribute ``check`` of ``xacrokit``, so
    ``xacrokit.check(path)`` must work on the package too."""

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return __getattr__("check")(*args, **kwargs)


sys.modules[__name__].__class__ = _CheckPackage
