"""A package's public names, imported from their modules when first read (PEP 562).

A package that re-exports the names of its modules would import all of them, and what
they import, as soon as any one is used: ``curvefold --help`` would pay for SciPy and the
file writers. :func:`lazy_exports` gives such a package a module ``__getattr__`` (and
``__dir__``) that imports a name's module the first time the name is read, as SciPy and
NumPy do for their submodules; ``from package import name`` works as before.

Examples
--------
>>> import types
>>> package = types.ModuleType("demo")
>>> package.__getattr__, package.__dir__ = lazy_exports("demo", {"dedent": "textwrap", "json": "json"})
>>> package.dedent("  a")  # a name of a module
'a'
>>> package.json.__name__  # a module itself
'json'
>>> package.missing
Traceback (most recent call last):
...
AttributeError: module 'demo' has no attribute 'missing'
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Mapping

__all__ = ["lazy_exports"]


def lazy_exports(package: str, names: Mapping[str, str]) -> tuple[Callable[[str], object], Callable[[], list[str]]]:
    """``__getattr__`` and ``__dir__`` for a package whose public names are imported when first read.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    names : mapping of str to str
        Each public name -> the module that defines it, absolute or relative to the package
        (``".geometry.crease"``). A name that is the last part of its module's name is the
        module itself (``"measure": ".analysis.measure"``).

    Returns
    -------
    getattr, dir : callables
        To assign to the package's ``__getattr__`` and ``__dir__``. A name read once is
        kept in the package's namespace, so later reads cost nothing.
    """
    table = dict(names)

    def __getattr__(name: str) -> object:
        try:
            where = table[name]
        except KeyError:
            raise AttributeError(f"module {package!r} has no attribute {name!r}") from None
        module = importlib.import_module(where, package)
        value = module if module.__name__.rpartition(".")[2] == name else getattr(module, name)
        home = sys.modules.get(package)
        if home is not None:
            setattr(home, name, value)
        return value

    def __dir__() -> list[str]:
        home = sys.modules.get(package)
        return sorted(set(table) | set(vars(home) if home is not None else ()))

    return __getattr__, __dir__
