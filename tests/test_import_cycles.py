"""No import cycle in the package: a walk over the imports of every ``checker/**.py`` (ast).

Module-level, function-level and type-checking imports all count: an import moved into a
function or under ``if TYPE_CHECKING:`` to dodge a cycle is still a cycle (and is named as
such). The calculation modules import the graph, never the reverse (:mod:`checker.modules`
holds the registry). Every import points down the layers of docs/architecture.md
(:data:`LAYERS`); the one that points up is listed with its reason in :data:`UPWARD`.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

KNOWN_CYCLES: set[frozenset[str]] = set()  # none: every cycle is a failure

LAYERS: tuple[tuple[str, ...], ...] = (
    ("checker.errors", "checker.plumbing"),
    ("checker.workbook",),
    ("checker.calc",),
    ("checker.description",),
    ("checker.results",),
    ("checker.evaluation.graph",),
    ("checker.modules",),
    ("checker.evaluation",),  # the rule table: imports the modules to register them
    ("checker.api",),
    ("checker.outputs",),
    ("checker.study",),
    ("checker.remedies",),
    ("checker.sizing",),
    ("checker.correlation",),  # checker correlate: a measurement against the model
    ("checker.report",),
    ("checker.cli", "checker.__main__"),
)
"""docs/architecture.md's layers, bottom first; a module belongs to the longest prefix."""

UPWARD: dict[tuple[str, str], str] = {
    ("checker.workbook.example_v8", "checker.description.engine"):
        "the V8 template's TVModel cells left blank in its data are derived once, when the"
        " template is written, by the engine description from the template's own Crank sheet",
}
"""Imports that point up a layer, each with its reason (docs/architecture.md)."""


def module_names(root: Path, package: str) -> dict[str, tuple[Path, bool]]:
    """Dotted name -> (file, is a package) of every ``.py`` under ``root/package``."""
    out = {}
    for p in sorted((root / package).rglob("*.py")):
        parts = list(p.relative_to(root).with_suffix("").parts)
        is_pkg = parts[-1] == "__init__"
        if is_pkg:
            parts = parts[:-1]
        out[".".join(parts)] = (p, is_pkg)
    return out


def _targets(importer: str, is_pkg: bool, node: ast.AST, mods: dict, package: str) -> list[str]:
    if isinstance(node, ast.Import):
        return [a.name for a in node.names
                if a.name == package or a.name.startswith(package + ".")]
    assert isinstance(node, ast.ImportFrom)
    if node.level:
        base = importer.split(".") if is_pkg else importer.split(".")[:-1]
        base = base[:len(base) - (node.level - 1)]
        mod = ".".join(base + ([node.module] if node.module else []))
    else:
        mod = node.module or ""
    if not (mod == package or mod.startswith(package + ".")):
        return []
    return [f"{mod}.{a.name}" if f"{mod}.{a.name}" in mods else mod for a in node.names]


def _with_parents(importer: str, target: str) -> list[str]:
    """``target`` and the packages Python initialises to import it (those that do not
    contain the importer: they are being initialised already)."""
    parts = target.split(".")
    out = [target]
    for k in range(len(parts) - 1, 1, -1):
        parent = ".".join(parts[:k])
        if not (importer == parent or importer.startswith(parent + ".")):
            out.append(parent)
    return out


