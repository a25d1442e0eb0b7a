"""The public surface of the core: every public callable shows an example that the doctests run.

The core is the packages :data:`CORE` and the names of ``curvefold.__all__``. A public
callable is a function or class of a public module (no path component starting with ``_``)
that the module declares (its ``__all__``, else the names it defines without a leading
``_``), a name of a package's ``__all__`` (``curvefold.mechanics`` keeps its modules
private), and every public method a public class defines. Each must have a docstring
(its own, or the one it inherits from the method it implements) with a ``>>>`` example,
and that docstring must be one the doctest finder collects, so that ``pytest
--doctest-modules`` runs it: a method of a class re-labelled to its package (its
``__module__`` changed) is not collected from its own module, and must be listed in the
package's ``__test__``.
"""

from __future__ import annotations

import ast
import doctest
import importlib
import importlib.util
import inspect
import os
import pkgutil
import subprocess
import sys
import textwrap
import types
from collections.abc import Iterable, Iterator
from pathlib import Path

import pytest

import curvefold

#: The core packages: every public callable in them carries a run example.
CORE = ("kernel", "geometry", "vault", "mechanics")


def _is_private(module_name: str) -> bool:
    return any(part.startswith("_") for part in module_name.split("."))


def core_modules(packages: Iterable[str] = CORE) -> list[types.ModuleType]:
    """Every module of the packages, private ones included (their docstrings are collected too)."""
    out = []
    for name in packages:
        package = importlib.import_module(f"curvefold.{name}")
        out.append(package)
        out += [
            importlib.import_module(info.name)
            for info in pkgutil.walk_packages(package.__path__, package.__name__ + ".")
        ]
    return out


def declared_names(module: types.ModuleType) -> list[str]:
    """The names a module declares public: its ``__all__``, else what it defines without a
    leading ``_``."""
    if hasattr(module, "__all__"):
        return list(module.__all__)
    return [
        n
        for n, v in vars(module).items()
        if not n.startswith("_") and getattr(v, "__module__", None) == module.__name__
    ]


def public_callables(modules: Iterable[types.ModuleType]) -> Iterator[tuple[str, object]]:
    """(qualified name, object) of every public function, class and public method of the public
    modules, once each."""
    seen: set[int] = set()
    for module in modules:
        if _is_private(module.__name__):
            continue
        for name in declared_names(module):
            obj = getattr(module, name)
            if not (inspect.isfunction(obj) or inspect.isclass(obj)) or id(obj) in seen:
                continue
            seen.add(id(obj))
            yield f"{module.__name__}.{name}", obj
            if inspect.isclass(obj):
                for attr, value in vars(obj).items():
                    function = getattr(value, "__func__", value)  # classmethod, staticmethod
                    if not attr.startswith("_") and inspect.isfunction(function):
                        yield f"{module.__name__}.{name}.{attr}", function


def collected_docstrings(modules: Iterable[types.ModuleType]) -> set[str]:
    """The docstrings (cleaned) the doctest finder collects from the modules: the examples
    ``--doctest-modules`` runs."""
    finder = doctest.DocTestFinder(exclude_empty=True)
    return {
        inspect.cleandoc(test.docstring)
        for module in modules
        for test in finder.find(module)
        if test.examples
    }


def without_example(
    modules: list[types.ModuleType], extra: Iterable[tuple[str, object]] = ()
) -> list[str]:
    """Public callables whose docstring has no example, or has one that no doctest runs, each
    with why."""
    run = collected_docstrings(modules)
    out = []
    for name, obj in [*public_callables(modules), *extra]:
        doc = inspect.getdoc(obj) or ""
        if ">>>" not in doc:
            out.append(f"{name}: no example")
        elif doc not in run:
            out.append(f"{name}: its example is not collected by the doctests")
    return out


def top_level() -> list[tuple[str, object]]:
    """The callables of ``curvefold.__all__`` (classes with their public methods)."""
    fake = types.ModuleType("curvefold")
    for name in curvefold.__all__:
        setattr(fake, name, getattr(curvefold, name))
    fake.__all__ = list(curvefold.__all__)
    return list(public_callables([fake]))


def test_every_public_callable_of_the_core_has_an_example_that_runs():
    missing = without_example(core_modules(), top_level())
    assert not missing, "public callables without a run example:\n" + "\n".join(missing)


