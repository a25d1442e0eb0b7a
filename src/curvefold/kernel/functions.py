"""Scalar functions of arc length: curvature, torsion, fold angle, ruling angle.

Users give these as a number, a vectorised Python callable ``f(s)`` or samples over
``[0, L]``. :func:`as_function` turns any of them into a :class:`ScalarFunction` that can
be evaluated anywhere in ``[0, L]`` together with its first derivative, which the
ruling-angle rate ``β'`` (and hence the regression limits) needs.

Derivatives: exact for constants; a sixth-order central difference for callables
(truncation ~h⁶ f⁽⁷⁾ with h = 1e-3·max(L, 1), rounding ~1e-13·|f|/h); the derivative of
the interpolating cubic spline for samples.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Union

import numpy as np

from .errors import InputError

__all__ = ["ScalarFunction", "as_function", "check_finite"]

FunctionLike = Union[float, int, Callable[[np.ndarray], np.ndarray], np.ndarray, "ScalarFunction"]

# Sixth-order central difference weights for f'(s): Σ c_k (f(s+kh) − f(s−kh)) / h.
_FD6 = ((1, 45.0 / 60.0), (2, -9.0 / 60.0), (3, 1.0 / 60.0))


@dataclass(frozen=True)
class ScalarFunction:
    """A real function of arc length with its derivative.

    Parameters
    ----------
    value : callable
        ``value(s)`` for an array ``s`` of shape (M,) returns shape (M,).
    derivative : callable
        ``derivative(s)`` returns d value / ds, shape (M,).
    constant : float or None
        The value when the function is constant (lets callers take exact shortcuts).
    """

    value: Callable[[np.ndarray], np.ndarray]
    derivative: Callable[[np.ndarray], np.ndarray]
    constant: float | None = None

    def __call__(self, s: np.ndarray) -> np.ndarray:
        return self.value(s)

    def scaled(self, factor: float) -> ScalarFunction:
        """``factor · self``."""
        value, derivative = self.value, self.derivative
        const = None if self.constant is None else factor * self.constant
        return ScalarFunction(lambda s: factor * value(s), lambda s: factor * derivative(s), const)


def _broadcast_call(f: Callable, s: np.ndarray) -> np.ndarray:
    """Call ``f`` on an array; fall back to element-wise calls for scalar-only callables."""
    try:
        out = np.asarray(f(s), dtype=float)
    except (TypeError, ValueError):
        out = np.array([float(f(float(x))) for x in s.ravel()]).reshape(s.shape)
    if out.shape != s.shape:
        try:
            out = np.broadcast_to(out, s.shape).astype(float)
        except ValueError:
            out = np.array([float(f(float(x))) for x in s.ravel()]).reshape(s.shape)
    return out


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
    """
    if isinstance(f, ScalarFunction):
        return f
    if callable(f):
        h = 1e-3 * max(float(length), 1.0)

        def value(s: np.ndarray) -> np.ndarray:
            return _broadcast_call(f, np.asarray(s, dtype=float))

        def derivative(s: np.ndarray) -> np.ndarray:
            s = np.asarray(s, dtype=float)
            return sum(c * (value(s + k * h) - value(s - k * h)) for k, c in _FD6) / h

        return ScalarFunction(value, derivative)
    arr = np.asarray(f, dtype=float)
    if arr.ndim == 0:
        c = float(arr)
        check_finite(np.array([c]), name=name, s=np.array([0.0]))
        return ScalarFunction(lambda s: np.full(np.shape(s), c), lambda s: np.zeros(np.shape(s)), c)
    if arr.ndim != 1 or arr.size < 2:
        raise InputError(f"{name}: expected a number, a callable or a 1-D array of at least 2 samples, got shape {arr.shape}")
    grid = np.linspace(0.0, float(length), arr.size)
    check_finite(arr, name=name, s=grid)
    from scipy.interpolate import CubicSpline

    spline = CubicSpline(grid, arr, bc_type="not-a-knot" if arr.size > 3 else "natural")
    dspline = spline.derivative()
    return ScalarFunction(lambda s: spline(np.asarray(s, dtype=float)), lambda s: dspline(np.asarray(s, dtype=float)))


def check_finite(values: np.ndarray, *, name: str, s: np.ndarray) -> None:
    """Raise :class:`InputError` naming the first arc length where ``values`` is not finite."""
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        i = bad[np.argmin(s.flat[bad])]
        raise InputError(f"{name} must be finite; at s = {s.flat[i]:.6g} it is {values.flat[i]}")
