"""The expand stage: run the real xacro on a document, with ``$(find ...)`` resolved without ROS.

xacro is driven through ``xacro.process_file`` (``xacro.process`` calls ``sys.exit``). Two things xacro does not do on
its own are done here:

* ``$(find PKG)`` normally needs ``ament_index_python``. We resolve ``xacrokit`` to the installed macro library,
  packages named in ``package_paths`` to the folders given, and anything else through ``ament_index_python`` when it is
  importable or an ``AMENT_PREFIX_PATH`` share folder when it is not.
* xacro silently ignores a mapping ``name:=value`` that the document never declares with ``<xacro:arg>``; a typo in an
  argument name then goes unnoticed. We record which arguments the document declares and reject the others.
"""

from __future__ import annotations

import contextlib
import os
import re
import xml.parsers.expat
from collections.abc import Callable, Iterator, Mapping
from pathlib import Path
from typing import Any

import xacro
import xacro.substitution_args

from ..errors import ExpandError
from ..shared.input_files import require_regular_file
from ..shared.ros_packages import find_package, nearby_packages
from .bounded_child import Bounds, ChildFailed, OutOfBounds, run_bounded
from .expression_guard import HOW_TO_TRUST, NAMESPACE_REMOVED, guarded, trusted_by_default

MAX_DOCUMENT_BYTES = 64 * 1024 * 1024  # a xacro document (the file expanded; its includes are read by xacro)
# an untrusted document's expansion: wall time, memory beyond the parent's, size of the URDF
# (xacrokit.expansion.bounded_child). The largest description we write, a 1,000-Panda fleet, took xacro 2 min 48 s, 370
# MB and gave 10.4 MB (2026-11-24).
EXPAND_BOUNDS = Bounds(seconds=600.0, memory=4 * 2**30, output=64 * 2**20)


class _DeclaredArgs(dict):
    """The mapping table xacro writes its arguments into; remembers which names ``<xacro:arg>`` asked about.

    xacro declares an argument by testing ``name in table`` and adding the default when absent; looking the table up
    for ``$(arg name)`` goes through ``__getitem__`` and so does not count as a declaration.
    """

    def __init__(self, mappings: Mapping[str, str]) -> None:
        super().__init__(mappings)
        self.declared: set[str] = set()

    def __contains__(self, name: object) -> bool:
        if isinstance(name, str):
            self.declared.add(name)
        return super().__contains__(name)


@contextlib.contextmanager
def _find_resolver(package_paths: Mapping[str, str | os.PathLike[str]] | None, near: Path) -> Iterator[None]:
    """Point xacro's ``$(find)`` at :func:`find_package` for the duration of one expansion; packages found nowhere
    else are looked for around ``near`` (the document), once."""
    module = xacro.substitution_args
    saved_find, saved_eval = module._eval_find, module._eval_dict.get("find")
    around: list[dict[str, Path]] = []

    def resolve(name: str) -> str:
        try:
            return find_package(name, package_paths)
        except LookupError:
            if not around:
                around.append(nearby_packages(near))
            if name in around[0]:
                return str(around[0][name])
            raise

    module._eval_find = resolve
    module._eval_dict["find"] = resolve
    try:
        yield
    finally:
        module._eval_find = saved_find
        module._eval_dict["find"] = saved_eval


def _causes(exc: BaseException) -> Iterator[BaseException]:
    """The exceptions xacro wrapped in ``exc`` (its ``exc`` attribute), outermost first, ``exc`` included."""
    seen: set[int] = set()
    current: BaseException | None = exc
    while current is not None and id(current) not in seen:
        seen.add(id(current))
        yield current
        inner = getattr(current, "exc", None)
        current = inner if isinstance(inner, BaseException) else None


def _macro_stack() -> tuple[str, ...]:
    """Macros being instantiated, innermost first; our private helpers are left out (users never call them)."""
    names = (m.body.getAttribute("name") for m in reversed(xacro.macrostack or []))
    return tuple(name for name in names if not name.startswith("_xacrokit"))


def _file_stack() -> tuple[str, ...]:
    return tuple(str(f) for f in reversed(xacro.filestack or []) if f)


def _with_hint(message: str) -> str:
    """xacro's message, and for an argument the document declares without a default, how to give it."""
    undefined = re.fullmatch(r"Undefined substitution argument (\S+)", message.strip())
    if undefined is None:
        return message
    name = undefined.group(1)
    return (
        f"{message.strip()}: $(arg {name}) has no value where the document uses it (no default declared before that "
        f'use; UR\'s <robot name="$(arg name)"> comes before its <xacro:arg>): give it as {name}:=VALUE'
    )


