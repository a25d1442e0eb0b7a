"""Tubes and cellular blocks: sets of lattice cells, their creases, meshes and folded states.

A cell (i, j) is the tube spanned by the lattice curves at its corners, in construction
order (:mod:`curvefold.geometry._topology` owns the corner order, the crease kinds, the
strips, sheets and vertex numbering):

    corner 1 = (i, j)   fold      corner 2 = (i, j+1)   seam
    corner 3 = (i+1, j+1) fold    corner 4 = (i+1, j)   seam

Each tube is made of two sheets, strips 4-1-2 around crease 1 and strips 2-3-4 around
crease 3, welded along the seams 2 and 4; tubes of a block are glued where they touch.
The mesh of a structure is therefore the union of its tube meshes: every tube is a closed
strip of four ruled strips with its own copy of the shared curves, exactly as it is built.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Literal

import numpy as np

from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InputError
from ..kernel._validate import check_integer
from ._fold_angle import half_angle
from ._mesh import Mesh
from ._topology import (
    CORNER_KINDS,
    Topology,
    corner_members,
    lattice_corners,
    sample_index,
    thin_cells,
    unique_pairs,
)

if TYPE_CHECKING:  # pragma: no cover
    from ._kinds import StructureLattice

__all__ = ["Structure", "State", "check_structure", "drawable"]


@dataclass(frozen=True, eq=False)
class Structure(FrozenArrays):
    """A set of lattice cells on one lattice: a tube, a cellular block or a vault's stack.

    The structure says which cells; its lattice, of any kind
    (:class:`~curvefold.geometry.StructureLattice`: smooth lattice curves, or the
    polylines of rigid planar panels), does the geometry and answers what consumers ask
    about the kind.

    Attributes
    ----------
    lattice : StructureLattice
        A :class:`~curvefold.geometry.Lattice`, a
        :class:`~curvefold.geometry.PanelLattice`, or another kind.
    cells : (K, 2) ndarray of int
        Cell (i, j) spans [i, i+1] × [j, j+1] in (u, v).

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice
    >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
    >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
    >>> tube = Structure.tube(lat)
    >>> tube.cells.tolist(), tube.curve_kinds
    ([[0, 0]], ('fold', 'seam', 'seam', 'fold'))
    >>> Structure.from_cells(lat, [])
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: cells must be a non-empty list of (i, j) integer pairs, got
    shape (0,)
    """

    lattice: StructureLattice
    cells: np.ndarray

    @classmethod
    def from_cells(
        cls, lattice: StructureLattice, cells: Sequence[Sequence[int]] | np.ndarray
    ) -> Structure:
        """A structure of the given cells, refused if any crease passes regression.

        Parameters
        ----------
        lattice : StructureLattice
        cells : sequence of (i, j) integer pairs
            Distinct cells; at least one.

        Examples
        --------
        >>> from curvefold import SpaceCurve, Crease, Lattice
        >>> lat = Lattice.from_crease(
        ...     Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=33)), 0.1, 0.1
        ... )
        >>> Structure.tube(lat).curves_uv.tolist()
        [[0, 0], [0, 1], [1, 0], [1, 1]]
        """
        arr = np.asarray(cells)
        if arr.ndim != 2 or arr.shape[1] != 2 or len(arr) == 0:
            raise InputError(
                f"cells must be a non-empty list of (i, j) integer pairs, got shape {arr.shape}"
            )
        if not np.issubdtype(arr.dtype, np.integer):
            if not np.all(np.isfinite(arr)) or not np.all(arr == np.round(arr)):
                raise InputError(f"cells must hold integers, got {cells!r}")
            arr = arr.astype(np.int64)
        if len(unique_pairs(arr)[0]) != len(arr):
            raise InputError("cells must be distinct; a cell is listed twice")
        structure = cls(lattice, arr.astype(np.int64))
        lattice.check(structure.curves_uv, name="cells")
        return structure

    @classmethod
    def tube(cls, lattice: StructureLattice) -> Structure:
        """The tube of cell [0, 1]².

        Examples
        --------
        >>> from curvefold import SpaceCurve, Crease, Lattice
        >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
        >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
        >>> Structure.tube(lat).cells.tolist()
        [[0, 0]]
        """
        return cls.from_cells(lattice, [(0, 0)])

    @classmethod
    def diagonal(
        cls, lattice: StructureLattice, count: int, *, direction: int = 1, layers: int = 1
    ) -> Structure:
        """Tubes stacked along the lattice diagonal, curve 3 of one being curve 1 of the next.

        Parameters
        ----------
        count : int
            Number of tubes along the diagonal (≥ 1).
        direction : {1, -1}, keyword-only
            Stack from the base tube in +u +v or in −u −v.
        layers : int, keyword-only
            Number of parallel diagonals (a band): layer k holds cells (j, j + k).

        Examples
        --------
        >>> from curvefold import SpaceCurve, Crease, Lattice
        >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
        >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
        >>> (
        ...     Structure.diagonal(lat, 3).cells.tolist(),
        ...     Structure.diagonal(lat, 1, direction=-1).cells.tolist(),
        ... )
        ([[0, 0], [1, 1], [2, 2]], [[-1, -1]])
        >>> Structure.diagonal(lat, 0)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: count (tubes) must be an integer ≥ 1, got 0
        """
        count = check_integer(count, "count (tubes)", "[1, inf)")
        if direction not in (1, -1):
            raise InputError(f"direction must be +1 or -1, got {direction!r}")
        layers = check_integer(layers, "layers", "[1, inf)")
        j = np.arange(count) if direction == 1 else -np.arange(1, count + 1)
        cells = [(int(a), int(a) + k) for k in range(layers) for a in j]
        return cls.from_cells(lattice, cells)

    # -- topology --------------------------------------------------------------------------
    @cached_property
    def _corners(self) -> tuple[np.ndarray, np.ndarray]:
        return lattice_corners(self.cells)

    @property
    def curves_uv(self) -> np.ndarray:
        """The distinct lattice curves at the cells' corners, shape (M, 2), sorted, read-only."""
        return self._corners[0]

    @property
    def cell_curves(self) -> np.ndarray:
        """Index into :attr:`curves_uv` of corners 1–4 of every cell, shape (K, 4), read-only."""
        return self._corners[1]

    @property
    def regression_margin(self) -> float:
        """The smallest Eq. (17) speed factor of its lattice curves: > 0 when they are free of
        regression."""
        return float(self.lattice.domain.margin(self.curves_uv.astype(float)).min())

    @cached_property
    def curve_kinds(self) -> tuple[str, ...]:
        """For each curve: "fold" or "seam" in every cell it bounds, else "junction"."""
        kinds = (
            {CORNER_KINDS[c] for _, c in members}
            for members in corner_members(self.cell_curves, len(self.curves_uv))
        )
        return tuple(k.pop() if len(k) == 1 else "junction" for k in kinds)

    def dihedral_angles(self, fold_angle: float, *, degrees: bool = True) -> np.ndarray:
        """Interior angle of every cell at corners 1–4, shape (K, 4): π − 2α, 2α, π − 2α, 2α.

        Examples
        --------
        >>> from curvefold import SpaceCurve, Crease, Lattice
        >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
        >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
        >>> tube = Structure.tube(lat)
        >>> np.degrees(tube.dihedral_angles(60)).round(6).tolist()
        [[120.0, 60.0, 120.0, 60.0]]
        >>> np.degrees(tube.dihedral_angles(0)).round(6).tolist()  # flat: folds open, seams closed
        [[180.0, 0.0, 180.0, 0.0]]
        """
        a = half_angle(fold_angle, degrees=degrees, allow_flat=True)
        row = np.where(np.array(CORNER_KINDS) == "fold", np.pi - 2 * a, 2 * a)
        return np.broadcast_to(row, (len(self.cells), 4)).copy()

    def topology(
        self,
        faces: Literal["triangles", "quads"] = "triangles",
        *,
        keep: Sequence[np.ndarray] | None = None,
    ) -> Topology:
        """The mesh of the tubes and their sheets, as the lattice puts it on its curves.

        Parameters
        ----------
        faces : {"triangles", "quads"}
            On a smooth lattice (:meth:`Topology.tubes`), two triangles or one quad per
            ruling quad (planar only to O(h³), which the triangles' diagonals carry); both
            number the vertices alike. On a panel lattice every quad is a planar panel
            (:meth:`Topology.panels`), whatever ``faces`` asks.
        keep : sequence of (m_k,) array_like of int, optional, keyword-only
            The samples each tube's mesh keeps (e.g. ``Sampling.keep`` of
            :func:`curvefold.geometry.choose_sampling`); default every sample.
            A lattice that is not ``thinnable`` (panels) keeps every vertex: it refuses to
            be thinned.

        Examples
        --------
        >>> from curvefold import SpaceCurve, Crease, Lattice
        >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
        >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
        >>> tube = Structure.tube(lat)
        >>> tube.topology().faces_vertices.shape, tube.topology("quads").faces_vertices.shape
        ((32, 3), (16, 4))
        >>> [sheet.label for sheet in tube.topology().sheets]
        ['tube 1 · sheet A', 'tube 1 · sheet B']
        """
        if faces == "triangles" and keep is None:
            return self._triangles
        return self.lattice.topology(self.cell_curves, faces, keep=keep)

    @cached_property
    def _triangles(self) -> Topology:
        return self.lattice.topology(self.cell_curves, "triangles")

    # -- states ------------------------------------------------------------------------------
    def state(
        self,
        fold_angle: float | None = None,
        *,
        degrees: bool = True,
        anchor: Literal["start", "middle"] = "start",
    ) -> State:
        """The structure rigidly folded to 2α (default: the lattice's own fold angle).

        Parameters
        ----------
        fold_angle : float, optional
            2α ∈ [0°, 180°); 0 is the flat two-ply state (the crease pattern).
        anchor : {"start", "middle"}, keyword-only
            Which frame of curve 1 stays fixed: at t = 0, or at the middle sample.

        Examples
        --------
        >>> from curvefold import SpaceCurve, Crease, Lattice
        >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
        >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
        >>> tube = Structure.tube(lat)
        >>> (
        ...     tube.state().fold_angle,
        ...     round(tube.state(60).fold_angle, 9),
        ...     tube.state().vertices.shape,
        ... )
        (90.0, 60.0, (4, 5, 3))
        >>> float(np.abs(tube.state(0).vertices[..., 2]).max())  # 2α = 0: the flat crease pattern
        0.0
        >>> tube.state(180)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: fold_angle must be in [0°, 180°), got 180 (2α = 180°
        would need infinite curvature κ = κ_2D / cos α)
        """
        lattice = (
            self.lattice
            if fold_angle is None
            else self.lattice.refold(fold_angle, degrees=degrees, anchor=anchor)
        )
        return State(self, lattice, readonly(lattice.points(self.curves_uv)))


