"""Plane geometry of the crease-pattern pages: segments, distances, crossings, loops, boxes,
nearest points and convex hulls.

Vectorised NumPy on page coordinates (mm, x right, y up): points are (N, 2) arrays,
segments (S, 2, 2) arrays of their two ends, polylines (points, closed) pairs. Used by the
layout (:mod:`curvefold.io._layout`), its glue tabs (:mod:`curvefold.io._tabs`), label
placement (:mod:`curvefold.io._labels`) and page packing (:mod:`curvefold.io._packing`).
The nearest points and the hulls are those of scipy.spatial's cKDTree and ConvexHull (the
tests hold them to it), without that package's import in every job that lays out a pattern.

Examples
--------
>>> square = polyline_segments([(np.array([[0.0, 0], [2, 0], [2, 2], [0, 2]]), True)])
>>> inside_loops(np.array([[1.0, 1.0], [3.0, 1.0]]), square).tolist()
[True, False]
>>> distance_to_segments(np.array([[1.0, 3.0]]), square).tolist()
[1.0]
>>> polyline_segments([]).shape
(0, 2, 2)
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..kernel._arrays import distinct

__all__ = [
    "upright",
    "rotation",
    "box_corners",
    "polyline_segments",
    "cross2",
    "point_segment_distance",
    "distance_to_segments",
    "segments_touch",
    "segment_pairs_touch",
    "inside_loops",
    "ray_crossings",
    "ragged",
    "bounding_box",
    "cell_key",
    "cell_index",
    "nearest_points",
    "near_any",
    "convex_hull",
    "convex_hulls",
    "min_area_rotation",
    "min_area_rotations",
    "fit_arcs",
]


def upright(angle: float) -> float:
    """The direction ``angle`` (degrees) turned by a half turn if needed so text along it reads
    upright: in (-90, 90]."""
    a = (angle + 90.0) % 180.0 - 90.0
    return 90.0 if a == -90.0 else a


def rotation(phi: float) -> np.ndarray:
    """The (2, 2) matrix turning the plane by ``phi`` radians counter-clockwise."""
    c, s = math.cos(phi), math.sin(phi)
    return np.array([[c, -s], [s, c]])


def box_corners(center: np.ndarray, angle: float, width: float, height: float) -> np.ndarray:
    """Corners (4, 2) of the ``width`` × ``height`` box centred on ``center`` (2,), its width
    along ``angle`` (radians)."""
    u = np.array([math.cos(angle), math.sin(angle)])
    v = np.array([-u[1], u[0]])
    hw, hh = width / 2, height / 2
    return center + np.array([-hw * u - hh * v, hw * u - hh * v, hw * u + hh * v, -hw * u + hh * v])


def polyline_segments(polylines: Sequence[tuple[np.ndarray, bool]]) -> np.ndarray:
    """All segments of (points, closed) polylines, shape (S, 2, 2), polyline by polyline."""
    kept = [(pts, closed) for pts, closed in polylines if len(pts) >= 2]
    if not kept:
        return np.zeros((0, 2, 2))
    points = np.concatenate([pts for pts, _ in kept])
    length = np.array([len(pts) for pts, _ in kept])
    closed = np.array([c for _, c in kept], bool)
    line, place = ragged(length - 1 + closed)
    start = (np.cumsum(length) - length)[line]
    out = np.empty((len(line), 2, 2))
    out[:, 0] = points[start + place]
    out[:, 1] = points[start + (place + 1) % length[line]]
    return out


def cross2(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The z component of the cross product of 2D vectors (..., 2), shape (...)."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def point_segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance from points p to segments a–b, all (..., 2) broadcast together; shape (...).

    Computed on the x and y components apart (the same operations as sums and norms over
    the last axis, without their overhead on an axis of two).

    Examples
    --------
    >>> point_segment_distance(
    ...     np.array([[0.0, 1.0], [3.0, 0.0]]), np.zeros(2), np.array([2.0, 0.0])
    ... ).tolist()
    [1.0, 1.0]
    """
    p, a, b = (np.asarray(v, float) for v in (p, a, b))
    dx, dy = b[..., 0] - a[..., 0], b[..., 1] - a[..., 1]
    px, py = p[..., 0] - a[..., 0], p[..., 1] - a[..., 1]
    t = np.clip((px * dx + py * dy) / np.maximum(dx * dx + dy * dy, 1e-300), 0.0, 1.0)
    ex, ey = px - t * dx, py - t * dy
    return np.sqrt(ex * ex + ey * ey)


