"""Exceptions raised by curvefold.

Every error a user can provoke derives from :class:`CurvefoldError`, which is also a
:class:`ValueError`, so callers can catch either. Messages name the parameter, the
allowed range and the value received; the command line prints them as one line.

:class:`InternalError` is the other kind: an invariant that curvefold guarantees by
construction did not hold. It is a bug, never the user's mistake, so it is not a
:class:`CurvefoldError`.
"""

from __future__ import annotations

__all__ = [
    "CurvefoldError",
    "InputError",
    "RegressionError",
    "ConvergenceError",
    "InternalError",
]


class CurvefoldError(ValueError):
    """Base class of every error curvefold raises on purpose."""


class InputError(CurvefoldError):
    """A parameter is outside its allowed range, has the wrong shape, or is not finite."""


class RegressionError(CurvefoldError):
    """A requested width or lattice curve reaches past the curve of regression."""


class ConvergenceError(CurvefoldError):
    """A root search or solver did not reach the requested tolerance."""


class InternalError(RuntimeError):
    """An invariant that curvefold itself guarantees failed: a bug to report, not a user error."""
