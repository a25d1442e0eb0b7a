"""Labels of crease-pattern sheets: the sheet's name and, beside every seam, its name, placed clear
of the lines.

A :class:`Label` is a line of text centred on a point of the page (mm). Each sheet's label
goes near its middle, along the local direction of its lines; each seam's name
(:func:`seam_name`, the same on both sheets it joins) goes inside the sheet beside the
middle of the seam, parallel to it. Labels shrink, down to :data:`MIN_LABEL_SIZE`, to
keep a quarter of their height clear of every line (:class:`Obstacles`); text widths are
estimated by :func:`text_width`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..kernel._errors import InternalError
from ._pdf_font import WIDTHS
from ._planar import (
    box_corners,
    cell_index,
    cell_key,
    near_any,
    nearest_points,
    point_segment_distance,
    ragged,
    upright,
)

__all__ = [
    "MIN_LABEL_SIZE",
    "Label",
    "seam_name",
    "text_width",
    "Obstacles",
    "label_sizes",
    "label_candidates",
    "seam_label",
    "sheet_label",
]

#: Smallest label size (em height, mm) used before a label is placed regardless of lines.
MIN_LABEL_SIZE = 1.5


def seam_name(seam_id: int) -> str:
    """The label printed beside seam ``seam_id`` on both sheets it joins.

    Examples
    --------
    >>> seam_name(0), seam_name(12)
    ('S0', 'S12')
    """
    return f"S{int(seam_id)}"


def text_width(text: str, size: float) -> float:
    """Estimated advance width of ``text`` set in a sans-serif font of em height ``size``.

    A per-character estimate (DejaVu Sans / Arial proportions, rounded up) used to keep
    labels clear of lines, never narrower than the text set in DejaVu Sans (the font the PDF
    embeds and the SVG names first, :data:`curvefold.io._pdf_font.WIDTHS`); writers set text
    in a sans-serif font at this em height.

    Examples
    --------
    >>> round(text_width("S12", 10.0), 3), round(text_width("mm", 10.0), 3)
    (19.07, 19.48)
    """
    em = sum(
        [
            0.36 if c in _NARROW else 0.95 if c in _WIDE else 0.74 if c.isupper() else 0.64
            for c in text
        ]
    )
    unknown = WIDTHS["?"]
    return max(em, 0.001 * sum(WIDTHS.get(c, unknown) for c in text)) * size


_NARROW, _WIDE = frozenset(" .,:;·|!'ijlrtf1()-"), frozenset("MWmw@%")


@dataclass(frozen=True)
class Label:
    """A line of text centred on ``position``.

    Attributes
    ----------
    text : str
    position : tuple of float
        Centre of the text box, page mm.
    angle : float
        Direction of the baseline in degrees, counter-clockwise from +x, in (-90, 90].
    size : float
        Em height in mm (the font size).
    kind : str
        ``"sheet"`` or ``"seam"``.
    seam : int
        The seam id for seam labels, else -1.
    """

    text: str
    position: tuple[float, float]
    angle: float
    size: float
    kind: str = "sheet"
    seam: int = -1

    def transformed(self, matrix: np.ndarray, offset: np.ndarray) -> Label:
        """The label mapped by the rotation ``matrix`` and ``offset`` (kept upright)."""
        p = matrix @ np.asarray(self.position) + offset
        turn = math.degrees(math.atan2(matrix[1, 0], matrix[0, 0]))
        return Label(
            self.text,
            (float(p[0]), float(p[1])),
            upright(self.angle + turn),
            self.size,
            self.kind,
            self.seam,
        )

    def corners(self) -> np.ndarray:
        """The estimated text box, shape (4, 2): width from :func:`text_width`, height = size."""
        return box_corners(
            np.asarray(self.position),
            math.radians(self.angle),
            text_width(self.text, self.size),
            self.size,
        )


def _box_grid(text: str, size: float) -> tuple[np.ndarray, np.ndarray]:
    """The box's sample points along its baseline (m,) and across it (5,), from its centre, mm."""
    width = text_width(text, size)
    # a line between two points of a box comes within 0.2 size of one: caught by the 0.25 size
    # clearance
    step = 0.4 * size
    return np.linspace(-width / 2, width / 2, max(2, math.ceil(width / step) + 1)), np.linspace(
        -size / 2, size / 2, 5
    )


