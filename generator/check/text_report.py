"""Human-readable check reports: findings grouped by severity, consumers' verdicts, one summary line."""

from __future__ import annotations

from .findings import CheckReport, Finding
from .rule_table import RULES

_COLOURS = {"error": "\033[31m", "warning": "\033[33m", "ok": "\033[32m", "end": "\033[0m"}


def _paint(text: str, what: str, colour: bool) -> str:
    return f"{_COLOURS[what]}{text}{_COLOURS['end']}" if colour else text


def _where(finding: Finding) -> str:
    if finding.file and finding.line:
        return f" ({finding.file}:{finding.line})"
    return ""


def format_text(report: CheckReport, *, colour: bool = False, strict: bool = False) -> str:
    lines = [f"{report.source}: {report.kind}, robot {report.robot!r}"]
    for severity, findings in (("error", report.errors), ("warning", report.warnings), ("note", report.infos)):
        if findings:
            head = f"{len(findings)} {severity}{'s' if len(findings) != 1 else ''}:"
            lines.append(_paint(head, severity, colour) if severity != "note" else head)
            for f in findings:
                subject = f"{f.element_kind} {f.element!r}" if f.element else f.element_kind
                lines.append(f"  {f.rule} {f.name}: {subject}{_where(f)}: {f.message}")
    if report.consumers:
        verdicts = [
            f"{c.name} {c.status}" + (f" ({c.message})" if c.message and c.status != "accepted" else "")
            for c in report.consumers
        ]
        lines.append("consumers: " + "; ".join(verdicts))
    failed = bool(report.errors) or (strict and bool(report.warnings))
    summary = f"{len(report.errors)} error(s), {len(report.warnings)} warning(s)"
    summary += f", {len(report.infos)} note(s)" if report.infos else ""
    lines.append(_paint(("FAILED: " if failed else "OK: ") + summary, "error" if failed else "ok", colour))
    return "\n".join(lines) + "\n"


def rules_markdown() -> str:
    """The rules table of docs/check.md (between the check-rules markers)."""
    lines = ["| rule | name | severity | checks that |", "|---|---|---|---|"]
    lines += [f"| {rule} | {name} | {severity} | {text} |" for rule, (name, severity, text) in RULES.items()]
    return "\n".join(lines) + "\n"