@dataclass(frozen=True, eq=False)
class State(FrozenArrays):
    """A structure at one fold angle.

    Attributes
    ----------
    structure : Structure
    lattice : StructureLattice
        The lattice at this fold angle.
    vertices : (M, n, 3) ndarray
        Every lattice curve of the structure (rows of ``structure.curves_uv``) at the
        samples, read-only.

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice
    >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
    >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
    >>> state = Structure.tube(lat).state(45)
    >>> round(state.fold_angle, 9), state.vertices.shape, state.vertices.flags.writeable
    (45.0, (4, 5, 3), False)
    """

    structure: Structure
    lattice: StructureLattice
    vertices: np.ndarray

    @property
    def fold_angle(self) -> float:
        """2α in degrees."""
        return self.lattice.crease.fold_angle

    def mesh(
        self,
        *,
        faces: Literal["triangles", "quads"] = "triangles",
        keep: Sequence[np.ndarray] | None = None,
    ) -> Mesh:
        """The mesh of all tubes at this state (FOLD arrays, fold angles measured).

        Parameters
        ----------
        faces : {"triangles", "quads"}, keyword-only
        keep : sequence of (m_k,) array_like of int, optional, keyword-only
            The faces and samples of :meth:`Structure.topology`.

        Examples
        --------
        >>> from curvefold import SpaceCurve, Crease, Lattice
        >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
        >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
        >>> state = Structure.tube(lat).state()
        >>> mesh = state.mesh()
        >>> (
        ...     mesh.vertices_coords.shape,
        ...     mesh.faces_vertices.shape,
        ...     sorted(set(mesh.edges_kind.tolist())),
        ... )
        ((20, 3), (32, 3), ['boundary', 'diagonal', 'fold', 'ruling', 'seam'])
        >>> float(
        ...     np.abs(Structure.tube(lat).state(0).mesh().vertices_coords[:, 2]).max()
        ... )  # the flat state
        0.0
        """
        return self.structure.topology(faces, keep=keep).mesh(self.vertices)


