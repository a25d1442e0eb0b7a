"""Rigid planar panels: the discrete tubes, blocks and vaults (polyline creases, flat-foldable
vertices).

A panel lattice replaces the smooth lattice (Eq. 11) by its discrete form. Curve 1 is a
polyline x_0 … x_N with unit edge directions T_k (edge k from x_k to x_{k+1}, length h_k);
every vertex carries two fold-line vectors L_k, R_k with

    L_{k+1} − L_k ∥ T_k,   R_{k+1} − R_k ∥ T_k,

and the lattice polylines are ``x_k(u, v) = x_k + u L_k + v R_k``. Their edge k is
``(h_k + u μ^L_k + v μ^R_k) T_k`` with ``μ = (L_{k+1} − L_k)·T_k``: parallel to T_k, so every
quad between two lattice polylines is a trapezoid, planar in every state in which the
panels keep their shape, and a tube (curve 1 → 2 → 3 → 4 → 1 along +R, +L, −R, −L) closes
exactly. The speed factor ``1 + u μ^L/h + v μ^R/h`` is the discrete Eq. (17): a polyline is
valid where it stays positive on every edge (:attr:`PanelPattern.domain`).

The flat crease pattern and its folding are :mod:`curvefold.geometry._panel_pattern`'s
(:class:`~curvefold.geometry.PanelPattern`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Literal

import numpy as np

from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InputError, RegressionError
from ._curve import FramedCurve
from ._fold_angle import half_angle
from ._lattice import (
    Lattice,
    _example_lattice,  # noqa: F401  (the examples' lattice)
    check_anchor,
    check_curves,
    lattice_points,
)
from ._lattice_pattern import RegressionDomain, constant_alpha
from ._panel_pattern import PanelPattern
from ._topology import Topology

__all__ = ["MIN_SIDE", "PanelCrease", "PanelCurve", "PanelLattice", "check_sides"]

#: Shortest panel side a panel structure may have, as a fraction of the median side of its
#: kind (sides along the creases; left fold lines; right fold lines). Measured with the
#: smooth design's tubes at 4 … 64 panels: the paper's vault ≥ 0.078 of the median, the
#: atlas grid (a 0 … 1.2, p_xy 0.5 … 2, width 0.04 … 0.16) ≥ 0.0124 (its smooth margin
#: 0.011); the sliver a tube past the smooth count made (16 panels, tube 10) 0.0023.
MIN_SIDE = 0.01


def _median(values: np.ndarray) -> float:
    """Median of an array (np.median without its import of numpy.ma)."""
    flat = np.ravel(values)
    k = len(flat) // 2
    part = np.partition(flat, [k - 1, k] if len(flat) > 1 else [k])
    return float(part[k] if len(flat) % 2 else 0.5 * (part[k - 1] + part[k]))


def check_sides(
    pattern: PanelPattern, uv: np.ndarray, *, name: str = "cells", min_side: float = MIN_SIDE
) -> None:
    """Raise :class:`~curvefold.kernel.RegressionError` if a panel of the polylines uv (..., 2)
    has a side shorter than ``min_side`` × the median side of its kind (:data:`MIN_SIDE`).

    The kinds are the sides along the creases (edge k of polyline (u, v), ``h_k`` times
    its speed factor, which regression drives to 0) and the two families of fold lines
    (``|L_k|``, ``|R_k|``, which the width law shrinks). Each is measured against its own
    median, so that the panels' aspect, which the panel count sets (crease sides ∝ 1/N, fold
    lines the widths), is no sliver. The default, 1 %, admits every design whose smooth
    build clears regression by more than about 1 % (as N grows, the shortest crease side over
    the median tends to the smooth speed factor of the last tube: 0.077 for the paper's
    vault) and refuses the slivers of a tube past the smooth count (0.0023 of the median).

    Examples
    --------
    >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
    >>> panels = PanelLattice.from_lattice(lat, 4)
    >>> check_sides(panels.pattern, np.array([[1, 1], [14, 0]])) is None
    True
    >>> check_sides(panels.pattern, np.array([[1, 1], [14.14, 0]]))
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.RegressionError: cells: a panel side along lattice polyline (u, v) =
    (14.14, 0) on panel 4 of 4 is 0.0003 of the median of its kind, below min_side = 0.01 (a
    sliver panel)
    """
    uv = np.atleast_2d(np.asarray(uv, float)).reshape(-1, 2)
    n = pattern.panels
    crease = pattern.domain.factor(uv) * pattern.edge_lengths  # (M, N): edge k of each polyline
    folds = np.linalg.norm(np.stack([pattern.left, pattern.right]), axis=-1)  # (2, N + 1)
    ratios = crease / _median(crease), folds / np.array([[_median(f)] for f in folds])
    for family, ratio in enumerate(ratios):
        i, k = np.unravel_index(int(np.argmin(ratio)), ratio.shape)
        if not ratio[i, k] >= min_side:
            u, v = uv[i]
            where = (
                f"along lattice polyline (u, v) = ({u:g}, {v:g}) on panel {k + 1} of {n}"
                if family == 0
                else f"on the {('left', 'right')[i]} fold line at vertex {k} (of 0 … {n})"
            )
            raise RegressionError(
                f"{name}: a panel side {where} is {ratio[i, k]:.2g} of the median of its kind, "
                f"below min_side = {min_side:g} (a sliver panel)"
            )


@dataclass(frozen=True, eq=False)
class PanelCurve(FramedCurve, FrozenArrays):
    """Curve 1 of a panel lattice at one fold angle: a polyline with a frame at every vertex.

    Attributes
    ----------
    s : (N + 1,) ndarray
        Parameter of the vertices (:attr:`PanelPattern.s`).
    points : (N + 1, 3) ndarray
        The vertices x_k.
    frames : (N + 1, 3, 3) ndarray
        Vertex frames, columns t̃, ñ, b̃ (see the module notes).

    Examples
    --------
    >>> segment = PanelCurve(
    ...     np.array([0.0, 1.0]), np.array([[0.0, 0, 0], [1, 0, 0]]), np.stack([np.eye(3)] * 2)
    ... )  # one panel
    >>> segment.length, segment.tangent.tolist()
    (1.0, [[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    """

    s: np.ndarray
    points: np.ndarray
    frames: np.ndarray


@dataclass(frozen=True)
class PanelCrease:
    """Crease 1 of a panel lattice: its polyline and fold angle (a
    :class:`~curvefold.geometry.FoldedCrease`).

    Attributes
    ----------
    curve : PanelCurve
    fold_angle : float
        2α in degrees: the crease's dihedral angle is 180° − 2α along its whole length.

    Examples
    --------
    >>> from curvefold import Crease
    >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
    >>> panels = PanelLattice.from_lattice(lat, 4)
    >>> panels.crease.fold_angle, panels.crease.curve.points.shape, panels.crease.curve.length
    (90.0, (5, 3), 1.0)
    """

    curve: PanelCurve
    fold_angle: float


@dataclass(frozen=True, eq=False)
class PanelLattice(FrozenArrays):
    """A panel pattern folded at one angle and placed in space: the discrete :class:`Lattice`.

    Build it with :meth:`from_lattice`; fold it with :meth:`refold`. It is a
    :class:`~curvefold.geometry.StructureLattice`, so tubes, blocks and vaults are
    built on it with the same constructors, and their meshes are panels
    (:meth:`Topology.panels`).

    Attributes
    ----------
    pattern : PanelPattern
    alpha : float
        Half the fold angle, radians.
    rotation : (3, 3) ndarray
    translation : (3,) ndarray
        The placement: this state is ``rotation @ p + translation`` of the pattern's own
        placement ``p`` (:meth:`PanelPattern.fold`).
    source : Lattice or None
        The smooth lattice the panels sample, if any.

    Examples
    --------
    >>> from curvefold import Lattice
    >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
    >>> panels = PanelLattice.from_lattice(lat, 4)
    >>> (
    ...     panels.source is lat,
    ...     round(float(np.degrees(2 * panels.alpha)), 9),
    ...     panels.points(np.zeros(2)).shape,
    ... )
    (True, 90.0, (5, 3))
    """

    pattern: PanelPattern
    alpha: float
    rotation: np.ndarray
    translation: np.ndarray
    source: Lattice | None = None

    @classmethod
    def from_lattice(cls, lattice: Lattice, panels: int) -> PanelLattice:
        """The panel lattice of N panels sampling a smooth lattice, at its fold angle.

        It is placed so that its frame at vertex 0 is curve 1's frame at t = 0.

        Raises
        ------
        InputError
            For a panel count out of range, or too few panels for the crease's turns.
        RegressionError
            If a polyline of the unit cell passes the discrete regression limit.

        Examples
        --------
        >>> from curvefold import SpaceCurve, Crease, Lattice
        >>> smooth = Lattice.from_crease(
        ...     Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=33)), 0.1, 0.1
        ... )
        >>> PanelLattice.from_lattice(smooth, 8).points([[1, 1]]).shape
        (1, 9, 3)
        """
        if not isinstance(lattice, Lattice):
            raise InputError(f"lattice must be a Lattice, got {type(lattice).__name__}")
        pattern = PanelPattern.from_pattern(lattice.pattern, panels)
        a = float(constant_alpha(lattice.crease))
        points, _, _, frames = pattern.fold(np.array([a]))
        c = lattice.crease.curve
        R = c.frames[0] @ frames[0, 0].T
        panel = cls(pattern, a, R, c.points[0] - R @ points[0, 0], lattice)
        panel.check(np.array([[0, 1], [1, 0], [1, 1]]), name="widths")
        return panel

    # -- the placed state -------------------------------------------------------------------
    @cached_property
    def _state(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        points, left, right, frames = self.pattern.fold(np.array([self.alpha]))
        R = self.rotation
        placed = (points[0] @ R.T + self.translation, left[0] @ R.T, right[0] @ R.T, R @ frames[0])
        x, x_left, x_right, vertex_frames = (readonly(v) for v in placed)
        return x, x_left, x_right, vertex_frames

    @cached_property
    def crease(self) -> PanelCrease:
        """Crease 1 at this fold angle."""
        points, _, _, frames = self._state
        return PanelCrease(
            PanelCurve(self.pattern.s, points, frames), float(np.degrees(2 * self.alpha))
        )

    @property
    def left(self) -> np.ndarray:
        """Fold-line vectors L_k at this state, shape (N + 1, 3)."""
        return self._state[1]

    @property
    def right(self) -> np.ndarray:
        """Fold-line vectors R_k at this state, shape (N + 1, 3)."""
        return self._state[2]

    # -- what a structure asks of a lattice ---------------------------------------------------
    @property
    def s(self) -> np.ndarray:
        """Parameter of the vertices, shape (N + 1,)."""
        return self.pattern.s

    @property
    def t(self) -> np.ndarray:
        """Normalised parameter k / N of the vertices, shape (N + 1,)."""
        return (self.pattern.s - self.pattern.s[0]) / self.pattern.length

    @property
    def width_left(self) -> np.ndarray:
        """Distance of curve (1, 0) from curve 1's vertex tangent lines, shape (N + 1,)."""
        return self.pattern.widths[0]

    @property
    def width_right(self) -> np.ndarray:
        """Distance of curve (0, 1) from curve 1's vertex tangent lines, shape (N + 1,)."""
        return self.pattern.widths[1]

    @property
    def domain(self) -> RegressionDomain:
        """The discrete regression domain (:attr:`PanelPattern.domain`)."""
        return self.pattern.domain

    def points(self, uv: np.ndarray) -> np.ndarray:
        """Lattice polylines x_k + u L_k + v R_k for uv (..., 2); shape (..., N + 1, 3).

        Examples
        --------
        >>> from curvefold import Lattice
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> panels = PanelLattice.from_lattice(lat, 4)
        >>> (
        ...     panels.points(np.array([[1, 0], [1, 1]])).shape,
        ...     panels.points(np.zeros(2))[0].tolist(),
        ... )  # vertex 0 of curve 1 stays at the origin
        ((2, 5, 3), [0.0, 0.0, 0.0])
        """
        points, left, right, _ = self._state
        return lattice_points(points, left, right, uv)

    def check(self, uv: np.ndarray, *, name: str = "cells", min_side: float = MIN_SIDE) -> None:
        """Raise :class:`~curvefold.kernel.RegressionError` unless every polyline uv (..., 2) is
        valid (the discrete Eq. 17) and no panel between them is a sliver (:func:`check_sides`).

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> panels = PanelLattice.from_lattice(lat, 4)
        >>> panels.check(np.array([[1, 1]])) is None
        True
        >>> panels.check(np.array([[20, 0]]))
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.RegressionError: cells: lattice curve (u, v) = (20, 0) passes the
        curve of regression (Eq. 17 speed factor -0.414 ≤ 0, worst at t = 0.875, s = 0.875); along
        this direction the limit is (u, v) = (14.14, 0)
        """
        check_curves(self.domain, self.pattern.length, uv, name=name)
        check_sides(self.pattern, uv, name=name, min_side=min_side)

    def topology(
        self,
        cell_curves: np.ndarray,
        faces: str = "quads",
        *,
        keep: Sequence[np.ndarray] | None = None,
    ) -> Topology:
        """The panel mesh of cells (:meth:`Topology.panels`): one planar quad per panel, whatever
        ``faces`` asks.

        ``keep`` may only keep every vertex (as :func:`~curvefold.geometry.choose_sampling`
        does for panels): a mesh that left out a vertex would join two panels into one quad
        that is not planar.

        Raises
        ------
        InputError
            If ``keep`` leaves out a vertex of a tube.

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> panels = PanelLattice.from_lattice(lat, 4)
        >>> panels.topology(
        ...     np.array([[0, 1, 3, 2]]), "triangles"
        ... ).faces_vertices.shape  # quads all the same
        (16, 4)
        >>> panels.topology(np.array([[0, 1, 3, 2]]), keep=[[0, 4]])
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: keep: a panel mesh keeps every vertex of its polylines
        (5 per tube, 1 tubes); two panels joined into one quad are not planar
        """
        n = len(self.s)
        tubes = len(np.reshape(cell_curves, (-1, 4)))
        if keep is not None and (
            len(keep) != tubes or not all(np.array_equal(np.asarray(k), np.arange(n)) for k in keep)
        ):
            raise InputError(
                f"keep: a panel mesh keeps every vertex of its polylines ({n} per "
                f"tube, {tubes} tubes); two panels joined into one quad are not planar"
            )
        return Topology.panels(cell_curves, n)

    # -- what the consumers of a structure ask about its kind (curvefold.geometry._kinds) ---------
    @property
    def rigid(self) -> bool:
        """True: rigid planar panels, every state exact; the certificate counts their mechanism."""
        return True

    @property
    def thinnable(self) -> bool:
        """False: every vertex is a panel corner, which a mesh keeps."""
        return False

    @property
    def crease_degree(self) -> int:
        """1: the polylines are the creases."""
        return 1

    @property
    def smooth(self) -> Lattice | None:
        """The smooth lattice the panels sample (:attr:`source`), if any."""
        return self.source

    # -- rigid folding ----------------------------------------------------------------------------
    def _anchored(
        self, alphas: np.ndarray, anchor: str
    ) -> tuple[np.ndarray, np.ndarray, tuple[np.ndarray, ...]]:
        """Placements (A, 3, 3), (A, 3) of the states at α (A,) keeping this state's frame at the
        anchor vertex, and those states."""
        check_anchor(anchor)
        k = 0 if anchor == "start" else self.pattern.panels // 2
        states = self.pattern.fold(alphas)
        here_points, _, _, here_frames = self._state
        R = here_frames[k] @ np.swapaxes(states[3][:, k], -1, -2)
        shift = here_points[k] - np.einsum("aij,aj->ai", R, states[0][:, k])
        return R, shift, states

    def refold(
        self,
        fold_angle: float,
        *,
        degrees: bool = True,
        anchor: Literal["start", "middle"] = "start",
    ) -> PanelLattice:
        """The same panels rigidly folded to 2α ∈ [0°, 180°); the frame at the anchor vertex stays.

        Parameters
        ----------
        fold_angle : float
            2α, degrees by default; 0 is the flat crease pattern.
        anchor : {"start", "middle"}, keyword-only
            Vertex 0, or vertex N // 2.

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> panels = PanelLattice.from_lattice(lat, 4)
        >>> flat = panels.refold(0)
        >>> (
        ...     flat.crease.fold_angle,
        ...     round(float(np.abs(flat.points(np.array([[1, 1]]))[..., 2]).max()), 12),
        ... )
        (0.0, 0.0)
        """
        a = half_angle(fold_angle, degrees=degrees, allow_flat=True)
        R, shift, _ = self._anchored(np.array([a]), anchor)
        return PanelLattice(self.pattern, a, R[0], shift[0], self.source)

    def fold_points(
        self,
        uv: np.ndarray,
        fold_angles: np.ndarray,
        *,
        degrees: bool = True,
        anchor: Literal["start", "middle"] = "start",
    ) -> np.ndarray:
        """Lattice polylines uv (K, 2) at many fold angles at once, shape (A, K, N + 1, 3).

        Equivalent to ``[self.refold(f, anchor=anchor).points(uv) for f in fold_angles]``.

        Examples
        --------
        >>> from curvefold import Lattice
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> panels = PanelLattice.from_lattice(lat, 4)
        >>> frames = panels.fold_points(np.array([[1, 1]]), [0, 90])
        >>> (
        ...     frames.shape,
        ...     bool(np.allclose(frames[1], panels.points(np.array([[1, 1]])), atol=1e-12)),
        ... )
        ((2, 1, 5, 3), True)
        """
        alphas = np.array(
            [half_angle(f, degrees=degrees, allow_flat=True) for f in np.atleast_1d(fold_angles)]
        )
        R, shift, (points, left, right, _) = self._anchored(alphas, anchor)
        points, left, right = (np.einsum("aij,akj->aki", R, v) for v in (points, left, right))
        return lattice_points(points + shift[:, None], left, right, uv)

    def head(self, panels: int) -> PanelLattice:
        """The lattice of the first ``panels`` panels, in place (:meth:`PanelPattern.head`).

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> panels = PanelLattice.from_lattice(lat, 4)
        >>> head = panels.head(2)
        >>> (
        ...     head.points(np.zeros(2)).shape,
        ...     bool(
        ...         np.allclose(
        ...             head.points(np.zeros(2)), panels.points(np.zeros(2))[:3], atol=1e-12
        ...         )
        ...     ),
        ... )
        ((3, 3), True)
        """
        return PanelLattice(
            self.pattern.head(panels), self.alpha, self.rotation, self.translation, self.source
        )

    def moved(self, rotation: np.ndarray, translation: np.ndarray) -> PanelLattice:
        """This lattice moved rigidly: ``rotation @ x + translation`` of every point.

        Examples
        --------
        >>> lat = _example_lattice()  # a unit circle folded at 90°, 5 samples
        >>> panels = PanelLattice.from_lattice(lat, 4)
        >>> lifted = panels.moved(np.eye(3), [0, 0, 1])
        >>> (lifted.points(np.zeros(2)) - panels.points(np.zeros(2))).round(12)[0].tolist()
        [0.0, 0.0, 1.0]
        """
        R = np.asarray(rotation, float)
        return PanelLattice(
            self.pattern,
            self.alpha,
            R @ self.rotation,
            R @ self.translation + np.asarray(translation, float),
            self.source,
        )
