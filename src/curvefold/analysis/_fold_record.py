"""The ``record`` check of a FOLD file: what a curvefold file says of itself, against its geometry.

A curvefold file records its design (``curvefold:design``: the design, the fold angle of every
frame, the samples kept) and how it was made (``curvefold:metadata``: tubes, bonds, the mesh's
deviation and stretch). Each claim is a statement about the geometry the file holds, and is
measured:

* ``frame_unit``: a file that records its design is in model units (``"unit"``, radius 1);
* the frames: as many as the recorded fold angles, titled by them, and each folded by its
  angle (on a smooth design, the median measured dihedral angle of its ``fold`` edges; on rigid
  panels, the largest, the crease's own, the fold lines between panels folding less; within
  twice the recorded bend bound: each triangle beside a crease tilts from the sheet's tangent
  plane by at most the fold across its diagonal). A frame deleted, frames in reverse order
  or a frame replaced by another's coordinates under its own title fail;
* every ``seam`` edge has its partner (``curvefold:seam_partners``), a file whose metadata
  names bonds holds them (``curvefold:bonds``), and two edges that lie on one another in every
  folded frame are a seam or bond pair;
* the sheets: two connected pieces per tube (one tube per recorded cell), so a stray piece
  shows;
* ``curve_length`` = ``kappa0_s0`` × ``radius``, and the radius is the design's; every
  figure that restates the design (the design angle, the widths, a, p_xy, a tube's length,
  the units of the sheet files written beside the FOLD file) is the design's, ``tubes`` is
  the number of cells, and the design angle is a frame's;
* ``mesh_deviation``: a thinned mesh deviates from the computed samples by about the sagitta
  κℓ²/8 of its chords, measured from the turning of its crease polylines in the frame at the
  design angle; a recorded deviation under half of that is false;
* ``mesh_stretch``: the largest relative change of an edge's length at the design angle,
  measured in that frame (to the rounding of the written lengths).
"""

from __future__ import annotations

import math
import re

import numpy as np

from ..geometry._mesh import Mesh, edges_faces
from ..geometry._mesh import fold_angles as dihedral_angles
from ..io._fold import COORDINATE_RTOL
from ..io._fold_reading import FoldFile
from ..kernel._arrays import distinct
from ._fold_results import FileCheck

__all__ = ["record", "crease_angles", "chord_sagitta", "records_smooth_design", "sheet_count"]

#: A frame title as curvefold writes it.
_TITLE = re.compile(r"fold angle (-?[0-9.]+)°")


