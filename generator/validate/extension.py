"""The spec's ``extension``: a XML file beside the spec whose ``<robot>`` children become the first content of the
package's user-owned ``urdf/NAME_extension.xacro``. Read here once (bounded, no entities, no network), refused with
a located error when it is not a ``.xacro``/``.xml``/``.urdf`` file in the spec's folder (as with meshes: a spec from
elsewhere must not carry another file of yours into a package), not well-formed, not a ``<robot>``, or holding a
xacro element or attribute (the content is copied for xacro verbatim: every ``$`` escaped, and no instruction of a
spec from elsewhere may run, an include of one of your files among them)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from lxml import etree

from ..errors import SpecError
from ..load import RawSpec
from ..shared.input_files import InputError, read_input
from ..shared.value_text import xacro_text
from ..shared.xml_parse import parser

LIMIT = 4 * 1024 * 1024  # bytes: an extension of hand-added content, not a robot of its own
SUFFIXES = (".xacro", ".xml", ".urdf")


def extension_body(raw: RawSpec, data: dict[str, Any]) -> tuple[str, list[SpecError]]:
    """The extension's ``<robot>`` children as xacro text copied verbatim (every text and attribute escaped so that
    xacro evaluates nothing), and the errors of reading it."""

    name = data.get("extension")
    if name is None:
        return "", []
    folder = Path(raw.file).parent
    file = folder / name
    if not file.resolve().is_relative_to(folder.resolve()) or file.suffix.lower() not in SUFFIXES:
        message = (
            f"the extension must be a {', '.join(SUFFIXES)} file in the spec's folder or below it; {name!r} is not"
        )
        return "", [raw.error(("extension",), message)]
    try:
        data_bytes = read_input(file, LIMIT)
    except InputError as exc:
        return "", [raw.error(("extension",), f"cannot read {name!r}: {exc.strerror}")]
    try:
        root = etree.fromstring(data_bytes, parser())
    except etree.XMLSyntaxError as exc:
        line, column = exc.position
        return "", [raw.error(("extension",), f"{name}:{line}:{column}: not well-formed XML: {exc.msg}")]
    if root.tag != "robot":
        return "", [raw.error(("extension",), f"{name}: the root element is <{root.tag}>, not <robot>")]
    for element in root.iter(etree.Element):  # (copied verbatim: a xacro instruction in it would be run)
        names = [element.tag, *element.attrib.keys()]
        if any(str(n).startswith("{") and "xacro" in str(n).split("}")[0] for n in names):
            line = element.sourceline or 1
            message = f"{name}:{line}: a xacro element or attribute; the extension is copied verbatim, not expanded"
            return "", [raw.error(("extension",), message)]
    for element in root.iter():
        if isinstance(element.tag, str):
            for key, value in element.attrib.items():
                element.set(key, xacro_text(value))
        if element.text and isinstance(element.tag, str):
            element.text = xacro_text(element.text)
        if element.tail:
            element.tail = xacro_text(element.tail)
    children = [etree.tostring(child, encoding="unicode").strip() for child in root]
    return "\n".join(c for c in children if c), []
