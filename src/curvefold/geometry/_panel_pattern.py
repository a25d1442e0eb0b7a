"""The flat crease pattern of rigid planar panels and its rigid folding (flat-foldable degree-4
vertices).

The lattice these panels make is :class:`~curvefold.geometry.PanelLattice` (the notation of
:mod:`curvefold.geometry._panels`).

The crease pattern (the flat state, :class:`PanelPattern`). At vertex k the crease turns by
φ_k; ``t_k`` is the vertex tangent, the bisector of T_{k−1} and T_k inside the crease. The
fold lines leave the vertex at the angle β_k from t_k on either side,
``l_k = cos β t + sin β n``, ``r_k = cos β t − sin β n`` (n the in-plane normal toward the
turn, where the smooth crease's N points): they are mirror images across the line of t_k
(the discrete β_L = β_R). The four sector angles are then β − φ/2, π − β − φ/2, π − β + φ/2,
β + φ/2: opposite ones sum to π, the vertex is flat-foldable (Kawasaki). Within panel k a
trapezoid has one height, ``|T_k × L_k| = |T_k × L_{k+1}|``, which fixes the fold-line
lengths from the first, ``ℓ_{k+1} = ℓ_k sin∠(T_k, l_k) / sin∠(T_k, l_{k+1})``: the discrete
width law (the trapezoid rule for ``d ln w_L = −κ_2D cot β ds``, second order). The end
vertices have no Kawasaki condition; their tangent t_0, t_N is chosen (the smooth crease's
tangent when sampling a smooth design), and virtual edges T_{−1}, T_N (T_0, T_{N−1} mirrored
across t_0, t_N) make every vertex a degree-4 vertex of the same form.

Folding (:func:`fold_line_angle`). At a flat-foldable degree-4 vertex the two crease edges
fold by the same angle and the two fold lines by opposite ones; with the crease folded by
2α (dihedral π − 2α, the smooth crease's),

    tan(ρ_R / 2) = −tan(ρ_L / 2) = sin(φ/2) / sin β · tan α

(spherical linkage of the sector angles above; checked against a numerical solve of the
vertex closure in the tests). So the fold angle 2α is the same along the whole crease in
every state, as in the smooth theory, and the fold lines turn by ``ρ ≈ κ_2D h tan α / sin β``,
the smooth surface's turn over a step (Eq. 19). Every panel's placement is its flat
placement moved by a rigid motion: the R panel k by ``G_0 ∘ … ∘ G_k``, where G_k turns
about the fold line through x_k along r_k by ρ_R,k (one prefix product of dual quaternions),
the L panel k by that and a turn of 2α about the edge T_k. The lattice vectors of the
folded state are the panels' images of the flat ones; that the L panels so placed agree on
their shared fold lines is the vertex closure, which the tests measure at rounding level
with every panel's four sides and two diagonals. 2α = 0 gives the flat pattern exactly.

Vertex frames: ``t̃_k ∝ T_{k−1} + T_k``, ``ñ_k ∝ l̂_k − r̂_k``, ``b̃ = t̃ × ñ``. The two are
orthogonal in every state (the sector angles make (l̂ − r̂)·T_k = −(l̂ − r̂)·T_{k−1}), and they
approach the smooth crease's T, N, B at second order. A state is placed by the frame at one
vertex (its "anchor"), as a smooth lattice is by its frame at one sample.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InputError
from ..kernel._lie import cross, dual_to_motion, exp_dual, prefix_dual
from ..kernel._validate import Spec
from ._curve import SpaceCurve
from ._lattice import _example_lattice  # noqa: F401  (the examples')
from ._lattice_pattern import Pattern, RegressionDomain

__all__ = ["MAX_PANELS", "PANELS", "PanelPattern", "check_panels", "fold_line_angle"]

#: Most panels along a crease.
MAX_PANELS = 100_000
#: The ``panels`` parameter of a design (0: the smooth structure).
PANELS = Spec(
    "panels",
    "integer",
    0,
    f"[0, {MAX_PANELS}]",
    help="rigid planar panels along each crease (polyline creases, exactly planar panels); 0 "
    "builds the smooth curved creases",
    why="memory bound",
    typical="[0, 64]",
    label="rigid panels per crease",
)
#: Integration steps of the flat crease sampled by :meth:`PanelPattern.from_pattern` (at least).
FLAT_STEPS = 2048


def fold_line_angle(turning: np.ndarray, beta: np.ndarray, alpha: np.ndarray) -> np.ndarray:
    """Fold angle ρ_R of the right fold line at a flat-foldable vertex (ρ_L = −ρ_R), radians.

    ``tan(ρ_R / 2) = sin(φ/2) / sin β · tan α`` for a crease folded by 2α, turning by φ at the
    vertex, with fold lines at β from the vertex tangent (arrays broadcast).

    Examples
    --------
    A straight crease (φ = 0) folds without folding its fold lines:

    >>> float(fold_line_angle(0.0, 1.2, 0.7))
    0.0
    """
    return 2.0 * np.arctan(np.sin(0.5 * np.asarray(turning)) / np.sin(beta) * np.tan(alpha))


def _cross2(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _turn(v: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """2D vectors (..., 2) turned counter-clockwise by angle (...)."""
    c, s = np.cos(angle)[..., None], np.sin(angle)[..., None]
    return np.concatenate(
        [c * v[..., :1] - s * v[..., 1:], s * v[..., :1] + c * v[..., 1:]], axis=-1
    )


def _lift(v: np.ndarray) -> np.ndarray:
    """2D vectors (..., 2) in the plane z = 0, shape (..., 3)."""
    return np.concatenate([v, np.zeros(v.shape[:-1] + (1,))], axis=-1)


def _mirror(v: np.ndarray, axis: np.ndarray) -> np.ndarray:
    """2D vector v mirrored across the line of the unit vector axis."""
    return 2.0 * (v @ axis) * axis - v


def _angle(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Signed angle from 2D vectors a to b (...), in (−π, π]."""
    return np.arctan2(_cross2(a, b), np.einsum("...i,...i->...", a, b))