def check_structure(structure: Structure, *, name: str = "structure") -> Structure:
    """The structure given, refused unless it is a :class:`Structure`.

    Examples
    --------
    >>> check_structure("a tube")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: structure must be a Structure, got str
    """
    if not isinstance(structure, Structure):
        raise InputError(f"{name} must be a Structure, got {type(structure).__name__}")
    return structure


def drawable(
    structure: Structure, vertices: np.ndarray, *, segments: int, max_cells: int
) -> tuple[np.ndarray, np.ndarray, tuple[str, ...]]:
    """Thin a structure's curves for drawing.

    Parameters
    ----------
    structure : Structure
    vertices : (..., M, n, 3) ndarray
        Its curves (rows of ``structure.curves_uv``), at one or more fold angles.
    segments : int, keyword-only
        About this many segments along t are kept (ends and middle sample included).
    max_cells : int, keyword-only
        At most this many cells, evenly spread along the cell list.

    Returns
    -------
    curves : (..., M', k, 3) ndarray
        The curves of the kept cells, subsampled.
    cells : (K', 4) ndarray of int
        Rows of ``curves`` at corners 1–4 of the kept cells.
    kinds : tuple of str
        Kind of every kept curve.

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice
    >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
    >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
    >>> tube = Structure.tube(lat)
    >>> curves, cells, kinds = drawable(tube, tube.state().vertices, segments=2, max_cells=1)
    >>> curves.shape, cells.tolist(), kinds
    ((4, 3, 3), [[0, 1, 3, 2]], ('fold', 'seam', 'seam', 'fold'))
    """
    cells = thin_cells(structure.cell_curves, max_cells)
    # the cells' curves, in order
    used = np.flatnonzero(np.bincount(cells.ravel(), minlength=len(structure.curves_uv)))
    remap = np.full(len(structure.curves_uv), -1)
    remap[used] = np.arange(len(used))
    idx = sample_index(vertices.shape[-2], segments + 1)
    kinds = tuple(str(k) for k in np.asarray(structure.curve_kinds)[used])
    # one gather: a copy of what is kept alone
    return vertices[..., used[:, None], idx, :], remap[cells], kinds
