"""Crease patterns laid out on printable pages: placement, glue tabs, layers and labels.

A tube is two developed sheets welded along seam curves; :func:`layout_sheets` places any
number of such sheets on pages of a given size, adds glue tabs along the seams and sorts
every line into a fabrication layer. The writers in :mod:`curvefold.io._pattern` turn
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
                          chain, the seam's name (:func:`~curvefold.io._labels.seam_name`), the same
                          on both partners.
    ====================  ================================================================

No line appears in two layers, so a laser never cuts or scores a line twice. Triangulating
diagonals are never drawn.

Glue tabs
    For every seam id the tabs go on one side only, the sheet with the lowest index that
    has the seam, so that the partner sheet overlaps the tab when glued. A seam whose
    chains all lie on one sheet gets its tab on the first chain only. How tabs are cut into
    pieces, tapered, checked as drawn, narrowed or left out is :mod:`curvefold.io._tabs`;
    both compromises are reported in :attr:`Layout.notes`.

The lines of one sheet in its own frame are drawn by :mod:`curvefold.io._sheet_lines`; the
plane geometry is :mod:`curvefold.io._planar`, the placement of labels
:mod:`curvefold.io._labels` and the packing of sheets on pages :mod:`curvefold.io._packing`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from ..geometry._sheets import PatternSheet
from ..kernel._arrays import frozen, readonly
from ..kernel._errors import InputError
from ._labels import Label, seam_name
from ._packing import pack_pages
from ._planar import bounding_box, min_area_rotations, rotation
from ._sheet_lines import SeamChain, SheetRules, build_sheet, local_sheet
from ._tables import mm_per_unit, page_mm

__all__ = [
    "FOOTER",
    "LAYERS",
    "Layout",
    "LayoutRules",
    "Page",
    "PlacedSheet",
    "Polyline",
    "layout_sheets",
    "page_size",
]

#: Layer names, bottom to top.
LAYERS = ("glue", "rulings", "seam", "valley", "mountain", "cut", "labels")

#: Height (mm) of the band above a page's bottom margin kept for its scale bar and legend.
FOOTER = 14.0


def page_size(page: str | tuple[float, float], *, units: str = "mm") -> tuple[float, float]:
    """Page (width, height) in mm from a name in :data:`~curvefold.io._tables.PAGES` or a pair in
    ``units``.

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
        # (a new array: held, not copied)
        return Polyline(
            self.layer, readonly(self.points @ matrix.T + offset), self.closed, self.seam
        )


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
    cutter : str
        The colour convention the writers draw it in (a key of :data:`curvefold.io.CUTTERS`).
    perforation : (float, float) or None
        (dash, gap) in mm when the creases are drawn as cut dashes (:mod:`curvefold.io._cutting`).
    kerf : float
        The kerf (mm) the cut outlines were moved out for, by half of it; 0 for none.
    sheet_note : str
        What the drawing accounts for of a thick sheet (:mod:`curvefold.io._thick_sheet`),
        a row of the legend; empty for a sheet of zero thickness.
    """

    pages: tuple[Page, ...]
    page_size: tuple[float, float]
    margin: float
    scale: float
    notes: tuple[str, ...] = field(default=())
    footer: float = 0.0
    cutter: str = "print"
    perforation: tuple[float, float] | None = None
    kerf: float = 0.0
    sheet_note: str = ""

    def sheets(self) -> tuple[PlacedSheet, ...]:
        """All placed sheets, page by page."""
        return tuple(s for p in self.pages for s in p.sheets)


# --------------------------------------------------------------------------------------
# layout


def _check_length(name: str, value: float, units: float, *, positive: bool) -> float:
    """``value`` in ``units`` as mm, once it is a finite number, positive or non-negative."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v) or v < 0 or (positive and v == 0):
        raise InputError(
            f"{name} must be {'positive' if positive else 'non-negative'} and finite, got {value!r}"
        )
    return v * units


