"""Strict JSON text of results: NumPy values as plain numbers, never a NaN or an infinity."""

from __future__ import annotations

import json
from typing import Any

import numpy as np

from ._errors import InternalError

__all__ = ["plain", "strict_json"]


def plain(value: object) -> object:
    """A JSON-ready form of NumPy scalars and arrays (anything else as its text).

    Examples
    --------
    >>> plain(np.float64(0.5)), plain(np.arange(2)), plain(np.zeros(0))
    (0.5, [0, 1], [])
    """
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    return str(value)


def strict_json(value: object, **kwargs: Any) -> str:
    """JSON text of ``value`` (NumPy values as plain numbers), refusing NaN and infinities.

    Raises
    ------
    InternalError
        A non-finite number in ``value``, named by its key (``result.p_xz = inf``): strict
        JSON has none, and a result that is not finite is never given as one.

    Examples
    --------
    >>> strict_json({"x": np.float64(1.5), "n": []})
    '{"x": 1.5, "n": []}'
    >>> strict_json({"x": [1.0, float("nan")]})
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InternalError: the result holds a number that is not finite:
    result.x[1] = nan
    """
    try:
        return json.dumps(value, allow_nan=False, default=plain, **kwargs)
    except ValueError:
        raise InternalError(
            f"the result holds a number that is not finite: {_non_finite(value)}"
        ) from None


def _non_finite(value: object, key: str = "result") -> str | None:
    """``key = value`` of the first non-finite number in a JSON-ready value, or None."""
    if isinstance(value, dict):
        return next(
            (found for k, v in value.items() if (found := _non_finite(v, f"{key}.{k}"))), None
        )
    if isinstance(value, (list, tuple, np.ndarray)):
        return next(
            (found for i, v in enumerate(value) if (found := _non_finite(v, f"{key}[{i}]"))), None
        )
    if isinstance(value, (float, np.floating)) and not np.isfinite(value):
        return f"{key} = {value}"
    return None
