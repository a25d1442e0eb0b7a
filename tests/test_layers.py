"""The layers and their seams: no cycle, no import up the layers, no reaching into geometry.

Every module of ``src/curvefold`` is read with :mod:`ast` (imports inside functions and
``TYPE_CHECKING`` blocks included, since they are dependencies all the same) and every
import of a curvefold module becomes an edge of a graph. So does a module named by a
string, which is imported all the same when the string is used: a ``"package.module"`` or
``"package.module:function"`` literal, and the literal argument of
``importlib.import_module`` or ``__import__``. The layers, from the ground up::

    kernel < geometry < {vault, io} < analysis < figures < app

A layer imports only the layers below it (and itself); vault and io, side by side, never
import each other. The top-level ``curvefold/__init__.py`` and ``__main__.py`` gather the
public names and may import anything; nothing imports them.

The seams between geometry and the layers above it:

* no module outside geometry tests which kind of structure it holds: no ``isinstance``,
  ``issubclass`` or ``type(x) is`` of a kind, a geometry class that has every member of a
  protocol geometry declares (``StructureLattice``: ``Lattice``, ``PanelLattice``;
  ``FoldedCrease``: ``Crease``, ``PanelCrease``). They ask the structure instead.
* no module above geometry imports a private name of a geometry module (``_name``), nor
  reads one off an imported geometry module.

And no module is over :data:`MAX_LINES` lines.
"""

from __future__ import annotations

import ast
import re
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
#: The layer whose classes are the kinds of structure, and the layers below it.
KINDS_LAYER = "geometry"
BELOW_KINDS = {"kernel", "geometry"}
#: Longest module, in lines (one concern each: about 600 lines).
MAX_LINES = 700
#: Modules over :data:`MAX_LINES` today, each with why. Remove an entry when the module is
#: split (the test fails until then, so the split is seen).
LONG: dict[str, str] = {}


def modules(root: Path, package: str) -> dict[str, Path]:
    """Dotted name -> file of every module of ``package`` under ``root`` (packages by their
    __init__)."""
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
                    base = ".".join(
                        here[: len(here) - node.level + 1] + ([node.module] if node.module else [])
                    )
                else:
                    base = node.module or ""
                # "from a import b" imports module a.b when there is one, else names of a
                targets = [
                    f"{base}.{alias.name}" if f"{base}.{alias.name}" in names else base
                    for alias in node.names
                ]
            elif isinstance(node, ast.Call) and _imports_by_name(node):
                literal = node.args[0].value  # type: ignore[attr-defined]
                targets = [_absolute(literal, name, is_package)]
            elif isinstance(node, ast.Constant) and isinstance(node.value, str):
                # a module named by a string, on its own or with an attribute: "a.b" or "a.b:f"
                named = node.value.partition(":")[0] if _QUALIFIED.fullmatch(node.value) else None
                if named not in names:
                    continue
                targets = [named]
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


#: A dotted name, optionally with an attribute after a colon: ``"a.b.c"``, ``"a.b:f"``.
_QUALIFIED = re.compile(r"[A-Za-z_]\w*(\.[A-Za-z_]\w*)+(:[A-Za-z_]\w*(\.[A-Za-z_]\w*)*)?")


def _imports_by_name(node: ast.Call) -> bool:
    """Whether a call is ``importlib.import_module("...")``, ``import_module("...")`` or
    ``__import__("...")``."""
    func = node.func
    called = (
        func.id
        if isinstance(func, ast.Name)
        else func.attr
        if isinstance(func, ast.Attribute)
        else ""
    )
    return (
        called in ("import_module", "__import__")
        and bool(node.args)
        and isinstance(node.args[0], ast.Constant)
        and isinstance(node.args[0].value, str)
    )


def _absolute(target: str, name: str, is_package: bool) -> str:
    """A module name given to ``import_module`` from module ``name``: relative (``".x"``) to its
    package."""
    level = len(target) - len(target.lstrip("."))
    if not level:
        return target
    here = name.split(".") if is_package else name.split(".")[:-1]
    rest = target[level:]
    return ".".join(here[: len(here) - level + 1] + ([rest] if rest else []))