def test_the_core_has_public_callables_to_check():
    """The walk finds what the core exports (a walk that found nothing would pass the test
    above)."""
    names = {name for name, _ in public_callables(core_modules())}
    assert {
        "curvefold.geometry.Structure.state",
        "curvefold.geometry.Lattice.refold",
        "curvefold.geometry.StructureLattice.fold_points",
        "curvefold.geometry.SingleFold.mesh",
        "curvefold.mechanics.analyse_load",
        "curvefold.mechanics.Material.crease_stiffness",
        "curvefold.vault.sweep",
        "curvefold.vault.Atlas.values",
        "curvefold.kernel.Spec.check",
    } <= names
    assert len(names) > 150


def _module(name: str, source: str) -> types.ModuleType:
    module = types.ModuleType(name)
    exec(compile(textwrap.dedent(source), f"<{name}>", "exec"), module.__dict__)
    return module


def test_a_callable_without_an_example_is_named():
    fake = _module(
        "fake_core",
        '''
        def shown(x):
            """Twice x.

            >>> shown(2)
            4
            """
            return 2 * x

        def bare(x):
            """Twice x, told but not shown."""
            return 2 * x

        class Thing:
            """A thing.

            >>> Thing().size()
            1
            """

            def size(self):
                """One.

                >>> Thing().size()
                1
                """
                return 1

            def weight(self):
                return 1

            def _private(self):
                return 0
        ''',
    )
    assert without_example([fake]) == [
        "fake_core.bare: no example",
        "fake_core.Thing.weight: no example",
    ]


def test_an_example_that_no_doctest_collects_is_named():
    """A class re-labelled to another module (as a package re-labels what its private modules
    define)."""
    fake = _module(
        "fake_private",
        '''
        __all__ = ["Relabelled"]

        class Relabelled:
            """Shown.

            >>> 1 + 1
            2
            """

            def method(self):
                """Shown too.

                >>> 2 + 2
                4
                """
        ''',
    )
    fake.Relabelled.__module__ = "fake_package"
    assert without_example([fake]) == [
        "fake_private.Relabelled: its example is not collected by the doctests",
        "fake_private.Relabelled.method: its example is not collected by the doctests",
    ]


def test_an_inherited_docstring_counts_where_its_example_runs():
    """A method implementing a documented one (``Constant.value`` of ``ScalarFunction.value``)
    shows that example."""
    from curvefold.kernel import Constant, ScalarFunction

    assert inspect.getdoc(Constant.value) == inspect.getdoc(ScalarFunction.value)
    assert inspect.getdoc(ScalarFunction.value) in collected_docstrings(core_modules(["kernel"]))


# -- the packages' declared surfaces -------------------------------------------------------------

#: Every package, with the heavy libraries importing it may bring in (measured on main before
#: the lazy exports: only the mechanics, whose model is scipy.sparse matrices, imported scipy).
PACKAGES = {
    "kernel": (),
    "geometry": (),
    "vault": (),
    "io": (),
    "analysis": (),
    "figures": (),
    "mechanics": ("scipy",),
    "app": (),
}
#: Libraries a package import must not bring in unless listed above.
HEAVY = ("scipy", "matplotlib")


def surface_problems(package: types.ModuleType) -> list[str]:
    """What is wrong with a package's ``__all__``: a name missing, a module, or a name its
    submodule shadows."""
    names = getattr(package, "__all__", None)
    if not names:
        return [f"{package.__name__} declares no __all__"]
    out = []
    submodules = {info.name for info in pkgutil.iter_modules(package.__path__)}
    for name in names:
        if name in submodules:
            out.append(
                f"{package.__name__}.{name} is also a module's name: importing the module "
                "replaces it"
            )
        elif not hasattr(package, name):
            out.append(f"{package.__name__}.{name} is in __all__ but cannot be imported")
        elif inspect.ismodule(getattr(package, name)):
            out.append(f"{package.__name__}.{name} is a module")
    missing = set(names) - set(dir(package))
    if missing:
        out.append(f"{package.__name__}: dir() leaves out {sorted(missing)}")
    return out


