"""A curved crease: a space curve with the two developable surfaces folded along it.

Conventions (the paper's Eqs. 2, 5–8, with the torsion sign corrected, see DESIGN.md):

- α is half the fold angle: each sheet leaves the osculating plane at angle α; 2α = 0 is
  the flat sheet.
- Rulings ``r_L = cos β_L T + sin β_L cos α N + sin β_L sin α B`` and
  ``r_R = cos β_R T − sin β_R cos α N + sin β_R sin α B``; normals
  ``p_L = −sin α N + cos α B``, ``p_R = sin α N + cos α B``; ``κ_2D = κ cos α``.
- Developable ruling angles: ``cot β_L = (α' + τ)/(κ sin α)``, ``cot β_R = (τ − α')/(κ sin α)``
  (the paper's Eqs. 4 and 9 print the torsion with the opposite sign).
- Regression (Eqs. 14–15): ``w_lim_R = sin²β_R / (β_R' − κ_2D)``, ``w_lim_L = sin²β_L / (β_L' +
  κ_2D)``; a side whose denominator is ≤ 0 has its curve of regression on the other side of the
  crease, and its limit is +∞.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InputError, RegressionError
from ..kernel._functions import (
    Constant,
    Differenced,
    FunctionLike,
    ScalarFunction,
    as_function,
    check_finite,
    difference_step,
)
from ._curve import SpaceCurve, check_length, check_samples
from ._topology import quadrant_kind, quadrant_name

__all__ = ["Crease", "QUADRANTS", "check_fold_angle", "check_fold_angles", "half_angle"]

#: The four surfaces a crease and its rulings define, by the signs of the ruling
#: directions used on the left and right side: (sign_L, sign_R, kind), the kind by
#: :func:`curvefold.geometry._topology.quadrant_kind`.
QUADRANTS = {
    quadrant_name(sl, sr): (sl, sr, quadrant_kind(sl, sr))
    for sl, sr in ((1, 1), (-1, 1), (-1, -1), (1, -1))
}


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


@dataclass(frozen=True, eq=False)
class Crease(FrozenArrays):
    """A space curve with the ruling angles and fold angle of the surfaces on both sides.

    Build it with :meth:`from_curve` (the curve is given, the rulings follow) or
    :meth:`from_pattern` (the crease pattern is given, the curve follows).

    Attributes
    ----------
    curve : SpaceCurve
        The crease.
    alpha, beta_left, beta_right : ScalarFunction
        α(s), β_L(s), β_R(s) in radians, with their derivatives.

    Examples
    --------
    A unit circle folded at 90°, then a crease folded from its pattern:

    >>> crease = Crease.from_curve(
    ...     SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=3), fold_angle=90
    ... )
    >>> crease.fold_angle, crease.s.tolist()
    (90.0, [0.0, 0.5, 1.0])
    >>> Crease.from_pattern(
    ...     0.5, 90.0, 90.0, 3.0, fold_angle=60.0, samples=5
    ... ).fold_angle is None  # α from an ODE
    True
    """

    curve: SpaceCurve
    alpha: ScalarFunction = field(repr=False)
    beta_left: ScalarFunction = field(repr=False)
    beta_right: ScalarFunction = field(repr=False)

    # -- constructors -------------------------------------------------------------------
    @classmethod
    def from_curve(
        cls, curve: SpaceCurve, *, fold_angle: FunctionLike = 90.0, degrees: bool = True
    ) -> Crease:
        """Fold the two developable surfaces along a given space curve.

        Parameters
        ----------
        curve : SpaceCurve
        fold_angle : float, callable or array_like, keyword-only
            2α, constant (default 90°) or a function of s (degrees by default).
        degrees : bool, keyword-only

        Examples
        --------
        A planar circle folded at 90° has rulings normal to the crease (β = 90°):

        >>> c = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
        >>> cr = Crease.from_curve(c, fold_angle=90)
        >>> [round(float(b), 12) for b in np.degrees(cr.beta_left(c.s[:2]))]
        [90.0, 90.0]
        """
        L = curve.length
        kappa, tau = curve.kappa, curve.tau
        if callable(fold_angle) or np.ndim(fold_angle) > 0:
            alpha = as_function(fold_angle, name="fold_angle", length=L).scaled(
                np.pi / 360.0 if degrees else 0.5
            )
            a_s = alpha(curve.s)
            check_finite(a_s, name="fold_angle", s=curve.s)
            bad = np.flatnonzero(~((a_s > 0) & (a_s < np.pi / 2)))
            if bad.size:
                i = bad[0]
                raise InputError(
                    "fold_angle must be in (0°, 180°) along the whole crease; at s "
                    f"= {curve.s[i]:.6g} it is {np.degrees(2 * a_s[i]):.6g}°"
                )
            h = difference_step(L)
            return cls(
                curve,
                alpha,
                _VaryingRulingAngle(kappa, tau, alpha, 1.0, L, h),
                _VaryingRulingAngle(kappa, tau, alpha, -1.0, L, h),
            )

        a = half_angle(fold_angle, degrees=degrees)
        beta = _RulingAngle(kappa, tau, float(np.sin(a)))
        return cls(curve, Constant(a), beta, beta)

    @classmethod
    def from_pattern(
        cls,
        kappa_2d: FunctionLike,
        beta_left: FunctionLike,
        beta_right: FunctionLike,
        length: float,
        *,
        fold_angle: float = 90.0,
        samples: int = 1001,
        degrees: bool = True,
        origin: np.ndarray | None = None,
        frame: np.ndarray | None = None,
        rtol: float = 1e-12,
    ) -> Crease:
        """Fold a single curved crease from its crease pattern (the paper's Fig. 08).

        Integrates the corrected Eqs. (3)–(4):
        ``α' = ½ κ_2D tan α (cot β_L − cot β_R)``, ``τ = ½ κ_2D tan α (cot β_L + cot β_R)``,
        ``κ = κ_2D / cos α``. One crease pattern with different ruling layouts folds into
        different shapes: a single curved fold has excess freedom.

        Parameters
        ----------
        kappa_2d : float, callable or array_like
            Curvature of the crease in the flat pattern, > 0.
        beta_left, beta_right : float, callable or array_like
            Ruling angles of the pattern, in (0°, 180°) (degrees by default).
        length : float
            Arc length of the crease.
        fold_angle : float, keyword-only
            2α at s = 0.
        samples : int, keyword-only
        degrees : bool, keyword-only
            Units of ``beta_left``, ``beta_right`` and ``fold_angle``.
        origin, frame : optional
            Start point and start frame of the folded crease.
        rtol : float, keyword-only
            Relative tolerance of the α(s) integration (DOP853).

        Raises
        ------
        InputError
            If κ_2D ≤ 0, a β leaves (0°, 180°), or α(s) leaves (0°, 90°) (the message
            gives the arc length where it does).

        Examples
        --------
        Rulings normal to the crease on both sides keep α constant (a planar crease, τ = 0);
        unequal ones make α grow along it:

        >>> c = Crease.from_pattern(0.5, 90.0, 90.0, 3.0, fold_angle=60.0, samples=5)
        >>> (
        ...     np.degrees(2 * c.alpha(c.s)).round(6).tolist(),
        ...     round(float(np.abs(c.curve.tau(c.s)).max()), 12),
        ... )
        ([60.0, 60.0, 60.0, 60.0, 60.0], 0.0)
        >>> c = Crease.from_pattern(0.5, 60.0, 120.0, 1.0, fold_angle=60.0, samples=3)
        >>> np.degrees(2 * c.alpha(c.s)).round(6).tolist()
        [60.0, 70.569028, 83.722504]
        >>> Crease.from_pattern(0.5, 0.0, 90.0, 1.0)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: beta_left must be in (0°, 180°); at s = 0 it is 0°
        """
        from scipy.integrate import solve_ivp

        samples = check_samples(samples)
        a0 = half_angle(fold_angle, degrees=degrees)
        L = check_length(length)
        k2 = as_function(kappa_2d, name="kappa_2d", length=L)
        unit = np.pi / 180.0 if degrees else 1.0
        bl = as_function(beta_left, name="beta_left", length=L).scaled(unit)
        br = as_function(beta_right, name="beta_right", length=L).scaled(unit)
        probe = np.linspace(0.0, L, max(samples, 257))
        _check_pattern(
            probe, ("kappa_2d", k2, np.inf), ("beta_left", bl, np.pi), ("beta_right", br, np.pi)
        )

        def rhs(s: float, y: np.ndarray) -> np.ndarray:
            return _fold_angle_rate(k2, bl, br, np.atleast_1d(s), y)

        def leaves(s: float, y: np.ndarray) -> float:
            return np.sin(2 * y[0])  # zero at α = 0 and α = 90°

        leaves.terminal = True  # type: ignore[attr-defined]  # SciPy reads its events' attributes
        sol = solve_ivp(
            rhs,
            (0.0, L),
            [a0],
            method="DOP853",
            rtol=rtol,
            atol=rtol * 1e-2,
            dense_output=True,
            events=leaves,
        )
        a_probe = sol.sol(probe)[0] if sol.status == 0 else None
        if a_probe is None or not ((a_probe > 0) & (a_probe < np.pi / 2)).all():
            # the event, the solver's failure point, or the first probe outside (0, π/2)
            if sol.status == 1:
                s_end = float(sol.t_events[0][0])
            elif sol.status == -1:
                s_end = float(sol.t[-1])
            else:
                assert a_probe is not None  # the solver finished (status 0)
                s_end = float(probe[np.argmax(~((a_probe > 0) & (a_probe < np.pi / 2)))])
            raise InputError(
                f"fold angle 2α leaves (0°, 180°) at s = {s_end:.6g} (α' = ½ κ_2D tan α (cot β_L "
                f"− cot β_R) drives it there); shorten the crease to length < {s_end:.6g} "
                "or change the ruling angles or the start fold angle",
                parameter="length",
            )

        alpha = _PatternFoldAngle(sol.sol, k2, bl, br)
        curve = SpaceCurve.from_curvature(
            _PatternCurvature(k2, alpha),
            _PatternTorsion(k2, alpha, bl, br),
            L,
            samples=samples,
            origin=origin,
            frame=frame,
        )
        return cls(curve, alpha, bl, br)

    @classmethod
    def from_alpha(
        cls,
        kappa_2d: FunctionLike,
        beta_left: FunctionLike,
        alpha: FunctionLike,
        length: float,
        *,
        samples: int = 1001,
        degrees: bool = True,
        origin: np.ndarray | None = None,
        frame: np.ndarray | None = None,
    ) -> Crease:
        """Fold a single curved crease from its crease pattern with the fold angle prescribed along
        it.

        With κ_2D, β_L and α(s) given, the corrected Eq. (3) gives the right ruling angle,
        ``cot β_R = cot β_L − 2α' / (κ_2D tan α)``, always in (0°, 180°); Eq. (4) gives the
        torsion ``τ = ½ κ_2D tan α (cot β_L + cot β_R) = κ_2D tan α cot β_L − α'`` and
        Eq. (2) the curvature ``κ = κ_2D / cos α``.

        Parameters
        ----------
        kappa_2d : float, callable or array_like
            Curvature of the crease in the flat pattern, > 0.
        beta_left : float, callable or array_like
            Ruling angle on the left, in (0°, 180°) (degrees by default).
        alpha : float, callable or array_like
            α(s), half the fold angle, in (0°, 90°) (degrees by default).
        length : float
            Arc length of the crease.
        samples, origin, frame : keyword-only
            As in :meth:`from_pattern`.
        degrees : bool, keyword-only
            Units of ``beta_left`` and ``alpha``.

        Raises
        ------
        InputError
            If κ_2D ≤ 0, β_L leaves (0°, 180°) or α leaves (0°, 90°) (the message gives the
            arc length where it does).

        Examples
        --------
        A constant α gives β_R = β_L, as :meth:`from_pattern` with equal ruling angles:

        >>> c = Crease.from_alpha(0.5, 80.0, 30.0, 2.0, samples=21)
        >>> round(float(np.degrees(c.beta_right(c.s[:1])[0])), 12), round(c.fold_angle, 12)
        (80.0, 60.0)
        """
        samples = check_samples(samples)
        L = check_length(length)
        unit = np.pi / 180.0 if degrees else 1.0
        k2 = as_function(kappa_2d, name="kappa_2d", length=L)
        bl = as_function(beta_left, name="beta_left", length=L).scaled(unit)
        a = as_function(alpha, name="alpha", length=L).scaled(unit)
        _check_pattern(
            np.linspace(0.0, L, max(samples, 257)),
            ("kappa_2d", k2, np.inf),
            ("beta_left", bl, np.pi),
            ("alpha", a, np.pi / 2),
        )
        # β_R = β_L for constant α
        br = (
            bl
            if a.constant is not None
            else _PrescribedRulingAngle(k2, bl, a, L, difference_step(L))
        )
        curve = SpaceCurve.from_curvature(
            _PatternCurvature(k2, a),
            _PatternTorsion(k2, a, bl, br),
            L,
            samples=samples,
            origin=origin,
            frame=frame,
        )
        return cls(curve, a, bl, br)

    # -- sampled quantities ---------------------------------------------------------------
    @property
    def s(self) -> np.ndarray:
        """Arc length of the samples, shape (n,)."""
        return self.curve.s

    @cached_property
    def fold_angle(self) -> float | None:
        """The constant fold angle 2α in degrees, or None where α varies along the crease."""
        return None if self.alpha.constant is None else float(np.degrees(2.0 * self.alpha.constant))

    @cached_property
    def kappa_2d(self) -> np.ndarray:
        """Curvature of the crease in the flat pattern, κ cos α, shape (n,), read-only."""
        return readonly(self.curve.kappa(self.s) * np.cos(self.alpha(self.s)))

    def rulings(self) -> tuple[np.ndarray, np.ndarray]:
        """Unit ruling directions r_L, r_R (Eqs. 5–6), each shape (n, 3).

        Examples
        --------
        A planar circle folded at 90°: rulings normal to the tangent T = (1, 0, 0), at 45° to the
        plane:

        >>> crease = Crease.from_curve(
        ...     SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=3), fold_angle=90
        ... )
        >>> left, right = crease.rulings()
        >>> left[0].round(6).tolist(), right[0].round(6).tolist()
        ([0.0, 0.707107, 0.707107], [0.0, -0.707107, 0.707107])
        """
        a, bl, br = self.alpha(self.s), self.beta_left(self.s), self.beta_right(self.s)
        return ruling_vectors(self.curve.frames, a, bl, br)

    def normals(self) -> tuple[np.ndarray, np.ndarray]:
        """Unit surface normals p_L, p_R at the crease (Eqs. 7–8), each shape (n, 3).

        Examples
        --------
        >>> crease = Crease.from_curve(
        ...     SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=3), fold_angle=90
        ... )
        >>> left, right = crease.normals()
        >>> left[0].round(6).tolist(), right[0].round(6).tolist()
        ([0.0, -0.707107, 0.707107], [0.0, 0.707107, 0.707107])
        """
        a = self.alpha(self.s)[:, None]
        N, B = self.curve.normal, self.curve.binormal
        return -np.sin(a) * N + np.cos(a) * B, np.sin(a) * N + np.cos(a) * B

    def regression_rates(self) -> tuple[np.ndarray, np.ndarray]:
        """1 / w_lim on the left and right (Eqs. 14–15), each shape (n,); ≤ 0 means no limit.

        Examples
        --------
        A unit circle at 90°: ±κ_2D = ±cos 45°, the right side has no curve of regression:

        >>> crease = Crease.from_curve(
        ...     SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=3), fold_angle=90
        ... )
        >>> [r.round(6).tolist() for r in crease.regression_rates()]
        [[0.707107, 0.707107, 0.707107], [-0.707107, -0.707107, -0.707107]]
        """
        s = self.s
        k2 = self.kappa_2d
        bl, br = self.beta_left(s), self.beta_right(s)
        return (self.beta_left.derivative(s) + k2) / np.sin(bl) ** 2, (
            self.beta_right.derivative(s) - k2
        ) / np.sin(br) ** 2

    def regression_limits(self) -> tuple[np.ndarray, np.ndarray]:
        """Width from the crease to the curve of regression, w_lim_L and w_lim_R, shape (n,).

        +∞ where that side has no curve of regression.

        Examples
        --------
        >>> crease = Crease.from_curve(
        ...     SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=3), fold_angle=90
        ... )
        >>> [w.round(6).tolist() for w in crease.regression_limits()]  # 1 / cos 45° and none
        [[1.414214, 1.414214, 1.414214], [inf, inf, inf]]
        """
        left, right = (
            np.where(r <= 0, np.inf, 1.0 / np.where(r <= 0, 1.0, r))
            for r in self.regression_rates()
        )
        return left, right  # NaN stays NaN

    def ruling_limits(self) -> tuple[np.ndarray, np.ndarray]:
        """Ruling length from the crease to the curve of regression, w_lim / sin β, shape (n,).

        Examples
        --------
        Rulings normal to the crease (β = 90°) are as long as the width:

        >>> crease = Crease.from_curve(
        ...     SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=3), fold_angle=90
        ... )
        >>> [w.round(6).tolist() for w in crease.ruling_limits()]
        [[1.414214, 1.414214, 1.414214], [inf, inf, inf]]
        """
        wl, wr = self.regression_limits()
        return wl / np.sin(self.beta_left(self.s)), wr / np.sin(self.beta_right(self.s))

    def dihedral_angle(
        self, quadrant: Literal["L+R+", "L-R+", "L-R-", "L+R-"] = "L+R+"
    ) -> np.ndarray:
        """Interior angle between the two surfaces of a quadrant, shape (n,): π − 2α or 2α.

        Examples
        --------
        >>> crease = Crease.from_curve(
        ...     SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=2), fold_angle=60
        ... )
        >>> (
        ...     np.degrees(crease.dihedral_angle()).round(6).tolist(),
        ...     np.degrees(crease.dihedral_angle("L-R+")).round(6).tolist(),
        ... )
        ([120.0, 120.0], [60.0, 60.0])
        >>> crease.dihedral_angle("up")
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: quadrant must be one of L+R+, L-R+, L-R-, L+R-, got
        'up'
        """
        kind = _quadrant(quadrant)[2]
        a = self.alpha(self.s)
        return np.pi - 2 * a if kind == "fold" else 2 * a

    def surface(
        self, quadrant: str = "L+R+", *, width: float | tuple[float, float] = 0.1, rulings: int = 2
    ) -> np.ndarray:
        """Points of the creased surface of one quadrant, shape (2, rulings, n, 3).

        Axis 0 is the side (left, right); along each ruling the points run from the crease
        to the given width (distance between the crease's tangent line and the edge).

        Raises
        ------
        RegressionError
            If the width reaches a curve of regression.

        Examples
        --------
        >>> crease = Crease.from_curve(
        ...     SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=3), fold_angle=90
        ... )
        >>> points = crease.surface(width=0.1)
        >>> (
        ...     points.shape,
        ...     bool(np.array_equal(points[0, 0], crease.curve.points)),
        ... )  # the first ruling point is the crease
        ((2, 2, 3, 3), True)
        >>> crease.surface(width=2.0)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.RegressionError: width on the left must stay below the regression
        limit 1.41421 (reached at s = 0), got 2
        """
        sign_l, sign_r, _ = _quadrant(quadrant)
        widths = np.broadcast_to(np.asarray(width, float), (2,))
        rl, rr = self.rulings()
        rate_l, rate_r = self.regression_rates()
        out = []
        for w, sign, r, rate, beta, side in (
            (widths[0], sign_l, rl, rate_l, self.beta_left, "left"),
            (widths[1], sign_r, rr, rate_r, self.beta_right, "right"),
        ):
            margin = 1.0 - sign * w * rate
            if not (margin > 0).all():
                i = int(np.argmin(np.where(margin > 0, np.inf, margin)))  # the worst (a NaN first)
                lim = 1.0 / abs(rate[i])
                raise RegressionError(
                    f"width on the {side} must stay below the regression limit "
                    f"{lim:.6g} (reached at s = {self.s[i]:.6g}), got {w:.6g}"
                )
            ell = sign * w / np.sin(beta(self.s))
            lam = np.linspace(0.0, 1.0, rulings)
            out.append(self.curve.points[None] + lam[:, None, None] * (ell[:, None] * r)[None])
        return np.stack(out)


def ruling_vectors(
    frames: np.ndarray, alpha: ArrayLike, beta_left: ArrayLike, beta_right: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """Rulings r_L, r_R (Eqs. 5–6) from frames (..., 3, 3) and angles (...,); each (..., 3)."""
    a = np.asarray(alpha, float)[..., None]
    bl = np.asarray(beta_left, float)[..., None]
    br = np.asarray(beta_right, float)[..., None]
    T, N, B = frames[..., 0], frames[..., 1], frames[..., 2]
    ca, sa = np.cos(a), np.sin(a)
    rl = np.cos(bl) * T + np.sin(bl) * (ca * N + sa * B)
    rr = np.cos(br) * T + np.sin(br) * (-ca * N + sa * B)
    return rl, rr


def _quadrant(name: str) -> tuple[int, int, str]:
    try:
        return QUADRANTS[name]
    except KeyError:
        raise InputError(f"quadrant must be one of {', '.join(QUADRANTS)}, got {name!r}") from None


def _fold_angle_rate(
    kappa_2d: ScalarFunction,
    beta_left: ScalarFunction,
    beta_right: ScalarFunction,
    s: np.ndarray,
    alpha: np.ndarray,
) -> np.ndarray:
    """α' = ½ κ_2D tan α (cot β_L − cot β_R) (the corrected Eq. 3), shape of ``s``."""
    return (
        0.5 * kappa_2d(s) * np.tan(alpha) * (1 / np.tan(beta_left(s)) - 1 / np.tan(beta_right(s)))
    )