def layer_of(name: str) -> str | None:
    """The layer of a module (``pkg.layer.module``), or None for the top-level modules."""
    parts = name.split(".")
    return parts[1] if len(parts) > 1 and parts[1] not in EXEMPT else None


def upward(
    graph: dict[str, dict[str, int]], allowed: dict[str, set[str]] = ALLOWED
) -> list[tuple[str, str, str]]:
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


def _members(node: ast.ClassDef) -> set[str]:
    """Names a class body defines: fields, attributes, methods and properties."""
    out = set()
    for item in node.body:
        if isinstance(item, (ast.FunctionDef, ast.AsyncFunctionDef)):
            out.add(item.name)
        elif isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name):
            out.add(item.target.id)
        elif isinstance(item, ast.Assign):
            out |= {t.id for t in item.targets if isinstance(t, ast.Name)}
    return out


def _trees(root: Path, package: str) -> dict[str, ast.Module]:
    return {
        name: ast.parse(path.read_text(encoding="utf-8"), str(path))
        for name, path in modules(root, package).items()
    }


def kinds(root: Path, package: str) -> dict[str, str]:
    """The kinds of :data:`KINDS_LAYER`: class name -> the protocol of that layer whose every
    member it has."""
    trees = {
        name: tree for name, tree in _trees(root, package).items() if layer_of(name) == KINDS_LAYER
    }
    classes = [
        node for tree in trees.values() for node in ast.walk(tree) if isinstance(node, ast.ClassDef)
    ]

    def is_protocol(node: ast.ClassDef) -> bool:
        return any(
            (b.id if isinstance(b, ast.Name) else getattr(b, "attr", "")) == "Protocol"
            for b in node.bases
        )

    protocols = {node.name: _members(node) - {"__init__"} for node in classes if is_protocol(node)}
    return {
        node.name: proto
        for node in classes
        if not is_protocol(node)
        for proto, members in protocols.items()
        if members and members <= _members(node)
    }


def _named(node: ast.expr) -> list[str]:
    """The class names an isinstance target names: ``A``, ``m.A``, ``(A, B)``, ``A | B``."""
    if isinstance(node, ast.Name):
        return [node.id]
    if isinstance(node, ast.Attribute):
        return [node.attr]
    if isinstance(node, (ast.Tuple, ast.List)):
        return [n for e in node.elts for n in _named(e)]
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitOr):
        return _named(node.left) + _named(node.right)
    return []


def kind_tests(root: Path, package: str) -> list[tuple[str, str, str]]:
    """Tests of a structure's kind outside the kinds' layer: (module, kind, why)."""
    found = kinds(root, package)
    out = []
    for name, tree in _trees(root, package).items():
        if layer_of(name) in BELOW_KINDS:
            continue
        for node in ast.walk(tree):
            tested = []
            if (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Name)
                and node.func.id in ("isinstance", "issubclass")
                and len(node.args) == 2
            ):
                tested = [(node.func.id, n) for n in _named(node.args[1])]
            elif (
                isinstance(node, ast.Compare)
                and isinstance(node.left, ast.Call)
                and isinstance(node.left.func, ast.Name)
                and node.left.func.id == "type"
            ):
                tested = [("type() is", n) for c in node.comparators for n in _named(c)]
            out += [
                (name, kind, f"line {node.lineno}: {how} {kind}, a kind of {found[kind]}")
                for how, kind in tested
                if kind in found
            ]
    return out


def private_imports(root: Path, package: str) -> list[tuple[str, str, str]]:
    """Private names of the kinds' layer used above it: (module, name, why).

    ``from a.geometry.m import _x``, ``from a.geometry import _m``, and ``m._x`` where ``m``
    was imported as a geometry module.
    """
    names = modules(root, package)
    out = []
    for name, tree in _trees(root, package).items():
        if layer_of(name) in BELOW_KINDS | {None}:
            continue
        is_package = names[name].name == "__init__.py"
        bound: dict[str, str] = {}  # local name -> geometry module
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                here = name.split(".") if is_package else name.split(".")[:-1]
                base = (
                    ".".join(
                        here[: len(here) - node.level + 1] + ([node.module] if node.module else [])
                    )
                    if node.level
                    else node.module or ""
                )
                if layer_of(base) != KINDS_LAYER:
                    continue
                for alias in node.names:
                    full = f"{base}.{alias.name}"
                    if full in names:
                        bound[alias.asname or alias.name] = full
                    if alias.name.startswith("_"):
                        out.append(
                            (
                                name,
                                full,
                                f"line {node.lineno}: imports the private name "
                                f"{alias.name} of {base}",
                            )
                        )
            elif isinstance(node, ast.Import):
                for alias in node.names:
                    if alias.asname and alias.name in names and layer_of(alias.name) == KINDS_LAYER:
                        bound[alias.asname] = alias.name
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.Attribute)
                and node.attr.startswith("_")
                and not node.attr.startswith("__")
                and isinstance(node.value, ast.Name)
                and node.value.id in bound
            ):
                module = bound[node.value.id]
                out.append(
                    (
                        name,
                        f"{module}.{node.attr}",
                        f"line {node.lineno}: reads the private name {node.attr} of {module}",
                    )
                )
    return out


