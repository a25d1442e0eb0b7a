"""Plots of lattices, sections and mechanisms, and the writing of figures (matplotlib, optional).

Every function returns a :class:`matplotlib.figure.Figure` built directly, without
``pyplot`` and its global state, so figures can be made in threads, tests and servers
alike; :func:`save_figure` writes them atomically. matplotlib is imported only when a
function is called (``pip install curvefold[plot]``).

What each plot shows is a value of :mod:`curvefold.figures._plot_data`, drawn here. The 3D
views of structures and vaults are in :mod:`curvefold.figures._views`, the frames of the
folding motion's GIF in :mod:`curvefold.figures._motion`. Lengths are in model units (the
unit of the design's radius).
"""

from __future__ import annotations

import os
import re
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..io._atomic import atomic_path
from ..kernel._errors import InputError
from ..kernel._validate import check_integer
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

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from ..analysis._mechanism import Mechanism
    from ..geometry._kinds import StructureLattice
    from ..geometry._structure import State, Structure
    from ..vault._assembly import Vault

__all__ = [
    "new_figure",
    "mathtext",
    "plot_regression_domain",
    "plot_width_proportion",
    "plot_sections",
    "plot_singular_values",
    "save_figure",
]


def mathtext(label: str) -> str:
    """A label with subscripts written ``w_L`` or ``p_{xy}`` in matplotlib's mathtext.

    Examples
    --------
    >>> mathtext("w_R(t) / w_R(0)")
    '$w_R$(t) / $w_R$(0)'
    """
    return re.sub(r"([A-Za-z])_(\{[^}]*\}|\w)", lambda m: f"${m.group(1)}_{m.group(2)}$", label)


def new_figure(**kwargs: Any) -> Figure:
    """A new Figure with constrained layout, never registered with pyplot (keyword arguments go
    to it)."""
    try:
        from matplotlib.figure import Figure
    except ImportError as err:  # pragma: no cover - exercised only without matplotlib
        raise ImportError(
            "curvefold's plots need matplotlib: pip install 'curvefold[plot]'"
        ) from err
    kwargs.setdefault("layout", "constrained")
    return Figure(**kwargs)


