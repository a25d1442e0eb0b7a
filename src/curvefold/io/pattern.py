"""Crease patterns for fabrication: SVG, DXF and PDF at true scale in millimetres.

Build a :class:`~curvefold.io.layout.Layout` with :func:`layout_sheets` (placement on
pages, glue tabs, layers, labels; see :mod:`curvefold.io.layout`), then write it:

* :func:`write_svg` — one SVG per page, ``width``/``height`` in mm and a viewBox in mm,
  one Inkscape layer per fabrication layer and a ``legend`` layer (not to cut). One page:
  written to ``path``. Several pages: ``name-p1.svg``, ``name-p2.svg``… beside ``path``
  (``path`` itself is not written), unless ``page_index`` picks one page, which is then
  written to ``path``.
* :func:`write_dxf` — one DXF (R2010, ``$INSUNITS`` = 4, mm) with real layers, colours
  and linetypes; pages in a grid, each framed, with the drawing's extents set. Needs
  ``ezdxf``.
* :func:`write_pdf` — one printable PDF page per layout page at 1:1. Needs ``matplotlib``.

Every page carries a footer (:func:`page_footer`) inside its margins: a 10 mm scale bar
with the print scale, the page number, and a legend of the line styles and seam names
on that page.

Layer styles (:data:`LAYER_STYLES`, colours from :data:`curvefold.io.tables.COLOURS`):
``cut`` black solid, ``mountain`` red dash-dot, ``valley`` blue dashed, ``seam`` (tab fold
lines) green short dashes, ``glue`` light-green fill, ``rulings`` thin green, ``labels``
purple text. Writers draw every layer except ``rulings`` unless told otherwise
(``layers=``). All files are written atomically.
"""

from __future__ import annotations

import contextlib
import math
import os
from collections.abc import Collection, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from ..geometry.sheets import PatternSheet, sheets
from ..geometry.structure import Structure, check_structure
from ..kernel.arrays import FrozenArrays, readonly
from ..kernel.errors import InputError
from ..kernel.text import one_line
from ..kernel.validate import check_integer
from .atomic import atomic_path
from .formats import FORMATS, check_formats, formats_of
from .labels import Label, seam_name, text_width
from .layout import FOOTER, LAYERS, Layout, Page, PlacedSheet, Polyline, layout_sheets, page_size
from .tables import COLOURS, CREATOR, mm_per_unit, rgb8

#: Crease-pattern formats :func:`write_pattern` writes.
PATTERN_FORMATS = formats_of("pattern")
#: Print scales are rounded down to one of these times a power of ten.
_NICE = (1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0)


__all__ = [
    "DEFAULT_LAYERS",
    "LAYERS",
    "LAYER_STYLES",
    "LayerStyle",
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
    "page_grid",
    "write_dxf",
    "write_pdf",
    "write_svg",
]

_PT_PER_MM = 72.0 / 25.4


@dataclass(frozen=True)
class LayerStyle:
    """How one layer is drawn.

    Attributes
    ----------
    color : str
        ``#rrggbb`` for SVG, PDF and the DXF true colour.
    aci : int
        AutoCAD colour index, for DXF readers that ignore true colour.
    linetype : str
        DXF linetype name.
    dashes : tuple of float
        Dash pattern in mm (on, off, on, off…); empty for a solid line.
    width : float
        Line width as a multiple of the writer's ``line_width``.
    fill : bool
        Closed polylines are filled areas, not lines.
    """

    color: str
    aci: int
    linetype: str = "CONTINUOUS"
    dashes: tuple[float, ...] = ()
    width: float = 1.0
    fill: bool = False


#: Style of every layer in :data:`curvefold.io.layout.LAYERS`.
LAYER_STYLES = MappingProxyType({
    "glue": LayerStyle(COLOURS["glue"], 3, fill=True),
    "rulings": LayerStyle(COLOURS["ruling"], 3, width=0.5),
    "seam": LayerStyle(COLOURS["tab"], 3, "DOT", (0.8, 0.8)),
    "valley": LayerStyle(COLOURS["valley"], 5, "DASHED", (3.0, 1.5)),
    "mountain": LayerStyle(COLOURS["fold"], 1, "DASHDOT", (4.0, 1.2, 0.7, 1.2)),
    "cut": LayerStyle(COLOURS["boundary"], 7),
    "labels": LayerStyle(COLOURS["label"], 6),
})

#: Layers the writers draw by default.
DEFAULT_LAYERS = tuple(name for name in LAYERS if name != "rulings")

