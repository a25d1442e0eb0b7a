"""Arch curves whose end sections stand on one ground plane (the paper's Eq. 20).

A vault stands when every end section of its tubes lies on the ground. With β = 90° at
both ends (τ = 0 there) each end section is normal to the crease's tangent, so the ends of
curve 1 must face opposite ways and lie in one plane:

    T(0) + T(s₁) = 0,   (x(s₁) − x(0))·T(0) = 0

(the paper prints ``T(0) − T(s₁) = 0``: a curve whose ends face the same way cannot start
and end on one plane it leaves upward). With reflection symmetry ``κ(s) = κ(s₁ − s)``,
``τ(s) = −τ(s₁ − s)`` both conditions reduce to ``T(s₁/2)·T(0) = 0`` (Eq. 20).

The paper's family is ``κ = κ₀``, ``τ = a κ₀ sin(2π s / s₀)`` with s₁ = s₀; all lengths
scale with 1/κ₀, so it is solved for the dimensionless κ₀ s₀.

A vault of rigid panels (:mod:`curvefold.geometry._panels`) stands when every polyline's end
vertex lies on the ground. Those at vertex 0 are ``x_0 + u L_0 + v R_0``: all in the plane P₀
through x_0 spanned by L_0 and R_0, and likewise P_N. The pattern sampled from a
reflection-symmetric design is mirror-symmetric, hence so is every folded state (the mirror
is the plane bisecting x_0 x_N and takes vertex k to N − k), and P_N is P₀'s mirror image:
the two coincide exactly when P₀ is perpendicular to the mirror,

    (x_N − x_0)·n₀ = 0,   n₀ ∝ L_0 × R_0               (the discrete Eq. 20)

at the design angle, solved for κ₀ s₀ by :func:`solve_panel_arch`. The end fold lines leave
the vertices at β(0) = 90° from the smooth crease's tangent, so the panel arch approaches
the smooth one at second order in 1/N.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..geometry._crease import Crease
from ..geometry._curve import SpaceCurve, gauss_nodes, integrate_frenet
from ..geometry._fold_angle import half_angle
from ..geometry._lattice_pattern import Pattern
from ..geometry._panel_pattern import PanelPattern, check_panels
from ..kernel._arrays import readonly
from ..kernel._errors import ConvergenceError, InputError
from ..kernel._functions import ScalarFunction
from ..kernel._lie import cross, exp_rotation, product_quaternions
from ..kernel._validate import Interval

__all__ = [
    "A_MAX",
    "A_STANDING",
    "check_standing",
    "ArchRoot",
    "solve_symmetric_arch",
    "symmetric_arch_condition",
    "proportion_change",
    "GeneralArch",
    "solve_general_arch",
    "HarmonicTorsion",
    "panel_arch_condition",
    "solve_panel_arch",
]

#: Largest torsion amplitude with a standing arch: there the two roots of Eq. (20) near
#: κ₀s₀ ≈ 4.4 merge and vanish (measured; an independent DOP853 integration agrees).
A_MAX = 1.2707093728
#: The torsion amplitudes of a standing arch, [0, A_MAX): the range of a design's ``a``.
A_STANDING = Interval(0.0, A_MAX, True, False)

#: Where the root next to π lies for every a < A_MAX (π at a = 0, about 4.42 at A_MAX): one
#: Chebyshev interpolant on this window finds it directly.
WINDOW = (0.9 * np.pi, 1.5 * np.pi)

#: Integration steps over half the arch: the condition at the root, integrated with 8× the steps,
#: stays below 1e-14 for every a < A_MAX (tested; 64 steps left 7e-13 near A_MAX, which the built
#: curve 1 shows as a failed arch_condition).
HALF_STEPS = 128

#: Largest ``|T(s₀/2)·T(0)|`` accepted at a returned root: the condition's rounding over the
#: steps (~1e-14) plus its slope (≤ 1) times the bracket half-width (1e-13), with a margin.
#: Over a ∈ [0, A_MAX) the roots found have at most 3e-15 (measured on 400 values).
RESIDUAL_TOL = 1e-12


def symmetric_arch_condition(
    kappa0_s0: float | np.ndarray, a: float, *, steps: int = HALF_STEPS
) -> np.ndarray:
    """``T(s₀/2)·T(0)`` for the curve κ = 1, τ = a sin(2π s / s₀) with s₀ = κ₀ s₀.

    Parameters
    ----------
    kappa0_s0 : float or (m,) array_like
        Dimensionless arch lengths to evaluate at (a batch is integrated at once).
    a : float
        Torsion amplitude.
    steps : int, keyword-only
        Integration steps over [0, s₀/2].

    Returns
    -------
    ndarray
        Same shape as ``kappa0_s0``. For a = 0 it is cos(κ₀ s₀ / 2).

    Examples
    --------
    >>> symmetric_arch_condition([np.pi, 2.0], 0.0).round(
    ...     6
    ... ).tolist()  # no torsion: cos(κ₀ s₀ / 2), a half circle stands
    [0.0, 0.540302]
    >>> round(float(symmetric_arch_condition(solve_symmetric_arch(0.3).kappa0_s0, 0.3)), 12)
    0.0
    """
    x = np.atleast_1d(np.asarray(kappa0_s0, float))
    h, s1, d1, d2 = _half_arch_grid(steps)
    # The Magnus-6 rotation (lie.magnus6_rotation) with κ = 1 and τ = a sin(π q) written
    # out: with hs = h s₀/2 every term is hs or hs² times a fixed array of the grid.
    hs = (0.5 * h * x)[:, None]
    k, f, g = np.sqrt(15.0) / 3.0, -1.0 / 60.0, 1.0 / 240.0
    a1, A, E = hs * (a * s1), hs * (k * a * d1), hs * ((10.0 / 3.0) * a * d2)
    p = -A * hs
    Z = (A + f * p * hs, -2 * f * E * hs, -f * p * a1)
    X = (-20 * a1 - E, p, -20 * hs)
    w = (Z[1] * X[2] - Z[2] * X[1], Z[2] * X[0] - Z[0] * X[2], Z[0] * X[1] - Z[1] * X[0])
    omega = (a1 + E / 12 + g * w[0], g * w[1], hs + g * w[2])
    # Only the end frame is needed: multiply the steps pairwise.
    w0, qx, y, z = product_quaternions(exp_rotation(omega))
    value = 1 - 2 * (y * y + z * z) / (w0 * w0 + qx * qx + y * y + z * z)  # T(s₀/2)·T(0), T(0) = e₁
    return value.reshape(np.shape(kappa0_s0))


@lru_cache(maxsize=8)
def _half_arch_grid(steps: int) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
    """Step h in q = 2s/s₀ and, per step, sin(π q) at the middle Gauss node and its first
    and second differences across the three nodes (read-only)."""
    q = np.linspace(0.0, 1.0, steps + 1)
    sin = np.sin(np.pi * gauss_nodes(q))
    s1, d1, d2 = sin[:, 1], sin[:, 2] - sin[:, 0], sin[:, 2] - 2 * sin[:, 1] + sin[:, 0]
    return 1.0 / steps, readonly(s1), readonly(d1), readonly(d2)


@dataclass(frozen=True)
class ArchRoot:
    """The solution of Eq. (20) for the harmonic-torsion family.

    Attributes
    ----------
    a : float
        Torsion amplitude.
    kappa0_s0 : float
        Dimensionless arch length κ₀ s₀ (π for a = 0).
    residual : float
        ``|T(s₀/2)·T(0)|`` at the root, at most :data:`RESIDUAL_TOL`.
    bracket : tuple of float
        The bracket the root was refined in.
    smooth : ArchRoot or None
        For a panel arch (:func:`solve_panel_arch`), the smooth root its search started
        from: the arch of the design's smooth build, which decides its tubes.

    Examples
    --------
    >>> root = solve_symmetric_arch(0.0)  # no torsion: the half circle, κ₀ s₀ = π
    >>> root.a, round(root.kappa0_s0, 12), root.residual < 1e-12
    (0.0, 3.14159265359, True)
    """

    a: float
    kappa0_s0: float
    residual: float
    bracket: tuple[float, float]
    smooth: ArchRoot | None = None


def check_standing(a: float) -> float:
    """``a`` when the arch family stands for it (a < :data:`A_MAX`), else the error saying why not.

    Raises
    ------
    ConvergenceError
        For a ≥ :data:`A_MAX`, where Eq. (20) has no root next to π.

    Examples
    --------
    >>> check_standing(0.3)
    0.3
    >>> check_standing(1.5)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.ConvergenceError: no standing arch for a = 1.5: Eq. (20), T(s0/2)·T(0)
    = 0, has a root next to π only for a < 1.2707 (there the two roots near κ0·s0 ≈ 4.4 merge and
    vanish)
    """
    if a >= A_MAX:
        raise ConvergenceError(
            f"no standing arch for a = {a:g}: Eq. (20), T(s0/2)·T(0) = 0, has a root next to π "
            f"only for a < {A_MAX:.4f} (there the two roots near κ0·s0 ≈ 4.4 merge and "
            "vanish)",
            parameter="a",
        )
    return a


def solve_symmetric_arch(a: float, *, xtol: float = 1e-13, steps: int = HALF_STEPS) -> ArchRoot:
    """Solve Eq. (20) for κ₀ s₀ on the root next to π, by a bracketed search.

    1. Interpolate the condition at 16 Chebyshev points of :data:`WINDOW`, where the
       root next to π lies for every a < A_MAX (one batched integration; the condition is
       analytic in κ₀ s₀, so the interpolant is exact to rounding), and take the
       interpolant's root nearest π.
    2. Verify it: the condition must change sign across ``root ± xtol`` (one batched
       integration), which brackets the root to ``xtol``.
    3. Should that fail (near the end of the family, or for no root), scan 16 points over
       [π/2, 2π] for the sign change nearest π, interpolate that bracket the same way,
       and fall back on Brent's method.

    Every root returned is verified: ``|T(s₀/2)·T(0)|`` at it is at most :data:`RESIDUAL_TOL`.

    Parameters
    ----------
    a : float
        Torsion amplitude, finite and ≥ 0 (the family is symmetric in the sign of a).
    xtol : float, keyword-only
        Half-width of the final bracket on κ₀ s₀.

    Raises
    ------
    InputError
        ``a`` is not a finite number ≥ 0.
    ConvergenceError
        For a ≥ :data:`A_MAX` ≈ 1.2707, where the family has no standing arch (refused
        before solving); when no root lies in (π/2, 2π); or when the root found does not
        pass the residual check.

    Examples
    --------
    >>> round(solve_symmetric_arch(0.0).kappa0_s0, 12) == round(float(np.pi), 12)
    True
    """
    a = float(a)
    if not np.isfinite(a) or a < 0:
        raise InputError(
            f"a (torsion amplitude) must be a finite number ≥ 0, got {a!r}", parameter="a"
        )
    check_standing(a)
    f = lambda x: float(symmetric_arch_condition(x, a, steps=steps))  # noqa: E731
    found = _chebyshev_root(a, *WINDOW, xtol, steps)
    if found is not None:
        return _verified(a, *found, WINDOW)
    grid = np.pi * np.linspace(0.5, 2.0, 16)
    # signs only: coarse steps (error ~1e-7)
    values = symmetric_arch_condition(grid, a, steps=max(steps // 4, 8))
    changes = np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) <= 0)
    if changes.size == 0:
        # Near the end of the family the two roots merge: look for a dip below zero between grid
        # points.
        from scipy.optimize import minimize_scalar

        k = int(np.clip(np.argmin(values), 1, len(grid) - 2))
        dip = minimize_scalar(
            f, bounds=(grid[k - 1], grid[k + 1]), method="bounded", options={"xatol": 1e-12}
        )
        if dip.fun > 0:
            raise ConvergenceError(
                f"no standing arch for a = {a:g}: Eq. (20), T(s0/2)·T(0) = 0, has no root with "
                f"κ0·s0 in (π/2, 2π); the root next to π exists only for a < {A_MAX:.4f}",
                parameter="a",
            )
        grid, changes = np.array([grid[k - 1], dip.x]), np.array([0])
    i = changes[np.argmin(np.abs(0.5 * (grid[changes] + grid[changes + 1]) - np.pi))]
    lo, hi = float(grid[i]), float(grid[i + 1])
    found = _chebyshev_root(a, lo, hi, xtol, steps)
    if found is not None:
        return _verified(a, *found, (lo, hi))
    # Brent on a bracket checked at full accuracy (widened if the coarse scan misled)
    from scipy.optimize import brentq  # here only: the Chebyshev root above spares start-up SciPy

    while f(lo) * f(hi) > 0 and lo > grid[0] - 1e-12:
        lo, hi = lo - (hi - lo), hi + (hi - lo)
    root = float(brentq(f, lo, hi, xtol=xtol, rtol=4 * np.finfo(float).eps, maxiter=200))
    return _verified(a, root, abs(f(root)), (lo, hi))


def _verified(a: float, root: float, residual: float, bracket: tuple[float, float]) -> ArchRoot:
    """The root, if the condition at it is within :data:`RESIDUAL_TOL`; never a false one."""
    if not (np.isfinite(root) and residual <= RESIDUAL_TOL):
        raise ConvergenceError(
            f"the arch equation for a = {a:g} was not solved: at κ0·s0 = {root:.12g}, "
            f"|T(s0/2)·T(0)| = {residual:.2e} exceeds {RESIDUAL_TOL:g}"
        )
    return ArchRoot(a, root, float(residual), bracket)


def _chebyshev_root(
    a: float, lo: float, hi: float, xtol: float, steps: int, points: int = 16
) -> tuple[float, float] | None:
    """The root nearest π in [lo, hi] of the Chebyshev interpolant of Eq. (20), if a sign
    change across ``root ± xtol`` confirms it.

    Returns the root and |condition| at it (evaluated with ``root ± xtol`` in one batch),
    or None.
    """
    from numpy.polynomial import chebyshev

    k = np.arange(points)
    theta = np.pi * (k + 0.5) / points
    values = symmetric_arch_condition(
        0.5 * (lo + hi) + 0.5 * (hi - lo) * np.cos(theta), a, steps=steps
    )
    coefficients = (2.0 / points) * np.cos(np.outer(k, theta)) @ values  # discrete cosine transform
    coefficients[0] /= 2
    # Sign changes between neighbouring nodes (ascending in x), the one nearest π refined by
    # Newton's method on the interpolant (a cheap polynomial), kept inside its node interval.
    y = np.cos(theta)[::-1]  # nodes in [-1, 1], ascending
    v = values[::-1]
    changes = np.flatnonzero(v[:-1] * v[1:] <= 0)
    if changes.size == 0:
        return None
    to_x = lambda u: 0.5 * (lo + hi) + 0.5 * (hi - lo) * u  # noqa: E731
    i = changes[np.argmin(np.abs(to_x(0.5 * (y[changes] + y[changes + 1])) - np.pi))]
    lo_u, hi_u = y[i], y[i + 1]
    derivative = chebyshev.chebder(coefficients)
    u = lo_u - v[i] * (hi_u - lo_u) / (v[i + 1] - v[i])  # secant start
    for _ in range(30):
        step = chebyshev.chebval(u, coefficients) / chebyshev.chebval(u, derivative)
        u = min(max(u - step, lo_u), hi_u)
        if abs(step) < 1e-16:
            break
    root = float(to_x(u))
    low, at, high = symmetric_arch_condition(
        np.array([root - xtol, root, root + xtol]), a, steps=steps
    )
    return (root, float(abs(at))) if low * high <= 0 else None


@dataclass(frozen=True)
class HarmonicTorsion(ScalarFunction):
    """τ(s) = amplitude · sin(2π s / period), with its exact derivative.

    Examples
    --------
    >>> tau = HarmonicTorsion(0.3, 2.0)
    >>> (
    ...     tau(np.array([0.5, 1.0])).round(6).tolist(),
    ...     tau.derivative(np.array([0.0])).round(6).tolist(),
    ... )
    ([0.3, 0.0], [0.942478])
    >>> HarmonicTorsion(0.0, 2.0)(np.array([0.5])).tolist()  # a = 0: no torsion
    [0.0]
    """

    amplitude: float
    period: float

    def value(self, s: np.ndarray) -> np.ndarray:
        return self.amplitude * np.sin(2 * np.pi * s / self.period)

    def derivative(self, s: np.ndarray) -> np.ndarray:
        return self.amplitude * (2 * np.pi / self.period) * np.cos(2 * np.pi * s / self.period)


def panel_arch_condition(
    kappa0_s0: float, a: float, panels: int, *, fold_angle: float = 90.0
) -> float:
    """``(x_N − x_0)·n₀ / |x_N − x_0|`` of the panel arch of κ = 1, τ = a sin(2π s / s₀), s₀ = κ₀
    s₀.

    The crease pattern of the smooth arch at the design angle 2α (degrees), sampled with
    ``panels`` panels (:meth:`~curvefold.geometry.PanelPattern.from_pattern`) and
    folded to 2α; n₀ is the unit normal of its end section at vertex 0. Zero when both end
    sections lie in one plane (see the module notes).

    Examples
    --------
    Four panels do not stand at the smooth half circle's κ₀ s₀ = π; their own root does:

    >>> round(panel_arch_condition(np.pi, 0.0, 4), 6)
    0.038037
    >>> abs(panel_arch_condition(solve_panel_arch(0.0, 4).kappa0_s0, 0.0, 4)) < 1e-12
    True
    """
    x = float(kappa0_s0)
    curve = SpaceCurve.from_curvature(1.0, HarmonicTorsion(a, x), x, samples=3)
    pattern = Pattern.from_crease(Crease.from_curve(curve, fold_angle=fold_angle), 1.0, 1.0)
    points, left, right, _ = PanelPattern.from_pattern(pattern, panels).fold(
        np.array([half_angle(fold_angle)])
    )
    normal = cross(left[0, 0], right[0, 0])
    chord = points[0, -1] - points[0, 0]
    return float(normal @ chord / (np.linalg.norm(normal) * np.linalg.norm(chord)))


def solve_panel_arch(
    a: float, panels: int, *, fold_angle: float = 90.0, xtol: float = 1e-14
) -> ArchRoot:
    """Solve the discrete Eq. (20) of a panel arch for κ₀ s₀, next to the smooth root.

    The smooth root (:func:`solve_symmetric_arch`) starts a search for a sign change of
    :func:`panel_arch_condition` (the two roots differ by O(1/N²)); Brent's method refines it.

    Parameters
    ----------
    a : float
        Torsion amplitude (as in :func:`solve_symmetric_arch`).
    panels : int
        Panels along each crease.
    fold_angle : float, keyword-only
        Design angle 2α in degrees, at which the arch stands.
    xtol : float, keyword-only
        Width of the final bracket on κ₀ s₀, relative.

    Raises
    ------
    ConvergenceError
        If the family has no standing arch for ``a``, or the panel arch none near it.

    Examples
    --------
    >>> root = solve_panel_arch(0.3, 24)
    >>> abs(root.kappa0_s0 / solve_symmetric_arch(0.3).kappa0_s0 - 1) < 1e-3
    True
    """
    from scipy.optimize import brentq

    n = check_panels(panels)
    half_angle(fold_angle)
    smooth = solve_symmetric_arch(a)
    x0 = smooth.kappa0_s0
    f = lambda x: panel_arch_condition(x, a, n, fold_angle=fold_angle)  # noqa: E731
    f0 = f(x0)
    for step in x0 * 1e-3 * 4.0 ** np.arange(6):  # up to 1 % of κ₀s₀ … 100 %
        for other in (x0 - step, x0 + step):
            if other > 0 and f(other) * f0 <= 0:
                lo, hi = sorted((x0, other))
                root = brentq(f, lo, hi, xtol=xtol * x0, rtol=4 * np.finfo(float).eps, maxiter=200)
                return ArchRoot(float(a), float(root), abs(f(root)), (lo, hi), smooth)
    raise ConvergenceError(
        f"no standing arch of {n} panels for a = {a:g} near the smooth one (κ0·s0 = {x0:.6g}): "
        "the discrete Eq. (20) has no root there; use more panels",
        parameter="panels",
    )


def proportion_change(a: float, kappa0_s0: float, *, fold_angle: float = 90.0) -> float:
    """w_R(s₀/2) / w_R(0) = exp(a κ₀ s₀ cot α / π) for the harmonic-torsion family.

    ``ln w_R`` grows by ``∫ τ cot α ds = a κ₀ cot α ∫₀^{s₀/2} sin(2π s/s₀) ds = a κ₀ s₀ cot α / π``;
    at the paper's 2α = 90° this is its ``exp(a κ₀ s₀ / π)``.

    Raises
    ------
    InputError
        When the change, squared for p_xz, overflows float64 (a fold angle so small that
        cot α is huge), or the fold angle is 0 in radians.

    Examples
    --------
    >>> (
    ...     round(proportion_change(0.3, solve_symmetric_arch(0.3).kappa0_s0), 6),
    ...     proportion_change(0.0, np.pi),
    ... )  # a = 0: no change
    (1.352972, 1.0)
    >>> proportion_change(0.3, 3.0, fold_angle=0.0)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: fold_angle 2α = 0.0° is 0 in radians (below the smallest
    positive float): no fold angle
    """
    alpha = np.radians(fold_angle) / 2
    if not alpha > 0:
        raise InputError(
            f"fold_angle 2α = {fold_angle!r}° is 0 in radians (below the smallest "
            "positive float): no fold angle",
            parameter="fold_angle",
        )
    exponent = a * kappa0_s0 / np.tan(alpha) / np.pi
    if exponent > _LOG_MAX:
        smallest = 2 * np.degrees(np.arctan(a * kappa0_s0 / (np.pi * _LOG_MAX)))
        raise InputError(
            f"the proportion change exp(a κ0·s0 cot α / π) overflows for a = {a:g} at fold angle "
            f"2α = {fold_angle:g}°: the fold angle must be at least {smallest:.3g}°"
        )
    return float(np.exp(exponent))


#: Largest log of a proportion change: p_xz = p_xy × change² (p_xy ≤ 100) stays a float64.
_LOG_MAX = float(np.log(np.finfo(float).max) - np.log(100.0)) / 2


@dataclass(frozen=True)
class GeneralArch:
    """A solved general arch.

    Attributes
    ----------
    length : float
        Arc length s₁ of the arch.
    params : tuple of float
        The free parameters at the solution.
    residuals : (4,) ndarray
        ``T(s₁) + T(0)`` (3 components) and ``(x(s₁) − x(0))·T(0)`` at the solution.

    Examples
    --------
    >>> arch = solve_general_arch(
    ...     lambda s, p: np.ones_like(s), lambda s, p: 0 * s, 3.0
    ... )  # κ = 1, τ = 0, no parameter
    >>> round(arch.length, 9), arch.params, bool(np.abs(arch.residuals).max() < 1e-10)
    (3.141592654, (), True)
    """

    length: float
    params: tuple[float, ...]
    residuals: np.ndarray


def solve_general_arch(
    kappa: Callable[[np.ndarray, Sequence[float]], np.ndarray],
    tau: Callable[[np.ndarray, Sequence[float]], np.ndarray],
    length0: float,
    params0: Sequence[float] = (),
    *,
    steps: int = 800,
    tol: float = 1e-10,
) -> GeneralArch:
    """Solve the end conditions of a general arch without assuming reflection symmetry.

    Unknowns are the arc length s₁ and the free parameters; the equations are
    ``T(s₁) + T(0) = 0`` and ``(x(s₁) − x(0))·T(0) = 0``, solved by least squares
    (Levenberg–Marquardt on the four residuals). They are three independent conditions
    (T is a unit vector), so a family generically needs two free parameters besides s₁;
    with fewer, a solution exists only where symmetry removes conditions, as for Eq. (20).

    Parameters
    ----------
    kappa, tau : callable
        ``kappa(s, params)`` and ``tau(s, params)``, vectorised in s; κ > 0.
    length0 : float
        Starting guess for s₁.
    params0 : sequence of float
        Starting guess for the free parameters (at most 3, so the system is not
        under-determined).
    tol : float, keyword-only
        Largest accepted residual norm.

    Raises
    ------
    ConvergenceError
        If the solver stops with a residual norm above ``tol``; the message gives it.

    Examples
    --------
    The unit circle turns back on itself (T(s₁) = −T(0)) after half a turn:

    >>> round(solve_general_arch(lambda s, p: np.ones_like(s), lambda s, p: 0 * s, 3.0).length, 9)
    3.141592654
    >>> solve_general_arch(lambda s, p: np.ones_like(s), lambda s, p: 0 * s, -1.0)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: length0 must be a finite number > 0, got -1.0
    """
    from scipy.optimize import least_squares

    params0 = tuple(float(p) for p in params0)
    if len(params0) > 3:
        raise InputError(f"params0: at most 3 free parameters (4 equations), got {len(params0)}")
    if not np.isfinite(length0) or length0 <= 0:
        raise InputError(f"length0 must be a finite number > 0, got {length0!r}")
    q = np.linspace(0.0, 1.0, steps + 1)
    nodes = gauss_nodes(q)

    def residuals(z: np.ndarray) -> np.ndarray:
        L, p = z[0], tuple(z[1:])
        if L <= 0:
            return np.full(4, 1e3)
        k = np.asarray(kappa(nodes * L, p), float) * np.ones_like(nodes)
        if not np.all(k > 0) or not np.all(np.isfinite(k)):
            return np.full(4, 1e3)
        t = np.asarray(tau(nodes * L, p), float) * np.ones_like(nodes)
        points, frames = integrate_frenet(q, k, t, speed_nodes=L)
        T0, T1 = frames[0, :, 0], frames[-1, :, 0]
        return np.concatenate([T1 + T0, [(points[-1] - points[0]) @ T0]])

    sol = least_squares(
        residuals,
        np.array((float(length0),) + params0),
        method="lm",
        xtol=1e-15,
        ftol=1e-15,
        gtol=1e-15,
    )
    r = residuals(sol.x)
    if not np.linalg.norm(r) <= tol:
        raise ConvergenceError(
            f"general arch did not converge: residual norm {np.linalg.norm(r):.3g} > tol {tol:g} "
            f"(s1 = {sol.x[0]:.6g}, params = {tuple(np.round(sol.x[1:], 6))}); try another "
            "starting guess"
        )
    return GeneralArch(float(sol.x[0]), tuple(float(p) for p in sol.x[1:]), r)
