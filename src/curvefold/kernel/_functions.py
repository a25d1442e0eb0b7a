"""Scalar functions of arc length: curvature, torsion, fold angle, ruling angle.

Users give these as a number, a vectorised Python callable ``f(s)`` or samples over
``[0, L]``. :func:`as_function` turns any of them into a :class:`ScalarFunction` that can
be evaluated anywhere in ``[0, L]`` together with its first derivative, which the
ruling-angle rate ``β'`` (and hence the regression limits) needs.

Every :class:`ScalarFunction` is a small frozen dataclass holding data, never a closure,
so curves, creases, lattices and everything built on them pickle (for process pools and
distributed sweeps). A user's own callable pickles only if it does itself (a lambda or a
closure does not).

Derivatives: exact for constants; the derivative of the interpolating cubic spline for
samples; for callables a sixth-order finite difference that samples the function only
inside ``[0, L]``: the central stencil ``s ± h, ±2h, ±3h`` where it fits, otherwise the
seven-point stencil of the same order shifted into the domain (truncation ~h⁶ f⁽⁷⁾ with
h = min(1e-3·max(L, 1), L/8), rounding ``~1e-13·|f|/h`` centrally and up to ``~1e-12·|f|/h``
for the fully one-sided stencil at the ends).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cache
from typing import Union

import numpy as np

from ._arrays import FrozenArrays, readonly
from ._errors import InputError

__all__ = [
    "ScalarFunction",
    "Constant",
    "Sampled",
    "UserFunction",
    "Scaled",
    "Differenced",
    "as_function",
    "check_finite",
    "difference_derivative",
    "difference_step",
]

FunctionLike = Union[float, int, Callable[[np.ndarray], np.ndarray], np.ndarray, "ScalarFunction"]


class ScalarFunction(ABC):
    """A real function of arc length on ``[0, L]`` with its derivative.

    Call it on an array ``s`` of any shape for the values (same shape);
    :meth:`derivative` gives d/ds. ``constant`` is the value when the function is
    constant (callers then take exact shortcuts), else None.

    Examples
    --------
    >>> f = as_function(lambda s: s**2, name="kappa", length=1.0)
    >>> f(np.array([0.5])).tolist(), f.constant
    ([0.25], None)
    >>> as_function(2.0, name="kappa", length=1.0).constant
    2.0
    """

    constant: float | None = None

    def __call__(self, s: np.ndarray) -> np.ndarray:
        return self.value(np.asarray(s, dtype=float))

    @abstractmethod
    def value(self, s: np.ndarray) -> np.ndarray:
        """f(s) for a float array ``s``, same shape.

        Examples
        --------
        >>> Constant(2.0).value(np.array([0.0, 1.0])).tolist()
        [2.0, 2.0]
        >>> Constant(2.0).value(np.array([])).shape  # no points, no values
        (0,)
        """

    @abstractmethod
    def derivative(self, s: np.ndarray) -> np.ndarray:
        """df/ds at ``s``, same shape.

        Examples
        --------
        >>> Sampled(np.array([0.0, 1.0, 2.0]), 2.0).derivative(np.array([0.5, 1.5])).round(
        ...     6
        ... ).tolist()
        [1.0, 1.0]
        >>> Constant(2.0).derivative(
        ...     np.array([0.0])
        ... ).tolist()  # a constant's derivative is exactly 0
        [0.0]
        """

    def scaled(self, factor: float) -> ScalarFunction:
        """``factor · self``.

        Examples
        --------
        >>> Constant(2.0).scaled(-0.5).constant
        -1.0
        >>> Sampled(np.array([0.0, 1.0]), 1.0).scaled(0.0)(
        ...     np.array([0.5])
        ... ).tolist()  # zero times anything
        [0.0]
        """
        return Scaled(self, float(factor))


@dataclass(frozen=True)
class Constant(ScalarFunction):
    """A constant c; derivative exactly 0.

    Examples
    --------
    >>> (
    ...     Constant(0.0)(np.array([0.0, 1.0])).tolist(),
    ...     Constant(0.0).derivative(np.array([0.5])).tolist(),
    ... )
    ([0.0, 0.0], [0.0])
    """

    constant: float

    def value(self, s: np.ndarray) -> np.ndarray:
        return np.full(np.shape(s), self.constant)

    def derivative(self, s: np.ndarray) -> np.ndarray:
        return np.zeros(np.shape(s))


@dataclass(frozen=True)
class Scaled(ScalarFunction):
    """``factor · base``.

    Examples
    --------
    >>> (
    ...     Scaled(Constant(3.0), 2.0).constant,
    ...     Scaled(Sampled(np.array([0.0, 1.0]), 1.0), 2.0).constant,
    ... )
    (6.0, None)
    """

    base: ScalarFunction
    factor: float

    @property
    def constant(self) -> float | None:  # type: ignore[override]
        return None if self.base.constant is None else self.factor * self.base.constant

    def value(self, s: np.ndarray) -> np.ndarray:
        return self.factor * self.base(s)

    def derivative(self, s: np.ndarray) -> np.ndarray:
        return self.factor * self.base.derivative(s)


@dataclass(frozen=True, eq=False)
class Sampled(FrozenArrays, ScalarFunction):
    """The cubic spline through samples at ``linspace(0, length, m)``.

    Not-a-knot end conditions for m > 3 samples, natural ones below.

    Attributes
    ----------
    samples : (m,) ndarray
        Values at the uniform grid, read-only.
    length : float
        The domain's arc length L.

    Examples
    --------
    >>> f = Sampled(np.array([0.0, 1.0, 4.0, 9.0]), 3.0)  # s² sampled at s = 0, 1, 2, 3
    >>> f(np.array([1.5])).round(6).tolist(), f.derivative(np.array([1.5])).round(6).tolist()
    ([2.25], [3.0])
    >>> Sampled(np.array([1.0, 1.0]), 3.0)(
    ...     np.array([2.0])
    ... ).tolist()  # two equal samples: a constant
    [1.0]
    """

    samples: np.ndarray
    length: float
    spline: Callable[[np.ndarray], np.ndarray] = field(init=False, repr=False)
    slope: Callable[[np.ndarray], np.ndarray] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        from scipy.interpolate import CubicSpline

        object.__setattr__(self, "samples", np.asarray(self.samples, dtype=float))
        super().__post_init__()
        grid = np.linspace(0.0, float(self.length), self.samples.size)
        spline = CubicSpline(
            grid, self.samples, bc_type="not-a-knot" if self.samples.size > 3 else "natural"
        )
        object.__setattr__(self, "spline", spline)
        object.__setattr__(self, "slope", spline.derivative())

    def value(self, s: np.ndarray) -> np.ndarray:
        return self.spline(s)

    def derivative(self, s: np.ndarray) -> np.ndarray:
        return self.slope(np.asarray(s, dtype=float))


class Differenced(ScalarFunction):
    """A function whose derivative is a sixth-order difference inside ``[0, length]``.

    Subclasses provide :meth:`ScalarFunction.value` and the attributes ``length`` (L) and ``step``
    (h).

    Examples
    --------
    >>> f = UserFunction(np.sin, 1.0, difference_step(1.0))  # a Differenced function
    >>> isinstance(f, Differenced), round(float(f.derivative(np.array([0.0]))[0]), 9)
    (True, 1.0)
    """

    length: float
    step: float

    def derivative(self, s: np.ndarray) -> np.ndarray:
        return difference_derivative(self, s, length=self.length, step=self.step)


@dataclass(frozen=True)
class UserFunction(Differenced):
    """A user's vectorised callable of arc length, differentiated numerically.

    It pickles only if ``function`` does (a module-level function does, a lambda or a
    closure does not).

    Attributes
    ----------
    function : callable
        ``function(s)``; a callable that only takes scalars is called element by element.
    length : float
        The domain's arc length L: the function is never sampled outside ``[0, L]``.
    step : float
        Difference step h (:func:`difference_step`).

    Examples
    --------
    >>> f = UserFunction(np.exp, 1.0, difference_step(1.0))
    >>> (
    ...     f(np.array([0.0])).tolist(),
    ...     round(float(f.derivative(np.array([1.0]))[0]), 9),
    ... )  # e at the end, one-sided
    ([1.0], 2.718281828)
    >>> UserFunction(lambda s: 1.0, 1.0, 0.01)(
    ...     np.array([0.2, 0.4])
    ... ).tolist()  # a constant callable is broadcast
    [1.0, 1.0]
    """

    function: Callable[[np.ndarray], np.ndarray]
    length: float
    step: float

    def value(self, s: np.ndarray) -> np.ndarray:
        return _broadcast_call(self.function, s)


def difference_step(length: float) -> float:
    """The difference step h = min(1e-3 · max(L, 1), L / 8) for a domain of length L.

    At most L / 8, so that a seven-point stencil (6 h wide) fits in the domain with room
    for rounding.

    Examples
    --------
    >>> difference_step(10.0), difference_step(0.004)  # a short domain: L / 8
    (0.01, 0.0005)
    """
    return min(1e-3 * max(float(length), 1.0), float(length) / 8.0)


def _stencil_weights(offsets: range) -> np.ndarray:
    """Weights w of f'(0) ≈ Σ w_k f(k h) / h on the integer nodes ``offsets`` (exact, then
    float)."""
    from fractions import Fraction

    nodes = list(offsets)
    weights = []
    for k, xk in enumerate(nodes):
        total = Fraction(0)
        for m, xm in enumerate(nodes):
            if m == k:
                continue
            term = Fraction(1, xk - xm)
            for j, xj in enumerate(nodes):
                if j not in (k, m):
                    term *= Fraction(-xj, xk - xj)
            total += term
        weights.append(float(total))
    return np.array(weights)


#: Sixth-order central difference weights for f'(s): Σ c_k (f(s+kh) − f(s−kh)) / h.
_CENTRAL6 = ((1, 45.0 / 60.0), (2, -9.0 / 60.0), (3, 1.0 / 60.0))


@cache
def _shifted6() -> np.ndarray:
    """Seven-point stencils on the nodes shift − 3 … shift + 3 (rows: shift = −3 … 3), made when
    first needed."""
    return readonly(
        np.stack([_stencil_weights(range(shift - 3, shift + 4)) for shift in range(-3, 4)])
    )


#: Shifts tried in order: the central stencil first, then the least one-sided.
_SHIFT_ORDER = (0, 1, -1, 2, -2, 3, -3)


def difference_derivative(
    f: Callable[[np.ndarray], np.ndarray], s: np.ndarray, *, length: float, step: float
) -> np.ndarray:
    """Sixth-order finite-difference derivative of ``f`` that samples only ``[0, length]``.

    At every point the central stencil ``s + k h`` (k = −3 … 3) is used if all its nodes
    lie in ``[0, length]``; otherwise the same seven-point stencil shifted by the fewest
    steps that bring it inside. Every stencil is exact for polynomials of degree 6.

    Parameters
    ----------
    f : callable
        Vectorised: f of an (M,) array returns (M,).
    s : array_like
        Points in ``[0, length]``, any shape.
    length : float
        L; needs ``length ≥ 6 step`` (points where no stencil fits get NaN).
    step : float
        h.

    Returns
    -------
    ndarray
        f'(s), the shape of ``s``.

    Examples
    --------
    The square root is not defined left of 0, and is never asked for it:

    >>> d = difference_derivative(np.sqrt, np.array([0.25, 1.0]), length=1.0, step=1e-2)
    >>> bool(np.allclose(d, [1.0, 0.5], rtol=1e-8))
    True
    """
    s = np.asarray(s, dtype=float)
    flat = s.reshape(-1)
    h = float(step)
    # The central stencil where it fits (its nodes grow with m, so its ends tell), the others placed
    # one by one.
    central = (flat + -3 * h >= 0.0) & (flat + 3 * h <= length)
    if central.all():
        return _central(f, flat, h).reshape(s.shape)
    out = np.empty(flat.shape)
    if central.any():
        out[central] = _central(f, flat[central], h)
    out[~central] = _shifted(f, flat[~central], length=length, h=h)
    return out.reshape(s.shape)


def _central(f: Callable[[np.ndarray], np.ndarray], x: np.ndarray, h: float) -> np.ndarray:
    """The central sixth-order difference of ``f`` at x (M,)."""
    return sum(c * (f(x + k * h) - f(x - k * h)) for k, c in _CENTRAL6) / h


def _shifted(
    f: Callable[[np.ndarray], np.ndarray], x: np.ndarray, *, length: float, h: float
) -> np.ndarray:
    """The difference at points x (M,) where the central stencil does not fit: the least shifted
    one that does, else NaN."""
    # (M, 7): first node of the stencil shifted by σ = −3 … 3
    first = x[:, None] + (np.arange(-3, 4) - 3) * h
    last = x[:, None] + (np.arange(-3, 4) + 3) * h
    # columns by preference
    fits = ((first >= 0.0) & (last <= length))[:, np.array(_SHIFT_ORDER) + 3]
    sigma = np.array(_SHIFT_ORDER)[np.argmax(fits, axis=1)]
    out = np.full(x.shape, np.nan)
    edge = np.flatnonzero(fits.any(axis=1))
    if edge.size:
        nodes = x[edge, None] + (sigma[edge, None] + np.arange(-3, 4)) * h  # (E, 7)
        out[edge] = (
            np.einsum("ij,ij->i", _shifted6()[sigma[edge] + 3], f(nodes.reshape(-1)).reshape(-1, 7))
            / h
        )
    return out


def _broadcast_call(f: Callable, s: np.ndarray) -> np.ndarray:
    """Call ``f`` on an array; fall back to element-wise calls for scalar-only callables."""
    try:
        out = np.asarray(f(s), dtype=float)
        return out if out.shape == s.shape else np.broadcast_to(out, s.shape).astype(float)
    except (TypeError, ValueError):
        return np.array([float(f(float(x))) for x in s.ravel()]).reshape(s.shape)


def as_function(f: FunctionLike, *, name: str, length: float) -> ScalarFunction:
    """Turn a number, callable or sample array over ``[0, length]`` into a function.

    Parameters
    ----------
    f : float, callable or (M,) array_like
        A constant, a callable of arc length, or M ≥ 2 samples at ``linspace(0, length, M)``.
    name : str
        Parameter name used in error messages.
    length : float
        Arc length L of the domain.

    Returns
    -------
    ScalarFunction

    Examples
    --------
    >>> as_function(0.0, name="tau", length=1.0)  # a straight, untwisted curve's torsion
    Constant(constant=0.0)
    >>> as_function([1.0, 2.0], name="kappa", length=1.0)(np.array([0.5])).round(6).tolist()
    [1.5]
    >>> as_function([1.0], name="kappa", length=1.0)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: kappa: expected a number, a callable or a 1-D array of at
    least 2 samples, got shape (1,)
    """
    if isinstance(f, ScalarFunction):
        return f
    if callable(f):
        return UserFunction(f, float(length), difference_step(length))
    arr = np.asarray(f, dtype=float)
    if arr.ndim == 0:
        c = float(arr)
        check_finite(np.array([c]), name=name, s=np.array([0.0]))
        return Constant(c)
    if arr.ndim != 1 or arr.size < 2:
        raise InputError(
            f"{name}: expected a number, a callable or a 1-D array of at least 2 "
            f"samples, got shape {arr.shape}"
        )
    check_finite(arr, name=name, s=np.linspace(0.0, float(length), arr.size))
    return Sampled(arr, float(length))


def check_finite(values: np.ndarray, *, name: str, s: np.ndarray) -> None:
    """Raise :class:`InputError` naming the first arc length where ``values`` is not finite.

    Examples
    --------
    >>> check_finite(np.array([1.0, 2.0]), name="kappa", s=np.array([0.0, 1.0])) is None
    True
    >>> check_finite(np.array([1.0, np.nan]), name="kappa", s=np.array([0.0, 0.5]))
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: kappa must be finite; at s = 0.5 it is nan
    """
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        i = bad[np.argmin(s.flat[bad])]
        raise InputError(f"{name} must be finite; at s = {s.flat[i]:.6g} it is {values.flat[i]}")