def legend_handles(entries: Sequence[tuple[str, dict]]) -> list:
    """matplotlib legend handles of (label, style) entries (the styles of
    :meth:`curvefold.figures._canvas.Frame.legend`)."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    def handle(label: str, style: dict):
        if "line" in style:
            dash = style.get("dash")
            return Line2D(
                [],
                [],
                color=style["line"],
                lw=style.get("width", 1.2),
                ls="-" if dash is None else (0, dash),
                label=label,
            )
        if "patch" in style:
            return Patch(
                facecolor=style["patch"], edgecolor=style.get("edge", "#555555"), label=label
            )
        shape, size = style.get("shape", "o"), style.get("size", 4.0)
        face = "none" if shape == "ring" else style["marker"]
        return Line2D(
            [],
            [],
            ls="",
            marker="o" if shape == "ring" else shape,
            ms=size,
            mfc=face,
            mec=style["marker"],
            label=label,
        )

    return [handle(label, style) for label, style in entries]


# -- the regression domain (Fig. 07) ---------------------------------------------------------------


def plot_regression_domain(
    lattice: StructureLattice,
    cells: np.ndarray | Sequence[Sequence[int]] | None = None,
    *,
    box: float | None = None,
    lines: int = 24,
) -> Figure:
    """The regression domain of a lattice in (u, v) (the paper's Fig. 07).

    The valid set ``1 − u a(t) − v b(t) > 0`` for all t (Eq. 18) is shaded; a family of
    the limiting lines ``u a(t) + v b(t) = 1`` is drawn coloured by t; cells are drawn as
    unit squares and the lattice curves at their corners as dots coloured by kind (fold,
    seam, junction). Corners past regression are marked with a black ×. What it shows is
    :func:`domain_plot`'s.

    Parameters
    ----------
    lattice : Lattice
    cells : (K, 2) array_like of int, optional
        Cells (i, j) spanning [i, i+1] × [j, j+1], e.g. ``vault.structure.cells``.
    box : float, optional, keyword-only
        Half-size of the (u, v) window; default fits the cells and the domain's extent
        along the axes and the diagonals (at least 2).
    lines : int, keyword-only
        Number of limiting lines drawn (evenly spread in t).

    Returns
    -------
    Figure
    """
    from matplotlib.collections import LineCollection, PolyCollection
    from matplotlib.patches import Polygon

    plot = domain_plot(lattice, cells, box=box, lines=lines)
    box = plot.box
    fig = new_figure(figsize=(6.4, 5.4))
    ax = fig.add_subplot()
    ax.add_patch(
        Polygon(
            plot.valid,
            closed=True,
            facecolor=DOMAIN_FILL,
            edgecolor=DOMAIN_EDGE,
            linewidth=1.4,
            zorder=1,
        )
    )
    if len(plot.lines):
        lc = LineCollection(list(plot.lines), cmap="viridis", linewidths=0.8, alpha=0.9, zorder=2)
        lc.set_array(plot.line_t)
        lc.set_clim(0.0, 1.0)
        ax.add_collection(lc, autolim=False)
        cbar = fig.colorbar(lc, ax=ax, shrink=0.85, pad=0.02)
        cbar.set_label(plot.key_label)
    if len(plot.cells):
        ax.add_collection(
            PolyCollection(
                list(plot.cells),
                facecolors="#ffffff80",
                edgecolors="#555555",
                linewidths=0.8,
                zorder=3,
            ),
            autolim=False,
        )
        for kind in MARKED_KINDS:
            sel = plot.kinds == kind
            if sel.any():
                ax.scatter(
                    plot.corners[sel, 0],
                    plot.corners[sel, 1],
                    s=14,
                    color=KIND_COLORS[kind],
                    zorder=4,
                )
        if plot.past.any():
            bad = plot.corners[plot.past]
            ax.scatter(
                bad[:, 0], bad[:, 1], s=40, marker="x", color="black", linewidths=1.2, zorder=5
            )
    ax.plot([0], [0], marker="o", ms=9, mfc="none", mec="black", mew=1.0, zorder=6)
    ax.annotate("curve 1", (0, 0), xytext=(6, -12), textcoords="offset points", fontsize=7)
    ax.axhline(0, color="#999999", lw=0.5, zorder=0)
    ax.axvline(0, color="#999999", lw=0.5, zorder=0)
    ax.set_xlim(-box, box)
    ax.set_ylim(-box, box)
    ax.set_aspect("equal")
    ax.set_xlabel(mathtext(plot.xlabel))
    ax.set_ylabel(mathtext(plot.ylabel))
    ax.set_title(plot.title)
    ax.legend(handles=legend_handles(plot.legend()), fontsize=7, loc="upper left", framealpha=0.9)
    return fig


# -- width laws ------------------------------------------------------------------------------------


def plot_width_proportion(lattice: StructureLattice) -> Figure:
    """Widths w_L(t), w_R(t) and the section proportion w_R/w_L along the crease.

    Two panels sharing t: the widths in model units (Eqs. 12–13: ``ln w_R`` grows by
    ``∫ τ cot α ds``, ``ln w_L`` shrinks by as much) and the proportions ``w_R/w_L`` and
    ``w_R(t)/w_R(0)``. t = 0 (the feet of a vault) and t = ½ (its apex) are marked. What it
    shows is :func:`width_plot`'s.

    Parameters
    ----------
    lattice : Lattice

    Returns
    -------
    Figure
    """
    plot = width_plot(lattice)
    fig = new_figure(figsize=(6.4, 5.2))
    top, bottom = fig.subplots(2, 1, sharex=True)
    for ax, curves, values in (
        (top, plot.top_curves, (plot.width_left, plot.width_right)),
        (bottom, plot.bottom_curves, (plot.ratio, plot.change)),
    ):
        for (label, color, width, dash), y in zip(curves, values):
            ax.plot(
                plot.t,
                y,
                color=color,
                lw=width,
                ls="-" if dash is None else "--",
                label=mathtext(label),
            )
        for x in plot.marks:
            ax.axvline(x, color="#999999", lw=0.8, ls=":", zorder=0)
        ax.grid(True, lw=0.3, alpha=0.5)
        ax.legend(fontsize=8, loc="best")
    top.set_ylabel(plot.widths_label)
    top.set_title(plot.title)
    bottom.set_ylabel(plot.ratio_label)
    bottom.set_xlabel(plot.xlabel)
    for (x, y), (text, above) in zip(plot.mark_ratio, plot.notes):
        bottom.plot([x], [y], "o", color="black", ms=4)
        bottom.annotate(
            text,
            (x, y),
            xytext=(6, 7 if above else -7),
            textcoords="offset points",
            fontsize=8,
            va="bottom" if above else "top",
        )
    bottom.margins(y=0.18)
    bottom.set_xlim(-0.02, 1.02)
    return fig


# -- sections (the pantograph) ---------------------------------------------------------------------


def plot_sections(
    obj: Vault | Structure | State,
    t_values: Sequence[float] = (0.0, 0.5),
    *,
    fold_angles: Sequence[float] | None = None,
) -> Figure:
    """Sections of a structure normal to curve 1's tangent, at several fold angles (the pantograph).

    All lattice curves share curve 1's frame at equal t (Eq. 11), so projected along the
    common tangent T(t) they form a lattice of parallelograms with fixed sides
    w_L(t), w_R(t): rigid folding shears it like a pantograph, flat at 2α = 0. What it
    shows is :func:`section_plot`'s.

    Parameters
    ----------
    obj : Vault, Structure or State
    t_values : sequence of float
        Curve parameters in [0, 1]; the nearest samples are drawn, one panel each.
    fold_angles : sequence of float, optional, keyword-only
        2α in degrees, in [0°, 180°); default 30°, 60°, 90° and the structure's own angle.

    Returns
    -------
    Figure
    """
    from matplotlib.collections import PolyCollection
    from matplotlib.colors import to_rgba

    plot = section_plot(obj, t_values, fold_angles=fold_angles)
    colors = [to_rgba(c) for c in plot.colors]
    fig = new_figure(figsize=(4.6 * len(plot.titles) + 0.4, 4.8))
    axes = np.atleast_1d(fig.subplots(1, len(plot.titles), squeeze=False)[0])
    for ax, cells, corners, title in zip(axes, plot.cells, plot.corners, plot.titles):
        for k, polys in enumerate(cells):
            strong = k == plot.design
            ax.add_collection(
                PolyCollection(
                    polys,
                    facecolors=(*colors[k][:3], 0.06 if strong else 0.0),
                    edgecolors=[colors[k]],
                    linewidths=1.5 if strong else 1.0,
                    linestyles="solid" if strong else (0, plot.dash),
                    zorder=2 + strong,
                )
            )
        for kind in MARKED_KINDS:
            sel = plot.kinds == kind
            if sel.any():
                ax.scatter(
                    corners[sel, 0], corners[sel, 1], s=12, color=KIND_COLORS[kind], zorder=5
                )
        ax.plot([0], [0], marker="o", ms=8, mfc="none", mec="black", mew=1.0, zorder=6)
        ax.autoscale_view()
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(True, lw=0.3, alpha=0.5)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel(plot.xlabel)
    axes[0].set_ylabel(plot.ylabel)
    fig.legend(
        handles=legend_handles(plot.legend()), loc="outside right center", fontsize=8, frameon=False
    )
    fig.suptitle(plot.title, fontsize=11)
    return fig


# -- mechanism -------------------------------------------------------------------------------------


def plot_singular_values(
    mechanisms: Sequence[Mechanism], *, title: str = "Singular values of the constraint Jacobian"
) -> Figure:
    """The singular values of panel structures' constraint Jacobians, smallest first, one line per
    state.

    Each state's values are divided by its largest and drawn against their rank from the
    smallest (log–log), with its rank tolerance: those on or below it are the first-order
    motions (6 of them rigid), and the gap above them shows how clear the count is. What it
    shows is :func:`singular_values_plot`'s.

    Parameters
    ----------
    mechanisms : sequence of Mechanism
        From :func:`curvefold.analysis.analyse` or :func:`curvefold.analysis.analyse_fold`.
    title : str, keyword-only

    Returns
    -------
    Figure
    """
    plot = singular_values_plot(mechanisms, title=title)
    fig = new_figure(figsize=(6.4, 4.6))
    ax = fig.add_subplot()
    for s, tolerance, label, color in zip(plot.values, plot.tolerances, plot.labels, plot.colors):
        ax.loglog(np.arange(1, len(s) + 1), s, ".-", ms=3, lw=0.8, color=color, label=label)
        ax.axhline(tolerance, color="#999999", lw=0.8, ls="--", zorder=0)
    ax.text(
        1.05, plot.tolerances[0], plot.tolerance_label, fontsize=8, color="#666666", va="bottom"
    )
    ax.set_xlabel(plot.xlabel)
    ax.set_ylabel(plot.ylabel)
    ax.set_title(plot.title, fontsize=10)
    ax.grid(True, which="major", lw=0.3, alpha=0.5)
    ax.legend(fontsize=7, loc="lower right")
    return fig


# -- output ----------------------------------------------------------------------------------------


def save_figure(
    fig: Figure,
    path_stem: str | os.PathLike,
    formats: Sequence[str] = ("png", "svg"),
    dpi: int = 150,
) -> list[Path]:
    """Write a figure in several formats, each atomically, to ``path_stem + "." + format``.

    Parameters
    ----------
    fig : Figure
    path_stem : str or path-like
        Target path without the suffix; its folder must exist.
    formats : sequence of str
        File formats matplotlib can write ("png", "svg", "pdf", ...).
    dpi : int
        Resolution of raster formats.

    Returns
    -------
    list of Path
        The files written, in the order of ``formats``.
    """
    from matplotlib import rc_context

    supported = fig.canvas.get_supported_filetypes()
    formats = tuple(formats)
    bad = [f for f in formats if f not in supported]
    if bad or not formats:
        raise InputError(
            f"formats must be a non-empty list of {', '.join(sorted(supported))}; "
            f"got {list(formats)!r}"
        )
    dpi = check_integer(dpi, "dpi", "[10, 2400]")
    stem = os.fspath(path_stem)
    written = []
    for fmt in formats:
        target = Path(f"{stem}.{fmt}")
        metadata = {"svg": {"Date": None}, "pdf": {"CreationDate": None}}.get(fmt)
        with (
            rc_context({"svg.hashsalt": "curvefold", "svg.fonttype": "path"}),
            atomic_path(target) as tmp,
        ):
            fig.savefig(tmp, format=fmt, dpi=int(dpi), metadata=metadata)
        written.append(target)
    return written
