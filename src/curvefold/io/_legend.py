"""What every crease-pattern page carries besides its sheets: the look of each layer, and the
footer.

:func:`layer_look` gives a layout layer's file layer name, colour and line style in the
layout's cutter convention (:mod:`curvefold.io._cutters`); :func:`page_footer` lays out the
footer of a page inside its footer band: a 10 mm scale bar with the print scale and page
number, and a legend of the layers drawn on that page. Its text and scale bar are drawn in
the convention's reference colour (dark, never the colour of an operation), and each legend
sample in its layer's colour and dash pattern, so that the legend shows what it names; for
a cutting machine the text also gives each layer's colour code (the print convention's
legend, for people, names the layers only). The SVG, DXF and PDF writers share these.
"""

from __future__ import annotations

import math
from collections.abc import Collection
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InputError
from ._cutters import STYLES, LayerStyle, cutter, layer_name
from ._labels import Label, seam_name, text_width
from ._layout import LAYERS, Layout

__all__ = [
    "DEFAULT_LAYERS",
    "LEGEND",
    "Footer",
    "check_layout",
    "check_layers",
    "check_line_width",
    "layer_look",
    "page_footer",
]

#: Layers the writers draw by default.
DEFAULT_LAYERS = tuple(name for name in LAYERS if name != "rulings")

#: What each layer means, as the legend says it.
LEGEND = MappingProxyType(
    {
        "cut": "cut",
        "mountain": "mountain fold",
        "valley": "valley fold",
        "seam": "glue-tab fold",
        "glue": "glue",
        "rulings": "ruling",
        "labels": "glue the edges named alike",
    }
)
_FOOTER_TEXT = 2.2  # em height of the footer's text, mm
_SAMPLE = 8.0  # length of a legend's sample line, mm


def check_layout(layout: Layout) -> None:
    """Refuse what is not a :class:`~curvefold.io.Layout`."""
    if not isinstance(layout, Layout):
        raise InputError(
            f"layout must be a Layout (from layout_sheets), got {type(layout).__name__}"
        )


def check_layers(layers: Collection[str] | None) -> tuple[str, ...]:
    """The layout layers to draw, in drawing order; default :data:`DEFAULT_LAYERS`."""
    if layers is None:
        return DEFAULT_LAYERS
    if isinstance(layers, str):
        layers = (layers,)
    unknown = sorted(set(layers) - set(LAYERS))
    if unknown:
        raise InputError(f"layers must be among {list(LAYERS)}, got unknown {unknown}")
    return tuple(name for name in LAYERS if name in set(layers))


def layer_look(layout: Layout, key: str) -> tuple[str, str, LayerStyle]:
    """(file layer name, colour ``#rrggbb``, style) of a layout layer or of ``"legend"``.

    Perforated creases are solid lines: their dashes are geometry.
    """
    perforated = layout.perforation is not None and key in ("mountain", "valley")
    return (
        layer_name(key, perforated=perforated),
        cutter(layout.cutter).colours[key],
        LayerStyle() if perforated else STYLES[key],
    )


@dataclass(frozen=True, eq=False)
class Footer(FrozenArrays):
    """The scale bar, scale note and legend of one page, in page mm inside its footer band,
    all in the reference colour :attr:`colour`.

    Attributes
    ----------
    samples : tuple of (str, (k, 2) ndarray)
        A sample of every drawn layer but the labels: a line in the layer's dash pattern, or
        for a filled layer a closed rectangle, in the layer's colour (:attr:`inks`).
    bar : (4, 2) ndarray
        The 10 mm scale bar, a rectangle to fill.
    texts : tuple of Label
    colour : str
        ``#rrggbb`` of the scale bar and the text (the convention's reference colour).
    inks : tuple of str
        ``#rrggbb`` of each sample, and of the seam name that samples the labels (its text's
        colour in :attr:`text_inks`).
    text_inks : tuple of str
        ``#rrggbb`` of each text.
    """

    samples: tuple[tuple[str, np.ndarray], ...]
    bar: np.ndarray
    texts: tuple[Label, ...]
    colour: str
    inks: tuple[str, ...] = ()
    text_inks: tuple[str, ...] = ()


