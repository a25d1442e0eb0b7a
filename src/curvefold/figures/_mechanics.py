"""Pictures of a structure under load: its deflected shape coloured by the displacement, and its
first free modes.

Drawn like every 3D view (:mod:`curvefold.figures._views`): the scene renderer's shaded
strips (:mod:`curvefold.figures._scene`), here each quad coloured by the mean size of its
corners' displacement before shading, and the creases in their colours. The displacement
of the model's nodes is laid on every sample of the structure's curves
(:meth:`curvefold.mechanics.StructureModel.interpolate`) and magnified by a stated factor,
so that a deflection of micrometres shows.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..geometry._structure import drawable
from ..geometry._topology import tube_strips
from ._plot_data import KIND_COLORS
from ._plots import new_figure
from ._scene import View, ground_polygon, render_strips
from ._views import _draw, _fit, _scale_bar

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from ..mechanics import Collapse, LoadResult

__all__ = ["plot_deflection", "plot_modes", "plot_collapse", "field_scene"]

#: The colour maps of the displacement and of the modes' amplitude.
DEFLECTION_MAP, MODE_MAP = "viridis", "plasma"


def field_scene(
    result: LoadResult,
    shape: np.ndarray,
    scale: float,
    *,
    cmap: str,
    view: View = View(),
    ground: bool = False,
    segments: int = 96,
    max_cells: int = 200,
):
    """A scene of the structure displaced by ``scale`` × ``shape`` (P, 3), each quad coloured by the
    size of ``shape``.

    Returns
    -------
    scene : Scene
    top : float
        The largest size of ``shape`` at the drawn points (the colour scale's top), in its unit.
    """
    from matplotlib import colormaps

    sm = result.structure
    state = sm.state
    moved = sm.interpolate(shape)
    size = np.linalg.norm(moved, axis=-1)
    both = np.stack([state.vertices + scale * moved, np.repeat(size[..., None], 3, axis=-1)])
    drawn, cells, kinds = drawable(state.structure, both, segments=segments, max_cells=max_cells)
    vertices, values = drawn[0], drawn[1][..., 0]
    strips = tube_strips(cells)
    a, b = values[strips[:, 0]], values[strips[:, 1]]  # (S, k)
    quad = 0.25 * (a[:, :-1] + a[:, 1:] + b[:, :-1] + b[:, 1:])
    top = float(np.nanmax(values, initial=0.0))
    rgb = colormaps[cmap](quad / top if top > 0 else quad)[..., :3]
    scene = render_strips(
        vertices, strips, kinds, view, colors=KIND_COLORS, strip_rgb=rgb, crease_width=0.7
    )
    if ground:
        flat = vertices.reshape(-1, 3)
        lo, hi = flat.min(axis=0), flat.max(axis=0)
        from dataclasses import replace

        scene = replace(
            scene, ground=ground_polygon(lo, hi, view, pad=0.08 * float(np.max(hi - lo)))
        )
    return scene, top


def _colorbar(fig, ax, cmap: str, top: float, label: str) -> None:
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize

    bar = fig.colorbar(ScalarMappable(Normalize(0.0, top), cmap), ax=ax, shrink=0.6, pad=0.02)
    bar.set_label(label, fontsize=8)
    bar.ax.tick_params(labelsize=7)


def length_unit(largest: float) -> tuple[float, str]:
    """The scale and unit a length of the size of ``largest`` (m) reads best in: µm below a
    millimetre, mm below a metre, else m.

    Examples
    --------
    >>> length_unit(9.9e-5), length_unit(1.98e-3), length_unit(2.5)
    ((1000000.0, 'µm'), (1000.0, 'mm'), (1.0, 'm'))
    """
    return (1e6, "µm") if largest < 1e-3 else (1e3, "mm") if largest < 1.0 else (1.0, "m")


def plot_deflection(
    result: LoadResult, *, magnification: float, view: View = View(), title: str | None = None
) -> Figure:
    """The deflected structure, its displacement magnified and coloured by its size (µm), over the
    ground if it stands on it.

    Parameters
    ----------
    result : LoadResult
    magnification : float, keyword-only
        How many times the displacement is drawn (stated in the title).
    view : View, keyword-only
    title : str, optional, keyword-only
        Default: what loads it and the magnification.
    """
    scene, top = field_scene(
        result,
        result.static.displacements,
        magnification,
        cmap=DEFLECTION_MAP,
        view=view,
        ground=result.supports.at == "feet",
    )
    fig = new_figure(figsize=(6.8, 5.0))
    ax = fig.add_subplot()
    _draw(ax, scene)
    _fit(ax, scene.box, below=0.1)
    _scale_bar(ax, scene.span, "m")  # the mechanics' model is in metres
    largest = result.static.max_displacement
    scale, unit = length_unit(max(top, largest))
    _colorbar(fig, ax, DEFLECTION_MAP, scale * top, f"displacement ({unit})")
    ax.set_title(
        title
        or f"Deflected shape, displacement × {magnification:g} (largest "
        f"{largest * scale:.3g} {unit})",
        fontsize=10,
    )
    return fig


def plot_modes(
    result: LoadResult, *, amplitude: float, count: int = 3, view: View = View()
) -> Figure:
    """The first free modes side by side, each at largest displacement ``amplitude`` (m), coloured
    by its amplitude.

    The first is the folding motion (when the structure folds); each title gives the
    frequency, λ over the first and the share of the energy in stretching.
    """
    modes = result.modes
    count = min(count, len(modes.eigenvalues))
    fig = new_figure(figsize=(3.4 * count, 3.4))
    for k in range(count):
        ax = fig.add_subplot(1, count, k + 1)
        scene, _ = field_scene(
            result, modes.shapes[k], amplitude, cmap=MODE_MAP, view=view, ground=False
        )
        _draw(ax, scene)
        _fit(ax, scene.box)
        ratio = modes.eigenvalues[k] / modes.eigenvalues[0]
        ax.set_title(
            f"mode {k + 1}: {modes.frequencies[k]:.3g} Hz, λ/λ₁ = "
            f"{ratio:.3g}\nstretching {modes.stretching[k]:.0%} of its energy",
            fontsize=8,
        )
    fig.suptitle(
        f"The first free modes (largest displacement {amplitude:g} m); the first is the "
        "folding motion",
        fontsize=10,
    )
    scale, unit = length_unit(amplitude)
    _colorbar(fig, fig.axes, MODE_MAP, scale * amplitude, f"displacement ({unit})")
    return fig


def plot_collapse(collapse: Collapse) -> Figure:
    """The load–displacement curve of a collapse path: the load factor on its combination against
    the control displacement (mm, drawn growing to the right), stable states filled, the
    collapse factor and the linear buckling factor marked."""
    path = collapse.path
    w = 1e3 * path.control_displacement
    w = w * (-1.0 if w[np.argmax(np.abs(w))] < 0 else 1.0)
    node, axis = divmod(path.control, 3)
    fig = new_figure(figsize=(6.4, 4.4))
    ax = fig.add_subplot()
    ax.plot(w, path.factors, "-", color="0.35", lw=1.2, zorder=1)
    stable = np.asarray(path.stable, bool)
    ax.plot(w[stable], path.factors[stable], "o", ms=3.5, color="C0", label="stable state")
    ax.plot(
        w[~stable], path.factors[~stable], "o", ms=3.5, mfc="white", color="C3", label="unstable"
    )
    ax.axhline(collapse.linear_factor, color="C2", ls="--", lw=1.0)
    ax.annotate(
        f"linear buckling factor {collapse.linear_factor:.4g}",
        (0.02, collapse.linear_factor),
        xycoords=("axes fraction", "data"),
        xytext=(0, 3),
        textcoords="offset points",
        fontsize=8,
        color="C2",
    )
    k = collapse.at_collapse
    ax.plot([w[k]], [path.factors[k]], "*", ms=11, color="C3", zorder=3)
    ax.annotate(
        f"collapse {collapse.factor:.4g} ({collapse.knock_down:.3g} × linear)",
        (w[k], path.factors[k]),
        xytext=(-8, 12),
        textcoords="offset points",
        fontsize=8,
        color="C3",
        ha="right",
    )
    ax.set_xlabel(f"displacement of node {node} along {'xyz'[axis]} (mm, magnitude)", fontsize=9)
    ax.set_ylabel(f"load factor on {collapse.combination}", fontsize=9)
    ax.set_ylim(0, 1.12 * max(collapse.linear_factor, float(path.factors.max())))
    ax.set_xlim(left=0)
    ax.tick_params(labelsize=8)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    ratio = collapse.imperfection / collapse.span if collapse.span else 0.0
    shown = f"span / {1 / ratio:.0f}" if ratio else "none"
    import textwrap

    reason = "\n".join(textwrap.wrap(collapse.reason, 90))
    ax.set_title(
        f"Load path to collapse, imperfection {1e3 * collapse.imperfection:.3g} mm ({shown})\n"
        f"{reason}",
        fontsize=9,
    )
    return fig
