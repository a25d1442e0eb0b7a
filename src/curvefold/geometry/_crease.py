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

from dataclasses import dataclass, field
from functools import cached_property
from typing import Literal

import numpy as np

from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InputError, RegressionError
from ..kernel._functions import (
    Constant,
    FunctionLike,
    ScalarFunction,
    as_function,
    check_finite,
    difference_step,
)
from ._crease_laws import (
    _check_pattern,
    _fold_angle_rate,
    _PatternCurvature,
    _PatternFoldAngle,
    _PatternTorsion,
    _PrescribedRulingAngle,
    _RulingAngle,
    _VaryingRulingAngle,
    ruling_vectors,
)
from ._curve import SpaceCurve, check_length, check_samples
from ._fold_angle import half_angle
from ._pattern_steps import StepGuard, require_pattern_steps
from ._topology import quadrant_kind, quadrant_name

__all__ = ["Crease", "QUADRANTS"]

#: The four surfaces a crease and its rulings define, by the signs of the ruling
#: directions used on the left and right side: (sign_L, sign_R, kind), the kind by
#: :func:`curvefold.geometry._topology.quadrant_kind`.
QUADRANTS = {
    quadrant_name(sl, sr): (sl, sr, quadrant_kind(sl, sr))
    for sl, sr in ((1, 1), (-1, 1), (-1, -1), (1, -1))
}


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

        require_pattern_steps(L, k2, bl, br)  # the dense output grows with the steps

        @StepGuard
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


def _quadrant(name: str) -> tuple[int, int, str]:
    try:
        return QUADRANTS[name]
    except KeyError:
        raise InputError(f"quadrant must be one of {', '.join(QUADRANTS)}, got {name!r}") from None
