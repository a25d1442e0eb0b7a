"""Topology: the one owner of corner order, strips, sheets, vertex numbering and M/V/B/F.

A cell (i, j) of the lattice is a tube whose corners 1–4 are the lattice curves
(i, j), (i, j+1), (i+1, j+1), (i+1, j) (:data:`CORNERS`), in the paper's construction
order: curve 1 → 2 along +r_R, 2 → 3 along +r_L, 3 → 4 along −r_R, 4 → 1 along −r_L.
Strip c of a tube runs from corner c to corner c + 1 (mod 4). From the corner order
follow, and are derived here rather than restated:

* the quadrant of every corner (the signs of r_L and r_R along its two strips,
  :data:`CORNER_QUADRANTS`) and hence its kind (:data:`CORNER_KINDS`): a fold where both
  signs agree (interior angle π − 2α), a seam where they differ (2α);
* the sheets (:data:`SHEETS`): each tube is two sheets, strips 4→1, 1→2 around fold
  crease 1 (sheet A) and strips 2→3, 3→4 around fold crease 3 (sheet B), welded along the
  seams 2 and 4; seam 2 of tube k has id 2k, seam 4 has id 2k + 1.

A :class:`Topology` is the mesh that a structure's lattice curves are put on: which
lattice curve and sample every vertex is, the faces and edges with their kinds, the face
groups, the seam ids and the sheets with their vertex maps. Writers, sheets and
measurements read it; nobody recomputes it. :meth:`Topology.tubes` builds the tube mesh
(4 ruled strips per tube, triangles or planar-to-O(h³) quads); :meth:`Topology.panels`
the mesh of rigid planar panels (:mod:`curvefold.geometry._panels`), the same value.

The single rule for FOLD assignments is :func:`fold_assignment`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Literal

import numpy as np

from ..kernel._arrays import FrozenArrays, distinct, readonly
from ..kernel._errors import InputError, InternalError
from ._mesh import CREASE_KINDS, Mesh, edges_faces, fold_angles

__all__ = [
    "unique_pairs",
    "CORNERS",
    "CORNER_QUADRANTS",
    "CORNER_KINDS",
    "STRIPS",
    "SHEETS",
    "quadrant_kind",
    "quadrant_name",
    "seam_id",
    "fold_assignment",
    "lattice_corners",
    "corner_members",
    "SheetTopology",
    "Topology",
    "is_tube_numbering",
    "sample_index",
    "tube_strips",
    "thin_cells",
]

#: Offsets of a cell's corners 1–4 from its (i, j), in construction order.
CORNERS = readonly(np.array([[0, 0], [0, 1], [1, 1], [1, 0]]))
#: Strip c runs from corner c to corner c + 1 (0-based corner indices).
STRIPS = tuple((c, (c + 1) % 4) for c in range(4))


def quadrant_kind(sign_left: int, sign_right: int) -> str:
    """Kind of the crease between strips along ``sign_left · r_L`` and ``sign_right · r_R``.

    ``"fold"`` when the signs agree (interior angle π − 2α), ``"seam"`` when they differ (2α).

    Examples
    --------
    >>> quadrant_kind(1, 1), quadrant_kind(-1, -1), quadrant_kind(-1, 1)
    ('fold', 'fold', 'seam')
    """
    return "fold" if sign_left == sign_right else "seam"


def _corner_signs(c: int) -> tuple[int, int]:
    """Signs of the steps in u (along r_L) and v (along r_R) from corner c to its neighbours."""
    steps = CORNERS[[(c - 1) % 4, (c + 1) % 4]] - CORNERS[c]  # one step in u, one in v
    return int(steps[:, 0].sum()), int(steps[:, 1].sum())


def quadrant_name(sign_left: int, sign_right: int) -> str:
    """``"L+R-"`` for rulings ``+r_L`` and ``−r_R``.

    Examples
    --------
    >>> quadrant_name(1, -1), quadrant_name(-1, -1)
    ('L+R-', 'L-R-')
    """
    return f"L{'+' if sign_left > 0 else '-'}R{'+' if sign_right > 0 else '-'}"


#: Quadrant of the crease at corners 1–4 (see :data:`curvefold.geometry._crease.QUADRANTS`).
CORNER_QUADRANTS = tuple(quadrant_name(*_corner_signs(c)) for c in range(4))
#: Kind of crease at corners 1–4: ("fold", "seam", "fold", "seam").
CORNER_KINDS = tuple(quadrant_kind(*_corner_signs(c)) for c in range(4))
#: The two sheets of a tube: name and strips, the strips in order across the sheet.
SHEETS = (("A", (3, 0)), ("B", (1, 2)))
#: Seam corners in id order.
_SEAMS = tuple(c for c in range(4) if CORNER_KINDS[c] == "seam")
_SEAM_INDEX = np.array([_SEAMS.index(c) if c in _SEAMS else -1 for c in range(4)])


def seam_id(tube: np.ndarray | int, corner: np.ndarray | int) -> np.ndarray:
    """Id of the seam at 0-based corner 1 or 3 of a tube: 2·tube, 2·tube + 1 (arrays broadcast).

    Examples
    --------
    >>> seam_id(np.array([0, 0, 4]), np.array([1, 3, 1])).tolist()
    [0, 1, 8]
    """
    return len(_SEAMS) * np.asarray(tube) + _SEAM_INDEX[corner]


def fold_assignment(
    edges_kind: np.ndarray, edges_foldAngle: np.ndarray, *, seams_open: bool = False
) -> np.ndarray:
    """FOLD assignment of every edge from its kind and fold angle: the one rule.

    ``B`` on boundaries, and on seams cut open (``seams_open``: a sheet, where each seam
    edge borders one face); ``F`` on rulings and diagonals; on folds and closed seams
    ``V`` where the fold angle is positive (FOLD sign: valley positive), ``M`` where it is
    negative and ``F`` where it is 0 (an unfolded crease).

    Parameters
    ----------
    edges_kind : (E,) array of str
    edges_foldAngle : (E,) array of float
        Degrees, valley positive.
    seams_open : bool, keyword-only

    Returns
    -------
    (E,) ndarray of str

    Examples
    --------
    >>> kind = np.array(["fold", "fold", "seam", "boundary", "ruling"])
    >>> fold_assignment(kind, np.array([30.0, -2.0, -150.0, 0.0, 0.0])).tolist()
    ['V', 'M', 'M', 'B', 'F']
    >>> fold_assignment(kind, np.array([30.0, -2.0, -150.0, 0.0, 0.0]), seams_open=True).tolist()
    ['V', 'M', 'B', 'B', 'F']
    """
    kind = np.asarray(edges_kind)
    angle = np.asarray(edges_foldAngle, float)
    boundary = (kind == "boundary") | ((kind == "seam") & seams_open)
    crease = np.where(angle > 0, "V", np.where(angle < 0, "M", "F"))
    return np.where(boundary, "B", np.where(np.isin(kind, CREASE_KINDS), crease, "F")).astype("<U1")


def lattice_corners(cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The distinct lattice curves at the corners of cells, and each cell's corners among them.

    Parameters
    ----------
    cells : (K, 2) ndarray of int

    Returns
    -------
    curves_uv : (M, 2) ndarray of int
        Sorted, read-only.
    cell_curves : (K, 4) ndarray of int
        Row of ``curves_uv`` at corners 1–4 of every cell, read-only.

    Examples
    --------
    >>> uv, rows = lattice_corners(np.array([[0, 0], [1, 1]]))
    >>> rows.tolist()
    [[0, 1, 3, 2], [3, 4, 6, 5]]
    """
    corners = (np.asarray(cells)[:, None, :] + CORNERS[None]).reshape(-1, 2)
    curves_uv, inverse = unique_pairs(corners)
    return readonly(curves_uv), readonly(inverse.reshape(-1, 4))


