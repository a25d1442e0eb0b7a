"""The ``rebuild`` check of a FOLD file: every array against the design it records, built again."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..io._fold_reading import FoldFile
from ._fold_checks import judge, named_ids
from ._fold_matching import canonical_pairs, renumbered, rigid_residual, turned_over, unsplit
from ._fold_results import FileCheck

__all__ = ["rebuild"]


def rebuild(
    doc: FoldFile, reference: FoldFile, labels: list[str], size: float, tol: dict
) -> FileCheck:
    """Every array the rebuilt file holds against the file's (its frames named by ``labels``), up
    to the numbering of vertices, edges and faces, an edge split at a point of its line, a
    rigid motion of each frame and the sheet turned over
    (:mod:`curvefold.analysis._fold_matching`): what differs is named."""
    found = _compared(doc, reference, labels, size, tol)
    if found.status == "pass" or reference.crease_pattern is None:
        return found
    turned = _compared(doc, turned_over(reference), labels, size, tol)
    if turned.status != "pass":
        return found
    note = (
        "the sheet turned over (its faces wound the other way, M and V and the fold angles "
        "reversed, the crease pattern mirrored)"
    )
    return replace(turned, where="; ".join(w for w in (turned.where, note) if w))


def _compared(
    doc: FoldFile, reference: FoldFile, labels: list[str], size: float, tol: dict
) -> FileCheck:
    titles = [t for t, _ in doc.folded]
    mine = [
        (label, m)
        for label, m in zip(
            labels,
            ([doc.crease_pattern] if doc.crease_pattern is not None else [])
            + [m for _, m in doc.folded],
        )
    ]
    theirs = (
        [("crease pattern", reference.crease_pattern)]
        if reference.crease_pattern is not None
        else []
    ) + list(reference.folded)
    seams, bonds = doc.seam_partners, doc.bonds
    joined = np.zeros(0, np.int64)
    if len(mine) == len(theirs) and len(mine[0][1].vertices_coords) > len(
        theirs[0][1].vertices_coords
    ):  # an edge split at a point of its line is the same geometry
        meshes, (seams, bonds), joined = unsplit(
            [m for _, m in mine], [seams, bonds], tol["rebuild_tol"] * size
        )
        mine = [(label, m) for (label, _), m in zip(mine, meshes)]
    if len(mine) != len(theirs) or any(
        m.vertices_coords.shape != r.vertices_coords.shape for (_, m), (_, r) in zip(mine, theirs)
    ):
        return FileCheck(
            "rebuild",
            "fail",
            math.inf,
            tol["rebuild_tol"],
            "relative",
            f"the rebuilt design has {len(theirs)} frames of "
            f"{len(theirs[0][1].vertices_coords)} vertices; the file "
            f"{len(mine)} of {len(mine[0][1].vertices_coords)}",
        )
    # the file in the rebuilt numbering, where its geometry is the same up to numbering
    matched = renumbered(
        [m for _, m in mine], [seams, bonds], theirs[0][1], tol["rebuild_tol"] * size
    )
    if matched is not None:
        mine = [(label, m) for (label, _), m in zip(mine, matched[0])]
        seams, bonds = matched[1]
    differ = []
    (label, first), (_, rebuilt) = mine[0], theirs[0]
    # shared by every frame
    for name in (
        "edges_vertices",
        "faces_vertices",
        "edges_assignment",
        "edges_kind",
        "faces_group",
    ):
        a, b = getattr(first, name), getattr(rebuilt, name)
        if a.shape != b.shape:
            differ.append(f"{label}: {name} has {len(a)} entries, the rebuilt {len(b)}")
        elif not np.array_equal(a, b):
            differ.append(
                f"{label}: {name} at "
                f"{named_ids('rows')(np.flatnonzero((a != b).reshape(len(a), -1).any(axis=1)))}"
            )
    # fold angles as the coordinates' tolerance allows: an angle moves by about the coordinates'
    # error over the shortest edge
    angle_tol = math.degrees(tol["rebuild_tol"] * size / float(first.edge_lengths().min()))
    for (title, m), (_, r) in zip(mine, theirs):
        if m.edges_foldAngle.shape == r.edges_foldAngle.shape:
            off = np.flatnonzero(~(np.abs(m.edges_foldAngle - r.edges_foldAngle) <= angle_tol))
            if off.size:
                differ.append(
                    f"{title}: edges_foldAngle at {named_ids('edges')(off)} "
                    f"(more than {angle_tol:.1g}°)"
                )
    if titles != [t for t, _ in reference.folded]:
        differ.append(f"frame titles {titles} (rebuilt {[t for t, _ in reference.folded]})")
    if doc.classes != reference.classes:
        differ.append(
            f"frame_classes {[list(c) for c in doc.classes]} (rebuilt "
            f"{[list(c) for c in reference.classes]})"
        )
    for what, a, b in (
        ("curvefold:seam_partners", seams, reference.seam_partners),
        ("curvefold:bonds", bonds, reference.bonds),
    ):
        if not np.array_equal(canonical_pairs(a), canonical_pairs(b)):
            differ.append(f"{what}: {len(a)} pairs, the rebuilt {len(b)}, not the same")
    differ += _metadata_differs(doc.metadata, reference.metadata)
    results = [
        (title, _coordinate_residual(m.vertices_coords, r.vertices_coords, tol, size) / size)
        for (title, m), (_, r) in zip(mine, theirs)
    ]
    coords = judge("rebuild", "relative", tol["rebuild_tol"], results, named_ids("vertices"))
    if joined.size and not differ:
        note = f"{named_ids('vertices')(joined)} on a straight edge joined (a split edge)"
        return replace(coords, where="; ".join(w for w in (coords.where, note) if w))
    if not differ:
        return coords
    where = "; ".join(([coords.where] if coords.status == "fail" else []) + differ[:4]) + (
        f" (+{len(differ) - 4} more)" if len(differ) > 4 else ""
    )
    return FileCheck("rebuild", "fail", coords.value, coords.tolerance, "relative", where)


def _coordinate_residual(mine: np.ndarray, theirs: np.ndarray, tol: dict, size: float):
    """Per vertex, the largest coordinate difference, as the file stands or after the best rigid
    motion, whichever is smaller (a frame moved rigidly is the same geometry)."""
    direct = np.abs(mine - theirs).max(axis=1)
    if direct.max(initial=0.0) <= tol["rebuild_tol"] * size:
        return direct
    aligned = rigid_residual(mine, theirs)
    return aligned if aligned.max(initial=0.0) < direct.max(initial=0.0) else direct


def _metadata_differs(mine: dict, theirs: dict) -> list[str]:
    """The keys of curvefold:metadata in both whose values differ from the rebuilt file's
    (numbers beyond 1e-6 relative: figures measured on the build)."""
    out = []
    # samples: the design's as the command line writes it, the panels' as a rebuild does
    for key in sorted(set(mine) & set(theirs) - {"samples"}):
        a, b = mine[key], theirs[key]
        numbers = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (a, b))
        if numbers:
            same = math.isclose(float(a), float(b), rel_tol=1e-6, abs_tol=1e-12)
        else:
            same = a == b
        if not same:
            out.append(f"curvefold:metadata {key} {a!r} (rebuilt {b!r})")
    return out
