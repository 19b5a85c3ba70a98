"""The layout of the xacrokit package stays as issue 12 left it: no import cycle among its modules (imports inside
functions included; the names the package __init__ files load by string with import_module are not seen), no private
name imported from another module, no module over 500 lines, and no stage module importing a later stage."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from conftest import REPO

PACKAGE = REPO / "generator"
MAX_LINES = 500


def module_name(path: Path) -> str:
    parts = ["xacrokit", *path.relative_to(PACKAGE).with_suffix("").parts]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def imports(name: str) -> list[tuple[str, list[str], int]]:
    """(module imported, names taken from it, line) for every import statement of xacrokit's own modules in ``name``,
    at any depth (an import inside a function counts: it runs the other module all the same)."""
    path = MODULES[name]
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            base = package
            for _ in range(node.level - 1):
                base = base.rpartition(".")[0]
            target = f"{base}.{node.module}" if node.level and node.module else (node.module or base)
            if not target.startswith("xacrokit"):
                continue
            names = [alias.name for alias in node.names]
            submodules = [f"{target}.{n}" for n in names if f"{target}.{n}" in MODULES]
            if submodules:  # from . import emit: the module emit
                found += [(module, [], node.lineno) for module in submodules]
                names = [n for n in names if f"{target}.{n}" not in MODULES]
            if names or not submodules:
                found.append((target, names, node.lineno))
        elif isinstance(node, ast.Import):
            found += [(a.name, [], node.lineno) for a in node.names if a.name.startswith("xacrokit")]
    return [(target, names, line) for target, names, line in found if target in MODULES]


GRAPH = {name: sorted({target for target, _, _ in imports(name)} - {name}) for name in MODULES}


def test_the_package_has_the_modules_the_layout_names():
    assert {"xacrokit.check", "xacrokit.validate", "xacrokit.render", "xacrokit.scene"} <= set(MODULES)
    assert len(MODULES) > 40


def test_no_import_cycle():
    state: dict[str, str] = {}
    path: list[str] = []

    def visit(name: str) -> None:
        state[name] = "open"
        path.append(name)
        for target in GRAPH[name]:
            if state.get(target) == "open":
                cycle = path[path.index(target) :] + [target]
                pytest.fail("import cycle: " + " -> ".join(cycle))
            if target not in state:
                visit(target)
        path.pop()
        state[name] = "done"

    for name in MODULES:
        if name not in state:
            visit(name)


def test_the_checker_finds_a_cycle_when_there_is_one(monkeypatch):
    """The cycle test above can fail: a graph with a cycle makes it fail."""
    monkeypatch.setitem(GRAPH, "xacrokit.model", [*GRAPH["xacrokit.model"], "xacrokit.emit"])
    with pytest.raises(pytest.fail.Exception, match="import cycle"):
        test_no_import_cycle()


def private_imports(modules: dict[str, list[tuple[str, list[str], int]]]) -> list[str]:
    """Where a module takes a private name (``_x``, not ``__x__``) from another: by ``from M import _x``, or by
    ``M._x`` on a module it imported as a whole."""
    found = []
    for name, taken in modules.items():
        for target, names, line in taken:
            found += [f"{name}:{line} imports {n} from {target}" for n in names if n.startswith("_") and n[1:2] != "_"]
    return found


def private_attributes(name: str) -> list[str]:
    """``module._x`` in ``name`` where ``module`` is one of xacrokit's modules imported by ``name`` as a whole."""
    path = MODULES[name]
    tree = ast.parse(path.read_text(encoding="utf-8"))
    whole = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level:
            whole |= {a.asname or a.name for a in node.names if any(t.endswith("." + a.name) for t in GRAPH[name])}
        elif isinstance(node, ast.Import):
            whole |= {a.asname or a.name for a in node.names if a.name.startswith("xacrokit")}
    return [
        f"{name}:{node.lineno} uses {node.value.id}.{node.attr}"
        for node in ast.walk(tree)
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in whole
        and node.attr.startswith("_") and node.attr[1:2] != "_"
    ]  # fmt: skip


def test_no_private_name_is_imported_from_another_module():
    assert not private_imports({name: imports(name) for name in MODULES})
    assert not [use for name in MODULES for use in private_attributes(name)]


def test_the_private_name_check_can_fail():
    assert private_imports({"xacrokit.a": [("xacrokit.b", ["_helper", "public", "__version__"], 3)]}) == [
        "xacrokit.a:3 imports _helper from xacrokit.b"
    ]


@pytest.mark.parametrize("name", sorted(MODULES))
def test_no_module_is_over_500_lines(name):
    lines = len(MODULES[name].read_text(encoding="utf-8").splitlines())
    assert lines <= MAX_LINES, f"{MODULES[name]} has {lines} lines"


# the stages in pipeline order: a module of a stage imports no module of a later stage (STYLE.md's one-way data flow)
STAGES = [
    "xacrokit.load",
    "xacrokit.validate",
    "xacrokit.resolve",
    "xacrokit.emit",
    "xacrokit.render",
    "xacrokit.write.package_writer",
]


def _stage(name: str) -> int | None:
    return next((i for i, stage in enumerate(STAGES) if name == stage or name.startswith(stage + ".")), None)


def backwards_imports(graph: dict[str, list[str]]) -> list[str]:
    """Imports of a module of a later stage from a module of an earlier one."""
    found = []
    for name, targets in graph.items():
        here = _stage(name)
        found += [f"{name} imports {t}" for t in targets if here is not None and (_stage(t) or -1) > here]
    return found


def test_no_stage_imports_a_later_stage():
    assert not backwards_imports(GRAPH)


def test_the_stage_check_can_fail():
    assert backwards_imports({"xacrokit.validate.names": ["xacrokit.render.package", "xacrokit.load"]}) == [
        "xacrokit.validate.names imports xacrokit.render.package"
    ]
