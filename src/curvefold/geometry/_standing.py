"""Frames of a folding motion set on the ground as the design frame stands (a vault's feet)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..kernel._arrays import readonly
from ._fold_arrays import FoldArrays
from ._mesh import Mesh

__all__ = ["standing_frames"]


def standing_frames(arrays: FoldArrays, *, tol: float = 1e-9) -> tuple[tuple[str, Mesh], ...]:
    """The folded frames of a structure that stands on the ground ``z = 0`` at its design angle
    (a vault, its span along +y), each moved rigidly to stand there too.

    Its feet are the vertices on the ground in the design frame, split at their mean ``y`` into
    the start and the end foot. In every frame the structure is turned about the x axis until
    the centroids of its feet are level, moved along y to keep their midpoint where the design
    frame has it, and set down on the ground (lowest ``z`` = 0). A frame that folds past the
    design angle no longer sinks its far foot below the ground.

    Parameters
    ----------
    arrays : FoldArrays
        Frames on one topology, the design angle among them.
    tol : float, keyword-only
        Largest ``|z|`` of a vertex on the ground in the design frame, model units.

    Returns
    -------
    tuple of (str, Mesh)
        The frames, titled as given; unchanged when the design frame is not among them or has
        not a foot at each end.
    """
    design = np.flatnonzero(np.isclose(arrays.fold_angles, arrays.fold_angle))
    if design.size == 0:
        return arrays.folded
    key = arrays.folded[int(design[0])][1].vertices_coords
    feet = np.flatnonzero(np.abs(key[:, 2]) <= tol)
    if feet.size == 0:
        return arrays.folded
    middle = key[feet, 1].mean()
    start, end = feet[key[feet, 1] < middle], feet[key[feet, 1] >= middle]
    if start.size == 0 or end.size == 0:
        return arrays.folded
    frames = []
    for title, mesh in arrays.folded:
        x = mesh.vertices_coords
        (y0, z0), (y1, z1) = x[start, 1:].mean(axis=0), x[end, 1:].mean(axis=0)
        turn = -np.arctan2(z1 - z0, y1 - y0)
        c, s = np.cos(turn), np.sin(turn)
        y, z = c * x[:, 1] - s * x[:, 2], s * x[:, 1] + c * x[:, 2]
        y += middle - 0.5 * (y[start].mean() + y[end].mean())
        placed = np.column_stack([x[:, 0], y, z - z.min()])
        frames.append((title, replace(mesh, vertices_coords=readonly(placed))))
    return tuple(frames)
