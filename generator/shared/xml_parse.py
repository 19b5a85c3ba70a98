"""The one hardened XML parse: every URDF, package.xml, extension file or expanded document xacrokit reads goes
through :func:`parser` (no entities resolved, no DTD loaded, no network, no huge trees).

A URDF that uses a namespace prefix it never declares (``<limit drake:acceleration="..."/>``) is read the way every
URDF consumer reads it: past the undeclared names. :func:`parse_urdf` says which prefixes those were and where, and
keeps the document (check reports them as U003)."""

from __future__ import annotations

from dataclasses import dataclass, field

from lxml import etree

from ..errors import XacrokitError


def parser(*, recover: bool = False, comments: bool = True) -> etree.XMLParser:
    """A parser for a file from elsewhere: no entity is resolved (no file or URL is read through one), no DTD is
    loaded, nothing is fetched, and libxml2's limits for huge documents stay on. ``recover`` reads past faults (only
    used once a strict parse has said that undeclared prefixes were the only ones); ``comments`` keeps them."""
    return etree.XMLParser(
        resolve_entities=False,
        no_network=True,
        load_dtd=False,
        huge_tree=False,
        recover=recover,
        remove_comments=not comments,
    )


def parse_xml(data: str | bytes, where: str) -> etree._Element:
    """The root element of a well-formed XML document.

    Raises:
        XacrokitError: not well-formed (located: ``where:line:column``).
    """
    raw = data.encode("utf-8") if isinstance(data, str) else data
    try:
        return etree.fromstring(raw, parser())
    except etree.XMLSyntaxError as exc:
        line, column = exc.position
        raise XacrokitError(f"{where}:{line}:{column}: not well-formed XML: {exc.msg}") from None


@dataclass(frozen=True)
class ParsedUrdf:
    """A URDF text as parsed: its ``<robot>`` root (None when there is none), why not (``error``, ``error_line``),
    and each namespace prefix used without a declaration with the line it is first used on."""

    root: etree._Element | None
    error: str = ""
    error_line: int | None = None
    error_column: int | None = None
    undeclared: dict[str, int] = field(default_factory=dict)

    def where(self, file: str) -> str:
        """``file:line:column`` of the error (as much of it as is known)."""
        place = f"{file}:{self.error_line or 1}"
        return place + (f":{self.error_column}" if self.error_column else "")


def parse_urdf(text: str) -> ParsedUrdf:
    """Parse a URDF text strictly; when its only faults are undeclared namespace prefixes, read past them (as every
    URDF consumer does) and name them."""
    data = text.encode("utf-8")
    strict = parser()
    try:
        root = etree.fromstring(data, strict)
        undeclared: dict[str, int] = {}
    except etree.XMLSyntaxError as exc:
        log = strict.error_log  # (this parse's own: the exception's may hold earlier parses' errors of the thread)
        if not log or any(e.domain_name != "NAMESPACE" for e in log):
            line, column = exc.position
            return ParsedUrdf(None, f"not well-formed XML: {exc.msg}", line, column)
        root = etree.fromstring(data, parser(recover=True))
        undeclared = _undeclared_prefixes(log)
    if root is None or root.tag != "robot":
        said = f"the root element is <{root.tag}>, not <robot>" if root is not None else "no root element"
        return ParsedUrdf(None, said, root.sourceline if root is not None else 1)
    return ParsedUrdf(root, undeclared=undeclared)


def _undeclared_prefixes(log: etree._ListErrorLog) -> dict[str, int]:
    first: dict[str, int] = {}
    for entry in log:  # 'Namespace prefix drake for foo on link is not defined', 'Namespace prefix drake on thing ...'
        words = entry.message.split()
        if len(words) > 2 and words[:2] == ["Namespace", "prefix"]:
            first.setdefault(words[2], entry.line)
    return first


def read_urdf_root(text: str, where: str) -> etree._Element:
    """The ``<robot>`` root of a URDF text, undeclared prefixes read past.

    Raises:
        XacrokitError: not well-formed XML, or a root that is not ``<robot>`` (located).
    """
    parsed = parse_urdf(text)
    if parsed.root is None:
        raise XacrokitError(f"{parsed.where(where)}: {parsed.error}: not a URDF")
    return parsed.root
