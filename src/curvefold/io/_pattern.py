"""Crease patterns for fabrication: SVG, DXF and PDF at true scale in millimetres.

Build a :class:`~curvefold.io.Layout` with :func:`layout_pattern` (placement on
pages, glue tabs, layers, labels, and for cutting machines perforated creases and kerf
compensation; see :mod:`curvefold.io._layout` and :mod:`curvefold.io._cutting`), then write it:

* :func:`write_svg` — one SVG per page, ``width``/``height`` in mm and a viewBox in mm,
  one Inkscape layer per operation and a legend layer (not to cut). One page: written to
  ``path``. Several pages: ``name-p1.svg``, ``name-p2.svg``… beside ``path`` (``path``
  itself is not written), unless ``page_index`` picks one page, which is then written to
  ``path``.
* :func:`write_dxf` — one DXF (R2010, ``$INSUNITS`` = 4, mm) with real layers, colours
  and linetypes; pages in a grid, each framed (:mod:`curvefold.io._dxf`). Needs ``ezdxf``.
* :func:`write_pdf` — one printable PDF page per layout page at 1:1, each operation on
  its own PDF layer (optional content), the page's lines drawn from the layout's arrays
  by :mod:`curvefold.io._pdf`.

Layers are named by operation and drawn in the colours of the layout's cutter convention
(:mod:`curvefold.io._cutters`; ``cutter="print"`` by default: cut black, mountain red
dash-dot, valley blue dashed, glue-tab folds green dotted, glue light green, rulings thin
green, labels purple). Every page carries a footer (:func:`~curvefold.io._legend.page_footer`)
inside its margins, in the convention's reference colour: a 10 mm scale bar with the print
scale, the page number, and a legend of the layers and seam names on that page. Writers
draw every layer except ``rulings`` unless told otherwise (``layers=``). All files are
written atomically.
"""

from __future__ import annotations

import contextlib
import math
import os
from collections.abc import Collection, Sequence
from dataclasses import replace
from pathlib import Path

import numpy as np

from ..geometry._sheets import PatternSheet, sheets
from ..geometry._structure import Structure, check_structure
from ..kernel._errors import InputError
from ..kernel._text import one_line
from ..kernel._validate import check_integer
from ._atomic import atomic_path
from ._cutters import DEFAULT_CUTTER, LEGEND_LAYER
from ._cutters import cutter as _cutter
from ._cutting import prepare_layout
from ._dxf import page_grid, write_dxf
from ._formats import FORMATS, check_formats, formats_of
from ._labels import Label, seam_name
from ._layout import FOOTER, LAYERS, Layout, Page, PlacedSheet, Polyline, layout_sheets, page_size
from ._legend import DEFAULT_LAYERS, LEGEND, Footer, check_layers, check_layout, layer_look, page_footer
from ._pdf import PdfDocument
from ._tables import mm_per_unit

#: Crease-pattern formats :func:`write_pattern` writes.
PATTERN_FORMATS = formats_of("pattern")
#: Print scales are rounded down to one of these times a power of ten.
_NICE = (1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0)


__all__ = [
    "DEFAULT_LAYERS",
    "LAYERS",
    "Label",
    "LEGEND",
    "Footer",
    "page_footer",
    "Layout",
    "Page",
    "PatternSheet",
    "PlacedSheet",
    "Polyline",
    "layout_sheets",
    "page_size",
    "seam_name",
    "PATTERN_FORMATS",
    "layout_pattern",
    "svg_page",
    "write_pattern",
    "write_layout",
    "page_grid",
    "write_dxf",
    "write_pdf",
    "write_svg",
    "draw_footer",
]


def _escape(text: str) -> str:
    """``text`` with &, < and > escaped for XML (:func:`xml.sax.saxutils.escape`, whose import brings urllib's).

    Examples
    --------
    >>> _escape("a < b & c")
    'a &lt; b &amp; c'
    """
    return text.replace("&", "&amp;").replace(">", "&gt;").replace("<", "&lt;")


