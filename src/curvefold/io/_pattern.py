"""Crease patterns for fabrication: SVG, DXF and PDF at true scale in millimetres.

Build a :class:`~curvefold.io.Layout` with :func:`layout_pattern` (placement on
pages, glue tabs, layers, labels, and for cutting machines perforated creases and kerf
compensation; see :mod:`curvefold.io._layout` and :mod:`curvefold.io._cutting`) as a
:class:`PatternOutput` says (page, units, scale, cutter…), then write it:

* :func:`write_svg` — one SVG per page, ``width``/``height`` in mm and a viewBox in mm,
  one Inkscape layer per operation and a legend layer (not to cut). One page: written to
  ``path``. Several pages: ``name-p1.svg``, ``name-p2.svg``… beside ``path`` (``path``
  itself is not written), unless ``page_index`` picks one page, which is then written to
  ``path`` (:mod:`curvefold.io._svg`).
* :func:`write_dxf` — one DXF (R2010, ``$INSUNITS`` = 4, mm) with real layers, colours
  and linetypes; pages in a grid, each framed (:mod:`curvefold.io._dxf`). Needs ``ezdxf``.
* :func:`write_pdf` — one printable PDF page per layout page at 1:1, each operation on
  its own PDF layer (optional content), the page's lines drawn from the layout's arrays
  by :mod:`curvefold.io._pdf` (:mod:`curvefold.io._pattern_pdf`).

:func:`write_pattern` lays out and writes in one call; :func:`write_layout` writes a
layout made already, each format with the writer the registry names for it.

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

import math
import os
from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path

import numpy as np

from ..geometry._sheets import PatternSheet, sheets
from ..geometry._structure import Structure, check_structure
from ..kernel._errors import InputError
from ._cutters import cutter as _cutter
from ._cutting import prepare_layout
from ._dxf import page_grid, write_dxf
from ._formats import FORMATS, check_formats, formats_of
from ._labels import Label, seam_name
from ._layout import (
    FOOTER,
    LAYERS,
    Layout,
    LayoutRules,
    Page,
    PlacedSheet,
    Polyline,
    layout_sheets,
    page_size,
)
from ._legend import DEFAULT_LAYERS, LEGEND, Footer, check_layout, page_footer
from ._output import PatternOutput, check_output
from ._pattern_pdf import draw_footer, write_pdf
from ._svg import svg_page, write_svg
from ._tables import mm_per_unit
from ._thick_sheet import thick_layout

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
    "PatternOutput",
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
    room = (
        np.array(sorted((W - 2 * margin_mm, H - 2 * margin_mm - footer_mm), reverse=True))
        - 2 * tab_mm
    )
    if (room <= 0).any():
        raise InputError(
            f"page {page!r} leaves no room for a sheet inside the margins and glue tabs"
        )
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
    output: PatternOutput = PatternOutput(),
    *,
    fold_angle: float | None = None,
    degrees: bool = True,
    keep: Sequence[np.ndarray] | None = None,
) -> Layout:
    """The sheets of a structure placed on pages with glue tabs, layers and labels, ready to cut.

    Parameters
    ----------
    structure : Structure
    output : PatternOutput
        Page, units, scale, glue tabs, cutter convention, perforation, kerf and label prefix.
        Without a scale, the largest sheet (along its principal axes, long side along the
        page's long side, with room for glue tabs) fills the page inside its margins,
        rounded down to 1, 1.25, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 × 10^k so the print scale
        reads plainly (the PDF footer states it).
    fold_angle : float, optional, keyword-only
        Target 2α of the folds (their M/V); default the lattice's own.
    degrees : bool, keyword-only
    keep : sequence of (m_k,) array_like of int, optional, keyword-only
        The samples each tube's sheets keep (:func:`curvefold.geometry.choose_sampling`);
        default every sample.

    Returns
    -------
    curvefold.io.Layout
    """
    check_structure(structure)
    check_output(output)
    _cutter(output.cutter)
    parts = sheets(structure, fold_angle=fold_angle, degrees=degrees, name=output.name, keep=keep)
    if output.bend is not None:  # a thick sheet: its own module draws it
        return thick_layout(parts, output, _fit)
    fitted = _fit(parts, output)
    return prepare_layout(
        replace(fitted, cutter=output.cutter), perforation=output.perforation, kerf=output.kerf
    )


def _fit(
    parts: Sequence[PatternSheet],
    output: PatternOutput,
    rules: Callable[[float], LayoutRules] = lambda scale: LayoutRules(),
) -> Layout:
    """The layout of ``parts`` at the output's scale, or at the largest plain scale that fits;
    ``rules`` gives the layout's rules at a scale."""
    page, units, glue_tabs = output.page, output.units, output.glue_tabs
    if output.scale is not None:
        return layout_sheets(
            parts,
            page=page,
            units=units,
            scale=output.scale,
            glue_tabs=glue_tabs,
            rules=rules(output.scale),
        )
    guess = _fit_scale(parts, page, units, 10.0, FOOTER, 6.0 if glue_tabs else 0.0)
    # The layout turns each sheet to its minimum-area rectangle, which can be longer than the
    # principal-axes box; step down the series of plain scales until it fits.
    for attempt in range(4):
        try:
            return layout_sheets(
                parts, page=page, units=units, scale=guess, glue_tabs=glue_tabs, rules=rules(guess)
            )
        except InputError:
            if attempt == 3:
                raise
            guess = _nice_floor(guess * (1 - 1e-9))
    raise AssertionError("unreachable")  # pragma: no cover


def write_pattern(
    path_stem: str | os.PathLike,
    structure: Structure,
    output: PatternOutput = PatternOutput(),
    *,
    formats: Sequence[str] = PATTERN_FORMATS,
    fold_angle: float | None = None,
    degrees: bool = True,
    keep: Sequence[np.ndarray] | None = None,
) -> tuple[Path, ...]:
    """Write the crease pattern of a structure, laid out on pages, as SVG, DXF and/or PDF.

    Parameters
    ----------
    path_stem : path-like
        Files are ``<stem>.svg`` (or ``<stem>-p1.svg``… for several pages), ``<stem>.dxf``
        and ``<stem>.pdf``.
    structure : Structure
    output : PatternOutput
        As in :func:`layout_pattern`; its ``rulings`` also draws the rulings (thin green,
        for scoring).
    formats : sequence of {"svg", "dxf", "pdf"}, keyword-only
    fold_angle, degrees, keep : keyword-only
        As in :func:`layout_pattern`.

    Returns
    -------
    tuple of Path
        The files written, in the order of ``formats``; the pages of a format in page
        order (``<stem>-p1.svg``, ``<stem>-p2.svg``…).

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice, Structure
    >>> curve = SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=9)
    >>> tube = Structure.tube(Lattice.from_crease(Crease.from_curve(curve), 0.1, 0.1))
    >>> write_pattern("tube", tube, PatternOutput(page="A3", scale=50.0), formats=("svg", "pdfx"))
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: formats must be a non-empty selection of ('svg', 'dxf',
    'pdf'), got ('svg', 'pdfx')
    """
    formats = check_formats(formats, "pattern")
    layout = layout_pattern(structure, output, fold_angle=fold_angle, degrees=degrees, keep=keep)
    return write_layout(path_stem, layout, formats=formats, rulings=output.rulings)


def write_layout(
    path_stem: str | os.PathLike,
    layout: Layout,
    *,
    formats: Sequence[str] = PATTERN_FORMATS,
    rulings: bool = False,
) -> tuple[Path, ...]:
    """Write a crease pattern already laid out (:func:`layout_pattern`) in each of ``formats``,
    with the writer the registry names for it; arguments and result as in
    :func:`write_pattern`."""
    check_layout(layout)
    formats = check_formats(formats, "pattern")
    layers = LAYERS if rulings else DEFAULT_LAYERS
    out: list[Path] = []
    for name in formats:  # each format's writer, from the registry
        f = FORMATS[name]
        written = f.load_writer()(f.path(path_stem), layout, layers=layers)
        out.extend(written if isinstance(written, tuple) else (written,))
    return tuple(out)