def _xacro_message(exc: BaseException) -> str:
    """xacro wraps a ``xacro.fatal`` message in 'when evaluating expression ...'; the macro's own words suffice."""
    inner = getattr(exc, "exc", None)
    if isinstance(exc, xacro.XacroException) and isinstance(inner, xacro.XacroException):
        return _xacro_message(inner)
    if isinstance(exc, xacro.XacroException) and isinstance(inner, KeyError) and inner.args:
        key = inner.args[0]
        where = str(exc).strip().splitlines()[-1] if "when evaluating" in str(exc) else ""
        said = f"no key {key!r}" + (f" ({where})" if where else "")
        if key in NAMESPACE_REMOVED:  # python['type'], python['vars']: out of reach while untrusted
            said += f"; python.{key} is out of reach of documents from elsewhere: {HOW_TO_TRUST}"
        return said
    if isinstance(exc, xacro.XacroException) and type(inner) is LookupError and inner.args:  # ($(find): ours)
        return str(inner.args[0])
    if isinstance(exc, xacro.XacroException) and isinstance(inner, Exception) and str(exc).startswith("<class '"):
        return str(inner).strip()  # (xacro says '<class ...SubstitutionException>: text text')
    if str(exc).strip() == "Not enough blocks":
        return (
            "Not enough blocks: the macro takes a block parameter (*origin, say) that the call does not give; put "
            'the block inside the call, e.g. <origin xyz="0 0 0" rpy="0 0 0"/>'
        )
    if isinstance(exc, xacro.XacroException) and isinstance(inner, OSError):  # (xacro says it twice otherwise)
        return f"cannot read {inner.filename}: {inner.strerror or inner}" if inner.filename else str(inner)
    return str(exc).strip()


def expand_file(
    path: str | os.PathLike[str],
    mappings: Mapping[str, str] | None = None,
    *,
    package_paths: Mapping[str, str | os.PathLike[str]] | None = None,
    xacro_banner: bool = True,
    trust: bool | None = None,
) -> str:
    """Expand a xacro document to URDF text with the real xacro.

    Args:
        path: the ``.xacro`` file.
        mappings: ``xacro:arg`` values, as on xacro's command line (``name:=value``). Every name must be declared by
            the document with ``<xacro:arg name=...>``.
        package_paths: folders for ``$(find PKG)`` of packages other than xacrokit. A package found neither there
            nor in a ROS workspace is looked for around the document (:func:`nearby_packages`).
        xacro_banner: keep the comment xacro puts on top (it names the input path, so output that must not depend
            on where it was made leaves it out).
        trust: evaluate every expression, as xacro does; untrusted (the default, unless
            :func:`xacrokit.expansion.expression_guard.trusting` or ``XACROKIT_TRUST_XACRO=1`` says otherwise),
            expressions that could reach Python's internals are refused (:mod:`xacrokit.expansion.expression_guard`).

    Returns:
        The expanded URDF as pretty-printed XML text.

    Raises:
        ExpandError: the file cannot be read or parsed, xacro stops (a macro's argument check, an undefined property,
            an unknown package), an untrusted document's expression is refused, or a mapping names an argument the
            document does not declare.
    """
    where = str(path)
    try:  # the document itself: a regular file of sane size (xacro would read a device or a link loop forever)
        require_regular_file(path, MAX_DOCUMENT_BYTES)
        source = Path(path).resolve()
    except OSError as exc:
        raise ExpandError(f"cannot read the document: {exc.strerror}", file=where) from None
    except RuntimeError as exc:  # (resolve: a link loop)
        raise ExpandError(f"cannot read the document: {exc}", file=where) from None
    trusted = trusted_by_default() if trust is None else trust

    def expand() -> str:
        return _expand(source, where, mappings, package_paths=package_paths, xacro_banner=xacro_banner, trust=trusted)

    if trusted:
        try:
            return expand()
        except MemoryError:
            raise ExpandError("expanding it ran out of memory", file=where) from None
    return _expand_bounded(expand, where)