@dataclass(frozen=True)
class _RulingAngle(ScalarFunction):
    """β = atan2(κ sin α, τ) on both sides of a crease of constant α, with its exact derivative."""

    kappa: ScalarFunction
    tau: ScalarFunction
    sin_alpha: float

    def value(self, s: np.ndarray) -> np.ndarray:
        return np.arctan2(self.kappa(s) * self.sin_alpha, self.tau(s))

    def derivative(self, s: np.ndarray) -> np.ndarray:
        k, t, sa = self.kappa(s), self.tau(s), self.sin_alpha
        return (
            sa
            * (self.kappa.derivative(s) * t - k * self.tau.derivative(s))
            / ((k * sa) ** 2 + t**2)
        )


@dataclass(frozen=True)
class _VaryingRulingAngle(Differenced):
    """β = atan2(κ sin α, τ + sign · α') for a varying α (sign +1 left, −1 right); β' by
    differences."""

    kappa: ScalarFunction
    tau: ScalarFunction
    alpha: ScalarFunction
    sign: float
    length: float
    step: float

    def value(self, s: np.ndarray) -> np.ndarray:
        return np.arctan2(
            self.kappa(s) * np.sin(self.alpha(s)),
            self.tau(s) + self.sign * self.alpha.derivative(s),
        )


