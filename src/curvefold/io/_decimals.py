"""Arrays rounded to decimal places, and JSON text of documents holding them, written from NumPy at
once.

:func:`json.dumps` writes every float with ``repr``, one at a time: a FOLD file holds some
10⁵ coordinates, and writing them was most of the file's cost. Here a document may hold
:class:`Decimals` leaves, arrays rounded to a number of decimal places; :func:`dumps` writes
it as :func:`json.dumps` writes the document with those arrays as lists, byte for byte.

A number x rounded to d places is the float nearest to the decimal D = n / 10^d. Where
x is not 0, 10⁻⁴ ≤ ``abs(x)`` < 10¹⁵ (``repr`` writes no exponent), ``abs(n)`` < 2^52 and the floats
near x are closer together than 10^-d, no other decimal of at most as many digits reads
back as x, so ``repr(x)`` is D without its trailing zeros (one decimal kept, as in
``1.0``): those digits are computed for all numbers at once. Below 10⁻⁴ ``repr`` writes
the same digits with an exponent (``-1.5e-05``), also computed at
once. Every other number (an exponent of 10¹⁵ or more, a float that is not nearest to its
rounded decimal) is written with ``repr``.
"""

from __future__ import annotations

import json
from dataclasses import dataclass

import numpy as np

from ..kernel._arrays import FrozenArrays

__all__ = ["Decimals", "Integers", "array_json", "dumps", "integer_json", "plain"]

_MARK = "\0curvefold:array\0"  # stands for a Decimals leaf in the text json.dumps writes


@dataclass(frozen=True, eq=False)
class Decimals(FrozenArrays):
    """An array of numbers written to ``decimals`` places (``np.round(values, decimals)``).

    Attributes
    ----------
    values : ndarray of float
        Already rounded.
    decimals : int
    """

    values: np.ndarray
    decimals: int

    @classmethod
    def round(cls, values, decimals: int) -> Decimals:
        """The numbers rounded to ``decimals`` places."""
        return cls(np.round(np.asarray(values, float), decimals), int(decimals))

    def tolist(self) -> list:
        return self.values.tolist()


@dataclass(frozen=True, eq=False)
class Integers(FrozenArrays):
    """An array of integers (vertex ids, groups) written at once.

    Attributes
    ----------
    values : ndarray of int
    """

    values: np.ndarray

    def tolist(self) -> list:
        return self.values.tolist()


def plain(doc):
    """The document with every :class:`Decimals` and :class:`Integers` as its list: JSON data
    (the leaves are values of objects, or items of arrays of objects and leaves; other arrays
    are left as they are)."""
    if isinstance(doc, (Decimals, Integers)):
        return doc.tolist()
    if isinstance(doc, dict):
        return {key: plain(value) for key, value in doc.items()}
    if isinstance(doc, list) and any(
        isinstance(value, (dict, Decimals, Integers)) for value in doc
    ):
        return [plain(value) for value in doc]
    return doc


def dumps(doc) -> str:
    """``json.dumps(plain(doc), allow_nan=False, separators=(",", ":"))``, the arrays written at
    once.

    Examples
    --------
    >>> dumps(
    ...     {
    ...         "x": Decimals.round([[0.1, -2.5], [1e-5, 0.0]], 3),
    ...         "n": [1, 2],
    ...         "i": Integers(np.array([[3, 4]])),
    ...     }
    ... )
    '{"x":[[0.1,-2.5],[0.0,0.0]],"n":[1,2],"i":[[3,4]]}'
    >>> dumps(
    ...     {"x": Decimals.round([3.14159, -0.0, 1.5e-5, 2.0], 6)}
    ... )  # exponents as repr writes them
    '{"x":[3.14159,-0.0,1.5e-05,2.0]}'
    """
    leaves: list[Decimals | Integers] = []

    def leaf(value):
        if isinstance(value, (Decimals, Integers)):
            leaves.append(value)
            return _MARK
        raise TypeError(f"Object of type {type(value).__name__} is not JSON serializable")

    text = json.dumps(doc, allow_nan=False, separators=(",", ":"), default=leaf)
    pieces = text.split(json.dumps(_MARK))
    if len(pieces) != len(leaves) + 1:  # the mark in a string of the document: no shortcut
        return json.dumps(plain(doc), allow_nan=False, separators=(",", ":"))
    texts = [
        array_json(a.values, a.decimals) if isinstance(a, Decimals) else integer_json(a.values)
        for a in leaves
    ]
    return "".join(piece for pair in zip(pieces, texts + [""]) for piece in pair)