def _quoteattr(text: str) -> str:
    """``text`` escaped and quoted as an XML attribute value (:func:`xml.sax.saxutils.quoteattr`).

    Examples
    --------
    >>> print(_quoteattr('say "hi"'), _quoteattr("it's"), _quoteattr("it's \\"x\\""))
    'say "hi"' "it's" "it's &quot;x&quot;"
    """
    text = _escape(text).replace("\n", "&#10;").replace("\r", "&#13;").replace("\t", "&#9;")
    if '"' not in text:
        return f'"{text}"'
    return f"'{text}'" if "'" not in text else '"{}"'.format(text.replace('"', "&quot;"))


def _check_width(line_width: float) -> float:
    if not (isinstance(line_width, (int, float)) and math.isfinite(line_width) and line_width > 0):
        raise InputError(f"line_width must be a positive number of mm, got {line_width!r}")
    return float(line_width)


# --------------------------------------------------------------------------------------
# SVG


def _svg_points(points: np.ndarray, height: float) -> str:
    flipped = np.column_stack([points[:, 0], height - points[:, 1]])  # y down
    return " ".join(["%.3f,%.3f"] * len(points)) % tuple(flipped.ravel().tolist())


def _svg_label(t: Label, height: float) -> str:
    a = math.radians(t.angle)
    # baseline 0.35 em below the centre, so the capitals sit centred on it
    x = t.position[0] + 0.35 * t.size * math.sin(a)
    y = height - (t.position[1] - 0.35 * t.size * math.cos(a))
    rot = f' transform="rotate({-t.angle:.2f} {x:.3f} {y:.3f})"' if abs(t.angle) > 1e-9 else ""
    return f'<text x="{x:.3f}" y="{y:.3f}" font-size="{t.size:.3f}"{rot}>{_escape(one_line(t.text))}</text>'


_FONT = "font-family:'DejaVu Sans',Arial,Helvetica,sans-serif;text-anchor:middle"


def _svg_style(layout: Layout, key: str, lw: float, colour: str | None = None) -> str:
    """The SVG style of a layer's lines (or text, for ``labels``), in ``colour`` or the layer's own."""
    _, own, st = layer_look(layout, key)
    colour = colour or own
    if key in ("labels", "legend"):
        return f"fill:{colour};stroke:none;{_FONT}"
    if st.fill:
        return f"fill:{colour};stroke:none"
    style = f"fill:none;stroke:{colour};stroke-width:{lw * st.width:g};stroke-linecap:butt;stroke-linejoin:round"
    return style + (";stroke-dasharray:" + ",".join(f"{d:g}" for d in st.dashes) if st.dashes else "")


def svg_page(layout: Layout, page_index: int = 0, *, layers: Collection[str] | None = None,
             line_width: float = 0.25) -> str:
    """One page of ``layout`` as SVG text (see :func:`write_svg`)."""
    check_layout(layout)
    page_index = check_integer(page_index, "page_index", f"[0, {len(layout.pages) - 1}]")
    names = check_layers(layers)
    lw = _check_width(line_width)
    page = layout.pages[page_index]
    W, H = page.size
    out = [
        '<?xml version="1.0" encoding="UTF-8" standalone="no"?>',
        '<svg xmlns="http://www.w3.org/2000/svg" version="1.1"',
        '     xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"',
        '     xmlns:sodipodi="http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd"',
        f'     width="{W:g}mm" height="{H:g}mm" viewBox="0 0 {W:g} {H:g}">',
        f"<title>curvefold crease pattern, page {page_index + 1} of {len(layout.pages)}</title>",
        '<sodipodi:namedview id="namedview" inkscape:document-units="mm" showgrid="false"/>',
    ]
    for key in names:
        if key == "labels":
            body = [_svg_label(t, H) for t in page.labels()]
        else:
            body = [f'<{"polygon" if p.closed else "polyline"} points="{_svg_points(p.points, H)}"/>'
                    for p in page.on_layer(key)]
        out.append(f'<g inkscape:groupmode="layer" id="layer-{key}" inkscape:label={_quoteattr(layer_look(layout, key)[0])} '
                   f'style={_quoteattr(_svg_style(layout, key, lw))}>')
        out.extend(body)
        out.append("</g>")
    footer = page_footer(layout, page_index, names)
    out.append(f'<g inkscape:groupmode="layer" id="layer-legend" inkscape:label={_quoteattr(LEGEND_LAYER)} '
               f'style={_quoteattr(_svg_style(layout, "legend", lw))}>')
    out.append(f'<polygon points="{_svg_points(footer.bar, H)}" style="fill:{footer.colour};stroke:none"/>')
    out += [f'<{"polygon" if layer_look(layout, key)[2].fill else "polyline"} points="{_svg_points(points, H)}" '
            f'style={_quoteattr(_svg_style(layout, key, lw, footer.colour))}/>' for key, points in footer.samples]
    out += [_svg_label(t, H) for t in footer.texts]
    out.append("</g>")
    out.append("</svg>\n")
    return "\n".join(out)


