"""Crease patterns laid out on printable pages: placement, glue tabs, layers and labels.

A tube is two developed sheets welded along seam curves; :func:`layout_sheets` places any
number of such sheets on pages of a given size, adds glue tabs along the seams and sorts
every line into a fabrication layer. The writers in :mod:`curvefold.io.pattern` turn
the resulting :class:`Layout` into SVG, DXF and PDF.

Coordinates and units
    Everything in a :class:`Layout` is in millimetres on the page, origin at the page's
    bottom-left corner, x to the right, y up (the DXF and PDF convention; SVG flips y when
    it writes). The lengths given to :func:`layout_sheets` are in its ``units``;
    ``scale`` multiplies model units into those units.

Which side is up
    Each sheet is drawn as seen from the side its face normals point to (triangles
    counter-clockwise), so mountain and valley read as assigned in the mesh (FOLD's
    convention). A sheet whose triangles are clockwise in the xy-plane is mirrored.
    Sheets are otherwise only rotated and translated, never scaled unevenly.

Layers, drawn bottom to top (:data:`LAYERS`)
    ====================  ================================================================
    ``glue``              glue tab areas, filled polygons (a guide: no line to cut);
    ``rulings``           straight rulings, for scoring or engraving (writers skip it by default);
    ``seam``              the fold line of each glue tab, i.e. the seam on the tab side;
    ``valley``            fold creases assigned ``V``;
    ``mountain``          fold creases assigned ``M``;
    ``cut``               everything to cut through: each sheet's closed outline (boundary and
                          seam edges) going around the outer sides of its glue tabs;
    ``labels``            the sheet label and, inside the sheet beside the middle of every seam
                          chain, the seam's name (:func:`seam_name`), the same on both partners.
    ====================  ================================================================

No line appears in two layers, so a laser never cuts or scores a line twice. Triangulating
diagonals are never drawn.

Glue tabs
    For every seam id the tabs go on one side only, the sheet with the lowest index that
    has the seam, so that the partner sheet overlaps the tab when glued. A seam whose
    chains all lie on one sheet gets its tab on the first chain only. Tabs are cut into
    pieces (at most ``tab_length`` long and turning at most 30° each, split in the middle
    of a seam segment) with tapered ends, so they bend along curved seams. Every piece is
    checked as drawn: one whose outline would cross or touch itself, its sheet or another
    tab is narrowed (½, ¼ of ``tab_width``) and, failing that, left out; both are reported
    in :attr:`Layout.notes`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from ..geometry.mesh import edges_faces
from ..geometry.sheets import PatternSheet
from ..kernel.arrays import frozen
from ..kernel.errors import InputError
from .tables import mm_per_unit, page_mm

__all__ = [
    "FOOTER",
    "LAYERS",
    "Label",
    "Layout",
    "Page",
    "PlacedSheet",
    "Polyline",
    "layout_sheets",
    "page_size",
    "seam_name",
    "text_width",
]

#: Layer names, bottom to top.
LAYERS = ("glue", "rulings", "seam", "valley", "mountain", "cut", "labels")

#: Smallest label size (em height, mm) used before a label is placed regardless of lines.
MIN_LABEL_SIZE = 1.5
#: Height (mm) of the band above a page's bottom margin kept for its scale bar and legend.
FOOTER = 14.0

_TAB_MAX_TURN = math.radians(30.0)
_TAB_WIDTH_STEPS = (1.0, 0.5, 0.25)


def seam_name(seam_id: int) -> str:
    """The label printed beside seam ``seam_id`` on both sheets it joins.

    Examples
    --------
    >>> seam_name(0), seam_name(12)
    ('S0', 'S12')
    """
    return f"S{int(seam_id)}"


def page_size(page: str | tuple[float, float], *, units: str = "mm") -> tuple[float, float]:
    """Page (width, height) in mm from a name in :data:`~curvefold.io.tables.PAGES` or a pair in ``units``.

    Examples
    --------
    >>> page_size("a4")
    (210.0, 297.0)
    >>> page_size((8.5, 11), units="in")
    (215.9, 279.4)
    """
    f = mm_per_unit(units)
    if isinstance(page, str):
        return page_mm(page)
    try:
        w, h = (float(v) for v in page)
    except (TypeError, ValueError):
        raise InputError(f"page must be a name or a (width, height) pair, got {page!r}") from None
    if not (math.isfinite(w) and math.isfinite(h) and w > 0 and h > 0):
        raise InputError(f"page width and height must be positive and finite, got {page!r}")
    return (round(w * f, 9), round(h * f, 9))


def text_width(text: str, size: float) -> float:
    """Estimated advance width of ``text`` set in a sans-serif font of em height ``size``.

    A per-character estimate (DejaVu Sans / Arial proportions, rounded up) used to keep
    labels clear of lines; writers set text in a sans-serif font at this em height.
    """
    narrow, wide = set(" .,:;·|!'ijlrtf1()-"), set("MWmw@%")
    em = sum(0.36 if c in narrow else 0.95 if c in wide else 0.74 if c.isupper() else 0.64 for c in text)
    return em * size


# --------------------------------------------------------------------------------------
# values


@dataclass(frozen=True, eq=False)
class Polyline:
    """A chain of line segments on one layer, page millimetres.

    Attributes
    ----------
    layer : str
        One of :data:`LAYERS`.
    points : (n, 2) ndarray
        Vertices; a closed polyline does not repeat its first point.
    closed : bool
    seam : int
        The seam id for ``seam`` and ``glue`` polylines, else -1.
    """

    layer: str
    points: np.ndarray
    closed: bool = False
    seam: int = -1

    def __post_init__(self) -> None:
        object.__setattr__(self, "points", frozen(np.asarray(self.points, float)))

    def transformed(self, matrix: np.ndarray, offset: np.ndarray) -> Polyline:
        """The polyline mapped by ``x -> matrix @ x + offset``."""
        return Polyline(self.layer, self.points @ matrix.T + offset, self.closed, self.seam)


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
        return Label(self.text, (float(p[0]), float(p[1])), _upright(self.angle + turn), self.size, self.kind, self.seam)

    def corners(self) -> np.ndarray:
        """The estimated text box, shape (4, 2): width from :func:`text_width`, height = size."""
        return _box_corners(np.asarray(self.position), math.radians(self.angle), text_width(self.text, self.size), self.size)


@dataclass(frozen=True, eq=False)
class PlacedSheet:
    """A sheet placed on a page.

    Attributes
    ----------
    index : int
        Position of the sheet in the sequence given to :func:`layout_sheets`.
    label : str
    transform : (2, 3) ndarray
        Maps the sheet's model (x, y) to page mm: ``page = transform[:, :2] @ xy + transform[:, 2]``
        (scale times a rotation, with a mirror when the sheet was seen from its back).
    polylines : tuple of Polyline
        Every line of the sheet, glue tabs included.
    labels : tuple of Label
    """

    index: int
    label: str
    transform: np.ndarray
    polylines: tuple[Polyline, ...]
    labels: tuple[Label, ...]

    def __post_init__(self) -> None:
        object.__setattr__(self, "transform", frozen(np.asarray(self.transform, float)))

    def on_layer(self, layer: str) -> tuple[Polyline, ...]:
        """The polylines of one layer."""
        return tuple(p for p in self.polylines if p.layer == layer)

    def bounds(self) -> np.ndarray:
        """Bounding box of all lines, ``[[xmin, ymin], [xmax, ymax]]`` in page mm."""
        pts = np.concatenate([p.points for p in self.polylines])
        return np.stack([pts.min(axis=0), pts.max(axis=0)])


@dataclass(frozen=True, eq=False)
class Page:
    """One page: its size in mm and the sheets on it."""

    size: tuple[float, float]
    sheets: tuple[PlacedSheet, ...]

    def on_layer(self, layer: str) -> tuple[Polyline, ...]:
        """The polylines of one layer over all sheets of the page."""
        return tuple(p for s in self.sheets for p in s.polylines if p.layer == layer)

    def labels(self) -> tuple[Label, ...]:
        """All labels on the page."""
        return tuple(t for s in self.sheets for t in s.labels)


@dataclass(frozen=True, eq=False)
class Layout:
    """Sheets placed on pages, ready for the writers.

    Attributes
    ----------
    pages : tuple of Page
    page_size : tuple of float
        (width, height) in mm.
    margin : float
        Page margin in mm; all lines lie inside it.
    scale : float
        Millimetres on the page per model unit.
    footer : float
        Height in mm of the band kept free of sheets above the bottom margin, for the
        scale bar and the legend the writers draw there.
    notes : tuple of str
        What the layout had to compromise on (narrowed or dropped glue tabs, labels that
        could not be kept clear of lines, seams whose partners differ in length).
    """

    pages: tuple[Page, ...]
    page_size: tuple[float, float]
    margin: float
    scale: float
    notes: tuple[str, ...] = field(default=())
    footer: float = 0.0

    def sheets(self) -> tuple[PlacedSheet, ...]:
        """All placed sheets, page by page."""
        return tuple(s for p in self.pages for s in p.sheets)


# --------------------------------------------------------------------------------------
# small geometry


def _upright(angle: float) -> float:
    a = (angle + 90.0) % 180.0 - 90.0
    return 90.0 if a == -90.0 else a


def _rotation(phi: float) -> np.ndarray:
    c, s = math.cos(phi), math.sin(phi)
    return np.array([[c, -s], [s, c]])


def _box_corners(center: np.ndarray, angle: float, width: float, height: float) -> np.ndarray:
    u = np.array([math.cos(angle), math.sin(angle)])
    v = np.array([-u[1], u[0]])
    hw, hh = width / 2, height / 2
    return center + np.array([-hw * u - hh * v, hw * u - hh * v, hw * u + hh * v, -hw * u + hh * v])


def _segments(polylines: Sequence[tuple[np.ndarray, bool]]) -> np.ndarray:
    """All segments of (points, closed) polylines, shape (S, 2, 2)."""
    out = []
    for pts, closed in polylines:
        if len(pts) < 2:
            continue
        q = np.concatenate([pts, pts[:1]]) if closed else pts
        out.append(np.stack([q[:-1], q[1:]], axis=1))
    return np.concatenate(out) if out else np.zeros((0, 2, 2))


def _cross2(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _point_segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance from points p to segments a–b, all (..., 2) broadcast together; shape (...)."""
    d = b - a
    t = np.clip(np.sum((p - a) * d, axis=-1) / np.maximum(np.sum(d * d, axis=-1), 1e-300), 0.0, 1.0)
    return np.linalg.norm(p - a - t[..., None] * d, axis=-1)