def heavy_imports(module: str, heavy: Iterable[str] = HEAVY, path: str | None = None) -> list[str]:
    """The libraries of ``heavy`` that ``import module`` brings in, in a fresh interpreter."""
    code = f"import sys, {module}; print(' '.join(m for m in {tuple(heavy)!r} if m in sys.modules))"
    env = dict(
        os.environ, PYTHONPATH=os.pathsep.join(p for p in (path, os.environ.get("PYTHONPATH")) if p)
    )
    done = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
        check=True,
    )
    return done.stdout.split()


@pytest.mark.parametrize("name", PACKAGES)
def test_every_package_declares_its_public_names(name):
    package = importlib.import_module(f"curvefold.{name}")
    assert not surface_problems(package)
    for item in package.__all__:  # the package's name is its module's object
        value = getattr(package, item)
        module = getattr(value, "__module__", None)
        if (
            module
            and module.startswith(f"curvefold.{name}.")
            and hasattr(sys.modules[module], item)
        ):
            assert getattr(sys.modules[module], item) is value


@pytest.mark.parametrize("name", PACKAGES)
def test_importing_a_package_brings_in_no_heavy_library(name):
    assert set(heavy_imports(f"curvefold.{name}")) <= set(PACKAGES[name])


def test_a_package_surface_that_does_not_resolve_is_named(tmp_path):
    package = tmp_path / "fakepkg"
    package.mkdir()
    (package / "part.py").write_text("def shown():\n    return 1\n")
    (package / "__init__.py").write_text(
        textwrap.dedent("""
        import json
        from curvefold.kernel._exports import lazy_exports
        __all__, __getattr__, __dir__ = lazy_exports(__name__, {"part": ["shown", "gone", "part"]})
        """)
    )
    sys.path.insert(0, str(tmp_path))
    try:
        fake = importlib.import_module("fakepkg")
        assert surface_problems(fake) == [
            "fakepkg.gone is in __all__ but cannot be imported",
            "fakepkg.part is also a module's name: importing the module replaces it",
        ]
        assert fake.shown() == 1
    finally:
        sys.path.remove(str(tmp_path))
        for key in [k for k in sys.modules if k.startswith("fakepkg")]:
            del sys.modules[key]
    assert heavy_imports("fakepkg", ("json", "scipy"), path=str(tmp_path)) == ["json"]


# -- the packages' stubs: the lazy names as type checkers see them -------------------------------


def stub_exports(source: str, package: str) -> tuple[dict[str, tuple[str, str]], list[str]]:
    """What an ``__init__.pyi`` declares: its ``__all__``, and each name it imports.

    Returns the imported names, each → (absolute module, name there), and the ``__all__``.
    """
    imported: dict[str, tuple[str, str]] = {}
    listed: list[str] = []
    for node in ast.parse(source).body:
        if isinstance(node, ast.ImportFrom):
            module = importlib.util.resolve_name("." * node.level + (node.module or ""), package)
            imported |= {alias.asname or alias.name: (module, alias.name) for alias in node.names}
        elif isinstance(node, ast.Assign) and ast.unparse(node.targets[0]) == "__all__":
            listed = list(ast.literal_eval(node.value))
    return imported, listed


def _stub_source(module: str, name: str) -> object:
    """``from module import name`` at run time: an attribute of the module, else its submodule."""
    try:
        return getattr(importlib.import_module(module), name)
    except AttributeError:
        return importlib.import_module(f"{module}.{name}")


def stub_problems(package: types.ModuleType, source: str) -> list[str]:
    """Where a package's stub and its lazy exports differ.

    A name the package exports that the stub leaves out of its ``__all__`` or does not import,
    a name the stub declares that the package does not export, and a name the stub imports
    from a module whose object is not the package's.
    """
    imported, listed = stub_exports(source, package.__name__)
    exported = list(package.__all__)
    where = package.__name__
    out = [
        f"{where}.{name}: exported, not in the stub's __all__"
        for name in exported
        if name not in listed
    ]
    out += [
        f"{where}.{name}: in the stub's __all__, not exported"
        for name in listed
        if name not in exported
    ]
    out += [
        f"{where}.{name}: in the stub's __all__, not imported"
        for name in listed
        if name not in imported
    ]
    for name, (module, original) in imported.items():
        if name not in exported:
            out.append(f"{where}.{name}: imported by the stub, not exported")
        elif _stub_source(module, original) is not getattr(package, name):
            out.append(f"{where}.{name}: the stub imports another object, from {module}")
    return out


