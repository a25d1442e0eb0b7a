"""Plots of lattices, sections and mechanisms, and the writing of figures (matplotlib, optional).

Every function returns a :class:`matplotlib.figure.Figure` built directly, without
``pyplot`` and its global state, so figures can be made in threads, tests and servers
alike; :func:`save_figure` writes them atomically. matplotlib is imported only when a
function is called (``pip install curvefold[plot]``).

The 3D views of structures and vaults are in :mod:`curvefold.figures._views`, the frames of
the folding motion's GIF in :mod:`curvefold.figures._motion`. Lengths are in model units
(the unit of the design's radius).
"""

from __future__ import annotations

import os
import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..io._atomic import atomic_path
from ..io._tables import COLOURS
from ..kernel._arrays import FrozenArrays
from ..kernel._errors import InputError
from ..kernel._validate import check_integer

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from ..analysis._mechanism import Mechanism
    from ..geometry._kinds import StructureLattice
    from ..geometry._structure import State, Structure
    from ..vault._assembly import Vault

__all__ = [
    "KIND_COLORS",
    "UNITS",
    "new_figure",
    "structure_of",
    "mathtext",
    "DomainPlot",
    "domain_plot",
    "plot_regression_domain",
    "WidthPlot",
    "width_plot",
    "plot_width_proportion",
    "section_coordinates",
    "SectionPlot",
    "section_plot",
    "plot_sections",
    "SingularValuesPlot",
    "singular_values_plot",
    "plot_singular_values",
    "save_figure",
]

#: Line colours of the crease kinds (from :data:`curvefold.io._tables.COLOURS`).
KIND_COLORS = {kind: COLOURS[kind] for kind in ("fold", "seam", "junction", "edge")}
#: How the figures name the model unit.
UNITS = "model units"
#: Fill and outline of the valid set of the regression domain.
DOMAIN_FILL, DOMAIN_EDGE = "#cfe8cf", "#2e7d32"
#: Colours of the non-design fold angles of the sections and of the states of the singular values.
PALETTE = ("#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02", "#a6761d")
#: The lattice curves' kinds the plots mark, in legend order.
MARKED_KINDS = ("fold", "seam", "junction")


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


def structure_of(obj: Any) -> tuple[Structure, StructureLattice, float]:
    """(structure, lattice, design fold angle in degrees) of a Vault, Structure or State."""
    from ..geometry._structure import State, Structure
    from ..vault._assembly import Vault

    if isinstance(obj, Vault):
        return obj.structure, obj.lattice, float(obj.design.fold_angle)
    if isinstance(obj, State):
        return obj.structure, obj.lattice, float(obj.fold_angle)
    if isinstance(obj, Structure):
        return obj, obj.lattice, float(obj.lattice.crease.fold_angle)
    raise InputError(f"expected a Vault, Structure or State, got {type(obj).__name__}")


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


# -- the regression domain (Fig. 07) --------------------------------------------------------


def _clip_line(a: float, b: float, box: float) -> np.ndarray | None:
    """The segment of the line a u + b v = 1 inside |u|, |v| ≤ box, shape (2, 2), or None."""
    pts = []
    if abs(b) > 1e-300:
        for u in (-box, box):
            v = (1 - a * u) / b
            if abs(v) <= box:
                pts.append((u, v))
    if abs(a) > 1e-300:
        for v in (-box, box):
            u = (1 - b * v) / a
            if abs(u) <= box:
                pts.append((u, v))
    if len(pts) < 2:
        return None
    pts_arr = np.array(pts)
    d = np.array([-b, a])
    proj = pts_arr @ d
    return pts_arr[[np.argmin(proj), np.argmax(proj)]]