def _expand_bounded(expand: Callable[[], str], where: str) -> str:
    """``expand()`` run in a bounded child (an untrusted document): its text, or its error raised as an ExpandError."""
    try:
        text, error = run_bounded(expand, EXPAND_BOUNDS, errors=_error_fields)
    except OutOfBounds as exc:
        raise ExpandError(_out_of_bounds(exc.which), file=where) from None
    except ChildFailed as exc:
        raise ExpandError(f"expanding the document stopped ({exc.detail})", file=where) from None
    if error is not None:
        raise ExpandError(
            str(error["message"]),
            file=str(error["file"]),
            macro_stack=tuple(map(str, error["macro_stack"])),
            file_stack=tuple(map(str, error["file_stack"])),
        )
    return str(text)


def _error_fields(exc: BaseException) -> dict[str, Any] | None:
    """An ExpandError as plain data, to come back from the bounded child (see
    :mod:`xacrokit.expansion.bounded_child`)."""
    if not isinstance(exc, ExpandError):
        return None
    return {"message": exc.message, "file": exc.file, "macro_stack": exc.macro_stack, "file_stack": exc.file_stack}


def _out_of_bounds(which: str) -> str:
    bounds = EXPAND_BOUNDS
    said = {
        "seconds": f"it did not finish expanding within {bounds.seconds:g} s",
        "memory": f"expanding it needs more than {bounds.memory / 2**30:g} GiB of memory",
        "output": f"it expands to more than {bounds.output / 2**20:g} MiB of URDF",
    }[which]
    return f"{said} (the bounds on documents from elsewhere); {HOW_TO_TRUST}"


def _expand(
    source: Path,
    where: str,
    mappings: Mapping[str, str] | None,
    *,
    package_paths: Mapping[str, str | os.PathLike[str]] | None,
    xacro_banner: bool,
    trust: bool,
) -> str:
    """:func:`expand_file`'s work, after the document was found to be a regular file (in a bounded child when the
    document is not trusted)."""
    table = _DeclaredArgs({str(k): str(v) for k, v in (mappings or {}).items()})
    xacro.all_includes = []  # module-level list xacro only ever appends to
    try:
        with _find_resolver(package_paths, source), guarded(trust):
            document = xacro.process_file(str(source), mappings=table)
    except xacro.XacroException as exc:
        if any(isinstance(cause, MemoryError) for cause in _causes(exc)):
            raise MemoryError from None  # (what xacro wraps is no error of the document's text: a bound, said as one)
        raise ExpandError(
            _with_hint(_xacro_message(exc)), file=where, macro_stack=_macro_stack(), file_stack=_file_stack()
        ) from None
    except xml.parsers.expat.ExpatError as exc:
        raise ExpandError(f"not well-formed XML: {exc}", file=_file_stack()[0] if _file_stack() else where) from None
    except (OSError, LookupError) as exc:
        raise ExpandError(str(exc), file=where, file_stack=_file_stack()) from None
    except RecursionError:  # a macro that calls itself, a file that includes itself: xacro recurses without end
        macros, files = _macro_stack(), _file_stack()
        what = (
            f"macro {macros[0]} calls itself without end" if macros and len(set(macros[:50])) < 50 else
            f"file {files[0]} includes itself" if files and len(set(files[:50])) < 50 else "it recurses without end"
        )  # fmt: skip
        raise ExpandError(
            f"the document never ends expanding: {what}", file=where, macro_stack=macros[:3], file_stack=files[:3]
        ) from None
    except RuntimeError as exc:  # (xacro's own complaints about elements: 'xacro:include: missing attribute')
        raise ExpandError(str(exc), file=where, file_stack=_file_stack()) from None
    except UnicodeDecodeError:  # (xacro decodes what it reads: the document, or a file it includes)
        files = _file_stack()
        if not files or files[0] == str(source):
            raise ExpandError("cannot read the document: it is not UTF-8 text", file=where) from None
        raise ExpandError("an included file is not UTF-8 text", file=where, file_stack=files) from None
    undeclared = sorted(set(mappings or {}) - table.declared)
    if undeclared:
        declared = ", ".join(sorted(table.declared)) or "none"
        raise ExpandError(
            f"argument(s) {', '.join(undeclared)} not declared by the document with <xacro:arg>; "
            f"it declares: {declared}",
            file=where,
        )
    if not xacro_banner:
        while document.firstChild is not None and document.firstChild.nodeType == document.COMMENT_NODE:
            document.removeChild(document.firstChild)
    return document.toprettyxml(indent="  ")