def write_svg(path: str | os.PathLike, layout: Layout, page_index: int | None = None, *,
              layers: Collection[str] | None = None, line_width: float = 0.25) -> tuple[Path, ...]:
    """Write the layout as SVG, one file per page, in millimetres.

    Parameters
    ----------
    path : path-like
        Target file. With several pages and no ``page_index`` the pages go to
        ``<stem>-p1<suffix>``, ``<stem>-p2<suffix>``… in the same folder instead.
    layout : Layout
    page_index : int, optional
        Write only this page (0-based) to ``path``.
    layers : collection of str, optional
        Layers to draw; default :data:`DEFAULT_LAYERS` (all but ``rulings``).
    line_width : float
        Stroke width in mm (rulings are drawn at half of it).

    Returns
    -------
    tuple of Path
        The files written, in page order. Either every page is written or, on an error,
        none is (and no temporary file is left).
    """
    check_layout(layout)
    target = Path(path)
    if page_index is not None:
        jobs = [(target, page_index)]
    elif len(layout.pages) == 1:
        jobs = [(target, 0)]
    else:
        jobs = [(target.with_name(f"{target.stem}-p{i + 1}{target.suffix}"), i) for i in range(len(layout.pages))]
    texts = [(p, svg_page(layout, i, layers=layers, line_width=line_width).encode("utf-8")) for p, i in jobs]
    # All pages or none: every page goes to a temporary file, renamed only once all are written.
    with contextlib.ExitStack() as stack:
        for p, data in texts:
            stack.enter_context(atomic_path(p)).write_bytes(data)
    return tuple(p for p, _ in texts)


# --------------------------------------------------------------------------------------
# PDF


def draw_footer(canvas, layout: Layout, page_index: int, names: Sequence[str], lw: float, *, page_text: str | None = None) -> None:
    """Draw a page's footer (:func:`page_footer`) on a :class:`~curvefold.io._pdf.PdfPage`, on the legend layer."""
    foot = page_footer(layout, page_index, names, page_text=page_text)
    canvas.fill([foot.bar], foot.colour, layer=LEGEND_LAYER)
    for key, points in foot.samples:
        st = layer_look(layout, key)[2]
        if st.fill:
            canvas.fill([points], foot.colour, layer=LEGEND_LAYER)
        else:
            canvas.stroke([points], foot.colour, lw * st.width, dashes=st.dashes, layer=LEGEND_LAYER)
    for t in foot.texts:
        canvas.text(t.text, t.position[0], t.position[1] - 0.35 * t.size, t.size, foot.colour, layer=LEGEND_LAYER)


def _draw_page(canvas, page: Page, layout: Layout, index: int, names: tuple[str, ...], lw: float, footer: bool) -> None:
    for key in names:
        layer, colour, st = layer_look(layout, key)
        if key == "labels":
            for t in page.labels():
                a = math.radians(t.angle)  # baseline 0.35 em below the centre, as in the SVG
                canvas.text(t.text, t.position[0] + 0.35 * t.size * math.sin(a), t.position[1] - 0.35 * t.size * math.cos(a),
                            t.size, colour, angle=t.angle, layer=layer)
            continue
        lines = page.on_layer(key)
        if not lines:
            continue
        if st.fill:
            canvas.fill([p.points for p in lines], colour, layer=layer)
        else:
            canvas.stroke([p.points for p in lines], colour, lw * st.width, dashes=st.dashes, closed=[p.closed for p in lines], layer=layer)
    if footer:
        draw_footer(canvas, layout, index, names, lw)


