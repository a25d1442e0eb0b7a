"""The import layers: no cycle between modules and no import up the layers.

Every module of ``src/curvefold`` is read with :mod:`ast` (imports inside functions and
``TYPE_CHECKING`` blocks included, since they are dependencies all the same) and every
import of a curvefold module becomes an edge of a graph. The layers, from the ground up::

    kernel < geometry < {vault, io} < analysis < figures < app

A layer imports only the layers below it (and itself); vault and io, side by side, never
import each other. The top-level ``curvefold/__init__.py`` and ``__main__.py`` gather the
public names and may import anything; nothing imports them.
"""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"

#: The layers each layer may import (besides itself).
ALLOWED = {
    "kernel": set(),
    "geometry": {"kernel"},
    "vault": {"kernel", "geometry"},
    "io": {"kernel", "geometry"},
    "mechanics": {"kernel", "geometry", "vault"},
    "analysis": {"kernel", "geometry", "vault", "io", "mechanics"},
    "figures": {"kernel", "geometry", "vault", "io", "analysis", "mechanics"},
    "app": {"kernel", "geometry", "vault", "io", "analysis", "figures", "mechanics"},
}
#: Modules that may import any layer.
EXEMPT = {"__init__", "__main__"}

#: Violations in today's code, each with why it is still there. Remove an entry when its
#: import is fixed (the test fails until then, so the fix is seen).
KNOWN: dict[tuple[str, str], str] = {}


