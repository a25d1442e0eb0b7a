"""What a cutting machine needs beyond the drawing: perforated creases and kerf compensation.

* :func:`perforation_dashes`: for machines that only cut (cutting plotters, a laser without
  a scoring setting), each crease becomes a row of short cuts of a given dash length and
  gap, real geometry rather than a line style. Valley creases are even dashes; mountain
  creases alternate a dash and a third of a dash, so the two read apart once cut. The
  row starts and ends half a gap inside the crease's ends, so no cut reaches the outline.
* :func:`offset_outline`: a cutter removes a kerf of material along the line it follows;
  moving each cut outline outward by half the kerf keeps the parts at their drawn size.
  Corners are mitred, and bevelled where the mitre would reach past four times the offset.
* :func:`prepare_layout`: both applied to every sheet of a layout.

Lengths are page millimetres.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..kernel._errors import InputError
from ._layout import Layout, Page, Polyline
from ._planar import cross2

__all__ = [
    "MITRE_LIMIT",
    "perforation_dashes",
    "offset_outline",
    "prepare_layout",
    "check_perforation",
    "check_kerf",
]

#: Longest mitre of an offset corner, as a multiple of the offset; sharper corners are bevelled.
MITRE_LIMIT = 4.0


def check_perforation(perforation) -> tuple[float, float] | None:
    """``None`` or a (dash, gap) pair of positive finite millimetres."""
    if perforation is None:
        return None
    try:
        dash, gap = (float(v) for v in perforation)
    except (TypeError, ValueError):
        raise InputError(
            f"perforation must be a (dash, gap) pair of lengths in mm, got {perforation!r}",
            parameter="perforation",
        ) from None
    if not (math.isfinite(dash) and math.isfinite(gap) and dash > 0 and gap > 0):
        raise InputError(
            f"perforation dash and gap must be positive and finite mm, got {perforation!r}",
            parameter="perforation",
        )
    return dash, gap


def check_kerf(kerf) -> float:
    """A kerf width: a non-negative finite number of millimetres."""
    if (
        isinstance(kerf, bool)
        or not isinstance(kerf, (int, float))
        or not math.isfinite(kerf)
        or kerf < 0
    ):
        raise InputError(
            f"kerf must be a non-negative number of mm, got {kerf!r}", parameter="kerf"
        )
    return float(kerf)


def perforation_dashes(
    points: np.ndarray, dash: float, gap: float, *, mountain: bool = False
) -> list[np.ndarray]:
    """The cuts (each (k, 2)) that perforate an open polyline ``points`` (n, 2).

    Examples
    --------
    >>> line = np.array([[0.0, 0.0], [10.0, 0.0]])
    >>> [d[:, 0].tolist() for d in perforation_dashes(line, 2.0, 1.0)]
    [[0.5, 2.5], [3.5, 5.5], [6.5, 8.5]]
    >>> perforation_dashes(line[:1], 2.0, 1.0)
    []
    """
    points = np.asarray(points, float)
    if len(points) < 2:
        return []
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])
    end = s[-1] - 0.5 * gap
    lengths = (dash, dash / 3.0) if mountain else (dash,)
    out, at, k = [], 0.5 * gap, 0
    while at < end:
        a, b = at, min(at + lengths[k % len(lengths)], end)
        inside = (s > a) & (s < b)
        piece = np.concatenate(
            [
                [np.array([np.interp(a, s, points[:, 0]), np.interp(a, s, points[:, 1])])],
                points[inside],
                [np.array([np.interp(b, s, points[:, 0]), np.interp(b, s, points[:, 1])])],
            ]
        )
        out.append(piece)
        at, k = b + gap, k + 1
    return out


def offset_outline(points: np.ndarray, distance: float) -> np.ndarray:
    """A closed outline (n, 2), not repeating its first point, moved outward by ``distance``.

    Outward is away from the region it encloses (either turning sense). Each side moves
    parallel to itself; neighbouring sides meet at their mitre, or where that lies past
    :data:`MITRE_LIMIT` × ``distance`` at two bevel points.

    Examples
    --------
    >>> square = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])
    >>> offset_outline(square, 0.5).tolist()
    [[-0.5, -0.5], [2.5, -0.5], [2.5, 2.5], [-0.5, 2.5]]
    """
    p = np.asarray(points, float)
    if distance == 0 or len(p) < 3:
        return p.copy()
    area2 = float(np.sum(cross2(p, np.roll(p, -1, axis=0))))
    d = np.roll(p, -1, axis=0) - p  # side i runs from p_i to p_{i+1}
    t = d / np.maximum(np.linalg.norm(d, axis=1), 1e-300)[:, None]
    # outward normals of the sides
    n = np.stack([t[:, 1], -t[:, 0]], axis=1) * (1.0 if area2 > 0 else -1.0)
    before, after = np.roll(n, 1, axis=0), n  # at vertex i: side i − 1 and side i
    cosine = np.sum(before * after, axis=1)
    mitre = (before + after) / np.maximum(1.0 + cosine, 1e-300)[:, None]
    sharp = np.linalg.norm(mitre, axis=1) > MITRE_LIMIT
    corners = p[:, None] + distance * np.where(
        sharp[:, None, None], np.stack([before, after], axis=1), mitre[:, None]
    )
    counts = np.where(sharp, 2, 1)
    keep = np.repeat(np.arange(len(p)), counts) * 2 + np.concatenate([np.arange(c) for c in counts])
    return corners.reshape(-1, 2)[keep]


def prepare_layout(layout: Layout, *, perforation=None, kerf: float = 0.0) -> Layout:
    """The layout with its creases perforated (``perforation`` = (dash, gap) mm) and its cut
    outlines moved out by half the ``kerf`` (mm); the same layout when neither is asked."""
    perforation = check_perforation(perforation)
    kerf = check_kerf(kerf)
    if perforation is None and kerf == 0:
        return layout

    def lines(p: Polyline) -> list[Polyline]:
        if p.layer == "cut" and p.closed and kerf > 0:
            return [Polyline("cut", offset_outline(p.points, 0.5 * kerf), True)]
        if p.layer in ("mountain", "valley") and perforation is not None:
            points = np.concatenate([p.points, p.points[:1]]) if p.closed else p.points
            return [
                Polyline(p.layer, d)
                for d in perforation_dashes(points, *perforation, mountain=p.layer == "mountain")
            ]
        return [p]

    pages = tuple(
        Page(
            page.size,
            tuple(
                replace(s, polylines=tuple(q for p in s.polylines for q in lines(p)))
                for s in page.sheets
            ),
        )
        for page in layout.pages
    )
    return replace(layout, pages=pages, perforation=perforation, kerf=kerf)