def long_modules(root: Path, package: str, limit: int = MAX_LINES) -> dict[str, int]:
    """Modules over ``limit`` lines: name -> lines."""
    counts = {
        name: len(path.read_text(encoding="utf-8").splitlines())
        for name, path in modules(root, package).items()
    }
    return {name: n for name, n in counts.items() if n > limit}


def test_curvefold_keeps_its_layers():
    graph = imports(SRC, "curvefold")
    assert {"curvefold.kernel._errors", "curvefold.figures._plots", "curvefold.app.cli"} <= set(
        graph
    )
    assert sum(map(len, graph.values())) > 100  # it found the imports
    assert cycles(graph) == []
    found = {(a, b): why for a, b, why in upward(graph)}
    unexpected = [f"{a} -> {b} ({why})" for (a, b), why in found.items() if (a, b) not in KNOWN]
    assert not unexpected, "imports up or across the layers:\n" + "\n".join(unexpected)
    fixed = sorted(set(KNOWN) - set(found))
    assert not fixed, f"fixed, remove from KNOWN: {fixed}"


def test_no_module_outside_geometry_tests_the_kind_of_a_structure():
    assert kinds(SRC, "curvefold") == {
        "Lattice": "StructureLattice",
        "PanelLattice": "StructureLattice",
        "Crease": "FoldedCrease",
        "PanelCrease": "FoldedCrease",
    }
    assert kind_tests(SRC, "curvefold") == []


def test_no_module_above_geometry_uses_a_private_geometry_name():
    assert private_imports(SRC, "curvefold") == []


def test_no_module_is_too_long():
    found = long_modules(SRC, "curvefold")
    # it read them
    assert (
        sum(
            len(p.read_text(encoding="utf-8").splitlines())
            for p in modules(SRC, "curvefold").values()
        )
        > 10_000
    )
    unexpected = {name: n for name, n in found.items() if name not in LONG}
    assert not unexpected, f"modules over {MAX_LINES} lines: {unexpected}"
    split = sorted(set(LONG) - set(found))
    assert not split, f"split, remove from LONG: {split}"


def _package(root: Path, files: dict[str, str]) -> None:
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")


BASE = {f"pkg/{layer}/__init__.py": "" for layer in ALLOWED} | {
    "pkg/__init__.py": "from .app.cli import run\n",
    "pkg/app/cli.py": "def run(): ...\n",
}


def test_a_cycle_is_reported_with_its_edges(tmp_path):
    _package(
        tmp_path,
        BASE
        | {
            "pkg/geometry/a.py": "from .b import f\n",
            "pkg/geometry/b.py": "def f():\n    from . import c  # inside a function\n",
            "pkg/geometry/c.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import "
            "pkg.geometry.a\n",
            "pkg/geometry/d.py": "from . import a\n",  # on the way in, not on the cycle
        },
    )
    graph = imports(tmp_path, "pkg")
    assert graph["pkg.geometry.b"] == {"pkg.geometry.c": 2}
    assert cycles(graph) == [
        ["pkg.geometry.a", "pkg.geometry.b", "pkg.geometry.c", "pkg.geometry.a"]
    ]
    assert upward(graph) == []