def label_candidates(center: np.ndarray, angle: np.ndarray, text: str, size: float) -> np.ndarray:
    """Sample points covering the text boxes, shape (C, K, 2): K = 5·m, row by row across the
    baseline (``_box_grid``)."""
    return _grid_points(center, angle, *_box_grid(text, size))


def _grid_points(center: np.ndarray, angle: np.ndarray, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The points (C, len(u)·len(v), 2) of the grid ``u`` × ``v`` (row by row) around each centre
    (C, 2), turned by ``angle`` (C,)."""
    uu, vv = np.tile(u, len(v)), np.repeat(v, len(u))
    c, s = np.cos(angle)[:, None], np.sin(angle)[:, None]
    return np.stack(
        [center[:, None, 0] + uu * c - vv * s, center[:, None, 1] + uu * s + vv * c], axis=-1
    )


class Obstacles:
    """Lines that labels keep clear of: a sheet's lines sampled densely for nearest-point
    queries, and a few more segments (the labels placed so far) measured exactly."""

    points: np.ndarray  # (N, 2) the lines sampled
    directions: np.ndarray  # (N, 2) the unit direction of each sample's line
    _x: np.ndarray  # (N,) the samples' coordinates apart
    _y: np.ndarray
    # nearest_points' index of the samples
    _cells: tuple[np.ndarray, float, np.ndarray, np.ndarray, np.ndarray]
    # near_any's, by the cells' side
    _grids: dict[float, tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]

    def __init__(
        self,
        segments: np.ndarray,
        spacing: float,
        extra: np.ndarray | None = None,
        *,
        _from: Obstacles | None = None,
    ):
        self.spacing = spacing
        self.extra = (
            np.zeros((0, 2, 2)) if extra is None else np.asarray(extra, float).reshape(-1, 2, 2)
        )
        if _from is not None:  # share the sampled lines of another
            self.points, self.directions, self._cells, self._grids = (
                _from.points,
                _from.directions,
                _from._cells,
                _from._grids,
            )
            self._x, self._y = _from._x, _from._y
            return
        self._grids = {}  # the points bucketed in finer cells, by their side (:meth:`blocked`)
        (ax, ay), (dx, dy) = segments[:, 0].T, (segments[:, 1] - segments[:, 0]).T
        length = np.sqrt(dx * dx + dy * dy)
        count = np.maximum(1, np.ceil(length / spacing).astype(int))
        seg, place = ragged(count + 1)
        t = place / count[seg]
        self._x, self._y = ax[seg] + t * dx[seg], ay[seg] + t * dy[seg]  # (apart: gathered faster)
        self.points = np.stack([self._x, self._y], axis=1)
        self.directions = (np.stack([dx, dy], axis=1) / np.maximum(length, 1e-300)[:, None])[seg]
        origin, side = (
            (np.array([self._x.min(), self._y.min()]) if len(self.points) else np.zeros(2)),
            20.0 * spacing,
        )
        # the points bucketed in cells
        self._cells = (origin, side, *cell_index(self.points, origin, side))

    def plus(self, segments: np.ndarray) -> Obstacles:
        """These obstacles and ``segments`` (S, 2, 2) besides, without sampling the lines again."""
        return Obstacles(
            np.zeros((0, 2, 2)), self.spacing, np.concatenate([self.extra, segments]), _from=self
        )

    def clearance(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Distance to the nearest obstacle (a sampled line's less half the spacing) and its
        direction."""
        shape = points.shape[:-1]
        flat = points.reshape(-1, 2)
        found_dist, idx = nearest_points(self.points, flat, index=self._cells)
        found = idx < len(self.points)
        dist = np.where(found, found_dist - self.spacing / 2, np.inf)
        direction = np.where(
            found[:, None], self.directions[np.where(found, idx, 0)], np.array([1.0, 0.0])
        )
        if len(self.extra):
            a, b = self.extra[:, 0], self.extra[:, 1]
            to_extra = point_segment_distance(flat[:, None], a[None], b[None])  # (N, S)
            nearest = np.argmin(to_extra, axis=1)
            exact = to_extra[np.arange(len(flat)), nearest]
            closer = exact < dist
            d = b - a
            along = d / np.maximum(np.linalg.norm(d, axis=1), 1e-300)[:, None]
            dist = np.where(closer, exact, dist)
            direction = np.where(closer[:, None], along[nearest], direction)
        return dist.reshape(shape), direction.reshape(shape + (2,))

    def _nearest_to_boxes(
        self,
        boxes: np.ndarray,
        grid: tuple[np.ndarray, np.ndarray],
        center: np.ndarray,
        angle: np.ndarray,
        limit: float,
        bounds: tuple[np.ndarray, np.ndarray],
    ) -> np.ndarray:
        """For boxes (C, K, 2) of :func:`label_candidates`: the smallest distance from their points
        to the sampled lines if below ``limit``, else inf, (C,). ``bounds`` are the boxes'
        :func:`_bounds` for ``limit``.

        The distance of the nearest point to each box point, to the last bit (as
        :func:`~curvefold.io._planar.nearest_points` measures it), without measuring every pair:
        a sampled point near a box is measured only to the four box points around it in the
        box's grid, one of them its nearest.
        """
        u, v = grid
        origin, side, order, keys, cells = self._cells
        reach = np.floor((np.stack(bounds, axis=1) - origin) / side)
        # the cells around each box, (C, 2) each
        lo, hi = (np.clip(reach[:, k], 0, cells - 1).astype(np.int64) for k in (0, 1))
        box, place = ragged(np.maximum(hi[:, 0] - lo[:, 0] + 1, 0))  # a column of cells, per box
        column = np.stack([lo[box, 0] + place, lo[box, 1]], axis=1)
        first = np.searchsorted(keys, cell_key(column), "left")
        column[:, 1] = hi[box, 1]
        group, place = ragged(
            np.maximum(np.searchsorted(keys, cell_key(column), "right") - first, 0)
        )
        box, near = box[group], order[first[group] + place]
        x, y = np.take(self._x, near), np.take(self._y, near)
        rx, ry = (
            x - np.take(np.ascontiguousarray(center[:, 0]), box),
            y - np.take(np.ascontiguousarray(center[:, 1]), box),
        )
        c, s = np.take(np.cos(angle), box), np.take(np.sin(angle), box)
        frame = rx * c + ry * s, ry * c - rx * s  # in the box's frame
        slack = limit * (1 + 1e-9)
        # within reach of the box
        keep = (np.abs(frame[0]) <= u[-1] + slack) & (np.abs(frame[1]) <= v[-1] + slack)
        box, x, y = box[keep], x[keep], y[keep]
        grid_cell = [
            np.clip(np.floor((f[keep] - g[0]) / (g[1] - g[0])).astype(np.int64), 0, len(g) - 2)
            for f, g in zip(frame, (u, v))
        ]
        # the corner (0, 0) of the grid's cell around each point
        at = box * boxes.shape[1] + grid_cell[1] * len(u) + grid_cell[0]
        corners_x, corners_y = boxes[..., 0].ravel(), boxes[..., 1].ravel()
        best = np.full(len(box), np.inf)
        for step in (0, 1, len(u), len(u) + 1):
            dx, dy = np.take(corners_x, at + step) - x, np.take(corners_y, at + step) - y
            best = np.minimum(best, dx * dx + dy * dy)
        out = np.full(len(boxes), np.inf)
        np.minimum.at(out, box, best)
        out = np.sqrt(out)  # the distance of the nearest, as measured between the two points
        return np.where(out < limit, out, np.inf)

    def blocked(self, center: np.ndarray, angle: np.ndarray, text: str, size: float) -> np.ndarray:
        """Which boxes of :meth:`fits` surely do not keep clear, (C,) bool: a sampled line's point
        nearer than 0.25·size (and half the spacing, less a rounding's margin) to one of five
        points on either long side. Cheaper than :meth:`fits`; a box it passes may still not fit."""
        if len(self.points) == 0:
            return np.zeros(len(center), bool)
        reach = (0.25 * size + self.spacing / 2) * (1 - 1e-9)
        if reach not in self._grids:
            origin = self._cells[0]  # below and left of every point
            self._grids[reach] = (origin, *cell_index(self.points, origin, reach))
        u, v = _box_grid(text, size)
        points = _grid_points(
            center, angle, u[[0, len(u) // 4, len(u) // 2, 3 * len(u) // 4, -1]], v[[0, -1]]
        )
        near = near_any(self.points, points.reshape(-1, 2), reach, self._grids[reach])
        return np.asarray(near.reshape(len(center), -1).any(axis=1))

    def fits(
        self, center: np.ndarray, angle: np.ndarray, text: str, size: float
    ) -> tuple[np.ndarray, np.ndarray]:
        """For the boxes of ``text`` at ``size`` centred on ``center`` (C, 2) along ``angle``
        (C,) radians: whether each keeps 0.25·size clear of every line, and its margin
        (counted up to one ``size``)."""
        grid = _box_grid(text, size)
        boxes = _grid_points(center, angle, *grid)
        lo, hi = _bounds(boxes, len(grid[0]), size)
        worst = (
            self._nearest_to_boxes(boxes, grid, center, angle, size, (lo, hi)) - self.spacing / 2
        )
        # each box against the extra segments whose bounding boxes come within size of its own
        if len(self.extra):
            box, segment = np.nonzero(
                (
                    (self.extra.max(axis=1)[None] >= lo[:, None])
                    & (self.extra.min(axis=1)[None] <= hi[:, None])
                ).all(axis=2)
            )
            # (pairs, K)
            exact = point_segment_distance(
                boxes[box], self.extra[segment, None, 0], self.extra[segment, None, 1]
            )
            nearest = np.full(len(boxes), np.inf)
            np.minimum.at(
                nearest, box, np.where(exact <= size, exact, np.inf).min(axis=1, initial=np.inf)
            )
            worst = np.minimum(worst, nearest)
        worst = np.minimum(worst, size)
        return worst >= 0.25 * size, worst


def _bounds(boxes: np.ndarray, m: int, reach: float) -> tuple[np.ndarray, np.ndarray]:
    """Corners (C, 2) of boxes around the points of boxes (C, 5·m, 2) (:func:`label_candidates`),
    ``reach`` wider (and a little more: they are found from the four corner points, those of a
    straight grid)."""
    corners = boxes[:, [0, m - 1, -m, -1]]
    reach = reach * (1 + 1e-9) + 1e-9 * float(np.abs(corners).max(initial=1.0))
    return corners.min(axis=1) - reach, corners.max(axis=1) + reach


def _best_box(
    obstacles: Obstacles,
    center: np.ndarray,
    angle: np.ndarray,
    middle: np.ndarray,
    text: str,
    h: float,
) -> int | None:
    """The candidate box that keeps clear of the lines with the best score: its margin (up to
    one ``h``) less a twentieth of its distance to ``middle``; None if none keeps clear.

    Candidates are measured nearest the middle first, in batches, until no candidate left
    could score above the best so far (a score is at most h less a twentieth of the
    distance): the same choice as measuring them all, ties going to the first candidate.
    """
    away = np.linalg.norm(center - middle, axis=1)
    order = np.argsort(away, kind="stable")
    # (they would score -inf)
    order = order[~obstacles.blocked(center[order], angle[order], text, h)]
    score = np.full(len(center), -np.inf)
    best = -np.inf
    for start in range(0, len(order), 16):
        if h - 0.05 * away[order[start]] < best:
            break
        batch = order[start : start + 16]
        ok, worst = obstacles.fits(center[batch], angle[batch], text, h)
        score[batch] = np.where(ok, np.minimum(worst, h) - 0.05 * away[batch], -np.inf)
        best = max(best, float(score[batch].max()))
    return int(np.argmax(score)) if np.isfinite(best) else None


def label_sizes(preferred: float) -> list[float]:
    out, s = [], preferred
    while s > MIN_LABEL_SIZE:
        out.append(s)
        s *= 0.8
    return out + [MIN_LABEL_SIZE]


def seam_label(
    points: np.ndarray, seam: int, obstacles: Obstacles, size: float
) -> tuple[Label, bool]:
    """The name of seam ``seam`` inside the sheet beside the middle of its chain ``points`` (m +
    1, 2) (the sheet on their left), parallel to it, and whether it keeps clear of every line."""
    text = seam_name(seam)
    p = points
    d = np.diff(p, axis=0)
    seg = np.linalg.norm(d, axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    offsets = np.array([0.0, 0.05, -0.05, 0.1, -0.1, 0.17, -0.17, 0.25, -0.25, 0.33, -0.33])
    fallback = None
    for h in label_sizes(size):
        at = s[-1] * (0.5 + offsets)
        k = np.clip(np.searchsorted(s, at, side="right") - 1, 0, len(seg) - 1)
        t = d[k] / np.maximum(seg[k], 1e-300)[:, None]
        base = p[k] + t * (at - s[k])[:, None]
        left = np.stack([-t[:, 1], t[:, 0]], axis=1)
        gaps = np.array([0.85, 1.2, 1.7]) * h
        center = (base[:, None] + gaps[None, :, None] * left[:, None]).reshape(-1, 2)
        angle = np.repeat(np.arctan2(t[:, 1], t[:, 0]), len(gaps))
        if fallback is None:
            fallback = Label(
                text,
                tuple(center[0]),
                upright(math.degrees(angle[0])),
                MIN_LABEL_SIZE,
                "seam",
                seam,
            )
        # candidates are in order of preference: the first that keeps clear
        for first in range(0, len(center), 12):
            ok, _ = obstacles.fits(center[first : first + 12], angle[first : first + 12], text, h)
            if ok.any():
                i = first + int(np.argmax(ok))
                return Label(
                    text,
                    (float(center[i, 0]), float(center[i, 1])),
                    upright(math.degrees(angle[i])),
                    h,
                    "seam",
                    seam,
                ), True
    if fallback is None:  # pragma: no cover - label_sizes gives at least one size
        raise InternalError(f"no label size to try for seam {seam}")
    return fallback, False


def sheet_label(
    text: str, centroids: np.ndarray, areas: np.ndarray, obstacles: Obstacles, size: float
) -> tuple[Label, bool]:
    """The sheet's label: clear of every line, along the local direction, near the middle.

    Candidates are triangle centroids (C, 2); among the boxes that keep clear of the lines
    the one with the best clearance (counted up to one em) less a twentieth of its distance
    to the sheet's area centroid wins, so labels sit in the middle unless it is crowded.
    """
    middle = (centroids * areas[:, None]).sum(axis=0) / max(areas.sum(), 1e-300)
    if len(centroids) > 1500:
        centroids = centroids[:: math.ceil(len(centroids) / 1500)]
    dist, direction = obstacles.clearance(centroids)
    best = int(np.argmax(dist))
    for h in label_sizes(size):
        keep = np.flatnonzero(dist >= 0.75 * h)
        keep = keep[np.argsort(-dist[keep])][:80]
        if keep.size == 0:
            continue
        along = np.arctan2(direction[keep, 1], direction[keep, 0])
        center = np.concatenate([centroids[keep], centroids[keep]])
        angle = np.concatenate([along, np.zeros(keep.size)])
        found = _best_box(obstacles, center, angle, middle, text, h)
        if found is not None:
            return Label(
                text,
                (float(center[found, 0]), float(center[found, 1])),
                upright(math.degrees(angle[found])),
                h,
            ), True
    along = math.degrees(math.atan2(direction[best, 1], direction[best, 0]))
    return Label(
        text, (float(centroids[best, 0]), float(centroids[best, 1])), upright(along), MIN_LABEL_SIZE
    ), False