def write_pdf(path: str | os.PathLike, layout: Layout, *, layers: Collection[str] | None = None,
              line_width: float = 0.25, scale_bar: bool = True) -> Path:
    """Write the layout as a printable multi-page PDF at 1:1, one PDF layer per operation.

    Each page is the layout's page size in mm; its footer (:func:`page_footer`: a 10 mm
    scale bar to check the print scale with a ruler, and the legend) sits inside the
    margins, where printers print.

    Parameters
    ----------
    path : path-like
    layout : Layout
    layers : collection of str, optional
        Layers to draw; default :data:`DEFAULT_LAYERS` (all but ``rulings``).
    line_width : float
        Line width in mm.
    scale_bar : bool
        Draw the footer: the 10 mm scale bar and the legend.

    Returns
    -------
    Path
    """
    check_layout(layout)
    names = check_layers(layers)
    lw = _check_width(line_width)
    doc = PdfDocument(title="crease pattern", layers=[layer_look(layout, key)[0] for key in names] + [LEGEND_LAYER] * scale_bar)
    for index, page in enumerate(layout.pages):
        _draw_page(doc.page(*page.size), page, layout, index, names, lw, scale_bar)
    return doc.save(path)


# --------------------------------------------------------------------------------------
# crease patterns on paper


def _nice_floor(value: float) -> float:
    """The largest 1, 1.25, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 × 10^k not above ``value``."""
    exp = math.floor(math.log10(value))
    mant = value / 10.0**exp
    return max(m for m in _NICE if m <= mant * (1 + 1e-12)) * 10.0**exp


def _fit_scale(parts, page, units: str, margin_mm: float, footer_mm: float, tab_mm: float) -> float:
    """Page units per model unit that fit the largest sheet (principal axes) with its tabs."""
    W, H = page_size(page, units=units)
    room = np.array(sorted((W - 2 * margin_mm, H - 2 * margin_mm - footer_mm), reverse=True)) - 2 * tab_mm
    if (room <= 0).any():
        raise InputError(f"page {page!r} leaves no room for a sheet inside the margins and glue tabs")
    best = math.inf
    for p in parts:
        xy = p.mesh.vertices_coords[:, :2]
        xy = xy - xy.mean(axis=0)
        _, _, vt = np.linalg.svd(xy, full_matrices=False)
        ext = np.sort(np.ptp(xy @ vt.T, axis=0))[::-1]
        best = min(best, float(np.min(room / np.maximum(ext, 1e-300))))
    return _nice_floor(best / mm_per_unit(units))


def layout_pattern(
    structure: Structure,
    *,
    fold_angle: float | None = None,
    degrees: bool = True,
    page="A4",
    units: str = "mm",
    scale: float | None = None,
    glue_tabs: bool = True,
    name: str = "",
    keep: Sequence[np.ndarray] | None = None,
    cutter: str = DEFAULT_CUTTER,
    perforation: tuple[float, float] | None = None,
    kerf: float = 0.0,
) -> Layout:
    """The sheets of a structure placed on pages with glue tabs, layers and labels, ready to cut.

    Parameters
    ----------
    structure : Structure
    fold_angle : float, optional, keyword-only
        Target 2α of the folds (their M/V); default the lattice's own.
    degrees : bool, keyword-only
    page : str or (2,) tuple, keyword-only
        Page name (``"A4"``…) or (width, height) in ``units``.
    units : {"mm", "cm", "in", "pt"}, keyword-only
        Unit of ``page`` and ``scale``.
    scale : float, optional, keyword-only
        Page length in ``units`` per model unit. Default: the largest sheet (along its
        principal axes, long side along the page's long side, with room for glue tabs)
        fills the page inside its margins, rounded down to 1, 1.25, 1.5, 2, 2.5, 3, 4, 5,
        6 or 8 × 10^k so the print scale reads plainly (the PDF footer states it).
    glue_tabs : bool, keyword-only
    name : str, keyword-only
        Label prefix.
    keep : sequence of (m_k,) array_like of int, optional, keyword-only
        The samples each tube's sheets keep (:func:`curvefold.geometry.choose_sampling`);
        default every sample.
    cutter : str, keyword-only
        The colour convention of the files, a key of :data:`curvefold.io.CUTTERS`.
    perforation : (float, float), optional, keyword-only
        (dash, gap) in mm: draw every crease as cut dashes (:func:`curvefold.io._cutting.perforation_dashes`).
    kerf : float, keyword-only
        Width in mm a cutter removes: the cut outlines move out by half of it.

    Returns
    -------
    curvefold.io.Layout
    """
    check_structure(structure)
    _cutter(cutter)
    parts = sheets(structure, fold_angle=fold_angle, degrees=degrees, name=name, keep=keep)
    fitted = _fit(parts, page, units, scale, glue_tabs)
    return prepare_layout(replace(fitted, cutter=cutter), perforation=perforation, kerf=kerf)


