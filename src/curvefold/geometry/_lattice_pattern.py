"""The pattern of a lattice: everything about it that rigid folding does not change.

A :class:`Pattern` holds curve 1's κ_2D and β, the widths by the corrected width laws
(Eqs. 12–13), the ruling lengths, the regression rates (Eqs. 14–15) and the
:class:`RegressionDomain` of valid lattice curves (Eq. 18), with the invariants at the
integration nodes that a refolded curve 1 is integrated from. Every
:class:`~curvefold.geometry._lattice.Lattice` folded from one crease holds one pattern.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass

import numpy as np

from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InputError
from ..kernel._functions import ScalarFunction, check_finite
from ..kernel._lie import GAUSS3_WEIGHTS
from ._crease import Crease
from ._curve import SpaceCurve, gauss_nodes  # noqa: F401  (the examples' curve)

__all__ = [
    "Pattern",
    "RegressionDomain",
    "WIDTH_RESOLUTION",
    "constant_alpha",
    "log_width_ratio",
]

#: Narrowest width w(t) of a strip, as a fraction of the structure's size (the curve's length or its
#: widest strip): coordinates of that size resolve it by 10⁷ ulps; a narrower strip's edges round to
#: nothing.
WIDTH_RESOLUTION = 1e-9


@dataclass(frozen=True, eq=False)
class RegressionDomain(FrozenArrays):
    """The valid (u, v) set: ``1 − u a(t) − v b(t) > 0`` for every t (Eq. 18).

    An intersection of half-planes, convex, containing the origin. The arrays are
    read-only copies.

    Attributes
    ----------
    t : (n,) ndarray
        Curve parameter of the constraints.
    a, b : (n,) ndarray
        ``w_L(t) / w_lim_L(t)`` and ``w_R(t) / w_lim_R(t)`` (signed; ≤ 0 means no limit).

    Examples
    --------
    >>> circle = Crease.from_curve(
    ...     SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5), fold_angle=90
    ... )
    >>> domain = Pattern.from_crease(circle, 0.1, 0.1).domain
    >>> # a unit circle at 90°: a = w_L / w_lim_L = 0.1 cos 45°, b = −a
    >>> domain.a.round(6).tolist(), domain.b.round(6).tolist()
    ([0.070711, 0.070711, 0.070711, 0.070711, 0.070711], [-0.070711, -0.070711, -0.070711,
    -0.070711, -0.070711])
    """

    t: np.ndarray
    a: np.ndarray
    b: np.ndarray

    def __post_init__(self) -> None:
        for name in ("t", "a", "b"):
            object.__setattr__(self, name, np.asarray(getattr(self, name), dtype=float))
        super().__post_init__()

    def factor(self, uv: np.ndarray) -> np.ndarray:
        """``1 − u a(t) − v b(t)`` for points uv (..., 2); shape (..., n).

        Examples
        --------
        >>> domain = RegressionDomain(np.zeros(2), np.array([0.1, 0.1]), np.array([-0.1, -0.1]))
        >>> (
        ...     domain.factor(np.array([1.0, 0.0])).round(6).tolist(),
        ...     domain.factor(np.zeros(2)).tolist(),
        ... )  # curve 1: factor 1
        ([0.9, 0.9], [1.0, 1.0])
        """
        uv = np.asarray(uv, float)
        return 1.0 - uv[..., :1] * self.a - uv[..., 1:2] * self.b

    def margin(self, uv: np.ndarray) -> np.ndarray:
        """Smallest speed factor over t for points uv (..., 2); > 0 inside, shape (...).

        Examples
        --------
        >>> domain = RegressionDomain(np.zeros(2), np.array([0.1, 0.1]), np.array([-0.1, -0.1]))
        >>> domain.margin(np.array([[1.0, 1.0], [20.0, 0.0]])).round(6).tolist()
        [1.0, -1.0]
        """
        return self.factor(uv).min(axis=-1)

    def contains(self, uv: np.ndarray) -> np.ndarray:
        """Whether the lattice curves uv (..., 2) are free of regression, shape (...).

        Examples
        --------
        >>> domain = RegressionDomain(np.zeros(2), np.array([0.1, 0.1]), np.array([-0.1, -0.1]))
        >>> domain.contains(np.array([[0.0, 0.0], [20.0, 0.0], [-20.0, 0.0]])).tolist()
        [True, False, True]
        """
        return self.margin(uv) > 0

    def extent(self, direction: np.ndarray) -> np.ndarray:
        """Largest λ with λ·direction inside the domain (∞ if unbounded), shape (...).

        Parameters
        ----------
        direction : (..., 2) array_like

        Examples
        --------
        >>> domain = RegressionDomain(np.zeros(2), np.array([0.1, 0.1]), np.array([-0.1, -0.1]))
        >>> domain.extent(np.array([[1.0, 0.0], [0.0, 1.0]])).round(
        ...     6
        ... ).tolist()  # 1 / a; no limit along v
        [10.0, inf]
        """
        d = np.asarray(direction, float)
        worst = (d[..., :1] * self.a + d[..., 1:2] * self.b).max(axis=-1)
        with np.errstate(divide="ignore"):
            return np.where(worst > 0, 1.0 / np.where(worst > 0, worst, 1.0), np.inf)

    def where_limited(self, uv: np.ndarray) -> np.ndarray:
        """Curve parameter t where the speed factor of uv (..., 2) is smallest, shape (...).

        Examples
        --------
        >>> domain = RegressionDomain(np.zeros(2), np.array([0.1, 0.1]), np.array([-0.1, -0.1]))
        >>> float(
        ...     domain.where_limited(np.array([1.0, 0.0]))
        ... )  # the same all along a circle: the first
        0.0
        """
        return self.t[self.factor(uv).argmin(axis=-1)]

    def polygon(self, box: float = 10.0) -> np.ndarray:
        """Vertices (K, 2) of the domain clipped to ``|u|, |v| ≤ box``, counter-clockwise.

        Examples
        --------
        >>> domain = RegressionDomain(np.zeros(2), np.array([0.1, 0.1]), np.array([-0.1, -0.1]))
        >>> domain.polygon(box=20.0).round(6).tolist()  # the box cut by the line 0.1 u − 0.1 v = 1
        [[-20.0, 20.0], [-20.0, -20.0], [-10.0, -20.0], [20.0, 10.0], [20.0, 20.0]]
        """
        # The box, cut by each half-plane a u + b v ≤ 1 in turn (Sutherland–Hodgman; a convex
        # polygon stays convex).
        poly = np.array([[-box, box], [-box, -box], [box, -box], [box, box]], float)
        for a, b in zip(self.a.tolist(), self.b.tolist()):
            side = poly @ np.array([a, b]) - 1.0
            if side.max() <= 0:
                continue
            # np.roll(·, -1), cheaper
            following, side_next = (
                np.concatenate([poly[1:], poly[:1]]),
                np.concatenate([side[1:], side[:1]]),
            )
            # a vertex on the line is kept, not cut again
            crossing = ((side < 0) & (side_next > 0)) | ((side > 0) & (side_next < 0))
            cut = poly + (side / np.where(crossing, side - side_next, 1.0))[:, None] * (
                following - poly
            )
            # each vertex if inside, then the crossing after it
            keep = np.stack([side <= 0, crossing], axis=1)
            poly = np.concatenate([poly[:, None], cut[:, None]], axis=1)[keep]
        return poly


@dataclass(frozen=True, eq=False)
class Pattern(FrozenArrays):
    """Everything about a lattice that rigid folding does not change.

    Build it with :meth:`from_crease`. Arrays are read-only; their shape is (n,) over the
    samples of curve 1 unless stated.

    Attributes
    ----------
    s : (n,) ndarray
        Arc length of curve 1 at the samples.
    kappa_2d : ScalarFunction
        Curvature of curve 1 in the flat pattern, κ cos α (Eq. 2).
    beta : ScalarFunction
        Ruling angle β(s), the same on both sides.
    beta_samples : (n,) ndarray
        β at the samples.
    width_left, width_right : (n,) ndarray
        w_L(t), w_R(t).
    log_width_ratio : (n,) ndarray
        ``∫₀^s τ cot α ds = ln(w_R(t) / w_R(0)) = −ln(w_L(t) / w_L(0))``.
    ruling_lengths : tuple of two (n,) ndarray
        ℓ_L = w_L / sin β and ℓ_R = w_R / sin β.
    regression_rates : tuple of two (n,) ndarray
        1 / w_lim on the left and right (Eqs. 14–15), finite; ≤ 0 means no limit.
    domain : RegressionDomain
        The valid (u, v) set (Eq. 18).
    kappa_2d_nodes, log_width_rate_nodes : (n − 1, 3) ndarray
        κ_2D and ``κ_2D cot β = τ cot α`` (d ln w_R / ds) at the Gauss nodes of every
        interval of ``s``: what a refolded curve 1 is integrated from.

    Examples
    --------
    >>> helix = Crease.from_curve(
    ...     SpaceCurve.from_curvature(1.0, 0.2, 1.0, samples=3), fold_angle=90
    ... )
    >>> Pattern.from_crease(helix, 0.1, 0.1).width_right.round(
    ...     6
    ... ).tolist()  # the width law: w_R(0) exp(τ cot α s)
    [0.1, 0.110517, 0.12214]
    """

    s: np.ndarray
    kappa_2d: ScalarFunction
    beta: ScalarFunction
    beta_samples: np.ndarray
    width_left: np.ndarray
    width_right: np.ndarray
    log_width_ratio: np.ndarray
    ruling_lengths: tuple[np.ndarray, np.ndarray]
    regression_rates: tuple[np.ndarray, np.ndarray]
    domain: RegressionDomain
    kappa_2d_nodes: np.ndarray
    log_width_rate_nodes: np.ndarray

    @classmethod
    def from_crease(
        cls, crease: Crease, width_left: float | np.ndarray, width_right: float | np.ndarray
    ) -> Pattern:
        """The pattern of a crease with constant fold angle and the given widths.

        Parameters
        ----------
        crease : Crease
            Curve 1, constant fold angle (then β_L = β_R).
        width_left, width_right : float or (n,) array_like
            w_L(0), w_R(0) > 0, continued along t by the width law; or, as arrays, w_L(t)
            and w_R(t) at every sample, taken as given.

        Raises
        ------
        InputError
            If the fold angle varies, a width is not finite and > 0, or the regression
            rates are not finite (β' is not finite somewhere: the message names where).

        Examples
        --------
        >>> crease = Crease.from_curve(
        ...     SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5), fold_angle=90
        ... )
        >>> p = Pattern.from_crease(crease, 0.1, 0.2)
        >>> (
        ...     p.width_left.tolist(),
        ...     p.width_right.tolist(),
        ...     np.degrees(p.beta_samples).round(6).tolist(),
        ... )
        ([0.1, 0.1, 0.1, 0.1, 0.1], [0.2, 0.2, 0.2, 0.2, 0.2], [90.0, 90.0, 90.0, 90.0, 90.0])
        >>> Pattern.from_crease(crease, 0.0, 0.1)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: width_left must be a finite number > 0, got 0.0
        """
        if crease.fold_angle is None:
            raise InputError(
                "a lattice needs a crease with a constant fold angle; this crease's "
                "fold angle varies along s"
            )
        s = crease.s
        log_ratio, rates, beta_samples, k2_nodes, width_rate_nodes = _crease_rates(crease)
        widths = []
        for name, w, sign in (("width_left", width_left, -1.0), ("width_right", width_right, 1.0)):
            arr = np.asarray(w, dtype=float)
            if arr.ndim == 0:
                if not (np.isfinite(arr) and arr > 0):
                    raise InputError(f"{name} must be a finite number > 0, got {w!r}")
                with np.errstate(over="ignore", under="ignore"):
                    arr = float(arr) * np.exp(sign * log_ratio)
                bad = np.flatnonzero(~(np.isfinite(arr) & (arr > 0)))
                if bad.size:
                    i = int(bad[0])
                    raise InputError(
                        f"{name} w(t) = w(0)·exp({'-' if sign < 0 else '+'}∫ τ cot α ds) leaves "
                        f"the range of float64 at s = {s[i]:.6g} (∫ τ cot α ds = "
                        f"{log_ratio[i]:.6g} there); lower tau or the length"
                    )
            elif arr.shape != s.shape or not (np.isfinite(arr) & (arr > 0)).all():
                raise InputError(
                    f"{name} must be a number or {len(s)} finite values > 0 (one "
                    f"per sample), got shape {arr.shape}"
                )
            widths.append(arr)
        wl, wr = widths
        _check_resolved(wl, wr, crease)
        for side, rate in zip(("left", "right"), rates):
            check_finite(
                rate, name=f"the regression rate 1/w_lim on the {side} (β' ± κ_2D)/sin²β", s=s
            )
        sin_beta = np.sin(beta_samples)
        return cls(
            s=s,
            kappa_2d=_kappa_2d(crease),
            beta=crease.beta_left,
            beta_samples=beta_samples,
            width_left=wl,
            width_right=wr,
            log_width_ratio=log_ratio,
            ruling_lengths=(wl / sin_beta, wr / sin_beta),
            regression_rates=rates,
            domain=RegressionDomain(s / crease.curve.length, wl * rates[0], wr * rates[1]),
            kappa_2d_nodes=k2_nodes,
            log_width_rate_nodes=width_rate_nodes,
        )

    @property
    def length(self) -> float:
        """Arc length L of curve 1."""
        return float(self.s[-1])

    @property
    def t(self) -> np.ndarray:
        """Common curve parameter t = s / L, shape (n,)."""
        return self.domain.t


def constant_alpha(crease: Crease) -> float:
    """α of a lattice's crease, the same all along it (:meth:`Pattern.from_crease` checks it)."""
    assert crease.alpha.constant is not None, "a lattice's crease has a constant fold angle"
    return crease.alpha.constant