def _distance(points: np.ndarray, segments: np.ndarray) -> np.ndarray:
    """Distance (N,) from each of points (N, 2) to the nearest of segments (S, 2, 2), inf without any."""
    if len(segments) == 0:
        return np.full(len(points), np.inf)
    return _point_segment_distance(points[:, None], segments[None, :, 0], segments[None, :, 1]).min(axis=1)


def _touching(a: np.ndarray, b: np.ndarray, tol: float) -> np.ndarray:
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
    da = _point_segment_distance(A, B[:, :, None, 0], B[:, :, None, 1])  # ends of a to b, (S, T, 2)
    db = _point_segment_distance(B, A[:, :, None, 0], A[:, :, None, 1])  # ends of b to a
    near = ((da < tol) & ~a_shared).any(axis=-1) | ((db < tol) & ~b_shared).any(axis=-1)
    p, r = A[..., 0, :], A[..., 1, :] - A[..., 0, :]
    q, s = B[..., 0, :], B[..., 1, :] - B[..., 0, :]
    cross = ((_cross2(s, p - q) * _cross2(s, p + r - q) < 0) & (_cross2(r, q - p) * _cross2(r, q + s - p) < 0))
    return near | (cross & ~a_shared.any(axis=-1)) | a_shared.all(axis=-1)


