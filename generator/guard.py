"""The guard on xacro's expressions: expanding a xacro document runs its ``${...}`` and ``$(eval ...)`` expressions
with Python's ``eval``, and xacro's own safety check (no name starting with ``__``) can be walked around, e.g.
``python.vars(python.type)['__subclasses__']`` reaches every class and from there ``os.system``; ``$(eval ...)`` even
has Python's builtins (``exec``, ``open``). A description downloaded from the internet must not run code when it is
checked or expanded.

So, unless the document is trusted, every expression is parsed (Python's ``ast``) before xacro evaluates it, and
refused when it could reach Python's internals: an attribute or name starting with ``_`` (``x.__class__``,
``m._private``; a name with two, as xacro already refuses), a string holding ``__`` (a dunder name by subscript or
``getattr``), the introspection and code builtins (``type``, ``vars``, ``getattr``, ``eval``, ``exec``, ``open`` ...,
also as ``python.type``), and ``format``/``format_map`` on a text that is not written out (a format string can read
attributes). What real descriptions do passes: arithmetic, ``math``, ``xacro.load_yaml`` and dictionary indexing,
string methods, conditionals, comprehensions, ``python.isinstance``. A refused expression stops the expansion with a
message that names it and says how to trust one's own documents: ``--trust`` or ``XACROKIT_TRUST_XACRO=1``.

A guard, not a proof: it keeps documents from reaching Python's object graph through the ways known to work; it does
not bound time or memory (``${'x' * 10**10}``).
"""

from __future__ import annotations

import ast
import contextlib
import contextvars
import os
from collections.abc import Iterator
from functools import lru_cache
from typing import Any

TRUST_VARIABLE = "XACROKIT_TRUST_XACRO"
# builtins that reach Python's internals or run code; xacro exposes type and vars (python.type, python.vars) itself
REFUSED_NAMES = frozenset(
    {
        "type",
        "vars",
        "dir",
        "getattr",
        "setattr",
        "delattr",
        "hasattr",
        "globals",
        "locals",
        "eval",
        "exec",
        "compile",
        "open",
        "input",
        "breakpoint",
        "help",
        "super",
        "object",
        "memoryview",
        "classmethod",
        "staticmethod",
        "property",
        "exit",
        "quit",
    }
)
HOW_TO_TRUST = f"if the document is your own, expand it with --trust (or {TRUST_VARIABLE}=1)"


_TRUSTING: contextvars.ContextVar[bool] = contextvars.ContextVar("xacrokit_trusting", default=False)


def trusted_by_default() -> bool:
    """Whether expansions that are not told otherwise trust their documents: inside :func:`trusting`, or when the
    environment says so (``XACROKIT_TRUST_XACRO=1``)."""
    return _TRUSTING.get() or os.environ.get(TRUST_VARIABLE, "").strip().lower() in ("1", "true", "yes")


@contextlib.contextmanager
def trusting(trust: bool = True) -> Iterator[None]:
    """Expansions inside (a scene's third-party macros, say) trust their documents when ``trust``."""
    token = _TRUSTING.set(trust or _TRUSTING.get())
    try:
        yield
    finally:
        _TRUSTING.reset(token)


@lru_cache(maxsize=4096)
def expression_problem(expression: str) -> str | None:
    """Why an untrusted document may not evaluate ``expression``, or None when it may (also when it does not parse:
    xacro then says so itself)."""
    try:
        tree = ast.parse(expression.strip(), mode="eval")
    except (SyntaxError, ValueError):
        return None
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute):
            if node.attr.startswith("_"):
                return f"it reads the attribute {node.attr!r} (names starting with _ are Python's internals)"
            if node.attr in REFUSED_NAMES:
                return f"it uses {node.attr!r}, which reaches Python's internals or runs code"
            if node.attr in ("format", "format_map") and not _literal_text(node.value):
                return f"it calls {node.attr} on a text built at run time (a format string can read attributes)"
        elif isinstance(node, ast.Name):
            if node.id.startswith("__"):
                return f"it uses the name {node.id!r}"
            if node.id in REFUSED_NAMES:
                return f"it uses {node.id!r}, which reaches Python's internals or runs code"
        elif isinstance(node, ast.Constant) and isinstance(node.value, (str, bytes)):
            text = node.value if isinstance(node.value, str) else node.value.decode("latin-1")
            if "__" in text:
                return f"it holds the text {node.value!r} (double underscores name Python's internals)"
    return None


def _literal_text(node: ast.expr) -> bool:
    return isinstance(node, ast.Constant) and isinstance(node.value, str)


def refusal_message(expression: str, problem: str) -> str:
    return f"refused to evaluate '{expression.strip()}': {problem}; {HOW_TO_TRUST}"


@contextlib.contextmanager
def guarded(trust: bool) -> Iterator[None]:
    """While expanding: refuse the expressions :func:`expression_problem` refuses, unless ``trust``."""
    if trust:
        yield
        return
    import xacro  # (here, not on top: the CLI imports this module and starts without xacro)
    import xacro.substitution_args

    module, substitution = xacro, xacro.substitution_args
    saved_eval, saved_extension = module.safe_eval, substitution._eval

    def safe_eval(expr: str, globals: Any, locals: Any = None) -> Any:
        problem = expression_problem(expr)
        if problem is not None:
            raise xacro.XacroException(refusal_message(expr, problem))
        return saved_eval(expr, globals, locals)

    def extension_eval(expression: str, context: Any) -> Any:  # $(eval ...): Python's builtins are in reach there
        problem = expression_problem(expression)
        if problem is not None:
            raise xacro.XacroException(refusal_message(expression, problem))
        return saved_extension(expression, context)

    module.safe_eval = safe_eval
    substitution._eval = extension_eval
    try:
        yield
    finally:
        module.safe_eval = saved_eval
        substitution._eval = saved_extension
