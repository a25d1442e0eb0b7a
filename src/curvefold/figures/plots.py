"""Figures of lattices, sections, vaults and their folding motion (matplotlib, optional).

Every function returns a :class:`matplotlib.figure.Figure` built directly, without
``pyplot`` and its global state, so figures can be made in threads, tests and servers
alike; :func:`save_figure` writes them atomically. matplotlib is imported only when a
function is called (``pip install curvefold[plot]``).

3D views draw the scenes of :mod:`curvefold.figures.scene` (a fixed orthographic view,
shaded strips and creases sorted far to near; folds red, seams blue) as one collection
each. Lengths are in model units (the unit of the design's radius).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..geometry.topology import sample_index, thin_cells
from ..io.atomic import atomic_path
from ..io.tables import COLOURS
from ..kernel.errors import InputError
from .scene import (
    GROUND_COLOR,
    GROUND_EDGE,
    STRIP_RGB,
    Scene,
    View,
    motion_scenes,
    render_strips,
    state_scene,
    vault_scene,
)

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from PIL import Image

    from ..analysis.mechanism import Mechanism
    from ..geometry.crease import Crease
    from ..geometry.lattice import Lattice
    from ..geometry.structure import State, Structure
    from ..vault.assembly import Vault

__all__ = [
    "View",
    "KIND_COLORS",
    "plot_regression_domain",
    "plot_width_proportion",
    "plot_sections",
    "plot_motion_strip",
    "plot_vault",
    "plot_structure",
    "plot_crease",
    "write_motion_gif",
    "plot_singular_values",
    "save_figure",
]

#: Line colours of the crease kinds (from :data:`curvefold.io.tables.COLOURS`).
KIND_COLORS = {kind: COLOURS[kind] for kind in ("fold", "seam", "junction", "edge")}
UNITS = "model units"


def _figure(**kwargs: Any) -> Figure:
    """A new Figure with constrained layout, never registered with pyplot."""
    try:
        from matplotlib.figure import Figure
    except ImportError as err:  # pragma: no cover - exercised only without matplotlib
        raise ImportError("curvefold's plots need matplotlib: pip install 'curvefold[plot]'") from err
    kwargs.setdefault("layout", "constrained")
    return Figure(**kwargs)


# -- drawing scenes ----------------------------------------------------------------------------------


def _collection(scene: Scene):
    """A matplotlib PolyCollection of a scene's paths, in painter's order."""
    from matplotlib.collections import PolyCollection

    return PolyCollection(
        scene.paths,
        closed=False,
        facecolors=scene.fill,
        edgecolors=scene.stroke,
        linewidths=scene.widths,
        joinstyle="round",
        capstyle="round",
        zorder=2.0,
    )


def _draw(ax: Axes, scene: Scene) -> None:
    """Draw a scene, its ground first, into ``ax``."""
    from matplotlib.patches import Polygon

    if scene.ground is not None:
        ax.add_patch(Polygon(scene.ground, closed=True, facecolor=GROUND_COLOR, edgecolor=GROUND_EDGE, linewidth=0.6, zorder=0))
    ax.add_collection(_collection(scene), autolim=False)


def _fit(ax: Axes, points: np.ndarray, *, margin: float = 0.04, below: float = 0.0) -> None:
    """Equal-aspect limits around screen points (P, 2).

    ``below`` adds that fraction of the height under the drawing (room for a scale bar).
    """
    lo, hi = points.min(axis=0), points.max(axis=0)
    c = 0.5 * (lo + hi)
    half = np.maximum(0.5 * (hi - lo) * (1 + 2 * margin), 1e-9)
    ax.set_xlim(c[0] - half[0], c[0] + half[0])
    ax.set_ylim(c[1] - half[1] * (1 + 2 * below), c[1] + half[1])
    ax.set_aspect("equal", adjustable="box")
    ax.set_axis_off()


def _scale_bar(ax: Axes, span: float) -> None:
    """A horizontal scale bar of a round length (about a fifth of ``span``) in the lower right of a view."""
    from mpl_toolkits.axes_grid1.anchored_artists import AnchoredSizeBar

    length = _nice_length(span)
    label = f"{length:g} {UNITS}" if length != 1 else "1 model unit"
    ax.add_artist(AnchoredSizeBar(ax.transData, length, label, "lower right", pad=0.3, frameon=False, size_vertical=0, fontproperties={"size": 7}))


def _nice_length(span: float) -> float:
    """A round length (1, 2 or 5 × 10^k) near a fifth of ``span``."""
    target = max(span / 5.0, 1e-12)
    k = np.floor(np.log10(target))
    for m in (1.0, 2.0, 5.0, 10.0):
        if m * 10**k >= target:
            return float(m * 10**k)
    return float(10 ** (k + 1))  # pragma: no cover


def _legend_creases(ax: Axes, kinds: Sequence[str], lattice: Any = None, **kwargs: Any) -> None:
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    names = {"fold": "fold (creases 1, 3)", "seam": "seam (curves 2, 4)", "junction": "junction"}
    handles = [Line2D([], [], color=KIND_COLORS[k], lw=1.5, label=names[k]) for k in ("fold", "seam", "junction") if k in set(kinds)]
    rigid = lattice is not None and lattice.rigid
    handles.append(Patch(facecolor=STRIP_RGB, edgecolor="#999999", label="rigid planar panels" if rigid else "developable strips"))
    ax.legend(handles=handles, fontsize=7, frameon=False, **kwargs)


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

    from ..geometry.structure import Structure

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

    fig = _figure(figsize=(6.4, 5.4))
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

    fig = _figure(figsize=(6.4, 5.2))
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


def _structure_of(obj: Any) -> tuple[Structure, Lattice, float]:
    """(structure, lattice, design fold angle in degrees) of a Vault, Structure or State."""
    from ..geometry.structure import State, Structure
    from ..vault.assembly import Vault

    if isinstance(obj, Vault):
        return obj.structure, obj.lattice, float(obj.design.fold_angle)
    if isinstance(obj, State):
        return obj.structure, obj.lattice, float(obj.fold_angle)
    if isinstance(obj, Structure):
        return obj, obj.lattice, float(obj.lattice.crease.fold_angle)
    raise InputError(f"expected a Vault, Structure or State, got {type(obj).__name__}")


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

    from ..vault.assembly import Vault

    structure, lattice, own = _structure_of(obj)
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

    fig = _figure(figsize=(4.6 * len(t_arr) + 0.4, 4.8))
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


# -- 3D views of vaults ----------------------------------------------------------------------------


def plot_vault(
    vault: Vault,
    *,
    angle: float | None = None,
    ax: Axes | None = None,
    view: View = View(),
    anchor: str = "start",
    segments: int = 96,
    max_tubes: int = 200,
) -> Figure:
    """One shaded 3D view of a vault: strips light grey shaded by normal, folds red, seams blue.

    Parameters
    ----------
    vault : Vault
    angle : float, optional, keyword-only
        Fold angle 2α in degrees; default the design angle (standing on the ground).
    ax : matplotlib Axes, optional, keyword-only
        Draw into this (2D) axes instead of a new figure; its figure is returned.
    view : View, keyword-only
        Orthographic view direction.
    anchor : {"start", "middle"}, keyword-only
        Which frame stays fixed when ``angle`` differs from the design angle.
    segments : int, keyword-only
        Segments drawn along each crease (the crease is subsampled; ends and apex kept).
    max_tubes : int, keyword-only
        Draw at most this many tubes, evenly spread along the stack.

    Returns
    -------
    Figure
    """
    scene = vault_scene(vault, colors=KIND_COLORS, angle=angle, view=view, anchor=anchor, segments=segments, max_tubes=max_tubes)
    if ax is None:
        fig = _figure(figsize=(7.0, 5.2))
        ax = fig.add_subplot()
    else:
        fig = ax.figure
    _draw(ax, scene)
    _fit(ax, scene.box, below=0.06)
    _scale_bar(ax, scene.span)
    d = vault.design
    drawn = len(thin_cells(vault.structure.cell_curves, max_tubes))
    shown = "" if drawn == len(vault.structure.cells) else f", {drawn} drawn"
    angle_value = float(d.fold_angle if angle is None else angle)
    panels = f", {d.panels} panels per crease" if d.panels else ""
    ax.set_title(
        f"Vault: a = {d.a:g}, $p_{{xy}}$ = {d.p_xy:g}, {d.tubes} tube{'s' if d.tubes != 1 else ''}{shown}{panels}, 2α = {angle_value:g}°",
        fontsize=10,
    )
    _legend_creases(ax, scene.roles, vault.lattice, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=3)
    return fig


def plot_motion_strip(
    vault: Vault,
    angles: Sequence[float] = (0.0, 30.0, 60.0, 90.0),
    *,
    anchor: str = "start",
    view: View = View(),
    segments: int = 64,
    max_tubes: int = 100,
) -> Figure:
    """Small multiples of a vault's rigid folding motion, all at one scale (the paper's Fig. 09).

    Each panel shows the vault at one fold angle 2α over the ground plane z = 0, with the
    largest lift of its end sections off the ground (zero at the design angle).

    Parameters
    ----------
    vault : Vault
    angles : sequence of float
        2α in degrees, each in [0°, 180°).
    anchor : {"start", "middle"}, keyword-only
        Hold curve 1's frame at its first foot or at the apex.
    view : View, keyword-only
    segments : int, keyword-only
        Segments drawn along each crease.
    max_tubes : int, keyword-only
        Draw at most this many tubes per panel.

    Returns
    -------
    Figure
    """
    angles_arr = np.atleast_1d(np.asarray(angles, float))
    if angles_arr.ndim != 1 or angles_arr.size == 0:
        raise InputError(f"angles must be a non-empty list of fold angles in degrees, got {angles!r}")
    motion = vault.motion(angles_arr, anchor=anchor)  # (A, M, n, 3); validates the angles
    lift = vault.lift_off(angles_arr, anchor=anchor)
    scenes = motion_scenes(vault.structure, motion, colors=KIND_COLORS, view=view, segments=segments, max_cells=max_tubes, crease_width=0.45)
    count = len(angles_arr)
    columns = 2 if count == 4 else count  # four panels in a square: readable on a phone as on a desktop
    rows = -(-count // columns)
    fig = _figure(figsize=(3.4 * columns + 0.3, 3.2 * rows + 0.4))
    grid = fig.subplots(rows, columns, squeeze=False).ravel()
    for ax in grid[count:]:
        ax.set_axis_off()
    axes = grid[:count]
    for ax, scene, f, lf in zip(axes, scenes, angles_arr, lift):
        _draw(ax, scene)
        design = abs(f - vault.design.fold_angle) < 1e-9
        ax.set_title(f"2α = {f:g}°" + (" (design)" if design else ""), fontsize=10)
        ax.text(0.5, -0.02, f"ends off the ground: {lf.max():.3f} {UNITS}", transform=ax.transAxes, ha="center", va="top", fontsize=7, color="#555555")
    for ax in axes:
        _fit(ax, np.concatenate([scene.box for scene in scenes]))  # one scale for all
    _scale_bar(axes[-1], scenes[0].span)
    d = vault.design
    fig.suptitle(f"Rigid folding of the vault (a = {d.a:g}, $p_{{xy}}$ = {d.p_xy:g}, {d.tubes} tubes; {anchor} held fixed)", fontsize=11)
    return fig


def plot_structure(
    structure: Structure,
    *,
    fold_angle: float | None = None,
    view: View = View(),
    segments: int = 96,
    max_cells: int = 400,
) -> Figure:
    """One shaded 3D view of a tube or cellular block: folds red, seams blue, junctions purple.

    Parameters
    ----------
    structure : Structure
    fold_angle : float, optional, keyword-only
        2α in degrees, in [0°, 180°); default the lattice's own angle.
    view : View, keyword-only
    segments : int, keyword-only
        Segments drawn along each crease.
    max_cells : int, keyword-only
        Draw at most this many cells, evenly spread.

    Returns
    -------
    Figure
    """
    state = structure.state(fold_angle)
    scene = state_scene(state, colors=KIND_COLORS, view=view, segments=segments, max_cells=max_cells)
    fig = _figure(figsize=(6.4, 5.2))
    ax = fig.add_subplot()
    _draw(ax, scene)
    _fit(ax, scene.box, below=0.1)
    _scale_bar(ax, scene.span)
    k = len(structure.cells)
    drawn = len(thin_cells(structure.cell_curves, max_cells))
    what = "Tube" if k == 1 else f"Cellular block of {k} cells"
    shown = "" if drawn == k else f" ({drawn} drawn)"
    ax.set_title(f"{what}{shown}, 2α = {state.fold_angle:.4g}°", fontsize=10)
    _legend_creases(ax, scene.roles, structure.lattice, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=4)
    return fig


def plot_crease(crease: Crease, *, width: float | tuple[float, float] | None = None, view: View = View(), segments: int = 160) -> Figure:
    """A single curved fold: the crease with the developable surfaces on both sides, and its functions.

    Left, a 3D view of the crease (red) and the two surfaces along the rulings ``+r_L``
    and ``+r_R`` (Eqs. 5–6). Right, κ(s) and τ(s), then the fold angle 2α(s) and the ruling
    angles β_L(s), β_R(s) in degrees.

    Parameters
    ----------
    crease : Crease
    width : float or (float, float), optional, keyword-only
        Surface widths on the left and right (distance from the crease's tangent line to
        the edge, model units); default 15 % of the crease's length, kept to 60 % of the
        regression limit on each side.
    view : View, keyword-only
    segments : int, keyword-only
        Segments drawn along the crease.

    Returns
    -------
    Figure
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    s = crease.s
    L = crease.curve.length
    if width is None:
        limits = [float(np.min(w)) for w in crease.regression_limits()]
        widths = tuple(min(0.15 * L, 0.6 * lim) for lim in limits)
    else:
        widths = tuple(float(w) for w in np.broadcast_to(np.asarray(width, float), (2,)))
    sheets = crease.surface("L+R+", width=widths, rulings=2)  # (2 sides, 2, n, 3); raises past regression
    idx = sample_index(len(s), segments + 1)
    curves = np.stack([sheets[0, 0], sheets[0, 1], sheets[1, 1]])[:, idx]  # crease, left edge, right edge
    kinds = ("fold", "edge", "edge")

    fig = _figure(figsize=(10.0, 4.8))
    mosaic = fig.subplot_mosaic([["view", "kt"], ["view", "angles"]], width_ratios=[1.35, 1.0])
    ax = mosaic["view"]
    scene = render_strips(curves, np.array([[0, 1], [0, 2]]), kinds, view, colors=KIND_COLORS, crease_width=1.4)
    _draw(ax, scene)
    _fit(ax, scene.box, below=0.1)
    _scale_bar(ax, scene.span)
    ax.set_title(f"Curved fold: surfaces {widths[0]:.3g} | {widths[1]:.3g} {UNITS} wide", fontsize=10)
    ax.legend(
        handles=[
            Line2D([], [], color=KIND_COLORS["fold"], lw=1.5, label="crease"),
            Line2D([], [], color=KIND_COLORS["edge"], lw=1.5, label="surface edges"),
            Patch(facecolor=STRIP_RGB, edgecolor="#999999", label="developable surfaces"),
        ],
        fontsize=7,
        frameon=False,
        loc="upper center",
        bbox_to_anchor=(0.5, 0.0),
        ncol=3,
    )
    kt = mosaic["kt"]
    kt.plot(s, crease.curve.kappa(s), color="#2ca02c", lw=1.5, label="κ(s)")
    kt.plot(s, crease.curve.tau(s), color="#9467bd", lw=1.5, label="τ(s)")
    kt.axhline(0, color="#999999", lw=0.5)
    kt.set_ylabel(f"1 / {UNITS}")
    kt.legend(fontsize=8)
    kt.grid(True, lw=0.3, alpha=0.5)
    kt.tick_params(labelbottom=False)
    ang = mosaic["angles"]
    ang.sharex(kt)
    ang.plot(s, np.degrees(2 * crease.alpha(s)), color="black", lw=1.5, label="2α(s)")
    ang.plot(s, np.degrees(crease.beta_left(s)), color="#ff7f0e", lw=1.2, label="β_L(s)")
    ang.plot(s, np.degrees(crease.beta_right(s)), color="#17becf", lw=1.2, ls="--", label="β_R(s)")
    ang.set_ylabel("angle (°)")
    ang.set_xlabel(f"arc length s ({UNITS})")
    ang.legend(fontsize=8)
    ang.grid(True, lw=0.3, alpha=0.5)
    return fig