def _near_box(segments: np.ndarray, box_of: np.ndarray, tol: float) -> np.ndarray:
    """The segments (T, 2, 2) whose bounding boxes meet the bounding box of points ``box_of`` (..., 2)."""
    pts = box_of.reshape(-1, 2)
    lo, hi = pts.min(axis=0) - tol, pts.max(axis=0) + tol
    return segments[((segments.max(axis=1) >= lo) & (segments.min(axis=1) <= hi)).all(axis=1)]


def _inside(points: np.ndarray, segments: np.ndarray) -> np.ndarray:
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


def _min_area_rotation(points: np.ndarray) -> float:
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


# --------------------------------------------------------------------------------------
# one sheet in its own frame (mm)


def _chain_edges(edges: np.ndarray) -> list[tuple[np.ndarray, bool]]:
    """Chain undirected edges (k, 2) into polylines of vertex indices: (indices, closed)."""
    if len(edges) == 0:
        return []
    adj: dict[int, list[tuple[int, int]]] = {}
    for k, (a, b) in enumerate(edges.tolist()):
        adj.setdefault(a, []).append((k, b))
        adj.setdefault(b, []).append((k, a))
    used = np.zeros(len(edges), bool)

    def walk(start: int) -> tuple[list[int], bool]:
        path, cur = [start], start
        while True:
            nxt = next(((k, o) for k, o in adj[cur] if not used[k]), None)
            if nxt is None:
                return path, False
            used[nxt[0]] = True
            cur = nxt[1]
            if cur == start:
                return path, True
            path.append(cur)
            if len(adj[cur]) != 2:
                return path, False

    chains = []
    for v in sorted(adj):
        if len(adj[v]) != 2:
            while any(not used[k] for k, _ in adj[v]):
                path, closed = walk(v)
                chains.append((np.array(path), closed))
    for k in range(len(edges)):
        if not used[k]:
            path, closed = walk(int(edges[k, 0]))
            chains.append((np.array(path), closed))
    return chains


@dataclass(frozen=True, eq=False)
class _Chain:
    """A maximal run of seam edges with one id on one outline loop (local mm)."""

    sheet: int
    seam: int
    loop: int
    start: int  # position of its first edge in the loop
    count: int  # number of edges
    points: np.ndarray  # (count + 1, 2), sheet interior on the left


@dataclass(frozen=True, eq=False)
class _Local:
    """A sheet in its own frame, scaled to mm and seen from the front."""

    xy: np.ndarray  # (V, 2)
    mirror: bool
    loops: list[tuple[np.ndarray, np.ndarray]]  # per loop: vertex ids (n,), edge ids (n,), interior on the left
    chains: list[_Chain]
    creases: list[Polyline]  # mountain, valley, rulings


