"""Human-readable check reports: findings grouped by severity, consumers' verdicts, one summary line.

Every piece of outside text a report prints (file names, names from the robot in messages, a consumer's words, why a
file cannot be read) goes through :func:`~xacrokit.shared.terminal_text.printable`: a name's ESC or newline can neither
drive the terminal nor forge a report line. (A subject's and the robot's names are quoted with repr, which escapes
them already.)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import TYPE_CHECKING

from ..shared.terminal_text import printable
from .findings import CheckReport, Finding
from .rule_table import RULES

if TYPE_CHECKING:
    from .file_workers import FileCheck

_COLOURS = {"error": "\033[31m", "warning": "\033[33m", "ok": "\033[32m", "end": "\033[0m"}


def _paint(text: str, what: str, colour: bool) -> str:
    return f"{_COLOURS[what]}{text}{_COLOURS['end']}" if colour else text


def _where(finding: Finding) -> str:
    if finding.file and finding.line:
        return f" ({printable(finding.place(finding.file))})"
    return ""


def format_text(report: CheckReport, *, colour: bool = False, strict: bool = False) -> str:
    lines = [f"{printable(report.source)}: {report.kind}, robot {report.robot!r}"]
    for severity, findings in (("error", report.errors), ("warning", report.warnings), ("note", report.infos)):
        if findings:
            head = f"{len(findings)} {severity}{'s' if len(findings) != 1 else ''}:"
            lines.append(_paint(head, severity, colour) if severity != "note" else head)
            for f in findings:
                lines.append(f"  {f.rule} {f.name}: {f.subject}{_where(f)}: {printable(f.message)}")
    if report.consumers:
        verdicts = [
            f"{c.name} {c.status}" + (f" ({printable(c.message)})" if c.message and c.status != "accepted" else "")
            for c in report.consumers
        ]
        lines.append("consumers: " + "; ".join(verdicts))
    failed = report.exit_code(strict) == 1
    lines.append(_paint(_verdict(report, failed), "error" if failed else "ok", colour))
    return "\n".join(lines) + "\n"


def format_files(checks: Sequence[FileCheck], *, colour: bool = False, strict: bool = False) -> str:
    """A run over many files: a summary line per file (its errors and warnings below it, one line each, at
    file:line:column), then a line for the run."""
    lines = []
    for check in checks:
        source = printable(check.source)
        if check.report is None:
            lines.append(_paint(f"{source}: UNREADABLE: ", "error", colour) + printable(check.error or ""))
            continue
        report = check.report
        failed = report.exit_code(strict) == 1
        lines.append(f"{source}: " + _paint(_verdict(report, failed), "error" if failed else "ok", colour))
        for f in [*report.errors, *report.warnings]:
            shown = replace(f, file=f.file and printable(f.file), message=printable(f.message))
            lines.append(f"  {shown.said(source)}")
    codes = [c.exit_code(strict) for c in checks]
    tally = f"{len(checks)} file(s) checked: {codes.count(0)} passed, {codes.count(1)} failed"
    lines.append(tally + (f", {codes.count(2)} unreadable" if 2 in codes else ""))
    return "\n".join(lines) + "\n"


def _verdict(report: CheckReport, failed: bool) -> str:
    summary = f"{len(report.errors)} error(s), {len(report.warnings)} warning(s)"
    summary += f", {len(report.infos)} note(s)" if report.infos else ""
    return ("FAILED: " if failed else "OK: ") + summary


def rules_markdown() -> str:
    """The rules table of docs/check.md (between the check-rules markers)."""
    lines = ["| rule | name | severity | checks that |", "|---|---|---|---|"]
    lines += [f"| {rule} | {name} | {severity} | {text} |" for rule, (name, severity, text) in RULES.items()]
    return "\n".join(lines) + "\n"