def integer_json(values: np.ndarray) -> str:
    """``json.dumps(values.tolist(), separators=(",", ":"))`` of an array of integers, formatted at
    once.

    Examples
    --------
    >>> (
    ...     integer_json(np.array([[0, 1], [-2, 30]])),
    ...     integer_json(np.zeros((0, 2), int)),
    ...     integer_json(np.arange(3)),
    ... )
    ('[[0,1],[-2,30]]', '[]', '[0,1,2]')
    """
    x = np.asarray(values)
    # (booleans are JSON's true and false)
    if x.size == 0 or x.ndim == 0 or x.dtype.kind not in "iu":
        return json.dumps(x.tolist(), separators=(",", ":"))
    text = "%d"
    # the innermost axis first: "[%d,%d]", then "[[%d,%d],[%d,%d]]"…
    for length in reversed(x.shape):
        text = "[" + ",".join([text] * length) + "]"
    return text % tuple(x.ravel().tolist())


def array_json(values: np.ndarray, decimals: int) -> str:
    """``json.dumps(values.tolist(), separators=(",", ":"))`` of an array of floats (module notes).

    Parameters
    ----------
    values : ndarray of float
        Finite numbers, as rounded to ``decimals`` places (any others are written with ``repr``).
    decimals : int

    Examples
    --------
    >>> array_json(np.array([[1.25, -0.5, 12.0]]), 2), array_json(np.zeros((0, 3)), 2)
    ('[[1.25,-0.5,12.0]]', '[]')
    """
    x = np.asarray(values, float)
    if x.size == 0 or x.ndim == 0 or not np.isfinite(x).all() or not 0 <= decimals <= 15:
        return json.dumps(x.tolist(), allow_nan=False, separators=(",", ":"))
    flat = x.reshape(-1)
    scale = 10.0**decimals
    n = np.rint(flat * scale)
    size = np.abs(flat)
    exact = (np.abs(n) < 2.0**52) & (n / scale == flat) & (2 * np.spacing(size) < 10.0**-decimals)
    fast = (size == 0) | ((size >= 1e-4) & (size < 1e15) & exact)
    small = (size > 0) & (size < 1e-4) & exact
    count, depth = len(flat), x.ndim - 1
    m = np.where(fast, np.abs(n), 0).astype(np.int64)  # the digits of |x| · 10^d
    whole = max(len(str(int(m.max()))) - decimals, 1)  # digits before the point, one at least
    slow, tiny = np.flatnonzero(~(fast | small)), np.flatnonzero(small)
    texts = [repr(v) for v in flat[slow].tolist()]
    tiny_chars, tiny_keep = (
        _scientific(np.abs(n[tiny]).astype(np.int64), decimals, np.signbit(flat[tiny]))
        if tiny.size
        else ((), ())
    )
    # sign, digits, point, digits; a repr
    width = max([whole + max(decimals, 1) + 2, len(tiny_chars), *map(len, texts)])
    # each number's characters, then what follows it: column i of these (W, count) arrays is number
    # i
    chars = np.zeros((width + 2 * depth + 1, count), np.uint8)
    keep = np.zeros(chars.shape, bool)
    chars[0], keep[0] = ord("-"), np.signbit(flat)
    point, places = whole + 1, max(decimals, 1)
    units = m // 10**decimals  # the whole part, < 10^whole
    zeros = np.ones(count, bool)  # the fraction's digits so far, from its last, are 0
    trailing = np.zeros(count, np.int64)  # how many of them, but the first after the point
    for row in [*range(point + decimals, point, -1), *range(whole, 0, -1)]:  # the last digit first
        rest = m // 10  # (np.divmod takes four times as long)
        digit = m - 10 * rest
        chars[row], m = digit + 48, rest
        if point + 1 < row:
            zeros &= digit == 0
            trailing += zeros
    chars[point] = ord(".")
    if decimals == 0:
        chars[point + 1] = ord("0")  # "3.0"
    # no leading or trailing zeros, but one digit either side of the point
    keep[1:point] = units >= 10 ** np.arange(whole - 1, -1, -1, dtype=np.int64)[:, None]
    keep[whole] = keep[point] = True
    keep[point + 1 : point + 1 + places] = np.arange(places)[:, None] < places - trailing
    if tiny.size:
        chars[: len(tiny_chars), tiny] = tiny_chars
        keep[:width, tiny] = False
        keep[: len(tiny_chars), tiny] = tiny_keep
    if slow.size:  # repr, from the number's first row
        block = (
            np.frombuffer("".join(t.ljust(width, "\0") for t in texts).encode(), np.uint8)
            .reshape(-1, width)
            .T
        )
        chars[:width, slow] = block
        keep[:width, slow] = block != 0
    # after each number: "," closing and opening the axes that end there ("],[" in a matrix)
    ends = np.zeros(count, np.int64)
    for stride in np.cumprod(x.shape[::-1])[:-1]:
        ends += np.arange(1, count + 1) % stride == 0
    k = np.arange(depth)[:, None]
    chars[width : width + depth], chars[width + depth], chars[width + depth + 1 :] = (
        ord("]"),
        ord(","),
        ord("["),
    )
    keep[width : width + depth], keep[width + depth], keep[width + depth + 1 :] = (
        k[::-1] < ends,
        True,
        k < ends,
    )
    keep[width:, -1] = False
    body = chars.T[keep.T]
    return "[" * x.ndim + body.tobytes().decode() + "]" * x.ndim


