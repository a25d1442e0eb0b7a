"""Crease patterns for thick sheets: each crease inset by its bend, the seams' plies offset, glue
tabs and perforation sized to the sheet.

A smooth design (``panels = 0``) drawn for a sheet of thickness t folds to the design only if
its pattern gives up what the bends take (:mod:`curvefold.geometry._bend`). With the design's
faces the neutral surface of the sheet, sharply folded at a crease of fold angle θ(s) = 2α(s),
the real sheet bends round a neutral radius ρ = R + K t; its flat length from a point on one
face to a point on the other is shorter than the design's by twice the inset
``δ(s) = ρ (tan(θ/2) − θ/2)``. :func:`thick_sheet` moves every vertex of a developed sheet
that is not on a crease toward its nearest crease, perpendicular to it, by the inset there
(interpolated along the crease between its samples, each sample's θ the mean of its fold
edges' ``edges_foldAngle``); the crease is then the bend's centre line. A 1 mm aluminium
sheet (R = t, K = 0.325) at the paper's 2α = 90° gives up δ = 0.284 mm per side.

Seams: the two sheets of a tube are glued along seams 2 and 4 with tabs on one ply only, the
sheet of lower index (sheet A of each tube, :func:`~curvefold.io.layout_sheets`'s choice).
That ply laps over its partner: its seam line, where its tabs fold, moves out by t
(:data:`~curvefold.io._sheet_bend.SEAM_OFFSET` × t), so that its tabs wrap the partner's edge
and lie on its outer face; the partner is drawn to the design's seam. Where the plies meet at a
right angle the lapping ply's mid-surface then meets the partner's at the design's seam curve;
at a dihedral φ the lap would need t / sin φ, so the rule leaves t (1 / sin φ − 1) there. A
tube's seams meet at φ = 2α (measured: 90.0005° on the paper's vault at 2α = 90°, where the
rule is exact; 80.02° at 2α = 80°, where it leaves 1.5 % of t).

Glue tabs and perforation are sized to the sheet by :class:`~curvefold.io._sheet_bend.SheetBend`.
Every length on the page is the model's × the print scale: at 1 model unit = 1000 mm the
drawing is the sheet's own.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np

from ..geometry._bend import Bend
from ..geometry._mesh import edges_faces
from ..geometry._sheets import PatternSheet
from ..kernel._errors import InputError
from ._cutting import check_perforation, prepare_layout
from ._layout import Layout, LayoutRules
from ._output import PatternOutput
from ._sheet_bend import SEAM_OFFSET, SheetBend
from ._tables import mm_per_unit

__all__ = [
    "thick_sheet",
    "thick_sheets",
    "thick_layout",
    "crease_insets_of",
]


def crease_insets_of(sheet: PatternSheet, bend: Bend) -> tuple[np.ndarray, np.ndarray]:
    """The crease vertices of a sheet and the inset at each, (n,) int and (n,) model units: the
    inset at the mean fold angle of the vertex's fold edges."""
    mesh = sheet.mesh
    fold = np.flatnonzero(mesh.edges_kind == "fold")
    ends = mesh.edges_vertices[fold]
    V = len(mesh.vertices_coords)
    angle = np.abs(np.asarray(mesh.edges_foldAngle, float)[fold])
    total = np.bincount(ends.ravel(), np.repeat(angle, 2), minlength=V)
    count = np.bincount(ends.ravel(), minlength=V)
    verts = np.flatnonzero(count)
    return verts, bend.inset(total[verts] / count[verts])


def thick_sheet(
    sheet: PatternSheet, bend: Bend, lapping: frozenset[int] = frozenset()
) -> PatternSheet:
    """A developed sheet drawn for a thick sheet (module notes): every vertex off the creases
    moved toward its nearest crease segment (a crease's end segments run on past its ends),
    along that segment's normal, by the inset interpolated at its foot (held past the ends);
    then the seams whose ids are in ``lapping`` moved out by
    :data:`~curvefold.io._sheet_bend.SEAM_OFFSET` × t, each edge parallel to itself (mitred).

    Raises
    ------
    InputError
        When an inset reaches a vertex's distance from its crease (the sheet is too thick for
        the strip): the thickness, the strip width there and the inset.

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice, Structure
    >>> from curvefold.geometry._sheets import sheets
    >>> lat = Lattice.from_crease(
    ...     Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5), fold_angle=90),
    ...     0.1,
    ...     0.1,
    ... )
    >>> a = sheets(Structure.tube(lat))[0]
    >>> moved = (
    ...     thick_sheet(a, Bend(0.001, 0.001, 0.5)).mesh.vertices_coords - a.mesh.vertices_coords
    ... )
    >>> # mm: 1.5 mm (tan(θ/2) − θ/2) at the sampled mesh's θ = 90.5° (2α = 90°: 0.3219 mm)
    >>> round(float(np.linalg.norm(moved[:, :2], axis=1).max()) * 1e3, 4)
    0.3278
    """
    mesh = sheet.mesh
    xy = mesh.vertices_coords[:, :2]
    verts, inset = crease_insets_of(sheet, bend)
    out = xy.copy()
    if verts.size:
        delta = np.zeros(len(xy))
        delta[verts] = inset
        fold = mesh.edges_vertices[mesh.edges_kind == "fold"]
        a, b = xy[fold[:, 0]], xy[fold[:, 1]]  # (F, 2)
        off = _others(len(xy), verts)
        p = xy[off][:, None]  # (P, 1, 2)
        d = b - a
        # a crease's end segments run on along their tangents (past its ends, rulings fan out)
        end = np.bincount(fold.ravel(), minlength=len(xy)) == 1
        lo, hi = np.where(end[fold[:, 0]], -np.inf, 0.0), np.where(end[fold[:, 1]], np.inf, 1.0)
        u = np.clip(np.sum((p - a) * d, axis=2) / np.sum(d * d, axis=1), lo, hi)  # (P, F)
        foot = a + u[..., None] * d
        dist = np.linalg.norm(p - foot, axis=2)
        near = np.argmin(dist, axis=1)
        rows = np.arange(len(off))
        un = np.clip(u[rows, near], 0.0, 1.0)  # the inset held past the crease's ends
        e = fold[near]
        at = (1 - un) * delta[e[:, 0]] + un * delta[e[:, 1]]
        normal = (
            np.stack([-d[near, 1], d[near, 0]], axis=1) / np.linalg.norm(d[near], axis=1)[:, None]
        )
        side = np.sign(np.sum((xy[off] - foot[rows, near]) * normal, axis=1))
        width = dist[rows, near]
        if np.any(at >= width):
            k = int(np.argmax(at - width))
            raise InputError(
                f"thickness must leave the strips a width: {bend.thickness:g} insets a crease of "
                f"{sheet.label!r} by {at[k]:.3g}, at or past its width {width[k]:.3g} there; "
                "choose a thinner sheet or a wider strip",
                parameter="thickness",
            )
        out[off] -= (at * side)[:, None] * normal
    if lapping:
        out += _seam_offsets(sheet, out, lapping, SEAM_OFFSET * bend.thickness)
    coords = np.column_stack([out, mesh.vertices_coords[:, 2]])
    return replace(sheet, mesh=replace(mesh, vertices_coords=coords))


