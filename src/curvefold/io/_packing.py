"""Packing sheets onto pages: each sheet's minimum-area rectangle, first-fit on shelves, tallest
first.

Page millimetres; used by :func:`curvefold.io.layout_sheets`.
"""

from __future__ import annotations

import math

import numpy as np

from ..kernel._errors import InputError
from ._planar import bounding_box, min_area_rotations, rotation

__all__ = ["pack_pages", "shelf_pack"]


def pack_pages(footprints, avail, gap, margin, page, labels, page_name):
    """Shelf packing of the sheets' minimum-area rectangles: per sheet (page, rotation, offset).

    ``footprints`` are the points (n_i, 2) of each sheet (mm), ``avail`` the (width,
    height) inside a page's margins and footer, ``gap`` the space between sheets, ``page``
    the page's (width, height); ``labels`` and ``page_name`` name the sheets and the page
    in the message refusing a sheet that fits no page.

    Two passes, one laying every rectangle with its long side across the page and one
    standing it up where it fits; the pass with fewer pages (then the emptier last
    page) wins.
    """
    W, H = page
    rects = []
    for i, (pts, rot) in enumerate(zip(footprints, min_area_rotations(footprints))):
        lo, hi = bounding_box(pts @ rotation(rot).T)
        w, h = hi - lo
        if w < h:
            rot += math.pi / 2
            w, h = h, w
        lying, standing = (w <= avail[0] and h <= avail[1]), (h <= avail[0] and w <= avail[1])
        if not (lying or standing):
            raise InputError(
                f"sheet {labels[i]!r} needs {w:.1f} × {h:.1f} mm (with glue tabs) but the "
                f"{page_name} page ({W:g} × {H:g} mm) has {avail[0]:g} × {avail[1]:g} mm "
                "inside its margins; lower the scale or choose a larger page"
            )
        options = [(float(w), float(h), rot)] if lying else []
        if standing:
            options.append((float(h), float(w), rot + math.pi / 2))
        rects.append(options)
    best = None
    for stand in (False, True):
        prefs = [sorted(o, key=lambda t: -t[1] if stand else t[1]) for o in rects]
        got = shelf_pack(prefs, avail, gap)
        if best is None or got[1] < best[1]:
            best = got
    out = []
    for i, (pg, x, y_top, angle) in enumerate(best[0]):
        lo, hi = bounding_box(footprints[i] @ rotation(angle).T)
        out.append((pg, angle, np.array([margin + x - lo[0], H - margin - y_top - hi[1]])))
    return out


def shelf_pack(options, avail, gap):
    """First-fit decreasing-height shelves over pages.

    ``options[i]`` lists (width, height, rotation) of rectangle i, preferred first.
    Returns per rectangle (page, x from the left margin, y down from the top margin,
    rotation), and (page count, height used on the last page) to compare passes.
    """
    order = sorted(range(len(options)), key=lambda i: (-options[i][0][1], -options[i][0][0], i))
    shelves: list[list[float]] = []  # [page, top, height, used width]
    used: list[float] = []  # height used on each page
    out: list = [None] * len(options)
    for i in order:
        spot = None
        for shelf in shelves:
            for w, h, rot in options[i]:
                x = shelf[3] + (gap if shelf[3] > 0 else 0.0)
                if h <= shelf[2] + 1e-9 and x + w <= avail[0] + 1e-9:
                    spot = (shelf, x, w, rot)
                    break
            if spot:
                break
        if spot is None:
            w, h, rot = options[i][0]
            pg = next((p for p, u in enumerate(used) if u + gap + h <= avail[1] + 1e-9), None)
            if pg is None:
                used.append(0.0)
                pg, top = len(used) - 1, 0.0
            else:
                top = used[pg] + gap
            used[pg] = top + h
            shelves.append([pg, top, h, 0.0])
            spot = (shelves[-1], 0.0, w, rot)
        shelf, x, w, rot = spot
        shelf[3] = x + w
        out[i] = (int(shelf[0]), x, shelf[1], rot)
    return out, (len(used), used[-1])
