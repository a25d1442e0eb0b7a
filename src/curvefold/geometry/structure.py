"""Tubes and cellular blocks: sets of lattice cells, their creases, meshes and folded states.

A cell (i, j) is the tube spanned by the lattice curves at its corners, in construction
order (the paper builds curve 1 → 2 along +r_R, 2 → 3 along +r_L, 3 → 4 along −r_R,
4 → 1 along −r_L):

    corner 1 = (i, j)   fold      corner 2 = (i, j+1)   seam
    corner 3 = (i+1, j+1) fold    corner 4 = (i+1, j)   seam

Each tube is made of two sheets, strips 4-1-2 around crease 1 and strips 2-3-4 around
crease 3, welded along the seams 2 and 4; tubes of a block are glued where they touch.
The mesh of a structure is therefore the union of its tube meshes: every tube is a closed
strip of four ruled strips with its own copy of the shared curves, exactly as it is built.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import Literal

import numpy as np

from ..kernel.errors import InputError
from .crease import half_angle
from .lattice import Lattice
from .mesh import Mesh

__all__ = ["Structure", "State", "CORNERS", "CORNER_KINDS"]

#: Offsets of a cell's corners 1–4 from its (i, j), in construction order.
CORNERS = np.array([[0, 0], [0, 1], [1, 1], [1, 0]])
#: Kind of crease at corners 1–4.
CORNER_KINDS = ("fold", "seam", "fold", "seam")


@dataclass(frozen=True, eq=False)
class Structure:
    """A set of lattice cells on one lattice: a tube, a cellular block or a vault's stack.

    Attributes
    ----------
    lattice : Lattice
    cells : (K, 2) ndarray of int
        Cell (i, j) spans [i, i+1] × [j, j+1] in (u, v).
    """

    lattice: Lattice
    cells: np.ndarray

    @classmethod
    def from_cells(cls, lattice: Lattice, cells: Sequence[Sequence[int]]) -> Structure:
        """A structure of the given cells, refused if any crease passes regression.

        Parameters
        ----------
        lattice : Lattice
        cells : sequence of (i, j) integer pairs
            Distinct cells; at least one.

        Examples
        --------
        >>> from curvefold import SpaceCurve, Crease, Lattice
        >>> lat = Lattice.from_crease(Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=33)), 0.1, 0.1)
        >>> Structure.tube(lat).curves_uv.tolist()
        [[0, 0], [0, 1], [1, 0], [1, 1]]
        """
        arr = np.asarray(cells)
        if arr.ndim != 2 or arr.shape[1] != 2 or len(arr) == 0:
            raise InputError(f"cells must be a non-empty list of (i, j) integer pairs, got shape {arr.shape}")
        if not np.issubdtype(arr.dtype, np.integer):
            if not np.all(np.isfinite(arr)) or not np.all(arr == np.round(arr)):
                raise InputError(f"cells must hold integers, got {cells!r}")
            arr = arr.astype(np.int64)
        if len(np.unique(arr, axis=0)) != len(arr):
            raise InputError("cells must be distinct; a cell is listed twice")
        arr = arr.astype(np.int64)
        arr.flags.writeable = False
        structure = cls(lattice, arr)
        lattice.check(structure.curves_uv, name="cells")
        return structure

    @classmethod
    def tube(cls, lattice: Lattice) -> Structure:
        """The tube of cell [0, 1]²."""
        return cls.from_cells(lattice, [(0, 0)])

    @classmethod
    def diagonal(cls, lattice: Lattice, count: int, *, direction: int = 1, layers: int = 1) -> Structure:
        """Tubes stacked along the lattice diagonal, curve 3 of one being curve 1 of the next.

        Parameters
        ----------
        count : int
            Number of tubes along the diagonal (≥ 1).
        direction : {1, -1}, keyword-only
            Stack from the base tube in +u +v or in −u −v.
        layers : int, keyword-only
            Number of parallel diagonals (a band): layer k holds cells (j, j + k).
        """
        if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 1:
            raise InputError(f"count (tubes) must be an integer ≥ 1, got {count!r}")
        if direction not in (1, -1):
            raise InputError(f"direction must be +1 or -1, got {direction!r}")
        if isinstance(layers, bool) or not isinstance(layers, (int, np.integer)) or layers < 1:
            raise InputError(f"layers must be an integer ≥ 1, got {layers!r}")
        j = np.arange(count) if direction == 1 else -np.arange(1, count + 1)
        cells = [(int(a), int(a) + k) for k in range(layers) for a in j]
        return cls.from_cells(lattice, cells)

    # -- topology --------------------------------------------------------------------------
    @cached_property
    def curves_uv(self) -> np.ndarray:
        """The distinct lattice curves at the cells' corners, shape (M, 2), sorted."""
        corners = (self.cells[:, None, :] + CORNERS[None]).reshape(-1, 2)
        return np.unique(corners, axis=0)

    @cached_property
    def cell_curves(self) -> np.ndarray:
        """Index into :attr:`curves_uv` of corners 1–4 of every cell, shape (K, 4)."""
        corners = self.cells[:, None, :] + CORNERS[None]
        lookup = {tuple(uv): i for i, uv in enumerate(self.curves_uv.tolist())}
        return np.array([[lookup[tuple(c)] for c in cell] for cell in corners.tolist()])

    @cached_property
    def curve_kinds(self) -> tuple[str, ...]:
        """For each curve: "fold" or "seam" in every cell it bounds, else "junction"."""
        kinds: list[set[str]] = [set() for _ in range(len(self.curves_uv))]
        for row in self.cell_curves:
            for c, kind in zip(row, CORNER_KINDS):
                kinds[c].add(kind)
        return tuple(k.pop() if len(k) == 1 else "junction" for k in kinds)

    def dihedral_angles(self, fold_angle: float, *, degrees: bool = True) -> np.ndarray:
        """Interior angle of every cell at corners 1–4, shape (K, 4): π − 2α, 2α, π − 2α, 2α."""
        a = half_angle(fold_angle, degrees=degrees, allow_flat=True)
        row = np.array([np.pi - 2 * a, 2 * a, np.pi - 2 * a, 2 * a])
        return np.broadcast_to(row, (len(self.cells), 4)).copy()

    @cached_property
    def _mesh_topology(self) -> dict[str, np.ndarray]:
        return _tube_mesh_topology(len(self.cells), len(self.lattice.s))

    # -- states ------------------------------------------------------------------------------
    def state(self, fold_angle: float | None = None, *, degrees: bool = True, anchor: Literal["start", "middle"] = "start") -> State:
        """The structure rigidly folded to 2α (default: the lattice's own fold angle).

        Parameters
        ----------
        fold_angle : float, optional
            2α ∈ [0°, 180°); 0 is the flat two-ply state (the crease pattern).
        anchor : {"start", "middle"}, keyword-only
            Which frame of curve 1 stays fixed: at t = 0, or at the middle sample.
        """
        lattice = self.lattice if fold_angle is None else self.lattice.refold(fold_angle, degrees=degrees, anchor=anchor)
        return State(self, lattice, lattice.points(self.curves_uv))