def _stub(package: types.ModuleType) -> str:
    return Path(str(package.__file__)).with_suffix(".pyi").read_text(encoding="utf-8")


@pytest.mark.parametrize("name", ["", *PACKAGES])
def test_every_package_stub_declares_exactly_its_lazy_names(name):
    package = importlib.import_module(f"curvefold.{name}".rstrip("."))
    assert stub_problems(package, _stub(package)) == []


def test_every_package_with_lazy_names_has_a_stub():
    """A package loading names through a module ``__getattr__`` is opaque to type checkers."""
    found = pkgutil.walk_packages(curvefold.__path__, "curvefold.")
    packages = [curvefold, *(importlib.import_module(info.name) for info in found if info.ispkg)]
    lazy = [package for package in packages if "__getattr__" in vars(package)]
    assert {"curvefold", "curvefold.geometry", "curvefold.mechanics"} <= {p.__name__ for p in lazy}
    stubs = [Path(str(package.__file__)).with_suffix(".pyi") for package in lazy]
    assert [str(stub) for stub in stubs if not stub.is_file()] == []


#: Damages to the geometry's stub: the texts replaced, each with its replacement.
STUB_DAMAGES = {
    "a name left out": [("from ._crease import Crease as Crease\n", ""), ('    "Crease",\n', "")],
    "a name not exported": [
        ("from ._mesh import Mesh as Mesh\n", "from ._mesh import Mesh as Mesh, Part as Part\n"),
        ('    "Mesh",\n', '    "Mesh",\n    "Part",\n'),
    ],
    "a name not imported": [("from ._lattice_pattern import Pattern as Pattern\n", "")],
    "a name from another module": [
        ("from ._structure import State as State\n", "from ._lattice import Lattice as State\n"),
    ],
}


@pytest.mark.parametrize(
    ("damage", "expected"),
    [
        ("a name left out", ["curvefold.geometry.Crease: exported, not in the stub's __all__"]),
        (
            "a name not exported",
            [
                "curvefold.geometry.Part: in the stub's __all__, not exported",
                "curvefold.geometry.Part: imported by the stub, not exported",
            ],
        ),
        (
            "a name not imported",
            ["curvefold.geometry.Pattern: in the stub's __all__, not imported"],
        ),
        (
            "a name from another module",
            [
                "curvefold.geometry.State: the stub imports another object, from "
                "curvefold.geometry._lattice"
            ],
        ),
    ],
)
def test_a_damaged_stub_is_named(damage, expected):
    import curvefold.geometry as geometry

    source = _stub(geometry)
    for old, new in STUB_DAMAGES[damage]:
        assert source.count(old) == 1, old  # the damage applies to the stub as it stands
        source = source.replace(old, new)
    assert stub_problems(geometry, source) == expected


@pytest.mark.slow
def test_a_type_checker_sees_the_lazy_names_through_the_stubs(tmp_path, monkeypatch):
    """mypy, run on a user's imports, finds the classes (without the stubs: ``object``)."""
    api = pytest.importorskip("mypy.api")
    probe = tmp_path / "probe.py"
    probe.write_text(
        "from curvefold import Structure\nfrom curvefold.geometry import Crease\n"
        "reveal_type(Crease)\nreveal_type(Structure.state)\n"
    )
    monkeypatch.setenv("MYPYPATH", str(Path(str(curvefold.__file__)).parents[1]))  # this checkout
    out, _, _ = api.run(
        [
            str(probe),
            "--config-file=",
            "--follow-imports=silent",
            "--no-error-summary",
            f"--cache-dir={tmp_path / 'cache'}",
            "--python-version=3.11",
        ]
    )
    revealed = [
        line.split("Revealed type is ", 1)[1]
        for line in out.splitlines()
        if "Revealed type" in line
    ]
    assert len(revealed) == 2, out
    assert revealed[0].startswith('"def (curve: curvefold.geometry._curve.SpaceCurve'), revealed[0]
    assert revealed[1].endswith('-> curvefold.geometry._structure.State"'), revealed[1]