def _check_pattern(probe: np.ndarray, *functions: tuple[str, ScalarFunction, float]) -> None:
    """Raise :class:`InputError` at the first probe where a (name, f, top) leaves (0, top), or is
    not finite."""
    for name, f, top in functions:
        v = f(probe)
        check_finite(v, name=name, s=probe)
        bad = np.flatnonzero(~((v > 0) & (v < top)))
        if bad.size:
            i = bad[0]
            need, shown = (
                ("> 0 everywhere", f"{v[i]:.6g}")
                if top == np.inf
                else (f"in (0°, {np.degrees(top):g}°)", f"{np.degrees(v[i]):.6g}°")
            )
            raise InputError(f"{name} must be {need}; at s = {probe[i]:.6g} it is {shown}")


@dataclass(frozen=True)
class _PrescribedRulingAngle(Differenced):
    """β_R of a crease with α(s) prescribed: cot β_R = cot β_L − 2α' / (κ_2D tan α) (corrected
    Eq. 3)."""

    kappa_2d: ScalarFunction
    beta_left: ScalarFunction
    alpha: ScalarFunction
    length: float
    step: float

    def value(self, s: np.ndarray) -> np.ndarray:
        a = self.alpha(s)
        cot = 1 / np.tan(self.beta_left(s)) - 2 * self.alpha.derivative(s) / (
            self.kappa_2d(s) * np.tan(a)
        )
        return np.arctan2(1.0, cot)