def _kappa_2d(crease: Crease) -> ScalarFunction:
    """κ_2D = κ cos α of a crease of constant fold angle."""
    return crease.curve.kappa.scaled(np.cos(constant_alpha(crease)))


#: What a pattern reads from a crease, kept while the crease lives (creases are immutable).
_RATES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _crease_rates(
    crease: Crease,
) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray], np.ndarray, np.ndarray, np.ndarray]:
    """What a pattern reads from its crease alone, whatever its widths: the log width ratio,
    the regression rates, β at the samples, κ_2D and κ_2D cot β at the Gauss nodes.

    Kept with the crease (read-only), so patterns of one crease and many widths (a sweep
    over p_xy) compute them once.
    """
    if crease not in _RATES:
        _RATES[crease] = _compute_rates(crease)
    return _RATES[crease]


def _compute_rates(
    crease: Crease,
) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray], np.ndarray, np.ndarray, np.ndarray]:
    s = crease.s
    nodes = gauss_nodes(s)
    k2_nodes = _kappa_2d(crease)(nodes)
    left, right = crease.regression_rates()
    rates = (readonly(left), readonly(right))
    values = (
        log_width_ratio(crease),
        crease.beta_left(s),
        k2_nodes,
        k2_nodes / np.tan(crease.beta_left(nodes)),
    )
    log_ratio, beta_samples, k2_nodes, width_rate_nodes = (readonly(v) for v in values)
    return log_ratio, rates, beta_samples, k2_nodes, width_rate_nodes


