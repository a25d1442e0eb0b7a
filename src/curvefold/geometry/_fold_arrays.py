"""A structure as its files hold it: FOLD's parallel arrays of its crease pattern and folded frames.

:func:`fold_arrays` converts a structure, of any kind, to one topology of FOLD arrays
(:class:`~curvefold.geometry.Mesh`); :mod:`curvefold.io._fold` only writes them:

* the crease pattern is every developed sheet (:func:`~curvefold.geometry._sheets.develop`),
  laid in a row along +x, bounding boxes 5 % of the largest sheet apart, each seen from
  outside its tube, so its faces are counter-clockwise;
* seams are cut open: each seam edge appears once per sheet as a boundary edge, and the
  two copies are paired in ``seam_partners`` (they run opposite ways, as their faces
  traverse them);
* the folded frames put the same vertices at their 3D positions, so partner vertices
  coincide there, as do the crease edges of tubes glued where they touch (``bonds``);
* every frame carries the dihedral angle it has at every edge with two faces (the crease
  pattern those of the design state): a sampled curved sheet bends a little across its
  rulings and diagonals too, and a folder that follows the angles lands on the frame.

:func:`structure_metadata` is what every file records about the structure (tubes, cells,
samples, widths, angles, the seam numbering and the bonds).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InternalError
from ._fold_angle import check_fold_angle, check_fold_angles
from ._mesh import Mesh, edges_faces
from ._mesh import fold_angles as dihedral_angles
from ._sheets import PatternSheet, bonds, develop, folding_motion
from ._structure import Structure, check_structure
from ._topology import Topology

__all__ = ["FoldArrays", "fold_arrays", "structure_metadata"]


@dataclass(frozen=True, eq=False)
class FoldArrays(FrozenArrays):
    """A structure's crease pattern and folded frames in FOLD's parallel arrays, on one topology.

    Attributes
    ----------
    crease_pattern : Mesh
        Every sheet, flat (z = 0), in a row; the fold angles of the design state.
    folded : tuple of (str, Mesh)
        Title (``"fold angle 90°"``) and mesh of every folded frame: the crease pattern's
        topology at the frame's vertex positions, with its measured fold angles.
    seam_partners : (P, 2) ndarray of int
        Pairs of boundary edges glued together: the two sides of a seam.
    bonds : (Q, 2) ndarray of int
        Pairs of edges of different tubes glued where the tubes touch.
    fold_angle : float
        The design angle 2α whose fold angles the crease pattern carries, degrees.
    fold_angles : (A,) ndarray
        2α of the folded frames, degrees.
    sheets : tuple of PatternSheet
        The developed sheets laid in a row (:func:`~curvefold.geometry._sheets.develop`),
        each in its own place: :func:`~curvefold.geometry._sheets.sheets` of the structure at
        the design angle, on the same faces and samples.

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice, Structure
    >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
    >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
    >>> tube = Structure.tube(lat)
    >>> from curvefold.geometry._fold_arrays import fold_arrays
    >>> arrays = fold_arrays(tube, fold_angles=[0, 45])
    >>> (
    ...     arrays.fold_angle,
    ...     arrays.fold_angles.tolist(),
    ...     arrays.bonds.shape,
    ... )  # a single tube has no bonds
    (90.0, [0.0, 45.0], (0, 2))
    """

    crease_pattern: Mesh
    folded: tuple[tuple[str, Mesh], ...]
    seam_partners: np.ndarray
    bonds: np.ndarray
    fold_angle: float
    fold_angles: np.ndarray
    sheets: tuple[PatternSheet, ...]


def structure_metadata(
    structure: Structure, fold_angle: float | None = None, *, degrees: bool = True
) -> dict:
    """What the files of a structure record about it, JSON-ready.

    Parameters
    ----------
    structure : Structure
    fold_angle : float, optional
        The design angle 2α recorded; default the lattice's own.
    degrees : bool, keyword-only

    Returns
    -------
    dict
        ``tubes``, ``cells`` (as text), ``samples``, ``curve_length``, ``width_left`` and
        ``width_right`` at t = 0, ``design_fold_angle_deg``, ``fold_crease_angle_deg`` and
        ``seam_angle_deg`` (FOLD's sign), ``seams`` (their numbering) and ``bonds`` (as text).

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice
    >>> tube = Structure.tube(
    ...     Lattice.from_crease(
    ...         Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=9)), 0.1, 0.1
    ...     )
    ... )
    >>> meta = structure_metadata(tube)
    >>> meta["tubes"], meta["samples"], meta["seam_angle_deg"], meta["bonds"]
    (1, 9, -90.0, 'none')
    """
    check_structure(structure)
    lat = structure.lattice
    design = (
        lat.crease.fold_angle
        if fold_angle is None
        else check_fold_angle(fold_angle, degrees=degrees)
    )
    return {
        "tubes": len(structure.cells),
        "cells": "; ".join(f"({i}, {j})" for i, j in structure.cells.tolist()),
        "samples": len(lat.s),
        "curve_length": float(lat.crease.curve.length),
        "width_left": float(lat.width_left[0]),
        "width_right": float(lat.width_right[0]),
        "design_fold_angle_deg": float(design),
        "fold_crease_angle_deg": -float(design),
        "seam_angle_deg": -(180.0 - float(design)),
        "seams": "seam 2 of tube k has id 2k, seam 4 has id 2k + 1 (tubes from 0)",
        "bonds": " | ".join(b.describe() for b in bonds(structure)) or "none",
    }


def _row_offsets(xys: Sequence[np.ndarray], gap: float) -> list[np.ndarray]:
    """Translations (2,) placing 2D point sets in a row along +x, bounding boxes ``gap`` apart."""
    out, x = [], 0.0
    for xy in xys:
        lo, hi = xy.min(axis=0), xy.max(axis=0)
        out.append(np.array([x - lo[0], -lo[1]]))
        x += hi[0] - lo[0] + gap
    return out


def fold_arrays(
    structure: Structure,
    *,
    fold_angles: ArrayLike | None = None,
    fold_angle: float | None = None,
    degrees: bool = True,
    anchor: Literal["start", "middle"] = "start",
    faces: Literal["triangles", "quads"] = "triangles",
    keep: Sequence[np.ndarray] | None = None,
) -> FoldArrays:
    """A structure as FOLD arrays: its crease pattern and folded frames on one topology (module
    notes).

    Parameters
    ----------
    structure : Structure
    fold_angles : (A,) array_like, optional, keyword-only
        2α of the folded frames, in [0°, 180°); default the design angle only.
    fold_angle : float, optional, keyword-only
        The design angle whose fold angles the crease pattern carries; default the
        lattice's own.
    degrees : bool, keyword-only
    anchor : {"start", "middle"}, keyword-only
        Which frame of curve 1 stays fixed in the folded frames.
    faces : {"triangles", "quads"}, keyword-only
        Faces of the sheets (:meth:`Structure.topology`).
    keep : sequence of (m_k,) array_like of int, optional, keyword-only
        The samples each tube's mesh keeps (:func:`curvefold.geometry.choose_sampling`);
        default every sample.

    Returns
    -------
    FoldArrays

    Raises
    ------
    InputError
        A fold angle out of range, or an unknown anchor.

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice
    >>> tube = Structure.tube(
    ...     Lattice.from_crease(
    ...         Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=9)), 0.1, 0.1
    ...     )
    ... )
    >>> arrays = fold_arrays(tube, fold_angles=[0, 90])
    >>> [title for title, _ in arrays.folded], arrays.seam_partners.shape
    (['fold angle 0°', 'fold angle 90°'], (16, 2))
    >>> float(
    ...     abs(arrays.folded[0][1].vertices_coords[:, 2]).max()
    ... ) < 1e-12  # the flat frame is flat
    True
    """
    check_structure(structure)
    design = (
        structure.lattice.crease.fold_angle
        if fold_angle is None
        else check_fold_angle(fold_angle, degrees=degrees)
    )
    angles = (
        np.array([design])
        if fold_angles is None
        else check_fold_angles(fold_angles, degrees=degrees)
    )
    topology = structure.topology(faces, keep=keep)
    parts = develop(structure, topology, design)
    xys = [p.mesh.vertices_coords[:, :2] for p in parts]
    size = max(float(np.ptp(xy, axis=0).max()) for xy in xys)
    offsets = _row_offsets(xys, 0.05 * size)
    v_off = np.concatenate([[0], np.cumsum([len(xy) for xy in xys])])

    def cat(name: str) -> np.ndarray:
        return np.concatenate([getattr(p.mesh, name) for p in parts])

    cp = Mesh(
        vertices_coords=np.column_stack(
            [np.concatenate([xy + o for xy, o in zip(xys, offsets)]), np.zeros(v_off[-1])]
        ),
        edges_vertices=np.concatenate(
            [p.mesh.edges_vertices + v_off[i] for i, p in enumerate(parts)]
        ),
        edges_assignment=cat("edges_assignment"),
        edges_foldAngle=cat("edges_foldAngle"),
        faces_vertices=np.concatenate(
            [
                np.where(p.mesh.faces_vertices >= 0, p.mesh.faces_vertices + v_off[i], -1)
                for i, p in enumerate(parts)
            ]
        ),
        edges_kind=cat("edges_kind"),
        faces_group=cat("faces_group"),
    )
    # Seam partners: the two sheet edges that are one edge of the structure's mesh.
    mesh_edge = np.concatenate([sheet.edges for sheet in topology.sheets])
    ids = np.flatnonzero(np.concatenate([p.edges_seam for p in parts]) >= 0)
    ordered = ids[np.argsort(mesh_edge[ids], kind="stable")]
    pairs = ordered.reshape(-1, 2) if ordered.size % 2 == 0 else np.zeros((0, 2), np.int64)
    if (
        len(pairs) * 2 != ordered.size
        or not (mesh_edge[pairs[:, 0]] == mesh_edge[pairs[:, 1]]).all()
    ):
        raise InternalError("seam edges do not pair up between the two sheets of a tube")

    source = np.concatenate([sheet.vertices for sheet in topology.sheets])
    glued = _bond_pairs(cp.edges_vertices, source, topology, mesh_edge)
    # Every frame carries the dihedral angle it has at every edge; the key frame the design state's.
    # (1 + A, V, 3)
    coords = folding_motion(
        structure, np.concatenate([[design], angles]), anchor=anchor, topology=topology
    )[:, source]
    sides = edges_faces(cp.faces_vertices, cp.edges_vertices)
    measured = [
        dihedral_angles(x, cp.faces_vertices, cp.edges_vertices, faces_of_edges=sides)
        for x in coords
    ]
    cp = replace(cp, edges_foldAngle=measured[0])
    folded = tuple(
        (f"fold angle {a:g}°", replace(cp, vertices_coords=x, edges_foldAngle=m))
        for a, x, m in zip(angles, coords[1:], measured[1:])
    )
    return FoldArrays(cp, folded, readonly(pairs), glued, float(design), angles, parts)


def _bond_pairs(
    edges_vertices: np.ndarray, source: np.ndarray, topology: Topology, mesh_edge: np.ndarray
) -> np.ndarray:
    """Pairs of file edges between the same two samples of one lattice curve, in different tubes'
    meshes.

    Every tube carries its own copy of its curves; where tubes share a lattice curve those
    copies are glued. Each crease edge is keyed by its lattice curve and both its samples
    (tubes whose meshes keep different samples share only the edges between samples both
    keep); within a key, one file edge per mesh edge (a seam's two sheet edges are one mesh
    edge: that pair is a seam partner), chained pairwise.
    """
    a, b = source[edges_vertices[:, 0]], source[edges_vertices[:, 1]]
    # rulings and diagonals join two curves
    ids = np.flatnonzero(topology.vertex_curve[a] == topology.vertex_curve[b])
    n = int(topology.vertex_sample.max()) + 1
    lo = np.minimum(topology.vertex_sample[a[ids]], topology.vertex_sample[b[ids]])
    hi = np.maximum(topology.vertex_sample[a[ids]], topology.vertex_sample[b[ids]])
    key = (topology.vertex_curve[a[ids]].astype(np.int64) * n + lo) * n + hi
    order = np.lexsort((mesh_edge[ids], key))
    ids, key = ids[order], key[order]
    first = np.r_[True, (key[1:] != key[:-1]) | (mesh_edge[ids[1:]] != mesh_edge[ids[:-1]])]
    ids, key = ids[first], key[first]
    same = key[1:] == key[:-1]
    return readonly(np.stack([ids[:-1][same], ids[1:][same]], axis=1))
