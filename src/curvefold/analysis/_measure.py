"""Measurements: the geometry's residuals, taken from built points, never from the formulas.

The functions read built geometry (sampled curves, ruling vectors, mesh coordinates) and
return arrays: derivatives and the frame, curvature and angles they give, and residuals
that the construction makes zero in the continuum, so that a wrong formula shows at
order one while a correct design leaves only the truncation error of the measurement.
Derivatives along a curve are fourth-order central differences on its uniform samples
(truncation ~h⁴), defined at the samples 2 … n − 3: n − 4 entries along the curve axis.
Angles are in radians unless stated. :mod:`curvefold.analysis._certificate` turns the
residuals into checks; the last functions here reduce them to one number for a crease, a
lattice or a mesh.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..geometry._crease import Crease
from ..geometry._curve import gauss_nodes
from ..geometry._lattice import Lattice
from ..geometry._mesh import Mesh
from ..geometry._structure import State
from ..kernel._functions import ScalarFunction
from ..kernel._lie import GAUSS3_WEIGHTS, cross, cross3

__all__ = [
    "derivative",
    "second_derivative",
    "cumulative_integral",
    "norm",
    "unit",
    "angle_between",
    "tangent_deviation",
    "speed_factors",
    "curvature",
    "ruling_twist",
    "crease_half_angle",
    "half_angle_between",
    "tangent_line_distance",
    "line_distance",
    "frenet",
    "rebuilt_strip",
    "dot3",
    "norm3",
    "cross3",
    "angle3",
    "line_distance3",
    "frenet3",
    "half_angle3",
    "rebuilt_strip3",
    "corner_nonplanarity3",
    "dihedral_angles3",
    "hinge_angles3",
    "unit3",
    "edge_lengths",
    "quad_nonplanarity",
    "corner_nonplanarity",
    "width_integral",
    "fold_angle_deviation",
    "developability_residual",
    "frame_agreement",
    "eq19_residual",
    "width_law_error",
    "fold_angle_error",
    "ruling_quad_planarity",
    "IsometryError",
    "isometry_error",
]


def derivative(values: np.ndarray, step: float, *, axis: int | None = None) -> np.ndarray:
    """d/dq of uniform samples by fourth-order central differences.

    Parameters
    ----------
    values : (n,) or (..., n, 3) ndarray
        A sequence of numbers, or of points along axis -2; spacing ``step``, n ≥ 5.
    step : float
    axis : int, optional, keyword-only
        The axis of the samples instead (e.g. -1 of points stored by component, (3, ..., n)).

    Returns
    -------
    (n - 4,) or (..., n - 4, 3) ndarray
        The derivative at samples 2 … n - 3 (along ``axis``).

    Examples
    --------
    >>> derivative(np.arange(7.0) ** 2, 1.0).tolist()  # d(q²)/dq = 2q at q = 2, 3, 4
    [4.0, 6.0, 8.0]
    """
    at = _stencil(values, axis)
    return (at(0) - 8 * at(1) + 8 * at(3) - at(4)) / (12.0 * step)


def second_derivative(values: np.ndarray, step: float, *, axis: int | None = None) -> np.ndarray:
    """d²/dq² of samples (..., n, 3) along axis -2 (or ``axis``) by fourth-order central
    differences, (..., n - 4, 3)."""
    at = _stencil(values, axis)
    return (-at(0) + 16 * at(1) - 30 * at(2) + 16 * at(3) - at(4)) / (12.0 * step**2)


def _stencil(values: np.ndarray, axis: int | None):
    """``at(k)``: the samples k … n − 5 + k along the samples' axis (-1 of a sequence, else -2,
    or ``axis``)."""
    v = np.asarray(values, float)
    axis = (-1 if v.ndim == 1 else -2) if axis is None else axis
    n, head = v.shape[axis], (slice(None),) * (axis % v.ndim)
    return lambda k: v[head + (slice(k, n - 4 + k),)]


def cumulative_integral(rate: np.ndarray, step: float) -> np.ndarray:
    """∫ from the first sample of uniformly sampled ``rate`` (..., m), fourth order, same shape.

    The trapezoid rule with its Euler–Maclaurin end correction ``−h²/12 (g'(q) − g'(q₀))``
    (g' by second-order differences): the error is O(h⁴).

    Examples
    --------
    >>> q = np.linspace(0, 1, 11)
    >>> round(float(cumulative_integral(q**3, 0.1)[-1]), 12)
    0.25
    """
    g = np.asarray(rate, float)
    trapezoid = np.concatenate(
        [
            np.zeros(g.shape[:-1] + (1,)),
            np.cumsum(0.5 * step * (g[..., 1:] + g[..., :-1]), axis=-1),
        ],
        axis=-1,
    )
    slope = np.gradient(g, step, axis=-1, edge_order=2)
    return trapezoid - step**2 / 12 * (slope - slope[..., :1])


def norm(v: np.ndarray) -> np.ndarray:
    """Length of vectors (..., 3), shape (...)."""
    return np.sqrt(np.einsum("...i,...i->...", v, v))


def unit(v: np.ndarray) -> np.ndarray:
    """Vectors (..., 3) scaled to length 1 (NaN for a zero vector)."""
    v = np.asarray(v, float)
    with np.errstate(invalid="ignore", divide="ignore"):
        return v / norm(v)[..., None]


def angle_between(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Angle in [0, π] between vectors (..., 3), by atan2 (accurate near 0 and π)."""
    return np.arctan2(norm(cross(a, b)), np.einsum("...i,...i->...", a, b))


def tangent_deviation(curves: np.ndarray, tangent: np.ndarray, step: float) -> np.ndarray:
    """Angle between each curve's measured tangent and a reference tangent at equal t.

    Lattice curves share curve 1's frame, so for them this is zero; a curve that passed
    its curve of regression runs backwards there, and the angle is π.

    Parameters
    ----------
    curves : (..., n, 3) ndarray
        Curves sampled at equal t, spacing ``step``.
    tangent : (n, 3) ndarray
        The reference unit tangent (curve 1's T) at the samples.
    step : float

    Returns
    -------
    (..., n - 4) ndarray
        Radians, in [0, π].
    """
    return angle_between(derivative(curves, step), tangent[2:-2])


def speed_factors(curves: np.ndarray, tangent: np.ndarray, step: float) -> np.ndarray:
    """``x'·T₁`` of each curve, differentiated along curve 1's arc length, (..., n - 4).

    For the lattice curve (u, v) this is the Eq. (17) speed factor
    ``1 − u w_L/w_lim_L − v w_R/w_lim_R`` when ``step`` is curve 1's arc-length step: its
    sign says whether the curve runs forward (≤ 0 past the curve of regression).
    """
    return np.einsum("...i,...i->...", derivative(curves, step), tangent[2:-2])


def curvature(curve: np.ndarray, step: float) -> np.ndarray:
    """Curvature ``|x' × x''| / |x'|³`` of a curve (..., n, 3) from its samples, (..., n - 4)."""
    d1, d2 = derivative(curve, step), second_derivative(curve, step)
    return norm(cross(d1, d2)) / norm(d1) ** 3


def ruling_twist(curve: np.ndarray, rulings: np.ndarray, step: float) -> np.ndarray:
    """``|r' · p|`` along a crease: how fast the tangent plane turns about its ruling.

    r is the unit ruling, p the unit normal of the plane spanned by the crease's measured
    tangent and r; r'·p = 0 is developability. Per unit arc length when ``step`` is the
    crease's arc-length step.

    Parameters
    ----------
    curve : (n, 3) ndarray
        The crease.
    rulings : (..., n, 3) ndarray
        Ruling vectors at its samples (any length, any sign).
    step : float

    Returns
    -------
    (..., n - 4) ndarray
    """
    r = unit(rulings)
    p = unit(cross(derivative(curve, step), r[..., 2:-2, :]))
    return np.abs(np.einsum("...i,...i->...", derivative(r, step), p))


def crease_half_angle(
    curve: np.ndarray,
    before: np.ndarray,
    after: np.ndarray,
    step: float,
    *,
    kind: str,
    tangent: np.ndarray | None = None,
) -> np.ndarray:
    """Half the fold angle, α, at a crease, from the rulings to its two neighbour creases.

    The rulings ``before − curve`` and ``after − curve`` are projected on the plane normal
    to the crease's measured tangent; the angle δ between them is the interior dihedral
    angle, π − 2α at a fold and 2α at a seam.

    Parameters
    ----------
    curve, before, after : (..., n, 3) ndarray
        The crease and the creases across its two strips, at equal t.
    step : float
    kind : {"fold", "seam"}, keyword-only
    tangent : (..., n - 4, 3) ndarray, optional, keyword-only
        The crease's unit tangent at samples 2 … n − 3 measured already (``unit(derivative(curve,
        step))``).

    Returns
    -------
    (..., n - 4) ndarray
        α in radians.
    """
    T = unit(derivative(curve, step)) if tangent is None else tangent
    x = curve[..., 2:-2, :]
    return half_angle_between(before[..., 2:-2, :] - x, after[..., 2:-2, :] - x, T, kind == "fold")


def half_angle_between(
    before: np.ndarray, after: np.ndarray, tangent: np.ndarray, fold: bool | np.ndarray
) -> np.ndarray:
    """:func:`crease_half_angle` from the rulings (..., m, 3) to the two neighbour creases and the
    crease's unit tangent.

    ``fold`` (broadcasting against (..., m)) says where the crease is a fold, elsewhere a seam.
    """
    before3, after3, tangent3 = _components(before, after, tangent)
    return half_angle3(before3, after3, tangent3, fold)


def tangent_line_distance(x: np.ndarray, y: np.ndarray, T: np.ndarray) -> np.ndarray:
    """Distance between the parallel lines through x and y along unit T, shape (..., n)."""
    return line_distance(y - x, T)


def line_distance(d: np.ndarray, T: np.ndarray) -> np.ndarray:
    """Distance between two parallel lines along unit T (..., n, 3), one through the other plus d
    (..., n, 3), shape (..., n)."""
    return norm(d - np.einsum("...i,...i->...", d, T)[..., None] * T)


def frenet(
    d1: np.ndarray, d2: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Speed, Frenet frame and curvature of a curve from its first two derivatives.

    Parameters
    ----------
    d1, d2 : (..., m, 3) ndarray
        x' and x'' (e.g. :func:`derivative` and :func:`second_derivative`).

    Returns
    -------
    speed, T, N, B, kappa
        ``|x'|`` (..., m); the unit tangent, principal normal and binormal (..., m, 3)
        (NaN where x' × x'' vanishes); ``|x' × x''| / |x'|³`` (..., m).

    Examples
    --------
    >>> speed, T, N, B, kappa = frenet(
    ...     np.array([[0.0, 2, 0]]), np.array([[-2.0, 0, 0]])
    ... )  # a circle of radius 2 at (2, 0, 0)
    >>> speed.tolist(), N.tolist(), (B + 0.0).tolist(), kappa.tolist()
    ([2.0], [[-1.0, 0.0, 0.0]], [[0.0, 0.0, 1.0]], [0.5])
    """
    speed, T, N, B, kappa = frenet3(*_components(d1, d2))
    return speed, _rows(T), _rows(N), _rows(B), kappa


def rebuilt_strip(
    curve: np.ndarray,
    ruling: np.ndarray,
    following: np.ndarray,
    step: float,
    *,
    alpha: float,
    side: str | np.ndarray,
    sign: float | np.ndarray,
    frenet_frame: tuple[np.ndarray, ...] | None = None,
) -> np.ndarray:
    """The paper's construction of the next crease from this crease's own measured invariants.

    From the crease's samples alone: its frame T, N, B and curvature κ (differences), its
    ruling angle β (between T and the other family's ruling at this crease: β_L = β_R at a
    constant fold angle), the width law ``d ln w/ds = ±κ cos α cot β`` (+ on the right, −
    on the left: Eqs. 12–13 corrected) started from the measured width to ``following`` at
    the first sample, and the ruling ``r_R = cos β T − sin β cos α N + sin β sin α B`` or
    ``r_L = cos β T + sin β cos α N + sin β sin α B`` (Eqs. 5–6): the next crease is
    ``x + sign · (w / sin β) r``. Nothing of the lattice formula (Eq. 11) is used.

    Parameters
    ----------
    curve : (..., n, 3) ndarray
        This crease.
    ruling : (..., n, 3) ndarray
        A vector along the other family's ruling r (as oriented in Eqs. 5–6) at each
        sample, e.g. toward the crease before this one; any length.
    following : (..., n, 3) ndarray
        The next crease at equal t (its first interior sample sets the starting width).
    step : float
        Spacing of t (any uniform parameter).
    alpha : float, keyword-only
        Half the fold angle, radians.
    side : {"L", "R"} or array of them, keyword-only
        The ruling family of the strip toward ``following`` (an array broadcasts against the
        leading axes of ``curve``: several creases of several kinds at once).
    sign : {1.0, -1.0} or array of them, keyword-only
        Whether the step runs along +r or −r (broadcasting as ``side``).
    frenet_frame : tuple of ndarray, optional, keyword-only
        The crease's :func:`frenet` at samples 2 … n − 3, measured already.

    Returns
    -------
    (..., n - 4, 3) ndarray
        The rebuilt ``following`` at samples 2 … n − 3.
    """
    if frenet_frame is not None:
        speed, T, N, B, kappa = frenet_frame
        frenet_frame = (speed, *_components(T, N, B), kappa)
    curve3, ruling3, following3 = _components(curve, ruling, following)
    rebuilt = rebuilt_strip3(
        curve3,
        ruling3,
        following3,
        step,
        alpha=alpha,
        side=side,
        sign=sign,
        frenet_frame=frenet_frame,
    )
    return _rows(rebuilt)


def edge_lengths(coords: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """Length of every edge (E, 2) of vertices (V, 3), shape (E,)."""
    return norm(np.take(coords, edges[:, 1], axis=0) - np.take(coords, edges[:, 0], axis=0))


def quad_nonplanarity(coords: np.ndarray, quads: np.ndarray) -> np.ndarray:
    """Distance of each quad's third corner from the plane of the other three, over its diagonal,
    (F,).

    Parameters
    ----------
    coords : (V, 3) ndarray
    quads : (F, 4) ndarray of int
        Corners in order around each quad.
    """
    p0, p1, p2, p3 = (np.take(coords, quads[:, k], axis=0) for k in range(4))
    return corner_nonplanarity(p1 - p0, p3 - p0, p2 - p0)


def corner_nonplanarity(side: np.ndarray, other: np.ndarray, diagonal: np.ndarray) -> np.ndarray:
    """:func:`quad_nonplanarity` from the vectors from each quad's first corner to the others:
    its two sides and its diagonal, (F, 3) each."""
    side, other, diagonal = _components(side, other, diagonal)
    return corner_nonplanarity3(side, other, diagonal, norm3(diagonal))


# -------------------------------------------------------------------------------------- vectors
# stored by component, (3, ...): what the certificate's frames hold (each component contiguous)
#
# A dot product sums x + z, then y, as ``np.einsum("...i,...i->...")`` sums two vectors stored as
# contiguous rows (…, 3), and x + y + z (``order=(0, 1, 2)``) as it sums them when one is strided:
# the same numbers as the row forms.


def _components(*vectors: np.ndarray) -> list[np.ndarray]:
    """Vectors (..., 3) as their components (3, ...) (views), with as many axes each as the most
    has (to broadcast)."""
    arrays = [np.asarray(v, float) for v in vectors]
    ndim = max(v.ndim for v in arrays)
    return [np.moveaxis(v.reshape((1,) * (ndim - v.ndim) + v.shape), -1, 0) for v in arrays]


def _rows(v: np.ndarray) -> np.ndarray:
    """Components (3, ...) as vectors (..., 3) (a view)."""
    return np.moveaxis(v, 0, -1)


def dot3(a: np.ndarray, b: np.ndarray, order: tuple[int, int, int] = (0, 2, 1)) -> np.ndarray:
    """``a · b`` of vectors stored by component, (3, ...) each (broadcasting), shape (...), summed
    in ``order``.

    Examples
    --------
    >>> dot3(np.array([[1.0], [2.0], [3.0]]), np.array([[4.0], [5.0], [6.0]])).tolist()
    [32.0]
    """
    i, j, k = order
    out = a[i] * b[i]
    out += a[j] * b[j]
    out += a[k] * b[k]
    out += 0.0  # a zero is +0, as einsum's sum into zeros leaves it
    return out


def norm3(v: np.ndarray) -> np.ndarray:
    """Length of vectors stored by component (3, ...), shape (...): :func:`norm`'s numbers."""
    out = v[0] * v[0]
    out += v[2] * v[2]
    out += v[1] * v[1]
    return np.sqrt(out, out=out)


def angle3(a: np.ndarray, b: np.ndarray, order: tuple[int, int, int] = (0, 2, 1)) -> np.ndarray:
    """:func:`angle_between` of vectors stored by component (3, ...), shape (...) (``order`` that
    of the dot product)."""
    return np.arctan2(norm3(cross3(a, b)), dot3(a, b, order))


def line_distance3(
    d: np.ndarray, T: np.ndarray, order: tuple[int, int, int] = (0, 2, 1)
) -> np.ndarray:
    """:func:`line_distance` of vectors stored by component (3, ...), shape (...)."""
    return norm3(_across3(d, T, order))


def _across3(v: np.ndarray, T: np.ndarray, order: tuple[int, int, int] = (0, 2, 1)) -> np.ndarray:
    """``v − (v·T) T`` of vectors stored by component (3, ...): v's part normal to the unit T
    (one new array)."""
    along = dot3(v, T, order) * T
    return np.subtract(v, along, out=along)


def frenet3(
    d1: np.ndarray, d2: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`frenet` of derivatives stored by component (3, ..., m): speed (..., m), T, N, B (3,
    ..., m), κ (..., m)."""
    speed = norm3(d1)
    T = d1 / speed
    b = cross3(d1, d2)
    bend = norm3(b)
    with np.errstate(invalid="ignore", divide="ignore"):
        b /= bend  # B
    return speed, T, cross3(b, T), b, bend / speed**3


def half_angle3(
    before: np.ndarray, after: np.ndarray, tangent: np.ndarray, fold: bool | np.ndarray
) -> np.ndarray:
    """:func:`half_angle_between` of vectors stored by component (3, ..., m), shape (..., m)."""
    delta = angle3(_across3(before, tangent), _across3(after, tangent))
    return np.where(fold, 0.5 * (np.pi - delta), 0.5 * delta)


def rebuilt_strip3(
    curve: np.ndarray,
    ruling: np.ndarray,
    following: np.ndarray,
    step: float,
    *,
    alpha: float,
    side: str | np.ndarray,
    sign: float | np.ndarray,
    frenet_frame: tuple[np.ndarray, ...] | None = None,
) -> np.ndarray:
    """:func:`rebuilt_strip` of curves stored by component (3, ..., n) (``frenet_frame`` as
    :func:`frenet3` gives it), (3, ..., n − 4)."""
    if frenet_frame is None:
        frenet_frame = frenet3(
            derivative(curve, step, axis=-1), second_derivative(curve, step, axis=-1)
        )
    speed, T, N, B, kappa = frenet_frame
    beta = angle3(ruling[..., 2:-2], T)
    right = np.asarray(side) == "R"
    sin_beta = np.sin(beta)
    # r = cos β T + sin β (±cos α N + sin α B), in place
    r = np.where(right, -np.cos(alpha), np.cos(alpha)) * N
    r += np.sin(alpha) * B
    r *= sin_beta
    r += np.cos(beta) * T
    rate = np.where(right, 1.0, -1.0) * kappa
    rate *= np.cos(alpha)
    rate /= np.tan(beta)
    rate *= speed  # ±κ cos α / tan β · ds/dt
    x = curve[..., 2:-2]
    start = line_distance3(following[..., 2:3] - x[..., :1], T[..., :1])
    scale = np.exp(cumulative_integral(rate, step))
    scale *= start
    scale *= sign  # sign · w
    scale /= sin_beta
    r *= scale
    r += x
    return r


def corner_nonplanarity3(
    side: np.ndarray, other: np.ndarray, diagonal: np.ndarray, diagonal_length: np.ndarray
) -> np.ndarray:
    """:func:`corner_nonplanarity` of vectors stored by component (3, F), with the diagonals'
    lengths (F,) (:func:`norm3`)."""
    n = cross3(side, other)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.abs(dot3(diagonal, n)) / (norm3(n) * diagonal_length)


def dihedral_angles3(
    face_areas: np.ndarray,
    faces_of_edges: np.ndarray,
    edge_vectors: np.ndarray,
    edge_lengths: np.ndarray,
) -> np.ndarray:
    """:func:`~curvefold.geometry.dihedral_angles` of vectors stored by component: face areas (3,
    F), edge vectors (3, E) and their lengths (E,) (:func:`norm3`); degrees (E,), the same
    numbers."""
    ef = faces_of_edges
    ok = (ef[:, 0] >= 0) & (ef[:, 1] >= 0)
    out = np.zeros(len(ef))
    n = unit3(face_areas)
    e, length = edge_vectors, edge_lengths
    if not ok.all():
        ef, e, length = ef[ok], e[:, ok], length[ok]
    out[ok] = hinge_angles3(np.take(n, ef[:, 0], axis=1), np.take(n, ef[:, 1], axis=1), e, length)
    return out


def hinge_angles3(n1: np.ndarray, n2: np.ndarray, e: np.ndarray, length: np.ndarray) -> np.ndarray:
    """The fold angle (degrees, FOLD sign) at hinges e (3, ...) of lengths (...) between faces of
    unit normals n1, n2 (3, ...), the face n1 running each hinge forward:
    :func:`~curvefold.geometry.dihedral_angles`' numbers."""
    with np.errstate(invalid="ignore", divide="ignore"):
        sine = -dot3(cross3(n1, n2), e) / length
        return np.degrees(np.arctan2(sine, dot3(n1, n2)))


def unit3(v: np.ndarray) -> np.ndarray:
    """Vectors stored by component (3, ...) scaled to length 1 (NaN for a zero vector)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return v / norm3(v)


def width_integral(kappa_2d: ScalarFunction, beta: ScalarFunction, s: np.ndarray) -> np.ndarray:
    """``∫₀^s κ_2D cot β ds`` (the log-width law, Eqs. 12–13 corrected) at uniform samples s, (n,).

    Three-point Gauss–Legendre on a grid four times finer than ``s``: its error is 4⁶
    times smaller than that of the same rule at the sample step.
    """
    fine = np.linspace(s[0], s[-1], 4 * (len(s) - 1) + 1)
    rate = kappa_2d(gauss_nodes(fine)) / np.tan(beta(gauss_nodes(fine)))
    return np.concatenate([[0.0], np.cumsum(np.diff(fine) * (rate @ GAUSS3_WEIGHTS))])[::4]


def fold_angle_deviation(measured: np.ndarray, kinds: np.ndarray, fold_angle: float) -> np.ndarray:
    """``|measured − expected|`` fold angle (degrees, wrapped to [0°, 180°]) of fold and seam edges,
    same shape.

    Expected for a fold angle 2α (degrees): −2α on the folds (creases 1, 3) and −(180° − 2α)
    on the seams (2, 4), mountains seen from outside the tubes. ``kinds``: "fold" or "seam", or
    whether each is a fold (bool).
    """
    kinds = np.asarray(kinds)
    expect = np.where(
        kinds if kinds.dtype == bool else kinds == "fold", -fold_angle, -(180.0 - fold_angle)
    )
    turned = measured - expect + 180.0
    # the remainder by 360° exactly (x − 360 is exact there), for less than %
    if ((turned >= 0.0) & (turned < 720.0)).all():
        wrapped = np.where(turned >= 360.0, turned - 360.0, turned)
    else:
        wrapped = turned % 360.0
    return np.abs(wrapped - 180.0)


# --------------------------------------------------------------------------------------
# one number per measurement, for a crease, a lattice or a mesh


def developability_residual(crease: Crease) -> float:
    """Largest ``|r'·p|`` of both families of rulings of a crease (:func:`ruling_twist`), per
    unit length."""
    return float(
        np.max(
            ruling_twist(crease.curve.points, np.stack(crease.rulings()), crease.s[1] - crease.s[0])
        )
    )


def frame_agreement(lattice: Lattice, uv: np.ndarray) -> float:
    """Largest angle (rad) between the lattice curves uv (K, 2) and curve 1's T at equal t
    (:func:`tangent_deviation`)."""
    curves = lattice.points(np.asarray(uv, float).reshape(-1, 2))
    return float(
        np.max(
            tangent_deviation(
                curves, lattice.crease.curve.frames[:, :, 0], lattice.s[1] - lattice.s[0]
            )
        )
    )


def eq19_residual(lattice: Lattice, uv_a: np.ndarray, uv_b: np.ndarray) -> float:
    """Largest ``|κ_a s'_a / (κ_b s'_b) − 1|`` between two lattice curves, κ and s' measured.

    The paper's Eq. (19) between neighbouring creases of one lattice, where α and β are
    shared and cancel: the surface between them bends alike seen from both.
    """
    x = lattice.points(np.array([uv_a, uv_b], float))
    h = lattice.s[1] - lattice.s[0]
    bend = curvature(x, h) * norm(derivative(x, h))
    return float(np.max(np.abs(bend[0] / bend[1] - 1)))


def width_law_error(lattice: Lattice) -> float:
    """Largest ``|ln(w/w(0)) ∓ ∫ κ_2D cot β ds|`` of w_L and w_R, measured between tangent lines."""
    x = lattice.points(np.array([[0, 0], [1, 0], [0, 1]], float))
    T = lattice.crease.curve.frames[:, :, 0]
    law = width_integral(lattice.kappa_2d, lattice.pattern.beta, lattice.s)
    widths = tangent_line_distance(x[0], x[1:], T)
    return float(np.max(np.abs(np.log(widths / widths[:, :1]) - np.stack([-law, law]))))


def fold_angle_error(mesh: Mesh, fold_angle: float) -> float:
    """Largest :func:`fold_angle_deviation` on the fold and seam edges of a tube mesh (degrees)."""
    sel = np.isin(mesh.edges_kind, ("fold", "seam"))
    return float(
        np.max(fold_angle_deviation(mesh.edges_foldAngle[sel], mesh.edges_kind[sel], fold_angle))
    )


def ruling_quad_planarity(state: State) -> float:
    """Largest :func:`quad_nonplanarity` of the ruling quads of a state's mesh."""
    mesh = state.mesh(faces="quads")
    return float(np.max(quad_nonplanarity(mesh.vertices_coords, mesh.faces_vertices)))


@dataclass(frozen=True)
class IsometryError:
    """How far a folded mesh is from its flat crease pattern.

    Attributes
    ----------
    max_edge_error : float
        Largest ``|length − flat length|`` over all edges, model units.
    max_relative_edge_error : float
        The same divided by the flat length.
    """

    max_edge_error: float
    max_relative_edge_error: float


def isometry_error(folded: Mesh, flat: Mesh) -> IsometryError:
    """Compare the edge lengths of two meshes of the same topology (a triangle mesh is
    isometric to another exactly when all its edges keep their lengths). NaN propagates."""
    lf, l0 = folded.edge_lengths(), flat.edge_lengths()
    diff = np.abs(lf - l0)
    return IsometryError(
        max_edge_error=float(np.max(diff)), max_relative_edge_error=float(np.max(diff / l0))
    )