#: What each layer means, as the legend says it.
LEGEND = MappingProxyType({
    "cut": "cut",
    "mountain": "mountain fold",
    "valley": "valley fold",
    "seam": "glue-tab fold",
    "glue": "glue",
    "rulings": "ruling (score)",
    "labels": "glue the edges named alike",
})
_FOOTER_TEXT = 2.5  # em height of the footer's text, mm
_SAMPLE = 8.0  # length of a legend's sample line, mm


@dataclass(frozen=True, eq=False)
class Footer(FrozenArrays):
    """The scale bar, scale note and legend of one page, in page mm inside its footer band.

    Attributes
    ----------
    samples : tuple of (str, (k, 2) ndarray)
        A sample of every drawn layer but the labels: a line in the layer's style, or for
        a filled layer a closed rectangle.
    bar : (4, 2) ndarray
        The 10 mm scale bar, a rectangle to fill black.
    texts : tuple of (Label, str)
        Text and its colour ``#rrggbb``.
    """

    samples: tuple[tuple[str, np.ndarray], ...]
    bar: np.ndarray
    texts: tuple[tuple[Label, str], ...]


def page_footer(layout: Layout, page_index: int, layers: Collection[str] | None = None) -> Footer:
    """The footer of a page: a 10 mm scale bar with the print scale, and the legend of the ``layers`` it draws.

    It lies in the band of :attr:`Layout.footer` above the bottom margin, so it prints
    wherever the sheets do. Text starts where its box is estimated (:func:`text_width`).
    """
    page = layout.pages[page_index]
    drawn = set(_check_layers(layers))
    names = [name for name in LEGEND if name in drawn and (page.labels() if name == "labels" else page.on_layer(name))]
    W, _ = layout.page_size
    m, size = layout.margin, _FOOTER_TEXT
    top = m + max(layout.footer, 3 * size) - 0.5 * size  # centre line of the first row
    grey = "#444444"

    def text(words: str, x: float, y: float, colour: str = grey) -> tuple[Label, str]:
        return Label(words, (x + 0.5 * text_width(words, size), y), 0.0, size, "legend"), colour

    bar = np.array([[m, top - 0.6], [m + 10.0, top - 0.6], [m + 10.0, top + 0.6], [m, top + 0.6]])
    note = (f"10 mm: print at 100 % · 1 model unit = {layout.scale:.4g} mm · "
            f"page {page_index + 1} of {len(layout.pages)} · curvefold")
    texts = [text(note, m + 12.0, top)]
    samples = []
    x, y = m, top - 1.8 * size
    for name in names:
        words = LEGEND[name]
        lead = text_width(seam_name(1), size) if name == "labels" else _SAMPLE
        width = lead + 1.5 + text_width(words, size)
        if x > m and x + width > W - m:  # next row
            x, y = m, y - 1.8 * size
        if name == "labels":
            texts.append(text(seam_name(1), x, y, LAYER_STYLES["labels"].color))
        elif LAYER_STYLES[name].fill:
            samples.append((name, np.array([[x, y - 1.0], [x + _SAMPLE, y - 1.0], [x + _SAMPLE, y + 1.0], [x, y + 1.0]])))
        else:
            samples.append((name, np.array([[x, y], [x + _SAMPLE, y]])))
        texts.append(text(words, x + lead + 1.5, y))
        x += width + 4.0
    return Footer(tuple((name, readonly(points)) for name, points in samples), bar, tuple(texts))

# Cap height of a font as a fraction of its em height (DXF TEXT heights are cap heights).
_CAP_HEIGHT = 0.72


def _check_layout(layout: Layout) -> None:
    if not isinstance(layout, Layout):
        raise InputError(f"layout must be a Layout (from layout_sheets), got {type(layout).__name__}")


def _check_layers(layers: Collection[str] | None) -> tuple[str, ...]:
    if layers is None:
        return DEFAULT_LAYERS
    if isinstance(layers, str):
        layers = (layers,)
    unknown = sorted(set(layers) - set(LAYERS))
    if unknown:
        raise InputError(f"layers must be among {list(LAYERS)}, got unknown {unknown}")
    return tuple(name for name in LAYERS if name in set(layers))


def _check_width(line_width: float) -> float:
    if not (isinstance(line_width, (int, float)) and math.isfinite(line_width) and line_width > 0):
        raise InputError(f"line_width must be a positive number of mm, got {line_width!r}")
    return float(line_width)


def _closed(p: Polyline) -> np.ndarray:
    return np.concatenate([p.points, p.points[:1]]) if p.closed else p.points


# --------------------------------------------------------------------------------------
# SVG


def _svg_points(points: np.ndarray, height: float) -> str:
    return " ".join(f"{x:.3f},{height - y:.3f}" for x, y in points.tolist())


