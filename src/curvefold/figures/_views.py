"""3D views of structures, vaults and single folds, drawn from scenes into matplotlib figures
(optional).

Each view draws the scenes of :mod:`curvefold.figures._scene` (a fixed orthographic view,
shaded strips and creases sorted far to near; folds red, seams blue) as one collection
each, with a scale bar in model units. Figures are built as in :mod:`curvefold.figures._plots`
(without ``pyplot``) and written with :func:`~curvefold.figures.save_figure`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np

from ..geometry._single_fold import default_widths
from ..geometry._topology import sample_index, thin_cells
from ..kernel._errors import InputError
from ._plot_data import KIND_COLORS, UNITS
from ._plots import legend_handles, mathtext, new_figure
from ._scene import (
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
    from matplotlib.figure import Figure, SubFigure

    from ..geometry._crease import Crease
    from ..geometry._structure import Structure
    from ..vault._assembly import Vault

__all__ = [
    "View",
    "crease_legend",
    "scale_length",
    "scale_label",
    "vault_title",
    "MotionStrip",
    "motion_strip",
    "structure_title",
    "plot_vault",
    "plot_motion_strip",
    "plot_structure",
    "plot_crease",
]


# -- drawing scenes
# ----------------------------------------------------------------------------------


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
        ax.add_patch(
            Polygon(
                scene.ground,
                closed=True,
                facecolor=GROUND_COLOR,
                edgecolor=GROUND_EDGE,
                linewidth=0.6,
                zorder=0,
            )
        )
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


def _scale_bar(ax: Axes, span: float, unit: str | None = None) -> None:
    """A horizontal scale bar of a round length (about a fifth of ``span``) in the lower right of
    a view, in ``unit`` (default model units)."""
    from mpl_toolkits.axes_grid1.anchored_artists import AnchoredSizeBar

    length = scale_length(span)
    label = scale_label(length, unit)
    ax.add_artist(
        AnchoredSizeBar(
            ax.transData,
            length,
            label,
            "lower right",
            pad=0.3,
            frameon=False,
            size_vertical=0,
            fontproperties={"size": 7},
        )
    )


def scale_label(length: float, unit: str | None = None) -> str:
    """The text of a scale bar of ``length`` in ``unit`` (default model units).

    Examples
    --------
    >>> scale_label(0.5), scale_label(1.0)
    ('0.5 model units', '1 model unit')
    """
    return (
        f"{length:g} {unit}" if unit else f"{length:g} {UNITS}" if length != 1 else "1 model unit"
    )


def scale_length(span: float) -> float:
    """A round length (1, 2 or 5 × 10^k) near a fifth of ``span``: the scale bar's."""
    target = max(span / 5.0, 1e-12)
    k = np.floor(np.log10(target))
    for m in (1.0, 2.0, 5.0, 10.0):
        if m * 10**k >= target:
            return float(m * 10**k)
    return float(10 ** (k + 1))  # pragma: no cover


def vault_title(vault: Vault, *, angle: float | None = None, max_tubes: int = 200) -> str:
    """The title of a view of a vault (subscripts written ``p_{xy}``): its parameters, tubes
    drawn, 2α."""
    d = vault.design
    drawn = len(thin_cells(vault.structure.cell_curves, max_tubes))
    shown = "" if drawn == len(vault.structure.cells) else f", {drawn} drawn"
    angle_value = float(d.fold_angle if angle is None else angle)
    panels = f", {d.panels} panels per crease" if d.panels else ""
    return (
        f"Vault: a = {d.a:g}, p_{{xy}} = {d.p_xy:g}, {d.tubes} "
        f"tube{'s' if d.tubes != 1 else ''}{shown}{panels}, 2α = {angle_value:g}°"
    )


def structure_title(structure: Structure, fold_angle: float, *, max_cells: int = 400) -> str:
    """The title of a view of a tube or cellular block at 2α = ``fold_angle`` degrees."""
    k = len(structure.cells)
    drawn = len(thin_cells(structure.cell_curves, max_cells))
    what = "Tube" if k == 1 else f"Cellular block of {k} cells"
    shown = "" if drawn == k else f" ({drawn} drawn)"
    return f"{what}{shown}, 2α = {fold_angle:.4g}°"


