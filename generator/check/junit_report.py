"""``gen-robot check --format junit``: the run as JUnit XML, which CI test dashboards read (GitLab's
``artifacts:reports:junit``, Jenkins' junit step, the JUnit-report actions of GitHub).

One ``<testsuite>`` (inside ``<testsuites>``) with a ``<testcase>`` per file: its ``name`` and ``file`` are the path,
``classname`` says ``gen-robot check``, ``time`` how long the file took (seconds). Each error finding is a
``<failure>`` of the case (``type``: the rule id; ``message``: where and what; the text: the whole finding), and with
``strict`` each warning too; a file that cannot be read is an ``<error>``. A case without either passed.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from lxml import etree

from .file_workers import FileCheck

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
    failing = check.report.errors + (check.report.warnings if strict else [])
    for finding in failing:
        said = _xml_text(finding.said(check.source))
        failure = etree.SubElement(case, "failure", type=finding.rule, message=_one_line(said))
        failure.text = said
    return case


def _one_line(text: str) -> str:
    return " ".join(text.split())[:1000]


# what XML 1.0 cannot hold (control characters; the lone surrogates a file name that is not UTF-8 decodes to)
_NOT_XML = re.compile("[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def _xml_text(text: str) -> str:
    """``text`` with each character XML cannot hold as U+FFFD (a path or name from elsewhere may have them)."""
    return _NOT_XML.sub("\ufffd", text)