def _svg_label(t: Label, height: float) -> str:
    a = math.radians(t.angle)
    # baseline 0.35 em below the centre, so the capitals sit centred on it
    x = t.position[0] + 0.35 * t.size * math.sin(a)
    y = height - (t.position[1] - 0.35 * t.size * math.cos(a))
    rot = f' transform="rotate({-t.angle:.2f} {x:.3f} {y:.3f})"' if abs(t.angle) > 1e-9 else ""
    return f'<text x="{x:.3f}" y="{y:.3f}" font-size="{t.size:.3f}"{rot}>{escape(one_line(t.text))}</text>'


def svg_page(layout: Layout, page_index: int = 0, *, layers: Collection[str] | None = None,
             line_width: float = 0.25) -> str:
    """One page of ``layout`` as SVG text (see :func:`write_svg`)."""
    _check_layout(layout)
    page_index = check_integer(page_index, "page_index", f"[0, {len(layout.pages) - 1}]")
    names = _check_layers(layers)
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
    for name in names:
        if name == "labels":
            body = [_svg_label(t, H) for t in page.labels()]
        else:
            body = [f'<{"polygon" if p.closed else "polyline"} points="{_svg_points(p.points, H)}"/>'
                    for p in page.on_layer(name)]
        out.append(f'<g inkscape:groupmode="layer" id="layer-{name}" inkscape:label={quoteattr(name)} '
                   f'style={quoteattr(_svg_style(name, lw))}>')
        out.extend(body)
        out.append("</g>")
    footer = page_footer(layout, page_index, names)
    out.append('<g inkscape:groupmode="layer" id="layer-legend" inkscape:label="legend (not to cut)">')
    out.append(f'<polygon points="{_svg_points(footer.bar, H)}" style="fill:#000000;stroke:none"/>')
    out += [f'<{"polygon" if LAYER_STYLES[name].fill else "polyline"} points="{_svg_points(points, H)}" '
            f'style={quoteattr(_svg_style(name, lw))}/>' for name, points in footer.samples]
    out += [f'<g style={quoteattr(_svg_style("labels", lw).replace(LAYER_STYLES["labels"].color, colour))}>{_svg_label(t, H)}</g>'
            for t, colour in footer.texts]
    out.append("</g>")
    out.append("</svg>\n")
    return "\n".join(out)


def _svg_style(name: str, lw: float) -> str:
    """The SVG style of a layer's lines (or text, for ``labels``)."""
    st = LAYER_STYLES[name]
    if name == "labels":
        return f"fill:{st.color};stroke:none;font-family:'DejaVu Sans',Arial,Helvetica,sans-serif;text-anchor:middle"
    if st.fill:
        return f"fill:{st.color};stroke:none"
    style = f"fill:none;stroke:{st.color};stroke-width:{lw * st.width:g};stroke-linecap:butt;stroke-linejoin:round"
    return style + (";stroke-dasharray:" + ",".join(f"{d:g}" for d in st.dashes) if st.dashes else "")


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
    _check_layout(layout)
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
# DXF


