"""How values are written into generated files: numbers, vectors, comments and text xacro must copy verbatim.

One place for these rules, shared by the direct emitter (``emit``), the templates (``render``) and scenes. Numbers
are written with ``repr`` (round-trip exact) and never as ``-0.0``.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable


def num(value: float) -> str:
    """A float written so that reading it back gives the same float."""
    text = _NUMBER_TEXT.get(value)
    if text is None:
        text = repr(float(value))
        if text == "-0.0":
            text = "0.0"
        if len(_NUMBER_TEXT) < 1 << 16:  # robots repeat their numbers (0.0, 0.1, pi/2): remember the text
            _NUMBER_TEXT[value] = text
    return text


_NUMBER_TEXT: dict[float, str] = {}


def vec(values: tuple[float, ...]) -> str:
    """Numbers separated by single spaces, each as :func:`num` writes it."""
    return " ".join(num(v) for v in values)


def comment_text(value: object) -> str:
    """Text from outside (a spec's file name) made safe for a one-line comment in every generated language (Python,
    CMake, YAML, XML, Markdown): a character that is not printable (a newline would end the comment and start code)
    becomes its escape (``\\n``, ``\\x00``, ``\\u2028``), a backtick too (it would end a Markdown code span) and a
    backslash is doubled. In an XML comment, see :func:`xml_comment_text`."""
    return "".join(ch if ch.isprintable() and ch not in "\\`" else _escaped(ch) for ch in str(value))


def command_text(command: str) -> str:
    """A shell command (its words quoted with ``shlex.quote``) for a Markdown code span: as it is, so that it can be
    copied and run, when every character is printable and none is a backtick; else :func:`comment_text` (safe, but
    then the escapes show what to type)."""
    return command if all(ch.isprintable() and ch != "`" for ch in command) else comment_text(command)


def xml_comment_text(value: object) -> str:
    """:func:`comment_text` for an XML comment, which may not hold ``--``: each becomes ``-\\x2d``."""
    return comment_text(value).replace("--", "-\\x2d").replace("--", "-\\x2d")


def _escaped(ch: str) -> str:
    if ch == "\\":
        return "\\\\"
    code = ord(ch)
    return {"\n": "\\n", "\r": "\\r", "\t": "\\t"}.get(ch) or (f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}")


def xacro_text(value: object) -> str:
    """Text xacro must copy verbatim. A run of ``$`` before ``{`` or ``(`` gets one more ``$`` (xacro drops one). A run
    of two or more elsewhere is refused by xacro's lexer ('invalid expression: $$'), whatever its length: all but its
    last ``$`` are written as the expression ``${'$'}``. A single ``$`` before anything else stays as it is."""
    return _DOLLARS.sub(_escape_dollars, str(value))


_DOLLARS = re.compile(r"(\$+)([{(]?)")


def _escape_dollars(match: re.Match[str]) -> str:
    run, opening = match.group(1), match.group(2)
    if opening:
        return f"${run}{opening}"
    return "${'$'}" * (len(run) - 1) + "$"


_MARKDOWN = re.compile(r"([\\`*_{}\[\]<>()#+\-.!|~])")


def markdown_text(value: object) -> str:
    """Text shown as it is in Markdown (a report's names, which come from a URDF): every character Markdown reads as
    markup backslash-escaped (GitHub's and CommonMark's set, ``|`` for tables, ``<`` for HTML), line breaks and other
    control characters as spaces."""
    text = "".join(" " if ord(ch) < 0x20 or ord(ch) == 0x7F else ch for ch in str(value))
    return _MARKDOWN.sub(r"\\\1", text)


def did_you_mean(name: str, known: Iterable[str]) -> str:
    """`` (did you mean 'base_link'?)`` when one of ``known`` is close to the mistyped ``name`` (difflib), else ''."""

    match = difflib.get_close_matches(name, sorted(known), n=1)
    return f" (did you mean {match[0]!r}?)" if match else ""
