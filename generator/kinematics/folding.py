"""A module's functions made anew for one arm from their own source: the numbers the arm fixes (what the functions
read from the arm's constants, named by :func:`specialised`'s pins) written in, and the arithmetic they make trivial
taken out: a term with a factor 0 is dropped from its sum, a factor 1 or -1 is its other factor (or its negative),
x + -y is x - y, numbers with numbers are computed, and an assignment that no remaining read reaches is dropped (the
flow followed through ifs and loops: a read on a later turn of a loop reaches what the loop assigned).

The closed forms (:mod:`.analytic`) are written once, for any arm; on an arm whose DH twists are multiples of pi/2
(axes along its root's) many of the numbers a solve multiplies by are 0 or +-1, and made for it the closed form's
steps take a quarter fewer instructions (the UR5 of the examples). Only exact 0s and 1s fold, and a number within
SNAP of 0 (a product of two roundings, 1e-32: a term it makes is below the last bit of any sum it is in): a quarter
turn's cosine is 6e-17, not 0, and is left as it is, so that every answer is the written steps' to the last bit,
but for the sign of a sum that is exactly 0 (0 - x written -x): at a target of joints on quarter turns an angle
atan2(+-0, -1) may come out pi where the written steps give -pi, the same position (tests/kinematics/
test_ik_folded.py: the branches alike, their values to 1e-12 or a whole turn). A function whose statements this
does not know (try, with, nested scopes) is not folded at all: :func:`specialised` says None, and the source's own
runs.
"""

from __future__ import annotations

import ast
import functools
from collections.abc import Callable, Iterator
from pathlib import Path
from types import ModuleType
from typing import Any

SNAP = 1e-30  # per m of the arm's size: a constant this near 0 is 0
_KNOWN: tuple[type[ast.stmt], ...] = (ast.Assign, ast.AugAssign, ast.Expr, ast.Return, ast.If, ast.For, ast.While)
_KNOWN += (ast.Continue, ast.Break, ast.Pass)


class Unfoldable(Exception):
    """A statement or expression folding does not know: the function is left as its source wrote it."""


@functools.cache
def _sources(path: str) -> dict[str, tuple[str, int]]:
    """Each top-level function of a module's source: its text and its first line (parsed anew for each arm: a fresh
    tree to fold, in a tenth of a deep copy's time)."""
    text = Path(path).read_text(encoding="utf-8")
    found = {}
    for node in ast.parse(text).body:
        if isinstance(node, ast.FunctionDef):
            found[node.name] = (ast.get_source_segment(text, node) or "", node.lineno)
    return found


def _function(path: str, name: str) -> ast.FunctionDef:
    text, line = _sources(path)[name]
    node = ast.parse("\n" * (line - 1) + text).body[0]  # (its lines numbered as in the module)
    if not isinstance(node, ast.FunctionDef):
        raise Unfoldable(name)
    return node


def specialised(
    module: ModuleType, pins: dict[str, dict[str, Any]], size: float
) -> dict[str, Callable[..., Any]] | None:
    """The functions of ``module`` named by ``pins``, each folded with its pinned names' objects (a parameter, or a
    local assigned once from a call, whose attributes are the arm's numbers), compiled together so that each calls
    the others' folded forms; None when one of them cannot be folded. ``size``: the arm's size in m."""
    path = module.__file__
    made: list[ast.stmt] = []
    try:
        for name, pinned in pins.items():  # (a module without its source, as a zipped one may be: left as it is)
            made.append(_Folder(pinned, SNAP * max(size, 1.0)).function(_function(path or "", name)))
    except (Unfoldable, KeyError, OSError, SyntaxError):
        return None
    folded = ast.fix_missing_locations(ast.Module(body=made, type_ignores=[]))
    namespace = dict(vars(module))
    exec(compile(folded, path or "", "exec"), namespace)  # (its source's lines: a traceback reads as the source)
    return {name: namespace[name] for name in pins}


def _snapped(value: float, snap: float) -> float:
    return 0.0 if -snap <= value <= snap else value