def _raster(scene: Scene, box: np.ndarray, size: tuple[int, int], title: str, *, supersample: int = 2) -> Image.Image:
    """A scene drawn with Pillow: the screen points ``box`` (P, 2) fit below a title line.

    Drawn at ``supersample`` times the size and reduced, so edges are smoothed; line widths
    in points are taken at 100 dots per inch, as in the figures.
    """
    from PIL import Image, ImageDraw, ImageFont

    w, h = size[0] * supersample, size[1] * supersample
    image = Image.new("RGB", (w, h), "white")
    draw = ImageDraw.Draw(image)
    top, pad = 0.12 * h, 0.02 * w
    lo, hi = box.min(axis=0), box.max(axis=0)
    scale = min((w - 2 * pad) / max(hi[0] - lo[0], 1e-12), (h - top - pad) / max(hi[1] - lo[1], 1e-12))
    centre = np.array([w / 2, (h + top - pad) / 2])

    def pixels(points: np.ndarray) -> np.ndarray:
        return (points - 0.5 * (lo + hi)) * scale * np.array([1.0, -1.0]) + centre

    if scene.ground is not None:
        draw.polygon([tuple(p) for p in pixels(scene.ground).tolist()], fill=GROUND_COLOR, outline=GROUND_EDGE, width=supersample)
    sizes = np.array([len(p) for p in scene.paths])
    paths = np.split(pixels(np.concatenate(scene.paths)), np.cumsum(sizes)[:-1])
    fills, strokes = (np.round(255 * np.asarray(c)[:, :3]).astype(int).tolist() for c in (scene.fill, scene.stroke))
    lines = np.maximum(1, np.round(np.asarray(scene.widths) * 100 / 72 * supersample)).astype(int).tolist()
    for path, fill, stroke, line in zip(paths, fills, strokes, lines):
        xy = path.ravel().tolist()
        if len(path) > 2:
            draw.polygon(xy, fill=tuple(fill), outline=tuple(stroke), width=line)
        else:
            draw.line(xy, fill=tuple(stroke), width=line)
    import matplotlib

    font = ImageFont.truetype(str(Path(matplotlib.get_data_path()) / "fonts" / "ttf" / "DejaVuSans.ttf"), round(0.05 * h))
    draw.text((w / 2, 0.02 * h), title, fill="black", font=font, anchor="ma")
    return image.resize(size, Image.Resampling.BOX)