def distance_to_segments(points: np.ndarray, segments: np.ndarray) -> np.ndarray:
    """Distance (N,) from each of points (N, 2) to the nearest of segments (S, 2, 2), inf without
    any."""
    if len(segments) == 0:
        return np.full(len(points), np.inf)
    return point_segment_distance(points[:, None], segments[None, :, 0], segments[None, :, 1]).min(
        axis=1
    )


def segments_touch(a: np.ndarray, b: np.ndarray, tol: float) -> np.ndarray:
    """Pairs of segments a (S, 2, 2) and b (T, 2, 2) that meet other than at one shared end, (S, T)
    bool.

    Segments meet when they cross or come within ``tol`` of each other. Two segments whose
    ends coincide (within ``tol``) may meet there and nowhere else: each one's other end
    must stay ``tol`` away from the other segment (else they run along each other, as in a
    spike), and two segments sharing both ends coincide. So a set of segments in which no
    two touch is a planar drawing: simple outlines, tabs that neither overlap nor graze.
    """
    return segment_pairs_touch(a[:, None], b[None], tol)


def segment_pairs_touch(a: np.ndarray, b: np.ndarray, tol: float) -> np.ndarray:
    """:func:`segments_touch` of segments a and b (..., 2, 2) paired element by element, broadcast
    together; shape (...).

    Examples
    --------
    >>> a = np.array([[[0.0, 0.0], [2.0, 0.0]], [[0.0, 0.0], [2.0, 0.0]]])
    >>> b = np.array([[[2.0, 0.0], [2.0, 1.0]], [[1.0, -1.0], [1.0, 1.0]]])
    >>> segment_pairs_touch(a, b, 1e-9).tolist()  # an end shared, a crossing
    [False, True]
    """
    a0, a1, b0, b1 = a[..., 0, :], a[..., 1, :], b[..., 0, :], b[..., 1, :]

    def at(p: np.ndarray, q: np.ndarray) -> np.ndarray:
        """Whether ends p and q lie within tol of each other (their distance as a norm over the
        last axis measures it)."""
        d = p - q
        return np.sqrt(d[..., 0] * d[..., 0] + d[..., 1] * d[..., 1]) < tol

    s00, s01, s10, s11 = at(a0, b0), at(a0, b1), at(a1, b0), at(a1, b1)  # end i of a at end j of b
    a_shared, b_shared = (s00 | s01, s10 | s11), (s00 | s10, s01 | s11)
    near = ((point_segment_distance(a0, b0, b1) < tol) & ~a_shared[0]) | (
        (point_segment_distance(a1, b0, b1) < tol) & ~a_shared[1]
    )
    near |= ((point_segment_distance(b0, a0, a1) < tol) & ~b_shared[0]) | (
        (point_segment_distance(b1, a0, a1) < tol) & ~b_shared[1]
    )
    r, s = a1 - a0, b1 - b0
    cross = (cross2(s, a0 - b0) * cross2(s, a0 + r - b0) < 0) & (
        cross2(r, b0 - a0) * cross2(r, b0 + s - a0) < 0
    )
    return near | (cross & ~(a_shared[0] | a_shared[1])) | (a_shared[0] & a_shared[1])


def inside_loops(
    points: np.ndarray, segments: np.ndarray, groups: np.ndarray | None = None
) -> np.ndarray:
    """Even-odd point-in-region test against closed loops given as segments, shape (N,).

    With ``groups`` (S,) of int, the segments form several regions, each tested on its own:
    a point is inside when it lies inside any of them.
    """
    if len(points) == 0 or len(segments) == 0:
        return np.zeros(len(points), bool)
    crossing = ray_crossings(points[:, None], segments[None, :, 0], segments[None, :, 1])
    if groups is None:
        return (np.count_nonzero(crossing, axis=1) % 2) == 1
    counts = np.stack(
        [np.count_nonzero(crossing[:, groups == g], axis=1) for g in distinct(groups)], axis=1
    )
    return ((counts % 2) == 1).any(axis=1)


