"""A package's public names, imported from their modules when first asked for.

A package declares its names in a table, module by module; :func:`lazy_exports` gives it
its ``__all__``, a module ``__getattr__`` that imports a name's module on first use (PEP
562, as NumPy and SciPy do) and a ``__dir__`` that lists the names. Importing the package
then imports none of its modules, so ``import curvefold.geometry`` costs what its
``__init__`` costs, and ``from curvefold.geometry import Crease`` what ``crease.py`` does.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Mapping, Sequence

__all__ = ["lazy_exports"]


def lazy_exports(
    package: str, table: Mapping[str, Sequence[str]]
) -> tuple[list[str], Callable[[str], object], Callable[[], list[str]]]:
    """``__all__``, ``__getattr__`` and ``__dir__`` of ``package`` from its table: module → names.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    table : mapping of str to sequence of str
        For each module of the package (relative, ``"crease"``), the names it exports.

    Returns
    -------
    names : list of str
        Every name, in the table's order: the package's ``__all__``.
    getattr : callable
        The module ``__getattr__``: the name from its module (imported then, and kept in
        the package's namespace), or :class:`AttributeError` for a name not in the table.
    dir : callable
        The module ``__dir__``: the package's namespace and every name.

    Examples
    --------
    The standard library's ``json`` package, its decoder's error exported anew:

    >>> names, get, listed = lazy_exports("json", {"decoder": ["JSONDecodeError"]})
    >>> names, get("JSONDecodeError").__name__, "JSONDecodeError" in listed()
    (['JSONDecodeError'], 'JSONDecodeError', True)
    >>> get("Nothing")
    Traceback (most recent call last):
    ...
    AttributeError: module 'json' has no attribute 'Nothing'
    """
    where = {name: module for module, names in table.items() for name in names}
    if len(where) != sum(len(names) for names in table.values()):
        raise ValueError(f"{package}: a name is exported by two modules")

    def __getattr__(name: str) -> object:
        if name not in where:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(f"{package}.{where[name]}"), name)
        setattr(sys.modules[package], name, value)  # asked once
        return value

    def __dir__() -> list[str]:
        return sorted(set(vars(sys.modules[package])) | set(where))

    return list(where), __getattr__, __dir__
