"""The document reader: a URDF parsed once (U001 when it cannot be), its links and joints, its numbers read leniently,
and findings placed at the line they are about."""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Mapping

from lxml import etree

from ..shared.urdf_view import joint_tree, view_of
from ..shared.xml_parse import parse_urdf
from .findings import Finding, Severity, rule_table, severity

RULES = rule_table(
    {
        "U001": ("urdf-readable", "error", "the document is well-formed XML with a <robot> root"),
        "U003": (
            "namespace-declared",
            "warning",
            "every namespace prefix used (drake:, gazebo:) is declared with xmlns:PREFIX; consumers read the file "
            "anyway, namespace-aware XML tools refuse it",
        ),
    }
)


def parse_robot(text: str, file: str) -> tuple[etree._Element | None, list[Finding]]:
    """The ``<robot>`` element of a URDF text (None when there is none, and the U001 finding says why), and the
    findings of reading it: U003 for each namespace prefix used without a declaration, which every consumer reads
    past (they ignore elements and attributes they do not know)."""
    parsed = parse_urdf(text)
    if parsed.root is None:
        return None, [Finding("U001", severity("U001"), "robot", "", parsed.error, file, parsed.error_line)]
    return parsed.root, [_undeclared(prefix, line, file) for prefix, line in parsed.undeclared.items()]


def _undeclared(prefix: str, line: int, file: str) -> Finding:
    return Finding(
        "U003",
        severity("U003"),
        "namespace",
        prefix,
        f"the prefix {prefix}: is used but never declared; consumers read past it, but XML tools that know "
        f'namespaces refuse the file: declare it on <robot> (xmlns:{prefix}="...")',
        file,
        line,
    )


class Doc:
    """The URDF the rules read: its typed view (:mod:`xacrokit.shared.urdf_view`, what the rules walk), and where
    each finding is placed (its element's line; for a spec, the spec's line of the link or joint it is about)."""

    def __init__(
        self,
        root: etree._Element,
        file: str | None,
        lines: Mapping[tuple[str, str], tuple[int, int]] | None = None,
        *,
        source: str | None = None,
    ) -> None:
        self.root = root
        self.file = file
        self.spec_lines = lines  # for spec input: (kind, name) -> (line, column) in the spec
        self.source = source  # URDF input: its text (element lines are the file's own)
        self.view = view_of(root)
        self.link_names = {link.name for link in self.view.links}
        self.joint_by_name = {joint.name: joint.element for joint in self.view.joints}

    @functools.cached_property
    def fixed_to_world(self) -> bool:
        """Whether the robot is fixed to the world: its one root link is named ``world`` (any case) and has no
        geometry (the convention of fixed-base descriptions: a KUKA's ``world`` -> ``base_link``). Its base then needs
        no mass (I007) and nothing of it rolls or walks (G006)."""
        roots = joint_tree(self.view).roots(self.link_names)
        root = self.view.link(roots[0]) if len(roots) == 1 else None
        return root is not None and root.name.lower() == "world" and not (root.visuals or root.collisions)

    def finding(
        self,
        rule: str,
        kind: str,
        name: str,
        message: str,
        element: etree._Element | None = None,
        level: Severity | None = None,
    ) -> Finding:
        """A finding of ``rule`` (at the rule's severity, or ``level`` for a case the rule's table says is milder)
        located at ``element``'s line and column (for a spec, the place of the link or joint it is about)."""
        line, column = None, None
        if self.spec_lines is not None:
            place = self.spec_lines.get((kind, name))
            owner = element
            while place is None and owner is not None:  # a mesh, say: the place of the link or joint it belongs to
                if owner.tag in ("link", "joint"):
                    place = self.spec_lines.get((owner.tag, owner.get("name", "")))
                owner = owner.getparent()
            line, column = place or (None, None)
        elif element is not None and self.source is not None:
            line = element.sourceline  # (an expanded xacro's lines are not the xacro file's: leave them out)
            column = self._column(line, element.tag) if isinstance(element.tag, str) else None
        return Finding(rule, level or severity(rule), kind, name, message, self.file, line or None, column or None)

    @functools.cached_property
    def _source_lines(self) -> list[str]:
        return (self.source or "").splitlines()

    def _column(self, line: int | None, tag: str) -> int | None:
        """Where on its line (1-based) an element is: its start tag when it begins there, else the line's first
        character (lxml gives the line where the start tag ends, and no column)."""
        if line is None or not 0 < line <= len(self._source_lines):
            return None
        text = self._source_lines[line - 1]
        found = re.search(rf"<{re.escape(tag)}[\s/>]|<{re.escape(tag)}$", text)
        if found is not None:
            return found.start() + 1
        return len(text) - len(text.lstrip()) + 1


def number_of(attributes: Mapping[str, str] | None, key: str, default: float | None = None) -> float | None:
    """An attribute of the view (``limit``, ``dynamics`` ...) as a number: ``default`` when it (or its element) is
    missing, NaN when it does not read."""
    if attributes is None or attributes.get(key) is None:
        return default
    try:
        return float(attributes[key])
    except ValueError:
        return math.nan


def triple_of(text: str | None, default: str = "0 0 0") -> tuple[float, float, float]:
    """Three numbers from an attribute's text of the view (xyz, rpy, size): ``default`` when it is missing, NaNs
    when it does not hold exactly three."""
    try:
        x, y, z = (float(v) for v in (default if text is None else text).split())
    except ValueError:
        return (math.nan, math.nan, math.nan)
    return (x, y, z)
