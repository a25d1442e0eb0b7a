"""Glue tabs along the seams of a crease-pattern sheet: their pieces, outlines and the check that
they fit.

For every seam id the tabs go on one side only (the layout, :func:`~curvefold.io.layout_sheets`,
chooses which). A seam is cut into pieces (:func:`tab_pieces`: at most ``tab_length``
long and turning at most :data:`TAB_MAX_TURN` each, split in the middle of a seam segment),
each a tapered tab (:func:`tab_outline`), so tabs bend along curved seams. Every piece is
checked as drawn (:func:`tab_fits`): one whose outline would cross or touch itself, its
sheet or another tab is narrowed (:data:`TAB_WIDTH_STEPS`) and, failing that, left out.
:func:`place_tabs` places a sheet's pieces in turn, testing the next ones together
(:func:`tabs_fit`). Lengths are page millimetres.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from ..kernel._arrays import distinct
from ._planar import (
    point_segment_distance,
    polyline_segments,
    ragged,
    ray_crossings,
    segment_pairs_touch,
)

__all__ = [
    "TAB_MAX_TURN",
    "TAB_WIDTH_STEPS",
    "tab_outline",
    "tab_outlines",
    "tab_pieces",
    "tab_fits",
    "tabs_fit",
    "place_tabs",
]

#: Largest turn of the seam along one tab piece, radians.
TAB_MAX_TURN = math.radians(30.0)
#: Widths tried for a tab piece, as fractions of the tab width, widest first.
TAB_WIDTH_STEPS = (1.0, 0.5, 0.25)


def tab_outline(
    base: np.ndarray, width: float, taper: float
) -> tuple[np.ndarray, np.ndarray] | None:
    """A tapered tab on the right of ``base`` (m + 1, 2): (polygon, outer polyline) or None."""
    return tab_outlines([base], width, taper)[0]


def tab_outlines(
    bases: list[np.ndarray], width: float, taper: float
) -> list[tuple[np.ndarray, np.ndarray] | None]:
    """The :func:`tab_outline` of each of ``bases`` (each (m_i + 1, 2)), found together: the
    pieces side by side, each padded with its last point (where its segments have length 0)."""
    if not bases:
        return []
    last = np.array([len(b) - 1 for b in bases])
    # (n, P): the point of each base at each place, its last past its end
    pad = np.minimum(np.arange(last.max() + 1), last[:, None])
    rows = np.arange(len(bases))[:, None]
    base = np.concatenate(bases)[(np.cumsum(last + 1) - last - 1)[:, None] + pad]  # (n, P, 2)
    d = np.diff(base, axis=1)
    length = np.linalg.norm(d, axis=2)
    t = d / np.maximum(length, 1e-300)[..., None]
    n = np.stack([t[..., 1], -t[..., 0]], axis=2)  # right-hand normals, 0 past the end
    miter = np.concatenate(
        [
            n[:, :1],
            (n[:, :-1] + n[:, 1:])
            / np.maximum(1 + np.sum(n[:, :-1] * n[:, 1:], axis=2), 0.5)[..., None],
            n[:, -1:],
        ],
        axis=1,
    )  # (at a last point before the end: its normal / 1)
    off = (base + width * miter)[rows, pad]
    s = np.concatenate(
        [
            np.zeros((len(bases), 1)),
            np.cumsum(np.linalg.norm(np.diff(off, axis=1), axis=2), axis=1),
        ],
        axis=1,
    )
    inset = np.minimum(width / math.tan(taper), 0.4 * s[:, -1])
    out: list[tuple[np.ndarray, np.ndarray] | None] = []
    for k, (m, a) in enumerate(zip(last.tolist(), inset.tolist())):
        along, offset = s[k, : m + 1], off[k, : m + 1]
        if length[k].sum() <= 0 or along[-1] <= 0 or a <= 0:
            out.append(None)
            continue
        b = along[-1] - a
        x, y = np.interp([a, b], along, offset[:, 0]), np.interp([a, b], along, offset[:, 1])
        outer = np.concatenate([[(x[0], y[0])], offset[(along > a) & (along < b)], [(x[1], y[1])]])
        out.append(
            (
                np.concatenate([bases[k], outer[::-1]]),
                np.concatenate([bases[k][:1], outer, bases[k][-1:]]),
            )
        )
    return out


def tab_pieces(points: np.ndarray, tab_length: float, min_length: float) -> list[np.ndarray]:
    """Split a seam chain (m + 1, 2) into pieces for separate tabs, each cut in the middle of a
    segment.

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
    at = distinct(np.clip(at, 0, len(seg) - 1))
    refined = np.insert(points, at + 1, 0.5 * (points[at] + points[at + 1]), axis=0)
    bounds = [0, *(at + 1 + np.arange(len(at))).tolist(), len(refined) - 1]
    return [refined[i : j + 1] for i, j in zip(bounds[:-1], bounds[1:])]


