"""A measured residual field: what every check of the certificate measures, as it judges it."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["Residual"]


@dataclass(frozen=True)
class Residual:
    """A measured residual field, as the checks see it.

    Attributes
    ----------
    values : ndarray
        ``|residual|`` in the check's unit (NaN where the measurement broke). With ``t`` its
        last axis runs along the creases; without, every entry is an element (an edge, a
        face, a named quantity).
    floor : float
        Its rounding floor.
    name : callable
        Index (into the leading axes when ``t`` is given) -> what it is, for people
        (``"curve (1, 1)"``).
    t : (m,) ndarray or None
        Curve parameter t ∈ [0, 1] of the last axis.
    """

    values: np.ndarray
    floor: float
    name: Callable[[tuple[int, ...]], str]
    t: np.ndarray | None = None

    @property
    def worst(self) -> tuple[float, int]:
        """The largest value and its flat index; NaN wins (a broken measurement is the worst)."""
        v = np.asarray(self.values, float).ravel()
        if v.size == 0:
            return 0.0, -1
        top = int(np.argmax(v))
        # every value finite: the largest, first where it is
        if math.isfinite(v[top]) and math.isfinite(v.min()):
            return float(v[top]), top
        bad = np.flatnonzero(~np.isfinite(v))
        return (math.nan, int(bad[0])) if bad.size else (float(v.max()), int(np.argmax(v)))

    def locate(self, index: int) -> str:
        """Where the entry at a flat index is."""
        at = np.unravel_index(index, np.shape(self.values))
        if self.t is None:
            return self.name(tuple(int(i) for i in at))
        head = self.name(tuple(int(i) for i in at[:-1]))
        return f"{head}, t = {self.t[at[-1]]:.3g}" if head else f"t = {self.t[at[-1]]:.3g}"

    def change(self, coarse: Residual) -> float:
        """``|r(2h) − r(h)|``: pointwise at the t both sample (where they have t), else of the
        largest values."""
        if self.t is None or coarse.t is None:
            return abs(coarse.worst[0] - self.worst[0])
        k = np.clip(np.searchsorted(self.t, coarse.t), 0, len(self.t) - 1)
        same = np.abs(self.t[k] - coarse.t) < 0.25 * (self.t[1] - self.t[0])
        fine, rough = np.asarray(self.values), np.asarray(coarse.values)
        # every coarse t, evenly: slices
        if same.all() and len(k) > 1 and (np.diff(k) == k[1] - k[0]).all() and k[1] > k[0]:
            diff = np.abs(rough - fine[..., k[0] : k[-1] + 1 : k[1] - k[0]])
        else:
            diff = np.abs(rough[..., same] - fine[..., k[same]])
        return float(np.max(diff)) if diff.size else math.inf