@dataclass(frozen=True, eq=False)
class DomainPlot(FrozenArrays):
    """What the regression-domain plot shows (:func:`domain_plot`), in (u, v), for any renderer.

    Attributes
    ----------
    box : float
        Half-size of the square window.
    valid : (P, 2) ndarray
        The valid set ``1 − u a(t) − v b(t) > 0`` for all t within the window, a polygon.
    lines : (L, 2, 2) ndarray
        Limiting lines ``u a(t) + v b(t) = 1`` clipped to the window, at parameters ``line_t`` (L,).
    cells : (K, 4, 2) ndarray
        The cells' unit squares (K = 0 without cells).
    corners : (M, 2) ndarray
        The lattice curves at the cells' corners, of kinds ``kinds`` (M,); ``past`` (M,) marks
        those past regression.
    """

    box: float
    valid: np.ndarray
    lines: np.ndarray
    line_t: np.ndarray
    cells: np.ndarray
    corners: np.ndarray
    kinds: np.ndarray
    past: np.ndarray

    title = "Regression domain of the lattice (Eq. 18)"
    xlabel, ylabel = "u  (× w_L)", "v  (× w_R)"
    valid_label = "valid: free of regression (Eq. 18)"
    lines_label = "limiting lines (coloured by t)"
    key_label = "t of the limiting line  u a(t) + v b(t) = 1"

    def legend(self) -> list[tuple[str, dict]]:
        """(label, style) of the legend's entries: see
        :meth:`curvefold.figures._canvas.Frame.legend`."""
        entries: list[tuple[str, dict]] = [
            (self.valid_label, {"patch": DOMAIN_FILL, "edge": DOMAIN_EDGE})
        ]
        if len(self.cells):
            entries.append((f"cells ({len(self.cells)})", {"patch": "#ffffff", "edge": "#555555"}))
        entries += [
            (f"lattice curve: {kind}", {"marker": KIND_COLORS[kind]})
            for kind in MARKED_KINDS
            if (self.kinds == kind).any()
        ]
        if self.past.any():
            entries.append(("past regression", {"marker": "#000000", "shape": "x", "size": 6.0}))
        return entries + [(self.lines_label, {"line": "#2ca02c", "width": 0.8})]


def domain_plot(
    lattice: StructureLattice,
    cells: np.ndarray | Sequence[Sequence[int]] | None = None,
    *,
    box: float | None = None,
    lines: int = 24,
) -> DomainPlot:
    """What the regression-domain plot of a lattice shows: see :func:`plot_regression_domain` (same
    parameters).

    Raises
    ------
    InputError
        Cells that are not a non-empty (K, 2) array of integers, or a box that is not > 0.
    """
    from ..geometry._structure import Structure

    domain = lattice.domain
    structure = None
    if cells is not None:
        arr = np.asarray(cells)
        if (
            arr.ndim != 2
            or arr.shape[1] != 2
            or len(arr) == 0
            or not np.issubdtype(arr.dtype, np.integer)
        ):
            raise InputError(
                "cells must be a non-empty (K, 2) array of integers, got shape "
                f"{arr.shape} and dtype {arr.dtype}"
            )
        # Unchecked: cells past regression are shown, not refused.
        structure = Structure(lattice, arr.astype(np.int64))
    if box is None:  # the nearest part of the boundary, and every cell
        dirs = np.array(
            [[1, 0], [0, 1], [-1, 0], [0, -1], [1, 1], [-1, -1], [1, -1], [-1, 1]], float
        )
        ext = domain.extent(dirs)
        reach = [1.5, float(ext[np.isfinite(ext)].min()) if np.isfinite(ext).any() else 1.5]
        if structure is not None:
            reach.append(float(np.abs(structure.curves_uv).max()))
        box = 1.3 * min(max(reach), 1e4)
    if not np.isfinite(box) or box <= 0:
        raise InputError(f"box must be a finite number > 0, got {box!r}")
    # increasing: repeats are neighbours
    spread = np.linspace(0, len(domain.t) - 1, max(lines, 2)).round().astype(int)
    idx = spread[np.r_[True, spread[1:] != spread[:-1]]]
    clipped = [(_clip_line(float(domain.a[i]), float(domain.b[i]), box), domain.t[i]) for i in idx]
    clipped = [(seg, t) for seg, t in clipped if seg is not None]
    if structure is None:
        squares, uv, kinds = np.zeros((0, 4, 2)), np.zeros((0, 2)), np.zeros(0, str)
    else:
        squares = (structure.cells[:, None, :] + np.array([[0, 0], [1, 0], [1, 1], [0, 1]])).astype(
            float
        )
        uv, kinds = structure.curves_uv.astype(float), np.asarray(structure.curve_kinds)
    return DomainPlot(
        float(box),
        domain.polygon(box=box),
        np.array([seg for seg, _ in clipped]).reshape(-1, 2, 2),
        np.array([t for _, t in clipped], float),
        squares,
        uv,
        kinds,
        ~domain.contains(uv),
    )


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


