"""Read-only arrays: how every immutable value of curvefold freezes the arrays it holds; and the
distinct values of an array, as every module takes them (:func:`distinct`)."""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator
from typing import Any, ClassVar

import numpy as np

__all__ = ["readonly", "frozen", "FrozenArrays", "distinct"]


def _chain(array: np.ndarray) -> Iterator[np.ndarray]:
    """``array`` and the arrays it is a view of."""
    item: object = array  # a base may be another buffer than an array
    while isinstance(item, np.ndarray):
        yield item
        item = item.base


def readonly(array: np.ndarray) -> np.ndarray:
    """Mark ``array``, and the arrays it is a view of, read-only in place; return it.

    For arrays the caller has just built; to hold someone else's array, use :func:`frozen`.

    Examples
    --------
    >>> a = readonly(np.zeros(4).reshape(2, 2))
    >>> a.base[0] = 1.0
    Traceback (most recent call last):
    ...
    ValueError: assignment destination is read-only
    """
    for a in _chain(array):
        a.flags.writeable = False
    return array


def frozen(array: np.ndarray) -> np.ndarray:
    """``array`` itself if nobody can write to it, else a read-only copy.

    Examples
    --------
    >>> a = np.zeros(2)
    >>> b = frozen(a)
    >>> b is a, a.flags.writeable, frozen(b) is b
    (False, True, True)
    """
    a = np.asarray(array)
    return a if not any(x.flags.writeable for x in _chain(a)) else readonly(np.array(a))


class FrozenArrays:
    """Mixin for frozen dataclasses that hold arrays.

    Every field that is an array, or a tuple of arrays, is held :func:`frozen`; pickling
    goes through the constructor, so the arrays come back read-only and cached values
    (``functools.cached_property``) are recomputed rather than stored. A subclass with its
    own ``__post_init__`` calls this one.

    Examples
    --------
    >>> import dataclasses
    >>> @dataclasses.dataclass(frozen=True)
    ... class Points(FrozenArrays):
    ...     xy: np.ndarray
    >>> p = Points(np.zeros((0, 2)))  # even an empty array is held read-only
    >>> p.xy.flags.writeable
    False
    """

    __dataclass_fields__: ClassVar[dict[str, dataclasses.Field[Any]]]  # a dataclass's

    def __post_init__(self) -> None:
        for name in self.__dataclass_fields__:
            value = getattr(self, name, None)  # fields with init=False may not be set yet
            if isinstance(value, np.ndarray):
                object.__setattr__(self, name, frozen(value))
            elif (
                isinstance(value, tuple) and value and all(isinstance(v, np.ndarray) for v in value)
            ):
                object.__setattr__(self, name, tuple(frozen(v) for v in value))

    def __reduce__(self) -> tuple[type[FrozenArrays], tuple[object, ...]]:
        return type(self), tuple(getattr(self, f.name) for f in dataclasses.fields(self) if f.init)


def distinct(values: np.ndarray) -> np.ndarray:
    """The distinct values (k,) of an array of integers or of numbers without NaN (any shape),
    ascending.

    ``np.unique(values)``, the same array, without its import of numpy.ma (NumPy 2 looks
    for a mask there: some 0.04 CPU-s in every process that calls it).

    Examples
    --------
    >>> distinct(np.array([[3, 1], [3, 2]])).tolist(), distinct(np.zeros(0, int)).tolist()
    ([1, 2, 3], [])
    """
    a = np.sort(np.ravel(values))
    return a[np.concatenate([[True], a[1:] != a[:-1]])] if a.size else a