def _local_sheet(index: int, sheet: PatternSheet, scale: float) -> _Local:
    mesh = sheet.mesh.triangulated()  # polygons split; the added diagonals come after the sheet's own edges
    name = sheet.label
    xy = mesh.vertices_coords[:, :2] * scale
    faces = mesh.faces_vertices
    tri = xy[faces]
    area2 = _cross2(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    mirror = bool(area2.sum() < 0)
    if mirror:
        xy = xy * np.array([-1.0, 1.0])
        area2 = -area2
    tol = 1e-9 * float(np.abs(area2).max(initial=0.0))
    if np.any(area2 < -tol):
        raise InputError(
            f"sheet {name!r}: triangles must all turn the same way in the plane; "
            f"{int(np.count_nonzero(area2 < -tol))} of {len(faces)} are flipped"
        )
    ef = edges_faces(faces, mesh.edges_vertices)  # counter-clockwise in xy, mirrored or not
    nfaces = np.count_nonzero(ef >= 0, axis=1)
    outline = np.isin(mesh.edges_kind, ("boundary", "seam"))
    bad = np.flatnonzero(outline & (nfaces != 1))
    if bad.size:
        raise InputError(f"sheet {name!r}: edge {bad[0]} of kind {str(mesh.edges_kind[bad[0]])!r} must border exactly one triangle, borders {nfaces[bad[0]]}")
    bad = np.flatnonzero(~outline & (nfaces != 2))
    if bad.size:
        raise InputError(f"sheet {name!r}: edge {bad[0]} borders {nfaces[bad[0]]} triangle(s), so it lies on the outline, "
                         f"but its kind is {str(mesh.edges_kind[bad[0]])!r} (must be 'boundary' or 'seam')")

    # Outline loops, directed as their triangle traverses them (interior on the left).
    ids = np.flatnonzero(outline)
    ev = mesh.edges_vertices[ids]
    directed = np.where((ef[ids, 0] >= 0)[:, None], ev, ev[:, ::-1])
    out_of: dict[int, list[int]] = {}
    for j, a in enumerate(directed[:, 0].tolist()):
        out_of.setdefault(a, []).append(j)
    used = np.zeros(len(ids), bool)
    loops = []
    for j0 in range(len(ids)):
        if used[j0]:
            continue
        verts, edges, j = [], [], j0
        while not used[j]:
            used[j] = True
            verts.append(int(directed[j, 0]))
            edges.append(int(ids[j]))
            j = next((k for k in out_of.get(int(directed[j, 1]), []) if not used[k]), j0)
        loops.append((np.array(verts), np.array(edges)))

    chains = []
    for li, (verts, edges) in enumerate(loops):
        sid = sheet.edges_seam[edges]
        n = len(edges)
        change = np.flatnonzero(sid != np.roll(sid, 1))
        starts = change.tolist() if change.size else [0]
        for k, s0 in enumerate(starts):
            count = ((starts[(k + 1) % len(starts)] - s0) % n) or n
            if sid[s0] < 0:
                continue
            idx = verts[(s0 + np.arange(count + 1)) % n]
            chains.append(_Chain(index, int(sid[s0]), li, s0, count, xy[idx]))

    creases = []
    kind, assign = mesh.edges_kind, mesh.edges_assignment
    for layer, mask in (("mountain", (kind == "fold") & (assign == "M")),
                        ("valley", (kind == "fold") & (assign == "V")),
                        ("rulings", kind == "ruling")):
        for path, closed in _chain_edges(mesh.edges_vertices[mask]):
            creases.append(Polyline(layer, xy[path], closed))
    return _Local(xy, mirror, loops, chains, creases)


def _tab(base: np.ndarray, width: float, taper: float) -> tuple[np.ndarray, np.ndarray] | None:
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


def _tab_pieces(points: np.ndarray, tab_length: float, min_length: float) -> list[np.ndarray]:
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
    count = max(1, math.ceil(s[-1] / tab_length - 1e-9), math.ceil(turn[-1] / _TAB_MAX_TURN - 1e-9))
    count = max(1, min(count, int(s[-1] // min_length), len(seg)))
    # Split where arc length and turning (each normalised) reach equal shares: in the middle
    # of the segment where each share is reached.
    progress = s / s[-1] + (turn / turn[-1] if turn[-1] > 0 else 0.0)
    at = np.searchsorted(progress, progress[-1] * np.arange(1, count) / count, side="right") - 1
    at = np.unique(np.clip(at, 0, len(seg) - 1))
    refined = np.insert(points, at + 1, 0.5 * (points[at] + points[at + 1]), axis=0)
    bounds = [0, *(at + 1 + np.arange(len(at))).tolist(), len(refined) - 1]
    return [refined[i:j + 1] for i, j in zip(bounds[:-1], bounds[1:])]


def _label_candidates(center: np.ndarray, angle: np.ndarray, text: str, size: float) -> np.ndarray:
    """Sample points covering the text boxes, shape (C, K, 2)."""
    width = text_width(text, size)
    step = 0.4 * size  # a line between two points of a box comes within 0.2 size of one: caught by the 0.25 size clearance
    u = np.linspace(-width / 2, width / 2, max(2, math.ceil(width / step) + 1))
    v = np.linspace(-size / 2, size / 2, 5)
    uu, vv = (g.ravel() for g in np.meshgrid(u, v))
    c, s = np.cos(angle)[:, None], np.sin(angle)[:, None]
    return np.stack([center[:, None, 0] + uu * c - vv * s, center[:, None, 1] + uu * s + vv * c], axis=-1)


class _Obstacles:
    """Lines that labels keep clear of, sampled densely for nearest-point queries."""

    def __init__(self, segments: np.ndarray, spacing: float):
        from scipy.spatial import cKDTree

        d = segments[:, 1] - segments[:, 0]
        length = np.linalg.norm(d, axis=1)
        count = np.maximum(1, np.ceil(length / spacing).astype(int))
        seg = np.repeat(np.arange(len(segments)), count + 1)
        first = np.concatenate([[0], np.cumsum(count + 1)[:-1]])  # index of each segment's first sample
        t = (np.arange(len(seg)) - first[seg]) / count[seg]
        self.points = segments[seg, 0] + t[:, None] * d[seg]
        self.directions = d[seg] / np.maximum(length[seg], 1e-300)[:, None]
        self.spacing = spacing
        self.tree = cKDTree(self.points) if len(self.points) else None

    def clearance(self, points: np.ndarray, limit: float = np.inf) -> tuple[np.ndarray, np.ndarray]:
        """Distance to the nearest obstacle (less half the spacing, inf beyond ``limit``) and its direction."""
        shape = points.shape[:-1]
        if self.tree is None:
            return np.full(shape, np.inf), np.tile([1.0, 0.0], shape + (1,))
        dist, idx = self.tree.query(points.reshape(-1, 2), distance_upper_bound=limit)
        found = idx < len(self.points)
        direction = np.where(found[:, None], self.directions[np.where(found, idx, 0)], [1.0, 0.0])
        return (dist - self.spacing / 2).reshape(shape), direction.reshape(shape + (2,))

    def fits(self, boxes: np.ndarray, size: float) -> tuple[np.ndarray, np.ndarray]:
        """For boxes (C, K, 2): whether each keeps 0.25·size clear of every line, and its margin
        (counted up to one ``size``)."""
        dist, _ = self.clearance(boxes, limit=size)
        worst = np.minimum(dist.min(axis=1), size)
        return worst >= 0.25 * size, worst


def _sizes(preferred: float) -> list[float]:
    out, s = [], preferred
    while s > MIN_LABEL_SIZE:
        out.append(s)
        s *= 0.8
    return out + [MIN_LABEL_SIZE]


def _seam_label(chain: _Chain, obstacles: _Obstacles, size: float) -> tuple[Label, bool]:
    """Seam name inside the sheet, beside the middle of the chain, parallel to it."""
    text = seam_name(chain.seam)
    p = chain.points
    d = np.diff(p, axis=0)
    seg = np.linalg.norm(d, axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    offsets = np.array([0.0, 0.05, -0.05, 0.1, -0.1, 0.17, -0.17, 0.25, -0.25, 0.33, -0.33])
    fallback = None
    for h in _sizes(size):
        at = s[-1] * (0.5 + offsets)
        k = np.clip(np.searchsorted(s, at, side="right") - 1, 0, len(seg) - 1)
        t = d[k] / np.maximum(seg[k], 1e-300)[:, None]
        base = p[k] + t * (at - s[k])[:, None]
        left = np.stack([-t[:, 1], t[:, 0]], axis=1)
        gaps = np.array([0.85, 1.2, 1.7]) * h
        center = (base[:, None] + gaps[None, :, None] * left[:, None]).reshape(-1, 2)
        angle = np.repeat(np.arctan2(t[:, 1], t[:, 0]), len(gaps))
        ok, _ = obstacles.fits(_label_candidates(center, angle, text, h), h)
        if fallback is None:
            fallback = Label(text, tuple(center[0]), _upright(math.degrees(angle[0])), MIN_LABEL_SIZE, "seam", chain.seam)
        if ok.any():
            i = int(np.argmax(ok))  # candidates are in order of preference
            return Label(text, (float(center[i, 0]), float(center[i, 1])), _upright(math.degrees(angle[i])), h, "seam", chain.seam), True
    return fallback, False


def _sheet_label(text: str, centroids: np.ndarray, areas: np.ndarray, obstacles: _Obstacles,
                 size: float) -> tuple[Label, bool]:
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
    for h in _sizes(size):
        keep = np.flatnonzero(dist >= 0.75 * h)
        keep = keep[np.argsort(-dist[keep])][:80]
        if keep.size == 0:
            continue
        along = np.arctan2(direction[keep, 1], direction[keep, 0])
        center = np.concatenate([centroids[keep], centroids[keep]])
        angle = np.concatenate([along, np.zeros(keep.size)])
        ok, worst = obstacles.fits(_label_candidates(center, angle, text, h), h)
        if ok.any():
            score = np.minimum(worst, h) - 0.05 * np.linalg.norm(center - middle, axis=1)
            i = int(np.argmax(np.where(ok, score, -np.inf)))
            return Label(text, (float(center[i, 0]), float(center[i, 1])), _upright(math.degrees(angle[i])), h), True
    along = math.degrees(math.atan2(direction[best, 1], direction[best, 0]))
    return Label(text, (float(centroids[best, 0]), float(centroids[best, 1])), _upright(along), MIN_LABEL_SIZE), False


# --------------------------------------------------------------------------------------
# layout


def _check_length(name: str, value: float | None, units: float, *, positive: bool) -> float | None:
    if value is None:
        return None
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v) or v < 0 or (positive and v == 0):
        raise InputError(f"{name} must be {'positive' if positive else 'non-negative'} and finite, got {value!r}")
    return v * units


def layout_sheets(
    sheets: Sequence[PatternSheet],
    *,
    page: str | tuple[float, float] = "A4",
    units: str = "mm",
    scale: float | None = None,
    target_size: float | None = None,
    margin: float | None = None,
    footer: float | None = None,
    gap: float | None = None,
    glue_tabs: bool = True,
    tab_width: float | None = None,
    tab_length: float | None = None,
    tab_angle: float = 60.0,
    label_size: float | None = None,
) -> Layout:
    """Place developed sheets on pages with glue tabs, layers and labels.

    Each sheet (with its tabs) is turned to its minimum-area bounding rectangle, lying
    flat, and the rectangles are packed first-fit on shelves, tallest first, over as many
    pages as needed. Sheets never overlap and keep ``gap`` between their bounding boxes.

    Parameters
    ----------
    sheets : sequence of PatternSheet
    page : str or (2,) tuple of float
        A name in :data:`~curvefold.io.tables.PAGES` (case-insensitive: ``"A4"``, ``"A3"``, ``"Letter"``…)
        or (width, height) in ``units``. Portrait names; pass a pair for landscape.
    units : str
        Unit of every length argument, a name in :data:`~curvefold.io.tables.UNITS` (``"mm"``, ``"cm"``, ``"in"``…).
    scale : float, optional
        Page length (in ``units``) per model unit; default 1.
    target_size : float, optional
        Instead of ``scale``: the longer side of the largest sheet's minimum-area
        rectangle (without tabs) becomes this length, in ``units``.
    margin : float, optional
        Free border of every page; default 10 mm (printers cannot print the outer 3–6 mm).
    footer : float, optional
        Height of the band above the bottom margin kept for the scale bar and legend;
        default :data:`FOOTER` mm.
    gap : float, optional
        Space between sheets; default 4 mm.
    glue_tabs : bool
        Add glue tabs along seams (see the module notes).
    tab_width : float, optional
        Tab width, perpendicular to the seam; default 6 mm.
    tab_length : float, optional
        Longest single tab piece along the seam; default 5 × ``tab_width``.
    tab_angle : float
        Angle in degrees between a tab's tapered end and the seam, in (0, 90).
    label_size : float, optional
        Em height of the sheet labels; seam names are set at 0.8 × this. Default 4 mm.
        Labels shrink (down to 1.5 mm) to stay clear of lines.

    Returns
    -------
    Layout

    Raises
    ------
    InputError
        For an invalid argument or sheet, a seam id on more than two sheets, or a sheet
        that does not fit the page at this scale (the message gives both sizes).
    """
    f = mm_per_unit(units)
    sheets = tuple(sheets)
    if not sheets:
        raise InputError("sheets must hold at least one PatternSheet, got none")
    for i, sh in enumerate(sheets):
        if not isinstance(sh, PatternSheet):
            raise InputError(f"sheets[{i}] must be a PatternSheet, got {type(sh).__name__}")
    W, H = page_size(page, units=units)
    page_name = page if isinstance(page, str) else "custom"
    if scale is not None and target_size is not None:
        raise InputError(f"give scale or target_size, not both (got scale={scale!r}, target_size={target_size!r})")
    scale_mm = _check_length("scale", 1.0 if scale is None else scale, f, positive=True)
    target = _check_length("target_size", target_size, f, positive=True)
    margin = _check_length("margin", 10.0 / f if margin is None else margin, f, positive=False)
    gap = _check_length("gap", 4.0 / f if gap is None else gap, f, positive=False)
    tab_width = _check_length("tab_width", 6.0 / f if tab_width is None else tab_width, f, positive=True)
    tab_length = _check_length("tab_length", 5 * tab_width / f if tab_length is None else tab_length, f, positive=True)
    label_size = _check_length("label_size", 4.0 / f if label_size is None else label_size, f, positive=True)
    if not (isinstance(tab_angle, (int, float)) and 0 < tab_angle < 90):
        raise InputError(f"tab_angle must be in (0, 90) degrees, got {tab_angle!r}")
    footer = _check_length("footer", FOOTER / f if footer is None else footer, f, positive=False)
    avail = (W - 2 * margin, H - 2 * margin - footer)
    if min(avail) <= 0:
        raise InputError(f"margin {margin:g} mm and footer {footer:g} mm leave no room on a {W:g} × {H:g} mm page")

    if target is not None:
        longest = 0.0
        for sh in sheets:
            xy = sh.mesh.vertices_coords[:, :2]
            r = xy @ _rotation(_min_area_rotation(xy)).T
            longest = max(longest, float(np.ptp(r, axis=0).max()))
        if longest <= 0:
            raise InputError("target_size needs sheets of non-zero size; every sheet is a point")
        scale_mm = target / longest

    for sh in sheets:  # a sheet too large for the page is refused before any tab or label is placed
        xy = sh.mesh.vertices_coords[:, :2] * scale_mm
        w, h = (np.ptp(xy @ _rotation(_min_area_rotation(xy)).T, axis=0) if np.isfinite(xy).all() else (math.inf,) * 2)
        if max(w, h) > max(avail) or min(w, h) > min(avail):
            raise InputError(
                f"sheet {sh.label!r} needs {max(w, h):.4g} × {min(w, h):.4g} mm before glue tabs at scale {scale_mm:g} mm per unit, "
                f"but the {page_name} page ({W:g} × {H:g} mm) has {avail[0]:g} × {avail[1]:g} mm inside its margins; "
                f"lower the scale or choose a larger page"
            )

    notes: list[str] = []
    locals_ = [_local_sheet(i, sh, scale_mm) for i, sh in enumerate(sheets)]

    # Which chains get tabs.
    by_seam: dict[int, list[_Chain]] = {}
    for loc in locals_:
        for ch in loc.chains:
            by_seam.setdefault(ch.seam, []).append(ch)
    tabbed: set[int] = set()  # id() of chains with tabs
    for sid, chains in sorted(by_seam.items()):
        owners = sorted({c.sheet for c in chains})
        if len(owners) > 2:
            raise InputError(f"seam id {sid} appears on sheets {owners}; a seam joins at most two sheets")
        if len(owners) == 2:
            lengths = [sum(float(np.linalg.norm(np.diff(c.points, axis=0), axis=1).sum()) for c in chains if c.sheet == o) for o in owners]
            if abs(lengths[0] - lengths[1]) > 1e-2 * max(lengths):
                notes.append(f"seam {seam_name(sid)}: lengths differ between {sheets[owners[0]].label!r} "
                             f"({lengths[0]:.2f} mm) and {sheets[owners[1]].label!r} ({lengths[1]:.2f} mm)")
        if glue_tabs:
            mine = [c for c in chains if c.sheet == owners[0]]
            for c in (mine[:1] if len(owners) == 1 and len(mine) > 1 else mine):
                tabbed.add(id(c))

    items = []
    for i, (sh, loc) in enumerate(zip(sheets, locals_)):
        items.append(_build_sheet(i, sh, loc, tabbed, tab_width, tab_length, math.radians(tab_angle), label_size, notes))

    placements = _pack([it[1] for it in items], avail, gap, margin, (W, H), sheets, page_name)
    pages: list[list[PlacedSheet]] = [[] for _ in range(1 + max(p[0] for p in placements))]
    for i, ((polylines, _footprint, labels, mirror), (pg, rot, offset)) in enumerate(zip(items, placements)):
        R = _rotation(rot)
        mat = R @ np.diag([-scale_mm if mirror else scale_mm, scale_mm])
        pages[pg].append(PlacedSheet(
            index=i,
            label=sheets[i].label,
            transform=np.concatenate([mat, offset[:, None]], axis=1),
            polylines=tuple(p.transformed(R, offset) for p in polylines),
            labels=tuple(t.transformed(R, offset) for t in labels),
        ))
    return Layout(tuple(Page((W, H), tuple(p)) for p in pages), (W, H), margin, scale_mm, tuple(notes), footer)


def _outline_segments(loc: _Local, pieces_of: dict[int, list[np.ndarray]]) -> np.ndarray:
    """Segments (S, 2, 2) of a sheet's outline loops, tabbed seams split where their tab pieces meet."""
    segs = []
    for li, (verts, _) in enumerate(loc.loops):
        n = len(verts)
        keep = np.ones(n, bool)
        for ch in loc.chains:
            if ch.loop == li and id(ch) in pieces_of:
                keep[(ch.start + np.arange(ch.count)) % n] = False
        p = loc.xy[verts]
        segs.append(np.stack([p, np.roll(p, -1, axis=0)], axis=1)[keep])
    segs += [_segments([(piece, False)]) for pieces in pieces_of.values() for piece in pieces]
    return np.concatenate(segs)


def _build_sheet(index, sheet, loc, tabbed, tab_width, tab_length, taper, label_size, notes):
    """Polylines and labels of one sheet in its local mm frame, and its footprint points."""
    name = sheet.label
    pieces_of = {id(ch): _tab_pieces(ch.points, tab_length, 2.5 * tab_width) for ch in loc.chains if id(ch) in tabbed}
    outline = _outline_segments(loc, pieces_of)
    tol = 1e-9 * max(float(np.ptp(loc.xy, axis=0).max()), 1.0)  # coordinate rounding, mm
    accepted: list[np.ndarray] = []  # polygons of the tabs on this sheet
    # per loop: position of first edge -> (count of edges, replacement points without the last)
    replace: dict[tuple[int, int], tuple[int, np.ndarray]] = {}
    polylines: list[Polyline] = []
    for ch in loc.chains:
        if id(ch) not in pieces_of:
            continue
        pieces = pieces_of[id(ch)]
        cut_parts, dropped, narrowed = [], 0, 0
        runs: list[list[np.ndarray]] = [[]]  # consecutive tabbed pieces: one fold line each
        for piece in pieces:
            got = None
            for k, frac in enumerate(_TAB_WIDTH_STEPS):
                tab = _tab(piece, frac * tab_width, taper)
                if tab is not None and _tab_fits(tab, outline, accepted, tol):
                    got, narrowed = tab, narrowed + (k > 0)
                    break
            if got is None:
                dropped += 1
                cut_parts.append(piece[:-1])
                runs.append([])
                continue
            accepted.append(got[0])
            polylines.append(Polyline("glue", got[0], closed=True, seam=ch.seam))
            cut_parts.append(got[1][:-1])
            runs[-1].append(piece)
        for run in runs:
            if run:
                line = np.concatenate([p[:-1] for p in run] + [run[-1][-1:]])
                polylines.append(Polyline("seam", line, seam=ch.seam))
        replace[(ch.loop, ch.start)] = (ch.count, np.concatenate(cut_parts))
        if narrowed or dropped:
            notes.append(f"sheet {name!r}, seam {seam_name(ch.seam)}: {narrowed} glue tab piece(s) narrowed, "
                         f"{dropped} left out (of {len(pieces)}) to keep clear of the sheet")

    for li, (verts, _) in enumerate(loc.loops):
        n = len(verts)
        starts = sorted(pos for (l2, pos) in replace if l2 == li)
        parts, pos, done = [], 0, 0
        # start the walk at a replaced run if any, so no run wraps around the walk's end
        pos = starts[0] if starts else 0
        while done < n:
            key = (li, pos % n)
            if key in replace:
                count, pts = replace[key]
                parts.append(pts)
            else:
                count = 1
                parts.append(loc.xy[verts[pos % n]][None])
            pos += count
            done += count
        polylines.append(Polyline("cut", np.concatenate(parts), closed=True))
    polylines.extend(loc.creases)

    # Labels: seam names first (each then becomes an obstacle), then the sheet label.
    obstacle_lines = [(p.points, p.closed) for p in polylines if p.layer in ("cut", "seam", "mountain", "valley")]
    segments = _segments(obstacle_lines)
    spacing = 0.1 * MIN_LABEL_SIZE
    labels: list[Label] = []
    for ch in loc.chains:
        lab, ok = _seam_label(ch, _Obstacles(segments, spacing), 0.8 * label_size)
        if not ok:
            notes.append(f"sheet {name!r}: seam name {lab.text} could not be kept clear of the lines")
        labels.append(lab)
        segments = np.concatenate([segments, _segments([(lab.corners(), True)])])
    tri = loc.xy[sheet.mesh.triangulated().faces_vertices]
    areas = 0.5 * np.abs(_cross2(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]))
    lab, ok = _sheet_label(name, tri.mean(axis=1), areas, _Obstacles(segments, spacing), label_size)
    if not ok:
        notes.append(f"sheet {name!r}: its label could not be kept clear of the lines")
    if name:
        labels.append(lab)
    return polylines, np.concatenate([p.points for p in polylines]), labels, loc.mirror


def _tab_fits(tab: tuple[np.ndarray, np.ndarray], outline: np.ndarray, accepted: list[np.ndarray], tol: float) -> bool:
    """Whether a tab may be drawn: its cut line is simple and keeps ``tol`` clear of the
    sheet's outline (S, 2, 2) and of the tabs already accepted, but for its two ends on the
    seam, and it neither lies inside them nor holds any of their corners."""
    polygon, cut = tab
    segs = _segments([(cut, False)])
    own = _touching(segs, segs, tol)
    np.fill_diagonal(own, False)
    if own.any():
        return False
    corners = cut[1:-1]
    mine = _segments([(polygon, True)])
    lo, hi = polygon.min(axis=0) - tol, polygon.max(axis=0) + tol
    near = [p for p in accepted if (p.max(axis=0) >= lo).all() and (p.min(axis=0) <= hi).all()]  # the others cannot touch it
    for other in (outline, *(_segments([(p, True)]) for p in near)):
        near = _near_box(other, cut, tol)
        if _touching(segs, near, tol).any() or (_distance(corners, near) < tol).any() or _inside(corners, other).any():
            return False
        theirs = other[:, 0][_distance(other[:, 0], mine) >= tol]  # their corners off this tab's outline
        if _inside(theirs, mine).any():
            return False
    return True


def _pack(footprints, avail, gap, margin, page, sheets, page_name):
    """Shelf packing of the sheets' minimum-area rectangles: per sheet (page, rotation, offset).

    Two passes, one laying every rectangle with its long side across the page and one
    standing it up where it fits; the pass with fewer pages (then the emptier last
    page) wins.
    """
    W, H = page
    rects = []
    for i, pts in enumerate(footprints):
        rot = _min_area_rotation(pts)
        r = pts @ _rotation(rot).T
        w, h = np.ptp(r, axis=0)
        if w < h:
            rot += math.pi / 2
            w, h = h, w
        lying, standing = (w <= avail[0] and h <= avail[1]), (h <= avail[0] and w <= avail[1])
        if not (lying or standing):
            raise InputError(
                f"sheet {sheets[i].label!r} needs {w:.1f} × {h:.1f} mm (with glue tabs) but the {page_name} page "
                f"({W:g} × {H:g} mm) has {avail[0]:g} × {avail[1]:g} mm inside its margins; "
                f"lower the scale or choose a larger page"
            )
        options = [(float(w), float(h), rot)] if lying else []
        if standing:
            options.append((float(h), float(w), rot + math.pi / 2))
        rects.append(options)
    best = None
    for stand in (False, True):
        prefs = [sorted(o, key=lambda t: -t[1] if stand else t[1]) for o in rects]
        got = _shelves(prefs, avail, gap)
        if best is None or got[1] < best[1]:
            best = got
    out = []
    for i, (pg, x, y_top, angle) in enumerate(best[0]):
        r = footprints[i] @ _rotation(angle).T
        lo, hi = r.min(axis=0), r.max(axis=0)
        out.append((pg, angle, np.array([margin + x - lo[0], H - margin - y_top - hi[1]])))
    return out


def _shelves(options, avail, gap):
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