@dataclass(frozen=True)
class LayoutRules:
    """The spacing of a layout: margins, footer band, gaps, glue tabs and labels.

    Lengths are in the ``units`` of :func:`layout_sheets`; None stands for the default in mm.

    Attributes
    ----------
    margin : float or None
        Free border of every page; default 10 mm (printers cannot print the outer 3–6 mm).
    footer : float or None
        Height of the band above the bottom margin kept for the scale bar and legend;
        default :data:`FOOTER` mm.
    gap : float or None
        Space between sheets; default 4 mm.
    tab_width : float or None
        Glue tab width, perpendicular to the seam; default 6 mm.
    tab_length : float or None
        Longest single tab piece along the seam; default 5 × ``tab_width``.
    tab_angle : float
        Angle in degrees between a tab's tapered end and the seam, in (0, 90).
    label_size : float or None
        Em height of the sheet labels; seam names are set at 0.8 × this. Default 4 mm.
        Labels shrink (down to 1.5 mm) to stay clear of lines.
    """

    margin: float | None = None
    footer: float | None = None
    gap: float | None = None
    tab_width: float | None = None
    tab_length: float | None = None
    tab_angle: float = 60.0
    label_size: float | None = None


def layout_sheets(
    sheets: Sequence[PatternSheet],
    *,
    page: str | tuple[float, float] = "A4",
    units: str = "mm",
    scale: float | None = None,
    target_size: float | None = None,
    glue_tabs: bool = True,
    rules: LayoutRules = LayoutRules(),
) -> Layout:
    """Place developed sheets on pages with glue tabs, layers and labels.

    Each sheet (with its tabs) is turned to its minimum-area bounding rectangle, lying
    flat, and the rectangles are packed first-fit on shelves, tallest first, over as many
    pages as needed. Sheets never overlap and keep ``gap`` between their bounding boxes.

    Parameters
    ----------
    sheets : sequence of PatternSheet
    page : str or (2,) tuple of float
        A name in :data:`~curvefold.io._tables.PAGES` (case-insensitive: ``"A4"``, ``"A3"``,
        ``"Letter"``…) or (width, height) in ``units``. Portrait names; pass a pair for landscape.
    units : str
        Unit of every length argument, a name in :data:`~curvefold.io._tables.UNITS` (``"mm"``,
        ``"cm"``, ``"in"``…).
    scale : float, optional
        Page length (in ``units``) per model unit; default 1.
    target_size : float, optional
        Instead of ``scale``: the longer side of the largest sheet's minimum-area
        rectangle (without tabs) becomes this length, in ``units``.
    glue_tabs : bool
        Add glue tabs along seams (see the module notes).
    rules : LayoutRules
        Margins, footer band, gaps between sheets, glue tab size and label size.

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
        raise InputError(
            f"give scale or target_size, not both (got scale={scale!r}, "
            f"target_size={target_size!r})"
        )
    scale_mm = _check_length("scale", 1.0 if scale is None else scale, f, positive=True)
    target = (
        None if target_size is None else _check_length("target_size", target_size, f, positive=True)
    )
    if not isinstance(rules, LayoutRules):
        raise InputError(
            f"rules must be a LayoutRules, got {type(rules).__name__}", parameter="rules"
        )
    r = rules
    margin = _check_length("margin", 10.0 / f if r.margin is None else r.margin, f, positive=False)
    gap = _check_length("gap", 4.0 / f if r.gap is None else r.gap, f, positive=False)
    tab_width = _check_length(
        "tab_width", 6.0 / f if r.tab_width is None else r.tab_width, f, positive=True
    )
    tab_length = _check_length(
        "tab_length", 5 * tab_width / f if r.tab_length is None else r.tab_length, f, positive=True
    )
    label_size = _check_length(
        "label_size", 4.0 / f if r.label_size is None else r.label_size, f, positive=True
    )
    tab_angle = r.tab_angle
    if not (isinstance(tab_angle, (int, float)) and 0 < tab_angle < 90):
        raise InputError(f"tab_angle must be in (0, 90) degrees, got {tab_angle!r}")
    footer = _check_length(
        "footer", FOOTER / f if r.footer is None else r.footer, f, positive=False
    )
    avail = (W - 2 * margin, H - 2 * margin - footer)
    if min(avail) <= 0:
        raise InputError(
            f"margin {margin:g} mm and footer {footer:g} mm leave no room on a "
            f"{W:g} × {H:g} mm page"
        )

    if target is not None:
        xys = [sh.mesh.vertices_coords[:, :2] for sh in sheets]
        longest = max(
            [
                0.0,
                *(
                    float(np.ptp(bounding_box(xy @ rotation(rot).T), axis=0).max())
                    for xy, rot in zip(xys, min_area_rotations(xys))
                ),
            ]
        )
        if longest <= 0:
            raise InputError("target_size needs sheets of non-zero size; every sheet is a point")
        scale_mm = target / longest

    xys = [sh.mesh.vertices_coords[:, :2] * scale_mm for sh in sheets]
    # a sheet too large for the page is refused before any tab or label is placed
    for sh, xy, rot in zip(sheets, xys, min_area_rotations(xys)):
        w, h = (
            np.ptp(bounding_box(xy @ rotation(rot).T), axis=0)
            if np.isfinite(xy).all()
            else (math.inf,) * 2
        )
        if max(w, h) > max(avail) or min(w, h) > min(avail):
            raise InputError(
                f"sheet {sh.label!r} needs {max(w, h):.4g} × {min(w, h):.4g} mm before glue tabs "
                f"at scale {scale_mm:g} mm per unit, but the {page_name} page ({W:g} × "
                f"{H:g} mm) has {avail[0]:g} × {avail[1]:g} mm inside its margins; lower "
                "the scale or choose a larger page"
            )

    notes: list[str] = []
    locals_ = [local_sheet(i, sh, scale_mm) for i, sh in enumerate(sheets)]

    # Which chains get tabs.
    by_seam: dict[int, list[SeamChain]] = {}
    for loc in locals_:
        for ch in loc.chains:
            by_seam.setdefault(ch.seam, []).append(ch)
    tabbed: set[int] = set()  # id() of chains with tabs
    for sid, chains in sorted(by_seam.items()):
        owners = sorted({c.sheet for c in chains})
        if len(owners) > 2:
            raise InputError(
                f"seam id {sid} appears on sheets {owners}; a seam joins at most two sheets"
            )
        if len(owners) == 2:
            lengths = [
                sum(
                    float(np.linalg.norm(np.diff(c.points, axis=0), axis=1).sum())
                    for c in chains
                    if c.sheet == o
                )
                for o in owners
            ]
            if abs(lengths[0] - lengths[1]) > 1e-2 * max(lengths):
                notes.append(
                    f"seam {seam_name(sid)}: lengths differ between "
                    f"{sheets[owners[0]].label!r} ({lengths[0]:.2f} mm) and "
                    f"{sheets[owners[1]].label!r} ({lengths[1]:.2f} mm)"
                )
        if glue_tabs:
            mine = [c for c in chains if c.sheet == owners[0]]
            for c in mine[:1] if len(owners) == 1 and len(mine) > 1 else mine:
                tabbed.add(id(c))

    sheet_rules = SheetRules(tab_width, tab_length, math.radians(tab_angle), label_size)
    items = [build_sheet(sh, loc, tabbed, sheet_rules, notes) for sh, loc in zip(sheets, locals_)]

    placements = pack_pages(
        [it[1] for it in items], avail, gap, margin, (W, H), [sh.label for sh in sheets], page_name
    )
    pages: list[list[PlacedSheet]] = [[] for _ in range(1 + max(p[0] for p in placements))]
    for i, ((lines, footprint, labels, mirror), (pg, rot, offset)) in enumerate(
        zip(items, placements)
    ):
        R = rotation(rot)
        mat = R @ np.diag([-scale_mm if mirror else scale_mm, scale_mm])
        points = readonly(footprint @ R.T + offset)  # every line's points, moved at once
        ends = np.cumsum([len(line[1]) for line in lines]).tolist()
        pages[pg].append(
            PlacedSheet(
                index=i,
                label=sheets[i].label,
                transform=np.concatenate([mat, offset[:, None]], axis=1),
                polylines=tuple(
                    Polyline(layer, points[end - len(pts) : end], closed, seam)
                    for (layer, pts, closed, seam), end in zip(lines, ends)
                ),
                labels=tuple(t.transformed(R, offset) for t in labels),
            )
        )
    return Layout(
        tuple(Page((W, H), tuple(p)) for p in pages), (W, H), margin, scale_mm, tuple(notes), footer
    )
