"""What a check says: findings, the consumers' verdicts, the report holding both, and the rule table they name.

Each rule family's module keeps its rows of the table beside its code and enters them here with :func:`rule_table`;
a finding reads its rule's name and severity from there. ``xacrokit.check.rule_table.RULES`` lists every row in order.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

from ..reader import InputKind

# error: a consumer rejects the file, or the physics is impossible for a body that moves; warning: a likely mistake an
# expert would fix; info: style, or what a simulator assumes when the file is silent (never fails a check)
Severity = Literal["error", "warning", "info"]
Row = tuple[str, Severity, str]  # (name, severity, what it checks)
ConsumerStatus = Literal["accepted", "rejected", "crashed", "timeout", "skipped", "unavailable"]

# rule id -> row, as each rule family's module enters it. The ids are stable: scripts may filter on them.
_ROWS: dict[str, Row] = {}


def rule_table(rows: dict[str, Row]) -> dict[str, Row]:
    """Enter a rule family's rows (id -> (name, severity, what it checks)); returns them for the family to keep."""
    taken = sorted(_ROWS.keys() & rows.keys())
    if taken:
        raise ValueError(f"rule id(s) {', '.join(taken)} entered twice; give each rule an id of its own")
    _ROWS.update(rows)
    return rows


def severity(rule: str) -> Severity:
    """The severity of a rule's findings, as its row says."""
    return _ROWS[rule][1]


@dataclass(frozen=True)
class Finding:
    rule: str
    severity: Severity
    element_kind: str  # robot, link, joint, gazebo, material, mesh, ros2_control, consumer, value (a spec's), namespace
    element: str
    message: str
    file: str | None = None
    line: int | None = None
    column: int | None = None  # (1-based, like line; None where only the line is known, or neither)

    @property
    def name(self) -> str:
        return _ROWS[self.rule][0]

    @property
    def subject(self) -> str:
        """What the finding is about, as reports say it: ``joint 'elbow'``, or the kind alone (``robot``)."""
        return f"{self.element_kind} {self.element!r}" if self.element else self.element_kind

    def place(self, source: str) -> str:
        """Where the finding is, as ``file:line:column`` (``source``, the checked file, when it names no file of its
        own; as much of the line and column as is known)."""
        where = self.file or source
        if self.line:
            where += f":{self.line}" + (f":{self.column}" if self.column else "")
        return where

    def said(self, source: str) -> str:
        """The finding on one line, as a run over many files prints it: ``file:line:column: RULE name (severity):
        subject: message``."""
        return f"{self.place(source)}: {self.rule} {self.name} ({self.severity}): {self.subject}: {self.message}"

    def to_dict(self) -> dict[str, object]:
        return {
            "rule": self.rule,
            "name": self.name,
            "severity": self.severity,
            "element": {"kind": self.element_kind, "name": self.element},
            "file": self.file,
            "line": self.line,
            "column": self.column,
            "message": self.message,
        }


@dataclass(frozen=True)
class ConsumerResult:
    """``status``: accepted, rejected, crashed, timeout, skipped or unavailable."""

    name: str
    status: ConsumerStatus
    message: str = ""

    @property
    def failed(self) -> bool:
        return self.status in ("rejected", "crashed", "timeout")


@dataclass(frozen=True)
class CheckReport:
    source: str
    kind: InputKind
    robot: str | None
    findings: tuple[Finding, ...]
    consumers: tuple[ConsumerResult, ...] = field(default=())

    @property
    def errors(self) -> list[Finding]:
        return [f for f in self.findings if f.severity == "error"]

    @property
    def warnings(self) -> list[Finding]:
        return [f for f in self.findings if f.severity == "warning"]

    @property
    def infos(self) -> list[Finding]:
        return [f for f in self.findings if f.severity == "info"]

    def exit_code(self, strict: bool = False) -> int:
        return 1 if self.errors or (strict and self.warnings) else 0

    def to_dict(self) -> dict[str, object]:
        return {
            "format": "xacrokit-check/1",
            "source": self.source,
            "kind": self.kind,
            "robot": self.robot,
            "summary": {
                "errors": len(self.errors),
                "warnings": len(self.warnings),
                "infos": len(self.infos),
                "verdict": "clean" if not self.errors else "errors",
            },
            "findings": [f.to_dict() for f in self.findings],
            "consumers": [{"name": c.name, "status": c.status, "message": c.message} for c in self.consumers],
        }
