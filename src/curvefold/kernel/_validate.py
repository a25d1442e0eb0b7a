"""One validator per kind of value, and :class:`Spec`, the description of one parameter.

A :class:`Spec` names a parameter and says what kind of value it takes, its default, its
allowed range and unit, what it means and why its range is what it is. The owner of a
parameter declares its spec once (vault parameters beside
:class:`~curvefold.vault.VaultDesign`, output parameters in :mod:`curvefold.io._formats`,
curve and tube parameters in :mod:`curvefold.app._design`); design files, command-line
flags and the Python API all check values with :meth:`Spec.check`, so they accept the
same values and refuse the others with the same words.

Every refusal is one :class:`~curvefold.kernel.InputError` line: where the value
was given (a flag, a file key or a parameter name), the requirement and the value received,
e.g. ``design.toml: [vault] fold_angle must be in (0, 180) degrees, got 180.0``.

Kinds of value (:data:`KINDS`):

``real``
    a finite real number in ``range``, in ``unit``;
``integer``
    an integer in ``range``;
``count``
    an integer in ``range`` or the word ``"max"``;
``choice``
    one of ``choices``;
``text``
    one line of at most :data:`MAX_TEXT` characters, without control characters
    (:data:`curvefold.kernel._text.CONTROL`);
``flag``
    true or false;
``page``
    one of ``choices`` (case-insensitive) or a [width, height] pair in ``range``;
``formats``
    a list of names from ``choices``, duplicates dropped;
``cells``
    a list of distinct [i, j] integer pairs in ``range``;
``function``
    a real function of arc length whose values lie in ``range``: a number here;
    its owner parses expressions and tables and checks their samples with
    :meth:`Spec.check_samples`.
"""

from __future__ import annotations

import difflib
import json
import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

import numpy as np

from ._errors import InputError
from ._text import control_characters

__all__ = [
    "Interval",
    "Spec",
    "REQUIRED",
    "KINDS",
    "MAX_TEXT",
    "check_integer",
    "describe",
    "from_text",
    "is_integer",
    "suggest",
]

#: Longest string a ``text`` value may hold.
MAX_TEXT = 1000
#: Most pairs a ``cells`` value may hold.
MAX_CELLS = 10_000


class _Required:
    """The default of a parameter that has none."""

    def __repr__(self) -> str:
        return "REQUIRED"


#: Default of a required parameter.
REQUIRED: Any = _Required()


@dataclass(frozen=True)
class Interval:
    """A real interval with open or closed ends, written like ``"(0, 180)"`` or ``"[3, inf)"``.

    Examples
    --------
    >>> r = Interval.parse("[0, 3)")
    >>> 0 in r, 3 in r, str(r)
    (True, False, 'in [0, 3)')
    >>> Interval.parse("(0, inf)").mask(np.array([-1.0, 0.5, np.inf, np.nan])).tolist()
    [False, True, False, False]
    """

    lo: float
    hi: float
    lo_closed: bool
    hi_closed: bool

    @classmethod
    def parse(cls, text: str) -> Interval:
        """Read interval notation: ``"[0, 3)"``, ``"(0, inf)"``, ``"(-inf, inf)"``.

        Examples
        --------
        >>> Interval.parse("[3, inf)")
        Interval(lo=3.0, hi=inf, lo_closed=True, hi_closed=False)
        >>> str(Interval.parse("(-inf, inf)")), 0.0 in Interval.parse("(0, 0]")  # an empty interval
        ('finite', False)
        """
        lo, hi = (float(x) for x in text[1:-1].split(","))
        return cls(lo, hi, text[0] == "[", text[-1] == "]")

    def __contains__(self, x: float) -> bool:
        above = self.lo <= x if self.lo_closed else self.lo < x
        below = x <= self.hi if self.hi_closed else x < self.hi
        return above and below

    def mask(self, values: np.ndarray) -> np.ndarray:
        """Which of ``values`` (any shape) are finite and inside, same shape.

        Examples
        --------
        >>> Interval.parse("[0, 1]").mask(np.array([0.0, 1.0, 1.5])).tolist()
        [True, True, False]
        >>> Interval.parse("[0, 1]").mask(np.array([])).shape  # no values
        (0,)
        """
        with np.errstate(invalid="ignore"):
            above = values >= self.lo if self.lo_closed else values > self.lo
            below = values <= self.hi if self.hi_closed else values < self.hi
        return np.isfinite(values) & above & below

    @property
    def unbounded(self) -> bool:
        """Whether every finite number is inside."""
        return self.lo == -math.inf and self.hi == math.inf

    def __str__(self) -> str:
        if self.unbounded:
            return "finite"
        if self.hi == math.inf:
            return f"{'>=' if self.lo_closed else '>'} {_fmt(self.lo)}"
        left, right = "[" if self.lo_closed else "(", "]" if self.hi_closed else ")"
        return f"in {left}{_fmt(self.lo)}, {_fmt(self.hi)}{right}"