@dataclass(frozen=True, eq=False)
class MotionStrip:
    """What the small multiples of a vault's folding show (:func:`motion_strip`).

    Attributes
    ----------
    scenes : tuple of Scene
        One per fold angle, at one scale (:attr:`box` holds them all).
    titles, notes : tuple of str
        Each panel's title and the line under it (the lift of the ends off the ground).
    title : str
        The whole picture's (subscripts written ``p_{xy}``).
    """

    scenes: tuple
    titles: tuple
    notes: tuple
    title: str

    @property
    def box(self) -> np.ndarray:
        """Screen points (2·A, 2) that every panel fits (one scale for all)."""
        return np.concatenate([scene.box for scene in self.scenes])

    @property
    def columns(self) -> int:
        """Panels per row: four in a square (readable on a phone as on a desktop), else one row."""
        return 2 if len(self.scenes) == 4 else len(self.scenes)


def motion_strip(
    vault: Vault,
    angles: Sequence[float] = (0.0, 30.0, 60.0, 90.0),
    *,
    anchor: Literal["start", "middle"] = "start",
    view: View = View(),
    segments: int = 64,
    max_tubes: int = 100,
) -> MotionStrip:
    """What :func:`plot_motion_strip` shows (same parameters and errors)."""
    angles_arr = np.atleast_1d(np.asarray(angles, float))
    if angles_arr.ndim != 1 or angles_arr.size == 0:
        raise InputError(
            f"angles must be a non-empty list of fold angles in degrees, got {angles!r}"
        )
    motion = vault.motion(angles_arr, anchor=anchor)  # (A, M, n, 3); validates the angles
    lift = vault.lift_off(angles_arr, anchor=anchor)
    scenes = motion_scenes(
        vault.structure,
        motion,
        colors=KIND_COLORS,
        view=view,
        segments=segments,
        max_cells=max_tubes,
        crease_width=0.45,
    )
    d = vault.design
    titles = tuple(
        f"2α = {f:g}°" + (" (design)" if abs(f - d.fold_angle) < 1e-9 else "")
        for f in angles_arr.tolist()
    )
    notes = tuple(f"ends off the ground: {lf.max():.3f} {UNITS}" for lf in lift)
    return MotionStrip(
        scenes,
        titles,
        notes,
        f"Rigid folding of the vault (a = {d.a:g}, "
        f"p_{{xy}} = {d.p_xy:g}, {d.tubes} tubes; {anchor} held fixed)",
    )


def crease_legend(kinds: Sequence[str] | np.ndarray, lattice: Any = None) -> list[tuple[str, dict]]:
    """(label, style) legend entries of a view's crease kinds and strips (see
    :meth:`curvefold.figures._canvas.Frame.legend`)."""
    names = {"fold": "fold (creases 1, 3)", "seam": "seam (curves 2, 4)", "junction": "junction"}
    drawn = set(kinds)
    entries = [
        (names[k], {"line": KIND_COLORS[k], "width": 1.5})
        for k in ("fold", "seam", "junction")
        if k in drawn
    ]
    rigid = lattice is not None and lattice.rigid
    return entries + [
        (
            "rigid planar panels" if rigid else "developable strips",
            {"patch": tuple(STRIP_RGB.tolist()), "edge": "#999999"},
        )
    ]


def _legend_creases(
    ax: Axes, kinds: Sequence[str] | np.ndarray, lattice: Any = None, **kwargs: Any
) -> None:
    ax.legend(
        handles=legend_handles(crease_legend(kinds, lattice)), fontsize=7, frameon=False, **kwargs
    )


# -- 3D views of vaults ----------------------------------------------------------------------------


