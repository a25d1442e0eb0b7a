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
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..io._atomic import atomic_path
from ..io._tables import COLOURS
from ..kernel._errors import InputError
from ..kernel._validate import check_integer

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from ..analysis._mechanism import Mechanism
    from ..geometry._lattice import Lattice
    from ..geometry._structure import State, Structure
    from ..vault._assembly import Vault

__all__ = [
    "KIND_COLORS",
    "UNITS",
    "new_figure",
    "structure_of",
    "plot_regression_domain",
    "plot_width_proportion",
    "section_coordinates",
    "plot_sections",
    "plot_singular_values",
    "save_figure",
]

#: Line colours of the crease kinds (from :data:`curvefold.io._tables.COLOURS`).
KIND_COLORS = {kind: COLOURS[kind] for kind in ("fold", "seam", "junction", "edge")}
#: How the figures name the model unit.
UNITS = "model units"


def new_figure(**kwargs: Any) -> Figure:
    """A new Figure with constrained layout, never registered with pyplot (keyword arguments go to it)."""
    try:
        from matplotlib.figure import Figure
    except ImportError as err:  # pragma: no cover - exercised only without matplotlib
        raise ImportError("curvefold's plots need matplotlib: pip install 'curvefold[plot]'") from err
    kwargs.setdefault("layout", "constrained")
    return Figure(**kwargs)


def structure_of(obj: Any) -> tuple[Structure, Lattice, float]:
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


