"""Certify an exported FOLD file: its folded frames against its own crease pattern."""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from ..geometry.mesh import fold_angles

__all__ = ["FoldCheck", "check_fold"]


@dataclass(frozen=True)
class FoldCheck:
    """The result of :func:`check_fold` (worst over the folded frames).

    Attributes
    ----------
    frames : int
        Number of folded frames checked.
    max_isometry_error : float
        Largest |ℓ_folded / ℓ_pattern − 1| over all edges.
    max_face_planarity_error : float
        Largest fold angle, in degrees, across the diagonals that split a face into
        triangles: the ``"diagonal"`` edges of a triangle mesh (across a ruling quad) and
        the fan diagonals of every polygon face with more than three vertices
        (:meth:`~curvefold.geometry.mesh.Mesh.triangulated`). 0 for planar faces.
    max_fold_angle_error : float
        Largest |measured − recorded| fold angle on the M and V edges, degrees.
    ok : bool
        All three within their tolerances.
    tolerances : dict
    """

    frames: int
    max_isometry_error: float
    max_face_planarity_error: float
    max_fold_angle_error: float
    ok: bool
    tolerances: dict

    def to_dict(self) -> dict:
        return {
            "frames": self.frames,
            "max_isometry_error": self.max_isometry_error,
            "max_face_planarity_error": self.max_face_planarity_error,
            "max_fold_angle_error": self.max_fold_angle_error,
            "ok": self.ok,
            "tolerances": self.tolerances,
        }


def check_fold(
    path: str | os.PathLike,
    *,
    isometry_tol: float = 1e-4,
    planarity_tol: float = 0.5,
    fold_angle_tol: float = 0.5,
) -> FoldCheck:
    """Read a FOLD file and measure its folded frames against its crease pattern.

    Parameters
    ----------
    path : path-like
        A FOLD file with a crease pattern frame and at least one folded frame sharing its
        topology (as ``curvefold`` writes them).
    isometry_tol : float, keyword-only
        Largest accepted relative edge-length change (default 1e-4: polyline creases change
        length with curvature at second order in the sample spacing).
    planarity_tol : float, keyword-only
        Largest accepted fold angle across the diagonals of ruling quads and polygon
        faces, degrees.
    fold_angle_tol : float, keyword-only
        Largest accepted fold-angle discrepancy on creases, degrees.

    Raises
    ------
    InputError
        The file is not a FOLD file curvefold can read, or has no folded frame.
    """
    from ..io.fold import read_fold
    from ..kernel.errors import InputError

    doc = read_fold(path)
    if not doc.folded:
        raise InputError(f"{os.fspath(path)}: no folded frame to check (the file holds only a crease pattern)")
    pattern = doc.crease_pattern
    base = pattern.edge_lengths()
    iso = plan = angle = 0.0
    for _, folded in doc.folded:
        iso = max(iso, float(np.max(np.abs(folded.edge_lengths() / base - 1))))
        measured = fold_angles(folded.vertices_coords, folded.faces_vertices, folded.edges_vertices)
        triangles = folded.triangulated()
        split = measured if triangles is folded else fold_angles(triangles.vertices_coords, triangles.faces_vertices, triangles.edges_vertices)
        diag = triangles.edges_kind == "diagonal"
        if diag.any():
            plan = max(plan, float(np.max(np.abs(split[diag]))))
        creases = np.isin(folded.edges_assignment, ("M", "V"))
        if creases.any():
            angle = max(angle, float(np.max(np.abs(measured[creases] - folded.edges_foldAngle[creases]))))
    tolerances = {"isometry": isometry_tol, "face_planarity_deg": planarity_tol, "fold_angle_deg": fold_angle_tol}
    ok = iso <= isometry_tol and plan <= planarity_tol and angle <= fold_angle_tol
    return FoldCheck(len(doc.folded), iso, plan, angle, bool(ok), tolerances)
