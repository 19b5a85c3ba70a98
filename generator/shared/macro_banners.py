"""The macro reference, read from the banner comments above each public macro.

A banner is the XML comment directly before ``<xacro:macro>`` and has lines of the form::

    macro: NAME
    makes: what it makes (may continue on indented lines)
    param: NAME [UNIT] (required|default VALUE) description
    creates: the links, joints and frames it creates

The macro reference in docs/macros.md is rendered from these banners (``gen-robot macros --reference``), and a test
checks both that every banner matches its macro's real parameter list and that docs/macros.md holds the current
rendering.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from lxml import etree

from .package_data import PUBLIC_MACRO_FILES, macros_dir
from .xml_parse import parser

XACRO_NS = "http://www.ros.org/wiki/xacro"
_PARAM_LINE = re.compile(
    r"^(?P<name>\*{0,2}\w+) \[(?P<unit>[^\]]*)\] \((?P<kind>required|default (?P<default>.*?))\) (?P<text>.+)$"
)
_FIELD = re.compile(r"^(macro|makes|param|creates):\s*(.*)$")


@dataclass(frozen=True)
class MacroParam:
    """One documented parameter. ``default`` is None for a required one; block parameters keep their ``*``."""

    name: str
    unit: str
    default: str | None
    description: str


@dataclass(frozen=True)
class MacroDoc:
    """One public macro as its banner documents it, plus the parameter list xacro will actually use."""

    file: str
    name: str
    makes: str
    creates: str
    params: tuple[MacroParam, ...]
    declared_params: str  # the macro's own params="..." attribute


def _banner_fields(comment: str) -> dict[str, list[str]]:
    """Split a banner into its fields; an indented line continues the field above it."""
    fields: dict[str, list[str]] = {}
    current: list[str] | None = None
    for raw in comment.splitlines():
        line = raw.strip()
        match = _FIELD.match(line)
        if match:
            current = fields.setdefault(match.group(1), [])
            current.append(match.group(2))
        elif line and current is not None:
            current[-1] += " " + line
    return fields


def _parse_param(line: str, where: str) -> MacroParam:
    match = _PARAM_LINE.match(line)
    if not match:
        raise ValueError(
            f"{where}: banner param line not in the form 'NAME [UNIT] (required|default X) text': {line!r}"
        )
    default = match.group("default")
    return MacroParam(match.group("name"), match.group("unit"), default, match.group("text"))


def read_macro_docs(folder: Path | None = None) -> list[MacroDoc]:
    """Read the banner of every public macro (names not starting with ``_``) in the public macro files."""
    folder = folder or macros_dir()
    docs: list[MacroDoc] = []
    for filename in PUBLIC_MACRO_FILES:
        tree = etree.parse(str(folder / filename), parser())
        for macro in tree.getroot().iter(f"{{{XACRO_NS}}}macro"):
            name = macro.get("name", "")
            if name.startswith("_"):
                continue
            previous = macro.getprevious()
            if not isinstance(previous, etree._Comment):
                raise ValueError(f"{filename}: public macro {name!r} has no banner comment directly above it")
            fields = _banner_fields(previous.text or "")
            where = f"{filename}: macro {name}"
            if fields.get("macro") != [name]:
                raise ValueError(f"{where}: banner names {fields.get('macro')!r}")
            docs.append(
                MacroDoc(
                    file=filename,
                    name=name,
                    makes=" ".join(fields.get("makes", [])),
                    creates=" ".join(fields.get("creates", [])),
                    params=tuple(_parse_param(line, where) for line in fields.get("param", [])),
                    declared_params=" ".join(macro.get("params", "").split()),
                )
            )
    return docs


_CODE_LIKE = re.compile(r"(<[^<>]+>|[\w<>.]*(?:\$\{[^}]*\}[\w<>.]*)+|`[^`]*`)")


def _markdown(text: str) -> str:
    """Banner prose to Markdown: XML tags and ${...} become code spans; a bare * is escaped (not emphasis)."""
    parts = _CODE_LIKE.split(text)
    out = []
    for k, part in enumerate(parts):
        if k % 2 == 0:
            out.append(part.replace("*", "\\*").replace("|", "\\|"))
        else:
            out.append(part if part.startswith("`") else f"`{part}`")
    return "".join(out)


def read_palette(folder: Path | None = None) -> list[tuple[str, str]]:
    """The colours of materials.xacro, (name, rgba), from its banner's ``palette:`` lines."""
    banner = etree.parse(str((folder or macros_dir()) / "materials.xacro"), parser()).getroot().getprevious()
    lines = (banner.text or "").splitlines() if isinstance(banner, etree._Comment) else []
    entries = [line.strip()[len("palette:") :].split(None, 1) for line in lines if line.strip().startswith("palette:")]
    return [(name, rgba) for name, rgba in entries]


def render_reference(docs: list[MacroDoc] | None = None) -> str:
    """The Markdown macro reference (the section of docs/macros.md between the macro-reference markers)."""
    reference = _render_macros(read_macro_docs() if docs is None else docs)
    if docs is not None:
        return reference
    palette = read_palette()
    rows = [
        "### `macros/materials.xacro`\n",
        "A colour palette of `<material>` elements, defined once however often the file is included: use "
        '`<material name="xacrokit_blue"/>` in a visual, or `material="xacrokit_blue"` on the link and wheel macros.\n',
        "| material | rgba |",
        "|---|---|",
        *(f"| `{name}` | {rgba} |" for name, rgba in palette),
    ]
    return reference + "\n" + "\n".join(rows) + "\n"


def _render_macros(docs: list[MacroDoc]) -> str:
    out: list[str] = []
    current_file = None
    for doc in docs:
        if doc.file != current_file:
            current_file = doc.file
            out.append(f"### `macros/{doc.file}`\n")
        out.append(f"#### `{doc.name}`\n")
        out.append(f"{_markdown(doc.makes)}\n")
        out.append("| parameter | unit | default | meaning |")
        out.append("|---|---|---|---|")
        for p in doc.params:
            default = "required" if p.default is None else f"`{p.default}`"
            out.append(f"| `{p.name}` | {_markdown(p.unit)} | {default} | {_markdown(p.description)} |")
        out.append("")
        out.append(f"Creates: {_markdown(doc.creates)}\n")
    return "\n".join(out).rstrip() + "\n"
