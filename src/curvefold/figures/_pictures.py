"""The report's pictures drawn with Pillow from NumPy, without matplotlib (optional: Pillow).

Each picture draws what its matplotlib figure shows, from the same pure function
(:func:`curvefold.figures._plot_data.domain_plot`, :func:`~curvefold.figures._plot_data.width_plot`,
:func:`~curvefold.figures._plot_data.section_plot`,
:func:`~curvefold.figures._plot_data.singular_values_plot`, the scenes and titles of
:mod:`curvefold.figures._views`) on a :class:`curvefold.figures._canvas.Canvas`, at the figures'
size and 150 dots per inch. :func:`write_picture` writes a picture as PNG, or a matplotlib figure
(the pictures of a design under load) with :func:`~curvefold.figures._plots.save_figure`.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ._canvas import Canvas, colour_key, legend
from ._motion import raster
from ._plot_data import (
    DOMAIN_EDGE,
    DOMAIN_FILL,
    KIND_COLORS,
    MARKED_KINDS,
    domain_plot,
    section_plot,
    singular_values_plot,
    width_plot,
)
from ._raster import viridis, write_png
from ._scene import View, state_scene, vault_scene
from ._views import (
    crease_legend,
    motion_strip,
    scale_label,
    scale_length,
    structure_title,
    vault_title,
)

if TYPE_CHECKING:  # pragma: no cover
    from PIL import Image

    from ..analysis._mechanism import Mechanism
    from ..geometry._kinds import StructureLattice
    from ..geometry._structure import Structure
    from ..vault._assembly import Vault

__all__ = [
    "DPI",
    "regression_domain_picture",
    "width_proportion_picture",
    "sections_picture",
    "singular_values_picture",
    "vault_picture",
    "motion_strip_picture",
    "structure_picture",
    "write_picture",
]

#: Pixels per inch of the pictures (the figures' sizes are in inches).
DPI = 150.0


def _canvas(inches: tuple[float, float]) -> Canvas:
    return Canvas((round(inches[0] * DPI), round(inches[1] * DPI)), dpi=DPI)


def _equal(lo: np.ndarray, hi: np.ndarray, rect: Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
    """Limits around [lo, hi] grown so that one data unit is as long across as up in ``rect``."""
    centre, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
    aspect = (rect[2] - rect[0]) / (rect[3] - rect[1])
    half = np.maximum(half, [half[1] * aspect, half[0] / aspect])
    return centre - half, centre + half


def regression_domain_picture(
    lattice: StructureLattice, cells: np.ndarray | None = None
) -> Image.Image:
    """The regression domain (:func:`curvefold.figures._plots.plot_regression_domain`) as a
    picture."""
    plot = domain_plot(lattice, cells)
    canvas = _canvas((6.4, 5.4))
    rect = (100, 42, 100 + 690, 42 + 690)
    frame = canvas.frame(rect, (-plot.box, plot.box), (-plot.box, plot.box), grid=False)
    frame.polygons([plot.valid], fill=DOMAIN_FILL)
    edge = np.array([[-1, 0], [1, 0], [0, -1], [0, 1]]) * plot.box
    frame.lines([edge[:2], edge[2:]], "#999999", 0.5)
    for segment, color in zip(plot.lines, viridis(plot.line_t)):
        frame.lines([segment], (*color, 0.9), 0.8)
    frame.lines([np.concatenate([plot.valid, plot.valid[:1]])], DOMAIN_EDGE, 1.4)
    if len(plot.cells):
        frame.polygons(list(plot.cells), fill=(1, 1, 1, 0.5), edge="#555555", width=0.8)
        for kind in MARKED_KINDS:
            frame.markers(plot.corners[plot.kinds == kind], KIND_COLORS[kind], 4.2)
        frame.markers(plot.corners[plot.past], "#000000", 6.5, shape="x", width=1.2)
    frame.markers(np.zeros((1, 2)), "#000000", 9.0, shape="ring")
    frame.text((0, 0), "curve 1", 7.0, offset=(6, -12))
    frame.finish(title=plot.title, xlabel=plot.xlabel, ylabel=plot.ylabel)
    legend(canvas, plot.legend(), frame.rect, "upper left", points=7.0)
    if len(plot.lines):
        s = canvas.supersample
        colour_key(canvas, (812 * s, 90 * s, 834 * s, 684 * s), plot.key_label, points=8.5)
    return canvas.picture()


def width_proportion_picture(lattice: StructureLattice) -> Image.Image:
    """The widths and proportion along the crease
    (:func:`curvefold.figures._plots.plot_width_proportion`) as a picture."""
    plot = width_plot(lattice)
    canvas = _canvas((6.4, 5.2))
    xlim = (-0.02, 1.02)
    panels = (
        (
            (100, 40, 945, 365),
            plot.top_curves,
            (plot.width_left, plot.width_right),
            plot.widths_label,
        ),
        ((100, 385, 945, 710), plot.bottom_curves, (plot.ratio, plot.change), plot.ratio_label),
    )
    for k, (rect, curves, values, ylabel) in enumerate(panels):
        lo, hi = min(v.min() for v in values), max(v.max() for v in values)
        pad = (0.05 if k == 0 else 0.18) * (hi - lo or 1.0)
        frame = canvas.frame(rect, xlim, (lo - pad, hi + pad))
        for x in plot.marks:
            frame.lines([np.array([[x, lo - pad], [x, hi + pad]])], "#999999", 0.8, dash=(1.0, 1.6))
        for (_label, color, width, dash), y in zip(curves, values):
            frame.lines([np.stack([plot.t, y], axis=-1)], color, width, dash=dash)
        if k == 1:
            frame.markers(plot.mark_ratio, "#000000", 4.5)
            for point, (text, above) in zip(plot.mark_ratio, plot.notes):
                frame.text(
                    point, text, 8.0, offset=(6, 7 if above else -7), anchor="lb" if above else "lt"
                )
        frame.finish(
            title=plot.title if k == 0 else "",
            xlabel=plot.xlabel if k == 1 else "",
            ylabel=ylabel,
            xticks=k == 1,
        )
        frame.legend(
            [
                (label, {"line": color, "width": width, "dash": dash})
                for label, color, width, dash in curves
            ],
            "best",
            points=8.0,
            avoid=[np.stack([plot.t, y], axis=-1) for y in values]
            + ([plot.mark_ratio] if k == 1 else []),
        )
    return canvas.picture()


def sections_picture(obj: Vault | Structure, t_values: Sequence[float] = (0.0, 0.5)) -> Image.Image:
    """The sections normal to the common tangent (:func:`curvefold.figures._plots.plot_sections`)
    as a picture."""
    plot = section_plot(obj, t_values)
    count = len(plot.titles)
    canvas = _canvas((4.6 * count + 0.4, 4.8))
    width, left, gap, top, bottom = 500, 105, 95, 82, 640
    colors = plot.colors
    for k, (cells, corners, title) in enumerate(zip(plot.cells, plot.corners, plot.titles)):
        rect = (left + k * (width + gap), top, left + k * (width + gap) + width, bottom)
        points = cells.reshape(-1, 2)
        lo, hi = points.min(axis=0), points.max(axis=0)
        lo, hi = _equal(lo - 0.05 * (hi - lo), hi + 0.05 * (hi - lo), rect)
        frame = canvas.frame(rect, (lo[0], hi[0]), (lo[1], hi[1]))
        order = [a for a in range(len(cells)) if a != plot.design] + [plot.design]
        for a in order:
            strong = a == plot.design
            frame.polygons(
                list(cells[a]),
                fill=(0, 0, 0, 0.06) if strong else None,
                edge=colors[a],
                width=1.5 if strong else 1.0,
                dash=None if strong else plot.dash,
            )
        for kind in MARKED_KINDS:
            frame.markers(corners[plot.kinds == kind], KIND_COLORS[kind], 4.0)
        frame.markers(np.zeros((1, 2)), "#000000", 8.0, shape="ring")
        frame.finish(
            title=title, xlabel=plot.xlabel, ylabel=plot.ylabel if k == 0 else "", points=8.5
        )
    s = canvas.supersample
    legend(
        canvas,
        plot.legend(),
        (0, top * s, (left + count * (width + gap) - gap) * s, bottom * s),
        "right",
        points=8.0,
        framed=False,
    )
    canvas.text((canvas.image.width / 2, 12 * s), plot.title, 11.0, anchor="mt")
    return canvas.picture()


def singular_values_picture(mechanisms: Sequence[Mechanism]) -> Image.Image:
    """The singular values of panel structures
    (:func:`curvefold.figures._plots.plot_singular_values`) as a picture."""
    plot = singular_values_plot(mechanisms)
    canvas = _canvas((6.4, 4.6))
    ranks = max(len(v) for v in plot.values)
    low = min(float(v.min()) for v in plot.values + (plot.tolerances,))
    ylim = (10 ** np.floor(np.log10(low)), 2.0)
    frame = canvas.frame((95, 40, 935, 610), (0.8, ranks * 1.25), ylim, log=True)
    for values, tolerance, color in zip(plot.values, plot.tolerances, plot.colors):
        frame.lines(
            [np.array([[0.8, tolerance], [ranks * 1.25, tolerance]])],
            "#999999",
            0.8,
            dash=(3.7, 1.6),
        )
        line = np.stack([np.arange(1, len(values) + 1), values], axis=-1)
        frame.lines([line], color, 0.8)
        frame.markers(line, color, 2.5)
    frame.text(
        (1.05, plot.tolerances[0]),
        plot.tolerance_label,
        8.0,
        offset=(0, 2),
        anchor="lb",
        color="#666666",
    )
    frame.finish(title=plot.title, xlabel=plot.xlabel, ylabel=plot.ylabel)
    frame.legend(
        [(label, {"line": color, "width": 0.8}) for label, color in zip(plot.labels, plot.colors)],
        "best",
        points=7.0,
        avoid=[np.stack([np.arange(1, len(v) + 1), v], axis=-1) for v in plot.values],
    )
    return canvas.picture()


def _scale_bar(canvas: Canvas, span: float, scale: float, at: tuple[float, float]) -> None:
    """A scale bar of a round length near a fifth of ``span`` (model units; ``scale`` canvas
    pixels per unit), its right end at ``at``."""
    length = scale_length(span)
    x1, y = at
    x0 = x1 - length * scale
    canvas.draw.line((x0, y, x1, y), fill=(0, 0, 0, 255), width=max(1, round(0.8 * canvas.pt)))
    canvas.text(((x0 + x1) / 2, y + 3 * canvas.pt), scale_label(length), 7.0, anchor="mt")


def _view_picture(scene, title: str, legend_entries, inches: tuple[float, float]) -> Image.Image:
    """One scene under a title, with a scale bar and a legend below."""
    canvas = _canvas(inches)
    w, h = canvas.size
    rect = (0.02 * w, 0.065 * h, 0.98 * w, 0.89 * h)
    scale = raster(scene, scene.box, None, "", canvas=canvas, rect=rect)
    s = canvas.supersample
    _scale_bar(canvas, scene.span, scale, (0.93 * w * s, 0.91 * h * s))
    canvas.text((w * s / 2, 0.018 * h * s), title, 10.0, anchor="mt")
    legend(canvas, legend_entries, (0, 0, w * s, 0.945 * h * s), "below", points=7.0, framed=False)
    return canvas.picture()


def vault_picture(vault: Vault, *, view: View = View()) -> Image.Image:
    """One shaded view of a vault over the ground (:func:`curvefold.figures._views.plot_vault`)
    as a picture."""
    scene = vault_scene(vault, colors=KIND_COLORS, view=view)
    return _view_picture(
        scene, vault_title(vault), crease_legend(scene.roles, vault.lattice), (7.0, 5.2)
    )


def structure_picture(structure: Structure, *, view: View = View()) -> Image.Image:
    """One shaded view of a tube or cellular block
    (:func:`curvefold.figures._views.plot_structure`) as a picture."""
    state = structure.state()
    scene = state_scene(state, colors=KIND_COLORS, view=view)
    return _view_picture(
        scene,
        structure_title(structure, state.fold_angle),
        crease_legend(scene.roles, structure.lattice),
        (6.4, 5.2),
    )


def motion_strip_picture(vault: Vault) -> Image.Image:
    """Small multiples of a vault's folding (:func:`curvefold.figures._views.plot_motion_strip`)
    as a picture."""
    strip = motion_strip(vault)
    columns = strip.columns
    rows = -(-len(strip.scenes) // columns)
    canvas = _canvas((3.4 * columns + 0.3, 3.2 * rows + 0.4))
    w, h = canvas.size
    s = canvas.supersample
    cell_w, cell_h, head = (w - 20) / columns, (h - 60) / rows, 60
    box = strip.box
    for k, (scene, title, note) in enumerate(zip(strip.scenes, strip.titles, strip.notes)):
        x0, y0 = 10 + (k % columns) * cell_w, head + (k // columns) * cell_h
        scale = raster(
            scene,
            box,
            None,
            title,
            canvas=canvas,
            rect=(x0, y0, x0 + cell_w, y0 + cell_h - 0.1 * cell_h),
            title_points=10.0,
        )
        canvas.text(
            ((x0 + cell_w / 2) * s, (y0 + 0.93 * cell_h) * s),
            note,
            7.0,
            color="#555555",
            anchor="mm",
        )
    _scale_bar(canvas, strip.scenes[0].span, scale, ((w - 40) * s, (h - 0.12 * cell_h) * s))
    canvas.text((w * s / 2, 14 * s), strip.title, 11.0, anchor="mt")
    return canvas.picture()


def write_picture(picture, path_stem: str | os.PathLike) -> list[Path]:
    """Write a picture (a PIL image, or a matplotlib figure) as ``path_stem + ".png"``,
    atomically; the files written."""
    if hasattr(picture, "savefig"):
        from ._plots import save_figure

        return save_figure(picture, path_stem, formats=("png",))
    return [write_png(picture, f"{os.fspath(path_stem)}.png")]
