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
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..kernel.errors import InputError, RegressionError
from ..kernel.functions import ScalarFunction
from ..kernel.lie import GAUSS3_WEIGHTS
from .crease import Crease, half_angle, ruling_vectors
from .curve import SpaceCurve, gauss_nodes, integrate_frenet

__all__ = ["Lattice", "RegressionDomain"]


@dataclass(frozen=True, eq=False)
class RegressionDomain:
    """The valid (u, v) set: ``1 − u a(t) − v b(t) > 0`` for every t (Eq. 18).

    An intersection of half-planes, convex, containing the origin.

    Attributes
    ----------
    t : (n,) ndarray
        Curve parameter of the constraints.
    a, b : (n,) ndarray
        ``w_L(t) / w_lim_L(t)`` and ``w_R(t) / w_lim_R(t)`` (signed; ≤ 0 means no limit).
    """

    t: np.ndarray
    a: np.ndarray
    b: np.ndarray

    def factor(self, uv: np.ndarray) -> np.ndarray:
        """``1 − u a(t) − v b(t)`` for points uv (..., 2); shape (..., n)."""
        uv = np.asarray(uv, float)
        return 1.0 - uv[..., :1] * self.a - uv[..., 1:2] * self.b

    def margin(self, uv: np.ndarray) -> np.ndarray:
        """Smallest speed factor over t for points uv (..., 2); > 0 inside, shape (...)."""
        return self.factor(uv).min(axis=-1)

    def contains(self, uv: np.ndarray) -> np.ndarray:
        """Whether the lattice curves uv (..., 2) are free of regression, shape (...)."""
        return self.margin(uv) > 0

    def extent(self, direction: np.ndarray) -> np.ndarray:
        """Largest λ with λ·direction inside the domain (∞ if unbounded), shape (...).

        Parameters
        ----------
        direction : (..., 2) array_like
        """
        d = np.asarray(direction, float)
        worst = (d[..., :1] * self.a + d[..., 1:2] * self.b).max(axis=-1)
        with np.errstate(divide="ignore"):
            return np.where(worst > 0, 1.0 / np.where(worst > 0, worst, 1.0), np.inf)

    def where_limited(self, uv: np.ndarray) -> np.ndarray:
        """Curve parameter t where the speed factor of uv (..., 2) is smallest, shape (...)."""
        return self.t[self.factor(uv).argmin(axis=-1)]

    def polygon(self, box: float = 10.0) -> np.ndarray:
        """Vertices (K, 2) of the domain clipped to ``|u|, |v| ≤ box``, counter-clockwise."""
        from scipy.spatial import ConvexHull, HalfspaceIntersection

        # Half-spaces A x + c ≤ 0: a u + b v − 1 ≤ 0, and the box.
        halfspaces = np.concatenate(
            [
                np.stack([self.a, self.b, -np.ones_like(self.a)], axis=1),
                np.array([[1, 0, -box], [-1, 0, -box], [0, 1, -box], [0, -1, -box]], float),
            ]
        )
        pts = HalfspaceIntersection(halfspaces, np.zeros(2)).intersections
        hull = ConvexHull(pts)
        return pts[hull.vertices]


