"""``gen-robot check --format sarif``: the run as a SARIF 2.1.0 log, which code-scanning services read.

One run of one tool (``gen-robot check``) whose driver lists every rule of the table (its id, name, title as the short
description, what it checks as the full one, help with a link to its row of docs/check.md, and its severity as the
default level: error, warning, note), and a result per finding at its file, line and column (a finding about the whole
file, such as a consumer's refusal, at its first line). A file that cannot be read is a tool execution notification of
level error at that file, and the invocation is then not successful.

What GitHub's code scanning needs to place and track an alert (docs.github.com, "SARIF support for code scanning"):

- a file below the working folder (run check at the repository's root) is a URI relative to ``%SRCROOT%``,
  percent-encoded; a file elsewhere cannot be mapped to the repository and keeps its absolute ``file://`` URI;
- each result carries ``partialFingerprints["xacrokitFinding/v1"]``: a hash of the rule, the file, the element the
  finding concerns and its message with every number taken out, then ``:n`` for its n-th repeat in the run. It does
  not change when lines move (nor when a value changes but stays wrong), so an upload through the API, which computes
  no fingerprints, does not open the same alert again;
- messages name files below the working folder relatively and the home folder as ``~``: a runner's absolute paths
  stay out of the alerts (and out of the fingerprints, which stay the same on every machine).

Columns count Unicode code points, as the log says.
"""

from __future__ import annotations

import hashlib
import os
import re
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any
from urllib.parse import quote_from_bytes

from .. import __version__
from .file_workers import FileCheck
from .findings import Finding
from .rule_table import RULES, TITLES, anchor

SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
LEVELS = {"error": "error", "warning": "warning", "info": "note"}
# The project names no public home of its own (no URL in README.md or pyproject.toml); docs/check.md names its
# repository by this placeholder ("where you get xacrokit from"), and so do the help links: the real home is set here.
HOME = "https://example.org/your-mirror-of/xacrokit"
DOCS_URL = f"{HOME}/blob/main/docs/check.md"  # (each rule's row has an anchor there: rule_table.anchor)
SOURCE_ROOT = "%SRCROOT%"
FINGERPRINT = "xacrokitFinding/v1"
_NUMBER = re.compile(r"[-+]?\d+(?:[.,]\d+)*(?:[eE][-+]?\d+)?")


def sarif_log(checks: Sequence[FileCheck]) -> dict[str, Any]:
    """The SARIF log of a run over ``checks``, its paths relative to the working folder."""

    places = _Places(Path.cwd())
    order = {rule: index for index, rule in enumerate(RULES)}
    seen: Counter[str] = Counter()
    results = [
        _result(finding, check.source, order, places, seen)
        for check in checks
        if check.report is not None
        for finding in check.report.findings
    ]
    driver = {
        "name": "gen-robot check",
        "fullName": "xacrokit gen-robot check",
        "version": __version__,
        "informationUri": DOCS_URL,
        "rules": [_rule(rule, row) for rule, row in RULES.items()],
    }
    run = {
        "tool": {"driver": driver},
        "invocations": [_invocation(checks, places)],
        "originalUriBaseIds": {
            SOURCE_ROOT: {"description": {"text": "The working folder gen-robot check ran in (the repository's root)."}}
        },
        "results": results,
        "columnKind": "unicodeCodePoints",
    }
    return {"$schema": SARIF_SCHEMA, "version": "2.1.0", "runs": [run]}


def help_uri(rule: str) -> str:
    """Where docs/check.md says what ``rule`` checks (its row's anchor)."""
    return f"{DOCS_URL}#{anchor(rule)}"


def _rule(rule: str, row: tuple[str, str, str]) -> dict[str, Any]:
    name, severity, checks = row
    link = help_uri(rule)
    said = checks.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")  # (<robot> is no HTML tag here)
    return {
        "id": rule,
        "name": name,
        "shortDescription": {"text": TITLES[rule]},
        "fullDescription": {"text": f"Checks that {checks}."[:1024]},
        "helpUri": link,
        "help": {
            "text": f"{rule} {name} ({severity}): checks that {checks}. See {link}",
            "markdown": f"**{rule} {name}** ({severity}): checks that {said}. [docs/check.md]({link})",
        },
        "defaultConfiguration": {"level": LEVELS[severity]},
    }


def _invocation(checks: Sequence[FileCheck], places: _Places) -> dict[str, Any]:
    unread = [check for check in checks if check.report is None]
    invocation: dict[str, Any] = {"executionSuccessful": not unread}
    if unread:
        invocation["toolExecutionNotifications"] = [
            {
                "level": "error",
                "message": {"text": places.redact(check.error or "cannot be read")},
                "locations": [places.location(check.source)],
            }
            for check in unread
        ]
    return invocation


def _result(
    finding: Finding, source: str, order: dict[str, int], places: _Places, seen: Counter[str]
) -> dict[str, Any]:
    location = places.location(finding.file or source, finding.line, finding.column)
    message = places.redact(finding.message)
    artifact = location["physicalLocation"]["artifactLocation"]
    key = (finding.rule, artifact.get("uriBaseId", ""), artifact["uri"], finding.element_kind, finding.element)
    digest = hashlib.sha256("\0".join((*key, _NUMBER.sub("#", message))).encode("utf-8", "surrogatepass"))
    fingerprint = digest.hexdigest()[:32]
    seen[fingerprint] += 1  # (the same finding twice in a run: told apart by its order)
    return {
        "ruleId": finding.rule,
        "ruleIndex": order[finding.rule],
        "level": LEVELS[finding.severity],
        "message": {"text": f"{finding.subject}: {message}"},
        "locations": [location],
        "partialFingerprints": {FINGERPRINT: f"{fingerprint}:{seen[fingerprint]}"},
    }


@dataclass(frozen=True)
class _Places:
    """Files as the log names them: relative to the working folder ``root`` when below it."""

    root: Path

    def location(self, file: str, line: int | None = None, column: int | None = None) -> dict[str, Any]:
        region: dict[str, int] = {"startLine": line or 1}
        if line and column:
            region["startColumn"] = column
        return {"physicalLocation": {"artifactLocation": self.artifact(file), "region": region}}

    def artifact(self, file: str) -> dict[str, str]:
        """``file`` relative to ``%SRCROOT%`` (percent-encoded, as a URI is) when it lies below the working folder
        (as given, or with its symbolic links resolved), else its absolute ``file://`` URI."""
        given = Path(os.path.abspath(os.path.join(self.root, file)))
        for path, root in ((given, self.root), (given.resolve(), self.root.resolve())):
            if path.is_relative_to(root) and path != root:
                encoded = quote_from_bytes(os.fsencode(path.relative_to(root).as_posix()), safe="/")
                return {"uri": encoded, "uriBaseId": SOURCE_ROOT}
        return {"uri": given.as_uri()}

    def redact(self, text: str) -> str:
        """``text`` with the paths below the working folder made relative and the home folder said as ``~``."""
        home = os.path.expanduser("~")  # (left as "~" where there is none)
        for root, said in ((str(self.root), ""), (str(self.root.resolve()), ""), (home, "~/")):
            prefix = root.rstrip(os.sep) + os.sep
            if len(prefix) > 1:
                text = text.replace("file://" + prefix, said).replace(prefix, said)
        return text
