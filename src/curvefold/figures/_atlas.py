"""The atlas figure: small views of every vault of a design grid (the paper's Fig. 10).

The figure draws at most :data:`MAX_VIEWS` views along each axis, so its size and the
memory it takes stay bounded; a larger grid is drawn every k-th row and column
(:func:`view_step`, :meth:`curvefold.vault.Atlas.every`) with a note saying so.
"""

from __future__ import annotations

import math
import textwrap
from dataclasses import replace
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from ..kernel._errors import InputError
from ..vault._atlas import Atlas
from ..vault._tubes import DEFAULT_TUBES_CAP
from ._plots import new_figure
from ._scene import GROUND_COLOR, View, ground_polygon, render_structure

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

__all__ = ["atlas_figure", "view_step", "standing_cells", "MAX_VIEWS"]

#: Most views along each axis of the figure (24 × 24 views of about an inch each).
MAX_VIEWS = 24


def view_step(shape: tuple[int, int]) -> int:
    """The smallest k such that every k-th row and column of a grid of ``shape`` fit in the figure.

    >>> view_step((5, 5)), view_step((24, 3)), view_step((200, 200))
    (1, 1, 9)
    """
    return max(1, math.ceil(max(shape) / MAX_VIEWS))


def atlas_figure(
    atlas: Atlas, *, cell_size: float | None = None, view: Any = None, note: str | None = None
) -> Figure:
    """Small views of every vault: rows = a, columns = p_xy (the paper's Fig. 10).

    Each valid design is drawn at its design angle on the ground (strips shaded grey,
    each view scaled to fit its cell) with its section feature lines: at the feet in
    the xy plane (red) and at the apex in the zx plane (blue), their slopes written
    below and the number of tubes at the top left. An invalid design shows its reason
    in grey. All views are one rasterised collection, so even a 20 × 20 atlas makes a
    small SVG quickly.

    An atlas under load (its grid's ``load``) writes every analysed design's mass at the
    top right, outlines the designs that stand (dashed) and the lightest of those drawn
    (thick), says the governing check and its utilisation of one that fails, and has a legend
    below the grid (:func:`standing_cells`).

    Parameters
    ----------
    cell_size : float, optional, keyword-only
        Size of one view in inches; default fits the grid in about 24 inches.
    view : curvefold.figures.View, optional, keyword-only
    note : str, optional, keyword-only
        A last line for the title (say which designs of a larger grid are shown).

    Returns
    -------
    Figure
    """
    from matplotlib.collections import LineCollection, PolyCollection

    view = View() if view is None else view
    rows, cols = atlas.shape
    if max(rows, cols) > MAX_VIEWS:
        raise InputError(
            f"atlas_figure draws at most {MAX_VIEWS} × {MAX_VIEWS} views, got a "
            f"{rows} × {cols} atlas; draw atlas.every({view_step(atlas.shape)})"
        )
    size = float(np.clip(24.0 / max(rows, cols), 0.9, 2.2)) if cell_size is None else cell_size
    if not isinstance(size, (int, float)) or not np.isfinite(size) or size <= 0:
        raise InputError(f"cell_size must be a finite number > 0, got {cell_size!r}")
    font = float(np.clip(5.0 * size, 4.5, 9.0))
    margin_l, margin_r, margin_t = 0.45 + 0.02 * font, 0.15, 0.25 + 0.04 * font * 2
    margin_b = 0.12 + (0.03 * font if atlas.grid.load is not None else 0.0)  # the legend
    fig_w, fig_h = size * cols + margin_l + margin_r, size * rows + margin_b + margin_t
    fig = new_figure(figsize=(fig_w, fig_h), layout=None)
    ax = fig.add_axes(
        (margin_l / fig_w, margin_b / fig_h, size * cols / fig_w, size * rows / fig_h)
    )
    ax.set_xlim(0, cols)
    ax.set_ylim(0, rows)
    ax.set_aspect("equal")
    ax.set_axis_off()

    paths: list[np.ndarray] = []
    faces, edges, widths, grounds, lines, line_colors = [], [], [], [], [], []
    for index, (r, sk) in enumerate(zip(atlas.records, atlas.sketches)):
        i, j = divmod(index, cols)
        x0, y0 = float(j), float(rows - 1 - i)  # lower-left corner of the cell; row 0 on top
        if sk is None:
            ax.text(
                x0 + 0.5,
                y0 + 0.5,
                _short_reason(r),
                ha="center",
                va="center",
                fontsize=font * 0.8,
                color="#8a8a8a",
                linespacing=1.1,
            )
            continue
        curves = sk.curves.astype(float)
        lo, hi = curves.reshape(-1, 3).min(axis=0), curves.reshape(-1, 3).max(axis=0)
        ground = ground_polygon(lo, hi, view, pad=0.04 * float(np.max(hi - lo)))
        scene = replace(
            render_structure(
                curves, sk.cells, sk.kinds, view, colors={}, crease_width=0.0, strip_edge=0.25
            ),
            ground=ground,
        )
        low, high = scene.box
        c = 0.5 * (low + high)
        ext = np.maximum(high - low, 1e-12)
        scale = min(0.94 / ext[0], 0.70 / ext[1])
        offset = np.array([x0 + 0.5, y0 + 0.17 + 0.35]) - scale * c
        paths += [p * scale + offset for p in scene.paths]
        faces.append(scene.fill)
        edges.append(scene.stroke)
        widths.append(scene.widths)
        grounds.append(ground * scale + offset)
        for line, color in ((sk.feet, "#d62728"), (sk.apex, "#1f77b4")):
            xy, _ = view.project(_extend(line, 0.12))
            lines.append(xy * scale + offset)
            line_colors.append(color)
        ax.text(
            x0 + 0.04,
            y0 + 0.96,
            f"{r['tubes']}",
            ha="left",
            va="top",
            fontsize=font * 0.75,
            color="#666666",
        )
        ax.text(
            x0 + 0.28,
            y0 + 0.03,
            f"{r['slope_xy_deg']:.1f}°",
            ha="center",
            va="bottom",
            fontsize=font * 0.8,
            color="#d62728",
        )
        ax.text(
            x0 + 0.72,
            y0 + 0.03,
            f"{r['slope_zx_deg']:.1f}°",
            ha="center",
            va="bottom",
            fontsize=font * 0.8,
            color="#1f77b4",
        )
    if grounds:
        ax.add_collection(
            PolyCollection(
                grounds,
                facecolors=GROUND_COLOR,
                edgecolors="#c9bfa9",
                linewidths=0.3,
                zorder=1,
                rasterized=True,
            ),
            autolim=False,
        )
        strips = PolyCollection(
            paths,
            closed=False,
            facecolors=np.concatenate(faces),
            edgecolors=np.concatenate(edges),
            linewidths=np.concatenate(widths),
            zorder=2,
        )
        strips.set_rasterized(True)
        ax.add_collection(strips, autolim=False)
        ax.add_collection(
            LineCollection(lines, colors=line_colors, linewidths=1.1, capstyle="round", zorder=3),
            autolim=False,
        )
    if atlas.grid.load is not None:
        _mark_standing(ax, atlas, font)
    for j in range(1, cols):
        ax.axvline(j, color="#e4e4e4", lw=0.5, zorder=0)
    for i in range(1, rows):
        ax.axhline(i, color="#e4e4e4", lw=0.5, zorder=0)
    for i, a in enumerate(atlas.grid.a_values):
        ax.text(
            -0.06,
            rows - 1 - i + 0.5,
            f"a = {a:.3g}",
            ha="right",
            va="center",
            rotation=90,
            fontsize=font,
        )
    for j, p in enumerate(atlas.grid.p_xy_values):
        ax.text(
            j + 0.5, rows + 0.04, f"$p_{{xy}}$ = {p:.3g}", ha="center", va="bottom", fontsize=font
        )
    tubes = (
        f"up to {DEFAULT_TUBES_CAP} tubes, fewer where regression limits the stack"
        if atlas.grid.tubes is None
        else f"{atlas.grid.tubes} tubes"
    )
    title_size = max(font * 1.1, 7.0)
    chars = max(40, int(fig_w * 72 / (0.55 * title_size)))
    title = "\n".join(
        textwrap.fill(line, chars)
        for line in (
            f"Vault design atlas: width w_L(0)·κ₀ = {atlas.grid.width:g}, 2α = "
            f"{atlas.grid.fold_angle:g}°, {tubes} (number at the top left of each view)",
            "slope of the section feature line at the feet (xy plane) in red, at the apex (zx "
            "plane) in blue",
            *([] if atlas.grid.load is None else [_load_words(atlas)]),
            *([note] if note else []),
        )
    )
    fig.text(0.5, 1 - 0.08 / fig_h, title, ha="center", va="top", fontsize=title_size)
    # room for a wrapped title: grow the figure at the top, keeping the grid's size in inches
    title_lines = title.count("\n") + 1
    extra = max(0.0, (title_lines - 2) * title_size * 1.25 / 72)
    if extra:
        fig.set_size_inches(fig_w, fig_h + extra)
        ax.set_position(
            (
                margin_l / fig_w,
                margin_b / (fig_h + extra),
                size * cols / fig_w,
                size * rows / (fig_h + extra),
            )
        )
        fig.texts[-1].set_y(1 - 0.08 / (fig_h + extra))
    return fig