def _fit(parts, page, units, scale, glue_tabs) -> Layout:
    """The layout of ``parts`` at ``scale``, or at the largest plain scale that fits."""
    if scale is not None:
        return layout_sheets(parts, page=page, units=units, scale=scale, glue_tabs=glue_tabs)
    guess = _fit_scale(parts, page, units, 10.0, FOOTER, 6.0 if glue_tabs else 0.0)
    # The layout turns each sheet to its minimum-area rectangle, which can be longer than the
    # principal-axes box; step down the series of plain scales until it fits.
    for attempt in range(4):
        try:
            return layout_sheets(parts, page=page, units=units, scale=guess, glue_tabs=glue_tabs)
        except InputError:
            if attempt == 3:
                raise
            guess = _nice_floor(guess * (1 - 1e-9))
    raise AssertionError("unreachable")  # pragma: no cover


def write_pattern(
    path_stem: str | os.PathLike,
    structure: Structure,
    *,
    formats: Sequence[str] = PATTERN_FORMATS,
    page="A4",
    scale: float | None = None,
    units: str = "mm",
    glue_tabs: bool = True,
    rulings: bool = False,
    fold_angle: float | None = None,
    degrees: bool = True,
    name: str = "",
    keep: Sequence[np.ndarray] | None = None,
    cutter: str = DEFAULT_CUTTER,
    perforation: tuple[float, float] | None = None,
    kerf: float = 0.0,
) -> tuple[Path, ...]:
    """Write the crease pattern of a structure, laid out on pages, as SVG, DXF and/or PDF.

    Parameters
    ----------
    path_stem : path-like
        Files are ``<stem>.svg`` (or ``<stem>-p1.svg``… for several pages), ``<stem>.dxf``
        and ``<stem>.pdf``.
    structure : Structure
    formats : sequence of {"svg", "dxf", "pdf"}, keyword-only
    page, scale, units, glue_tabs, fold_angle, degrees, name, keep, cutter, perforation, kerf : keyword-only
        As in :func:`layout_pattern`.
    rulings : bool, keyword-only
        Also draw the rulings (thin green, for scoring).

    Returns
    -------
    tuple of Path
        The files written, in the order of ``formats``; the pages of a format in page
        order (``<stem>-p1.svg``, ``<stem>-p2.svg``…).
    """
    formats = check_formats(formats, "pattern")
    layout = layout_pattern(structure, fold_angle=fold_angle, degrees=degrees, page=page, units=units, scale=scale,
                            glue_tabs=glue_tabs, name=name, keep=keep, cutter=cutter, perforation=perforation, kerf=kerf)
    return write_layout(path_stem, layout, formats=formats, rulings=rulings)


def write_layout(path_stem: str | os.PathLike, layout: Layout, *, formats: Sequence[str] = PATTERN_FORMATS,
                 rulings: bool = False) -> tuple[Path, ...]:
    """Write a crease pattern already laid out (:func:`layout_pattern`) in each of ``formats``, with the
    writer the registry names for it; arguments and result as in :func:`write_pattern`."""
    check_layout(layout)
    formats = check_formats(formats, "pattern")
    layers = LAYERS if rulings else DEFAULT_LAYERS
    out: list[Path] = []
    for name in formats:  # each format's writer, from the registry
        f = FORMATS[name]
        written = f.load_writer()(f.path(path_stem), layout, layers=layers)
        out.extend(written if isinstance(written, tuple) else (written,))
    return tuple(out)