def _turning(T: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Turn φ_k at every vertex from the unit edges T (N, 2) and vertex tangents t (N + 1, 2).

    Inside, from edge k − 1 to edge k; at the ends twice the angle between the tangent and
    the end edge (the turn to the virtual edge mirrored across the tangent), so that an end
    edge leaving the tangent by more than 90° shows as a turn of more than 180°.
    """
    return np.concatenate(
        [2 * _angle(t[:1], T[:1]), _angle(T[:-1], T[1:]), 2 * _angle(T[-1:], t[-1:])]
    )


def check_panels(panels: int, *, name: str = "panels") -> int:
    """A panel count for a panel lattice: an integer in [1, MAX_PANELS].

    Examples
    --------
    >>> check_panels(4)
    4
    >>> check_panels(0)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: panels must be ≥ 1 for a panel lattice (0 is the smooth
    structure), got 0
    """
    n = PANELS.check(panels, name)
    if n < 1:
        raise InputError(
            f"{name} must be ≥ 1 for a panel lattice (0 is the smooth structure), got {n}"
        )
    return n


@dataclass(frozen=True, eq=False)
class PanelPattern(FrozenArrays):
    """The flat crease pattern of a panel lattice: everything rigid folding keeps.

    Build it with :meth:`from_pattern` (sampling a smooth design) or :meth:`from_polyline`.
    Coordinates are in the plane of the pattern, model units; arrays are read-only.

    Attributes
    ----------
    s : (N + 1,) ndarray
        Parameter of the vertices: arc length along the smooth crease they sample.
    points : (N + 1, 2) ndarray
        Crease 1, x_k.
    tangents : (N + 1, 2) ndarray
        Unit vertex tangents t_k (inside: the bisector of the two crease edges).
    beta : (N + 1,) ndarray
        Angle β_k of both fold lines from t_k, radians.
    left, right : (N + 1, 2) ndarray
        Fold-line vectors L_k (toward the crease's turn) and R_k.

    Examples
    --------
    >>> from curvefold import Crease
    >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
    >>> pattern = PanelPattern.from_pattern(lat.pattern, 4)
    >>> pattern.panels, pattern.s.tolist(), pattern.points.shape
    (4, [0.0, 0.25, 0.5, 0.75, 1.0], (5, 2))
    """

    s: np.ndarray
    points: np.ndarray
    tangents: np.ndarray
    beta: np.ndarray
    left: np.ndarray
    right: np.ndarray

    @classmethod
    def from_polyline(
        cls,
        s: np.ndarray,
        points: np.ndarray,
        beta: np.ndarray,
        *,
        start_tangent: np.ndarray,
        end_tangent: np.ndarray,
        left_length: float,
        right_length: float,
    ) -> PanelPattern:
        """The pattern of a flat polyline crease with fold lines at β_k from the vertex tangents.

        Parameters
        ----------
        s : (N + 1,) array_like
            Increasing parameter of the vertices (arc length of the crease they sample).
        points : (N + 1, 2) array_like
            The crease, N ≥ 1 (the left fold lines go to the left of it, toward +n).
        beta : (N + 1,) array_like
            Fold-line angles in (0, π), radians.
        start_tangent, end_tangent : (2,) array_like, keyword-only
            Tangents t_0, t_N of the end vertices (the inner ones are the bisectors).
        left_length, right_length : float, keyword-only
            ``|L_0|, |R_0| > 0``; the others follow from the trapezoids' heights.

        Raises
        ------
        InputError
            For a malformed polyline, or a vertex whose fold lines would cross the crease
            (a sector angle ≤ 0: too few panels for the crease's turn there).

        Examples
        --------
        A straight crease (no turn) with fold lines normal to it:

        >>> p = PanelPattern.from_polyline(
        ...     [0, 1, 2],
        ...     [[0, 0], [1, 0], [2, 0]],
        ...     [np.pi / 2] * 3,
        ...     start_tangent=[1, 0],
        ...     end_tangent=[1, 0],
        ...     left_length=0.1,
        ...     right_length=0.2,
        ... )
        >>> p.left.round(6).tolist(), p.right.round(6).tolist()
        ([[0.0, 0.1], [0.0, 0.1], [0.0, 0.1]], [[0.0, -0.2], [0.0, -0.2], [0.0, -0.2]])
        >>> PanelPattern.from_polyline(
        ...     [0, 1],
        ...     [[0, 0], [0, 0]],
        ...     [1, 1],
        ...     start_tangent=[1, 0],
        ...     end_tangent=[1, 0],
        ...     left_length=0.1,
        ...     right_length=0.2,
        ... )
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: panel crease: vertices 0 and 1 coincide
        """
        s = np.asarray(s, float)
        x = np.asarray(points, float)
        beta = np.asarray(beta, float)
        if (
            x.ndim != 2
            or x.shape[1] != 2
            or len(x) < 2
            or s.shape != (len(x),)
            or beta.shape != s.shape
        ):
            raise InputError(
                "a panel crease needs N + 1 ≥ 2 points (N + 1, 2) with one s and "
                f"one beta each, got shapes {x.shape}, {s.shape}, {beta.shape}"
            )
        if not all(np.isfinite(a).all() for a in (s, x, beta)) or not (np.diff(s) > 0).all():
            raise InputError("a panel crease needs finite points and beta, and increasing s")
        chords = np.diff(x, axis=0)
        h = np.linalg.norm(chords, axis=1)
        if not (h > 0).all():
            raise InputError(
                f"panel crease: vertices {int(np.argmin(h))} and {int(np.argmin(h)) + 1} coincide"
            )
        T = chords / h[:, None]
        t = np.concatenate(
            [
                _unit(np.asarray(start_tangent, float))[None],
                _unit(T[:-1] + T[1:]),
                _unit(np.asarray(end_tangent, float))[None],
            ]
        )
        turning = _turning(T, t)
        bad = np.flatnonzero(~((np.abs(turning) / 2 < beta) & (beta < np.pi - np.abs(turning) / 2)))
        if bad.size:
            k = int(bad[0])
            raise InputError(
                f"too few panels: at vertex {k} (s = {s[k]:.6g}) the crease turns by "
                f"{np.degrees(turning[k]):.4g}° and its fold lines leave at "
                f"{np.degrees(beta[k]):.4g}°; they would cross the crease (need |turn|/2 < "
                "beta < 180° − |turn|/2)",
                parameter="panels",
            )
        normal = _turn(t, np.full(len(t), 0.5 * np.pi))
        lhat = np.cos(beta)[:, None] * t + np.sin(beta)[:, None] * normal
        rhat = np.cos(beta)[:, None] * t - np.sin(beta)[:, None] * normal
        lengths = []
        for name, first, hat in (
            ("left_length", left_length, lhat),
            ("right_length", right_length, rhat),
        ):
            if not (np.isfinite(first) and first > 0):
                raise InputError(f"{name} must be a finite number > 0, got {first!r}")
            # equal heights of trapezoid k at both ends: ℓ_{k+1} |T_k × l_{k+1}| = ℓ_k |T_k × l_k|
            ratio = _cross2(T, hat[:-1]) / _cross2(T, hat[1:])
            lengths.append(float(first) * np.concatenate([[1.0], np.cumprod(ratio)]))
        return cls(s, x, t, beta, lengths[0][:, None] * lhat, lengths[1][:, None] * rhat)

    @classmethod
    def from_pattern(cls, pattern: Pattern, panels: int) -> PanelPattern:
        """Sample a smooth crease pattern (κ_2D, β, widths at s = 0) with N panels.

        The vertices are the flat smooth crease at ``s_k = k L / N``; the fold lines leave
        them at β(s_k) from the vertex tangents (the smooth crease's tangent at the ends),
        with lengths from w_L(0), w_R(0) and the discrete width law. Vertex positions of the
        folded states then approach the smooth ones at second order in 1/N (measured in
        the tests).

        Parameters
        ----------
        pattern : Pattern
        panels : int
            N ≥ 1.

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> PanelPattern.from_pattern(lat.pattern, 2).s.tolist()
        [0.0, 0.5, 1.0]
        >>> PanelPattern.from_pattern(lat.pattern, 0)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: panels must be ≥ 1 for a panel lattice (0 is the smooth
        structure), got 0
        """
        n = check_panels(panels)
        m = -(-FLAT_STEPS // n)
        flat = SpaceCurve.from_curvature(pattern.kappa_2d, 0.0, pattern.length, samples=m * n + 1)
        s = flat.s[::m]
        turn = np.diff(np.unwrap(np.arctan2(flat.tangent[:, 1], flat.tangent[:, 0]))[::m])
        if not (np.abs(turn) < 0.5 * np.pi).all():
            k = int(np.argmax(np.abs(turn)))
            raise InputError(
                f"too few panels: the crease turns by {np.degrees(turn[k]):.4g}° "
                f"over panel {k} (s = {s[k]:.6g} to {s[k + 1]:.6g}); use more panels (below "
                "90° each)",
                parameter="panels",
            )
        ends = flat.tangent[[0, -1], :2]
        return cls.from_polyline(
            s,
            flat.points[::m, :2],
            pattern.beta(s),
            start_tangent=ends[0],
            end_tangent=ends[1],
            left_length=float(pattern.ruling_lengths[0][0]),
            right_length=float(pattern.ruling_lengths[1][0]),
        )

    # -- derived, fold-invariant ---------------------------------------------------------
    @property
    def panels(self) -> int:
        """N, the number of panels along each crease."""
        return len(self.s) - 1

    @property
    def length(self) -> float:
        """Parameter length s_N − s_0."""
        return float(self.s[-1] - self.s[0])

    @cached_property
    def edge_lengths(self) -> np.ndarray:
        """h_k, shape (N,)."""
        return readonly(np.linalg.norm(np.diff(self.points, axis=0), axis=1))

    @cached_property
    def chords(self) -> np.ndarray:
        """Unit edge directions T_{−1}, T_0 … T_{N−1}, T_N (the two ends virtual), shape (N + 2,
        2)."""
        T = np.diff(self.points, axis=0) / self.edge_lengths[:, None]
        t = self.tangents
        return readonly(np.concatenate([_mirror(T[0], t[0])[None], T, _mirror(T[-1], t[-1])[None]]))

    @cached_property
    def turning(self) -> np.ndarray:
        """φ_k, the turn of the crease at every vertex (virtual edges at the ends), shape (N +
        1,)."""
        return readonly(_turning(self.chords[1:-1], self.tangents))

    @cached_property
    def domain(self) -> RegressionDomain:
        """The valid (u, v): ``1 − u a_k − v b_k > 0`` on every edge, ``a = −μ^L/h``, ``b =
        −μ^R/h``.

        ``t`` holds the edges' midpoints in the normalised parameter.
        """
        T = self.chords[1:-1]
        h = self.edge_lengths
        a = -np.einsum("ij,ij->i", np.diff(self.left, axis=0), T) / h
        b = -np.einsum("ij,ij->i", np.diff(self.right, axis=0), T) / h
        t = (self.s - self.s[0]) / self.length
        return RegressionDomain(0.5 * (t[:-1] + t[1:]), a, b)

    @cached_property
    def widths(self) -> tuple[np.ndarray, np.ndarray]:
        """Distances of x_k + L_k and x_k + R_k from the vertex tangent lines, each (N + 1,)."""
        return readonly(np.abs(_cross2(self.tangents, self.left))), readonly(
            np.abs(_cross2(self.tangents, self.right))
        )

    def head(self, panels: int) -> PanelPattern:
        """The pattern of the first ``panels`` panels (1 ≤ panels ≤ N).

        Its last vertex keeps its tangent, the bisector of the crease edges there, so the
        virtual edge after it is the edge it leaves out: it folds exactly as the first
        panels of this pattern do.

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> pattern = PanelPattern.from_pattern(lat.pattern, 4)
        >>> pattern.head(1).s.tolist()
        [0.0, 0.25]
        >>> pattern.head(0)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: panels must be in [1, 4] for the head of this pattern,
        got 0
        """
        k = int(panels) + 1
        if not 2 <= k <= len(self.s):
            raise InputError(
                f"panels must be in [1, {self.panels}] for the head of this pattern, got {panels!r}"
            )
        return PanelPattern(
            self.s[:k],
            self.points[:k],
            self.tangents[:k],
            self.beta[:k],
            self.left[:k],
            self.right[:k],
        )

    def fold(self, alphas: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The folded states at half fold angles α (A,), in the pattern's own placement.

        The pattern lies in z = 0 and the virtual R panel before vertex 0 stays there.

        Returns
        -------
        points, left, right : (A, N + 1, 3) ndarray
            x_k, L_k, R_k.
        frames : (A, N + 1, 3, 3) ndarray
            Vertex frames, columns t̃, ñ, b̃.

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> pattern = PanelPattern.from_pattern(lat.pattern, 4)
        >>> points, left, right, frames = pattern.fold(np.array([0.0, np.pi / 4]))
        >>> (
        ...     points.shape,
        ...     frames.shape,
        ...     float(np.abs(points[0, :, 2]).max()),
        ... )  # α = 0: the flat pattern
        ((2, 5, 3), (2, 5, 3, 3), 0.0)
        """
        a = np.asarray(alphas, float).reshape(-1, 1)
        A = len(a)
        x = _lift(self.points)
        rhat = _lift(self.right / np.linalg.norm(self.right, axis=1, keepdims=True))
        # (A, N + 1, 3): ρ_R along r
        w = fold_line_angle(self.turning, self.beta, a)[..., None] * rhat
        twist = np.concatenate([w, -cross(w, np.broadcast_to(x, w.shape))], axis=-1)
        # R panels 0 … N
        R, shift = dual_to_motion(prefix_dual(exp_dual(tuple(np.moveaxis(twist, -1, 0)))))
        chords = _lift(self.chords)
        T = np.concatenate(
            [np.broadcast_to(chords[0], (A, 1, 3)), np.einsum("akij,kj->aki", R, chords[1:])],
            axis=1,
        )
        points = np.einsum("akij,kj->aki", R, x) + shift
        right = np.einsum("akij,kj->aki", R, _lift(self.right))
        # L panel k: the R panel k turned by 2α about T_k (Rodrigues, flat vectors)
        Tk, Lk = chords[1:], _lift(self.left)
        along = np.einsum("kj,kj->k", Lk, Tk)[:, None] * Tk
        c2, s2 = np.cos(2 * a)[..., None], np.sin(2 * a)[..., None]
        left = np.einsum("akij,akj->aki", R, along + c2 * (Lk - along) + s2 * cross(Tk, Lk))
        t = _unit(T[:, :-1] + T[:, 1:])
        d = _unit(left) - _unit(right)
        n = _unit(d - np.einsum("aki,aki->ak", d, t)[..., None] * t)
        return points, left, right, np.stack([t, n, cross(t, n)], axis=-1)
