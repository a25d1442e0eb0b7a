"""Glue tabs along the seams of a crease-pattern sheet: their pieces, outlines and the check that they fit.

For every seam id the tabs go on one side only (the layout, :func:`~curvefold.io.layout_sheets`,
chooses which). A seam is cut into pieces (:func:`tab_pieces`: at most ``tab_length``
long and turning at most :data:`TAB_MAX_TURN` each, split in the middle of a seam segment),
each a tapered tab (:func:`tab_outline`), so tabs bend along curved seams. Every piece is
checked as drawn (:func:`tab_fits`): one whose outline would cross or touch itself, its
sheet or another tab is narrowed (:data:`TAB_WIDTH_STEPS`) and, failing that, left out.
Lengths are page millimetres.
"""

from __future__ import annotations

import math

import numpy as np

from ._planar import distance_to_segments, inside_loops, polyline_segments, segments_near_box, segments_touch

__all__ = ["TAB_MAX_TURN", "TAB_WIDTH_STEPS", "tab_outline", "tab_pieces", "tab_fits"]

#: Largest turn of the seam along one tab piece, radians.
TAB_MAX_TURN = math.radians(30.0)
#: Widths tried for a tab piece, as fractions of the tab width, widest first.
TAB_WIDTH_STEPS = (1.0, 0.5, 0.25)


def tab_outline(base: np.ndarray, width: float, taper: float) -> tuple[np.ndarray, np.ndarray] | None:
    """A tapered tab on the right of ``base`` (m + 1, 2): (polygon, outer polyline) or None."""
    d = np.diff(base, axis=0)
    length = np.linalg.norm(d, axis=1)
    if length.sum() <= 0:
        return None
    t = d / np.maximum(length, 1e-300)[:, None]
    n = np.stack([t[:, 1], -t[:, 0]], axis=1)  # right-hand normals
    miter = np.concatenate([n[:1], (n[:-1] + n[1:]) / np.maximum(1 + np.sum(n[:-1] * n[1:], axis=1), 0.5)[:, None], n[-1:]])
    off = base + width * miter
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(off, axis=0), axis=1))])
    inset = min(width / math.tan(taper), 0.4 * s[-1])
    if s[-1] <= 0 or inset <= 0:
        return None
    a, b = inset, s[-1] - inset
    qa = np.array([np.interp(a, s, off[:, 0]), np.interp(a, s, off[:, 1])])
    qb = np.array([np.interp(b, s, off[:, 0]), np.interp(b, s, off[:, 1])])
    outer = np.concatenate([qa[None], off[(s > a) & (s < b)], qb[None]])
    polygon = np.concatenate([base, outer[::-1]])
    cut = np.concatenate([base[:1], outer, base[-1:]])
    return polygon, cut


def tab_pieces(points: np.ndarray, tab_length: float, min_length: float) -> list[np.ndarray]:
    """Split a seam chain (m + 1, 2) into pieces for separate tabs, each cut in the middle of a segment.

    Neighbouring tabs taper toward their common point. Where the seam is straight their
    tapered ends share 180°, leaving 180° − 2 × tab angle between them; at a vertex where the
    seam turns by φ toward the tabs they would share only 180° − φ, and touch or overlap
    once φ ≥ 180° − 2 × tab angle (a seam of few segments around a tight concave curve).
    """
    d = np.diff(points, axis=0)
    seg = np.linalg.norm(d, axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    ang = np.arctan2(d[:, 1], d[:, 0])
    turn = np.cumsum(np.abs((np.diff(ang) + math.pi) % (2 * math.pi) - math.pi))
    turn = np.concatenate([[0.0], turn, turn[-1:] if turn.size else [0.0]])  # per vertex
    count = max(1, math.ceil(s[-1] / tab_length - 1e-9), math.ceil(turn[-1] / TAB_MAX_TURN - 1e-9))
    count = max(1, min(count, int(s[-1] // min_length), len(seg)))
    # Split where arc length and turning (each normalised) reach equal shares: in the middle
    # of the segment where each share is reached.
    progress = s / s[-1] + (turn / turn[-1] if turn[-1] > 0 else 0.0)
    at = np.searchsorted(progress, progress[-1] * np.arange(1, count) / count, side="right") - 1
    at = np.unique(np.clip(at, 0, len(seg) - 1))
    refined = np.insert(points, at + 1, 0.5 * (points[at] + points[at + 1]), axis=0)
    bounds = [0, *(at + 1 + np.arange(len(at))).tolist(), len(refined) - 1]
    return [refined[i:j + 1] for i, j in zip(bounds[:-1], bounds[1:])]


def tab_fits(tab: tuple[np.ndarray, np.ndarray], outline: np.ndarray, accepted: list[np.ndarray], tol: float) -> bool:
    """Whether a tab may be drawn: its cut line is simple and keeps ``tol`` clear of the
    sheet's outline (S, 2, 2) and of the tabs already accepted, but for its two ends on the
    seam, and it neither lies inside them nor holds any of their corners.

    The sheet's outline and the accepted tabs near this one are tested together, in one
    array of segments: each test is one vectorised pass, whatever the number of tabs.
    """
    polygon, cut = tab
    segs = polyline_segments([(cut, False)])
    own = segments_touch(segs, segs, tol)
    np.fill_diagonal(own, False)
    if own.any():
        return False
    corners = cut[1:-1]
    mine = polyline_segments([(polygon, True)])
    lo, hi = polygon.min(axis=0) - tol, polygon.max(axis=0) + tol
    near = [accepted[k] for k in np.flatnonzero(_boxes_meet(accepted, lo, hi))]  # the others cannot touch it
    loops = [outline, *(polyline_segments([(p, True)]) for p in near)]  # the sheet (its loops, even-odd) and each tab
    group = np.repeat(np.arange(len(loops)), [len(loop) for loop in loops])
    others = np.concatenate(loops)
    close = segments_near_box(others, cut, tol)
    if segments_touch(segs, close, tol).any() or (distance_to_segments(corners, close) < tol).any():
        return False
    level = _straddling(others, corners)  # the others cannot cross a ray from a corner
    if inside_loops(corners, others[level], group[level]).any():
        return False
    theirs = others[:, 0][((others[:, 0] >= lo) & (others[:, 0] <= hi)).all(axis=1)]  # their corners in reach of this tab
    theirs = theirs[distance_to_segments(theirs, mine) >= tol]  # ... and off its outline
    return not inside_loops(theirs, mine).any()


def _boxes_meet(polygons: list[np.ndarray], lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Which of polygons (each (n, 2)) have bounding boxes meeting the box from ``lo`` to ``hi`` (2,), (P,) bool."""
    if not polygons:
        return np.zeros(0, bool)
    starts = np.cumsum([0] + [len(p) for p in polygons[:-1]])
    points = np.concatenate(polygons)
    return (np.maximum.reduceat(points, starts) >= lo).all(axis=1) & (np.minimum.reduceat(points, starts) <= hi).all(axis=1)


def _straddling(segments: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Which of segments (S, 2, 2) may cross the horizontal ray from one of points (N, 2): those from at or
    below the highest point to above the lowest (:func:`~curvefold.io._planar.inside_loops` counts no other)."""
    low, high = segments[:, :, 1].min(axis=1), segments[:, :, 1].max(axis=1)
    return (high > points[:, 1].min(initial=np.inf)) & (low <= points[:, 1].max(initial=-np.inf))
