"""What every renderer shares: the rendered file, the macro modes, and the one jinja2 environment.

jinja2 with StrictUndefined (a template that asks for something the model lacks fails loudly) and XML autoescaping
for the .xacro/.xml templates. Every user string that lands in a xacro file goes through ``xacro_text``, so a ``${``
or ``$(`` in it is written escaped and never evaluated by xacro. Numbers are written with ``repr`` (round-trip exact).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import cache
from typing import Literal

import jinja2
from markupsafe import Markup

from ..model import Box, Cylinder
from ..shared.package_data import templates_dir
from ..shared.value_text import num, vec, xacro_text, xml_comment_text

MacroMode = Literal["copy", "find", "inline"]


@dataclass(frozen=True)
class RenderedFile:
    """One file of the package: a POSIX path relative to the package root and its full text (bytes for a binary file,
    such as a mesh copied from the spec's folder). ``seed``: the user's file, written only when it is missing, never
    rewritten, reported as a conflict or removed (the package's extension file)."""

    path: str
    content: str | bytes
    seed: bool = False

    @property
    def text(self) -> str:
        """The content as text (a binary file's bytes read as UTF-8)."""
        return self.content if isinstance(self.content, str) else self.content.decode("utf-8")


def indent_block(text: str, width: int) -> Markup:
    """Rendered template text with every non-empty line indented by ``width`` spaces (jinja's ``indent`` also
    indents an empty block's first line)."""
    return Markup(re.sub(r"(?m)^(?=.)", " " * width, str(text)))  # (already rendered, so already escaped)


@cache
def environment() -> jinja2.Environment:
    """The jinja2 environment of every template (packages, scenes, starter specs), built once."""
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates_dir())),
        undefined=jinja2.StrictUndefined,
        autoescape=jinja2.select_autoescape(enabled_extensions=("xacro.j2", "xml.j2"), default_for_string=False),
        keep_trailing_newline=True,
        trim_blocks=True,
        lstrip_blocks=True,
    )
    env.filters.update(num=num, vec=vec, xacro_text=xacro_text, indent_block=indent_block, xml_comment=xml_comment_text)
    env.globals.update(
        is_box=lambda s: isinstance(s, Box),
        is_cylinder=lambda s: isinstance(s, Cylinder),
    )
    return env
