"""The fold angle at the boundary: 2α checked, in degrees or radians, and α in radians.

One owner for the range of a fold angle, (0°, 180°) or [0°, 180°) with the flat state, and
for the messages that name it.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..kernel._errors import InputError

__all__ = ["check_fold_angle", "check_fold_angles", "half_angle"]


def half_angle(
    fold_angle: float | np.ndarray,
    *,
    degrees: bool = True,
    name: str = "fold_angle",
    allow_flat: bool = False,
) -> float:
    """Validate a fold angle 2α and return α in radians.

    Parameters
    ----------
    fold_angle : float
        The full fold angle 2α, in degrees by default.
    degrees : bool, keyword-only
        Whether ``fold_angle`` is in degrees (default) or radians.
    allow_flat : bool, keyword-only
        Accept 2α = 0 (the flat, two-ply state); the range is then [0°, 180°).

    Examples
    --------
    >>> (
    ...     round(float(half_angle(90.0)), 12),
    ...     float(half_angle(0.0, allow_flat=True)),
    ... )  # the flat state: α = 0
    (0.785398163397, 0.0)
    >>> half_angle(180.0)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: fold_angle must be in (0°, 180°), got 180.0 (2α = 180°
    would need infinite curvature κ = κ_2D / cos α)
    """
    try:
        value = float(fold_angle)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {fold_angle!r}") from None
    full = np.radians(value) if degrees else value
    unit, top = ("°", 180.0) if degrees else (" rad", np.pi)
    low = "[0" if allow_flat else "(0"
    if not np.isfinite(full) or full < 0 or (full == 0 and not allow_flat) or full >= np.pi:
        extra = (
            " (2α = 180° would need infinite curvature κ = κ_2D / cos α)"
            if np.isfinite(full) and full >= np.pi
            else " (0 in radians: below the smallest positive float)"
            if full == 0 and value != 0
            else ""
        )
        # -10, not np.int64(-10)
        shown = fold_angle.item() if isinstance(fold_angle, np.generic) else fold_angle
        raise InputError(f"{name} must be in {low}{unit}, {top:g}{unit}), got {shown!r}{extra}")
    return 0.5 * full


def check_fold_angle(
    fold_angle: float, *, degrees: bool = True, name: str = "fold_angle", allow_flat: bool = False
) -> float:
    """Validate a fold angle 2α (as :func:`half_angle` does) and return it in degrees.

    Examples
    --------
    >>> check_fold_angle(np.pi / 2, degrees=False)
    90.0
    >>> check_fold_angle(0.0)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: fold_angle must be in (0°, 180°), got 0.0
    """
    half_angle(fold_angle, degrees=degrees, name=name, allow_flat=allow_flat)
    return float(fold_angle) if degrees else float(np.degrees(fold_angle))


def check_fold_angles(
    fold_angles: ArrayLike, *, degrees: bool = True, name: str = "fold_angles"
) -> np.ndarray:
    """Validate a non-empty sequence of fold angles 2α, each in [0°, 180°), and return them in
    degrees.

    Parameters
    ----------
    fold_angles : (A,) array_like
        Degrees, or radians if ``degrees`` is False.
    degrees : bool, keyword-only
    name : str, keyword-only
        The parameter named in the messages.

    Returns
    -------
    (A,) ndarray

    Examples
    --------
    >>> check_fold_angles([0, 45, 90]).tolist()
    [0.0, 45.0, 90.0]
    >>> check_fold_angles([])
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: fold_angles must be a non-empty sequence of fold angles,
    got shape (0,)
    """
    try:
        arr = np.atleast_1d(np.asarray(fold_angles, float))
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a sequence of numbers, got {fold_angles!r}") from None
    if arr.ndim != 1 or arr.size == 0:
        raise InputError(
            f"{name} must be a non-empty sequence of fold angles, got shape {np.shape(fold_angles)}"
        )
    for a in arr:
        half_angle(a, degrees=degrees, name=name, allow_flat=True)
    return arr if degrees else np.degrees(arr)
