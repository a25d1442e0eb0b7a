"""Exceptions raised by curvefold.

Every error a user can provoke derives from :class:`CurvefoldError`, which is also a
:class:`ValueError`, so callers can catch either. Messages name the parameter, the
allowed range and the value received; the command line prints them as one line.
"""

from __future__ import annotations

__all__ = [
    "CurvefoldError",
    "InputError",
    "RegressionError",
    "ConvergenceError",
]


class CurvefoldError(ValueError):
    """Base class of every error curvefold raises on purpose."""


class InputError(CurvefoldError):
    """A parameter is outside its allowed range, has the wrong shape, or is not finite."""


class RegressionError(CurvefoldError):
    """A requested width or lattice curve reaches past the curve of regression."""


class ConvergenceError(CurvefoldError):
    """A root search or solver did not reach the requested tolerance."""
