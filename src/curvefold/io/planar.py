"""Plane geometry of the crease-pattern pages: segments, distances, crossings, loops and boxes.

Vectorised NumPy on page coordinates (mm, x right, y up): points are (N, 2) arrays,
segments (S, 2, 2) arrays of their two ends, polylines (points, closed) pairs. Used by the
layout (:mod:`curvefold.io.layout`), its glue tabs (:mod:`curvefold.io.tabs`), label
placement (:mod:`curvefold.io.labels`) and page packing (:mod:`curvefold.io.packing`).

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

__all__ = [
    "upright",
    "rotation",
    "box_corners",
    "polyline_segments",
    "cross2",
    "point_segment_distance",
    "distance_to_segments",
    "segments_touch",
    "segments_near_box",
    "inside_loops",
    "min_area_rotation",
]


def upright(angle: float) -> float:
    """The direction ``angle`` (degrees) turned by a half turn if needed so text along it reads upright: in (-90, 90]."""
    a = (angle + 90.0) % 180.0 - 90.0
    return 90.0 if a == -90.0 else a


def rotation(phi: float) -> np.ndarray:
    """The (2, 2) matrix turning the plane by ``phi`` radians counter-clockwise."""
    c, s = math.cos(phi), math.sin(phi)
    return np.array([[c, -s], [s, c]])


def box_corners(center: np.ndarray, angle: float, width: float, height: float) -> np.ndarray:
    """Corners (4, 2) of the ``width`` × ``height`` box centred on ``center`` (2,), its width along ``angle`` (radians)."""
    u = np.array([math.cos(angle), math.sin(angle)])
    v = np.array([-u[1], u[0]])
    hw, hh = width / 2, height / 2
    return center + np.array([-hw * u - hh * v, hw * u - hh * v, hw * u + hh * v, -hw * u + hh * v])


def polyline_segments(polylines: Sequence[tuple[np.ndarray, bool]]) -> np.ndarray:
    """All segments of (points, closed) polylines, shape (S, 2, 2)."""
    out = []
    for pts, closed in polylines:
        if len(pts) < 2:
            continue
        q = np.concatenate([pts, pts[:1]]) if closed else pts
        out.append(np.stack([q[:-1], q[1:]], axis=1))
    return np.concatenate(out) if out else np.zeros((0, 2, 2))


def cross2(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The z component of the cross product of 2D vectors (..., 2), shape (...)."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def point_segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance from points p to segments a–b, all (..., 2) broadcast together; shape (...)."""
    d = b - a
    t = np.clip(np.sum((p - a) * d, axis=-1) / np.maximum(np.sum(d * d, axis=-1), 1e-300), 0.0, 1.0)
    return np.linalg.norm(p - a - t[..., None] * d, axis=-1)


def distance_to_segments(points: np.ndarray, segments: np.ndarray) -> np.ndarray:
    """Distance (N,) from each of points (N, 2) to the nearest of segments (S, 2, 2), inf without any."""
    if len(segments) == 0:
        return np.full(len(points), np.inf)
    return point_segment_distance(points[:, None], segments[None, :, 0], segments[None, :, 1]).min(axis=1)


def segments_touch(a: np.ndarray, b: np.ndarray, tol: float) -> np.ndarray:
    """Pairs of segments a (S, 2, 2) and b (T, 2, 2) that meet other than at one shared end, (S, T) bool.

    Segments meet when they cross or come within ``tol`` of each other. Two segments whose
    ends coincide (within ``tol``) may meet there and nowhere else: each one's other end
    must stay ``tol`` away from the other segment (else they run along each other, as in a
    spike), and two segments sharing both ends coincide. So a set of segments in which no
    two touch is a planar drawing: simple outlines, tabs that neither overlap nor graze.
    """
    A, B = a[:, None], b[None]  # (S, 1, 2, 2), (1, T, 2, 2)
    shared = np.linalg.norm(A[:, :, :, None] - B[:, :, None, :], axis=-1) < tol  # (S, T, 2, 2): end i of a at end j of b
    a_shared, b_shared = shared.any(axis=3), shared.any(axis=2)  # (S, T, 2)
    da = point_segment_distance(A, B[:, :, None, 0], B[:, :, None, 1])  # ends of a to b, (S, T, 2)
    db = point_segment_distance(B, A[:, :, None, 0], A[:, :, None, 1])  # ends of b to a
    near = ((da < tol) & ~a_shared).any(axis=-1) | ((db < tol) & ~b_shared).any(axis=-1)
    p, r = A[..., 0, :], A[..., 1, :] - A[..., 0, :]
    q, s = B[..., 0, :], B[..., 1, :] - B[..., 0, :]
    cross = ((cross2(s, p - q) * cross2(s, p + r - q) < 0) & (cross2(r, q - p) * cross2(r, q + s - p) < 0))
    return near | (cross & ~a_shared.any(axis=-1)) | a_shared.all(axis=-1)


def segments_near_box(segments: np.ndarray, box_of: np.ndarray, tol: float) -> np.ndarray:
    """The segments (T, 2, 2) whose bounding boxes meet the bounding box of points ``box_of`` (..., 2)."""
    pts = box_of.reshape(-1, 2)
    lo, hi = pts.min(axis=0) - tol, pts.max(axis=0) + tol
    return segments[((segments.max(axis=1) >= lo) & (segments.min(axis=1) <= hi)).all(axis=1)]


def inside_loops(points: np.ndarray, segments: np.ndarray) -> np.ndarray:
    """Even-odd point-in-region test against closed loops given as segments, shape (N,)."""
    if len(points) == 0 or len(segments) == 0:
        return np.zeros(len(points), bool)
    a, b = segments[None, :, 0], segments[None, :, 1]
    x, y = points[:, None, 0], points[:, None, 1]
    straddle = (a[..., 1] > y) != (b[..., 1] > y)
    # left of the crossing point, without dividing by the segment's height
    side = (x - a[..., 0]) * (b[..., 1] - a[..., 1]) - (y - a[..., 1]) * (b[..., 0] - a[..., 0])
    left = np.where(b[..., 1] > a[..., 1], side < 0, side > 0)
    return (np.count_nonzero(straddle & left, axis=1) % 2) == 1


def min_area_rotation(points: np.ndarray) -> float:
    """Rotation (radians) that turns ``points`` (N, 2) to their minimum-area bounding box.

    Among rotations within 1e-6 of the minimum area, the one closest to a multiple of 90°
    is kept, so a sheet already aligned stays as it is.
    """
    from scipy.spatial import ConvexHull, QhullError

    try:
        hull = points[ConvexHull(points).vertices]
    except (QhullError, ValueError):
        return 0.0
    e = np.roll(hull, -1, axis=0) - hull
    ang = np.arctan2(e[:, 1], e[:, 0])
    c, s = np.cos(ang)[:, None], np.sin(ang)[:, None]
    u = hull[None, :, 0] * c + hull[None, :, 1] * s
    v = -hull[None, :, 0] * s + hull[None, :, 1] * c
    area = np.ptp(u, axis=1) * np.ptp(v, axis=1)
    near = np.flatnonzero(area <= area.min() * (1 + 1e-6))
    off = np.abs((ang[near] + math.pi / 4) % (math.pi / 2) - math.pi / 4)
    return float(-ang[near[np.argmin(off)]])