def page_grid(count: int, size: tuple[float, float], spacing: float) -> np.ndarray:
    """Lower-left corners (count, 2) of pages laid in a grid of ⌈√count⌉ columns, row by row from the top.

    Examples
    --------
    >>> page_grid(3, (210.0, 297.0), 20.0).tolist()
    [[0.0, 0.0], [230.0, 0.0], [0.0, -317.0]]
    """
    columns = math.ceil(math.sqrt(count))
    i = np.arange(count)
    return np.stack([(i % columns) * (size[0] + spacing), -(i // columns) * (size[1] + spacing)], axis=1).astype(float)


def write_dxf(path: str | os.PathLike, layout: Layout, *, layers: Collection[str] | None = None,
              page_spacing: float = 20.0) -> Path:
    """Write the layout as one DXF drawing in millimetres (needs ``ezdxf``).

    Every fabrication layer is a DXF layer with its colour (AutoCAD index and true colour),
    linetype (``CONTINUOUS`` cut, ``DASHDOT`` mountain, ``DASHED`` valley, ``DOT`` tab
    fold lines; patterns in mm) and lineweight. Lines are ``LWPOLYLINE`` entities, glue
    areas solid ``HATCH`` entities and labels ``TEXT`` (height = cap height, centred).
    Pages lie in a grid (:func:`page_grid`), each framed on layer ``pages``, with its
    footer (scale bar and legend) on layer ``legend``; both layers do not plot. The
    header's ``$EXTMIN``/``$EXTMAX`` and the initial view hold every page.

    Parameters
    ----------
    path : path-like
    layout : Layout
    layers : collection of str, optional
        Layers to write; default :data:`DEFAULT_LAYERS` (all but ``rulings``).
    page_spacing : float
        Gap between pages, mm.

    Returns
    -------
    Path
    """
    _check_layout(layout)
    names = _check_layers(layers)
    if not (isinstance(page_spacing, (int, float)) and math.isfinite(page_spacing) and page_spacing >= 0):
        raise InputError(f"page_spacing must be a non-negative number of mm, got {page_spacing!r}")
    try:
        import ezdxf
        from ezdxf import colors
        from ezdxf.enums import TextEntityAlignment
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("write_dxf needs ezdxf: pip install 'ezdxf>=1.1,<2'") from exc

    doc = ezdxf.new("R2010", units=4)
    doc.header["$INSUNITS"] = 4
    doc.header["$MEASUREMENT"] = 1
    doc.header["$LTSCALE"] = 1.0
    for name in names:
        st = LAYER_STYLES[name]
        if st.dashes and st.linetype not in doc.linetypes:
            pattern = [float(sum(st.dashes))] + [d if k % 2 == 0 else -d for k, d in enumerate(st.dashes)]
            doc.linetypes.add(st.linetype, pattern, description=f"curvefold {name} " + " ".join(f"{d:g}" for d in st.dashes))
        doc.layers.add(name, color=st.aci, true_color=colors.rgb2int(rgb8(st.color)),
                       linetype=st.linetype if st.dashes else "CONTINUOUS", lineweight=13 if st.width < 1 else 25)
    for name in ("pages", "legend"):
        doc.layers.add(name, color=8).dxf.plot = 0
    msp = doc.modelspace()

    def text(words: str, position, size: float, angle: float, layer: str, **attributes) -> None:
        entity = msp.add_text(words, height=_CAP_HEIGHT * size, rotation=angle, dxfattribs={"layer": layer, **attributes})
        entity.set_placement(tuple(float(v) for v in position), align=TextEntityAlignment.MIDDLE_CENTER)

    W, H = layout.page_size
    corners = page_grid(len(layout.pages), (W, H), page_spacing)
    for i, (page, shift) in enumerate(zip(layout.pages, corners)):
        msp.add_lwpolyline([tuple(shift), (shift[0] + W, shift[1]), (shift[0] + W, shift[1] + H), (shift[0], shift[1] + H)],
                           close=True, dxfattribs={"layer": "pages"})
        for name in names:
            st = LAYER_STYLES[name]
            if name == "labels":
                for t in page.labels():
                    text(one_line(t.text), np.asarray(t.position) + shift, t.size, t.angle, name)
                continue
            for p in page.on_layer(name):
                pts = (p.points + shift).tolist()
                if st.fill and p.closed:
                    hatch = msp.add_hatch(color=256, dxfattribs={"layer": name})
                    hatch.paths.add_polyline_path(pts, is_closed=True)
                else:
                    msp.add_lwpolyline(pts, close=p.closed, dxfattribs={"layer": name})
        footer = page_footer(layout, i, names)
        msp.add_hatch(color=7, dxfattribs={"layer": "legend"}).paths.add_polyline_path((footer.bar + shift).tolist(), is_closed=True)
        for name, points in footer.samples:
            st = LAYER_STYLES[name]
            style = {"layer": "legend", "true_color": colors.rgb2int(rgb8(st.color)), "linetype": st.linetype if st.dashes else "CONTINUOUS"}
            if st.fill:
                msp.add_hatch(dxfattribs=style).paths.add_polyline_path((points + shift).tolist(), is_closed=True)
            else:
                msp.add_lwpolyline((points + shift).tolist(), dxfattribs=style)
        for t, colour in footer.texts:
            text(t.text, np.asarray(t.position) + shift, t.size, 0.0, "legend", true_color=colors.rgb2int(rgb8(colour)))
    lo, hi = corners.min(axis=0), corners.max(axis=0) + (W, H)
    msp.dxf.extmin = (float(lo[0]), float(lo[1]), 0.0)  # ezdxf writes them to $EXTMIN, $EXTMAX
    msp.dxf.extmax = (float(hi[0]), float(hi[1]), 0.0)
    doc.set_modelspace_vport(height=float(hi[1] - lo[1]) * 1.05, center=tuple(float(v) for v in 0.5 * (lo + hi)))
    with atomic_path(path) as tmp:
        doc.saveas(tmp)
    return Path(path)


# --------------------------------------------------------------------------------------
# PDF


def _draw_page(fig, page: Page, layout: Layout, number: int, names: tuple[str, ...], lw: float,
               footer: bool) -> None:
    from matplotlib.collections import LineCollection, PolyCollection
    from matplotlib.patches import Polygon

    W, H = page.size
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    ax.set_xlim(0, W)
    ax.set_ylim(0, H)
    ax.set_axis_off()
    for z, name in enumerate(names):
        st = LAYER_STYLES[name]
        if name == "labels":
            for t in page.labels():
                ax.text(t.position[0], t.position[1], one_line(t.text), fontsize=t.size * _PT_PER_MM, rotation=t.angle,
                        rotation_mode="anchor", ha="center", va="center", color=st.color,
                        family="sans-serif", zorder=z, parse_math=False)
            continue
        lines = page.on_layer(name)
        if not lines:
            continue
        if st.fill:
            ax.add_collection(PolyCollection([p.points for p in lines], facecolors=st.color, edgecolors="none",
                                             zorder=z))
            continue
        style = (0, tuple(d * _PT_PER_MM for d in st.dashes)) if st.dashes else "solid"
        ax.add_collection(LineCollection([_closed(p) for p in lines], colors=st.color,
                                         linewidths=lw * st.width * _PT_PER_MM, linestyles=style,
                                         capstyle="butt", joinstyle="round", zorder=z))
    if footer:
        foot = page_footer(layout, number - 1, names)
        ax.add_patch(Polygon(foot.bar, closed=True, facecolor="black", edgecolor="none"))
        for name, points in foot.samples:
            st = LAYER_STYLES[name]
            if st.fill:
                ax.add_patch(Polygon(points, closed=True, facecolor=st.color, edgecolor="none"))
            else:
                style = (0, tuple(d * _PT_PER_MM for d in st.dashes)) if st.dashes else "solid"
                ax.add_collection(LineCollection([points], colors=st.color, linewidths=lw * st.width * _PT_PER_MM,
                                                 linestyles=style, capstyle="butt"))
        for t, colour in foot.texts:
            ax.text(t.position[0], t.position[1], t.text, fontsize=t.size * _PT_PER_MM, ha="center", va="center",
                    color=colour, family="sans-serif")


def write_pdf(path: str | os.PathLike, layout: Layout, *, layers: Collection[str] | None = None,
              line_width: float = 0.25, scale_bar: bool = True) -> Path:
    """Write the layout as a printable multi-page PDF at 1:1 (needs ``matplotlib``).

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
    _check_layout(layout)
    names = _check_layers(layers)
    lw = _check_width(line_width)
    import matplotlib
    from matplotlib.backends.backend_pdf import PdfPages
    from matplotlib.figure import Figure

    rc = {"lines.scale_dashes": False, "path.simplify": False, "pdf.fonttype": 42,
          "font.sans-serif": ["DejaVu Sans", "Arial", "Helvetica"]}
    with matplotlib.rc_context(rc), atomic_path(path) as tmp:
        with PdfPages(tmp, metadata={"Creator": CREATOR, "Title": "crease pattern", "CreationDate": None}) as pdf:
            for number, page in enumerate(layout.pages, start=1):
                fig = Figure(figsize=(page.size[0] / 25.4, page.size[1] / 25.4))
                _draw_page(fig, page, layout, number, names, lw, scale_bar)
                pdf.savefig(fig)
    return Path(path)


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
) -> Layout:
    """The sheets of a structure placed on pages with glue tabs, layers and labels.

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
        The samples each tube's sheets keep (:func:`curvefold.geometry.sampling.choose_sampling`);
        default every sample.

    Returns
    -------
    curvefold.io.layout.Layout
    """
    check_structure(structure)
    parts = sheets(structure, fold_angle=fold_angle, degrees=degrees, name=name, keep=keep)
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
) -> tuple[Path, ...]:
    """Write the crease pattern of a structure, laid out on pages, as SVG, DXF and/or PDF.

    Parameters
    ----------
    path_stem : path-like
        Files are ``<stem>.svg`` (or ``<stem>-p1.svg``… for several pages), ``<stem>.dxf``
        and ``<stem>.pdf``.
    structure : Structure
    formats : sequence of {"svg", "dxf", "pdf"}, keyword-only
    page, scale, units, glue_tabs, fold_angle, degrees, name, keep : keyword-only
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
                            glue_tabs=glue_tabs, name=name, keep=keep)
    layers = LAYERS if rulings else DEFAULT_LAYERS
    out: list[Path] = []
    for name in formats:  # each format's writer, from the registry
        f = FORMATS[name]
        written = f.load_writer()(f.path(path_stem), layout, layers=layers)
        out.extend(written if isinstance(written, tuple) else (written,))
    return tuple(out)