#: Outline of a design that stands under load, and of the lightest of them.
STANDS_COLOR, LIGHTEST_COLOR = "#2ca02c", "#0b5d1e"


def standing_cells(atlas: Atlas) -> tuple[list[tuple[int, int]], tuple[int, int] | None]:
    """(row, col) of every design of ``atlas`` that stands under load, and of the lightest of
    them (the first of equal mass in grid order; None when none stands).

    Examples
    --------
    >>> from curvefold.mechanics import AtlasLoad, MATERIALS
    >>> from curvefold.vault import run_atlas
    >>> load = AtlasLoad(MATERIALS["polypropylene"], 1e-3, samples=21)
    >>> atlas = run_atlas([0.75, 1.0], [0.9], samples=41, load=load, workers=1)
    >>> standing_cells(atlas)
    ([(0, 0), (0, 1)], (0, 0))
    """
    cells = [(r["row"], r["col"]) for r in atlas.records if r.get("stands") is True]
    if not cells:
        return cells, None
    lightest = min((r for r in atlas.records if r.get("stands") is True), key=lambda r: r["mass"])
    return cells, (lightest["row"], lightest["col"])


def _mark_standing(ax: Any, atlas: Atlas, font: float) -> None:
    """Outline the designs that stand (the lightest thicker), write every analysed design's mass
    at its top right and, for one that fails, its governing check; and the legend."""
    from matplotlib.patches import Patch, Rectangle

    rows, cols = atlas.shape
    cells, lightest = standing_cells(atlas)
    for i, j in cells:
        light = (i, j) == lightest
        ax.add_patch(
            Rectangle(
                (j + 0.03, rows - 1 - i + 0.03),
                0.94,
                0.94,
                fill=False,
                edgecolor=LIGHTEST_COLOR if light else STANDS_COLOR,
                linewidth=2.6 if light else 1.4,
                linestyle="-" if light else "--",
                gid="lightest" if light else "stands",
                zorder=4,
            )
        )
    for r in atlas.records:
        if r.get("mass") is None:
            continue
        x0, y0 = float(r["col"]), float(rows - 1 - r["row"])
        ax.text(
            x0 + 0.96,
            y0 + 0.96,
            f"{r['mass']:.3g} kg",
            ha="right",
            va="top",
            fontsize=font * 0.75,
            color="#333333",
        )
        if r["stands"] is False:
            ax.text(
                x0 + 0.96,
                y0 + 0.96 - font * 0.012,
                f"fails: {r['governing']} {r['utilisation']:.3g}",
                ha="right",
                va="top",
                fontsize=font * 0.7,
                color="#b22222",
                bbox={"facecolor": "white", "alpha": 0.8, "edgecolor": "none", "pad": 0.6},
                zorder=5,
            )
    ax.legend(
        handles=[
            Patch(fill=False, edgecolor=STANDS_COLOR, linestyle="--", label="stands"),
            Patch(
                fill=False, edgecolor=LIGHTEST_COLOR, linewidth=2.6, label="lightest that stands"
            ),
        ],
        loc="upper left",
        bbox_to_anchor=(0.0, 0.0),
        ncols=2,
        fontsize=font,
        frameon=False,
    )