def import_edges(root: Path, package: str) -> list[tuple[str, str, str, int]]:
    """(importer, imported, "module" | "function", line) for every import inside the
    package (``from pkg import sub`` names the submodule)."""
    mods = module_names(root, package)
    edges = []
    for name, (path, is_pkg) in mods.items():
        def walk(node: ast.AST, level: str, name=name, is_pkg=is_pkg) -> None:
            for ch in ast.iter_child_nodes(node):
                if isinstance(ch, (ast.Import, ast.ImportFrom)):
                    for t in _targets(name, is_pkg, ch, mods, package):
                        for u in _with_parents(name, t):
                            if u != name:
                                edges.append((name, u, level, ch.lineno))
                elif isinstance(ch, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
                    walk(ch, "function")
                elif isinstance(ch, ast.If) and "TYPE_CHECKING" in ast.unparse(ch.test):
                    walk(ch, "type-checking")
                else:
                    walk(ch, level)

        walk(ast.parse(path.read_text(encoding="utf-8")), "module")
    return edges


def cycles(edges: list[tuple[str, str, str, int]]) -> list[frozenset[str]]:
    """Strongly connected components of more than one module (Tarjan, iterative)."""
    adj: dict[str, list[str]] = {}
    for a, b, _lvl, _ln in edges:
        adj.setdefault(a, []).append(b)
        adj.setdefault(b, [])
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out = []
    for start in adj:
        if start in index:
            continue
        work = [(start, iter(adj[start]))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on.add(start)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is None:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[v])
                if low[v] == index[v]:
                    comp = set()
                    while True:
                        x = stack.pop()
                        on.discard(x)
                        comp.add(x)
                        if x == v:
                            break
                    if len(comp) > 1:
                        out.append(frozenset(comp))
            elif w not in index:
                index[w] = low[w] = len(index)
                stack.append(w)
                on.add(w)
                work.append((w, iter(adj[w])))
            elif w in on:
                low[v] = min(low[v], index[w])
    return out


def _describe(comp: frozenset[str], edges) -> str:
    inner = [f"{a} -> {b} ({lvl}-level, line {ln})" for a, b, lvl, ln in edges
             if a in comp and b in comp]
    return "cycle among " + ", ".join(sorted(comp)) + ":\n    " + "\n    ".join(inner)


def test_no_import_cycle_in_the_package():
    edges = import_edges(ROOT, "checker")
    found = [c for c in cycles(edges) if c not in KNOWN_CYCLES]
    assert not found, "\n".join(_describe(c, edges) for c in found)


def layer_of(module: str) -> int:
    best, found = -1, -1
    for i, names in enumerate(LAYERS):
        for n in names:
            if (module == n or module.startswith(n + ".")) and len(n) > best:
                best, found = len(n), i
    return found


def test_every_module_has_a_layer():
    assert not [m for m in module_names(ROOT, "checker") if m != "checker" and layer_of(m) < 0]


def test_every_import_points_down_the_layers():
    edges = import_edges(ROOT, "checker")
    # a package initialised on the way to its submodule is judged by the submodule
    via = {(a, ln, b.rsplit(".", 1)[0]) for a, b, _lvl, ln in edges}
    ups = {(a, b): f"{a} -> {b} ({lvl}-level, line {ln})" for a, b, lvl, ln in edges
           if b != "checker" and (a, ln, b) not in via and layer_of(b) > layer_of(a)}
    unexplained = [text for key, text in sorted(ups.items()) if key not in UPWARD]
    assert not unexplained, "imports pointing up the layers:\n" + "\n".join(unexplained)
    assert set(UPWARD) <= set(ups), "an upward import listed that no longer exists"


def test_known_cycles_still_exist():
    """A known exception that no longer occurs is removed from the list."""
    found = set(cycles(import_edges(ROOT, "checker")))
    assert KNOWN_CYCLES <= found, KNOWN_CYCLES - found


def test_graph_imports_no_calculation_module():
    edges = import_edges(ROOT, "checker")
    graph = "checker.evaluation.graph"
    assert ("checker.modules.balance", graph) in {(a, b) for a, b, _l, _n in edges}
    assert not [e for e in edges if e[0] == graph and e[1].startswith("checker.modules")]


def test_walk_finds_a_cycle_hidden_in_a_function(tmp_path):
    pkg = tmp_path / "pkg"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "sub" / "__init__.py").write_text("from .. import a  # noqa\n")
    (pkg / "a.py").write_text("from .sub import b\n")
    (pkg / "sub" / "b.py").write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from pkg import c\n"
        "def f():\n    from ..a import x\n    return x\n")
    (pkg / "c.py").write_text("import pkg.sub.b\n")
    edges = import_edges(tmp_path, "pkg")
    assert ("pkg.sub.b", "pkg.a", "function", 5) in edges
    assert ("pkg.sub.b", "pkg.c", "type-checking", 3) in edges
    assert ("pkg.sub", "pkg.a", "module", 1) in edges
    assert ("pkg.a", "pkg.sub", "module", 1) in edges  # importing pkg.sub.b runs pkg.sub
    assert ("pkg.c", "pkg.sub.b", "module", 1) in edges
    assert cycles(edges) == [frozenset({"pkg.a", "pkg.sub", "pkg.sub.b", "pkg.c"})]
    (pkg / "sub" / "b.py").write_text("X = 1\n")
    (pkg / "sub" / "__init__.py").write_text("")
    assert cycles(import_edges(tmp_path, "pkg")) == []


def test_registry_orders_every_module_and_names_every_calculation():
    from checker import modules
    from checker.evaluation import graph

    assert list(graph.MODULES) == list(modules.ORDER)
    assert {c.module for c in graph.CALCULATIONS.values()} <= set(modules.ORDER)
    with pytest.raises(ValueError, match="registered as"):
        graph.register_module("loads", "another title")