@dataclass(frozen=True, eq=False)
class _PatternFoldAngle(ScalarFunction):
    """α(s) of a crease folded from its pattern: the ODE's dense output, α' from the ODE itself.

    Attributes
    ----------
    solution : scipy.integrate.OdeSolution
        Dense output of α' = ½ κ_2D tan α (cot β_L − cot β_R) (picklable).
    kappa_2d, beta_left, beta_right : ScalarFunction
        The pattern, β in radians.
    """

    solution: Callable[[np.ndarray], np.ndarray]
    kappa_2d: ScalarFunction
    beta_left: ScalarFunction
    beta_right: ScalarFunction

    def value(self, s: np.ndarray) -> np.ndarray:
        return self.solution(s.ravel())[0].reshape(s.shape)

    def derivative(self, s: np.ndarray) -> np.ndarray:
        s = np.asarray(s, float)
        return _fold_angle_rate(self.kappa_2d, self.beta_left, self.beta_right, s, self(s))


@dataclass(frozen=True)
class _PatternCurvature(ScalarFunction):
    """κ = κ_2D / cos α of a crease folded from its pattern (Eq. 2), with its exact derivative."""

    kappa_2d: ScalarFunction
    alpha: ScalarFunction

    def value(self, s: np.ndarray) -> np.ndarray:
        return self.kappa_2d(s) / np.cos(self.alpha(s))

    def derivative(self, s: np.ndarray) -> np.ndarray:
        a, ca = self.alpha(s), np.cos(self.alpha(s))
        return (
            self.kappa_2d.derivative(s) / ca
            + self.kappa_2d(s) * np.sin(a) * self.alpha.derivative(s) / ca**2
        )