def ray_crossings(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Whether segments a–b cross the ray from points p toward +x, all (..., 2) broadcast together;
    shape (...). A point has an odd number of crossings inside a closed loop (:func:`inside_loops`).

    Examples
    --------
    >>> ray_crossings(
    ...     np.array([[0.0, 0.0], [2.0, 0.0]]), np.array([1.0, -1.0]), np.array([1.0, 1.0])
    ... ).tolist()
    [True, False]
    """
    straddle = (a[..., 1] > p[..., 1]) != (b[..., 1] > p[..., 1])
    # left of the crossing point, without dividing by the segment's height
    side = (p[..., 0] - a[..., 0]) * (b[..., 1] - a[..., 1]) - (p[..., 1] - a[..., 1]) * (
        b[..., 0] - a[..., 0]
    )
    return straddle & np.where(b[..., 1] > a[..., 1], side < 0, side > 0)


def ragged(counts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For groups of ``counts`` (G,) items: each item's group and its place in it, each
    (sum(counts),).

    Examples
    --------
    >>> [a.tolist() for a in ragged(np.array([2, 0, 3]))]
    [[0, 0, 2, 2, 2], [0, 1, 0, 1, 2]]
    """
    group = np.repeat(np.arange(len(counts)), counts)
    return group, np.arange(len(group)) - (np.cumsum(counts) - counts)[group]


def bounding_box(points: np.ndarray) -> np.ndarray:
    """The smallest and the largest coordinates ``[lo, hi]`` (2, D) of points (..., D) (at least
    one).

    Each is taken along a contiguous copy of the coordinate: NumPy reduces the long first
    axis of an (N, D) array of a few columns some ten times slower.

    Examples
    --------
    >>> bounding_box(np.array([[0.0, 3.0], [2.0, -1.0]])).tolist()
    [[0.0, -1.0], [2.0, 3.0]]
    """
    columns = np.ascontiguousarray(np.reshape(points, (-1, np.shape(points)[-1])).T)
    return np.stack([columns.min(axis=1), columns.max(axis=1)])


def cell_key(cells: np.ndarray) -> np.ndarray:
    """A key (...) of integer cells (..., 2) that sorts them by column, then row (rows in (-2³¹,
    2³¹))."""
    return cells[..., 0] * (1 << 32) + cells[..., 1]


def cell_index(
    points: np.ndarray, origin: np.ndarray, side: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points (P, 2) bucketed in square cells of ``side`` from ``origin`` (below and left of them
    all): their order by cell (:func:`cell_key`; by index within one), the sorted keys (P,)
    and the number of cells along x and y (2,)."""
    column, row = (np.floor((points[:, k] - origin[k]) / side).astype(np.int64) for k in (0, 1))
    key = column * (1 << 32) + row  # cell_key
    order = np.argsort(key, kind="stable")
    return order, key[order], np.array([column.max(initial=0), row.max(initial=0)]) + 1


def nearest_points(
    points: np.ndarray,
    queries: np.ndarray,
    limit: float = math.inf,
    index: tuple[np.ndarray, float, np.ndarray, np.ndarray, np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The nearest of ``points`` (P, 2, finite) to each of ``queries`` (Q, 2) nearer than ``limit``:
    its distance (Q,) and index (Q,), inf and P where there is none; ties go to the lowest index.

    :meth:`scipy.spatial.cKDTree.query`'s answer (k = 1, ``distance_upper_bound=limit``), distances
    to the last bit: the points are bucketed in square cells of side r and each query looks in
    the 3 × 3 cells around its own, which hold every point nearer than r; the queries that
    find none look again with r doubled (up to ``limit``). The first cells may be given, made
    once for many queries: ``index`` is ``(origin, r, *cell_index(points, origin, r))``.

    Examples
    --------
    >>> d, i = nearest_points(
    ...     np.array([[0.0, 0.0], [3.0, 4.0]]),
    ...     np.array([[0.0, 1.0], [1.5, 2.0], [9.0, 9.0]]),
    ...     limit=6.0,
    ... )
    >>> d.tolist(), i.tolist()
    ([1.0, 2.5, inf], [0, 0, 2])
    """
    dist, nearest = np.full(len(queries), math.inf), np.full(len(queries), len(points))
    if len(points) == 0 or len(queries) == 0:
        return dist, nearest
    cells: tuple[np.ndarray, ...] | None = None
    if index is None:
        lo, hi = bounding_box(points)
        extent = float((hi - lo).max())
        # about a point per cell, were they spread evenly
        r = min(limit, max(extent, 1e-300) / math.sqrt(len(points)))
    else:
        lo, r, *given = index
        cells = tuple(given)
    todo = np.flatnonzero(np.isfinite(queries).all(axis=1))  # (a query not finite has no nearest)
    while todo.size:
        d, i = _nearest_in_cells(points, queries[todo], lo, r, cells=cells)
        done = d < r if r < limit else np.ones(todo.size, bool)
        found = done & (d < limit)
        dist[todo[found]], nearest[todo[found]] = d[found], i[found]
        todo, r, cells = todo[~done], min(2.0 * r, limit), None
    return dist, nearest


def near_any(
    points: np.ndarray,
    queries: np.ndarray,
    reach: float,
    index: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
) -> np.ndarray:
    """Whether any of ``points`` (P, 2) lies nearer than ``reach`` to each of ``queries`` (Q, 2),
    (Q,) bool.

    ``index`` is ``(origin, *cell_index(points, origin, reach))``, made once for many queries.

    Examples
    --------
    >>> pts = np.array([[0.0, 0.0], [3.0, 4.0]])
    >>> near_any(
    ...     pts,
    ...     np.array([[0.0, 0.9], [1.5, 2.0]]),
    ...     1.0,
    ...     (pts.min(axis=0), *cell_index(pts, pts.min(axis=0), 1.0)),
    ... ).tolist()
    [True, False]
    """
    origin, *cells = index
    return _nearest_in_cells(points, queries, origin, reach, cells=tuple(cells))[0] < reach


def _nearest_in_cells(
    points: np.ndarray,
    queries: np.ndarray,
    lo: np.ndarray,
    r: float,
    pairs: int = 1 << 16,
    cells: tuple[np.ndarray, ...] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The nearest of ``points`` in the 3 × 3 cells of side r (from ``lo``) around each query:
    distance and index (inf, P for none), measuring at most about ``pairs`` query–point pairs
    at a time (``cells``: the points' :func:`cell_index` for these cells, if made already).
    The three cells of a column are one run of the points sorted by cell."""
    order, keys, size = cell_index(points, lo, r) if cells is None else cells
    # (far off, an empty cell)
    own = np.clip(np.floor((queries - lo) / r), -2, size + 1).astype(np.int64)
    column = own[:, None, 0] + np.array([-1, 0, 1])  # (Q, 3)
    # cell_key of each column's lowest cell
    first = keys.searchsorted(column * (1 << 32) + (own[:, 1:] - 1), "left")
    last = keys.searchsorted(column * (1 << 32) + (own[:, 1:] + 1), "right")
    dist, index = np.full(len(queries), math.inf), np.full(len(queries), len(points))
    found = last - first  # (Q, 3): the points in each column's run
    total = found[:, 0] + found[:, 1] + found[:, 2]
    per_query = np.cumsum(total)
    bounds = distinct(
        np.searchsorted(
            per_query, np.arange(pairs, per_query[-1] if len(per_query) else 0, pairs), "right"
        )
    )
    x, y, qx, qy = (
        np.ascontiguousarray(c) for c in (points[:, 0], points[:, 1], queries[:, 0], queries[:, 1])
    )
    for a, b in zip([0, *bounds.tolist()], [*bounds.tolist(), len(queries)]):
        group, place = ragged(found[a:b].ravel())
        if group.size == 0:
            continue
        near = order[first[a:b].ravel()[group] + place]
        query = a + group // 3
        dx, dy = np.take(qx, query) - np.take(x, near), np.take(qy, query) - np.take(y, near)
        d = np.sqrt(dx * dx + dy * dy)
        count = total[a:b]
        some = np.flatnonzero(count)
        starts = (np.cumsum(count) - count)[some]
        dist[a + some] = np.minimum.reduceat(d, starts)
        index[a + some] = np.minimum.reduceat(
            np.where(d == np.repeat(dist[a + some], count[some]), near, len(points)), starts
        )
    return dist, index


def convex_hull(points: np.ndarray) -> np.ndarray:
    """Indices of the vertices of the convex hull of ``points`` (N, 2, finite), counter-clockwise
    from the leftmost (then lowest) point; fewer than 3 when the points span no area.

    Points on a hull edge (to 1e-13 of the largest coordinate) are not vertices:
    :class:`scipy.spatial.ConvexHull`'s ``vertices``, but for where they start. Quickhull, each
    round splitting every edge that has points outside at the farthest of them, all edges at once.

    Examples
    --------
    >>> convex_hull(
    ...     np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 0.0], [1.0, 0.2], [1.0, -1.0], [2.0, 2.0]])
    ... ).tolist()
    [0, 4, 2, 5]
    >>> convex_hull(np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])).tolist()  # on a line
    [0, 2]
    """
    return convex_hulls([points])[0]


def convex_hulls(point_sets: Sequence[np.ndarray]) -> list[np.ndarray]:
    """The :func:`convex_hull` of each of several point sets (each (N_i, 2), finite), found
    together: the edges of all the hulls are split in the same rounds.

    Examples
    --------
    >>> [
    ...     h.tolist()
    ...     for h in convex_hulls(
    ...         [np.array([[0.0, 0.0], [2.0, 0.0], [1.0, 1.0]]), np.zeros((0, 2)), np.ones((2, 2))]
    ...     )
    ... ]
    [[0, 1, 2], [], [0]]
    """
    hulls = [np.zeros(0, np.intp)] * len(point_sets)
    live = [k for k, p in enumerate(point_sets) if len(p)]
    if not live:
        return hulls
    sizes = np.array([len(point_sets[k]) for k in live])
    starts = np.cumsum(sizes) - sizes
    points = np.concatenate([np.asarray(point_sets[k], float).reshape(-1, 2) for k in live])
    group, index = np.repeat(np.arange(len(live)), sizes), np.arange(len(points))
    x, y = points[:, 0], points[:, 1]
    left = x == np.minimum.reduceat(x, starts)[group]
    left &= y == np.minimum.reduceat(np.where(left, y, np.inf), starts)[group]
    right = x == np.maximum.reduceat(x, starts)[group]
    right &= y == np.maximum.reduceat(np.where(right, y, -np.inf), starts)[group]
    # per set, the first leftmost-lowest
    ends = np.stack(
        [
            np.minimum.reduceat(np.where(left, index, len(points)), starts),
            # and the last rightmost-highest point
            np.maximum.reduceat(np.where(right, index, -1), starts),
        ],
        axis=1,
    )
    # nearer an edge than this, a point lies on it (as qhull's tolerance finds)
    roundoff = 1e-13 * np.maximum.reduceat(np.maximum(np.abs(x), np.abs(y)), starts)
    # the others are a single point: a hull of one
    wide = np.flatnonzero((points[ends[:, 0]] != points[ends[:, 1]]).any(axis=1))
    # the hulls one after the other, and each vertex's set
    chain, owner = ends[wide].ravel(), np.repeat(wide, 2)
    place = np.full(len(live), -1)
    place[wide] = 2 * np.arange(len(wide))  # the first edge of each set's chain
    fx, fy = x[ends[:, 0]][group], y[ends[:, 0]][group]
    # cross2(last - first, p - first)
    side = (x[ends[:, 1]][group] - fx) * (y - fy) - (y[ends[:, 1]][group] - fy) * (x - fx)
    candidates = np.flatnonzero((side != 0) & (place[group] >= 0))
    # below the first chord: outside edge 0 (left to right); above: edge 1
    edge = place[group[candidates]] + (side[candidates] > 0)
    while candidates.size:
        # the last edge of each hull goes back to its first vertex
        closing = np.append(owner[1:] != owner[:-1], True)
        after = np.where(closing, np.searchsorted(owner, owner), np.arange(1, len(chain) + 1))
        # each edge's start, its direction and what a point may lie outside it
        ax, ay = x[chain], y[chain]
        dx, dy = ax[after] - ax, ay[after] - ay
        allowed = -roundoff[owner] * np.hypot(dx, dy)
        px, py = x[candidates], y[candidates]
        # < 0: outside its edge (on its right)
        side = dx[edge] * (py - ay[edge]) - dy[edge] * (px - ax[edge])
        out = side < allowed[edge]
        candidates, edge, side = candidates[out], edge[out], side[out]
        if candidates.size == 0:
            break
        low = np.full(len(chain), np.inf)
        np.minimum.at(low, edge, side)
        farthest, at_low = np.full(len(chain), len(points)), side == low[edge]
        # per edge, the farthest out (then the lowest index)
        np.minimum.at(farthest, edge[at_low], candidates[at_low])
        split = np.flatnonzero(farthest < len(points))
        farthest = farthest[split]
        # each vertex's place once they are in
        moved = np.arange(len(chain)) + np.searchsorted(split, np.arange(len(chain)))
        grown = np.empty((2, len(chain) + len(split)), np.intp)
        # each farthest point after the start of its edge
        grown[:, moved], grown[:, moved[split] + 1] = (chain, owner), (farthest, owner[split])
        chain, owner = grown
        apex = farthest[np.searchsorted(split, edge)]
        sx, sy = x[chain[moved[edge]]], y[chain[moved[edge]]]
        px, py = px[out], py[out]
        # outside the edge to the apex, else test the one on
        before = (x[apex] - sx) * (py - sy) - (y[apex] - sy) * (px - sx) < 0
        keep = candidates != apex
        candidates, edge = candidates[keep], np.where(before, moved[edge], moved[edge] + 1)[keep]
    bounds = np.searchsorted(owner, np.arange(len(live) + 1)).tolist()
    for k, (a, b) in enumerate(zip(bounds[:-1], bounds[1:])):
        hulls[live[k]] = chain[a:b] - starts[k] if b > a else ends[k, :1] - starts[k]
    return hulls


def min_area_rotation(points: np.ndarray) -> float:
    """Rotation (radians) that turns ``points`` (N, 2) to their minimum-area bounding box.

    The box has a side along an edge of the convex hull; for each edge the points that
    bound the box are the hull's supports in the four directions along and across it,
    found by bisection in the hull's sorted edge angles (rotating calipers: O(H log H) time
    and O(H) memory for H hull vertices, where trying every edge against every vertex took
    H² of both: 9 GB for a single fold of 20001 samples). Among rotations within 1e-6 of
    the minimum area, the one closest to a multiple of 90° is kept, so a sheet already
    aligned stays as it is.

    Examples
    --------
    A rectangle tilted by 30° turns back by 30° (or by 30° − 90°, the same box):

    >>> c, s = np.cos(np.pi / 6), np.sin(np.pi / 6)
    >>> box = np.array([[0, 0], [2, 0], [2, 1], [0, 1]]) @ np.array([[c, s], [-s, c]])
    >>> round(float(np.degrees(min_area_rotation(box))), 9) in (-30.0, 60.0)
    True
    >>> min_area_rotation(np.zeros((3, 2)))  # no area: no hull, no turn
    0.0
    """
    return min_area_rotations([points])[0]


def min_area_rotations(point_sets: Sequence[np.ndarray]) -> list[float]:
    """The :func:`min_area_rotation` of each of several point sets (each (N_i, 2)), their hulls
    found together."""
    point_sets = [np.asarray(p, float) for p in point_sets]
    finite = [bool(np.isfinite(p).all()) for p in point_sets]
    hulls = convex_hulls([p if ok else p[:0] for p, ok in zip(point_sets, finite)])
    return [_min_area_turn(p[v]) if len(v) >= 3 else 0.0 for p, v in zip(point_sets, hulls)]


def _min_area_turn(hull: np.ndarray) -> float:
    """:func:`min_area_rotation` of the vertices of a convex hull (H ≥ 3, 2), counter-clockwise."""
    e = np.roll(hull, -1, axis=0) - hull
    raw = np.arctan2(e[:, 1], e[:, 0])
    # increasing around the hull, in [raw[0], raw[0] + 2π)
    ang = raw[0] + (raw - raw[0]) % (2 * math.pi)

    def support(directions: np.ndarray) -> np.ndarray:
        """The hull vertex farthest along each direction (angles): the one whose outward
        normals (edge angle − 90°) of its two edges bracket it."""
        turn = (directions + 0.5 * math.pi - ang[0]) % (2 * math.pi) + ang[0]
        return hull[np.searchsorted(ang, turn) % len(hull)]

    u = np.stack([np.cos(ang), np.sin(ang)], axis=1)
    v = np.stack([-u[:, 1], u[:, 0]], axis=1)
    width = np.einsum("ij,ij->i", support(ang) - support(ang + math.pi), u)
    height = np.einsum("ij,ij->i", support(ang + 0.5 * math.pi) - support(ang - 0.5 * math.pi), v)
    area = width * height
    near = np.flatnonzero(area <= area.min() * (1 + 1e-6))
    off = np.abs((raw[near] + math.pi / 4) % (math.pi / 2) - math.pi / 4)
    return float(-raw[near[np.argmin(off)]])


def _arc_error(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """(bulge, largest distance of the points ``x``, ``y`` (k ≥ 2,) from it) of the circular arc
    from the first point to the last through the middle one: the bulge is tan(θ/4) of its turn θ,
    positive counter-clockwise (DXF's convention); 0 for a straight segment.

    The largest distance is taken from the nearest and the farthest points (rounding a
    difference is monotone, so it is the largest of the rounded distances, bit for bit)."""
    k = len(x)
    ax, ay, mx, my, bx, by = x[0], y[0], x[k // 2], y[k // 2], x[-1], y[-1]
    cx, cy = bx - ax, by - ay
    length = math.hypot(cx, cy)
    # < 0: the arc bulges to the right of the chord, turning counter-clockwise
    side = cx * (my - ay) - cy * (mx - ax)
    if k < 3 or abs(side) <= 1e-12 * max(length, 1e-300) ** 2:
        return 0.0, float(
            (np.abs(cx * (y - ay) - cy * (x - ax)) / max(length, 1e-300)).max(initial=0.0)
        )
    ux, uy, vx, vy = mx - ax, my - ay, mx - bx, my - by
    uu, vv, det = ux * ux + uy * uy, vx * vx + vy * vy, 2.0 * (ux * vy - uy * vx)
    # the circle through the three
    ox, oy = mx - (uu * vy - vv * uy) / det, my - (vv * ux - uu * vx) / det
    r = math.hypot(ax - ox, ay - oy)
    half = math.asin(min(1.0, 0.5 * length / r))
    # the middle point and the centre on opposite sides of the chord
    minor = side * (cx * (oy - ay) - cy * (ox - ax)) < 0
    theta = 2.0 * half if minor else 2.0 * math.pi - 2.0 * half
    d = np.hypot(x - ox, y - oy)
    error = max(float(d.max()) - r, r - float(d.min()))
    return math.tan(theta / 4.0) * (1.0 if side < 0 else -1.0), error


def fit_arcs(points: np.ndarray, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """An open polyline (n, 2) as fewer, longer circular arcs through some of its points.

    Greedily from the first point, each arc runs to the farthest point such that the arc
    through its ends and its middle point passes within ``tol`` of every point between
    (and turns by less than a half circle). Each search starts from the length of the arc
    before (curvature changes slowly along a crease), doubling while it fits and halving
    back. Returns the indices (m,) of the points kept and the bulge (m,) of the arc that
    leaves each (DXF's ``tan(θ/4)``; the last is 0).

    Examples
    --------
    >>> t = np.linspace(0.0, np.pi / 2, 9)
    >>> keep, bulge = fit_arcs(np.stack([np.cos(t), np.sin(t)], axis=1), 1e-9)
    >>> keep.tolist(), np.round(bulge, 6).tolist()  # a quarter circle is one arc
    ([0, 8], [0.414214, 0.0])
    >>> fit_arcs(np.array([[0.0, 0.0], [1.0, 0.0]]), 1e-9)[0].tolist()
    [0, 1]
    """
    points = np.asarray(points, float)
    n = len(points)
    x, y = np.ascontiguousarray(points[:, 0]), np.ascontiguousarray(points[:, 1])
    keep, bulges, i, run = [0], [], 0, 2

    def fits(j: int) -> float | None:
        b, err = _arc_error(x[i : j + 1], y[i : j + 1])
        return b if err <= tol and abs(b) < 1.0 else None

    while i < n - 1:
        lo, bulge = i + 1, 0.0  # one chord always fits
        hi = min(i + run, n - 1)
        while hi > lo and (b := fits(hi)) is not None:  # grow while it fits
            lo, bulge = hi, b
            if hi == n - 1:
                break
            hi = min(lo + 2 * (lo - i), n - 1)
        if hi > lo and lo < n - 1:  # the largest run that fits lies in [lo, hi)
            while hi - lo > 1:
                mid = (lo + hi) // 2
                b = fits(mid)
                lo, bulge, hi = (mid, b, hi) if b is not None else (lo, bulge, mid)
        keep.append(lo)
        bulges.append(bulge)
        run, i = max(lo - i, 2), lo
    return np.array(keep), np.array(bulges + [0.0])
