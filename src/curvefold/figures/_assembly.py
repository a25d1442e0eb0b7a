"""The assembly guide (``assembly.pdf``): what to cut, which seam glues to which, and in what order.

Drawn on the pages of the crease pattern it goes with (the same page size, margins and
10 mm scale bar, :func:`~curvefold.io._legend.page_footer`), it holds

* which fold is a mountain and which a valley, seen from the printed side, and the line
  each is drawn with (:func:`fold_key`);
* the sheets to cut, each with its id (the label printed on it), the pattern page it is
  on, its seams (``S0``, ``S1``… as the pattern's labels name them, tabs marked) and the
  folds of its creases;
* the seams: which sheet carries the glue tabs of each and which sheet it glues to;
* the steps, tube by tube: score and fold its two sheets along their creases, glue its
  seams, then glue it to the tubes before it along the creases they share (the
  structure's bonds), each step with a picture of the structure built so far at its design
  angle, the new tube picked out, drawn by curvefold's own renderer
  (:func:`~curvefold.figures._scene.render_strips`), every picture at one scale;
* for a structure of thick panels (:class:`~curvefold.geometry.ThickPanels`), the panels
  instead of the sheets in its steps: each tube's panels by their ids, in the order they are
  assembled (:mod:`curvefold.geometry._thick_ids`), where their hinges go, and the cut list
  on its last pages, its rows in that order (:func:`~curvefold.io._solids.cut_list_pages`).

:func:`assembly_plan` gathers what the guide says from the layout and the structure;
:func:`write_assembly` draws it (:mod:`curvefold.io._pdf`).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..geometry._sheets import bonds
from ..geometry._structure import Structure, check_structure, drawable
from ..geometry._thick_ids import SHEET_STRIPS
from ..geometry._topology import tube_strips
from ..io._cutters import LEGEND_LAYER
from ..io._labels import seam_name
from ..io._layout import Layout
from ..io._legend import LEGEND, check_layout, layer_look
from ..io._pattern import draw_footer
from ..io._pdf import PdfDocument, PdfPage, PdfText, advance_units
from ..io._planar import bounding_box
from ..io._tables import COLOURS
from ._scene import GROUND_COLOR, GROUND_EDGE, STRIP_RGB, View, ground_polygon, render_strips

if TYPE_CHECKING:  # pragma: no cover
    from ..geometry._thick import ThickPanels

__all__ = [
    "HIGHLIGHT_RGB",
    "SheetToCut",
    "Seam",
    "Step",
    "AssemblyPlan",
    "assembly_plan",
    "fold_key",
    "write_assembly",
]

#: Base colour of the tube a step adds, RGB in [0, 1].
HIGHLIGHT_RGB = np.array([0.96, 0.72, 0.38])
_KIND_COLOURS = {kind: COLOURS[kind] for kind in ("fold", "seam", "junction", "edge")}
_TEXT, _HEAD, _TITLE = 3.2, 4.2, 6.0  # em heights, mm
_INK = "#222222"
_LAYERS = ("guide - text", "guide - pictures", LEGEND_LAYER)


@dataclass(frozen=True)
class SheetToCut:
    """One sheet: its id (printed on it), its pattern page (1-based), its seams (id, whether
    it has the tabs) and the folds its creases make seen from the printed side (``"mountain"``,
    ``"valley"``)."""

    label: str
    page: int
    seams: tuple[tuple[int, bool], ...]
    folds: tuple[str, ...] = ()


#: Plain names of the colours the cutter conventions draw folds in.
_COLOUR_WORDS = {
    "#ff0000": "red",
    "#0000ff": "blue",
    "#1f4fe0": "blue",
    "#00ff00": "green",
    "#16a016": "green",
    "#00ffff": "cyan",
}
#: How each fold's line looks (the dash patterns of :data:`curvefold.io._cutters.STYLES`).
_LINE_WORDS = {"mountain": "dash-dot line", "valley": "dashed line"}


def fold_key(layout: Layout) -> str:
    """Which fold is a mountain and which a valley, as the guide says it: seen from the printed
    side, with the line each is drawn with in the layout's convention.

    Examples
    --------
    >>> from curvefold.io import layout_pattern
    >>> from curvefold.vault import Vault
    >>> layout = layout_pattern(Vault.from_design(samples=21, tubes=1).structure)
    >>> print(fold_key(layout))  # doctest: +NORMALIZE_WHITESPACE
    Folds, seen from the printed side: a mountain fold (red dash-dot line) rises toward you, so
    fold the sheet away from you along it; a valley fold (blue dashed line) sinks away from
    you, so fold the sheet toward you along it.
    """
    looks = {}
    for key in ("mountain", "valley"):
        colour = layer_look(layout, key)[1]
        line = "line of cut dashes" if layout.perforation is not None else _LINE_WORDS[key]
        looks[key] = f"{_COLOUR_WORDS.get(colour, colour)} {line}"
    return (
        f"Folds, seen from the printed side: a {LEGEND['mountain']} ({looks['mountain']}) rises "
        "toward you, so fold the sheet away from you along it; a "
        f"{LEGEND['valley']} ({looks['valley']}) sinks away from you, so fold the sheet toward "
        "you along it."
    )


def _folds_words(folds: tuple[str, ...]) -> str:
    """``"a mountain fold"``, ``"mountain and valley folds"``."""
    if len(folds) == 1:
        return f"a {folds[0]} fold"
    return " and ".join(folds) + " folds"


@dataclass(frozen=True)
class Seam:
    """A seam: the sheet with its glue tabs and the sheet they glue to (the same one for a seam
    closing on itself)."""

    id: int
    tabs: str
    onto: str


@dataclass(frozen=True)
class Step:
    """Step ``number``: add tube ``tube`` (0-based); what to do, one sentence a line; of thick
    panels, the ids of the panels it adds in the order it adds them."""

    number: int
    tube: int
    title: str
    lines: tuple[str, ...]
    panels: tuple[str, ...] = ()


@dataclass(frozen=True)
class AssemblyPlan:
    """What the guide says: the sheets, the seams and the steps."""

    sheets: tuple[SheetToCut, ...]
    seams: tuple[Seam, ...]
    steps: tuple[Step, ...]

    @property
    def panels(self) -> tuple[str, ...]:
        """The ids of the thick panels in the order the steps assemble them (none for sheets)."""
        return tuple(p for step in self.steps for p in step.panels)


def _joined(bonds, tube: int):
    """(this tube's crease, the earlier tubes' creases) in words, per bond joining them."""
    for bond in bonds:
        others = [c for c in bond.creases if c[0] != tube]
        here = [c for c in bond.creases if c[0] == tube]
        if others and here:
            yield _crease_words(*here[0]), ", ".join(_crease_words(*c) for c in others)


def _crease_words(tube: int, crease: int) -> str:
    where = {
        1: "the crease of its sheet A",
        3: "the crease of its sheet B",
        2: "its seam 2",
        4: "its seam 4",
    }[crease]
    return f"tube {tube + 1}'s crease {crease} ({where})"


def _thick_lines(thick: ThickPanels, tube: int) -> tuple[list[str], tuple[str, ...]]:
    """What step ``tube`` (0-based) says of thick panels: its sheets' strips, panel by panel
    along the crease with their cut-list rows, the hinges that join them; and their ids."""
    group = thick.structure.topology().faces_group
    row = np.empty(len(group), dtype=np.int64)
    row[thick.order] = np.arange(1, len(group) + 1)
    labels = thick.labels()
    lines, ids = [], []
    for sheet, strips in SHEET_STRIPS:
        said = []
        for n, strip in enumerate(strips):
            faces = thick.order[group[thick.order] == 4 * tube + strip]
            ids += [labels[f] for f in faces.tolist()]
            first, last = labels[int(faces[0])], labels[int(faces[-1])].rsplit(" ", 1)[1]
            rows = f"cut-list rows {row[faces[0]]}–{row[faces[-1]]}"
            said.append(f"the {len(faces)} panels of strip {strip + 1} ({rows}: {first} to {last})")
            if n:
                said[-1] += f", each hinged also to strip {strips[0] + 1} along crease {strip + 1}"
        lines.append(
            f"Sheet {sheet}: lay {said[0]} in a row along the crease, each hinged to the one "
            f"before on their shared edge; then {said[1]}."
        )
    lines.append(
        "Close the tube: hinge strip 1 (sheet A) to strip 2 (sheet B) along crease 2, and strip 3 "
        "(sheet B) to strip 4 (sheet A) along crease 4."
    )
    return lines, tuple(ids)


def assembly_plan(
    structure: Structure, layout: Layout, *, thick: ThickPanels | None = None
) -> AssemblyPlan:
    """The sheets, seams and steps of a structure laid out as ``layout``
    (:func:`~curvefold.io.layout_pattern`).

    Seams and tabs are read from the layout (its seam labels and glue areas), tubes and the
    creases they share from the structure (:func:`~curvefold.geometry.bonds`). With ``thick``
    (the structure's thick panels), the steps assemble its panels instead of folding and
    gluing sheets: each step's ``panels`` are its tube's ids in the cut list's order.
    """
    check_structure(structure)
    check_layout(layout)
    placed = sorted(
        ((s, n) for n, page in enumerate(layout.pages, start=1) for s in page.sheets),
        key=lambda item: item[0].index,
    )
    tube_count = len(structure.cell_curves)
    if len(placed) != 2 * tube_count:
        raise ValueError(
            f"the layout holds {len(placed)} sheets, the structure "
            f"{2 * tube_count}: lay out this structure"
        )
    carriers: dict[int, list[str]] = {}
    tabbed: dict[int, str] = {}
    sheets = []
    for s, page in placed:
        ids = sorted({t.seam for t in s.labels if t.kind == "seam"})
        mine = {p.seam for p in s.on_layer("glue")}
        for i in ids:
            carriers.setdefault(i, []).append(s.label)
        for i in mine:
            tabbed.setdefault(i, s.label)
        folds = tuple(k for k in ("mountain", "valley") if s.on_layer(k))
        sheets.append(SheetToCut(s.label, page, tuple((i, i in mine) for i in ids), folds))
    seams = []
    for i, owners in sorted(carriers.items()):
        tabs = tabbed.get(i, owners[0])
        seams.append(Seam(i, tabs, next((o for o in owners if o != tabs), tabs)))
    by_tube: dict[int, list] = {}
    for bond in bonds(structure):
        by_tube.setdefault(max(k for k, _ in bond.creases), []).append(bond)
    steps = []
    for tube in range(tube_count):
        if thick is not None:
            lines, panels = _thick_lines(thick, tube)
            for here, others in _joined(by_tube.get(tube, []), tube):
                lines.append(
                    f"Hinge {here} to {others}: one hinge axis, on the crease, for the panels "
                    "of both."
                )
            title = f"Step {tube + 1}: tube {tube + 1}"
            steps.append(Step(tube + 1, tube, title, tuple(lines), panels))
            continue
        a, b = sheets[2 * tube].label, sheets[2 * tube + 1].label
        pair = (sheets[2 * tube], sheets[2 * tube + 1])
        if pair[0].folds == pair[1].folds and pair[0].folds:
            said = f", {_folds_words(pair[0].folds)} on both, seen from the printed side"
        else:
            each = "; ".join(f"{s.label}: {_folds_words(s.folds)}" for s in pair if s.folds)
            said = f" ({each}, seen from the printed side)" if each else ""
        lines = [f"Score the creases of {a} and {b} and fold each sheet along its crease{said}."]
        for seam in seams:
            if seam.tabs in (a, b):
                onto = (
                    f"the edge {seam_name(seam.id)} of {seam.onto}"
                    if seam.onto != seam.tabs
                    else f"its own edge {seam_name(seam.id)}"
                )
                lines.append(
                    f"Glue seam {seam_name(seam.id)}: fold the glue tabs of {seam.tabs} "
                    f"under and glue them to {onto}."
                )
        if len(lines) > 2:
            lines.append("Let the first seam set before closing the tube with the second.")
        for here, others in _joined(by_tube.get(tube, []), tube):
            lines.append(f"Glue {here} along {others}.")
        steps.append(Step(tube + 1, tube, f"Step {tube + 1}: tube {tube + 1}", tuple(lines)))
    return AssemblyPlan(tuple(sheets), tuple(seams), tuple(steps))


def _wrap(text: str, size: float, width: float) -> list[str]:
    """``text`` broken at spaces into lines no wider than ``width`` (mm) in Helvetica of em
    height ``size``."""
    lines, line, units = [], "", 0  # the line so far and its advance (thousandths of the em)
    space = advance_units(" ")
    for word in text.split():
        trial = units + space + advance_units(word) if line else advance_units(word)
        if line and trial * size / 1000.0 > width:  # text_advance of the line with the word
            lines.append(line)
            line, units = word, advance_units(word)
        else:
            line, units = (f"{line} {word}" if line else word), trial
    return lines + ([line] if line else [])


class _Pages:
    """Text and pictures flowing down pages of the layout's size, each page with its footer."""

    def __init__(self, doc: PdfDocument, layout: Layout):
        self.doc, self.layout = doc, layout
        W, H = layout.page_size
        self.left, self.width = layout.margin, W - 2 * layout.margin
        self.top, self.bottom = H - layout.margin, layout.margin + max(layout.footer, 3 * 2.2)
        self.pages: list[PdfPage] = []
        self.y = -np.inf

    def room(self, height: float) -> PdfPage:
        """The page to draw the next ``height`` mm on, a new one if this one is full; the cursor
        moves down."""
        if not self.pages or self.y - height < self.bottom:
            self.pages.append(self.doc.page(*self.layout.page_size))
            self.y = self.top
        self.y -= height
        return self.pages[-1]

    def text(self, words: str, size: float = _TEXT, indent: float = 0.0, gap: float = 1.45) -> None:
        for line in _wrap(words, size, self.width - indent):
            page = self.room(gap * size)
            page.text(
                PdfText(
                    line,
                    self.left + indent,
                    self.y + 0.3 * size,
                    size,
                    _INK,
                    anchor="start",
                    layer=_LAYERS[0],
                )
            )

    def footers(self) -> None:
        for n, page in enumerate(self.pages, start=1):
            draw_footer(
                page,
                self.layout,
                0,
                (),
                0.25,
                page_text=f"assembly guide, page {n} of {len(self.pages)}",
            )


def _facing_the_last(V: np.ndarray, cells: np.ndarray) -> View:
    """The figures' view, or the same from the other side, whichever sees the last tube in front
    of the first."""
    step = V[cells[-1]].mean(axis=(0, 1)) - V[cells[0]].mean(axis=(0, 1))
    view = View()
    return (
        view if float(step @ view.basis[2]) >= 0 else View(azim=view.azim + 180.0, elev=view.elev)
    )


def _pictures(structure: Structure, steps: int, view: View | None):
    """The scenes of the structure built so far after each step (design angle, the new tube
    picked out), and their common box."""
    state = structure.state()
    V, cells, kinds = drawable(
        structure, state.vertices, segments=32, max_cells=len(structure.cell_curves)
    )
    view = _facing_the_last(V, cells) if view is None else view
    lo, hi = bounding_box(V)
    # a vault's feet on z = 0: draw the ground
    standing = abs(float(lo[2])) <= 1e-6 * float(np.max(hi - lo))
    ground = ground_polygon(lo, hi, view, pad=0.08 * float(np.max(hi - lo))) if standing else None
    scenes = []
    for k in range(1, steps + 1):
        strips = tube_strips(cells[:k])
        rgb = np.tile(STRIP_RGB, (len(strips), 1))
        rgb[-4:] = HIGHLIGHT_RGB
        scenes.append(
            render_strips(
                V, strips, kinds, view, colors=_KIND_COLOURS, crease_width=0.8, strip_rgb=rgb
            )
        )
    corners = np.concatenate(
        [
            view.project(
                np.array(
                    [
                        [x, y, z]
                        for x in (lo[0], hi[0])
                        for y in (lo[1], hi[1])
                        for z in (lo[2], hi[2])
                    ]
                )
            )[0]
        ]
        + ([ground] if ground is not None else [])
    )
    return scenes, ground, np.stack([corners.min(axis=0), corners.max(axis=0)])


def _draw_scene(
    page: PdfPage, scene, ground, box: np.ndarray, frame: tuple[float, float, float, float]
) -> None:
    """A scene fitted, at the scale of ``box``, into ``frame`` = (x, y, width, height) mm."""
    x0, y0, w, h = frame
    size = np.maximum(box[1] - box[0], 1e-12)
    s = min(w / size[0], h / size[1])
    offset = np.array([x0 + 0.5 * (w - s * size[0]), y0 + 0.5 * (h - s * size[1])])

    def to_page(points: np.ndarray, sizes: np.ndarray) -> list[np.ndarray]:
        """Paths given as their points one after the other (N, 2) and the number of points of
        each, on the page."""
        ends = np.cumsum(sizes).tolist()
        mapped = offset + (points - box[0]) * s
        return list(map(mapped.__getitem__, map(slice, [0] + ends[:-1], ends)))

    pt = 25.4 / 72.0
    if ground is not None:
        page.paint(
            to_page(ground, np.array([len(ground)])),
            [GROUND_COLOR],
            [GROUND_EDGE],
            [0.6 * pt],
            layer=_LAYERS[1],
        )
    points, sizes = scene.flat
    fills = [f if n > 2 else None for n, f in zip(sizes.tolist(), _hex_codes(scene.fill))]
    page.paint(
        to_page(points, sizes),
        fills,
        _hex_codes(scene.stroke),
        (scene.widths * pt).tolist(),
        layer=_LAYERS[1],
    )


def _hex_codes(colours: np.ndarray) -> list[str]:
    """``"#rrggbb"`` of each RGB(A) colour (C, 3 or 4) in [0, 1]
    (:func:`~curvefold.figures._scene._hex` of each row, at once)."""
    if len(colours) == 0:
        return []
    # halves to even, as round()
    channels = np.round(255.0 * np.clip(np.asarray(colours, float)[:, :3], 0.0, 1.0)).astype(
        np.int64
    )
    # 0xrrggbb
    unique, which = np.unique(channels @ np.array([1 << 16, 1 << 8, 1]), return_inverse=True)
    codes = [f"#{code:06x}" for code in unique.tolist()]
    return [codes[k] for k in which.ravel().tolist()]


def _panels_text(pages: _Pages, thick: ThickPanels, units: str) -> None:
    """The guide's section on thick panels: what they are, their ids, the order, the hinges."""
    from ..io._tables import UNITS

    t = thick.thickness / UNITS[units].metres  # the model's lengths are metres
    where = "inside" if thick.side[0] > 0 else "outside"
    pages.text("Panels to cut and hinge", _HEAD, gap=2.0)
    for words in (
        f"{len(thick.side)} thick panels, {t:g} {units} thick: {thick.technique}. They are cut "
        "one by one from the cut list on the last pages of this guide (the same as the cut "
        "list PDF, CSV and JSON), a row per panel, numbered in the order the steps assemble "
        "them.",
        "Each panel is named by its id, tube · sheet · strip · panel: its tube, the sheet of "
        "the crease pattern that holds it, its strip (1 to 4 round the tube, strip c from "
        "crease c) and its place along the crease from its start. Mark it on the panel.",
        "Order: tube by tube; in each, sheet A (strip 4, then strip 1) then sheet B (strip 2, "
        "then strip 3), each strip panel by panel from the start of the crease.",
        "Hinges: every edge the cut list marks hinged (red) gets a hinge whose axis is that "
        f"edge of the panel's full face (the one its bevels do not set back), toward the {where} "
        "of its tube: the "
        "axis lies on the crease of the folded structure, so the panels fold exactly as the "
        "pattern does; the bevelled edges turn away from it.",
    ):
        pages.text(words, indent=3.0)


def write_assembly(
    path: str | os.PathLike,
    structure: Structure,
    layout: Layout,
    *,
    view: View | None = None,
    thick: ThickPanels | None = None,
    units: str = "mm",
) -> Path:
    """Write the assembly guide of a structure laid out as ``layout`` (see the module notes).

    Parameters
    ----------
    path : path-like
    structure : Structure
    layout : Layout
        The crease pattern the guide goes with (:func:`~curvefold.io.layout_pattern`):
        its sheets, seam labels, page size and scale bar.
    view : View, optional, keyword-only
        The direction the pictures look from; default the figures' view from the side where
        each new tube comes in front of those before it.
    thick : ThickPanels, optional, keyword-only
        The structure's thick panels: the steps assemble them, and the cut list (in ``units``,
        the model's lengths being metres) follows on A4 pages.

    Returns
    -------
    Path
    """
    plan = assembly_plan(structure, layout, thick=thick)
    doc = PdfDocument(title="assembly guide", layers=_LAYERS)
    pages = _Pages(doc, layout)
    first = layout.sheets()[0].label  # "vault · tube 1 · sheet A", "tube 1 · sheet A"
    kind = first.split(" · ")[0].split()[0] if " · " in first else "structure"
    pages.text(f"{kind.capitalize()}: assembly guide", _TITLE)
    tubes = len(plan.steps)
    pattern = (
        f"{len(layout.pages)} crease-pattern page{'s' * (len(layout.pages) != 1)} at 1 "
        f"model unit = {layout.scale:.4g} mm"
    )
    if thick is None:
        pages.text(
            f"{tubes} tube{'s' * (tubes != 1)} of two sheets each, {len(plan.sheets)} sheets "
            f"on {pattern}. Print the pattern at 100 % and check its 10 mm "
            "scale bar (the one below is the same), or send it to the cutter: cut the outlines, "
            "score the creases and the glue-tab folds. Seams are named S0, S1… on both sheets "
            "they join."
        )
    else:
        pages.text(
            f"{tubes} tube{'s' * (tubes != 1)}, {len(thick.side)} thick panels. The "
            f"{len(plan.sheets)} sheets on {pattern} are the map of the panels: each holds "
            "the panels of two strips of a tube as they lie flat. The panels are cut from the "
            "cut list, not from the pattern."
        )
    pages.text(fold_key(layout))
    heading = "Sheets to cut" if thick is None else "Sheets of the crease pattern"
    pages.text(heading, _HEAD, gap=2.0)
    for sheet in plan.sheets:
        seams = ", ".join(f"{seam_name(i)}{' (tabs)' * tabs}" for i, tabs in sheet.seams)
        seams = f"; seams {seams}" if thick is None else ""
        folds = f"; {_folds_words(sheet.folds)}" if sheet.folds else ""
        pages.text(f"{sheet.label}: pattern page {sheet.page}{seams}{folds}", indent=3.0)
    if thick is not None:
        _panels_text(pages, thick, units)
    else:
        pages.text("Seams", _HEAD, gap=2.0)
    for seam in plan.seams if thick is None else ():
        pages.text(f"{seam_name(seam.id)}: the tabs of {seam.tabs} glue to {seam.onto}", indent=3.0)
    scenes, ground, box = _pictures(structure, len(plan.steps), view)
    aspect = (box[1, 1] - box[0, 1]) / max(box[1, 0] - box[0, 0], 1e-12)
    picture = min(pages.width * aspect, 0.32 * (pages.top - pages.bottom))
    for step, scene in zip(plan.steps, scenes):
        lines = [_wrap(line, _TEXT, pages.width - 3.0) for line in step.lines]
        needed = 2.0 * _HEAD + sum(1.45 * _TEXT * len(w) for w in lines) + picture + 4.0
        if pages.pages and pages.y - needed < pages.bottom:
            pages.y = -np.inf  # a step is not split over two pages
        pages.text(step.title, _HEAD, gap=2.0)
        for line in step.lines:
            pages.text(line, indent=3.0)
        page = pages.room(picture + 4.0)
        _draw_scene(page, scene, ground, box, (pages.left, pages.y + 2.0, pages.width, picture))
    pages.footers()
    if thick is not None:
        from ..io._solids import cut_list_pages
        from ..io._tables import UNITS

        cut_list_pages(doc, thick, 1.0 / UNITS[units].metres, units)
    return doc.save(path)