def _assigned(nodes: list[ast.stmt]) -> set[str]:
    """Every name the statements store to (at any depth)."""
    return {
        n.id for s in nodes for n in ast.walk(s) if isinstance(n, ast.Name) and isinstance(n.ctx, (ast.Store, ast.Del))
    }


def _is_number(node: ast.AST) -> bool:
    return isinstance(node, ast.Constant) and type(node.value) in (float, int)


class _Folder:
    """One function's fold. Along the flow, ``env`` maps a local to the number it holds there, and ``reach`` maps a
    local to the assignments whose value it may hold there (and to the loops it may hold a value from a later
    turn of): an assignment of names only, whose value is pure, that no remaining read reaches is dropped."""

    def __init__(self, pinned: dict[str, Any], snap: float) -> None:
        self.pinned, self.snap = pinned, snap
        self.needed: set[int] = set()  # (the droppable assignments some read reaches: kept)
        self.droppable: dict[int, set[str]] = {}  # (an assignment's id: its names)
        self.carried: dict[int, set[str]] = {}  # (a loop's id: the names read before this turn's store)

    def function(self, node: ast.FunctionDef) -> ast.FunctionDef:
        node.decorator_list, node.returns = [], None
        for argument in (*node.args.posonlyargs, *node.args.args, *node.args.kwonlyargs):
            argument.annotation = None
        for extra in (node.args.vararg, node.args.kwarg):
            if extra is not None:
                extra.annotation = None
        body = self.block(node.body, {}, {})
        node.body = _live(body, set(self.droppable) - self.needed) or [ast.Pass()]
        return node

    def block(self, body: list[ast.stmt], env: dict[str, Any], reach: dict[str, set[int]]) -> list[ast.stmt]:
        out: list[ast.stmt] = []
        for statement in body:
            out.append(self.statement(statement, env, reach))
        return out

    def read(self, node: ast.AST, reach: dict[str, set[int]]) -> None:
        """The names ``node`` still reads: the assignments that reach them are needed."""
        for name in ast.walk(node):
            if isinstance(name, ast.Name) and isinstance(name.ctx, ast.Load):
                for origin in reach.get(name.id, ()):
                    if origin < 0:  # (a loop's: its turns' assignments of the name)
                        self.carried.setdefault(origin, set()).add(name.id)
                    else:
                        self.needed.add(origin)

    def statement(self, node: ast.stmt, env: dict[str, Any], reach: dict[str, set[int]]) -> ast.stmt:
        if isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name) and node.value is not None:
            node = ast.copy_location(ast.Assign(targets=[node.target], value=node.value), node)  # (its type left out)
        if not isinstance(node, _KNOWN):
            raise Unfoldable(type(node).__name__)
        if isinstance(node, ast.Assign):
            return self.assign(node, env, reach)
        if isinstance(node, (ast.For, ast.While)):
            return self.loop(node, env, reach)
        if isinstance(node, ast.If):
            node.test = self.expression(node.test, env)
            self.read(node.test, reach)
            inner, other = dict(reach), dict(reach)
            node.body = self.block(node.body, dict(env), inner) or [ast.Pass()]
            node.orelse = self.block(node.orelse, dict(env), other)
            for name in {*inner, *other}:
                reach[name] = inner.get(name, set()) | other.get(name, set())
            for name in _assigned([node]):
                env.pop(name, None)
            return node
        if isinstance(node, ast.AugAssign):
            node.value = self.expression(node.value, env)
            target = node.target
            self.read(ast.Name(target.id, ast.Load()) if isinstance(target, ast.Name) else target, reach)
            self.read(node.value, reach)
        elif isinstance(node, (ast.Expr, ast.Return)) and node.value is not None:
            node.value = self.expression(node.value, env)
            self.read(node.value, reach)
        for name in _assigned([node]):
            env.pop(name, None)
            reach[name] = set()  # (a store no fold drops)
        return node

    def loop(self, node: ast.For | ast.While, env: dict[str, Any], reach: dict[str, set[int]]) -> ast.stmt:
        """A loop: the names it assigns forgotten (a turn may change them); a read in it of one of those reaches
        every assignment of the name in the loop (a later turn's) as well as those before."""
        if node.orelse:
            raise Unfoldable("a loop's else")
        changed, mark = _assigned([node]), -len(self.carried) - 1
        self.carried[mark] = set()
        if isinstance(node, ast.For):
            node.iter = self.expression(node.iter, env)
            self.read(node.iter, reach)
        for name in changed:
            env.pop(name, None)
            reach[name] = reach.get(name, set()) | {mark}
        if isinstance(node, ast.For):
            for name in _assigned([ast.Assign(targets=[node.target], value=ast.Constant(0))]):
                reach[name] = set()
        else:
            node.test = self.expression(node.test, env)
            self.read(node.test, reach)
        first = len(self.droppable)
        inner = {name: set(origins) for name, origins in reach.items()}
        node.body = self.block(node.body, dict(env), inner) or [ast.Pass()]
        made = [i for i in self.droppable if i >= first]
        for i in made:
            if self.droppable[i] & self.carried[mark]:
                self.needed.add(i)
        for name in changed:
            stores = {i for i in made if name in self.droppable[i]}
            reach[name] = (reach[name] - {mark}) | inner.get(name, set()) | stores
        return node

    def assign(self, node: ast.Assign, env: dict[str, Any], reach: dict[str, set[int]]) -> ast.stmt:
        """An assignment: its value folded; names given numbers noted in ``env``, the others forgotten; one of names
        only, of a pure value, noted as droppable."""
        if len(node.targets) != 1:
            raise Unfoldable("chained assignment")
        before = dict(env)  # (the value is made before its names are stored)
        node.value = self.expression(node.value, before)
        self.read(node, reach)
        knowns = [(t, self.known(v, before)) for t, v in _pairs(node.targets[0], node.value)]
        names = _assigned([node])
        for name in names:
            env.pop(name, None)
            reach[name] = set()
        if any(isinstance(t, ast.Name) and t.id in self.pinned for t, _ in knowns):
            return node  # (a pinned local: its value is the pinned object's)
        for target, known in knowns:
            env.update(_leaves(target, known))
        if _names_only(node.targets[0]) and _pure(node.value):
            index = len(self.droppable)
            self.droppable[index] = names
            node.folding_index = index  # type: ignore[attr-defined]
            for name in names:
                reach[name] = {index}
        return node

    def known(self, node: ast.expr, env: dict[str, Any]) -> Any:
        """The object an expression is when the arm fixes it (a pinned name's attribute, a number, a local holding
        one, a tuple of those), else None."""
        if isinstance(node, ast.Name) and node.ctx.__class__ is ast.Load:
            return env.get(node.id, self.pinned.get(node.id))
        if isinstance(node, ast.Attribute):
            owner = self.known(node.value, env)
            return None if owner is None else getattr(owner, node.attr, None)
        if isinstance(node, ast.Tuple):
            items = [self.known(e, env) for e in node.elts]
            return None if any(i is None for i in items) else tuple(items)
        if _is_number(node):
            return node.value  # type: ignore[attr-defined]
        return None

    def number(self, node: ast.expr, env: dict[str, Any]) -> ast.expr | None:
        value = self.known(node, env)
        if type(value) is float:
            return ast.copy_location(ast.Constant(_snapped(value, self.snap)), node)
        return None

    def expression(self, node: ast.expr, env: dict[str, Any]) -> ast.expr:
        if isinstance(node, (ast.Lambda, ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp, ast.NamedExpr)):
            raise Unfoldable(type(node).__name__)
        if isinstance(node, (ast.Name, ast.Attribute)):
            return self.number(node, env) or node
        for field, value in ast.iter_fields(node):
            if isinstance(value, ast.expr):
                setattr(node, field, self.expression(value, env))
            elif isinstance(value, list):
                setattr(node, field, [self.expression(v, env) if isinstance(v, ast.expr) else v for v in value])
        if isinstance(node, ast.BinOp):
            return ast.copy_location(_binary(node), node)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub) and _is_number(node.operand):
            return ast.copy_location(ast.Constant(-node.operand.value), node)  # type: ignore[attr-defined]
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            return ast.copy_location(_negative(node.operand), node)
        return node


