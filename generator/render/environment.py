"""What every renderer shares: the rendered file, the macro modes, and the one jinja2 environment.

jinja2 with StrictUndefined (a template that asks for something the model lacks fails loudly) and XML autoescaping
for the .xacro/.xml templates. Every user string that lands in a xacro file goes through ``xacro_text``, so a ``${``
or ``$(`` in it is written escaped and never evaluated by xacro. Numbers are written with ``repr`` (round-trip exact).
"""

from __future__ import annotations

import contextlib
import re
from dataclasses import dataclass
from functools import cache
from typing import Literal

import jinja2
from markupsafe import Markup

from .. import __version__
from ..model import Box, Cylinder
from ..shared.package_data import templates_dir
from ..shared.user_cache import cache_folder, source_stamp
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


class _TemplateCache(jinja2.FileSystemBytecodeCache):
    """jinja2's compiled templates kept in the user's cache folder (``shared.user_cache``): a run takes them instead of
    compiling the templates again (about 0.25 s of a robot's generation). jinja2 writes each file to a temporary name
    and renames it, and compiles again a template whose text changed; a new jinja2, or an edit of this module, names
    other files; a file that cannot be read or written only means compiling, never a failed run."""

    def get_cache_key(self, name: str, filename: str | None = None) -> str:
        # (the code jinja2 compiles depends on its version and on this module's settings: autoescape, trim_blocks)
        return super().get_cache_key(f"{source_stamp('jinja2', 'xacrokit.render.environment')}|{name}", filename)

    def load_bytecode(self, bucket: jinja2.bccache.Bucket) -> None:
        try:
            super().load_bytecode(bucket)
        except Exception:  # a damaged file (truncated, or not ours): compile instead
            bucket.reset()

    def dump_bytecode(self, bucket: jinja2.bccache.Bucket) -> None:
        with contextlib.suppress(OSError):
            super().dump_bytecode(bucket)


def _bytecode_cache() -> jinja2.BytecodeCache | None:
    folder = cache_folder("templates", __version__)
    return None if folder is None else _TemplateCache(str(folder))


@cache
def environment() -> jinja2.Environment:
    """The jinja2 environment of every template (packages, scenes, starter specs), built once; its compiled templates
    are kept in the user's cache folder."""
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates_dir())),
        bytecode_cache=_bytecode_cache(),
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
