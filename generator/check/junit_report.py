"""``gen-robot check --format junit``: the run as JUnit XML, which CI test dashboards read (GitLab's
``artifacts:reports:junit``, Jenkins' junit step, the JUnit-report actions of GitHub).

One ``<testsuite>`` (inside ``<testsuites>``) with a ``<testcase>`` per file: its ``name`` and ``file`` are the path,
``classname`` says ``gen-robot check``, ``time`` how long the file took (seconds). A file whose check fails has one
``<failure>`` (many readers show only a case's first, and GitLab makes several an array): ``type`` the rule ids it
holds, ``message`` how many findings of which rules, and its text every failing finding, a line each (its errors, and
with ``strict`` its warnings too). The warnings that do not fail it are the lines of its ``<system-out>``. A file that
cannot be read is an ``<error>``; a case with neither passed. The counts of the suite and of the suites are those of
the cases written (``failures``, ``errors``: cases; ``skipped``: none).
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from lxml import etree

from .file_workers import FileCheck
from .rule_table import RULES

SUITE = "gen-robot check"


def junit_xml(checks: Sequence[FileCheck], *, strict: bool = False) -> str:
    """The JUnit XML document of a run over ``checks``."""
    cases = [_case(check, strict) for check in checks]
    failures = sum(1 for case in cases if case.find("failure") is not None)
    errors = sum(1 for case in cases if case.find("error") is not None)
    seconds = f"{sum(check.seconds for check in checks):.3f}"
    counts = {"tests": str(len(cases)), "failures": str(failures), "errors": str(errors), "time": seconds}
    suites = etree.Element("testsuites", name=SUITE, **counts)
    suite = etree.SubElement(suites, "testsuite", name=SUITE, skipped="0", **counts)
    suite.extend(cases)
    return etree.tostring(
        suites, encoding="unicode", pretty_print=True, doctype='<?xml version="1.0" encoding="UTF-8"?>'
    )


def _case(check: FileCheck, strict: bool) -> etree._Element:
    source = _xml_text(check.source)
    case = etree.Element("testcase", classname=SUITE, name=source, file=source, time=f"{check.seconds:.3f}")
    if check.report is None:
        said = _xml_text(check.error or "cannot be read")
        error = etree.SubElement(case, "error", type="unreadable", message=_one_line(said))
        error.text = said
        return case
    errors, warnings = check.report.errors, check.report.warnings
    failing = errors + (warnings if strict else [])
    if failing:
        rules = list(dict.fromkeys(finding.rule for finding in failing))  # (each once, in the findings' order)
        counts = f"{len(errors)} error(s)" + (f", {len(warnings)} warning(s)" if strict else "")
        named = ", ".join(f"{rule} {RULES[rule][0]}" for rule in rules)
        failure = etree.SubElement(case, "failure", type=",".join(rules), message=_one_line(f"{counts}: {named}"))
        failure.text = "\n".join(_xml_text(finding.said(check.source)) for finding in failing)
    if warnings and not strict:  # (visible, and failing nothing)
        etree.SubElement(case, "system-out").text = "\n".join(_xml_text(f.said(check.source)) for f in warnings)
    return case


def _one_line(text: str) -> str:
    return " ".join(text.split())[:1000]


# what XML 1.0 cannot hold (control characters; the lone surrogates a file name that is not UTF-8 decodes to)
_NOT_XML = re.compile("[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def _xml_text(text: str) -> str:
    """``text`` with each character XML cannot hold as U+FFFD (a path or name from elsewhere may have them)."""
    return _NOT_XML.sub("\ufffd", text)
