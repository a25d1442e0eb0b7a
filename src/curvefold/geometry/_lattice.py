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
refolded from it holds the same pattern object. (The pattern lives in
``curvefold.geometry._lattice_pattern``; ``curvefold.io._pattern`` is the printed crease pattern.)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Literal

import numpy as np

from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InputError, RegressionError
from ..kernel._functions import Constant, ScalarFunction
from ._crease import Crease
from ._crease_laws import ruling_vectors
from ._curve import SpaceCurve, integrate_frenet
from ._fold_angle import half_angle
from ._lattice_pattern import Pattern, RegressionDomain, constant_alpha
from ._topology import Topology

__all__ = [
    "Lattice",
    "check_anchor",
    "check_curves",
    "lattice_points",
]


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


def _example_lattice() -> Lattice:
    """The lattice of the examples: a unit circle folded at 90° (5 samples), widths 0.1."""
    crease = Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5), fold_angle=90)
    return Lattice.from_crease(crease, 0.1, 0.1)