@dataclass(frozen=True)
class _PatternTorsion(ScalarFunction):
    """τ = ½ κ_2D tan α (cot β_L + cot β_R) of a crease folded from its pattern (Eq. 4
    corrected)."""

    kappa_2d: ScalarFunction
    alpha: ScalarFunction
    beta_left: ScalarFunction
    beta_right: ScalarFunction

    def value(self, s: np.ndarray) -> np.ndarray:
        return (
            0.5
            * self.kappa_2d(s)
            * np.tan(self.alpha(s))
            * (1 / np.tan(self.beta_left(s)) + 1 / np.tan(self.beta_right(s)))
        )

    def derivative(self, s: np.ndarray) -> np.ndarray:
        k, a, bl, br = self.kappa_2d(s), self.alpha(s), self.beta_left(s), self.beta_right(s)
        cot_sum = 1 / np.tan(bl) + 1 / np.tan(br)
        d_cot_sum = (
            -self.beta_left.derivative(s) / np.sin(bl) ** 2
            - self.beta_right.derivative(s) / np.sin(br) ** 2
        )
        d_tan = self.alpha.derivative(s) / np.cos(a) ** 2
        return 0.5 * (
            (self.kappa_2d.derivative(s) * np.tan(a) + k * d_tan) * cot_sum
            + k * np.tan(a) * d_cot_sum
        )