@dataclass(frozen=True, init=False)
class Spec:
    """One parameter: its name, kind of value, default, range, unit and meaning.

    Parameters
    ----------
    name : str
        The parameter's name (a design-file key, a keyword argument).
    kind : str
        One of :data:`KINDS`.
    default : object
        Value taken when the parameter is not given; :data:`REQUIRED` if it must be given,
        None if it is optional with no value.
    range : Interval or str or None
        Allowed values, as an :class:`Interval` or its notation (``"(0, 180)"``); for
        ``page`` the allowed width and height, for ``cells`` the allowed indices.
    unit : str
        Unit of the values, shown in messages and help (``"degrees"``, ``"model units"``).
    help : str
        One line: what the parameter means.
    why : str
        Why the range is what it is (``"memory bound"``), shown in messages and help.
    choices : tuple of str
        Allowed names for ``choice``, ``page`` and ``formats``.
    typical : Interval or str or None
        Where most designs lie, within ``range``: the span of a slider (the designer's
        controls); None lets the control take it from the range and the default.
    label : str
        The quantity in plain words, as a reader meets it beside its symbol (``"design
        fold angle"`` for ``fold_angle``); empty: the name says it.

    Examples
    --------
    >>> angle = Spec("fold_angle", "real", 90.0, "(0, 180)", "degrees", help="fold angle 2 alpha")
    >>> angle.check(45)
    45.0
    >>> angle.check(180, "design.toml: [vault] fold_angle")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: design.toml: [vault] fold_angle must be in (0, 180)
    degrees, got 180.0
    """

    name: str
    kind: str
    default: Any = REQUIRED
    range: Interval | None = None
    unit: str = ""
    help: str = ""
    why: str = ""
    choices: tuple[str, ...] = ()
    typical: Interval | None = None
    label: str = ""

    # The fields, in their order; a range also in its notation ("(0, 180)"), held as an Interval.
    def __init__(
        self,
        name: str,
        kind: str,
        default: Any = REQUIRED,
        range: Interval | str | None = None,
        unit: str = "",
        help: str = "",
        why: str = "",
        choices: Iterable[str] = (),
        typical: Interval | str | None = None,
        label: str = "",
    ) -> None:
        if kind not in KINDS:
            raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")
        range_, typical_ = (
            Interval.parse(x) if isinstance(x, str) else x for x in (range, typical)
        )
        values = {
            "name": name,
            "kind": kind,
            "default": default,
            "range": range_,
            "unit": unit,
            "help": help,
            "why": why,
            "choices": tuple(choices),
            "typical": typical_,
            "label": label,
        }
        for key, value in values.items():
            object.__setattr__(self, key, value)

    @property
    def required(self) -> bool:
        """Whether the parameter has no default."""
        return self.default is REQUIRED

    @property
    def requirement(self) -> str:
        """The range with its unit and reason, e.g. ``in [3, 200000] (memory bound)`` or ``≥ 1``."""
        text = str(self.range).replace(">=", "≥")
        text = f"{text} {self.unit}" if self.unit else text
        return f"{text} ({self.why})" if self.why else text

    def check(self, value: Any, where: str | None = None, *, shown: str | None = None) -> Any:
        """The value in its canonical type, or :class:`InputError`.

        Parameters
        ----------
        value : object
            The value to check (a number, a string, a list… as a design file holds it).
            A ``function`` takes a number here; its owner parses expressions and tables.
        where : str, optional
            How the user named it, starting the message; default :attr:`name`.
        shown : str, optional
            The value as the user typed it, for the message; default a short description
            of ``value`` with its type.

        Raises
        ------
        InputError
            The value is refused; its :attr:`~curvefold.kernel.CurvefoldError.parameter`
            is :attr:`name`.

        Examples
        --------
        >>> samples = Spec("samples", "integer", 201, "[3, 200000]", why="memory bound")
        >>> samples.check(3)
        3
        >>> samples.check(2)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: samples must be an integer in [3, 200000] (memory
        bound), got 2
        """
        try:
            return _VALIDATORS[self.kind](self, value, where or self.name, shown)
        except InputError as err:
            raise InputError(str(err), parameter=self.name) from None

    def check_samples(self, values: np.ndarray, where: str, at: Callable[[int], str]) -> None:
        """Raise naming the first of ``values`` (M,) that is not finite or not in range.

        ``at(i)`` says where sample i lies, e.g. ``"at s = 1.5"``. The error's parameter
        is :attr:`name`.

        Examples
        --------
        >>> kappa = Spec("kappa", "function", 1.0, "(0, inf)")
        >>> kappa.check_samples(np.array([1.0, 2.0]), "kappa", lambda i: f"at sample {i}") is None
        True
        >>> kappa.check_samples(np.array([1.0, 0.0]), "kappa", lambda i: f"at sample {i}")
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: kappa must be finite and > 0; at sample 1 it is 0
        """
        bad = np.flatnonzero(~_bounds(self).mask(values))
        if bad.size:
            i = int(bad[0])
            need = "finite" if _bounds(self).unbounded else f"finite and {self.requirement}"
            raise InputError(
                f"{where} must be {need}; {at(i)} it is {values[i]:.6g}", parameter=self.name
            )

    def describe(self) -> str:
        """One line for help texts: meaning, allowed values, unit and default.

        Examples
        --------
        >>> Spec("fold_angle", "real", 90.0, "(0, 180)", "degrees", help="fold angle").describe()
        'fold angle; in (0, 180) degrees; default 90'
        >>> Spec("name", "text").describe()  # no help, no range, no default
        ''
        """
        parts = [self.help] if self.help else []
        if (
            self.kind in ("real", "integer", "count", "function")
            and self.range is not None
            and not self.range.unbounded
        ):
            parts.append(self.requirement)
        elif self.kind in ("choice", "formats"):
            parts.append(
                "one of " + ", ".join(self.choices)
                if self.kind == "choice"
                else "any of " + ",".join(self.choices)
            )
        elif self.kind == "page":
            parts.append(f"{', '.join(self.choices)}, or WIDTH,HEIGHT in {self.unit}")
        elif self.unit:
            parts.append(self.unit)
        if not self.required and self.default not in (None, ""):
            parts.append(f"default {_plain_default(self.default)}")
        return "; ".join(parts)