def plot_vault(
    vault: Vault,
    *,
    angle: float | None = None,
    ax: Axes | None = None,
    view: View = View(),
    anchor: Literal["start", "middle"] = "start",
    segments: int = 96,
    max_tubes: int = 200,
) -> Figure | SubFigure:
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
        The new figure, or the one ``ax`` is in (a SubFigure if it is in one).
    """
    scene = vault_scene(
        vault,
        colors=KIND_COLORS,
        angle=angle,
        view=view,
        anchor=anchor,
        segments=segments,
        max_tubes=max_tubes,
    )
    fig: Figure | SubFigure
    if ax is None:
        fig = new_figure(figsize=(7.0, 5.2))
        ax = fig.add_subplot()
    else:
        fig = ax.figure
    _draw(ax, scene)
    _fit(ax, scene.box, below=0.06)
    _scale_bar(ax, scene.span)
    ax.set_title(mathtext(vault_title(vault, angle=angle, max_tubes=max_tubes)), fontsize=10)
    _legend_creases(
        ax, scene.roles, vault.lattice, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=3
    )
    return fig


def plot_motion_strip(
    vault: Vault,
    angles: Sequence[float] = (0.0, 30.0, 60.0, 90.0),
    *,
    anchor: Literal["start", "middle"] = "start",
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
    strip = motion_strip(
        vault, angles, anchor=anchor, view=view, segments=segments, max_tubes=max_tubes
    )
    count, columns = len(strip.scenes), strip.columns
    rows = -(-count // columns)
    fig = new_figure(figsize=(3.4 * columns + 0.3, 3.2 * rows + 0.4))
    grid = fig.subplots(rows, columns, squeeze=False).ravel()
    for ax in grid[count:]:
        ax.set_axis_off()
    axes = grid[:count]
    for ax, scene, title, note in zip(axes, strip.scenes, strip.titles, strip.notes):
        _draw(ax, scene)
        ax.set_title(title, fontsize=10)
        ax.text(
            0.5,
            -0.02,
            note,
            transform=ax.transAxes,
            ha="center",
            va="top",
            fontsize=7,
            color="#555555",
        )
    for ax in axes:
        _fit(ax, strip.box)  # one scale for all
    _scale_bar(axes[-1], strip.scenes[0].span)
    fig.suptitle(mathtext(strip.title), fontsize=11)
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
    scene = state_scene(
        state, colors=KIND_COLORS, view=view, segments=segments, max_cells=max_cells
    )
    fig = new_figure(figsize=(6.4, 5.2))
    ax = fig.add_subplot()
    _draw(ax, scene)
    _fit(ax, scene.box, below=0.1)
    _scale_bar(ax, scene.span)
    ax.set_title(structure_title(structure, state.fold_angle, max_cells=max_cells), fontsize=10)
    _legend_creases(
        ax, scene.roles, structure.lattice, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=4
    )
    return fig


def plot_crease(
    crease: Crease,
    *,
    width: float | tuple[float, float] | None = None,
    view: View = View(),
    segments: int = 160,
) -> Figure:
    """A single curved fold: the crease with the developable surfaces on both sides, and its
    functions.

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
    if width is None:
        widths = default_widths(crease)
    else:
        w_left, w_right = (float(w) for w in np.broadcast_to(np.asarray(width, float), (2,)))
        widths = (w_left, w_right)
    # (2 sides, 2, n, 3); raises past regression
    sheets = crease.surface("L+R+", width=widths, rulings=2)
    idx = sample_index(len(s), segments + 1)
    # crease, left edge, right edge
    curves = np.stack([sheets[0, 0], sheets[0, 1], sheets[1, 1]])[:, idx]
    kinds = ("fold", "edge", "edge")

    fig = new_figure(figsize=(10.0, 4.8))
    mosaic = fig.subplot_mosaic([["view", "kt"], ["view", "angles"]], width_ratios=[1.35, 1.0])
    ax = mosaic["view"]
    scene = render_strips(
        curves, np.array([[0, 1], [0, 2]]), kinds, view, colors=KIND_COLORS, crease_width=1.4
    )
    _draw(ax, scene)
    _fit(ax, scene.box, below=0.1)
    _scale_bar(ax, scene.span)
    ax.set_title(
        f"Curved fold: surfaces {widths[0]:.3g} | {widths[1]:.3g} {UNITS} wide", fontsize=10
    )
    # An RGB array is a colour to matplotlib, not to its stubs
    surfaces = Patch(
        facecolor=STRIP_RGB,  # type: ignore[arg-type]
        edgecolor="#999999",
        label="developable surfaces",
    )
    ax.legend(
        handles=[
            Line2D([], [], color=KIND_COLORS["fold"], lw=1.5, label="crease"),
            Line2D([], [], color=KIND_COLORS["edge"], lw=1.5, label="surface edges"),
            surfaces,
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