def test_modules_named_by_strings_up_or_across_the_layers_are_reported(tmp_path):
    _package(
        tmp_path,
        BASE
        | {
            # "module:function" in a registry
            "pkg/io/w.py": 'REGISTRY = {"guide": "pkg.figures.guide:write"}\n',
            "pkg/io/r.py": (
                "import importlib\ndef f():\n    return importlib.import_module('pkg.app.cli')\n"
            ),
            "pkg/vault/v.py": (
                "from importlib import import_module\n"
                "m = import_module('..analysis.m', __package__)\n"
            ),
            "pkg/geometry/g.py": "x = __import__('pkg.vault.v')\n",
            "pkg/figures/guide.py": "def write(): ...\n",
            # a module's name on its own
            "pkg/analysis/m.py": "MODULES = ('pkg.io.w', 'pkg.figures')\n",
            "pkg/app/a.py": (
                '"""See pkg.figures.guide:write."""\n'  # prose, not a name
                'NAMES = ("pkg.io.w:REGISTRY", "pkg.kernel", "pkg.logs",\n'
                '         "pkg.io.nothing:f", "pkg.figures.guide:write")\n'
            ),
        },
    )
    graph = imports(tmp_path, "pkg")
    assert graph["pkg.app.a"] == {"pkg.io.w": 2, "pkg.kernel": 2, "pkg.figures.guide": 3}
    assert {(a, b): why for a, b, why in upward(graph)} == {
        ("pkg.io.w", "pkg.figures.guide"): "line 1: io may import geometry, kernel, not figures",
        ("pkg.io.r", "pkg.app.cli"): "line 3: io may import geometry, kernel, not app",
        (
            "pkg.vault.v",
            "pkg.analysis.m",
        ): "line 2: vault may import geometry, kernel, not analysis",
        ("pkg.geometry.g", "pkg.vault.v"): "line 1: geometry may import kernel, not vault",
        (
            "pkg.analysis.m",
            "pkg.figures",
        ): "line 1: analysis may import geometry, io, kernel, mechanics, vault, not figures",
    }


def test_the_registry_of_formats_names_no_module_above_io():
    """The assembly guide's writer is figures': figures registers it, io does not name it."""
    graph = imports(SRC, "curvefold")
    # its own writers, named by string, are read
    assert "curvefold.io._svg" in graph["curvefold.io._formats"]
    assert not any(layer_of(b) == "figures" for b in graph["curvefold.io._formats"])
    assert "curvefold.io._formats" in graph["curvefold.figures"]


def test_a_format_declared_without_its_writer_is_given_one_by_register_writer():
    """io declares the guide; figures gives its writer, and only a writer, only once."""
    from dataclasses import replace

    import pytest

    import curvefold.figures  # noqa: F401  (registers the guide's writer)
    from curvefold.figures._assembly import write_assembly
    from curvefold.io._formats import FORMATS, register_writer
    from curvefold.kernel import InputError, InternalError

    assert FORMATS["assembly"].load_writer() is write_assembly
    register_writer("assembly", "curvefold.figures._assembly:write_assembly")  # again: the same
    with pytest.raises(InternalError, match="'assembly' has no writer"):
        replace(FORMATS["assembly"], writer=None).load_writer()
    with pytest.raises(InputError, match="name must be a format of the registry"):
        register_writer("png", "curvefold.figures._plots:save_figure")
    with pytest.raises(InputError, match="writer must be a function or 'module:function'"):
        register_writer("assembly", "curvefold.figures._assembly.write_assembly")
    with pytest.raises(InputError, match="writer of 'assembly' is .* already"):
        register_writer("assembly", write_assembly)
    assert FORMATS["assembly"].writer == "curvefold.figures._assembly:write_assembly"


def test_imports_up_or_across_the_layers_are_reported(tmp_path):
    _package(
        tmp_path,
        BASE
        | {
            "pkg/kernel/k.py": "def f():\n    from ..geometry.g import x\n",
            "pkg/geometry/g.py": "import pkg.kernel.k\nx = 1\n",
            "pkg/geometry/h.py": "from .. import run\n",
            "pkg/vault/v.py": "from ..io import w\n",
            "pkg/io/w.py": "from pkg import app\n",
            "pkg/analysis/m.py": "from ..io.w import *\nfrom ..vault import v\nfrom ..geometry "
            "import g\n",
        },
    )
    graph = imports(tmp_path, "pkg")
    assert cycles(graph) == [["pkg.geometry.g", "pkg.kernel.k", "pkg.geometry.g"]]
    assert {(a, b): why for a, b, why in upward(graph)} == {
        ("pkg.kernel.k", "pkg.geometry.g"): "line 2: kernel may import no other layer, not "
        "geometry",
        ("pkg.geometry.h", "pkg"): "line 1: geometry imports the top-level package",
        ("pkg.vault.v", "pkg.io.w"): "line 1: vault may import geometry, kernel, not io",
        ("pkg.io.w", "pkg.app"): "line 1: io may import geometry, kernel, not app",
    }