def plot_regression_domain(
    lattice: Lattice,
    cells: np.ndarray | Sequence[Sequence[int]] | None = None,
    *,
    box: float | None = None,
    lines: int = 24,
) -> Figure:
    """The regression domain of a lattice in (u, v) (the paper's Fig. 07).

    The valid set ``1 − u a(t) − v b(t) > 0`` for all t (Eq. 18) is shaded; a family of
    the limiting lines ``u a(t) + v b(t) = 1`` is drawn coloured by t; cells are drawn as
    unit squares and the lattice curves at their corners as dots coloured by kind (fold,
    seam, junction). Corners past regression are marked with a black ×.

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
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch, Polygon

    from ..geometry._structure import Structure

    domain = lattice.domain
    structure = None
    if cells is not None:
        arr = np.asarray(cells)
        if arr.ndim != 2 or arr.shape[1] != 2 or len(arr) == 0 or not np.issubdtype(arr.dtype, np.integer):
            raise InputError(f"cells must be a non-empty (K, 2) array of integers, got shape {arr.shape} and dtype {arr.dtype}")
        structure = Structure(lattice, arr.astype(np.int64))  # unchecked: cells past regression are shown, not refused
    if box is None:  # the nearest part of the boundary, and every cell
        dirs = np.array([[1, 0], [0, 1], [-1, 0], [0, -1], [1, 1], [-1, -1], [1, -1], [-1, 1]], float)
        ext = domain.extent(dirs)
        reach = [1.5, float(ext[np.isfinite(ext)].min()) if np.isfinite(ext).any() else 1.5]
        if structure is not None:
            reach.append(float(np.abs(structure.curves_uv).max()))
        box = 1.3 * min(max(reach), 1e4)
    if not np.isfinite(box) or box <= 0:
        raise InputError(f"box must be a finite number > 0, got {box!r}")

    fig = new_figure(figsize=(6.4, 5.4))
    ax = fig.add_subplot()
    poly = domain.polygon(box=box)
    ax.add_patch(Polygon(poly, closed=True, facecolor="#cfe8cf", edgecolor="#2e7d32", linewidth=1.4, zorder=1))

    idx = np.unique(np.linspace(0, len(domain.t) - 1, max(lines, 2)).round().astype(int))
    segs, ts = [], []
    for i in idx:
        seg = _clip_line(float(domain.a[i]), float(domain.b[i]), box)
        if seg is not None:
            segs.append(seg)
            ts.append(domain.t[i])
    handles = [Patch(facecolor="#cfe8cf", edgecolor="#2e7d32", label="valid: free of regression (Eq. 18)")]
    if segs:
        lc = LineCollection(segs, cmap="viridis", linewidths=0.8, alpha=0.9, zorder=2)
        lc.set_array(np.asarray(ts))
        lc.set_clim(0.0, 1.0)
        ax.add_collection(lc, autolim=False)
        cbar = fig.colorbar(lc, ax=ax, shrink=0.85, pad=0.02)
        cbar.set_label("t of the limiting line  u a(t) + v b(t) = 1")
    if structure is not None:
        squares = [structure.cells[k] + np.array([[0, 0], [1, 0], [1, 1], [0, 1]]) for k in range(len(structure.cells))]
        ax.add_collection(PolyCollection(squares, facecolors="#ffffff80", edgecolors="#555555", linewidths=0.8, zorder=3), autolim=False)
        uv = structure.curves_uv
        kinds = np.asarray(structure.curve_kinds)
        for kind in ("fold", "seam", "junction"):
            sel = kinds == kind
            if sel.any():
                ax.scatter(uv[sel, 0], uv[sel, 1], s=14, color=KIND_COLORS[kind], zorder=4, label=f"lattice curve: {kind}")
        bad = ~domain.contains(uv.astype(float))
        if bad.any():
            ax.scatter(uv[bad, 0], uv[bad, 1], s=40, marker="x", color="black", linewidths=1.2, zorder=5, label="past regression")
        handles.append(Patch(facecolor="#ffffff", edgecolor="#555555", label=f"cells ({len(structure.cells)})"))
    handles += [h for h in ax.get_legend_handles_labels()[0]]
    handles.append(Line2D([], [], color="#2ca02c", lw=0.8, label="limiting lines (coloured by t)"))
    ax.plot([0], [0], marker="o", ms=9, mfc="none", mec="black", mew=1.0, zorder=6)
    ax.annotate("curve 1", (0, 0), xytext=(6, -12), textcoords="offset points", fontsize=7)
    ax.axhline(0, color="#999999", lw=0.5, zorder=0)
    ax.axvline(0, color="#999999", lw=0.5, zorder=0)
    ax.set_xlim(-box, box)
    ax.set_ylim(-box, box)
    ax.set_aspect("equal")
    ax.set_xlabel(r"u  (× $w_L$)")
    ax.set_ylabel(r"v  (× $w_R$)")
    ax.set_title("Regression domain of the lattice (Eq. 18)")
    ax.legend(handles=handles, fontsize=7, loc="upper left", framealpha=0.9)
    return fig


# -- width laws ---------------------------------------------------------------------------------


def plot_width_proportion(lattice: Lattice) -> Figure:
    """Widths w_L(t), w_R(t) and the section proportion w_R/w_L along the crease.

    Two panels sharing t: the widths in model units (Eqs. 12–13: ``ln w_R`` grows by
    ``∫ τ cot α ds``, ``ln w_L`` shrinks by as much) and the proportions ``w_R/w_L`` and
    ``w_R(t)/w_R(0)``. t = 0 (the feet of a vault) and t = ½ (its apex) are marked.

    Parameters
    ----------
    lattice : Lattice

    Returns
    -------
    Figure
    """
    t = lattice.t
    wl, wr = lattice.width_left, lattice.width_right
    ratio = wr / wl
    change = wr / wr[0]
    m = int(np.argmin(np.abs(t - 0.5)))

    fig = new_figure(figsize=(6.4, 5.2))
    top, bottom = fig.subplots(2, 1, sharex=True)
    top.plot(t, wl, color="#ff7f0e", lw=1.6, label=r"$w_L(t)$")
    top.plot(t, wr, color="#9467bd", lw=1.6, label=r"$w_R(t)$")
    top.set_ylabel(f"width ({UNITS})")
    top.legend(fontsize=8, loc="best")
    top.set_title("Section widths and proportion along the crease")

    bottom.plot(t, ratio, color="black", lw=1.6, label=r"$w_R / w_L$")
    bottom.plot(t, change, color="#8c564b", lw=1.2, ls="--", label=r"$w_R(t) / w_R(0)$")
    bottom.set_ylabel("proportion")
    bottom.set_xlabel("t  (curve 1's normalised arc length)")
    for ax in (top, bottom):
        for x, _name in ((t[0], "t = 0"), (t[m], "t = ½")):
            ax.axvline(x, color="#999999", lw=0.8, ls=":", zorder=0)
        ax.grid(True, lw=0.3, alpha=0.5)
    for x, y, other, text in ((t[0], ratio[0], ratio[m], f"{ratio[0]:.4g} at t = 0"), (t[m], ratio[m], ratio[0], f"{ratio[m]:.4g} at t = ½")):
        above = y >= other
        bottom.plot([x], [y], "o", color="black", ms=4)
        bottom.annotate(text, (x, y), xytext=(6, 7 if above else -7), textcoords="offset points", fontsize=8, va="bottom" if above else "top")
    bottom.margins(y=0.18)
    bottom.legend(fontsize=8, loc="best")
    bottom.set_xlim(-0.02, 1.02)
    return fig


# -- sections (the pantograph) --------------------------------------------------------------------


def section_coordinates(lattice: Lattice, uv: np.ndarray, index: int) -> np.ndarray:
    """Lattice curves uv (M, 2) at sample ``index`` projected along curve 1's tangent.

    Returns the coordinates (M, 2) of ``x(t; u, v) − x₁(t)`` on curve 1's N(t) and B(t)
    there: the section of the structure normal to the common tangent.
    """
    pts = lattice.points(np.asarray(uv, float))[:, index]
    curve = lattice.crease.curve
    d = pts - curve.points[index]
    return np.stack([d @ curve.normal[index], d @ curve.binormal[index]], axis=-1)


def plot_sections(
    obj: Vault | Structure | State,
    t_values: Sequence[float] = (0.0, 0.5),
    *,
    fold_angles: Sequence[float] | None = None,
) -> Figure:
    """Sections of a structure normal to curve 1's tangent, at several fold angles (the pantograph).

    All lattice curves share curve 1's frame at equal t (Eq. 11), so projected along the
    common tangent T(t) they form a lattice of parallelograms with fixed sides
    w_L(t), w_R(t): rigid folding shears it like a pantograph, flat at 2α = 0.

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
    from matplotlib.lines import Line2D

    from ..vault._assembly import Vault

    structure, lattice, own = structure_of(obj)
    t_arr = np.atleast_1d(np.asarray(t_values, float))
    if t_arr.ndim != 1 or t_arr.size == 0 or not np.all(np.isfinite(t_arr)) or np.any((t_arr < 0) | (t_arr > 1)):
        raise InputError(f"t_values must be a non-empty list of numbers in [0, 1], got {t_values!r}")
    angles = sorted(set(np.round([30.0, 60.0, 90.0, own], 9))) if fold_angles is None else list(np.atleast_1d(np.asarray(fold_angles, float)))
    if len(angles) == 0:
        raise InputError("fold_angles must hold at least one angle")
    lattices = [lattice.refold(f) for f in angles]  # validates every angle
    uv = structure.curves_uv
    cells = structure.cell_curves
    kinds = np.asarray(structure.curve_kinds)
    from matplotlib.colors import to_rgba

    design = int(np.argmin(np.abs(np.asarray(angles) - own)))
    palette = iter(["#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02", "#a6761d"] * len(angles))
    colors = [to_rgba("black") if k == design else to_rgba(next(palette)) for k in range(len(angles))]

    fig = new_figure(figsize=(4.6 * len(t_arr) + 0.4, 4.8))
    axes = np.atleast_1d(fig.subplots(1, len(t_arr), squeeze=False)[0])
    n = len(lattice.t)
    for ax, tv in zip(axes, t_arr):
        i = int(np.argmin(np.abs(lattice.t - tv)))
        for k, (_f, lat) in enumerate(zip(angles, lattices)):
            xy = section_coordinates(lat, uv, i)
            polys = xy[cells]
            strong = k == design
            ax.add_collection(
                PolyCollection(
                    polys,
                    facecolors=(*colors[k][:3], 0.06 if strong else 0.0),
                    edgecolors=[colors[k]],
                    linewidths=1.5 if strong else 1.0,
                    linestyles="solid" if strong else (0, (4, 2)),
                    zorder=2 + strong,
                )
            )
            if strong:
                for kind in ("fold", "seam", "junction"):
                    sel = kinds == kind
                    if sel.any():
                        ax.scatter(xy[sel, 0], xy[sel, 1], s=12, color=KIND_COLORS[kind], zorder=5)
        ax.plot([0], [0], marker="o", ms=8, mfc="none", mec="black", mew=1.0, zorder=6)
        ax.autoscale_view()
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(True, lw=0.3, alpha=0.5)
        where = {0: " (feet)", (n - 1) // 2: " (apex)"}.get(i, "") if isinstance(obj, Vault) else ""
        ax.set_title(f"section at t = {lattice.t[i]:.3g}{where}", fontsize=10)
        ax.set_xlabel(f"along N(t) ({UNITS})")
    axes[0].set_ylabel(f"along B(t) ({UNITS})")
    handles = [Line2D([], [], color=c, lw=1.5 if k == design else 1.0, ls="-" if k == design else (0, (4, 2)), label=f"2α = {f:g}°" + (" (design)" if k == design else "")) for k, (f, c) in enumerate(zip(angles, colors))]
    handles += [Line2D([], [], ls="", marker="o", ms=4, color=KIND_COLORS[kd], label=kd) for kd in ("fold", "seam", "junction") if kd in set(kinds)]
    handles.append(Line2D([], [], ls="", marker="o", ms=8, mfc="none", mec="black", label="curve 1"))
    fig.legend(handles=handles, loc="outside right center", fontsize=8, frameon=False)
    fig.suptitle("Sections normal to the common tangent T(t): the pantograph", fontsize=11)
    return fig


# -- mechanism -------------------------------------------------------------------------------------


def plot_singular_values(mechanisms: Sequence[Mechanism], *, title: str = "Singular values of the constraint Jacobian") -> Figure:
    """The singular values of panel structures' constraint Jacobians, smallest first, one line per state.

    Each state's values are divided by its largest and drawn against their rank from the
    smallest (log–log), with its rank tolerance: those on or below it are the first-order
    motions (6 of them rigid), and the gap above them shows how clear the count is.

    Parameters
    ----------
    mechanisms : sequence of Mechanism
        From :func:`curvefold.analysis.analyse` or :func:`curvefold.analysis.analyse_fold`.
    title : str, keyword-only

    Returns
    -------
    Figure
    """
    if len(mechanisms) == 0:
        raise InputError("mechanisms must hold at least one analysed state")
    fig = new_figure(figsize=(6.4, 4.6))
    ax = fig.add_subplot()
    palette = ["#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02"]
    tiny = np.finfo(float).tiny
    for k, m in enumerate(mechanisms):
        s = m.singular_values[::-1] / m.singular_values[0]
        gap = f"gap {m.gap:.1e}".replace("inf", "∞")
        ax.loglog(np.arange(1, len(s) + 1), np.maximum(s, tiny), ".-", ms=3, lw=0.8, color=palette[k % len(palette)],
                  label=f"{m.label}: {m.dof} internal DOF ({m.nullity} null), {gap}")
        ax.axhline(m.tolerance / m.singular_values[0], color="#999999", lw=0.8, ls="--", zorder=0)
    ax.text(1.05, mechanisms[0].tolerance / mechanisms[0].singular_values[0], "rank tolerance", fontsize=8, color="#666666", va="bottom")
    ax.set_xlabel("rank from the smallest")
    ax.set_ylabel("σ / σ_max")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="major", lw=0.3, alpha=0.5)
    ax.legend(fontsize=7, loc="lower right")
    return fig


# -- output ----------------------------------------------------------------------------------------


def save_figure(fig: Figure, path_stem: str | os.PathLike, formats: Sequence[str] = ("png", "svg"), dpi: int = 150) -> list[Path]:
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
        raise InputError(f"formats must be a non-empty list of {', '.join(sorted(supported))}; got {list(formats)!r}")
    dpi = check_integer(dpi, "dpi", "[10, 2400]")
    stem = os.fspath(path_stem)
    written = []
    for fmt in formats:
        target = Path(f"{stem}.{fmt}")
        metadata = {"svg": {"Date": None}, "pdf": {"CreationDate": None}}.get(fmt)
        with rc_context({"svg.hashsalt": "curvefold", "svg.fonttype": "path"}), atomic_path(target) as tmp:
            fig.savefig(tmp, format=fmt, dpi=int(dpi), metadata=metadata)
        written.append(target)
    return written