def write_motion_gif(
    obj: Vault | Structure,
    path: str | os.PathLike,
    *,
    angles: Sequence[float] | None = None,
    anchor: str = "start",
    view: View = View(),
    size: tuple[int, int] = (640, 480),
    frame_seconds: float = 0.12,
    segments: int = 48,
    max_cells: int = 60,
) -> Path:
    """An animated GIF of the rigid folding motion, flat to the design angle and back, written atomically.

    Parameters
    ----------
    obj : Vault or Structure
    path : str or path-like
        Target file (its folder must exist).
    angles : sequence of float, optional, keyword-only
        2α of the frames in degrees; default 16 steps from 0° to the design angle. The
        animation plays them forward, then backward, and loops.
    anchor : {"start", "middle"}, keyword-only
        Which frame of curve 1 stays fixed: at its start (t = 0) or at its middle sample.
    view : View, keyword-only
    size : (int, int), keyword-only
        Width and height in pixels.
    frame_seconds : float, keyword-only
        Duration of one frame.
    segments, max_cells : int, keyword-only
        Detail drawn: segments along each crease, and at most this many cells.

    Returns
    -------
    Path
    """
    from PIL import Image

    from ..geometry.lattice import check_anchor
    from ..vault.assembly import Vault

    structure, lattice, own = _structure_of(obj)
    check_anchor(anchor)
    w_px, h_px = (int(v) for v in size)
    if not (64 <= w_px <= 4096 and 64 <= h_px <= 4096):
        raise InputError(f"size must be (width, height) in pixels, each in [64, 4096], got {size!r}")
    if not np.isfinite(frame_seconds) or not 0.01 <= frame_seconds <= 10:
        raise InputError(f"frame_seconds must be in [0.01, 10], got {frame_seconds!r}")
    steps = np.linspace(0.0, own, 16) if angles is None else np.atleast_1d(np.asarray(angles, float))
    if steps.ndim != 1 or steps.size == 0:
        raise InputError(f"angles must be a non-empty list of fold angles in degrees, got {angles!r}")
    motion = lattice.fold_points(structure.curves_uv, steps, anchor=anchor)
    scenes = motion_scenes(structure, motion, colors=KIND_COLORS, view=view, segments=segments, max_cells=max_cells, crease_width=0.7, ground=isinstance(obj, Vault))
    joint = np.concatenate([scene.box for scene in scenes])  # one scale for all frames
    frames = [_raster(scene, joint, (w_px, h_px), f"2α = {f:5.1f}°") for f, scene in zip(steps, scenes)]
    sequence = frames + frames[-2:0:-1]  # forward, then back without repeating the ends
    palette = sequence[len(frames) - 1].quantize(colors=128)
    images = [im.quantize(palette=palette, dither=Image.Dither.NONE) for im in sequence]
    target = Path(path)
    with atomic_path(target) as tmp:
        images[0].save(tmp, format="GIF", save_all=True, append_images=images[1:], duration=int(round(1000 * frame_seconds)), loop=0)
    return target