def modules(root: Path, package: str) -> dict[str, Path]:
    """Dotted name -> file of every module of ``package`` under ``root`` (packages by their __init__)."""
    out = {}
    for path in sorted((root / package).rglob("*.py")):
        parts = path.relative_to(root).with_suffix("").parts
        out[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return out


def imports(root: Path, package: str) -> dict[str, dict[str, int]]:
    """The import graph: for every module, the modules of ``package`` it imports -> first line."""
    names = modules(root, package)
    graph: dict[str, dict[str, int]] = {}
    for name, path in names.items():
        is_package = path.name == "__init__.py"
        edges: dict[str, int] = {}
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            if isinstance(node, ast.Import):
                targets = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    here = name.split(".") if is_package else name.split(".")[:-1]
                    base = ".".join(here[: len(here) - node.level + 1] + ([node.module] if node.module else []))
                else:
                    base = node.module or ""
                # "from a import b" imports module a.b when there is one, else names of a
                targets = [f"{base}.{alias.name}" if f"{base}.{alias.name}" in names else base for alias in node.names]
            else:
                continue
            for target in targets:
                # "import a.b.c" runs a, a.b and a.b.c: the deepest one that is a module here
                while target and target not in names:
                    target = target.rpartition(".")[0]
                if target and target != name:
                    edges[target] = min(edges.get(target, node.lineno), node.lineno)
        graph[name] = edges
    return graph


def layer_of(name: str) -> str | None:
    """The layer of a module (``pkg.layer.module``), or None for the top-level modules."""
    parts = name.split(".")
    return parts[1] if len(parts) > 1 and parts[1] not in EXEMPT else None


def upward(graph: dict[str, dict[str, int]], allowed: dict[str, set[str]] = ALLOWED) -> list[tuple[str, str, str]]:
    """Imports that break the layers: (importer, imported, why)."""
    out = []
    for a, edges in graph.items():
        la = layer_of(a)
        if la is None:
            continue
        for b, line in edges.items():
            lb = layer_of(b)
            if lb is None:
                out.append((a, b, f"line {line}: {la} imports the top-level package"))
            elif lb != la and lb not in allowed.get(la, set()):
                below = ", ".join(sorted(allowed.get(la, set()))) or "no other layer"
                out.append((a, b, f"line {line}: {la} may import {below}, not {lb}"))
    return out


def cycles(graph: dict[str, dict[str, int]]) -> list[list[str]]:
    """One cycle (a list of modules, first = last) through every strongly connected component."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    components: list[list[str]] = []

    def connect(v: str) -> None:  # Tarjan's algorithm
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, {}):
            if w not in index:
                connect(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                components.append(component)

    for v in sorted(graph):
        if v not in index:
            connect(v)
    return [_cycle_within(graph, set(c)) for c in components]


def _cycle_within(graph: dict[str, dict[str, int]], component: set[str]) -> list[str]:
    """A shortest cycle through the smallest name of a strongly connected component."""
    start = min(component)
    paths = {start: [start]}
    queue = [start]
    for v in queue:  # breadth first
        for w in sorted(graph[v]):
            if w == start:
                return paths[v] + [start]
            if w in component and w not in paths:
                paths[w] = paths[v] + [w]
                queue.append(w)
    raise AssertionError(f"no cycle through {start}")  # pragma: no cover - a component has one


def test_curvefold_keeps_its_layers():
    graph = imports(SRC, "curvefold")
    assert {"curvefold.kernel.errors", "curvefold.figures.plots", "curvefold.app.cli"} <= set(graph)
    assert sum(map(len, graph.values())) > 100  # it found the imports
    assert cycles(graph) == []
    found = {(a, b): why for a, b, why in upward(graph)}
    unexpected = [f"{a} -> {b} ({why})" for (a, b), why in found.items() if (a, b) not in KNOWN]
    assert not unexpected, "imports up or across the layers:\n" + "\n".join(unexpected)
    fixed = sorted(set(KNOWN) - set(found))
    assert not fixed, f"fixed, remove from KNOWN: {fixed}"


def _package(root: Path, files: dict[str, str]) -> None:
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")


BASE = {f"pkg/{layer}/__init__.py": "" for layer in ALLOWED} | {"pkg/__init__.py": "from .app.cli import run\n", "pkg/app/cli.py": "def run(): ...\n"}


def test_a_cycle_is_reported_with_its_edges(tmp_path):
    _package(tmp_path, BASE | {
        "pkg/geometry/a.py": "from .b import f\n",
        "pkg/geometry/b.py": "def f():\n    from . import c  # inside a function\n",
        "pkg/geometry/c.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import pkg.geometry.a\n",
        "pkg/geometry/d.py": "from . import a\n",  # on the way in, not on the cycle
    })
    graph = imports(tmp_path, "pkg")
    assert graph["pkg.geometry.b"] == {"pkg.geometry.c": 2}
    assert cycles(graph) == [["pkg.geometry.a", "pkg.geometry.b", "pkg.geometry.c", "pkg.geometry.a"]]
    assert upward(graph) == []


def test_imports_up_or_across_the_layers_are_reported(tmp_path):
    _package(tmp_path, BASE | {
        "pkg/kernel/k.py": "def f():\n    from ..geometry.g import x\n",
        "pkg/geometry/g.py": "import pkg.kernel.k\nx = 1\n",
        "pkg/geometry/h.py": "from .. import run\n",
        "pkg/vault/v.py": "from ..io import w\n",
        "pkg/io/w.py": "from pkg import app\n",
        "pkg/analysis/m.py": "from ..io.w import *\nfrom ..vault import v\nfrom ..geometry import g\n",
    })
    graph = imports(tmp_path, "pkg")
    assert cycles(graph) == [["pkg.geometry.g", "pkg.kernel.k", "pkg.geometry.g"]]
    assert {(a, b): why for a, b, why in upward(graph)} == {
        ("pkg.kernel.k", "pkg.geometry.g"): "line 2: kernel may import no other layer, not geometry",
        ("pkg.geometry.h", "pkg"): "line 1: geometry imports the top-level package",
        ("pkg.vault.v", "pkg.io.w"): "line 1: vault may import geometry, kernel, not io",
        ("pkg.io.w", "pkg.app"): "line 1: io may import geometry, kernel, not app",
    }
