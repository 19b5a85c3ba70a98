"""The guard on xacro's expressions: expanding a xacro document runs its ``${...}`` and ``$(eval ...)`` expressions
with Python's ``eval``, and xacro's own safety check (no name starting with ``__``) can be walked around, e.g.
``python.vars(python.type)['__subclasses__']`` reaches every class and from there ``os.system``; ``$(eval ...)`` even
has Python's builtins (``exec``, ``open``). A description downloaded from the internet must not run code when it is
checked or expanded.

So, unless the document is trusted, ``type`` and ``vars`` leave xacro's ``python`` namespace for the expansion, and
every expression is parsed (Python's ``ast``) before xacro evaluates it and refused when it could reach Python's
internals: an attribute starting with ``_`` (``x.__class__``, ``m._private``) or naming a frame, generator or code
object's parts (``gi_frame``, ``f_back``, ``f_globals`` ...; a generator's frame leads to a module's globals without
one underscore), a name starting with ``__``, a text holding ``__``, ``:=``, ``format``/``format_map`` on a text built
at run time (a format string can read attributes), and in ``$(eval ...)``, which sees Python's builtins, the builtins
that introspect or run code (``getattr``, ``eval``, ``exec``, ``open`` ...). What real descriptions do passes:
arithmetic, ``math``, ``xacro.load_yaml`` and indexing, string methods, conditionals, comprehensions,
``python.isinstance``, a macro parameter named ``type``. A refused expression stops the expansion with a message that
names it and says how to trust one's own documents: ``--trust`` or ``XACROKIT_TRUST_XACRO=1``.

A guard, not a proof and not a sandbox: it refuses the ways of reaching Python's object graph that are known (two more
were found by a review and are now refused); time, memory and output are bounded elsewhere (an untrusted document
expands in a bounded child: :mod:`xacrokit.expansion.bounded_child`), and it leaves
what xacro offers on purpose: ``xacro.load_yaml`` reads any YAML file the process can read, ``$(env NAME)`` any
environment variable, into the output.
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


# attributes of Python's frames, generators, coroutines, tracebacks and code objects: a walk from any generator
# (x for x in ...) through gi_frame.f_back reaches a module's globals, without one underscore
INTROSPECTION_PREFIXES = ("gi_", "f_", "cr_", "ag_", "tb_", "co_", "func_")
# the names of xacro's python namespace that reach Python's classes: removed from it while a document is untrusted
NAMESPACE_REMOVED = ("type", "vars")


@lru_cache(maxsize=4096)
def expression_problem(expression: str, builtins: bool = False) -> str | None:
    """Why an untrusted document may not evaluate ``expression``, or None when it may (also when it does not parse:
    xacro then says so itself). ``builtins``: the expression sees Python's builtins (``$(eval ...)`` does; ``${...}``
    sees only xacro's symbols, where a name such as ``type`` is a document's own property)."""
    try:
        tree = ast.parse(expression.strip(), mode="eval")
    except (SyntaxError, ValueError):
        return None
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute):
            if node.attr.startswith("_"):
                return f"it reads the attribute {node.attr!r} (names starting with _ are Python's internals)"
            if node.attr.startswith(INTROSPECTION_PREFIXES) or node.attr == "mro":
                return f"it reads the attribute {node.attr!r} (Python's classes, frames and code objects)"
            if isinstance(node.value, ast.Name) and node.value.id == "python" and node.attr in REFUSED_NAMES:
                return f"it uses python.{node.attr}, which reaches Python's internals"
            if node.attr in ("format", "format_map") and not _literal_text(node.value):
                return f"it calls {node.attr} on a text built at run time (a format string can read attributes)"
        elif isinstance(node, ast.NamedExpr):
            return "it assigns with := (a name bound inside an expression can carry a frame out of it)"
        elif isinstance(node, ast.Name):
            if node.id.startswith("__"):
                return f"it uses the name {node.id!r}"
            if builtins and node.id in REFUSED_NAMES:
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
        problem = expression_problem(expression, builtins=True)
        if problem is not None:
            raise xacro.XacroException(refusal_message(expression, problem))
        return saved_extension(expression, context)

    namespace = getattr(module, "_global_symbols", {}).get("python")  # (a dict: python['type'] reaches it as well)
    removed = {k: namespace.pop(k) for k in NAMESPACE_REMOVED if k in namespace} if namespace is not None else {}
    module.safe_eval = safe_eval
    substitution._eval = extension_eval
    try:
        yield
    finally:
        module.safe_eval = saved_eval
        substitution._eval = saved_extension
        if namespace is not None:
            namespace.update(removed)