# -- width laws ---------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class WidthPlot(FrozenArrays):
    """What the width-proportion plot shows (:func:`width_plot`): curves along t in two panels.

    Attributes
    ----------
    t : (n,) ndarray
        Curve 1's normalised arc length.
    width_left, width_right : (n,) ndarray
        w_L(t), w_R(t), model units (the upper panel).
    ratio, change : (n,) ndarray
        w_R/w_L and w_R(t)/w_R(0) (the lower panel).
    marks : (2,) ndarray
        t = 0 and the sample nearest t = ½, marked in both panels; ``notes`` are the texts of
        the ratio there, each (text, above) with ``above`` whether it goes over its point.
    """

    t: np.ndarray
    width_left: np.ndarray
    width_right: np.ndarray
    ratio: np.ndarray
    change: np.ndarray
    marks: np.ndarray
    notes: tuple

    title = "Section widths and proportion along the crease"
    widths_label, ratio_label, xlabel = (
        f"width ({UNITS})",
        "proportion",
        "t  (curve 1's normalised arc length)",
    )
    #: (label, colour, width in points, dash or None) of the curves of each panel.
    top_curves = (("w_L(t)", "#ff7f0e", 1.6, None), ("w_R(t)", "#9467bd", 1.6, None))
    bottom_curves = (
        ("w_R / w_L", "#000000", 1.6, None),
        ("w_R(t) / w_R(0)", "#8c564b", 1.2, (3.7, 1.6)),
    )

    @property
    def mark_ratio(self) -> np.ndarray:
        """(2, 2) points (t, w_R/w_L) of the marks."""
        at = np.searchsorted(self.t, self.marks)
        return np.stack([self.marks, self.ratio[at]], axis=-1)


def width_plot(lattice: StructureLattice) -> WidthPlot:
    """What the width-proportion plot of a lattice shows: see :func:`plot_width_proportion`."""
    t = lattice.t
    ratio = lattice.width_right / lattice.width_left
    m = int(np.argmin(np.abs(t - 0.5)))
    notes = (
        (f"{ratio[0]:.4g} at t = 0", bool(ratio[0] >= ratio[m])),
        (f"{ratio[m]:.4g} at t = ½", bool(ratio[m] >= ratio[0])),
    )
    return WidthPlot(
        t,
        lattice.width_left,
        lattice.width_right,
        ratio,
        lattice.width_right / lattice.width_right[0],
        np.array([t[0], t[m]]),
        notes,
    )


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


# -- sections (the pantograph) --------------------------------------------------------------------


def section_coordinates(lattice: StructureLattice, uv: np.ndarray, index: int) -> np.ndarray:
    """Lattice curves uv (M, 2) at sample ``index`` projected along curve 1's tangent.

    Returns the coordinates (M, 2) of ``x(t; u, v) − x₁(t)`` on curve 1's N(t) and B(t)
    there: the section of the structure normal to the common tangent.
    """
    pts = lattice.points(np.asarray(uv, float))[:, index]
    curve = lattice.crease.curve
    d = pts - curve.points[index]
    return np.stack([d @ curve.normal[index], d @ curve.binormal[index]], axis=-1)


@dataclass(frozen=True, eq=False)
class SectionPlot(FrozenArrays):
    """What the sections plot shows (:func:`section_plot`): one panel per t, the cells at every fold
    angle.

    Attributes
    ----------
    angles : (A,) ndarray
        2α in degrees; ``design`` is the index of the structure's own angle (drawn solid, in
        black, over the others dashed in :data:`PALETTE`).
    cells : (T, A, K, 4, 2) ndarray
        The cells' parallelograms of every panel at every angle, model units along N(t), B(t).
    corners : (T, M, 2) ndarray
        The lattice curves at the design angle, of kinds ``kinds`` (M,).
    titles : tuple of str
        Each panel's title.
    """

    angles: np.ndarray
    design: int
    cells: np.ndarray
    corners: np.ndarray
    kinds: np.ndarray
    titles: tuple

    title = "Sections normal to the common tangent T(t): the pantograph"
    xlabel, ylabel = f"along N(t) ({UNITS})", f"along B(t) ({UNITS})"
    dash = (4.0, 2.0)

    @property
    def colors(self) -> list[str]:
        """The line colour of every angle."""
        others = iter(PALETTE * len(self.angles))
        return ["#000000" if k == self.design else next(others) for k in range(len(self.angles))]

    def legend(self) -> list[tuple[str, dict]]:
        """(label, style) of the legend's entries (see :meth:`DomainPlot.legend`)."""
        entries = [
            (
                f"2α = {f:g}°" + (" (design)" if k == self.design else ""),
                {"line": c, "width": 1.5}
                if k == self.design
                else {"line": c, "width": 1.0, "dash": self.dash},
            )
            for k, (f, c) in enumerate(zip(self.angles.tolist(), self.colors))
        ]
        entries += [
            (kind, {"marker": KIND_COLORS[kind]})
            for kind in MARKED_KINDS
            if (self.kinds == kind).any()
        ]
        return entries + [("curve 1", {"marker": "#000000", "shape": "ring", "size": 8.0})]


