"""Crease patterns as PDF: one printable page per layout page at 1:1, a PDF layer per operation.

The page's lines are drawn from the layout's arrays by :mod:`curvefold.io._pdf`; its footer
(:func:`~curvefold.io._legend.page_footer`) on the legend layer.
"""

from __future__ import annotations

import math
import os
from collections.abc import Collection, Sequence
from pathlib import Path

from ._cutters import LEGEND_LAYER
from ._layout import Layout, Page
from ._legend import check_layers, check_layout, check_line_width, layer_look, page_footer
from ._pdf import PdfDocument, PdfPage, PdfText

__all__ = ["draw_footer", "write_pdf"]


def draw_footer(
    canvas: PdfPage,
    layout: Layout,
    page_index: int,
    names: Sequence[str],
    lw: float,
    *,
    page_text: str | None = None,
) -> None:
    """Draw a page's footer (:func:`page_footer`) on a :class:`~curvefold.io._pdf.PdfPage`, on the
    legend layer."""
    foot = page_footer(layout, page_index, names, page_text=page_text)
    canvas.fill([foot.bar], foot.colour, layer=LEGEND_LAYER)
    for (key, points), ink in zip(foot.samples, foot.inks):
        st = layer_look(layout, key)[2]
        if st.fill:
            canvas.fill([points], ink, layer=LEGEND_LAYER)
        else:
            canvas.stroke([points], ink, lw * st.width, dashes=st.dashes, layer=LEGEND_LAYER)
    for t, ink in zip(foot.texts, foot.text_inks):
        canvas.text(
            PdfText(
                t.text,
                t.position[0],
                t.position[1] - 0.35 * t.size,
                t.size,
                ink,
                layer=LEGEND_LAYER,
            )
        )


def _draw_page(
    canvas: PdfPage,
    page: Page,
    layout: Layout,
    index: int,
    names: tuple[str, ...],
    lw: float,
    footer: bool,
) -> None:
    for key in names:
        layer, colour, st = layer_look(layout, key)
        if key == "labels":
            for t in page.labels():
                a = math.radians(t.angle)  # baseline 0.35 em below the centre, as in the SVG
                canvas.text(
                    PdfText(
                        t.text,
                        t.position[0] + 0.35 * t.size * math.sin(a),
                        t.position[1] - 0.35 * t.size * math.cos(a),
                        t.size,
                        colour,
                        angle=t.angle,
                        layer=layer,
                    )
                )
            continue
        lines = page.on_layer(key)
        if not lines:
            continue
        if st.fill:
            canvas.fill([p.points for p in lines], colour, layer=layer)
        else:
            canvas.stroke(
                [p.points for p in lines],
                colour,
                lw * st.width,
                dashes=st.dashes,
                closed=[p.closed for p in lines],
                layer=layer,
            )
    if footer:
        draw_footer(canvas, layout, index, names, lw)


def write_pdf(
    path: str | os.PathLike,
    layout: Layout,
    *,
    layers: Collection[str] | None = None,
    line_width: float = 0.25,
    scale_bar: bool = True,
) -> Path:
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
    lw = check_line_width(line_width)
    layers = [layer_look(layout, key)[0] for key in names] + [LEGEND_LAYER] * scale_bar
    doc = PdfDocument(title="crease pattern", layers=layers)
    for index, page in enumerate(layout.pages):
        _draw_page(doc.page(*page.size), page, layout, index, names, lw, scale_bar)
    return doc.save(path)
