"""The (u, v) lattice of creases sharing one frame (the paper's Eqs. 10–18).

Every crease of a tube or cellular block is a lattice curve

    x(t; u, v) = x₁(t) + u ℓ_L(t) r_L(t) + v ℓ_R(t) r_R(t)            (Eq. 11)

with ``ℓ = w / sin β`` and the width laws ``ln w_R(t) = ln w_R(0) + ∫ τ cot α ds``,
``ln w_L(t) = ln w_L(0) − ∫ τ cot α ds`` (Eqs. 12–13 corrected: the paper prints τ / cot α).
Its tangent is parallel to curve 1's at equal t, so all lattice curves share curve 1's
frame. Curves are built from curve 1 by this formula, never by chaining numerical curves:
each chained step differentiates the previous curve and loses digits.

t ∈ [0, 1] is curve 1's normalised arc length, ``s₁ = t L``. The curve (u, v) has speed
``ds/dt = (1 − u a(t) − v b(t)) L`` with ``a = w_L / w_lim_L``, ``b = w_R / w_lim_R``
(Eq. 17); it is valid where that factor is positive for all t (Eq. 18).

What rigid folding does not change is one :class:`Pattern` value (κ_2D, β, the widths,
ruling lengths, regression rates and domain, the invariants at the integration nodes);
a :class:`Lattice` is a pattern with curve 1 folded at one angle, and every lattice
refolded from it holds the same pattern object. (The pattern lives here, beside the
lattice it describes; ``curvefold.io._pattern`` is the printed crease pattern.)
"""

from __future__ import annotations

import weakref
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Literal

import numpy as np

from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InputError, RegressionError
from ..kernel._functions import Constant, ScalarFunction, check_finite
from ..kernel._lie import GAUSS3_WEIGHTS
from ._crease import Crease
from ._crease_laws import ruling_vectors
from ._curve import SpaceCurve, gauss_nodes, integrate_frenet
from ._fold_angle import half_angle
from ._topology import Topology

