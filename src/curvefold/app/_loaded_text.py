"""The words and rounding of a design under load's lines for the terminal
(:meth:`curvefold.app._loading.Loaded.lines`)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..mechanics import error_text

__all__: list[str] = []


def _finite(value: float) -> float | None:
    return value if math.isfinite(value) else None


def _vector(values: Sequence[float] | np.ndarray, scale: Sequence[float] | np.ndarray) -> str:
    """[x, y, z] with the rounding of forces that balance ``scale`` shown as 0."""
    shown = _rounded(np.asarray(values, float).tolist(), float(np.abs(scale).max(initial=0.0)))
    return "[" + ", ".join(f"{x:.6g}" for x in shown) + "]"


def _check_words(check: Any) -> str:
    """A check's value, limit, utilisation and combination for the terminal."""
    mark = "ok" if check.passed else "FAILS"
    if check.name == "stability":
        value = "none" if math.isinf(check.value) else f"{check.value:.4g}"
        what = f"buckling factor {value}, {check.limit:g} required"
    else:
        scale, unit = (1e-6, "MPa") if check.unit == "Pa" else (1e3, "mm")
        what = f"{check.value * scale:.4g} {unit} of {check.limit * scale:.4g} {unit}"
    return (
        f"{mark}: utilisation {check.utilisation:.3g}{error_text(check.error)} "
        f"({what}; {check.combination}; {check.basis})"
    )


def _rounded(values: Sequence[float], scale: float) -> np.ndarray:
    """Values with what is below 1e-9 of ``scale`` (the rounding of forces that balance a load of
    that size) shown as 0."""
    v = np.asarray(values, float)
    return np.where(np.abs(v) <= 1e-9 * abs(scale), 0.0, v) + 0.0