@dataclass(frozen=True, eq=False)
class Lattice:
    """Curve 1 with constant fold angle and the widths of its lattice.

    Build it with :meth:`from_crease`; fold it with :meth:`refold`.

    Attributes
    ----------
    crease : Crease
        Curve 1 (constant α, β_L = β_R = β).
    width_left, width_right : (n,) ndarray
        w_L(t) and w_R(t) at the samples.
    """

    crease: Crease
    width_left: np.ndarray
    width_right: np.ndarray

    @classmethod
    def from_crease(cls, crease: Crease, width_left: float, width_right: float) -> Lattice:
        """Lattice of a crease with constant fold angle from the widths at t = 0.

        Parameters
        ----------
        crease : Crease
            Must have a constant fold angle (then β_L = β_R).
        width_left, width_right : float
            w_L(0), w_R(0) > 0: the distances from curve 1's tangent line to those of the
            curves (1, 0) and (0, 1).

        Raises
        ------
        RegressionError
            If a corner of the unit cell [0, 1]² is not free of regression; the message
            gives the limit along that direction and where it is reached.
        """
        if crease.fold_angle is None:
            raise InputError("a lattice needs a crease with a constant fold angle; this crease's fold angle varies along s")
        for name, w in (("width_left", width_left), ("width_right", width_right)):
            if not np.isfinite(w) or w <= 0:
                raise InputError(f"{name} must be a finite number > 0, got {w!r}")
        log_ratio = log_width_ratio(crease)
        lattice = cls(crease, float(width_left) * np.exp(-log_ratio), float(width_right) * np.exp(log_ratio))
        for k in (lattice.width_left, lattice.width_right):
            k.flags.writeable = False
        lattice.check(np.array([[0, 1], [1, 0], [1, 1]]), name="widths")
        return lattice

    # -- intrinsic quantities (unchanged by rigid folding) ------------------------------
    @property
    def s(self) -> np.ndarray:
        """Arc length of curve 1 at the samples, shape (n,)."""
        return self.crease.s

    @property
    def t(self) -> np.ndarray:
        """Common curve parameter t = s₁ / L, shape (n,)."""
        return self.crease.s / self.crease.curve.length

    @cached_property
    def beta(self) -> np.ndarray:
        """Ruling angle β(t) (the same on both sides), shape (n,)."""
        return self.crease.beta_left(self.s)

    @cached_property
    def ruling_lengths(self) -> tuple[np.ndarray, np.ndarray]:
        """ℓ_L = w_L / sin β and ℓ_R = w_R / sin β, each shape (n,)."""
        sb = np.sin(self.beta)
        return self.width_left / sb, self.width_right / sb

    @cached_property
    def domain(self) -> RegressionDomain:
        """The regression domain in (u, v) (Eq. 18)."""
        rl, rr = self.crease.regression_rates()
        return RegressionDomain(self.t, self.width_left * rl, self.width_right * rr)

    def speed(self, uv: np.ndarray) -> np.ndarray:
        """ds/dt of lattice curves uv (..., 2), shape (..., n) (Eq. 17)."""
        return self.crease.curve.length * self.domain.factor(uv)

    def section_area(self) -> np.ndarray:
        """Area of the section parallelogram, w_L w_R sin 2α, shape (n,) (constant in t)."""
        return self.width_left * self.width_right * np.sin(2 * self.crease.alpha.constant)

    # -- geometry at this fold angle -------------------------------------------------------
    def points(self, uv: np.ndarray) -> np.ndarray:
        """Lattice curves x(t; u, v) (Eq. 11) for uv (..., 2); shape (..., n, 3)."""
        rl, rr = ruling_vectors(self.crease.curve.frames, self.crease.alpha.constant, self.beta, self.beta)
        ll, lr = self.ruling_lengths
        return lattice_points(self.crease.curve.points, ll[:, None] * rl, lr[:, None] * rr, uv)

    def check(self, uv: np.ndarray, *, name: str = "cells") -> None:
        """Raise :class:`RegressionError` unless every lattice curve uv (..., 2) is valid."""
        uv = np.atleast_2d(np.asarray(uv, float)).reshape(-1, 2)
        margin = self.domain.margin(uv)
        bad = np.flatnonzero(margin <= 0)
        if bad.size:
            i = bad[np.argmin(margin[bad])]
            u, v = uv[i]
            direction = uv[i] / np.abs(uv[i]).max()
            lam = float(self.domain.extent(direction))
            t = float(self.domain.where_limited(uv[i]))
            raise RegressionError(
                f"{name}: lattice curve (u, v) = ({u:g}, {v:g}) passes the curve of regression "
                f"(Eq. 17 speed factor {margin[i]:.3g} ≤ 0, worst at t = {t:.4g}, s = {t * self.crease.curve.length:.4g}); "
                f"along this direction the limit is (u, v) = ({lam * direction[0]:.4g}, {lam * direction[1]:.4g})"
            )

    # -- rigid folding ------------------------------------------------------------------------
    @cached_property
    def kappa_2d(self) -> ScalarFunction:
        """κ_2D(s) of curve 1, fold-invariant."""
        return self.crease.curve.kappa.scaled(np.cos(self.crease.alpha.constant))

    @cached_property
    def _intrinsic_nodes(self) -> tuple[np.ndarray, np.ndarray]:
        """κ_2D and κ_2D cot β (= τ cot α) at the Gauss nodes of curve 1, both fold-invariant."""
        nodes = gauss_nodes(self.s)
        k2 = self.kappa_2d(nodes)
        return k2, k2 / np.tan(self.crease.beta_left(nodes))

    def _folded_curve1(self, alphas: np.ndarray, anchor: str) -> tuple[np.ndarray, np.ndarray]:
        """Curve 1 at half fold angles α (A,): points (A, n, 3) and frames (A, n, 3, 3)."""
        if anchor not in ("start", "middle"):
            raise InputError(f"anchor must be 'start' or 'middle', got {anchor!r}")
        k2_nodes, k2cot_nodes = self._intrinsic_nodes
        c = self.crease.curve
        ca, ta = np.cos(alphas)[:, None, None], np.tan(alphas)[:, None, None]
        points, frames = integrate_frenet(c.s, k2_nodes / ca, k2cot_nodes * ta, origin=c.points[0], frame=c.frames[0])
        if anchor == "middle":
            m = (len(c.s) - 1) // 2
            R = c.frames[m] @ np.swapaxes(frames[:, m], -1, -2)  # (A, 3, 3)
            points = np.einsum("aij,anj->ani", R, points - points[:, m : m + 1]) + c.points[m]
            frames = R[:, None] @ frames
        return points, frames

    def fold_points(self, uv: np.ndarray, fold_angles: np.ndarray, *, degrees: bool = True, anchor: str = "start") -> np.ndarray:
        """Lattice curves uv at many fold angles at once, shape (A, K, n, 3).

        The vectorised path behind a folding motion: equivalent to
        ``[self.refold(f, anchor=anchor).points(uv) for f in fold_angles]``.

        Parameters
        ----------
        uv : (K, 2) array_like
        fold_angles : (A,) array_like
            2α values in [0°, 180°) (degrees by default).
        anchor : {"start", "middle"}, keyword-only
        """
        alphas = np.array([half_angle(f, degrees=degrees, allow_flat=True) for f in np.atleast_1d(fold_angles)])
        points, frames = self._folded_curve1(alphas, anchor)
        rl, rr = ruling_vectors(frames, alphas[:, None], self.beta, self.beta)
        ll, lr = self.ruling_lengths
        return lattice_points(points, ll[:, None] * rl, lr[:, None] * rr, uv)

    def refold(self, fold_angle: float, *, degrees: bool = True, anchor: str = "start") -> Lattice:
        """The same lattice rigidly folded to another fold angle 2α ∈ [0°, 180°).

        Intrinsic quantities (κ_2D, β, widths, t-correspondence) stay; curve 1 is rebuilt
        with ``κ = κ_2D / cos α`` and ``τ = κ_2D tan α cot β`` (= τ₀ tan α / tan α₀). 2α = 0
        gives the flat, two-ply state: the crease pattern.

        Parameters
        ----------
        fold_angle : float
            2α, degrees by default.
        anchor : {"start", "middle"}, keyword-only
            Which frame of curve 1 stays where it is in this lattice: the one at t = 0, or
            the one at the middle sample ``(n - 1) // 2``.
        """
        a = half_angle(fold_angle, degrees=degrees, allow_flat=True)
        points, frames = self._folded_curve1(np.array([a]), anchor)
        points, frames = points[0], frames[0]
        for arr in (points, frames):
            arr.flags.writeable = False
        c = self.crease.curve
        ca, ta = np.cos(a), np.tan(a)
        k2, beta = self.kappa_2d, self.crease.beta_left
        tau = ScalarFunction(
            lambda s: ta * k2(s) / np.tan(beta(s)),
            lambda s: ta * (k2.derivative(s) / np.tan(beta(s)) - k2(s) * beta.derivative(s) / np.sin(beta(s)) ** 2),
        )
        curve = SpaceCurve(c.s, points, frames, k2.scaled(1.0 / ca), tau)
        alpha = ScalarFunction(lambda s: np.full(np.shape(s), a), lambda s: np.zeros(np.shape(s)), a)
        crease = Crease(curve, alpha, beta, self.crease.beta_right)
        folded = Lattice(crease, self.width_left, self.width_right)
        # Fold-invariant cached values carry over (cached_property keeps them in __dict__).
        for name in ("beta", "ruling_lengths", "domain", "kappa_2d", "_intrinsic_nodes"):
            if name in self.__dict__:
                folded.__dict__[name] = self.__dict__[name]
        return folded


def lattice_points(x1: np.ndarray, left: np.ndarray, right: np.ndarray, uv: np.ndarray) -> np.ndarray:
    """Eq. 11, ``x1 + u ℓ_L r_L + v ℓ_R r_R``, for curve-1 data (..., n, 3) and uv (..., 2).

    For ``x1`` of shape (A, n, 3) and ``uv`` of shape (K, 2) the result is (A, K, n, 3);
    for (n, 3) and (..., 2) it is (..., n, 3). One matrix product per sample.
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


def log_width_ratio(crease: Crease) -> np.ndarray:
    """``∫₀^s τ cot α ds`` at the samples, by 3-point Gauss–Legendre per interval, shape (n,)."""
    s = crease.s
    nodes = gauss_nodes(s)
    integrand = crease.curve.tau(nodes) / np.tan(crease.alpha(nodes))  # = κ_2D cot β
    steps = np.diff(s) * (integrand @ GAUSS3_WEIGHTS)
    return np.concatenate([[0.0], np.cumsum(steps)])