def _plain_default(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple)):
        return ",".join(str(v) for v in value) if value else "none"
    return f"{value:g}" if isinstance(value, float) else str(value)


# --------------------------------------------------------------------------------------------
# The validators, one per kind: (spec, value, where, shown) -> value


def from_text(spec: Spec, text: str) -> Any:
    """Typed text (a command-line flag, a query parameter) as the value a design file would hold.

    Numbers read as integers, else as floats; ``formats`` split at commas; a page
    ``WIDTH,HEIGHT`` reads as two numbers; ``cells`` as JSON; a flag as true or false. Text
    that is no value of its kind is returned as it is, for :meth:`Spec.check` to refuse by
    name ("max", an expression in s, a word).

    Examples
    --------
    >>> from_text(Spec("samples", "integer"), "401"), from_text(Spec("a", "real"), "0.5")
    (401, 0.5)
    >>> from_text(Spec("samples", "integer"), "max")  # not a number: left for check to refuse
    'max'
    """
    if spec.kind in ("real", "integer", "count", "function"):
        for convert in (int, float):
            try:
                return convert(text)
            except ValueError:
                continue
        return text
    if spec.kind == "flag":
        return {"true": True, "false": False}.get(text.lower(), text)
    if spec.kind == "formats":
        return [f.strip() for f in text.split(",") if f.strip()]
    if spec.kind == "cells":
        try:
            return json.loads(text)
        except (ValueError, RecursionError):
            return text
    if spec.kind == "page" and "," in text:
        try:
            return [float(v) for v in text.split(",")]
        except ValueError:
            return text
    return text


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
        value, (bool, np.bool_)
    )


def is_integer(value: Any) -> bool:
    """Whether ``value`` is an integer: a Python or NumPy integer, not a boolean nor an integral
    float.

    Examples
    --------
    >>> is_integer(3), is_integer(np.int64(3)), is_integer(True), is_integer(3.0)
    (True, True, False, False)
    """
    return _is_number(value) and isinstance(value, (int, np.integer))


