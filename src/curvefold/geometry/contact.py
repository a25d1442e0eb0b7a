"""Where a structure's folding motion ends: the first contact between parts of it far apart.

Rigid folding never reaches a curve of regression (it is intrinsic), but past the design
angle κ = κ_2D / cos α grows and a structure curls until two of its parts meet: a vault's
arch closes on itself, its tubes on each other. :func:`first_contact` finds the first fold
angle where that happens; the motion (its files, its certificate) ends there.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from .structure import Structure

__all__ = ["first_contact", "far_pairs", "closest_far", "contact_scales"]


def far_pairs(points: np.ndarray, uv: np.ndarray, t: np.ndarray, *, radius: float, dt_min: float) -> np.ndarray:
    """Pairs of points closer than ``radius`` that are parts far apart, shape (P, 2) (flat indices).

    Points (M curves × m samples, flattened) are far apart when their curves are two lattice
    steps apart or more (``max(|Δu|, |Δv|) ≥ 2``: two tubes moved into each other) or their t
    differ by more than ``dt_min`` (an arch closing on itself); neighbours along a strip and the
    curves of one cell, which touch by construction, never are.

    Examples
    --------
    >>> x = np.array([[[0.0, 0, 0], [1, 0, 0]], [[0, 0, 0.01], [1, 0, 0.01]], [[0, 0, 0], [5, 0, 0]]])  # 3 curves × 2 samples
    >>> # curves (0, 0) and (0, 1) are one step apart: touching is theirs; (2, 2) is two steps from both
    >>> far_pairs(x.reshape(-1, 3), np.array([[0, 0], [0, 1], [2, 2]]), np.array([0.0, 1.0]), radius=0.1, dt_min=0.5).tolist()
    [[0, 4], [2, 4]]
    """
    from scipy.spatial import cKDTree

    m = len(t)
    pairs = cKDTree(points).query_pairs(radius, output_type="ndarray")
    if not len(pairs):
        return pairs.reshape(0, 2)
    ci, cj = pairs[:, 0] // m, pairs[:, 1] // m
    steps = np.abs(uv[ci] - uv[cj]).max(axis=1)
    far = (steps >= 2) | (np.abs(t[pairs[:, 0] % m] - t[pairs[:, 1] % m]) > dt_min)
    return pairs[far]


def contact_scales(lattice) -> tuple[float, float]:
    """(radius, dt_min) of :func:`far_pairs` for a lattice: half its smallest strip width, and four
    widths' worth of its curve's arc length in t."""
    w_min = float(min(lattice.width_left.min(), lattice.width_right.min()))
    dt_min = 4 * max(float(lattice.width_left.max()), float(lattice.width_right.max())) / float(lattice.crease.curve.length)
    return 0.5 * w_min, dt_min


def closest_far(vertices: np.ndarray, uv: np.ndarray, t: np.ndarray, *, radius: float, dt_min: float,
                samples: int = 201) -> tuple[float, tuple[int, int, int, int] | None]:
    """The distance of the closest two far-apart parts (:func:`far_pairs`) within ``radius``, and where.

    Parameters
    ----------
    vertices : (M, n, 3) ndarray
        The structure's curves at one fold angle.
    uv : (M, 2) ndarray
    t : (n,) ndarray
        Curve parameter of the samples.
    samples : int
        Samples along t the curves are resampled to.

    Returns
    -------
    distance : float
        ``inf`` when no far-apart parts are within ``radius``, NaN when a point is not finite.
    where : (curve, sample, curve, sample) or None
    """
    idx = np.unique(np.linspace(0, vertices.shape[1] - 1, samples).round().astype(int))
    points = vertices[:, idx].reshape(-1, 3)
    if not np.isfinite(points).all():
        return float("nan"), None
    pairs = far_pairs(points, uv, t[idx], radius=radius, dt_min=dt_min)
    if not len(pairs):
        return float("inf"), None
    d = np.linalg.norm(points[pairs[:, 0]] - points[pairs[:, 1]], axis=1)
    i, j = pairs[int(np.argmin(d))]
    m = len(idx)
    return float(d.min()), (int(i // m), int(idx[i % m]), int(j // m), int(idx[j % m]))


@lru_cache(maxsize=8)
def first_contact(structure: Structure, *, start: float | None = None, step: float = 1.0, max_angle: float = 179.0,
                  samples: int = 201) -> float | None:
    """The first fold angle from ``start`` (default the design angle, included) where parts of the structure far apart touch.

    The structure is refolded on a grid of ``step`` degrees up to ``max_angle``; points of
    all its curves, resampled to ``samples`` along t, touch when closer than half the
    smallest strip width (:func:`far_pairs`, with parts more than four widths' worth of arc
    length apart in t: :func:`contact_scales`).

    Returns
    -------
    float or None
        2α in degrees of the first contact on the grid, or None if none occurs up to
        ``max_angle``. Cached for the last few structures (they are immutable).

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice
    >>> tube = Structure.tube(Lattice.from_crease(Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=41)), 0.1, 0.1))
    >>> first_contact(tube, max_angle=120.0) is None   # a short tube does not curl onto itself
    True
    """
    lat = structure.lattice
    start = float(lat.crease.fold_angle) if start is None else float(start)
    radius, dt_min = contact_scales(lat)
    uv = structure.curves_uv
    angles = np.arange(start, max_angle + 1e-9, step)
    for chunk in range(0, len(angles), 16):
        for k, frame in enumerate(lat.fold_points(uv, angles[chunk : chunk + 16])):  # (M, n, 3) each
            if closest_far(frame, uv, lat.t, radius=radius, dt_min=dt_min, samples=samples)[1] is not None:
                return float(angles[chunk + k])
    return None
