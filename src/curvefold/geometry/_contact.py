"""Where a structure's folding motion ends: the first contact between parts of it far apart.

Rigid folding never reaches a curve of regression (it is intrinsic), but past the design
angle κ = κ_2D / cos α grows and a structure curls until two of its parts meet: a vault's
arch closes on itself, its tubes on each other. :func:`first_contact` finds the first fold
angle where that happens; the motion (its files, its certificate) ends there.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..kernel._arrays import distinct
from ._kinds import StructureLattice
from ._structure import Structure

__all__ = ["first_contact", "far_pairs", "closest_far", "contact_scales"]


#: Consecutive samples of a curve that :func:`far_pairs` bounds by one box.
_BOX = 8


def far_pairs(
    points: np.ndarray, uv: np.ndarray, arc: np.ndarray, *, radius: float, reach: float
) -> np.ndarray:
    """Pairs of points closer than ``radius`` that are parts far apart, shape (P, 2) (flat indices i
    < j, sorted).

    Points (M curves × m samples, flattened) are far apart when their curves are two lattice
    steps apart or more (``max(|Δu|, |Δv|) ≥ 2``: two tubes moved into each other), or when
    along each of their two curves the arc length between their samples exceeds ``reach`` (an
    arch closing on itself): the structure joins them otherwise by a path along one of the
    curves and across at most one strip. Neighbours along a strip, the curves of one cell
    and a curve that pinches (its samples bunch up near a curve of regression) touch by
    construction, and never count.

    The search is exact: a pair is close when its squared distance (summed over x, y, z) is at
    most ``radius²``. Every ``_BOX`` consecutive samples of a curve are bounded by a box;
    the pairs of boxes that overlap when grown by the radius (swept along the longest axis)
    and may hold parts far apart (their curves two steps apart, or more arc than ``reach``
    between their samples along both curves) give the point pairs whose distances decide.

    Parameters
    ----------
    points : (M·m, 3) ndarray
    uv : (M, 2) ndarray
        The lattice curve of every row of ``points``' curves.
    arc : (M, m) ndarray
        Arc length along every curve at its samples, non-decreasing.

    Examples
    --------
    >>> x = np.array(
    ...     [[[0.0, 0, 0], [1, 0, 0]], [[0, 0, 0.01], [1, 0, 0.01]], [[0, 0, 0], [5, 0, 0]]]
    ... )  # 3 curves × 2 samples
    >>> # curves (0, 0) and (0, 1) are one step apart: touching is theirs; (2, 2) is two steps
    >>> # from both
    >>> arc = np.array([[0.0, 1.0], [0.0, 1.0], [0.0, 5.0]])
    >>> far_pairs(
    ...     x.reshape(-1, 3), np.array([[0, 0], [0, 1], [2, 2]]), arc, radius=0.1, reach=2.0
    ... ).tolist()
    [[0, 4], [2, 4]]
    """
    M, m = arc.shape
    if M * m == 0:
        return np.zeros((0, 2), np.int64)
    per_curve = -(-m // _BOX)
    slots = np.arange(per_curve * _BOX).reshape(per_curve, _BOX)
    samples, real = np.minimum(slots, m - 1), slots < m  # the last box repeats its last sample
    x = points.reshape(M, m, 3)[:, samples]  # (M, boxes, _BOX, 3)
    a, b = _overlapping_boxes(
        x.min(axis=2).reshape(-1, 3), x.max(axis=2).reshape(-1, 3), radius * (1 + 1e-9)
    )
    (ca, ka), (cb, kb) = np.divmod(a, per_curve), np.divmod(b, per_curve)
    first, last = (
        np.minimum(samples[ka, 0], samples[kb, 0]),
        np.maximum(samples[ka, -1], samples[kb, -1]),
    )
    # bounds the arc between any two of their points
    span = np.minimum(arc[ca, last] - arc[ca, first], arc[cb, last] - arc[cb, first])
    boxes = (np.abs(uv[ca] - uv[cb]).max(axis=1) >= 2) | (span > reach)
    a, b, ca, ka, cb, kb = a[boxes], b[boxes], ca[boxes], ka[boxes], cb[boxes], kb[boxes]
    # flat indices
    i = np.broadcast_to((ca[:, None] * m + samples[ka])[:, :, None], (len(a), _BOX, _BOX))
    j = np.broadcast_to((cb[:, None] * m + samples[kb])[:, None, :], (len(a), _BOX, _BOX))
    # a box with itself: i < j
    once = real[ka][:, :, None] & real[kb][:, None, :] & ((a != b)[:, None, None] | (i < j))
    i, j = np.minimum(i, j)[once], np.maximum(i, j)[once]
    d = np.take(points, i, axis=0) - np.take(points, j, axis=0)
    close = d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1] + d[:, 2] * d[:, 2] <= radius * radius
    i, j = i[close], j[close]
    (ci, si), (cj, sj) = np.divmod(i, m), np.divmod(j, m)
    steps = np.abs(uv[ci] - uv[cj]).max(axis=1)
    along = np.minimum(np.abs(arc[ci, si] - arc[ci, sj]), np.abs(arc[cj, si] - arc[cj, sj]))
    pairs = np.stack([i, j], axis=1)[(steps >= 2) | (along > reach)]
    return pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]


def _overlapping_boxes(
    lo: np.ndarray, hi: np.ndarray, grown: float
) -> tuple[np.ndarray, np.ndarray]:
    """The pairs (a, b) of boxes (B, 3), each once and each box with itself, whose bounds overlap
    when grown by ``grown``.

    Sweep and prune: the boxes in order of their lower bound along the axis where this pairs the
    fewest, each paired with itself and the later ones that start before it ends there; the other
    two axes decide."""
    sweeps = [_sweep(lo[:, k], hi[:, k], grown) for k in range(3)]
    axis = min(range(3), key=lambda k: int(sweeps[k][1].sum()))
    order, count = sweeps[axis]
    lo, hi = lo[order].T, hi[order].T  # (3, B)
    a = np.repeat(np.arange(lo.shape[1]), count)
    b = a + np.arange(len(a)) - np.repeat(np.cumsum(count) - count, count)
    for k in (k for k in range(3) if k != axis):
        hit = np.take(lo[k], a) - np.take(hi[k], b) <= grown
        hit &= np.take(lo[k], b) - np.take(hi[k], a) <= grown
        a, b = a[hit], b[hit]
    return order[a], order[b]


def _sweep(lo: np.ndarray, hi: np.ndarray, grown: float) -> tuple[np.ndarray, np.ndarray]:
    """The boxes' order along one axis (by lower bound, (B,)) and how many boxes from each on,
    itself included, start before it ends there grown by ``grown`` (B,)."""
    order = np.argsort(lo, kind="stable")
    return order, np.searchsorted(lo[order], hi[order] + grown, side="right") - np.arange(len(lo))


def contact_scales(lattice: StructureLattice) -> tuple[float, float]:
    """(radius, reach) of :func:`far_pairs` for a lattice: half its smallest strip width, and four
    times its largest.

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice, Structure
    >>> lat = Lattice.from_crease(
    ...     Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5), fold_angle=90),
    ...     0.1,
    ...     0.2,
    ... )
    >>> contact_scales(lat)
    (0.05, 0.8)
    """
    w_min = float(min(lattice.width_left.min(), lattice.width_right.min()))
    return 0.5 * w_min, 4 * max(float(lattice.width_left.max()), float(lattice.width_right.max()))


def closest_far(
    vertices: np.ndarray, uv: np.ndarray, *, radius: float, reach: float, samples: int = 201
) -> tuple[float, tuple[int, int, int, int] | None]:
    """The distance of the closest two far-apart parts (:func:`far_pairs`) within ``radius``, and
    where.

    Parameters
    ----------
    vertices : (M, n, 3) ndarray
        The structure's curves at one fold angle.
    uv : (M, 2) ndarray
    samples : int
        Samples along t the curves are resampled to.

    Returns
    -------
    distance : float
        ``inf`` when no far-apart parts are within ``radius``, NaN when a point is not finite.
    where : (curve, sample, curve, sample) or None

    Examples
    --------
    Curves 0 and 2, two lattice steps apart, pass 0.01 from each other; curve 1 is far:

    >>> x = np.linspace(0, 1, 3)
    >>> curves = np.stack([np.stack([x, 0 * x, 0 * x + z], axis=-1) for z in (0.0, 1.0, 0.01)])
    >>> uv = np.array([[0, 0], [1, 0], [2, 0]])
    >>> closest_far(curves, uv, radius=0.1, reach=10.0, samples=3)
    (0.01, (0, 0, 2, 0))
    >>> closest_far(
    ...     curves[:2], uv[:2], radius=0.1, reach=10.0, samples=3
    ... )  # nothing far apart within the radius
    (inf, None)
    """
    idx = np.linspace(0, vertices.shape[1] - 1, samples).round().astype(int)
    idx = distinct(idx)
    curves = vertices[:, idx]
    points = curves.reshape(-1, 3)
    if not np.isfinite(points).all():
        return float("nan"), None
    arc = np.concatenate(
        [
            np.zeros((len(curves), 1)),
            np.cumsum(np.linalg.norm(np.diff(curves, axis=1), axis=-1), axis=1),
        ],
        axis=1,
    )
    pairs = far_pairs(points, uv, arc, radius=radius, reach=reach)
    if not len(pairs):
        return float("inf"), None
    d = np.linalg.norm(points[pairs[:, 0]] - points[pairs[:, 1]], axis=1)
    i, j = pairs[int(np.argmin(d))]
    m = len(idx)
    return float(d.min()), (int(i // m), int(idx[i % m]), int(j // m), int(idx[j % m]))


@lru_cache(maxsize=8)
def first_contact(
    structure: Structure,
    *,
    start: float | None = None,
    step: float = 1.0,
    max_angle: float = 179.0,
    samples: int = 201,
) -> float | None:
    """The first fold angle from ``start`` (default the design angle, included) where parts of the
    structure far apart touch.

    The structure is refolded on a grid of ``step`` degrees up to ``max_angle``; points of
    all its curves, resampled to ``samples`` along t, touch when closer than half the
    smallest strip width (:func:`far_pairs`, with parts more than four of the largest widths
    of arc length apart: :func:`contact_scales`).

    Returns
    -------
    float or None
        2α in degrees of the first contact on the grid, or None if none occurs up to
        ``max_angle``. Cached for the last few structures (they are immutable).

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice
    >>> tube = Structure.tube(
    ...     Lattice.from_crease(
    ...         Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=41)), 0.1, 0.1
    ...     )
    ... )
    >>> first_contact(tube, max_angle=120.0) is None  # a short tube does not curl onto itself
    True
    """
    lat = structure.lattice
    start = float(lat.crease.fold_angle) if start is None else float(start)
    radius, reach = contact_scales(lat)
    uv = structure.curves_uv
    angles = np.arange(start, max_angle + 1e-9, step)
    for chunk in range(0, len(angles), 8):
        for k, frame in enumerate(lat.fold_points(uv, angles[chunk : chunk + 8])):  # (M, n, 3) each
            if closest_far(frame, uv, radius=radius, reach=reach, samples=samples)[1] is not None:
                return float(angles[chunk + k])
    return None