def tab_fits(
    tab: tuple[np.ndarray, np.ndarray], outline: np.ndarray, accepted: list[np.ndarray], tol: float
) -> bool:
    """Whether a tab may be drawn: its cut line is simple and keeps ``tol`` clear of the
    sheet's outline (S, 2, 2) and of the tabs already accepted, but for its two ends on the
    seam, and it neither lies inside them nor holds any of their corners."""
    return bool(tabs_fit([tab], outline, accepted, tol)[0])


def place_tabs(
    pieces: list[np.ndarray], outline: np.ndarray, width: float, taper: float, tol: float
) -> list[tuple[tuple[np.ndarray, np.ndarray], int] | None]:
    """For each seam piece in turn, the widest of its tabs (:data:`TAB_WIDTH_STEPS` × ``width``)
    that fits (:func:`tab_fits`) the sheet's outline (S, 2, 2) and the tabs placed before it:
    (tab, its step in the widths) or None.

    The same tabs as trying every piece in turn, found a batch at a time: the widest tabs of the
    next pieces are tested together as if all were placed, and those before the first that does not
    fit are.
    """
    widest = tab_outlines(pieces, width, taper)
    placed: list[tuple[tuple[np.ndarray, np.ndarray], int] | None] = []
    accepted: list[np.ndarray] = []
    while len(placed) < len(pieces):
        i = len(placed)
        batch = [
            tab
            for tab in itertools.takewhile(lambda tab: tab is not None, widest[i : i + _BATCH])
            if tab is not None
        ]
        fit = np.append(tabs_fit(batch, outline, accepted, tol), False)
        fitting = batch[: int(np.argmin(fit))]
        placed += [(tab, 0) for tab in fitting]
        accepted += [tab[0] for tab in fitting]
        if len(fitting) == _BATCH or len(placed) == len(pieces):
            continue
        piece, got = pieces[len(placed)], None  # its widest tab does not fit: try narrower ones
        for step, fraction in enumerate(TAB_WIDTH_STEPS[1:], 1):
            tab = tab_outline(piece, fraction * width, taper)
            if tab is not None and tab_fits(tab, outline, accepted, tol):
                got = (tab, step)
                accepted.append(tab[0])
                break
        placed.append(got)
    return placed