KINDS = BASE | {
    "pkg/geometry/_kinds.py": (
        "from typing import Protocol\n"
        "class Shape(Protocol):\n"
        "    @property\n    def size(self) -> float: ...\n"
        "    def fold(self, angle): ...\n"
    ),
    "pkg/geometry/shapes.py": (
        # not every member: not a kind
        "from dataclasses import dataclass\n@dataclass\nclass Smooth:\n    size: float\n    def "
        "fold(self, angle): ...\nclass Panels:\n    size = 1.0\n    def fold(self, angle): "
        "...\n    def head(self, n): ...\nclass Sheet:\n    size = 2.0\n"
        "def _helper(): ...\n"
        "def check(x):\n    return isinstance(x, Smooth)\n"  # geometry may ask
    ),
}


def test_kinds_are_the_classes_with_every_member_of_a_protocol(tmp_path):
    _package(tmp_path, KINDS)
    assert kinds(tmp_path, "pkg") == {"Smooth": "Shape", "Panels": "Shape"}


def test_a_kind_test_outside_geometry_is_reported(tmp_path):
    _package(
        tmp_path,
        KINDS
        | {
            "pkg/io/w.py": (
                "from ..geometry.shapes import Panels, Sheet, Smooth\nfrom ..geometry "
                "import shapes\ndef write(x):\n    if isinstance(x.lattice, (Sheet, "
                "shapes.Panels)):\n        return 1\n    return isinstance(x, Sheet) or "
                "issubclass(type(x), Smooth | int) or type(x) is Panels\n"
            ),
            "pkg/app/a.py": "def run(x):\n    return x.size\n",  # asks the object: fine
        },
    )
    assert sorted(kind_tests(tmp_path, "pkg")) == [
        ("pkg.io.w", "Panels", "line 4: isinstance Panels, a kind of Shape"),
        ("pkg.io.w", "Panels", "line 6: type() is Panels, a kind of Shape"),
        ("pkg.io.w", "Smooth", "line 6: issubclass Smooth, a kind of Shape"),
    ]


def test_a_private_geometry_name_above_geometry_is_reported(tmp_path):
    _package(
        tmp_path,
        KINDS
        | {
            "pkg/io/w.py": "from ..geometry.shapes import Smooth, _helper\n",
            "pkg/analysis/c.py": "def f():\n    from pkg.geometry import shapes as s\n    return "
            "s._helper() + s.check(1)\n",
            "pkg/app/a.py": "import pkg.geometry.shapes as g\nfrom ..geometry import kinds\nx = "
            "g._helper, kinds.Shape, g.__name__\n",
            "pkg/vault/v.py": "class A:\n    _x = 1\nprint(A._x)\n",  # its own private names: fine
            "pkg/geometry/g.py": "from .shapes import _helper\n",  # within geometry: fine
        },
    )
    assert sorted(private_imports(tmp_path, "pkg")) == [
        (
            "pkg.analysis.c",
            "pkg.geometry.shapes._helper",
            "line 3: reads the private name _helper of pkg.geometry.shapes",
        ),
        (
            "pkg.app.a",
            "pkg.geometry.shapes._helper",
            "line 3: reads the private name _helper of pkg.geometry.shapes",
        ),
        (
            "pkg.io.w",
            "pkg.geometry.shapes._helper",
            "line 1: imports the private name _helper of pkg.geometry.shapes",
        ),
    ]


def test_a_long_module_is_reported(tmp_path):
    _package(
        tmp_path, BASE | {"pkg/io/long.py": "x = 1\n" * 701, "pkg/io/short.py": "x = 1\n" * 700}
    )
    assert long_modules(tmp_path, "pkg") == {"pkg.io.long": 701}
