"""Crease patterns for fabrication: SVG, DXF and PDF at true scale in millimetres.

Build a :class:`~curvefold.io.layout.Layout` with :func:`layout_sheets` (placement on
pages, glue tabs, layers, labels; see :mod:`curvefold.io.layout`), then write it:

* :func:`write_svg` — one SVG per page, ``width``/``height`` in mm and a viewBox in mm,
  one Inkscape layer per fabrication layer. One page: written to ``path``. Several pages:
  ``name-p1.svg``, ``name-p2.svg``… beside ``path`` (``path`` itself is not written),
  unless ``page_index`` picks one page, which is then written to ``path``.
* :func:`write_dxf` — one DXF (R2010, ``$INSUNITS`` = 4, mm) with real layers, colours
  and linetypes; pages side by side along +x, ``page_spacing`` apart. Needs ``ezdxf``.
* :func:`write_pdf` — one printable PDF page per layout page at 1:1, with a 10 mm scale
  bar in the bottom margin to check the print scale. Needs ``matplotlib``.

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

from ..geometry.sheets import PatternSheet, _check_structure, sheets
from ..geometry.structure import Structure
from ..kernel.errors import InputError
from ..kernel.text import one_line
from .atomic import atomic_path
from .formats import check_formats, formats_of
from .layout import (
    LAYERS,
    Label,
    Layout,
    Page,
    PlacedSheet,
    Polyline,
    layout_sheets,
    page_size,
    seam_name,
)
from .tables import COLOURS, mm_per_unit

#: Crease-pattern formats :func:`write_pattern` writes.
PATTERN_FORMATS = formats_of("pattern")
#: Print scales are rounded down to one of these times a power of ten.
_NICE = (1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0)


def _target(path_stem: str | os.PathLike, suffix: str) -> Path:
    stem = Path(path_stem)
    return stem.with_name(f"{stem.name}.{suffix}")


__all__ = [
    "DEFAULT_LAYERS",
    "LAYERS",
    "LAYER_STYLES",
    "LayerStyle",
    "Label",
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


#: Style of every layer in :data:`LAYERS`.
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
    if not (isinstance(page_index, (int, np.integer)) and 0 <= page_index < len(layout.pages)):
        raise InputError(f"page_index must be in [0, {len(layout.pages) - 1}], got {page_index!r}")
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
        st = LAYER_STYLES[name]
        if name == "labels":
            style = (f"fill:{st.color};stroke:none;font-family:'DejaVu Sans',Arial,Helvetica,sans-serif;"
                     "text-anchor:middle")
            body = [_svg_label(t, H) for t in page.labels()]
        else:
            if st.fill:
                style = f"fill:{st.color};stroke:none"
            else:
                style = (f"fill:none;stroke:{st.color};stroke-width:{lw * st.width:g};"
                         "stroke-linecap:butt;stroke-linejoin:round")
                if st.dashes:
                    style += ";stroke-dasharray:" + ",".join(f"{d:g}" for d in st.dashes)
            body = [f'<{"polygon" if p.closed else "polyline"} points="{_svg_points(p.points, H)}"/>'
                    for p in page.on_layer(name)]
        out.append(f'<g inkscape:groupmode="layer" id="layer-{name}" inkscape:label={quoteattr(name)} '
                   f'style={quoteattr(style)}>')
        out.extend(body)
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


def _rgb(color: str) -> tuple[int, int, int]:
    return int(color[1:3], 16), int(color[3:5], 16), int(color[5:7], 16)


def write_dxf(path: str | os.PathLike, layout: Layout, *, layers: Collection[str] | None = None,
              page_spacing: float = 20.0) -> Path:
    """Write the layout as one DXF drawing in millimetres (needs ``ezdxf``).

    Every fabrication layer is a DXF layer with its colour (AutoCAD index and true colour),
    linetype (``CONTINUOUS`` cut, ``DASHDOT`` mountain, ``DASHED`` valley, ``DOT`` tab
    fold lines; patterns in mm) and lineweight. Lines are ``LWPOLYLINE`` entities, glue
    areas solid ``HATCH`` entities and labels ``TEXT`` (height = cap height, centred).
    Page i is shifted by ``i × (page width + page_spacing)`` along +x.

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
    patterns = {}
    for name in names:
        st = LAYER_STYLES[name]
        if st.dashes and st.linetype not in patterns:
            dxf_pattern = [float(sum(st.dashes))] + [d if k % 2 == 0 else -d for k, d in enumerate(st.dashes)]
            doc.linetypes.add(st.linetype, dxf_pattern, description=f"curvefold {name} " + " ".join(f"{d:g}" for d in st.dashes))
            patterns[st.linetype] = dxf_pattern
        doc.layers.add(name, color=st.aci, true_color=colors.rgb2int(_rgb(st.color)),
                       linetype=st.linetype if st.dashes else "CONTINUOUS", lineweight=13 if st.width < 1 else 25)
    msp = doc.modelspace()
    for i, page in enumerate(layout.pages):
        shift = np.array([i * (page.size[0] + page_spacing), 0.0])
        for name in names:
            st = LAYER_STYLES[name]
            if name == "labels":
                for t in page.labels():
                    x, y = np.asarray(t.position) + shift
                    text = msp.add_text(one_line(t.text), height=_CAP_HEIGHT * t.size, rotation=t.angle,
                                        dxfattribs={"layer": name})
                    text.set_placement((float(x), float(y)), align=TextEntityAlignment.MIDDLE_CENTER)
                continue
            for p in page.on_layer(name):
                pts = (p.points + shift).tolist()
                if st.fill and p.closed:
                    hatch = msp.add_hatch(color=256, dxfattribs={"layer": name})
                    hatch.paths.add_polyline_path(pts, is_closed=True)
                else:
                    msp.add_lwpolyline(pts, close=p.closed, dxfattribs={"layer": name})
    with atomic_path(path) as tmp:
        doc.saveas(tmp)
    return Path(path)


