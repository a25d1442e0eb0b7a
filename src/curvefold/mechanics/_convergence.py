"""How a figure converges as its mesh is refined: the observed order and Richardson's estimate.

A figure f_h of a mesh of size h that converges at order p, f_h = f + c hᵖ + o(hᵖ), gives
from three meshes refined by the same ratio r (h, h / r, h / r²) its observed order

    p = log((f_h − f_h/r) / (f_h/r − f_h/r²)) / log r,

and from two of them Richardson's estimate of its limit and of the error of the finer:

    f ≈ f_h/r + (f_h/r − f_h) / (rᵖ − 1),     error(f_h/r) ≈ |f_h/r − f_h| / (rᵖ − 1).

The estimate holds once the meshes are in the asymptotic range (the order observed on
three meshes near the one assumed); the tests measure it on each figure.
"""

from __future__ import annotations

import math

from ..kernel._errors import InputError

__all__ = ["observed_order", "richardson"]


def observed_order(coarse: float, medium: float, fine: float, *, ratio: float = 2.0) -> float:
    """The order p observed on three meshes refined by ``ratio`` (module notes); inf when the
    finer two agree exactly.

    Examples
    --------
    >>> round(observed_order(1 + 1 / 4, 1 + 1 / 16, 1 + 1 / 64), 12)  # f = 1 + h², h = ½, ¼, ⅛
    2.0
    """
    if not ratio > 1:
        raise InputError(f"ratio must be > 1 (the meshes refined), got {ratio!r}")
    a, b = abs(coarse - medium), abs(medium - fine)
    if b == 0:
        return math.inf
    if a == 0:
        return -math.inf
    return math.log(a / b) / math.log(ratio)


def richardson(
    coarse: float, fine: float, *, order: float, ratio: float = 2.0
) -> tuple[float, float]:
    """Richardson's estimate from two meshes refined by ``ratio``: the limit and the error of the
    finer figure (module notes).

    Parameters
    ----------
    coarse, fine : float
        The figure on the coarser and the finer mesh.
    order : float, keyword-only
        p, the order of convergence (> 0): the observed one, or the one the method has.
    ratio : float, keyword-only
        r, how much finer the finer mesh is (> 1).

    Examples
    --------
    >>> limit, error = richardson(1 + 1 / 16, 1 + 1 / 64, order=2)  # f = 1 + h², h = ¼, ⅛
    >>> round(limit, 12), round(error, 12)
    (1.0, 0.015625)
    """
    if not order > 0:
        raise InputError(f"order must be > 0, got {order!r}")
    if not ratio > 1:
        raise InputError(f"ratio must be > 1 (the meshes refined), got {ratio!r}")
    step = (fine - coarse) / (ratio**order - 1)
    return fine + step, abs(step)