def section_plot(
    obj: Vault | Structure | State,
    t_values: Sequence[float] = (0.0, 0.5),
    *,
    fold_angles: Sequence[float] | None = None,
) -> SectionPlot:
    """What the sections plot shows: see :func:`plot_sections` (same parameters and errors)."""
    from ..vault._assembly import Vault

    structure, lattice, own = structure_of(obj)
    t_arr = np.atleast_1d(np.asarray(t_values, float))
    if (
        t_arr.ndim != 1
        or t_arr.size == 0
        or not np.all(np.isfinite(t_arr))
        or np.any((t_arr < 0) | (t_arr > 1))
    ):
        raise InputError(
            f"t_values must be a non-empty list of numbers in [0, 1], got {t_values!r}"
        )
    angles = (
        sorted(set(np.round([30.0, 60.0, 90.0, own], 9)))
        if fold_angles is None
        else list(np.atleast_1d(np.asarray(fold_angles, float)))
    )
    if len(angles) == 0:
        raise InputError("fold_angles must hold at least one angle")
    lattices = [lattice.refold(f) for f in angles]  # validates every angle
    design = int(np.argmin(np.abs(np.asarray(angles) - own)))
    n = len(lattice.t)
    samples = [int(np.argmin(np.abs(lattice.t - tv))) for tv in t_arr]
    # (T, A, M, 2)
    xy = np.array(
        [[section_coordinates(lat, structure.curves_uv, i) for lat in lattices] for i in samples]
    )
    vault = isinstance(obj, Vault)
    titles = tuple(
        f"section at t = {lattice.t[i]:.3g}"
        + ({0: " (feet)", (n - 1) // 2: " (apex)"}.get(i, "") if vault else "")
        for i in samples
    )
    return SectionPlot(
        np.asarray(angles, float),
        design,
        xy[:, :, structure.cell_curves],
        xy[:, design],
        np.asarray(structure.curve_kinds),
        titles,
    )


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


@dataclass(frozen=True, eq=False)
class SingularValuesPlot(FrozenArrays):
    """What the singular-values plot shows (:func:`singular_values_plot`), log–log.

    Attributes
    ----------
    values : tuple of (n_k,) ndarray
        Each state's singular values over its largest, smallest first (at least the smallest float).
    tolerances : (S,) ndarray
        Each state's rank tolerance over its largest singular value.
    labels : tuple of str
        Each state's legend text; its colour is :data:`PALETTE`'s in turn.
    """

    values: tuple
    tolerances: np.ndarray
    labels: tuple
    title: str

    xlabel, ylabel, tolerance_label = "rank from the smallest", "σ / σ_max", "rank tolerance"

    @property
    def colors(self) -> list[str]:
        return [PALETTE[k % 6] for k in range(len(self.labels))]


def singular_values_plot(
    mechanisms: Sequence[Mechanism], *, title: str = "Singular values of the constraint Jacobian"
) -> SingularValuesPlot:
    """What the singular-values plot shows: see :func:`plot_singular_values`."""
    if len(mechanisms) == 0:
        raise InputError("mechanisms must hold at least one analysed state")
    tiny = np.finfo(float).tiny
    values = tuple(
        np.maximum(m.singular_values[::-1] / m.singular_values[0], tiny) for m in mechanisms
    )
    labels = tuple(
        f"{m.label}: {m.dof} internal DOF ({m.nullity} null), "
        + f"gap {m.gap:.1e}".replace("inf", "∞")
        for m in mechanisms
    )
    return SingularValuesPlot(
        values, np.array([m.tolerance / m.singular_values[0] for m in mechanisms]), labels, title
    )


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
