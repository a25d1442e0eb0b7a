"""What the plots show, as values: computed once with NumPy, drawn by either renderer.

Each plot of a lattice, its sections and its mechanism is a frozen value built here
(:func:`domain_plot`, :func:`width_plot`, :func:`section_plot`,
:func:`singular_values_plot`), with the colours and names the figures share; matplotlib
draws it in :mod:`curvefold.figures._plots`, the raster canvas in
:mod:`curvefold.figures._pictures`. Lengths are in model units (the unit of the design's
radius).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..io._tables import COLOURS
from ..kernel._arrays import FrozenArrays
from ..kernel._errors import InputError

if TYPE_CHECKING:  # pragma: no cover
    from ..analysis._mechanism import Mechanism
    from ..geometry._kinds import StructureLattice
    from ..geometry._structure import State, Structure
    from ..vault._assembly import Vault

__all__ = [
    "KIND_COLORS",
    "UNITS",
    "structure_of",
    "DomainPlot",
    "domain_plot",
    "WidthPlot",
    "width_plot",
    "section_coordinates",
    "SectionPlot",
    "section_plot",
    "SingularValuesPlot",
    "singular_values_plot",
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


# -- width laws ------------------------------------------------------------------------------------


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