def _others(n: int, verts: np.ndarray) -> np.ndarray:
    """The indices in range(n) not in ``verts`` (without numpy.ma)."""
    mask = np.ones(n, bool)
    mask[verts] = False
    return np.flatnonzero(mask)


def _seam_offsets(
    sheet: PatternSheet, xy: np.ndarray, seams: frozenset[int], distance: float
) -> np.ndarray:
    """Per vertex, the move (V, 2) that carries the sheet's seam edges of ids ``seams`` out by
    ``distance``: each edge parallel to itself, neighbouring edges meeting at their mitre."""
    mesh = sheet.mesh.triangulated()  # (its own edges first)
    move = np.zeros_like(xy)
    pick = np.flatnonzero(np.isin(sheet.edges_seam, sorted(seams)))
    if not pick.size:
        return move
    ef = edges_faces(mesh.faces_vertices, mesh.edges_vertices)
    ev = mesh.edges_vertices[pick]
    # directed as their triangle runs them (counter-clockwise): the sheet on their left
    ev = np.where((ef[pick, 0] >= 0)[:, None], ev, ev[:, ::-1])
    d = xy[ev[:, 1]] - xy[ev[:, 0]]
    n = np.stack([d[:, 1], -d[:, 0]], axis=1) / np.linalg.norm(d, axis=1)[:, None]
    acc = np.zeros_like(xy)
    np.add.at(acc, ev[:, 0], n)
    np.add.at(acc, ev[:, 1], n)
    count = np.bincount(ev.ravel(), minlength=len(xy))
    hit = np.flatnonzero(count)
    # one edge: its normal; two: the mitre (n1 + n2) / (1 + n1·n2) = 2 acc / |acc|²
    square = np.maximum(np.sum(acc[hit] ** 2, axis=1), 0.25)
    move[hit] = distance * count[hit, None] * acc[hit] / square[:, None]
    return move


def thick_sheets(parts: tuple[PatternSheet, ...], bend: Bend) -> tuple[PatternSheet, ...]:
    """Every sheet drawn for the thick sheet (:func:`thick_sheet`), each seam's lapping ply the
    sheet of lower index that carries it (the ply the layout gives its tabs)."""
    first: dict[int, int] = {}
    for i, part in enumerate(parts):
        for sid in part.edges_seam[part.edges_seam >= 0].tolist():
            first.setdefault(sid, i)
    return tuple(
        thick_sheet(part, bend, frozenset(s for s, i0 in first.items() if i0 == i))
        for i, part in enumerate(parts)
    )


def thick_layout(
    parts: tuple[PatternSheet, ...],
    output: PatternOutput,
    fit: Callable[[tuple[PatternSheet, ...], PatternOutput, Callable], Layout],
) -> Layout:
    """The layout of a thick sheet's ``parts`` (``output.bend`` given): the sheets inset and
    lapped (:func:`thick_sheets`), laid out by ``fit`` with tabs sized to the sheet, perforated
    as sized to it, the legend's row saying so."""
    sb = output.bend
    if not isinstance(sb, SheetBend):
        raise InputError(
            f"bend must be a SheetBend (curvefold.io._sheet_bend.sheet_bend), got "
            f"{type(sb).__name__}",
            parameter="bend",
        )
    asked = check_perforation(output.perforation)
    f = mm_per_unit(output.units)

    def rules(scale: float) -> LayoutRules:
        return LayoutRules(tab_width=sb.tab_width(scale * f) / f)

    fitted = fit(thick_sheets(parts, sb.bend), output, rules)
    mm = fitted.scale  # page mm per model unit
    laid = replace(fitted, cutter=output.cutter, sheet_note=sb.note(mm))
    return prepare_layout(laid, perforation=sb.perforation(asked, mm), kerf=output.kerf)