def page_footer(
    layout: Layout,
    page_index: int,
    layers: Collection[str] | None = None,
    *,
    page_text: str | None = None,
) -> Footer:
    """The footer of a page: a 10 mm scale bar with the print scale, and the legend of the
    ``layers`` it draws.

    It lies in the band of :attr:`Layout.footer` above the bottom margin, so it prints
    wherever the sheets do. Text starts where its box is estimated (:func:`text_width`).
    ``page_text`` replaces the page number of a crease-pattern page (``"page 2 of 10"``),
    for other pages drawn at the layout's size (the assembly guide).
    """
    page = layout.pages[page_index]
    drawn = set(check_layers(layers))
    names = [
        name
        for name in LEGEND
        if name in drawn and (_has_seam_labels(page) if name == "labels" else page.on_layer(name))
    ]
    page_text = f"page {page_index + 1} of {len(layout.pages)}" if page_text is None else page_text
    W, _ = layout.page_size
    m, size = layout.margin, _FOOTER_TEXT
    top = m + max(layout.footer, 3 * size) - 0.5 * size  # centre line of the first row

    def text(words: str, x: float, y: float) -> Label:
        return Label(words, (x + 0.5 * text_width(words, size), y), 0.0, size, "legend")

    bar = np.array([[m, top - 0.6], [m + 10.0, top - 0.6], [m + 10.0, top + 0.6], [m, top + 0.6]])
    note = f"10 mm: print at 100 % · 1 model unit = {layout.scale:.4g} mm · {page_text} · curvefold"
    entries, x, row = [], m, 1  # (name, x, row) of every legend entry, wrapped into rows
    for name in names:
        lead = text_width(seam_name(1), size) if name == "labels" else _SAMPLE
        width = lead + 1.5 + text_width(_entry(layout, name), size)
        if x > m and x + width > W - m:  # next row
            x, row = m, row + 1
        entries.append((name, x, lead, row))
        x += width + 4.0
    row += bool(layout.sheet_note)  # a thick sheet's statement: a row of its own
    note_row = row
    # rows closer together rather than into the margin
    step = min(1.8 * size, (top - m - 0.5 * size) / max(row, 1))
    ink = layer_look(layout, "legend")[1]
    texts, text_inks = [text(note, m + 12.0, top)], [ink]
    samples, inks = [], []
    for name, x, lead, row in entries:
        _, colour, st = layer_look(layout, name)
        y = top - row * step
        if name == "labels":
            texts.append(text(seam_name(1), x, y))
            text_inks.append(colour)
        elif st.fill:
            samples.append(
                (
                    name,
                    np.array(
                        [[x, y - 1.0], [x + _SAMPLE, y - 1.0], [x + _SAMPLE, y + 1.0], [x, y + 1.0]]
                    ),
                )
            )
        else:
            samples.append((name, np.array([[x, y], [x + _SAMPLE, y]])))
        if name != "labels":
            inks.append(colour)
        texts.append(text(_entry(layout, name), x + lead + 1.5, y))
        text_inks.append(ink)
    if layout.sheet_note:
        texts.append(text(layout.sheet_note, m, top - note_row * step))
        text_inks.append(ink)
    return Footer(
        tuple((name, readonly(points)) for name, points in samples),
        bar,
        tuple(texts),
        ink,
        tuple(inks),
        tuple(text_inks),
    )


def _entry(layout: Layout, name: str) -> str:
    """A legend entry's words: what the layer means, and for a cutting machine its colour code
    (``cut #ff0000``); the print convention's sample shows the colour, for people."""
    meaning = LEGEND[name]
    return meaning if layout.cutter == "print" else f"{meaning} {layer_look(layout, name)[1]}"


def _has_seam_labels(page) -> bool:
    """Whether a page names a seam to glue (a single fold has none, only its sheet's name)."""
    return any(label.kind == "seam" for label in page.labels())


def check_line_width(line_width: float) -> float:
    """A line width in mm: a positive number."""
    if not (isinstance(line_width, (int, float)) and math.isfinite(line_width) and line_width > 0):
        raise InputError(f"line_width must be a positive number of mm, got {line_width!r}")
    return float(line_width)