def _pairs(target: ast.expr, value: ast.expr) -> Iterator[tuple[ast.expr, ast.expr]]:
    """A tuple assigned a tuple of as many, pair by pair (nested); else the one pair."""
    if isinstance(target, ast.Tuple) and isinstance(value, ast.Tuple) and len(target.elts) == len(value.elts):
        if not any(isinstance(e, ast.Starred) for e in (*target.elts, *value.elts)):
            for t, v in zip(target.elts, value.elts, strict=True):
                yield from _pairs(t, v)
            return
    yield target, value


def _leaves(target: ast.expr, known: Any) -> Iterator[tuple[str, Any]]:
    """The names a target binds to numbers (or tuples of them), when the value assigned is known."""
    if known is None:
        return
    if isinstance(target, ast.Name) and (type(known) is float or isinstance(known, tuple)):
        yield target.id, known  # (a tuple: unpacked later; only a float is written in)
    elif isinstance(target, ast.Tuple) and isinstance(known, tuple) and len(known) == len(target.elts):
        for t, k in zip(target.elts, known, strict=True):
            yield from _leaves(t, k)


def _binary(node: ast.BinOp) -> ast.expr:
    """A product or sum with a trivial number taken out, or two numbers computed."""
    left, right, op = node.left, node.right, node.op
    a = left.value if _is_number(left) else None  # type: ignore[attr-defined]
    b = right.value if _is_number(right) else None  # type: ignore[attr-defined]
    if a is not None and b is not None and isinstance(op, (ast.Add, ast.Sub, ast.Mult)):
        return ast.Constant(a + b if isinstance(op, ast.Add) else a - b if isinstance(op, ast.Sub) else a * b)
    if isinstance(op, ast.Mult):
        for number, other in ((a, right), (b, left)):
            if number == 0.0:
                return ast.Constant(0.0)
            if number == 1.0:
                return other
            if number == -1.0:
                return _negative(other)
    if isinstance(op, ast.Add):
        if a == 0.0:
            return right
        if b == 0.0:
            return left
    if isinstance(op, ast.Sub):
        if b == 0.0:
            return left
        if a == 0.0:
            return _negative(right)
    if isinstance(op, ast.Div) and b == 1.0:
        return left
    if isinstance(op, (ast.Add, ast.Sub)) and isinstance(right, ast.UnaryOp) and isinstance(right.op, ast.USub):
        flipped = ast.Sub() if isinstance(op, ast.Add) else ast.Add()  # (x + -y is x - y, x - -y is x + y: exactly)
        return ast.BinOp(left, flipped, right.operand)
    return node