def tabs_fit(
    tabs: list[tuple[np.ndarray, np.ndarray]],
    outline: np.ndarray,
    accepted: list[np.ndarray],
    tol: float,
) -> np.ndarray:
    """Whether each of ``tabs`` (polygon, cut) may be drawn (:func:`tab_fits`) were the tabs before
    it in the list accepted too, (n,) bool.

    Every test is one vectorised pass over all the tabs: the segment pairs whose bounding boxes
    meet, the points in each tab's box, the rays from every corner.
    """
    n = len(tabs)
    if n == 0:
        return np.zeros(0, bool)
    rank = np.arange(n)
    lo, hi = _boxes([t[0] for t in tabs], tol)
    # those in reach of these tabs (no other can touch them, nor hold or lie inside them)
    if accepted:
        low, high = _boxes(accepted, 0.0)
        accepted = [
            accepted[k] for k in np.flatnonzero(_meet(low, high, lo.min(axis=0), hi.max(axis=0)))
        ]
    polygons = [*accepted, *(t[0] for t in tabs)]
    # the sheet's loops (even-odd), then each tab
    others = np.concatenate([outline, polyline_segments([(p, True) for p in polygons])])
    sizes = np.array([len(outline), *(len(p) for p in polygons)])
    # a tab sees the loops of lower rank
    seen_by = np.repeat(np.concatenate([np.full(1 + len(accepted), -1), rank]), sizes)
    start = np.cumsum(sizes) - sizes
    cut = polyline_segments([(t[1], False) for t in tabs])
    cut_count = np.array([len(t[1]) - 1 for t in tabs])
    cut_start = np.cumsum(cut_count) - cut_count
    # as many as its cut has segments, less one
    corners = np.concatenate([t[1][1:-1] for t in tabs])
    corner_tab, _ = ragged(cut_count - 1)
    corner_start = cut_start - rank
    bad = np.zeros(n, bool)
    # their boxes: segments whose boxes lie tol apart cannot touch
    low, high = np.minimum(others[:, 0], others[:, 1]), np.maximum(others[:, 0], others[:, 1])
    cut_low, cut_high = np.minimum(cut[:, 0], cut[:, 1]), np.maximum(cut[:, 0], cut[:, 1])

    # its cut line is simple: no two of its segments touch
    tab, place = ragged(cut_count * cut_count)
    first, second = (
        cut_start[tab] + place // cut_count[tab],
        cut_start[tab] + place % cut_count[tab],
    )
    pair = (first != second) & _meet(
        cut_low[first] - tol, cut_high[first] + tol, cut_low[second], cut_high[second]
    )
    bad[tab[pair][segment_pairs_touch(cut[first[pair]], cut[second[pair]], tol)]] = True

    # it keeps clear of the others near its cut
    cut_lo, cut_hi = _boxes([t[1] for t in tabs], tol)
    # (n, T)
    tab, other = np.nonzero(
        _meet(low[None], high[None], cut_lo[:, None], cut_hi[:, None])
        & (seen_by[None] < rank[:, None])
    )
    pairs, place = ragged(cut_count[tab])
    mine, theirs = cut_start[tab[pairs]] + place, other[pairs]
    pair = _meet(cut_low[mine] - tol, cut_high[mine] + tol, low[theirs], high[theirs])
    bad[tab[pairs][pair][segment_pairs_touch(cut[mine[pair]], others[theirs[pair]], tol)]] = True
    pairs, place = ragged(cut_count[tab] - 1)
    mine, theirs = corners[corner_start[tab[pairs]] + place], other[pairs]
    pair = _meet(mine - tol, mine + tol, low[theirs], high[theirs])
    bad[
        tab[pairs][pair][
            point_segment_distance(mine[pair], others[theirs[pair], 0], others[theirs[pair], 1])
            < tol
        ]
    ] = True

    # none of its corners lies inside the sheet's outline (even-odd) or another tab
    corner, other = np.nonzero(
        (seen_by[None] < corner_tab[:, None])
        # (on a level)
        & (
            (others[None, :, 0, 1] > corners[:, None, 1])
            != (others[None, :, 1, 1] > corners[:, None, 1])
        )
    )
    crossing = ray_crossings(corners[corner], others[other, 0], others[other, 1])
    loop = np.repeat(np.arange(len(sizes)), sizes)
    counts = np.bincount(
        corner[crossing] * len(sizes) + loop[other[crossing]], minlength=len(corners) * len(sizes)
    )
    bad[corner_tab[(counts.reshape(len(corners), -1) % 2 == 1).any(axis=1)]] = True

    # it holds no corner of the others in reach (but those on its outline)
    tab, point = np.nonzero(
        _meet(others[None, :, 0], others[None, :, 0], lo[:, None], hi[:, None])
        & (seen_by[None] < rank[:, None])
    )
    own = sizes[1 + len(accepted) :]  # the segments of each tab's outline
    pairs, place = ragged(own[tab])
    if pairs.size:
        mine = others[start[1 + len(accepted) + tab[pairs]] + place]
        p, bounds = others[point[pairs], 0], np.cumsum(own[tab]) - own[tab]
        clear = (
            np.minimum.reduceat(point_segment_distance(p, mine[:, 0], mine[:, 1]), bounds) >= tol
        )
        inside = (
            np.add.reduceat(ray_crossings(p, mine[:, 0], mine[:, 1]), bounds, dtype=np.intp) % 2
            == 1
        )
        bad[tab[clear & inside]] = True
    return ~bad


#: Tabs tested together by :func:`place_tabs`.
_BATCH = 32


def _boxes(polylines: list[np.ndarray], tol: float) -> tuple[np.ndarray, np.ndarray]:
    """Corners (n, 2) of the bounding boxes of polylines (each (m, 2), m > 0), ``tol`` wider."""
    starts = np.cumsum([0] + [len(p) for p in polylines[:-1]])
    points = np.concatenate(polylines)
    return np.minimum.reduceat(points, starts) - tol, np.maximum.reduceat(points, starts) + tol


def _meet(low: np.ndarray, high: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Whether the boxes from ``low`` to ``high`` meet those from ``lo`` to ``hi``, all (..., 2)
    broadcast together; shape (...)."""
    return (
        (high[..., 0] >= lo[..., 0])
        & (low[..., 0] <= hi[..., 0])
        & (high[..., 1] >= lo[..., 1])
        & (low[..., 1] <= hi[..., 1])
    )