# -- mechanism -------------------------------------------------------------------------------------


def plot_singular_values(mechanisms: Sequence[Mechanism], *, title: str = "Singular values of the constraint Jacobian") -> Figure:
    """The singular values of panel structures' constraint Jacobians, smallest first, one line per state.

    Each state's values are divided by its largest and drawn against their rank from the
    smallest (log–log), with its rank tolerance: those on or below it are the first-order
    motions (6 of them rigid), and the gap above them shows how clear the count is.

    Parameters
    ----------
    mechanisms : sequence of Mechanism
        From :func:`curvefold.analysis.mechanism.analyse` or ``analyse_fold``.
    title : str, keyword-only

    Returns
    -------
    Figure
    """
    if len(mechanisms) == 0:
        raise InputError("mechanisms must hold at least one analysed state")
    fig = _figure(figsize=(6.4, 4.6))
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
    if isinstance(dpi, bool) or not isinstance(dpi, (int, np.integer)) or not 10 <= dpi <= 2400:
        raise InputError(f"dpi must be an integer in [10, 2400], got {dpi!r}")
    stem = os.fspath(path_stem)
    written = []
    for fmt in formats:
        target = Path(f"{stem}.{fmt}")
        metadata = {"svg": {"Date": None}, "pdf": {"CreationDate": None}}.get(fmt)
        with rc_context({"svg.hashsalt": "curvefold", "svg.fonttype": "path"}), atomic_path(target) as tmp:
            fig.savefig(tmp, format=fmt, dpi=int(dpi), metadata=metadata)
        written.append(target)
    return written
