"""``gen-robot check --format sarif``: the run as a SARIF 2.1.0 log, which code-scanning services read.

One run of one tool (``gen-robot check``) whose driver lists every rule of the table (its id, name, a short and a
full description, help, and its severity as the default level: error, warning, note), and a result per finding at
its file, line and column (a finding about the whole file, such as a consumer's refusal, at its first line). A file
that cannot be read is a tool execution notification of level error at that file, and the invocation is then not
successful. Paths are written relative to the working folder when they lie below it (code scanning reads them from
the repository's root), else as ``file://`` URIs. Columns count Unicode code points, as the log says.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from .. import __version__
from .file_workers import FileCheck
from .findings import Finding
from .rule_table import RULES

SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
LEVELS = {"error": "error", "warning": "warning", "info": "note"}
DOCS = "docs/check.md"  # (the rules table, and what each rule checks)


def sarif_log(checks: Sequence[FileCheck]) -> dict[str, Any]:
    """The SARIF log of a run over ``checks``."""

    order = {rule: index for index, rule in enumerate(RULES)}
    results = [
        _result(finding, check.source, order)
        for check in checks
        if check.report is not None
        for finding in check.report.findings
    ]
    unread = [check for check in checks if check.report is None]
    invocation: dict[str, Any] = {"executionSuccessful": not unread}
    if unread:
        invocation["toolExecutionNotifications"] = [
            {"level": "error", "message": {"text": c.error or "cannot be read"}, "locations": [_location(c.source)]}
            for c in unread
        ]
    driver = {
        "name": "gen-robot check",
        "fullName": "xacrokit gen-robot check",
        "version": __version__,
        "rules": [_rule(rule, row) for rule, row in RULES.items()],
    }
    run = {"tool": {"driver": driver}, "invocations": [invocation], "results": results}
    run["columnKind"] = "unicodeCodePoints"
    return {"$schema": SARIF_SCHEMA, "version": "2.1.0", "runs": [run]}


def _rule(rule: str, row: tuple[str, str, str]) -> dict[str, Any]:
    name, severity, checks = row
    text = f"{rule} {name} ({severity}): checks that {checks}."
    said = checks.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")  # (<robot> is no HTML tag here)
    return {
        "id": rule,
        "name": name,
        "shortDescription": {"text": _clause(checks)},
        "fullDescription": {"text": f"Checks that {checks}."[:1024]},
        "help": {"text": f"{text} See {DOCS} (rule {rule}).", "markdown": f"**{rule} {name}** ({severity}): {said}."},
        "defaultConfiguration": {"level": LEVELS[severity]},
    }


def _clause(text: str) -> str:
    """The first clause of what a rule checks (up to its first ';' or ' ('), as a short description."""
    cut = min((i for i in (text.find(";"), text.find(" (")) if i > 0), default=len(text))
    return text[:cut][:1024]


def _result(finding: Finding, source: str, order: dict[str, int]) -> dict[str, Any]:
    return {
        "ruleId": finding.rule,
        "ruleIndex": order[finding.rule],
        "level": LEVELS[finding.severity],
        "message": {"text": f"{finding.subject}: {finding.message}"},
        "locations": [_location(finding.file or source, finding.line, finding.column)],
    }


def _location(file: str, line: int | None = None, column: int | None = None) -> dict[str, Any]:
    region: dict[str, int] = {"startLine": line or 1}
    if line and column:
        region["startColumn"] = column
    return {"physicalLocation": {"artifactLocation": {"uri": _uri(file)}, "region": region}}


def _uri(file: str) -> str:
    path = Path(file)
    absolute = path.resolve() if not path.is_absolute() else path
    try:
        return absolute.relative_to(Path.cwd().resolve()).as_posix()
    except ValueError:
        return absolute.as_uri()
