"""Function-valued keys of a design: a number, an expression in s or a CSV column, checked on the
design's samples.

``kappa``, ``tau``, ``kappa_2d``, ``beta_left``, ``beta_right`` and ``alpha`` take a number,
an expression in ``s`` (:func:`curvefold.kernel.compile_expression`) or a CSV column
``{csv = "file.csv", column = "kappa"}`` read from the design file's folder
(:class:`TableColumn`); expressions and columns are checked on the design's sample grid
(:func:`check_function`), so a curvature that stops being positive is refused with the arc
length where it does. :mod:`curvefold.app._design` checks the other keys.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..io._columns import read_column, table_path
from ..kernel._arrays import readonly
from ..kernel._errors import InputError
from ..kernel._expr import Expression, compile_expression
from ..kernel._validate import Spec, describe

__all__ = ["TableColumn", "FunctionValue", "Context", "check_function"]


@dataclass(frozen=True, eq=False)
class TableColumn:
    """Samples of a function read from a CSV column, uniformly spaced over ``[0, length]``.

    ``np.asarray(column)`` gives the samples, so :func:`curvefold.kernel.as_function`
    accepts it directly.

    Parameters
    ----------
    path : str
        The path as written in the design file, relative to its folder.
    column : str
        Header of the column.
    values : (M,) ndarray
        The samples, read-only, M ≥ 2.
    """

    path: str
    column: str
    values: np.ndarray = field(repr=False)

    def __array__(self, dtype=None, copy=None) -> np.ndarray:
        if copy:
            return np.array(self.values, dtype=dtype)
        return np.asarray(self.values, dtype=dtype)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, TableColumn):
            return NotImplemented
        return (self.path, self.column) == (other.path, other.column) and np.array_equal(
            self.values, other.values
        )

    def __hash__(self) -> int:
        return hash((self.path, self.column, self.values.size))


FunctionValue = float | Expression | TableColumn


@dataclass(frozen=True)
class Context:
    """Where a design is checked: its name in messages, the folder of its CSV files and its
    samples along curve 1."""

    source: str
    base_dir: Path
    samples: int


def check_function(
    spec: Spec, value: Any, section: str, ctx: Context, length: float
) -> FunctionValue:
    """A function-valued key as an expression, a CSV column or a number, checked on the sample
    grid; every refusal is about ``spec.name``."""
    name = f"[{section}] {spec.name}"
    where = f"{ctx.source}: {name}"
    if isinstance(value, str):
        try:
            expression = compile_expression(value, name=name)
        except InputError as exc:
            raise InputError(f"{ctx.source}: {exc}", parameter=spec.name) from None
        grid = np.linspace(0.0, length, ctx.samples)
        spec.check_samples(expression(grid), where, lambda i: f"at s = {grid[i]:.6g}")
        return expression
    if isinstance(value, Mapping):
        try:
            return _read_table(spec, value, where, ctx, length)
        except InputError as exc:
            raise InputError(str(exc), parameter=spec.name) from None
    return spec.check(value, where)


def _read_table(
    spec: Spec, table: Mapping[str, Any], where: str, ctx: Context, length: float
) -> TableColumn:
    for k in table:
        if k not in ("csv", "column"):
            raise InputError(f"{where}: unknown key {k!r} in CSV table (allowed: csv, column)")
    raw, column = table.get("csv"), table.get("column", spec.name)
    if not isinstance(raw, str) or not raw.strip():
        raise InputError(
            f"{where}: csv must be a file name relative to the design file, got {describe(raw)}"
        )
    if not isinstance(column, str):
        raise InputError(f"{where}: column must be a column header, got {describe(column)}")
    file = table_path(raw, where, ctx.base_dir)
    label = f"{where} ({raw})"
    values, lines = read_column(file, column, length=length, label=label)
    grid = np.linspace(0.0, length, values.size)

    def at(i: int) -> str:
        return f"at line {lines[i]} (s = {grid[i]:.6g})"

    spec.check_samples(values, f"{label} column {column!r}", at)
    return TableColumn(raw, column, readonly(values))