def _scientific(
    n: np.ndarray, decimals: int, negative: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The characters (W, t) of ``repr`` of the numbers ±n / 10^decimals (each below 10⁻⁴, n ≥ 1 of
    (t,)), and which of them to keep: the sign, the first digit, the point and the others but
    trailing zeros, ``e-`` and two digits of the exponent.

    Examples
    --------
    >>> chars, keep = _scientific(np.array([15, 1, 99999]), 10, np.array([True, False, False]))
    >>> [chars[:, i][keep[:, i]].tobytes().decode() for i in range(3)]
    ['-1.5e-09', '1e-10', '9.9999e-06']
    """
    # of n
    digits = 1 + (n >= 10 ** np.arange(1, decimals + 1, dtype=np.int64)[:, None]).sum(axis=0)
    longest = int(digits.max(initial=1))
    mantissa = n * 10 ** (longest - digits)  # n's digits, each as long as the longest
    chars = np.zeros((longest + 6, len(n)), np.uint8)  # sign, digit, point, digits, "e-", exponent
    keep = np.zeros(chars.shape, bool)
    chars[0], keep[0] = ord("-"), negative
    zeros = np.ones(len(n), bool)  # the digits so far, from the last, are 0
    trailing = np.zeros(len(n), np.int64)  # how many of them, but the first digit
    # digit j (0: the first), at row j + 2 (the first at row 1)
    for j in range(longest - 1, -1, -1):
        rest = mantissa // 10
        digit = mantissa - 10 * rest
        chars[j + 2 if j else 1], mantissa = digit + 48, rest
        if j:
            zeros &= digit == 0
            trailing += zeros
    significant = longest - trailing
    chars[2] = ord(".")
    keep[1], keep[2] = True, significant > 1
    keep[3 : longest + 2] = np.arange(1, longest)[:, None] < significant
    exponent = decimals + 1 - digits  # x = d.ddd · 10^−exponent, exponent 5 … 15
    chars[longest + 2], chars[longest + 3] = ord("e"), ord("-")
    chars[longest + 4], chars[longest + 5] = exponent // 10 + 48, exponent % 10 + 48
    keep[longest + 2 :] = True
    return chars, keep
