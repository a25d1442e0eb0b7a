"""What a structure asks of its lattice: the one interface of every kind of structure.

A :class:`~curvefold.geometry.Structure` is a thin object over a lattice: it says
which cells, and forwards the geometry to the lattice (its curves at one fold angle, their
rigid folding, the mesh it puts on them). Every kind of lattice satisfies
:class:`StructureLattice`, and answers there what the consumers of a structure need to know
about its kind: files, figures, the certificate and the mechanism analysis ask the lattice,
never its type. Two kinds exist:

* :class:`~curvefold.geometry.Lattice`: smooth lattice curves at dense samples (Eq. 11);
* :class:`~curvefold.geometry.PanelLattice`: the polylines of rigid planar panels.

A new kind (thick panels, say) is one more class that satisfies :class:`StructureLattice`
and :class:`FoldedCrease`; the writers, figures and the certificate take it as they are
(``tests/test_kinds.py`` builds, writes, draws and certifies a kind they have never seen).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Literal, Protocol, runtime_checkable

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    from ._curve import FramedCurve
    from ._lattice import Lattice
    from ._lattice_pattern import RegressionDomain
    from ._panels import PanelLattice
    from ._topology import Topology

__all__ = ["FoldedCrease", "StructureLattice"]


@runtime_checkable
class FoldedCrease(Protocol):
    """Crease 1 of a lattice at one fold angle, as the consumers of a structure read it.

    :class:`~curvefold.geometry.Crease` and
    :class:`~curvefold.geometry.PanelCrease` satisfy it.

    Examples
    --------
    >>> kinds = _example_kinds()  # smooth curves of 5 samples, and 4 panels
    >>> [
    ...     (isinstance(k.crease, FoldedCrease), k.crease.fold_angle, k.crease.curve.points.shape)
    ...     for k in kinds
    ... ]
    [(True, 90.0, (5, 3)), (True, 90.0, (5, 3))]
    """

    @property
    def curve(self) -> FramedCurve:
        """Curve 1: ``s`` (n,), ``points`` (n, 3) and ``frames`` (n, 3, 3) at its samples (or
        vertices)."""

    @property
    def fold_angle(self) -> float:
        """2α in degrees, the same all along the crease."""


@runtime_checkable
class StructureLattice(Protocol):
    """The lattice a structure stands on, of any kind.

    Its first part is what a :class:`~curvefold.geometry.Structure` asks of it
    (the curves at this fold angle, their folding and their mesh); its second part is what
    the consumers of a structure ask about its kind, named by what they mean.

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice
    >>> from curvefold.geometry import PanelLattice
    >>> curve = SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=33)
    >>> smooth = Lattice.from_crease(Crease.from_curve(curve), 0.1, 0.1)
    >>> panels = PanelLattice.from_lattice(smooth, 8)
    >>> [isinstance(k, StructureLattice) for k in (smooth, panels)]
    [True, True]
    >>> [(k.rigid, k.thinnable, k.crease_degree, k.smooth is smooth) for k in (smooth, panels)]
    [(False, True, 3, True), (True, False, 1, True)]
    """

    @property
    def crease(self) -> FoldedCrease:
        """Crease 1 at this fold angle."""

    @property
    def s(self) -> np.ndarray:
        """Parameter of the samples along curve 1, shape (n,)."""

    @property
    def t(self) -> np.ndarray:
        """Common curve parameter t ∈ [0, 1] of the samples, shape (n,)."""

    @property
    def width_left(self) -> np.ndarray:
        """w_L(t): distance of curve (1, 0) from curve 1's tangent lines, shape (n,)."""

    @property
    def width_right(self) -> np.ndarray:
        """w_R(t): distance of curve (0, 1) from curve 1's tangent lines, shape (n,)."""

    @property
    def domain(self) -> RegressionDomain:
        """The (u, v) of the lattice curves free of regression."""

    def points(self, uv: np.ndarray) -> np.ndarray:
        """The lattice curves uv (..., 2) at this fold angle, shape (..., n, 3).

        Examples
        --------
        >>> kinds = _example_kinds()  # smooth curves of 5 samples, and 4 panels
        >>> [k.points(np.array([[0, 0], [1, 1]])).shape for k in kinds]
        [(2, 5, 3), (2, 5, 3)]
        """

    def check(self, uv: np.ndarray, *, name: str = "cells") -> None:
        """Raise :class:`~curvefold.kernel.RegressionError` unless every curve uv (..., 2) is valid.

        Examples
        --------
        >>> kinds = _example_kinds()  # smooth curves of 5 samples, and 4 panels
        >>> [k.check(np.array([[1, 1]])) for k in kinds]
        [None, None]
        >>> [k.check(np.array([[20, 0]])) for k in kinds]  # past the curve of regression
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.RegressionError: cells: lattice curve (u, v) = (20, 0) passes the
        curve of regression (Eq. 17 speed factor -0.414 ≤ 0, worst at t = 0, s = 0); along this
        direction the limit is (u, v) = (14.14, 0)
        """

    def topology(
        self,
        cell_curves: np.ndarray,
        faces: Literal["triangles", "quads"] = "triangles",
        *,
        keep: Sequence[np.ndarray] | None = None,
    ) -> Topology:
        """The mesh of the cells whose corners 1–4 are the curves ``cell_curves`` (K, 4).

        Examples
        --------
        >>> kinds = _example_kinds()  # smooth curves of 5 samples, and 4 panels
        >>> cell = np.array([[0, 1, 3, 2]])
        >>> [k.topology(cell).faces_vertices.shape for k in kinds]  # triangles; planar panels
        [(32, 3), (16, 4)]
        """

    def refold(
        self,
        fold_angle: float,
        *,
        degrees: bool = True,
        anchor: Literal["start", "middle"] = "start",
    ) -> StructureLattice:
        """The same lattice rigidly folded to 2α ∈ [0°, 180°); 0 is the flat crease pattern.

        Examples
        --------
        >>> kinds = _example_kinds()  # smooth curves of 5 samples, and 4 panels
        >>> [(type(k.refold(60)).__name__, round(k.refold(60).crease.fold_angle, 9)) for k in kinds]
        [('Lattice', 60.0), ('PanelLattice', 60.0)]
        >>> flat = [k.refold(0).points(np.array([[1, 1]])) for k in kinds]
        >>> [round(float(np.abs(x[..., 2]).max()), 12) for x in flat]  # flat
        [0.0, 0.0]
        """

    def fold_points(
        self,
        uv: np.ndarray,
        fold_angles: np.ndarray,
        *,
        degrees: bool = True,
        anchor: Literal["start", "middle"] = "start",
    ) -> np.ndarray:
        """The curves uv (K, 2) at many fold angles (A,) at once, shape (A, K, n, 3).

        Examples
        --------
        >>> kinds = _example_kinds()  # smooth curves of 5 samples, and 4 panels
        >>> [k.fold_points(np.array([[1, 1]]), [0, 45, 90]).shape for k in kinds]
        [(3, 1, 5, 3), (3, 1, 5, 3)]
        >>> kinds[0].fold_points(np.array([[1, 1]]), [0]).shape  # one angle: still a leading axis
        (1, 1, 5, 3)
        >>> kinds[1].fold_points(np.array([[1, 1]]), np.array([-10]))
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: fold_angle must be in [0°, 180°), got -10
        """

    # -- what the consumers of a structure ask about its kind -----------------------------------
    @property
    def rigid(self) -> bool:
        """Whether it is made of rigid planar panels, every state its flat panels moved rigidly.

        Such a structure is exact by construction: the certificate holds it to checks whose
        tolerance is rounding and counts its mechanism
        (:func:`curvefold.analysis.certified_mechanism`, which cuts a tube too
        large for it with ``head(panels)``), and its files hold the states the mechanism is
        counted at (flat, half and full design angle). A structure that is not rigid is
        certified against its own sampling error instead, by checks that also read the
        smooth lattice's ``pattern`` and :class:`~curvefold.geometry.Crease`.
        """

    @property
    def thinnable(self) -> bool:
        """Whether a mesh may keep only some of its samples.

        True where the samples are dense samples of smooth curves
        (:func:`~curvefold.geometry.choose_sampling` thins them); False where every
        sample is a corner of the geometry (a panel's), which a mesh must keep.
        """

    @property
    def crease_degree(self) -> int:
        """Degree of the curves that model its creases through its samples.

        3 for smooth creases (a cubic through the samples), 1 where the polylines are the
        creases themselves.
        """

    @property
    def smooth(self) -> Lattice | None:
        """The smooth lattice it is, or samples; None if it samples none.

        Its smooth crease is the design's curve 1, which the certificate's crease checks
        measure.
        """


def _example_kinds() -> tuple[Lattice, PanelLattice]:
    """The lattices of the examples: a unit circle folded at 90° (5 samples, widths 0.1),
    smooth and as 4 rigid panels."""
    from ._lattice import _example_lattice
    from ._panels import PanelLattice

    smooth = _example_lattice()
    return smooth, PanelLattice.from_lattice(smooth, 4)
