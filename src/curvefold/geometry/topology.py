"""Topology of tubes: corner order, strips and the thinned views of a structure.

A cell (i, j) of the lattice is a tube whose corners 1–4 are the lattice curves
(i, j), (i, j+1), (i+1, j+1), (i+1, j) in construction order; strip c of a tube runs from
corner c to corner c + 1 (mod 4).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..kernel.errors import InputError

if TYPE_CHECKING:  # pragma: no cover
    from .structure import Structure

__all__ = ["sample_index", "tube_strips", "thin_cells", "drawable"]


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
    return np.unique(picks)


def tube_strips(cell_curves: np.ndarray) -> np.ndarray:
    """The strips of tubes as pairs of curve rows, corner c to corner c+1, shape (K·4, 2).

    Examples
    --------
    >>> tube_strips(np.array([[0, 1, 3, 2]])).tolist()
    [[0, 1], [1, 3], [3, 2], [2, 0]]
    """
    cells = np.asarray(cell_curves)
    return np.stack([cells, np.roll(cells, -1, axis=1)], axis=-1).reshape(-1, 2)


def thin_cells(cell_curves: np.ndarray, limit: int) -> np.ndarray:
    """At most ``limit`` rows of cell_curves (K, 4), evenly spread, first and last kept."""
    k = len(cell_curves)
    if k <= limit:
        return np.asarray(cell_curves)
    return np.asarray(cell_curves)[np.unique(np.linspace(0, k - 1, limit).round().astype(int))]


def drawable(structure: Structure, vertices: np.ndarray, *, segments: int, max_cells: int) -> tuple[np.ndarray, np.ndarray, tuple[str, ...]]:
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
    """
    cells = thin_cells(structure.cell_curves, max_cells)
    used = np.unique(cells)
    remap = np.full(len(structure.curves_uv), -1)
    remap[used] = np.arange(len(used))
    idx = sample_index(vertices.shape[-2], segments + 1)
    kinds = tuple(str(k) for k in np.asarray(structure.curve_kinds)[used])
    return vertices[..., used, :, :][..., idx, :], remap[cells], kinds
