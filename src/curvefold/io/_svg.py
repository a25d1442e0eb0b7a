"""Crease patterns as SVG: one file per page, in millimetres, one Inkscape layer per operation.

:func:`write_svg` writes a :class:`~curvefold.io.Layout` (:func:`~curvefold.io.layout_pattern`)
one SVG per page, ``width``/``height`` in mm and a viewBox in mm, one Inkscape layer per
operation and a legend layer (not to cut). One page: written to ``path``. Several pages:
``name-p1.svg``, ``name-p2.svg``… beside ``path`` (``path`` itself is not written), unless
``page_index`` picks one page, which is then written to ``path``.
"""

from __future__ import annotations

import contextlib
import math
import os
from collections.abc import Collection
from pathlib import Path

import numpy as np

from ..kernel._text import one_line
from ..kernel._validate import check_integer
from ._atomic import atomic_path
from ._cutters import LEGEND_LAYER
from ._labels import Label
from ._layout import Layout
from ._legend import check_layers, check_layout, check_line_width, layer_look, page_footer

__all__ = ["svg_page", "write_svg"]


def _escape(text: str) -> str:
    """``text`` with &, < and > escaped for XML (:func:`xml.sax.saxutils.escape`, whose import
    brings urllib's).

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


def _svg_points(points: np.ndarray, height: float) -> str:
    flipped = np.column_stack([points[:, 0], height - points[:, 1]])  # y down
    return " ".join(["%.3f,%.3f"] * len(points)) % tuple(flipped.ravel().tolist())


def _svg_label(t: Label, height: float, colour: str | None = None) -> str:
    """A line of text centred on its position, in its layer's colour or in ``colour``."""
    a = math.radians(t.angle)
    # baseline 0.35 em below the centre, so the capitals sit centred on it
    x = t.position[0] + 0.35 * t.size * math.sin(a)
    y = height - (t.position[1] - 0.35 * t.size * math.cos(a))
    rot = f' transform="rotate({-t.angle:.2f} {x:.3f} {y:.3f})"' if abs(t.angle) > 1e-9 else ""
    text = _escape(one_line(t.text))
    fill = "" if colour is None else f' style="fill:{colour}"'
    return f'<text x="{x:.3f}" y="{y:.3f}" font-size="{t.size:.3f}"{rot}{fill}>{text}</text>'


_FONT = "font-family:'DejaVu Sans',Arial,Helvetica,sans-serif;text-anchor:middle"


def _svg_style(layout: Layout, key: str, lw: float, colour: str | None = None) -> str:
    """The SVG style of a layer's lines (or text, for ``labels``), in ``colour`` or the layer's
    own."""
    _, own, st = layer_look(layout, key)
    colour = colour or own
    if key in ("labels", "legend"):
        return f"fill:{colour};stroke:none;{_FONT}"
    if st.fill:
        return f"fill:{colour};stroke:none"
    style = (
        f"fill:none;stroke:{colour};stroke-width:{lw * st.width:g};stroke-linecap:butt;"
        "stroke-linejoin:round"
    )
    dashes = ";stroke-dasharray:" + ",".join(f"{d:g}" for d in st.dashes) if st.dashes else ""
    return style + dashes


def svg_page(
    layout: Layout,
    page_index: int = 0,
    *,
    layers: Collection[str] | None = None,
    line_width: float = 0.25,
) -> str:
    """One page of ``layout`` as SVG text (see :func:`write_svg`)."""
    check_layout(layout)
    page_index = check_integer(page_index, "page_index", f"[0, {len(layout.pages) - 1}]")
    names = check_layers(layers)
    lw = check_line_width(line_width)
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
            body = [
                f'<{"polygon" if p.closed else "polyline"} points="{_svg_points(p.points, H)}"/>'
                for p in page.on_layer(key)
            ]
        label = _quoteattr(layer_look(layout, key)[0])
        out.append(
            f'<g inkscape:groupmode="layer" id="layer-{key}" inkscape:label={label} '
            f"style={_quoteattr(_svg_style(layout, key, lw))}>"
        )
        out.extend(body)
        out.append("</g>")
    footer = page_footer(layout, page_index, names)
    out.append(
        f'<g inkscape:groupmode="layer" id="layer-legend" '
        f"inkscape:label={_quoteattr(LEGEND_LAYER)} "
        f"style={_quoteattr(_svg_style(layout, 'legend', lw))}>"
    )
    out.append(
        f'<polygon points="{_svg_points(footer.bar, H)}" style="fill:{footer.colour};stroke:none"/>'
    )
    out += [
        f"<{'polygon' if layer_look(layout, key)[2].fill else 'polyline'} "
        f'points="{_svg_points(points, H)}" '
        f"style={_quoteattr(_svg_style(layout, key, lw, ink))}/>"
        for (key, points), ink in zip(footer.samples, footer.inks)
    ]
    out += [
        _svg_label(t, H, None if ink == footer.colour else ink)
        for t, ink in zip(footer.texts, footer.text_inks)
    ]
    out.append("</g>")
    out.append("</svg>\n")
    return "\n".join(out)


def write_svg(
    path: str | os.PathLike,
    layout: Layout,
    page_index: int | None = None,
    *,
    layers: Collection[str] | None = None,
    line_width: float = 0.25,
) -> tuple[Path, ...]:
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
        jobs = [
            (target.with_name(f"{target.stem}-p{i + 1}{target.suffix}"), i)
            for i in range(len(layout.pages))
        ]
    texts = [
        (p, svg_page(layout, i, layers=layers, line_width=line_width).encode("utf-8"))
        for p, i in jobs
    ]
    # All pages or none: every page goes to a temporary file, renamed only once all are written.
    with contextlib.ExitStack() as stack:
        for p, data in texts:
            stack.enter_context(atomic_path(p)).write_bytes(data)
    return tuple(p for p, _ in texts)
