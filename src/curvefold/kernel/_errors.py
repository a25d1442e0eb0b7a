"""Exceptions raised by curvefold.

Every error a user can provoke derives from :class:`CurvefoldError`, which is also a
:class:`ValueError`, so callers can catch either. Messages name the parameter, the
allowed range and the value received; the command line prints them as one line. An error
about one parameter also carries its name as :attr:`CurvefoldError.parameter` (the
validators of :mod:`curvefold.kernel._validate` set it), so a caller can point at the
value without reading the message: the designer shows it under that parameter's control.

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
    """Base class of every error curvefold raises on purpose.

    Parameters
    ----------
    message : str
        One line: what is wrong, the requirement and the value received.
    parameter : str, optional, keyword-only
        The parameter the error is about, by its design key (``"a"``, ``"kappa"``), or
        None when it is about no single parameter.

    Examples
    --------
    >>> err = InputError("a must be in [0, 1.2707093728), got 2.0", parameter="a")
    >>> str(err), err.parameter
    ('a must be in [0, 1.2707093728), got 2.0', 'a')
    >>> CurvefoldError("the design regresses").parameter is None
    True
    """

    def __init__(self, *args: object, parameter: str | None = None) -> None:
        super().__init__(*args)
        self.parameter = parameter


class InputError(CurvefoldError):
    """A parameter is outside its allowed range, has the wrong shape, or is not finite.

    Examples
    --------
    >>> err = InputError("samples must be an integer ≥ 3, got 2", parameter="samples")
    >>> isinstance(err, ValueError), err.parameter
    (True, 'samples')
    """


class RegressionError(CurvefoldError):
    """A requested width or lattice curve reaches past the curve of regression.

    Examples
    --------
    >>> isinstance(RegressionError("width 2 reaches past the curve of regression"), CurvefoldError)
    True
    """


class ConvergenceError(CurvefoldError):
    """A root search or solver did not reach the requested tolerance.

    Examples
    --------
    >>> ConvergenceError("no arch root").parameter is None  # about no single parameter
    True
    """


class InternalError(RuntimeError):
    """An invariant that curvefold itself guarantees failed: a bug to report, not a user error.

    Examples
    --------
    >>> isinstance(InternalError("frames not orthonormal"), CurvefoldError)
    False
    """