def _negative(node: ast.expr) -> ast.expr:
    """-``node``, a negation of a negation taken out (exactly the value)."""
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        return node.operand
    return ast.UnaryOp(ast.USub(), node)


def _live(body: list[ast.stmt], dropped: set[int]) -> list[ast.stmt]:
    """The statements less the assignments ``dropped`` names (by their index: no read reaches them)."""
    kept: list[ast.stmt] = []
    for node in body:
        if getattr(node, "folding_index", None) in dropped:
            continue
        for field in ("body", "orelse"):
            inner = getattr(node, field, None)
            if isinstance(inner, list) and inner:
                setattr(node, field, _live(inner, dropped) or ([ast.Pass()] if field == "body" else []))
        kept.append(node)
    return kept


def _names_only(target: ast.expr) -> bool:
    """Whether a target stores to names only (no item or attribute: a store that does something)."""
    if isinstance(target, ast.Tuple):
        return all(_names_only(e) for e in target.elts)
    return isinstance(target, ast.Name)


def _pure(node: ast.expr) -> bool:
    """Whether evaluating the expression does nothing but read (names, attributes, numbers, tuples of those)."""
    if isinstance(node, ast.Tuple):
        return all(_pure(e) for e in node.elts)
    if isinstance(node, ast.Attribute):
        return _pure(node.value)
    return isinstance(node, (ast.Name, ast.Constant))