def check_integer(value: Any, name: str, range: Interval | str, *, why: str = "") -> int:
    """``value`` as an ``int``, or :class:`InputError` naming ``name``, the range, the reason and
    the value.

    The one check of an integer argument of the Python API (a design's integers are
    checked by their :class:`Spec`, which says the same words).

    Parameters
    ----------
    value : object
    name : str
        The argument's name, starting the message and set as the error's parameter.
    range : Interval or str
        Allowed values, e.g. ``"[1, inf)"``.
    why : str, keyword-only
        Why the range is what it is, shown in the message.

    Examples
    --------
    >>> check_integer(np.int64(4), "count", "[1, inf)")
    4
    >>> check_integer(0, "count", "[1, inf)")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: count must be an integer ≥ 1, got 0
    >>> check_integer(True, "dpi", "[10, 2400]", why="printable")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: dpi must be an integer in [10, 2400] (printable), got
    boolean True
    """
    return Spec(name, "integer", range=range, why=why).check(value)


def _bounds(spec: Spec) -> Interval:
    """The range of a spec of a kind that has one (a number, a function, a page, cells)."""
    assert spec.range is not None, f"{spec.name}: a {spec.kind} has a range"
    return spec.range


def _real(spec: Spec, value: Any, where: str, shown: str | None) -> float:
    if not _is_number(value):
        unit = f" ({spec.unit})" if spec.unit else ""
        raise InputError(f"{where} must be a number{unit}, got {shown or describe(value)}")
    try:
        x = float(value)
    except OverflowError:
        raise InputError(
            f"{where} is too large, got an integer of {int(value).bit_length()} bits"
        ) from None
    if not math.isfinite(x):
        raise InputError(f"{where} must be a finite number, got {shown or x}")
    if x not in _bounds(spec):
        raise InputError(f"{where} must be {spec.requirement}, got {shown or repr(x)}")
    return x


def _function(spec: Spec, value: Any, where: str, shown: str | None) -> float:
    if not _is_number(value):
        raise InputError(
            f"{where} must be a number, an expression in s or a table "
            f"{{csv = ..., column = ...}}, got {shown or describe(value)}"
        )
    return _real(spec, value, where, shown)


def _integer(spec: Spec, value: Any, where: str, shown: str | None) -> int:
    if not is_integer(value) or value not in _bounds(spec):
        raise InputError(
            f"{where} must be an integer {spec.requirement}, got {shown or describe(value)}"
        )
    return int(value)


def _count(spec: Spec, value: Any, where: str, shown: str | None) -> int | str:
    if isinstance(value, str) and value == "max":
        return value
    if not is_integer(value) or value not in _bounds(spec):
        raise InputError(
            f'{where} must be an integer {spec.requirement} or "max", got '
            f"{shown or describe(value)}"
        )
    return int(value)


def _choice(spec: Spec, value: Any, where: str, shown: str | None) -> str:
    if not isinstance(value, str) or value not in spec.choices:
        raise InputError(
            f"{where} must be one of {_quoted(spec.choices)}, got {shown or describe(value)}"
        )
    return value


def _text(spec: Spec, value: Any, where: str, shown: str | None) -> str:
    if not isinstance(value, str) or len(value) > MAX_TEXT:
        raise InputError(
            f"{where} must be a string of at most {MAX_TEXT} characters, got "
            f"{shown or describe(value)}"
        )
    bad = control_characters(value)
    if bad:
        raise InputError(
            f"{where} must be one line of printable text; character {bad[0] + 1} is "
            f"the control character U+{ord(value[bad[0]]):04X}"
        )
    return value


def _flag(spec: Spec, value: Any, where: str, shown: str | None) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise InputError(f"{where} must be true or false, got {shown or describe(value)}")
    return bool(value)


def _page(spec: Spec, value: Any, where: str, shown: str | None) -> str | tuple[float, float]:
    if isinstance(value, str):
        canonical = {c.casefold(): c for c in spec.choices}.get(value.strip().casefold())
        if canonical is not None:
            return canonical
    elif isinstance(value, (list, tuple)) and len(value) == 2:
        side = Spec(spec.name, "real", range=spec.range, unit=spec.unit)
        return tuple(
            _real(side, v, f"{where} {name}", None) for v, name in zip(value, ("width", "height"))
        )  # type: ignore[return-value]
    pair = f"[width, height] in {spec.unit}" if shown is None else f"WIDTH,HEIGHT in {spec.unit}"
    raise InputError(
        f"{where} must be one of {_quoted(spec.choices)} or {pair}, got {shown or describe(value)}"
    )