def _load_words(atlas: Atlas) -> str:
    """The title's line of the mechanics: the material, the loads and the model."""
    load = cast(Any, atlas.grid.load).to_dict()
    across = load["across"]
    return (
        f"under load: {load['material']} {load['thickness'] * 1e3:g} mm, {load['loads']}, "
        f"{load['supports']} feet (radius 1 m; model of {load['samples']} samples, {across} "
        f"element{'s' * (across != 1)} across); mass at the top right; outlined: stands "
        "(every check's utilisation ≤ 1)"
    )


def _extend(line: np.ndarray, fraction: float) -> np.ndarray:
    """A segment (2, 3) lengthened by ``fraction`` of its length at both ends."""
    d = line[1] - line[0]
    return np.stack([line[0] - fraction * d, line[1] + fraction * d])


def _short_reason(record: dict, width: int = 22, lines: int = 5) -> str:
    """The first clause of an invalid design's reason, wrapped for a small panel."""
    text = str(record.get("reason") or "invalid")
    head = text.split(": ")[0] if ": " in text else text
    kind = {
        "ConvergenceError": "no arch",
        "RegressionError": "regression",
        "InputError": "invalid input",
    }.get(str(record.get("error")), "invalid")
    # keep "a = 1.3" whole
    head = textwrap.shorten(head, width * (lines - 1), placeholder=" …").replace(
        " = ", "\u00a0=\u00a0"
    )
    return kind + "\n" + textwrap.fill(head, width)