__all__ = [
    "Lattice",
    "Pattern",
    "RegressionDomain",
    "WIDTH_RESOLUTION",
    "check_anchor",
    "check_curves",
    "lattice_points",
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
    >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
    >>> domain = lat.domain  # a unit circle at 90°: a = w_L / w_lim_L = 0.1 cos 45°, b = −a
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


@dataclass(frozen=True, eq=False)
class Lattice(FrozenArrays):
    """Curve 1 folded at one constant fold angle, with its fold-invariant pattern.

    Build it with :meth:`from_crease`; fold it with :meth:`refold` (the folded lattice
    holds the same :class:`Pattern` object). It is the smooth kind of
    :class:`~curvefold.geometry.StructureLattice`.

    Attributes
    ----------
    crease : Crease
        Curve 1 at this fold angle (constant α, β_L = β_R = β).
    pattern : Pattern
        κ_2D, β, widths, regression domain: unchanged by rigid folding.

    Examples
    --------
    >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)  # a unit circle
    >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
    >>> lat.crease.fold_angle, lat.refold(30).pattern is lat.pattern
    (90.0, True)
    """

    crease: Crease
    pattern: Pattern

    @classmethod
    def from_crease(
        cls, crease: Crease, width_left: float | np.ndarray, width_right: float | np.ndarray
    ) -> Lattice:
        """Lattice of a crease with constant fold angle from the widths at t = 0.

        Parameters
        ----------
        crease : Crease
            Must have a constant fold angle (then β_L = β_R).
        width_left, width_right : float or (n,) array_like
            w_L(0), w_R(0) > 0: the distances from curve 1's tangent line to those of the
            curves (1, 0) and (0, 1). Arrays give w_L(t), w_R(t) at every sample instead
            (see :meth:`Pattern.from_crease`).

        Raises
        ------
        RegressionError
            If a corner of the unit cell [0, 1]² is not free of regression; the message
            gives the limit along that direction and where it is reached.

        Examples
        --------
        >>> crease = Crease.from_curve(
        ...     SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5), fold_angle=90
        ... )
        >>> Lattice.from_crease(crease, 2.0, 0.1)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.RegressionError: widths: lattice curve (u, v) = (1, 0) passes the
        curve of regression (Eq. 17 speed factor -0.414 ≤ 0, worst at t = 0, s = 0); along this
        direction the limit is (u, v) = (0.7071, 0)
        """
        lattice = cls(crease, Pattern.from_crease(crease, width_left, width_right))
        lattice.check(np.array([[0, 1], [1, 0], [1, 1]]), name="widths")
        return lattice

    # -- intrinsic quantities (the pattern's) ------------------------------------------
    @property
    def s(self) -> np.ndarray:
        """Arc length of curve 1 at the samples, shape (n,)."""
        return self.pattern.s

    @property
    def t(self) -> np.ndarray:
        """Common curve parameter t = s₁ / L, shape (n,)."""
        return self.pattern.t

    @property
    def width_left(self) -> np.ndarray:
        """w_L(t) at the samples, shape (n,)."""
        return self.pattern.width_left

    @property
    def width_right(self) -> np.ndarray:
        """w_R(t) at the samples, shape (n,)."""
        return self.pattern.width_right

    @property
    def beta(self) -> np.ndarray:
        """Ruling angle β(t) (the same on both sides), shape (n,)."""
        return self.pattern.beta_samples

    @property
    def ruling_lengths(self) -> tuple[np.ndarray, np.ndarray]:
        """ℓ_L = w_L / sin β and ℓ_R = w_R / sin β, each shape (n,)."""
        return self.pattern.ruling_lengths

    @property
    def domain(self) -> RegressionDomain:
        """The regression domain in (u, v) (Eq. 18)."""
        return self.pattern.domain

    @property
    def kappa_2d(self) -> ScalarFunction:
        """κ_2D(s) of curve 1, fold-invariant."""
        return self.pattern.kappa_2d

    def speed(self, uv: np.ndarray) -> np.ndarray:
        """ds/dt of lattice curves uv (..., 2), shape (..., n) (Eq. 17).

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> lat.speed(np.array([[0, 0], [1, 0], [0, 1]]))[:, 0].round(
        ...     6
        ... ).tolist()  # curve 1 has L = 1; inside, outside the bend
        [1.0, 0.929289, 1.070711]
        """
        return self.crease.curve.length * self.domain.factor(uv)

    def section_area(self) -> np.ndarray:
        """Area of the section parallelogram, w_L w_R sin 2α, shape (n,) (constant in t).

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> (
        ...     lat.section_area().round(6).tolist(),
        ...     float(lat.refold(0).section_area().max()),
        ... )  # flat: no area
        ([0.01, 0.01, 0.01, 0.01, 0.01], 0.0)
        """
        return self.width_left * self.width_right * np.sin(2 * constant_alpha(self.crease))

    # -- what the consumers of a structure ask about its kind (curvefold.geometry._kinds) ---------
    @property
    def rigid(self) -> bool:
        """False: its strips bend; it is certified against its own sampling error."""
        return False

    @property
    def thinnable(self) -> bool:
        """True: its samples are dense samples of smooth curves, which a mesh may thin."""
        return True

    @property
    def crease_degree(self) -> int:
        """3: its creases are modelled by cubics through the samples."""
        return 3

    @property
    def smooth(self) -> Lattice:
        """The smooth lattice it is: itself."""
        return self

    # -- geometry at this fold angle -------------------------------------------------------
    def points(self, uv: np.ndarray) -> np.ndarray:
        """Lattice curves x(t; u, v) (Eq. 11) for uv (..., 2); shape (..., n, 3).

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> (
        ...     lat.points(np.array([1, 0]))[0].round(6).tolist(),
        ...     lat.points(np.array([[0, 0], [1, 1]])).shape,
        ... )
        ([0.0, 0.070711, 0.070711], (2, 5, 3))
        >>> bool(
        ...     np.array_equal(lat.points(np.zeros(2)), lat.crease.curve.points)
        ... )  # (0, 0) is curve 1
        True
        """
        return lattice_points(self.crease.curve.points, *self._rulings, uv)

    @cached_property
    def _rulings(self) -> tuple[np.ndarray, np.ndarray]:
        """ℓ_L r_L and ℓ_R r_R at this fold angle, each (n, 3), read-only."""
        alpha = constant_alpha(self.crease)
        rl, rr = ruling_vectors(self.crease.curve.frames, alpha, self.beta, self.beta)
        ll, lr = self.ruling_lengths
        return readonly(ll[:, None] * rl), readonly(lr[:, None] * rr)

    def check(self, uv: np.ndarray, *, name: str = "cells") -> None:
        """Raise :class:`RegressionError` unless every lattice curve uv (..., 2) is valid.

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> (
        ...     lat.check(np.array([[1, 1], [-5, 0]])),
        ...     lat.check(np.zeros((0, 2))),
        ... )  # valid curves; no curves (see check_curves)
        (None, None)
        """
        check_curves(self.domain, self.crease.curve.length, uv, name=name)

    def topology(
        self,
        cell_curves: np.ndarray,
        faces: Literal["triangles", "quads"] = "triangles",
        *,
        keep: Sequence[np.ndarray] | None = None,
    ) -> Topology:
        """The mesh of tubes on these cells' lattice curves, keeping the samples ``keep``
        (:meth:`Topology.tubes`).

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> (
        ...     lat.topology(np.array([[0, 1, 3, 2]])).faces_vertices.shape,
        ...     lat.topology(np.array([[0, 1, 3, 2]]), keep=[[0, 4]]).faces_vertices.shape,
        ... )
        ((32, 3), (8, 3))
        """
        return Topology.tubes(cell_curves, len(self.s), faces=faces, keep=keep)

    # -- rigid folding ------------------------------------------------------------------------
    def _folded_curve1(self, alphas: np.ndarray, anchor: str) -> tuple[np.ndarray, np.ndarray]:
        """Curve 1 at half fold angles α (A,): points (A, n, 3) and frames (A, n, 3, 3)."""
        check_anchor(anchor)
        p = self.pattern
        c = self.crease.curve
        ca, ta = np.cos(alphas)[:, None, None], np.tan(alphas)[:, None, None]
        points, frames = integrate_frenet(
            c.s,
            p.kappa_2d_nodes / ca,
            p.log_width_rate_nodes * ta,
            origin=c.points[0],
            frame=c.frames[0],
        )
        if anchor == "middle":
            m = (len(c.s) - 1) // 2
            R = c.frames[m] @ np.swapaxes(frames[:, m], -1, -2)  # (A, 3, 3)
            points = np.einsum("aij,anj->ani", R, points - points[:, m : m + 1]) + c.points[m]
            frames = R[:, None] @ frames
        return points, frames

    def fold_points(
        self,
        uv: np.ndarray,
        fold_angles: np.ndarray,
        *,
        degrees: bool = True,
        anchor: str = "start",
    ) -> np.ndarray:
        """Lattice curves uv at many fold angles at once, shape (A, K, n, 3).

        The vectorised path behind a folding motion: equivalent to
        ``[self.refold(f, anchor=anchor).points(uv) for f in fold_angles]``.

        Parameters
        ----------
        uv : (K, 2) array_like
        fold_angles : (A,) array_like
            2α values in [0°, 180°) (degrees by default).
        anchor : {"start", "middle"}, keyword-only

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> frames = lat.fold_points(np.array([[1, 0]]), [0, 90])
        >>> frames.shape, float(np.abs(frames[0, ..., 2]).max())  # 2α = 0: flat
        ((2, 1, 5, 3), 0.0)
        >>> bool(
        ...     np.allclose(frames[1], lat.points(np.array([[1, 0]])), atol=1e-12)
        ... )  # 90°: the lattice itself
        True
        """
        alphas = np.array(
            [half_angle(f, degrees=degrees, allow_flat=True) for f in np.atleast_1d(fold_angles)]
        )
        points, frames = self._folded_curve1(alphas, anchor)
        rl, rr = ruling_vectors(frames, alphas[:, None], self.beta, self.beta)
        ll, lr = self.ruling_lengths
        return lattice_points(points, ll[:, None] * rl, lr[:, None] * rr, uv)

    def refold(
        self,
        fold_angle: float,
        *,
        degrees: bool = True,
        anchor: Literal["start", "middle"] = "start",
    ) -> Lattice:
        """The same lattice rigidly folded to another fold angle 2α ∈ [0°, 180°).

        The pattern (κ_2D, β, widths, t-correspondence) is shared; curve 1 is rebuilt with
        ``κ = κ_2D / cos α`` and ``τ = κ_2D tan α cot β`` (= τ₀ tan α / tan α₀). 2α = 0
        gives the flat, two-ply state: the crease pattern.

        Parameters
        ----------
        fold_angle : float
            2α, degrees by default.
        anchor : {"start", "middle"}, keyword-only
            Which frame of curve 1 stays where it is in this lattice: the one at t = 0, or
            the one at the middle sample ``(n - 1) // 2``.

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> flat = lat.refold(
        ...     0
        ... )  # the crease pattern: curve 1 is the circle of radius 1 / κ_2D in the plane
        >>> (
        ...     flat.crease.fold_angle,
        ...     float(np.abs(flat.points(np.array([[1, 1]]))[..., 2]).max()),
        ...     round(float(flat.crease.curve.kappa(0.0)), 6),
        ... )
        (0.0, 0.0, 0.707107)
        """
        a = half_angle(fold_angle, degrees=degrees, allow_flat=True)
        points, frames = self._folded_curve1(np.array([a]), anchor)
        p = self.pattern
        curve = SpaceCurve(
            p.s,
            readonly(points[0]),
            readonly(frames[0]),
            p.kappa_2d.scaled(1.0 / np.cos(a)),
            _RefoldedTorsion(p.kappa_2d, p.beta, np.tan(a)),
        )
        return Lattice(Crease(curve, Constant(a), p.beta, p.beta), p)


@dataclass(frozen=True)
class _RefoldedTorsion(ScalarFunction):
    """τ = tan α · κ_2D cot β of curve 1 refolded to α, with its exact derivative."""

    kappa_2d: ScalarFunction
    beta: ScalarFunction
    tan_alpha: float

    def value(self, s: np.ndarray) -> np.ndarray:
        return self.tan_alpha * self.kappa_2d(s) / np.tan(self.beta(s))

    def derivative(self, s: np.ndarray) -> np.ndarray:
        k2, beta = self.kappa_2d, self.beta
        return self.tan_alpha * (
            k2.derivative(s) / np.tan(beta(s)) - k2(s) * beta.derivative(s) / np.sin(beta(s)) ** 2
        )


def check_anchor(anchor: str) -> None:
    """Refuse an ``anchor`` of a refolded lattice other than ``"start"`` and ``"middle"``.

    Examples
    --------
    >>> check_anchor("end")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: anchor must be 'start' or 'middle', got 'end'
    """
    if anchor not in ("start", "middle"):
        raise InputError(f"anchor must be 'start' or 'middle', got {anchor!r}")


def check_curves(
    domain: RegressionDomain, length: float, uv: np.ndarray, *, name: str = "cells"
) -> None:
    """Raise :class:`RegressionError` unless every lattice curve uv (..., 2) is inside ``domain``.

    The message names the curve, its worst speed factor and where (t and s = t · length),
    and the limit along its direction.

    Examples
    --------
    >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
    >>> check_curves(lat.domain, 1.0, np.array([[1, 1]])) is None
    True
    >>> check_curves(lat.domain, 1.0, np.array([[20, 0]]), name="curves")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.RegressionError: curves: lattice curve (u, v) = (20, 0) passes the
    curve of regression (Eq. 17 speed factor -0.414 ≤ 0, worst at t = 0, s = 0); along this
    direction the limit is (u, v) = (14.14, 0)
    """
    uv = np.atleast_2d(np.asarray(uv, float)).reshape(-1, 2)
    margin = domain.margin(uv)
    bad = np.flatnonzero(~(margin > 0))
    if bad.size:
        i = bad[np.argmin(margin[bad])]
        u, v = uv[i]
        direction = uv[i] / np.abs(uv[i]).max()
        lam = float(domain.extent(direction))
        t = float(domain.where_limited(uv[i]))
        raise RegressionError(
            f"{name}: lattice curve (u, v) = ({u:g}, {v:g}) passes the curve of regression (Eq. "
            f"17 speed factor {margin[i]:.3g} ≤ 0, worst at t = {t:.4g}, s = "
            f"{t * length:.4g}); along this direction the limit is (u, v) = "
            f"({lam * direction[0]:.4g}, {lam * direction[1]:.4g})"
        )


def lattice_points(
    x1: np.ndarray, left: np.ndarray, right: np.ndarray, uv: np.ndarray
) -> np.ndarray:
    """Eq. 11, ``x1 + u ℓ_L r_L + v ℓ_R r_R``, for curve-1 data (..., n, 3) and uv (..., 2).

    For ``x1`` of shape (A, n, 3) and ``uv`` of shape (K, 2) the result is (A, K, n, 3);
    for (n, 3) and (..., 2) it is (..., n, 3). One matrix product per sample.

    Examples
    --------
    >>> x1, left, right = np.zeros((2, 3)), np.array([[0, 1.0, 0]] * 2), np.array([[0, 0, 1.0]] * 2)
    >>> lattice_points(x1, left, right, np.array([[1, 2]])).tolist()
    [[[0.0, 1.0, 2.0], [0.0, 1.0, 2.0]]]
    >>> lattice_points(x1, left, right, np.zeros((0, 2))).shape  # no curves
    (0, 2, 3)
    """
    uv = np.asarray(uv, float)
    coeff = np.concatenate([np.ones(uv.shape[:-1] + (1,)), uv], axis=-1).reshape(-1, 3)  # (K, 3)
    if x1.ndim == 2:  # one curve 1: a single matrix product
        basis = np.stack([x1, left, right])  # (3, n, 3)
        out = (coeff @ basis.reshape(3, -1)).reshape((-1,) + x1.shape)
        return out.reshape(uv.shape[:-1] + x1.shape)
    basis = np.stack([x1, left, right], axis=-1)  # (..., n, 3, 3)
    out = np.moveaxis(basis @ coeff.T, -1, -3)  # (..., K, n, 3)
    return out.reshape(x1.shape[:-2] + uv.shape[:-1] + x1.shape[-2:])


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


def _example_lattice() -> Lattice:
    """The lattice of the examples: a unit circle folded at 90° (5 samples), widths 0.1."""
    crease = Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5), fold_angle=90)
    return Lattice.from_crease(crease, 0.1, 0.1)