def _check_resolved(width_left: np.ndarray, width_right: np.ndarray, crease: Crease) -> None:
    """Refuse widths that coordinates of the structure's size cannot resolve
    (:data:`WIDTH_RESOLUTION`)."""
    size = max(crease.curve.length, float(width_left.max()), float(width_right.max()))
    for name, w in (("width_left", width_left), ("width_right", width_right)):
        i = int(np.argmin(w))
        if w[i] < WIDTH_RESOLUTION * size:
            raise InputError(
                f"{name} w(t) = {w[i]:.3g} at s = {crease.s[i]:.6g} is below "
                f"{WIDTH_RESOLUTION:g} of the structure's size {size:.3g}: its coordinates "
                "cannot resolve so narrow a strip; widen it, or lower tau or the length"
            )


def log_width_ratio(crease: Crease) -> np.ndarray:
    """``∫₀^s τ cot α ds`` at the samples, by 3-point Gauss–Legendre per interval, shape (n,).

    Examples
    --------
    >>> helix = Crease.from_curve(
    ...     SpaceCurve.from_curvature(1.0, 0.2, 1.0, samples=3), fold_angle=90
    ... )
    >>> log_width_ratio(helix).round(6).tolist()  # τ cot 45° · s
    [0.0, 0.1, 0.2]
    >>> log_width_ratio(
    ...     Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=3))
    ... ).tolist()  # τ = 0: constant widths
    [0.0, 0.0, 0.0]
    """
    s = crease.s
    nodes = gauss_nodes(s)
    integrand = crease.curve.tau(nodes) / np.tan(crease.alpha(nodes))  # = κ_2D cot β
    steps = np.diff(s) * (integrand @ GAUSS3_WEIGHTS)
    return np.concatenate([[0.0], np.cumsum(steps)])