@dataclass(frozen=True, eq=False)
class State:
    """A structure at one fold angle.

    Attributes
    ----------
    structure : Structure
    lattice : Lattice
        The lattice at this fold angle.
    vertices : (M, n, 3) ndarray
        Every lattice curve of the structure (rows of ``structure.curves_uv``) at the samples.
    """

    structure: Structure
    lattice: Lattice
    vertices: np.ndarray

    @property
    def fold_angle(self) -> float:
        """2α in degrees."""
        return self.lattice.crease.fold_angle

    def mesh(self) -> Mesh:
        """The triangle mesh of all tubes at this state (FOLD arrays, fold angles measured)."""
        topo = self.structure._mesh_topology
        coords = self.vertices[self.structure.cell_curves].reshape(-1, 3)  # (K·4·n, 3)
        base = Mesh(
            vertices_coords=coords,
            edges_vertices=topo["edges_vertices"],
            edges_assignment=np.full(len(topo["edges_vertices"]), "F"),
            edges_foldAngle=np.zeros(len(topo["edges_vertices"])),
            faces_vertices=topo["faces_vertices"],
            edges_kind=topo["edges_kind"],
            faces_group=topo["faces_group"],
        )
        mesh = base.with_coords(coords)
        assignment = np.where(
            np.isin(mesh.edges_kind, ("fold", "seam")),
            np.where(mesh.edges_foldAngle > 0, "V", "M"),
            np.where(mesh.edges_kind == "boundary", "B", "F"),
        )
        return replace(mesh, edges_assignment=assignment)


def _tube_mesh_topology(cells: int, n: int) -> dict[str, np.ndarray]:
    """Faces and edges of ``cells`` closed tubes of 4 strips with n samples per curve.

    Vertex ``(k·4 + c)·n + j`` is sample j of corner c of tube k. Strip c of a tube runs
    from corner c to corner c+1 (mod 4); its faces are oriented consistently around the
    tube with their normals pointing out of it (checked in the tests).
    """
    j = np.arange(n - 1)
    faces, groups = [], []
    e_curve, e_rule, e_diag = [], [], []
    for k in range(cells):
        for c in range(4):
            a = (k * 4 + c) * n
            b = (k * 4 + (c + 1) % 4) * n
            faces.append(np.stack([a + j, b + j + 1, b + j], axis=1))
            faces.append(np.stack([a + j, a + j + 1, b + j + 1], axis=1))
            groups.append(np.full(2 * (n - 1), k * 4 + c))
            e_curve.append(np.stack([a + j, a + j + 1], axis=1))
            e_rule.append(np.stack([a + np.arange(n), b + np.arange(n)], axis=1))
            e_diag.append(np.stack([a + j, b + j + 1], axis=1))
    curve_edges = np.concatenate(e_curve)
    rule_edges = np.concatenate(e_rule)
    curve_kind = np.tile(np.repeat(np.array(CORNER_KINDS), n - 1), cells)
    rule_kind = np.where(np.tile(np.isin(np.arange(n), (0, n - 1)), 4 * cells), "boundary", "ruling")
    edges = np.concatenate([curve_edges, rule_edges, np.concatenate(e_diag)])
    kinds = np.concatenate([curve_kind, rule_kind, np.full(len(curve_edges), "diagonal")])
    return {
        "faces_vertices": np.concatenate(faces),
        "faces_group": np.concatenate(groups),
        "edges_vertices": edges,
        "edges_kind": kinds.astype("<U8"),
    }
