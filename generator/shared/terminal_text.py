"""Outside text (file names, names from a robot, a consumer's words) made safe to print on a terminal or in a CI log.

A file name can hold an ESC (``\\x1b[2J`` clears a terminal, ``\\x1b]8;;`` makes a link), a newline (a forged
``robot.urdf: OK`` line), a right-to-left override, or bytes that are not UTF-8 (Python gives them as lone surrogates,
which a UTF-8 stream refuses: a crash, where a report was due). :func:`printable` writes each character that is not
printable as its escape, the way Python writes a string's (``\\n``, ``\\x1b``, ``\\u202e``, ``\\udcff``), and a
backslash as ``\\\\``: the text stays on its line, and it reads back one way. (Its twin for generated files is
``shared.value_text.comment_text``, which escapes backticks too, for Markdown.)
"""

from __future__ import annotations

_NAMED = {"\n": "\\n", "\r": "\\r", "\t": "\\t", "\\": "\\\\"}


def printable(text: object) -> str:
    """``text`` with each character that is not printable (control characters, line and paragraph separators,
    format characters such as bidirectional overrides, lone surrogates) and each backslash written as its escape."""
    said = str(text)
    if said.isprintable() and "\\" not in said:
        return said  # (the usual case: nothing to do)
    return "".join(ch if ch.isprintable() and ch != "\\" else _escaped(ch) for ch in said)


def _escaped(ch: str) -> str:
    code = ord(ch)
    if ch in _NAMED:
        return _NAMED[ch]
    if code < 0x100:
        return f"\\x{code:02x}"
    return f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}"


def controls_escaped(text: object) -> str:
    """``text`` with each character that is not printable written as its escape, backslashes left as they are: for
    messages whose names were escaped where they were written (a second pass must not double their backslashes),
    as a last guard that no ESC or carriage return reaches the terminal."""
    said = str(text)
    return said if said.isprintable() else "".join(ch if ch.isprintable() else _escaped(ch) for ch in said)