def unique_pairs(pairs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``np.unique(pairs, axis=0, return_inverse=True)`` for integer pairs (N, 2), by one key per
    pair (many times faster).

    >>> uv, inverse = unique_pairs(np.array([[1, 0], [0, 5], [1, 0]]))
    >>> uv.tolist(), inverse.tolist()
    ([[0, 5], [1, 0]], [1, 0, 1])
    """
    pairs = np.asarray(pairs, np.int64).reshape(-1, 2)
    if not len(pairs):
        return pairs.copy(), np.zeros(0, np.int64)
    low = pairs.min(axis=0)
    span = int(pairs[:, 1].max()) - int(low[1]) + 1  # Python integers: no overflow
    if (int(pairs[:, 0].max()) - int(low[0]) + 1) * span >= 2**62:  # keys past int64: the slow way
        found, inverse = np.unique(pairs, axis=0, return_inverse=True)
        return found, inverse.reshape(-1)
    keys, inverse = np.unique(
        (pairs[:, 0] - low[0]) * span + (pairs[:, 1] - low[1]), return_inverse=True
    )
    return np.stack([keys // span + low[0], keys % span + low[1]], axis=1), inverse.reshape(-1)


def corner_members(cell_curves: np.ndarray, curves: int) -> tuple[tuple[tuple[int, int], ...], ...]:
    """For each of ``curves`` lattice curves, the (tube, 0-based corner) pairs on it, in tube order.

    Examples
    --------
    >>> corner_members(np.array([[0, 1, 3, 2], [3, 4, 6, 5]]), 7)[3]
    ((0, 2), (1, 0))
    """
    members: list[list[tuple[int, int]]] = [[] for _ in range(curves)]
    for k, row in enumerate(np.asarray(cell_curves).tolist()):
        for c, m in enumerate(row):
            members[m].append((k, c))
    return tuple(tuple(m) for m in members)


@dataclass(frozen=True, eq=False)
class SheetTopology(FrozenArrays):
    """One developed sheet in the numbering of its topology's mesh.

    Attributes
    ----------
    label : str
        ``"tube 2 · sheet A"`` (tubes numbered from 1).
    vertices : (V_s,) ndarray of int
        The mesh vertex of every sheet vertex, in sheet order.
    faces : (F_s,) ndarray of int
        The mesh faces of the sheet, ascending.
    edges : (E_s,) ndarray of int
        The mesh edges of the sheet, ascending.
    faces_vertices : (F_s, k) ndarray of int
        The faces in sheet numbering.
    edges_vertices : (E_s, 2) ndarray of int
        The edges in sheet numbering, each oriented as the sheet's first face (lowest
        index) that traverses it.
    edges_seam : (E_s,) ndarray of int
        Seam id of every seam edge (shared with the partner edge on the other sheet of
        the tube), -1 elsewhere.

    Examples
    --------
    >>> sheet = Topology.tubes([[0, 1, 3, 2]], 2).sheets[0]
    >>> sheet.label, sheet.faces.tolist(), sheet.vertices.tolist()
    ('tube 1 · sheet A', [0, 1, 6, 7], [6, 7, 0, 1, 2, 3])
    """

    label: str
    vertices: np.ndarray
    faces: np.ndarray
    edges: np.ndarray
    faces_vertices: np.ndarray
    edges_vertices: np.ndarray
    edges_seam: np.ndarray


@dataclass(frozen=True, eq=False)
class Topology(FrozenArrays):
    """The mesh a structure's lattice curves are put on, with its sheets.

    All arrays are read-only. Build it with :meth:`tubes` or :meth:`panels`.

    Attributes
    ----------
    vertex_curve, vertex_sample : (V,) ndarray of int
        The lattice curve (row of the structure's ``curves_uv``) and the sample of every
        vertex: vertex v is ``curves[vertex_curve[v], vertex_sample[v]]``.
    faces_vertices : (F, k) ndarray of int
        Polygons (-1 padded), counter-clockwise seen from outside the tubes.
    faces_group : (F,) ndarray of int
        Strip 4k + c of every face (strip c of tube k).
    edges_vertices : (E, 2) ndarray of int
    edges_kind : (E,) ndarray of str
        One of :data:`curvefold.geometry._mesh.EDGE_KINDS`.
    edges_seam : (E,) ndarray of int
        Seam id of every seam edge, -1 elsewhere.
    sheets : tuple of SheetTopology
        Tube by tube, sheet A then B.

    Examples
    --------
    >>> t = Topology.tubes([[0, 1, 3, 2]], 2)  # one tube, two samples per curve
    >>> t.vertex_curve.tolist(), t.vertex_sample.tolist(), len(t.sheets)
    ([0, 0, 1, 1, 3, 3, 2, 2], [0, 1, 0, 1, 0, 1, 0, 1], 2)
    """

    vertex_curve: np.ndarray
    vertex_sample: np.ndarray
    faces_vertices: np.ndarray
    faces_group: np.ndarray
    edges_vertices: np.ndarray
    edges_kind: np.ndarray
    edges_seam: np.ndarray
    sheets: tuple[SheetTopology, ...]

    @classmethod
    def tubes(
        cls,
        cell_curves: np.ndarray,
        samples: int,
        *,
        faces: Literal["triangles", "quads"] = "triangles",
        keep: Sequence[np.ndarray] | None = None,
    ) -> Topology:
        """Closed tubes of four ruled strips, one per cell, each with its own vertices.

        Vertex ``(4k + c)·n + j`` is sample j of corner c (0-based) of tube k. Strip c of a
        tube, between a = corner c and b = corner c + 1, has for j < n − 1 the quad
        ``(a_j, a_{j+1}, b_{j+1}, b_j)`` or the two triangles ``(a_j, b_{j+1}, b_j)``,
        ``(a_j, a_{j+1}, b_{j+1})`` (all first triangles of a strip, then all second ones);
        normals point out of the tube. Edges: the curve edges of every strip's corner a
        (kind of that corner), then the rulings ``(a_i, b_i)`` (``"boundary"`` at both
        ends), then the diagonals ``(a_j, b_{j+1})`` (triangles only). A ruling quad is
        planar to O(h³) only: the triangles' diagonals carry that bend.

        Parameters
        ----------
        cell_curves : (K, 4) array_like of int
            Lattice curve at corners 1–4 of every tube.
        samples : int
            Samples n ≥ 2 per curve.
        faces : {"triangles", "quads"}, keyword-only
        keep : sequence of (m_k,) array_like of int, optional, keyword-only
            For every tube, the samples its mesh keeps (ascending, at least two, within
            [0, n)): tube k then has m_k vertices per corner, vertex j being sample
            ``keep[k][j]``, and vertices are numbered tube after tube. Default: every sample.

        Examples
        --------
        >>> Topology.tubes([[0, 1, 3, 2]], 2).faces_vertices.tolist()
        [[0, 3, 2], [0, 1, 3], [2, 5, 4], [2, 3, 5], [4, 7, 6], [4, 5, 7], [6, 1, 0], [6, 7, 1]]
        >>> Topology.tubes([[0, 1, 3, 2]], 2, faces="hexagons")
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: faces must be 'triangles' or 'quads', got 'hexagons'
        """
        if faces not in ("triangles", "quads"):
            raise InputError(f"faces must be 'triangles' or 'quads', got {faces!r}")
        cells = np.asarray(cell_curves, dtype=np.int64).reshape(-1, 4)
        if keep is not None:
            return _kept_tubes(cls, cells, int(samples), faces, keep)
        K, n = len(cells), int(samples)
        i, strip = np.arange(n), np.arange(4 * K)  # strip 4k + c
        vertex_curve, vertex_sample, face_rows, curve_edges, rulings, diagonals = _tube_numbering(
            cells, n, faces
        )
        per_strip = face_rows.shape[1]
        corner = np.repeat(strip % 4, n - 1)  # corner of every curve edge
        curve_kind = np.array(CORNER_KINDS)[corner]
        ruling_kind = np.where(np.tile(np.isin(i, (0, n - 1)), 4 * K), "boundary", "ruling")
        edges_kind = np.concatenate(
            [curve_kind, ruling_kind, np.full(len(diagonals), "diagonal")], dtype="<U8"
        )
        seam = np.full(len(edges_kind), -1, np.int64)
        seam[: len(curve_edges)] = np.where(
            curve_kind == "seam", seam_id(np.repeat(strip // 4, n - 1), corner), -1
        )
        faces_vertices = face_rows.reshape(-1, face_rows.shape[-1])
        edges_vertices = np.concatenate([curve_edges, rulings, diagonals])

        # Edge ids by block: curve edges of strip g, rulings of strip g, diagonals of strip g.
        def block(start: int, size: int, g: int) -> np.ndarray:
            return start + g * size + np.arange(size)

        C, R = len(curve_edges), len(rulings)
        sheets: list[SheetTopology] = []
        for k in range(K):
            for m, (name, strips) in enumerate(SHEETS):
                corners = (strips[0],) + tuple(STRIPS[s][1] for s in strips)
                g = [4 * k + s for s in strips]
                edge_ids = np.concatenate(
                    [block(0, n - 1, 4 * k + c) for c in corners]
                    + [block(C, n, gg) for gg in g]
                    + ([block(C + R, n - 1, gg) for gg in g] if faces == "triangles" else [])
                )
                face_ids = np.concatenate([block(0, per_strip, gg) for gg in g])
                verts = np.concatenate([(4 * k + c) * n + i for c in corners])
                sheets.append(
                    _sheet(
                        f"tube {k + 1} · sheet {name}",
                        verts,
                        np.sort(face_ids),
                        np.sort(edge_ids),
                        faces_vertices,
                        edges_vertices,
                        seam,
                        like=sheets[m] if k else None,
                    )
                )
        return cls(  # arrays made here, held as they are (read-only, not copied)
            vertex_curve=readonly(vertex_curve),
            vertex_sample=readonly(vertex_sample),
            faces_vertices=readonly(faces_vertices),
            faces_group=readonly(np.repeat(strip, per_strip)),
            edges_vertices=readonly(edges_vertices),
            edges_kind=readonly(edges_kind),
            edges_seam=readonly(seam),
            sheets=tuple(sheets),
        )

    @classmethod
    def panels(cls, cell_curves: np.ndarray, samples: int) -> Topology:
        """Closed tubes of rigid planar panels: :meth:`tubes` with quads, the rulings fold lines.

        The numbering, faces, sheets and seams are those of ``tubes(..., faces="quads")``;
        each quad is one exactly planar panel (no diagonals), and the segments between
        consecutive panels of a strip, rulings of the smooth strips, are fold lines here:
        kind ``"fold"``, with measured fold angles and M/V assignments (the end ones stay
        ``"boundary"``).

        Parameters
        ----------
        cell_curves : (K, 4) array_like of int
            Lattice polyline at corners 1–4 of every tube.
        samples : int
            Vertices N + 1 ≥ 2 per polyline.

        Examples
        --------
        >>> quads = Topology.tubes([[0, 1, 3, 2]], 3, faces="quads")
        >>> panels = Topology.panels([[0, 1, 3, 2]], 3)
        >>> sorted(set(quads.edges_kind[panels.edges_kind != quads.edges_kind].tolist()))
        ['ruling']
        """
        quads = cls.tubes(cell_curves, samples, faces="quads")
        return replace(
            quads, edges_kind=np.where(quads.edges_kind == "ruling", "fold", quads.edges_kind)
        )

    def coords(self, curves: np.ndarray) -> np.ndarray:
        """Vertex positions from lattice curves (..., M, n, 3); shape (..., V, 3).

        Examples
        --------
        >>> t = Topology.tubes([[0, 1, 3, 2]], 2)
        >>> corners = np.array(
        ...     [[0, 0], [1, 0], [0, 1], [1, 1]], float
        ... )  # (y, z) of curves 0–3: a square section
        >>> curves = np.stack([[[x, y, z] for x in (0.0, 2.0)] for y, z in corners])  # (4, 2, 3)
        >>> t.coords(curves)[:3].tolist(), t.coords(curves[None]).shape
        ([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0]], (1, 8, 3))
        """
        return np.asarray(curves)[..., self.vertex_curve, self.vertex_sample, :]

    def mesh(self, curves: np.ndarray) -> Mesh:
        """The mesh at the positions of lattice curves (M, n, 3), fold angles measured.

        Fold and seam edges carry their measured fold angle (FOLD sign), every other edge
        0; assignments follow :func:`fold_assignment` (the seams are closed).

        Examples
        --------
        >>> t = Topology.tubes([[0, 1, 3, 2]], 2)
        >>> corners = np.array(
        ...     [[0, 0], [1, 0], [0, 1], [1, 1]], float
        ... )  # (y, z) of curves 0–3: a square section
        >>> curves = np.stack([[[x, y, z] for x in (0.0, 2.0)] for y, z in corners])  # (4, 2, 3)
        >>> mesh = t.mesh(curves)
        >>> mesh.edges_kind[:4].tolist(), mesh.edges_foldAngle[:4].round(6).tolist()
        (['fold', 'seam', 'fold', 'seam'], [90.0, 90.0, 90.0, 90.0])
        >>> bool(
        ...     np.isnan(t.mesh(0 * curves).edges_foldAngle[:4]).all()
        ... )  # every point at one place: no normals, NaN
        True
        """
        coords = self.coords(curves)
        measured = fold_angles(coords, self.faces_vertices, self.edges_vertices)
        angle = np.where(np.isin(self.edges_kind, CREASE_KINDS), measured, 0.0)
        return Mesh(
            vertices_coords=coords,
            edges_vertices=self.edges_vertices,
            edges_assignment=fold_assignment(self.edges_kind, angle),
            edges_foldAngle=angle,
            faces_vertices=self.faces_vertices,
            edges_kind=self.edges_kind,
            faces_group=self.faces_group,
        )


def _tube_numbering(cells: np.ndarray, n: int, faces: str) -> tuple[np.ndarray, ...]:
    """The numbering of :meth:`Topology.tubes` on cells (K, 4) of n samples: every vertex's curve
    and sample (4Kn,), every strip's faces (4K, F, 3 or 4), and the curve edges, rulings and
    diagonals (none for quads), each (E, 2)."""
    j, i = np.arange(n - 1), np.arange(n)
    strip = np.arange(4 * len(cells))  # 4k + c
    a = (strip * n)[:, None]  # first vertex of corner c of tube k
    b = ((strip - strip % 4 + (strip + 1) % 4) * n)[:, None]  # first vertex of corner c + 1
    if faces == "triangles":
        first = np.stack([a + j, b + j + 1, b + j], axis=-1)
        second = np.stack([a + j, a + j + 1, b + j + 1], axis=-1)
        face_rows = np.concatenate([first, second], axis=1)  # (4K, 2(n − 1), 3)
    else:
        face_rows = np.stack([a + j, a + j + 1, b + j + 1, b + j], axis=-1)  # (4K, n − 1, 4)
    curve_edges = np.stack([a + j, a + j + 1], axis=-1).reshape(-1, 2)
    rulings = np.stack([a + i, b + i], axis=-1).reshape(-1, 2)
    diagonals = (
        np.stack([a + j, b + j + 1], axis=-1).reshape(-1, 2)
        if faces == "triangles"
        else np.zeros((0, 2), np.int64)
    )
    return (
        np.repeat(cells.reshape(-1), n),
        np.tile(i, len(strip)),
        face_rows,
        curve_edges,
        rulings,
        diagonals,
    )


def is_tube_numbering(topology: Topology, cell_curves: np.ndarray, samples: int) -> bool:
    """Whether a topology numbers its vertices, edges and faces as :meth:`Topology.tubes` numbers
    triangles of these cells at every sample (its edges' kinds aside), without building that
    topology.

    Examples
    --------
    >>> cells = np.array([[0, 1, 3, 2]])
    >>> (
    ...     is_tube_numbering(Topology.tubes(cells, 3), cells, 3),
    ...     is_tube_numbering(Topology.tubes(cells, 3, faces="quads"), cells, 3),
    ... )
    (True, False)
    """
    curve, sample, face_rows, *edges = _tube_numbering(
        np.asarray(cell_curves, dtype=np.int64).reshape(-1, 4), int(samples), "triangles"
    )
    return (
        np.array_equal(topology.vertex_curve, curve)
        and np.array_equal(topology.vertex_sample, sample)
        and np.array_equal(topology.faces_vertices, face_rows.reshape(-1, 3))
        and np.array_equal(topology.edges_vertices, np.concatenate(edges))
    )


def _kept_tubes(
    cls: type[Topology],
    cells: np.ndarray,
    samples: int,
    faces: Literal["triangles", "quads"],
    keep: Sequence[np.ndarray],
) -> Topology:
    """:meth:`Topology.tubes` with its own samples per tube: the tubes one by one, renumbered."""
    if len(keep) != len(cells):
        raise InputError(
            f"keep must list the samples of each of the {len(cells)} tubes, got {len(keep)} lists"
        )
    parts = []
    # a tube of m samples; its curves only name its vertices' (vertex_curve, below)
    made: dict[int, Topology] = {}
    for k, picks in enumerate(keep):
        picks = np.asarray(picks, dtype=np.int64)
        if (
            picks.ndim != 1
            or len(picks) < 2
            or picks[0] < 0
            or picks[-1] >= samples
            or (np.diff(picks) <= 0).any()
        ):
            raise InputError(
                f"keep[{k}] must be at least two ascending sample indices in [0, "
                f"{samples}), got {picks.tolist()}"
            )
        if len(picks) not in made:
            made[len(picks)] = cls.tubes(cells[k : k + 1], len(picks), faces=faces)
        parts.append((made[len(picks)], picks))
    V = np.cumsum([0] + [len(p.vertex_sample) for p, _ in parts])
    F = np.cumsum([0] + [len(p.faces_vertices) for p, _ in parts])
    E = np.cumsum([0] + [len(p.edges_vertices) for p, _ in parts])
    seams = len(_SEAMS)  # seam ids per tube
    sheets = []
    for k, (one, _) in enumerate(parts):
        for sheet in one.sheets:
            sheets.append(
                SheetTopology(
                    label=sheet.label.replace("tube 1 ", f"tube {k + 1} ", 1),
                    vertices=sheet.vertices + V[k],
                    faces=sheet.faces + F[k],
                    edges=sheet.edges + E[k],
                    faces_vertices=sheet.faces_vertices,
                    edges_vertices=sheet.edges_vertices,
                    edges_seam=np.where(sheet.edges_seam >= 0, sheet.edges_seam + seams * k, -1),
                )
            )
    return cls(
        vertex_curve=np.repeat(cells.reshape(-1), np.repeat([len(picks) for _, picks in parts], 4)),
        vertex_sample=np.concatenate([picks[one.vertex_sample] for one, picks in parts]),
        faces_vertices=np.concatenate(
            [one.faces_vertices + V[k] for k, (one, _) in enumerate(parts)]
        ),
        faces_group=np.concatenate([one.faces_group + 4 * k for k, (one, _) in enumerate(parts)]),
        edges_vertices=np.concatenate(
            [one.edges_vertices + V[k] for k, (one, _) in enumerate(parts)]
        ),
        edges_kind=np.concatenate([one.edges_kind for one, _ in parts]),
        edges_seam=np.concatenate(
            [
                np.where(one.edges_seam >= 0, one.edges_seam + seams * k, -1)
                for k, (one, _) in enumerate(parts)
            ]
        ),
        sheets=tuple(sheets),
    )


def _sheet(
    label: str,
    verts: np.ndarray,
    face_ids: np.ndarray,
    edge_ids: np.ndarray,
    faces_vertices: np.ndarray,
    edges_vertices: np.ndarray,
    seam: np.ndarray,
    *,
    like: SheetTopology | None = None,
) -> SheetTopology:
    """A sheet of the given mesh vertices, faces and edges, in its own numbering; ``like``: the
    same sheet of another tube of one :meth:`Topology.tubes`, whose numbering differs from
    this one's by a shift per block, so that the sheet's own faces and edges are its."""
    # made for this sheet: not copied
    verts, face_ids, edge_ids = readonly(verts), readonly(face_ids), readonly(edge_ids)
    if like is not None:
        return SheetTopology(
            label,
            verts,
            face_ids,
            edge_ids,
            like.faces_vertices,
            like.edges_vertices,
            readonly(seam[edge_ids]),
        )
    lookup = np.full(int(verts.max()) + 1, -1, np.int64)
    lookup[verts] = np.arange(len(verts))
    rows = faces_vertices[face_ids]
    local_faces = np.where(rows >= 0, lookup[rows], -1)
    local_edges = lookup[edges_vertices[edge_ids]]
    ef = edges_faces(local_faces, local_edges)
    if not (ef >= 0).any(axis=1).all():
        raise InternalError(f"{label}: an edge borders none of the sheet's faces")
    big = np.iinfo(np.int64).max
    fwd, rev = np.where(ef[:, 0] >= 0, ef[:, 0], big), np.where(ef[:, 1] >= 0, ef[:, 1], big)
    # as the first face runs
    oriented = np.where((rev < fwd)[:, None], local_edges[:, ::-1], local_edges)
    return SheetTopology(label, verts, face_ids, edge_ids, local_faces, oriented, seam[edge_ids])


def sample_index(n: int, count: int) -> np.ndarray:
    """About ``count`` sample indices of n ≥ 2 spread evenly, keeping both ends and the middle.

    Vault curves have an odd number of samples with the apex in the middle; thumbnails
    subsample them and must keep t = 0, ½ and 1 exactly.

    Examples
    --------
    >>> sample_index(201, 5).tolist()
    [0, 50, 100, 150, 200]
    >>> sample_index(4, 100).tolist()
    [0, 1, 2, 3]
    """
    if n < 2 or count < 2:
        raise InputError(f"sample_index needs n ≥ 2 and count ≥ 2, got n = {n}, count = {count}")
    mid = (n - 1) / 2
    half = max(2, (count + 1) // 2)
    idx = np.concatenate([np.linspace(0, mid, half), np.linspace(mid, n - 1, half)])
    picks = np.floor(idx + 0.5).astype(int)
    if n % 2 == 1:
        picks = np.append(picks, (n - 1) // 2)
    return distinct(picks)


def tube_strips(cell_curves: np.ndarray) -> np.ndarray:
    """The strips of tubes as pairs of curve rows, corner c to corner c+1, shape (K·4, 2).

    Examples
    --------
    >>> tube_strips(np.array([[0, 1, 3, 2]])).tolist()
    [[0, 1], [1, 3], [3, 2], [2, 0]]
    """
    cells = np.asarray(cell_curves)
    return cells[:, np.array(STRIPS)].reshape(-1, 2)


def thin_cells(cell_curves: np.ndarray, limit: int) -> np.ndarray:
    """At most ``limit`` rows of cell_curves (K, 4), evenly spread, first and last kept.

    Examples
    --------
    >>> thin_cells(np.arange(20).reshape(5, 4), 3).tolist()
    [[0, 1, 2, 3], [8, 9, 10, 11], [16, 17, 18, 19]]
    >>> thin_cells(np.zeros((0, 4), int), 3).shape  # no cells
    (0, 4)
    """
    k = len(cell_curves)
    if k <= limit:
        return np.asarray(cell_curves)
    return np.asarray(cell_curves)[distinct(np.linspace(0, k - 1, limit).round().astype(int))]