def chord_sagitta(mesh: Mesh) -> float:
    """The largest sagitta κℓ²/8 of a chord of the mesh's crease polylines (``fold`` and
    ``seam`` edges): κ from the turning angle at each vertex between its two crease edges.

    Examples
    --------
    >>> from curvefold.geometry import Mesh
    >>> t = np.linspace(0, np.pi / 2, 5)
    >>> arc = np.c_[np.cos(t), np.sin(t), 0 * t]
    >>> edges = np.c_[np.arange(4), np.arange(1, 5)]
    >>> mesh = Mesh(
    ...     vertices_coords=arc,
    ...     edges_vertices=edges,
    ...     edges_assignment=["M"] * 4,
    ...     edges_foldAngle=[0.0] * 4,
    ...     faces_vertices=np.zeros((0, 3), int),
    ...     edges_kind=["fold"] * 4,
    ...     faces_group=np.zeros(0, int),
    ... )
    >>> sagitta = 1 - np.cos(np.pi / 16)  # of a chord of the unit circle over π/8
    >>> bool(abs(chord_sagitta(mesh) / sagitta - 1) < 0.05)
    True
    """
    ev = mesh.edges_vertices[np.isin(mesh.edges_kind, ("fold", "seam"))]
    x = np.asarray(mesh.vertices_coords, float)
    if x.shape[1] == 2:
        x = np.c_[x, np.zeros(len(x))]
    ends, other = np.r_[ev[:, 0], ev[:, 1]], np.r_[ev[:, 1], ev[:, 0]]
    order = np.argsort(ends, kind="stable")
    ends, other = ends[order], other[order]
    degree = np.bincount(ends, minlength=len(x))
    v = np.flatnonzero(degree == 2)
    if not v.size:
        return 0.0
    first = np.searchsorted(ends, v)
    a, b = x[other[first]] - x[v], x[other[first + 1]] - x[v]
    la, lb = np.linalg.norm(a, axis=1), np.linalg.norm(b, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        turning = np.arccos(np.clip(-(a * b).sum(axis=1) / (la * lb), -1.0, 1.0))
        kappa = 2 * np.sin(turning) / (la + lb)
    sagitta = kappa * np.maximum(la, lb) ** 2 / 8
    sagitta = sagitta[np.isfinite(sagitta)]
    return float(sagitta.max()) if sagitta.size else 0.0


def sheet_count(mesh: Mesh) -> int:
    """The connected pieces of the mesh's faces (faces sharing a vertex are connected)."""
    faces = mesh.faces_vertices
    parent = np.arange(len(mesh.vertices_coords))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = int(parent[i])
        return i

    for row in faces.tolist():
        corners = [c for c in row if c >= 0]
        for c in corners[1:]:
            a, b = root(corners[0]), root(c)
            if a != b:
                parent[b] = a
    used = distinct(faces[faces >= 0])
    return len({root(int(i)) for i in used})


def _frames(doc: FoldFile, design: dict, meta: dict, smooth: bool) -> list[str]:
    recorded = design.get("fold_angles")
    if not isinstance(recorded, list):
        return []
    found = []
    titles = [t for t, _ in doc.folded]
    if len(titles) != len(recorded):
        found.append(
            f"{len(titles)} folded frames, the record {len(recorded)} fold angles "
            f"({', '.join(f'{a:g}°' for a in recorded)})"
        )
        return found
    slack = 2 * float(meta.get("mesh_bend_bound_deg", 0.5))
    for i, ((title, mesh), angle) in enumerate(zip(doc.folded, recorded)):
        named = _TITLE.fullmatch(title)
        if named is not None and abs(float(named.group(1)) - angle) > 1e-9:
            found.append(f"frame {i + 1} is titled {title!r}, the record says {angle:g}°")
        folds = np.flatnonzero(mesh.edges_kind == "fold")
        if not folds.size:
            continue
        sides = edges_faces(mesh.faces_vertices, mesh.edges_vertices[folds])
        measured = np.abs(
            dihedral_angles(
                mesh.vertices_coords,
                mesh.faces_vertices,
                mesh.edges_vertices[folds],
                faces_of_edges=sides,
            )
        )
        # the median of the finite ones, sorted (np.median and np.nanmedian import numpy.ma);
        # rigid panels fold their crease lines by 2α, the most, and their fold lines by less
        finite = np.sort(measured[np.isfinite(measured)])
        n = finite.size
        median = 0.5 * float(finite[(n - 1) // 2] + finite[n // 2]) if n else math.nan
        folded = median if smooth else float(finite[-1]) if n else math.nan
        if not abs(folded - angle) <= slack:
            found.append(
                f"frame {i + 1} ({title!r}) folds its creases by {folded:.4g}°, the record "
                f"{angle:g}° (±{slack:g}°)"
            )
    return found


def _design_frame(doc: FoldFile, design: dict, meta: dict) -> Mesh | None:
    """The folded frame at the design angle, if the file holds it."""
    recorded = design.get("fold_angles")
    target = meta.get("design_fold_angle_deg")
    if not isinstance(recorded, list) or len(recorded) != len(doc.folded):
        return None
    return next(
        (m for (_, m), a in zip(doc.folded, recorded) if target is not None and a == target), None
    )


def _mesh_claims(doc: FoldFile, design: dict, meta: dict, eps: float) -> list[str]:
    found: list[str] = []
    frame = _design_frame(doc, design, meta)
    pattern = doc.crease_pattern
    if frame is None or pattern is None:
        return found
    deviation, computed = meta.get("mesh_deviation"), meta.get("samples_computed")
    written = str(meta.get("mesh_samples_per_crease", ""))
    thinned = isinstance(computed, int) and written not in ("", str(computed))
    if thinned and isinstance(deviation, (int, float)):
        sagitta = max(chord_sagitta(frame), chord_sagitta(pattern))
        if deviation < sagitta / 2:
            found.append(
                f"mesh_deviation {deviation:.3g}, but the written chords' sagitta at the design "
                f"angle is {sagitta:.3g} (a thinned mesh deviates by about that)"
            )
    stretch = meta.get("mesh_stretch")
    if isinstance(stretch, (int, float)):
        flat = pattern.edge_lengths()
        with np.errstate(invalid="ignore", divide="ignore"):
            measured = float(np.nanmax(np.abs(frame.edge_lengths() / flat - 1)))
        # at least curvefold's own rounding of what it wrote (a copy written again with more
        # digits, as a moved one, still holds it)
        size = max(float(np.ptp(m.vertices_coords, axis=0).max()) for m in (pattern, frame))
        floor = max(eps, 0.5 * COORDINATE_RTOL * size)
        rounding = 4 * math.sqrt(3) * floor / float(flat.min()) + 1e-9 * measured
        if abs(measured - stretch) > rounding:
            found.append(f"mesh_stretch {stretch:.6g}, measured {measured:.6g} at the design angle")
    return found


#: Metadata keys that restate a design value (metadata key: the design's key in its sections).
_RESTATED = {
    "design_fold_angle_deg": "fold_angle",
    "curve_length": "length",
    "width_left": "width_left",
    "width_right": "width_right",
    "width": "width",
    "a": "a",
    "p_xy": "p_xy",
}


def _design_claims(record_: dict, design: dict, meta: dict) -> list[str]:
    """The metadata that restates the design against it; the tubes against the cells; the design
    angle among the frames' angles (the mesh claims are measured in its frame)."""
    found = []
    values = {
        k: v
        for part in design.values()
        if isinstance(part, dict)
        for k, v in part.items()
        if isinstance(v, (int, float)) and not isinstance(v, bool)
    }
    for key, name in _RESTATED.items():
        claimed = meta.get(key)
        if isinstance(claimed, (int, float)) and name in values:
            if not math.isclose(float(claimed), float(values[name]), rel_tol=1e-9, abs_tol=1e-12):
                found.append(f"{key} {claimed:g}, the design's {name} {values[name]:g}")
    units, output = meta.get("sheet_units"), design.get("output")
    if isinstance(units, str) and isinstance(output, dict) and output.get("units") != units:
        found.append(f"sheet_units {units!r}, the design's [output] units {output.get('units')!r}")
    tubes, cells = meta.get("tubes"), meta.get("cells")
    layers = int(values.get("layers", 1))  # a layered vault records its tubes per layer
    if isinstance(tubes, int) and isinstance(cells, str) and cells:
        if tubes * layers != len(cells.split(";")):
            found.append(
                f"tubes {tubes}"
                + (f" × {layers} layers" if layers > 1 else "")
                + f", the record's cells {len(cells.split(';'))}"
            )
    # a motion that passes its design angle holds it as a frame (a motion written to another
    # angle, as the designer's downloads at its slider's, may stop short of it)
    recorded, target = record_.get("fold_angles"), meta.get("design_fold_angle_deg")
    if (
        isinstance(recorded, list)
        and isinstance(target, (int, float))
        and target not in recorded
        and all(isinstance(a, (int, float)) for a in recorded)
        and min(recorded, default=target) < target < max(recorded, default=target)
    ):
        found.append(f"design_fold_angle_deg {target:g} is the angle of no frame")
    return found


def _close_pairs(points: np.ndarray, tol: float) -> np.ndarray:
    """The pairs (i < j) of ``points`` (N, 3) at most ``tol`` apart, shape (K, 2): a sweep along
    x (the main job loads neither SciPy nor numpy.ma for it).

    Examples
    --------
    >>> _close_pairs(np.array([[0.0, 0, 0], [1, 0, 0], [0, 1e-9, 0], [1, 2, 0]]), 1e-6).tolist()
    [[0, 2]]
    """
    order = np.argsort(points[:, 0], kind="stable")
    x = points[order, 0]
    ends = np.searchsorted(x, x + tol, side="right")
    counts = ends - np.arange(len(x)) - 1
    first = np.repeat(np.arange(len(x)), counts)
    starts = np.repeat(np.cumsum(counts) - counts, counts)
    second = first + 1 + np.arange(int(counts.sum())) - starts
    a, b = order[first], order[second]
    near = np.linalg.norm(points[a] - points[b], axis=1) <= tol
    return np.sort(np.stack([a[near], b[near]], axis=1), axis=1).reshape(-1, 2)


def _pieces(count: int, pairs: np.ndarray) -> np.ndarray:
    """The connected piece of each of ``count`` items joined by ``pairs`` (K, 2): the lowest item
    of its piece (labels spread along the pairs until they stop changing).

    Examples
    --------
    >>> _pieces(5, np.array([[3, 4], [1, 3]])).tolist()
    [0, 1, 2, 1, 1]
    """
    label = np.arange(count)
    while True:
        lowest = np.minimum(label[pairs[:, 0]], label[pairs[:, 1]])
        before = label.copy()
        np.minimum.at(label, pairs[:, 0], lowest)
        np.minimum.at(label, pairs[:, 1], lowest)
        label = label[label]  # follow each label to its own
        if np.array_equal(label, before):
            return label


def _unglued(doc: FoldFile) -> list[str]:
    """Crease edges (``fold``, ``seam``) that lie on one another in every folded frame (both
    ends within 1e-6 of the size) and that no chain of seam or bond pairs glues: a pair deleted
    from the tables. (The ends of neighbouring tubes may meet along boundary edges and rulings,
    unglued.)"""
    if not doc.folded or "curvefold:seam_partners" not in doc.keys:
        return []
    common: set[tuple[int, int]] | None = None
    for _, mesh in doc.folded:
        x, ev = mesh.vertices_coords, mesh.edges_vertices
        tol = 1e-6 * float(np.ptp(x, axis=0).max())
        middle = (x[ev[:, 0]] + x[ev[:, 1]]) / 2
        pairs = _close_pairs(middle, tol)
        a, b = ev[pairs[:, 0]], ev[pairs[:, 1]]
        ends = np.minimum(
            np.maximum(*[np.linalg.norm(x[a[:, k]] - x[b[:, k]], axis=1) for k in (0, 1)]),
            np.maximum(*[np.linalg.norm(x[a[:, k]] - x[b[:, 1 - k]], axis=1) for k in (0, 1)]),
        )
        found = {(int(p), int(q)) for p, q in pairs[ends <= tol].tolist()}
        common = found if common is None else common & found
        if not common:
            return []
    # glued, directly or along a chain (three tubes on one curve are bonded two by two)
    pairs = np.concatenate([doc.seam_partners, doc.bonds]).reshape(-1, 2).astype(np.int64)
    piece = _pieces(len(doc.folded[0][1].edges_vertices), pairs)
    kinds = np.asarray(doc.folded[0][1].edges_kind)
    crease = (kinds == "fold") | (kinds == "seam")  # what seams and bonds glue
    lonely = sorted(
        tuple(sorted(p))
        for p in common or ()
        if piece[p[0]] != piece[p[1]] and crease[p[0]] and crease[p[1]]
    )
    if not lonely:
        return []
    shown = ", ".join(f"{p}–{q}" for p, q in lonely[:3])
    more = f" (+{len(lonely) - 3} more)" if len(lonely) > 3 else ""
    return [
        f"edges {shown}{more} lie on one another in every folded frame and no seam or bond "
        "pair glues them"
    ]


def _structure_claims(doc: FoldFile, meta: dict, vault: dict) -> list[str]:
    found = []
    base = doc.crease_pattern if doc.crease_pattern is not None else doc.folded[0][1]
    kinds = base.edges_kind
    seams = np.flatnonzero(kinds == "seam")
    if seams.size and "curvefold:metadata" in doc.keys:
        paired = np.bincount(doc.seam_partners.ravel(), minlength=len(kinds))[seams]
        lonely = seams[paired != 1]
        if lonely.size:
            shown = ", ".join(str(int(e)) for e in lonely[:5])
            more = f" (+{len(lonely) - 5} more)" if len(lonely) > 5 else ""
            found.append(
                f"seam edges {shown}{more} have no partner in curvefold:seam_partners "
                f"({len(doc.seam_partners)} pairs for {seams.size} seam edges)"
            )
    found += _unglued(doc)
    if meta.get("bonds") not in (None, "none") and not len(doc.bonds):
        found.append(f"the metadata names bonds ({meta['bonds'][:60]}…), the file holds none")
    cells = meta.get("cells")  # one tube per cell: "(0, 0); (1, 1)"
    if isinstance(cells, str) and cells and len(base.faces_vertices):
        tubes, pieces = len(cells.split(";")), sheet_count(base)
        if pieces != 2 * tubes:
            found.append(f"{pieces} connected sheets, {tubes} tubes (cells) make {2 * tubes}")
    radius = meta.get("radius")
    if isinstance(radius, (int, float)):
        if isinstance(vault.get("radius"), (int, float)) and vault["radius"] != radius:
            found.append(f"radius {radius:g}, the design's {vault['radius']:g}")
        length, k0s0 = meta.get("curve_length"), meta.get("kappa0_s0")
        if isinstance(length, (int, float)) and isinstance(k0s0, (int, float)):
            if not math.isclose(length, k0s0 * radius, rel_tol=1e-9):
                found.append(
                    f"radius {radius:g}: curve_length {length:.10g} is not kappa0_s0 "
                    f"{k0s0:.10g} × radius"
                )
    return found


def record(doc: FoldFile, eps: float) -> FileCheck:
    """The claims of a curvefold file's record against its geometry (see the module notes).

    Parameters
    ----------
    doc : FoldFile
    eps : float
        Half the written coordinate unit (the rounding of a written coordinate).
    """
    meta = doc.metadata
    if "curvefold:metadata" not in doc.keys:
        return FileCheck(
            "record",
            "not run",
            reason="the file records no curvefold:metadata (another tool's file)",
        )
    record_ = doc.design if isinstance(doc.design, dict) else {}
    found_design = record_.get("design")
    design: dict = found_design if isinstance(found_design, dict) else {}
    kind = design.get("kind")
    found_section = design.get(kind) if isinstance(kind, str) else None
    section: dict = found_section if isinstance(found_section, dict) else {}
    smooth = _is_smooth(doc)
    found = []
    if record_ and doc.unit != "unit":
        found.append(
            f"frame_unit {doc.unit!r}: a file that records its design is in model units "
            "('unit', radius 1)"
        )
    found += _frames(doc, record_, meta, smooth)
    found += _structure_claims(doc, meta, section)
    found += _design_claims(record_, design, meta)
    found += _mesh_claims(doc, record_, meta, eps)
    if not found:
        return FileCheck("record", "pass")
    return FileCheck(
        "record",
        "fail",
        where="; ".join(found[:4]) + (f" (+{len(found) - 4} more)" if len(found) > 4 else ""),
    )


def _is_smooth(doc: FoldFile) -> bool:
    """Whether the design the file records is smooth (rigid panels fold their fold lines by
    their own angles, not 2α)."""
    record_ = doc.design if isinstance(doc.design, dict) else {}
    found = record_.get("design")
    design: dict = found if isinstance(found, dict) else {}
    return not any(isinstance(v, dict) and v.get("panels") for v in design.values())


def records_smooth_design(doc: FoldFile) -> bool:
    """Whether the file records a curvefold design of smooth curved sheets (no rigid panels):
    its sheets bend between the samples, so its frames are no states of rigid panels."""
    record_ = doc.design if isinstance(doc.design, dict) else {}
    return isinstance(record_.get("design"), dict) and _is_smooth(doc)


def crease_angles(doc: FoldFile, tolerance: float) -> FileCheck | None:
    """Every fold crease of every folded frame against the frame's recorded fold angle 2α: the
    certificate's ``fold_angles``, measured on the file (its dihedral angles, in degrees).

    None for rigid panels, whose fold lines fold by their own angles, not 2α: the check does not
    apply to them (the certificate's ``fold_angles`` does not either)."""
    recorded = doc.design.get("fold_angles") if isinstance(doc.design, dict) else None
    if not isinstance(recorded, list) or len(recorded) != len(doc.folded):
        return FileCheck(
            "crease_angles",
            "not run",
            unit="°",
            reason="the file records no fold angle per frame (curvefold:design)",
        )
    if not _is_smooth(doc):  # not a check of rigid panels, as in the certificate
        return None
    worst, at, failing = 0.0, "", ""
    for i, ((title, mesh), angle) in enumerate(zip(doc.folded, recorded)):
        folds = np.flatnonzero(mesh.edges_kind == "fold")
        if not folds.size:
            continue
        measured = np.abs(
            dihedral_angles(mesh.vertices_coords, mesh.faces_vertices, mesh.edges_vertices[folds])
        )
        off = np.abs(measured - float(angle))
        off = np.where(np.isfinite(off), off, np.inf)
        k = int(np.argmax(off))
        label = f"frame {i + 1} ({title!r}): edges {int(folds[k])}"
        if off[k] > worst:
            worst, at = float(off[k]), label
        if off[k] > tolerance and not failing:
            failing = f"{label}, {off[k]:.3g}° off {float(angle):g}°"
    status = "fail" if failing else "pass"
    return FileCheck("crease_angles", status, worst, tolerance, "°", failing or at)