# --------------------------------------------------------------------------------------
# PDF


def _draw_page(fig, page: Page, layout: Layout, number: int, names: tuple[str, ...], lw: float,
               scale_bar: bool) -> None:
    from matplotlib.collections import LineCollection, PolyCollection
    from matplotlib.patches import Rectangle

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
    small = 2.5 * _PT_PER_MM
    y = max(0.45 * layout.margin, 1.0)
    if scale_bar:
        ax.add_patch(Rectangle((layout.margin, y - 0.3), 10.0, 0.6, facecolor="black", edgecolor="none"))
        ax.text(layout.margin + 12.0, y, "10 mm (print at 100 %)", fontsize=small, va="center", ha="left",
                family="sans-serif")
    ax.text(W - layout.margin, y, f"curvefold · page {number} of {len(layout.pages)} · "
            f"1 model unit = {layout.scale:.4g} mm", fontsize=small, va="center", ha="right", family="sans-serif",
            color="#555555")


def write_pdf(path: str | os.PathLike, layout: Layout, *, layers: Collection[str] | None = None,
              line_width: float = 0.25, scale_bar: bool = True) -> Path:
    """Write the layout as a printable multi-page PDF at 1:1 (needs ``matplotlib``).

    Each page is the layout's page size in mm; a 10 mm scale bar and a footer sit in
    the bottom margin so the print scale can be checked with a ruler.

    Parameters
    ----------
    path : path-like
    layout : Layout
    layers : collection of str, optional
        Layers to draw; default :data:`DEFAULT_LAYERS` (all but ``rulings``).
    line_width : float
        Line width in mm.
    scale_bar : bool
        Draw the 10 mm scale bar.

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
        with PdfPages(tmp, metadata={"Creator": "curvefold", "Title": "crease pattern", "CreationDate": None}) as pdf:
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


def _fit_scale(parts, page, units: str, margin_mm: float, tab_mm: float) -> float:
    """Page units per model unit that fit the largest sheet (principal axes) with its tabs."""
    W, H = page_size(page, units=units)
    room = np.array(sorted((W, H), reverse=True)) - 2 * margin_mm - 2 * tab_mm
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

    Returns
    -------
    curvefold.io.layout.Layout
    """
    _check_structure(structure)
    parts = sheets(structure, fold_angle=fold_angle, degrees=degrees, name=name)
    if scale is not None:
        return layout_sheets(parts, page=page, units=units, scale=scale, glue_tabs=glue_tabs)
    guess = _fit_scale(parts, page, units, 10.0, 6.0 if glue_tabs else 0.0)
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
) -> tuple[Path, ...]:
    """Write the crease pattern of a structure, laid out on pages, as SVG, DXF and/or PDF.

    Parameters
    ----------
    path_stem : path-like
        Files are ``<stem>.svg`` (or ``<stem>-p1.svg``… for several pages), ``<stem>.dxf``
        and ``<stem>.pdf``.
    structure : Structure
    formats : sequence of {"svg", "dxf", "pdf"}, keyword-only
    page, scale, units, glue_tabs, fold_angle, degrees, name : keyword-only
        As in :func:`layout_pattern`.
    rulings : bool, keyword-only
        Also draw the rulings (thin green, for scoring).

    Returns
    -------
    tuple of Path
        The files written, in the order of ``formats``.
    """
    formats = check_formats(formats, "pattern")
    layout = layout_pattern(structure, fold_angle=fold_angle, degrees=degrees, page=page, units=units, scale=scale,
                            glue_tabs=glue_tabs, name=name)
    layers = LAYERS if rulings else DEFAULT_LAYERS
    out: list[Path] = []
    for fmt in formats:
        target = _target(path_stem, fmt)
        if fmt == "svg":
            out.extend(write_svg(target, layout, layers=layers))
        elif fmt == "dxf":
            out.append(write_dxf(target, layout, layers=layers))
        else:
            out.append(write_pdf(target, layout, layers=layers))
    return tuple(out)