def _formats(spec: Spec, value: Any, where: str, shown: str | None) -> tuple[str, ...]:
    if not isinstance(value, (list, tuple)):
        raise InputError(
            f"{where} must be an array of format names ({', '.join(spec.choices)}), "
            f"got {shown or describe(value)}"
        )
    for item in value:
        if not isinstance(item, str) or item not in spec.choices:
            raise InputError(
                f"{where}: unknown format {describe(item)} (allowed: {', '.join(spec.choices)})"
            )
    return tuple(dict.fromkeys(value))


def _cells(spec: Spec, value: Any, where: str, shown: str | None) -> tuple[tuple[int, int], ...]:
    if not isinstance(value, (list, tuple)) or not 1 <= len(value) <= MAX_CELLS:
        raise InputError(
            f"{where} must be an array of 1 to {MAX_CELLS} [i, j] pairs, got "
            f"{shown or describe(value)}"
        )
    seen: dict[tuple[int, int], int] = {}
    for n, cell in enumerate(value):
        pair_ok = isinstance(cell, (list, tuple)) and len(cell) == 2
        if not (pair_ok and all(is_integer(x) and x in _bounds(spec) for x in cell)):
            raise InputError(
                f"{where}[{n}] must be a pair [i, j] of integers {spec.range}, got {describe(cell)}"
            )
        pair = (int(cell[0]), int(cell[1]))
        if pair in seen:
            raise InputError(
                f"{where}[{n}] repeats cell {list(pair)} (first at index {seen[pair]})"
            )
        seen[pair] = n
    return tuple(seen)


_VALIDATORS: Mapping[str, Callable[[Spec, Any, str, str | None], Any]] = MappingProxyType(
    {
        "real": _real,
        "integer": _integer,
        "count": _count,
        "choice": _choice,
        "text": _text,
        "flag": _flag,
        "page": _page,
        "formats": _formats,
        "cells": _cells,
        "function": _function,
    }
)

#: Every kind of value a :class:`Spec` can take.
KINDS = tuple(_VALIDATORS)


# --------------------------------------------------------------------------------------------
# Messages


def _fmt(x: float) -> str:
    """A bound as typed: ``inf``, an integer, ``1e13`` past ten digits, or the float's repr."""
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    if abs(x) >= 1e10:
        return f"{x:g}".replace("e+", "e")
    return str(int(x)) if x == int(x) else repr(x)


def _quoted(choices: tuple[str, ...]) -> str:
    return ", ".join(f'"{c}"' for c in choices)


_TYPE_NAMES = (
    (bool, "boolean"),
    (str, "string"),
    (int, "integer"),
    (float, "float"),
    (Mapping, "table"),
)


def describe(value: Any) -> str:
    """A value for a message: its TOML type name and a short repr, e.g. ``string '90'``.

    Examples
    --------
    >>> describe("90"), describe(2.0), describe([1]), describe(None)
    ("string '90'", '2.0', 'array [1]', 'NoneType None')
    """
    if isinstance(value, np.generic):
        value = value.item()
    try:
        text = repr(value)
    except ValueError:  # an integer past Python's digit limit
        text = "<too many digits>"
    if len(text) > 60:
        text = text[:57] + "..."
    if _is_number(value):
        return text
    for kind, name in _TYPE_NAMES:
        if isinstance(value, kind):
            return f"{name} {text}"
    if isinstance(value, (list, tuple)):
        return f"array {text}"
    return f"{type(value).__name__} {text}"


def suggest(key: Any, options: Iterable[str]) -> str:
    """``"; did you mean 'x'?"`` for the closest of ``options``, or ``""``.

    Examples
    --------
    >>> suggest("fold_angel", ["fold_angle", "samples"])
    "; did you mean 'fold_angle'?"
    >>> suggest("zzz", []), suggest(3, ["a"])  # nothing close, not a name
    ('', '')
    """
    if not isinstance(key, str):
        return ""
    close = difflib.get_close_matches(key, list(options), n=1)
    return f"; did you mean {close[0]!r}?" if close else ""
