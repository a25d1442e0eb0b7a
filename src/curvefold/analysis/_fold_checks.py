"""The checks of a FOLD file's frames: each takes the frames as read and returns one
:class:`~curvefold.analysis.FileCheck` (what each verifies: :mod:`curvefold.analysis._foldcheck`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from ..geometry._mesh import Mesh, edges_faces, face_sides, vector_areas
from ..geometry._mesh import fold_angles as dihedral_angles
from ..geometry._topology import fold_assignment
from ..io._fold_reading import FoldFile
from ..kernel._arrays import distinct
from ._fold_results import FileCheck

__all__ = [
    "Frame",
    "NEEDS_CREASE_PATTERN",
    "assignments",
    "edge_kinds",
    "named_ids",
    "isometry",
    "judge",
    "not_run",
    "planarity",
    "recorded_angles",
    "topology",
    "welds",
]

#: The checks that compare with a crease pattern, and why they need it.
NEEDS_CREASE_PATTERN = {"isometry": "edge lengths are compared with the crease pattern's"}


@dataclass(frozen=True)
class Frame:
    """A frame as the checks read it."""

    label: str
    mesh: Mesh
    flat: bool = False  # flat-folded: the direction of its folds is not in its coordinates
    # edges whose fold angle it does not record
    unrecorded: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    # the crease pattern: flat by definition, its recorded angles those of a folded state
    pattern: bool = False


def not_run(name: str, unit: str, reason: str) -> FileCheck:
    return FileCheck(name, "not run", unit=unit, reason=reason)


# --------------------------------------------------------------------------------------
# the checks; each takes its frames and returns one FileCheck


def named_ids(what: str) -> Callable[[np.ndarray], str]:
    """``ids -> "edges 3, 17, 40 (+12 more)"``."""

    def describe(ids: np.ndarray) -> str:
        shown = ", ".join(str(int(i)) for i in ids[:5])
        return f"{what} {shown}" + (f" (+{len(ids) - 5} more)" if len(ids) > 5 else "")

    return describe


def judge(
    name: str,
    unit: str,
    tolerance: float,
    results: list[tuple[str, np.ndarray]],
    describe: Callable[[np.ndarray], str],
) -> FileCheck:
    """A check from per-frame values (one per element, ids = positions).

    An element beyond the tolerance fails, and so does one that cannot be measured (NaN, or
    infinite against a reference of no length), named apart; the value is the worst over the
    measurable elements, so one degenerate element does not hide how far the others are off. The
    first failing frame is named.
    """
    worst, at, failing = -math.inf, "", ""
    for label, values in results:
        values = np.asarray(values, float)
        if not values.size:
            continue
        nan = ~np.isfinite(values)  # NaN, or infinite over a reference of no length
        over = np.flatnonzero((values > tolerance) & ~nan)
        if (over.size or nan.any()) and not failing:
            parts = ([describe(over)] if over.size else []) + (
                [f"not measurable (no length or no normal): {describe(np.flatnonzero(nan))}"]
                if nan.any()
                else []
            )
            failing = f"{label}: " + "; ".join(parts)
        if (~nan).any():
            i = int(np.nanargmax(np.where(nan, np.nan, values)))
            if values[i] > worst:
                worst, at = float(values[i]), f"{label}: {describe(np.array([i]))}"
    if worst == -math.inf:
        worst = math.nan if failing else 0.0
    return FileCheck(name, "fail" if failing else "pass", worst, tolerance, unit, failing or at)


def _edge_use(mesh: Mesh) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For every edge the faces running it a→b and b→a (counts), and the face sides that are no
    edge."""
    faces, edges = mesh.faces_vertices, mesh.edges_vertices
    V = int(max(len(mesh.vertices_coords), edges.max(initial=-1) + 1, faces.max(initial=-1) + 1))
    sides, side_face = face_sides(faces)
    key = edges[:, 0].astype(np.int64) * V + edges[:, 1]
    order = np.argsort(key)
    counts, missing = [], np.ones(len(sides), bool)
    for a, b in ((0, 1), (1, 0)):
        side_key = sides[:, a].astype(np.int64) * V + sides[:, b]
        pos = np.clip(np.searchsorted(key[order], side_key), 0, max(len(key) - 1, 0))
        hit = key[order][pos] == side_key if len(key) else np.zeros(len(side_key), bool)
        counts.append(np.bincount(order[pos[hit]], minlength=len(edges)))
        missing &= ~hit
    return counts[0], counts[1], side_face[missing]


def topology(frames: list[Frame], size: float) -> FileCheck:
    cp = frames[0].mesh
    forward, backward, strays = _edge_use(cp)
    total = forward + backward
    boundary = cp.edges_assignment == "B"
    filled = np.where(
        cp.faces_vertices >= 0,
        cp.faces_vertices,
        -1 - np.arange(cp.faces_vertices.size).reshape(cp.faces_vertices.shape),
    )
    problems = {
        frames[0].label: [
            (strays, "faces with a side that is no edge"),
            (np.flatnonzero(total == 0), "edges on no face"),
            (np.flatnonzero(boundary & (total > 1)), "B edges on more than one face"),
            (np.flatnonzero(~boundary & (total == 1)), "M/V/F edges on one face"),
            (np.flatnonzero(~boundary & (total > 2)), "M/V/F edges on more than two faces"),
            (
                np.flatnonzero(~boundary & (total == 2) & (forward != 1)),
                "edges whose two faces run them the same way (faces not consistently oriented)",
            ),
            (
                np.flatnonzero([len(set(row)) < len(row) for row in filled.tolist()]),
                "faces with a repeated vertex",
            ),
        ]
    }
    tiny = 1e-12 * size
    for f in frames:
        area = np.linalg.norm(vector_areas(f.mesh.vertices_coords, f.mesh.faces_vertices), axis=-1)
        problems.setdefault(f.label, []).extend(
            [
                (np.flatnonzero(~(f.mesh.edge_lengths() > tiny)), "edges of zero length"),
                (np.flatnonzero(~(area > tiny**2)), "faces of zero area"),
            ]
        )
    found = [
        f"{label}: " + "; ".join(named_ids(what)(distinct(ids)) for ids, what in listed if len(ids))
        for label, listed in problems.items()
        if any(len(ids) for ids, _ in listed)
    ]
    return FileCheck("topology", "fail" if found else "pass", where=" | ".join(found[:3]))


def welds(doc: FoldFile, frames: list[Frame], size: float, tolerance: float) -> FileCheck:
    if not {"curvefold:seam_partners", "curvefold:bonds"} & doc.keys:
        return not_run(
            "welds",
            "relative",
            "the file does not say which edges are glued (no "
            "curvefold:seam_partners or curvefold:bonds; another tool may have dropped them)",
        )
    if not frames:
        return not_run(
            "welds", "relative", "the file holds no folded frame, where glued edges meet"
        )
    pairs = np.concatenate([doc.seam_partners, doc.bonds])
    seams = len(doc.seam_partners)
    results = []
    for f in frames:
        ends = f.mesh.vertices_coords[f.mesh.edges_vertices[pairs]]  # (P, 2 edges, 2 ends, 3)
        same = np.linalg.norm(ends[:, 0] - ends[:, 1], axis=-1).max(axis=-1)
        reversed_ = np.linalg.norm(ends[:, 0] - ends[:, 1, ::-1], axis=-1).max(axis=-1)
        results.append((f.label, np.fmin(same, reversed_) / size))  # NaN only if both are

    def describe(ids: np.ndarray) -> str:
        kinds = ("seam partners" if i < seams else "bonds" for i in ids[:5])
        shown = ", ".join(f"{k} {pairs[i, 0]}–{pairs[i, 1]}" for k, i in zip(kinds, ids))
        return f"edges {shown}" + (f" (+{len(ids) - 5} more pairs)" if len(ids) > 5 else "")

    return judge("welds", "relative", tolerance, results, describe)


def edge_kinds(doc: FoldFile, frame: Frame) -> FileCheck:
    """A curvefold file's assignments against the one rule of its edge kinds."""
    if not {"edges_curvefold:kind", "curvefold:edges_kind"} & doc.keys:
        return not_run(
            "edge_kinds", "", "the file does not say what its edges are (no edges_curvefold:kind)"
        )
    mesh = frame.mesh
    kind, assignment = mesh.edges_kind, mesh.edges_assignment
    expected = fold_assignment(kind, mesh.edges_foldAngle, seams_open=True)
    wrong = np.flatnonzero(
        np.where(kind == "fold", ~np.isin(assignment, ("M", "V")), assignment != expected)
    )
    if not wrong.size:
        return FileCheck("edge_kinds", "pass")
    shown = ", ".join(f"{e} ({kind[e]}) assigned {assignment[e]}" for e in wrong[:5])
    more = f" (+{len(wrong) - 5} more)" if len(wrong) > 5 else ""
    return FileCheck(
        "edge_kinds",
        "fail",
        where=f"{frame.label}: edges {shown}{more}; a fold is "
        "M or V, a boundary or seam B, a ruling or diagonal F",
    )


def assignments(frames: list[Frame], slack: float, flat: float) -> FileCheck:
    results, reversed_, misrecorded = [], False, False
    for f in frames:
        a = f.mesh.edges_assignment
        recorded = np.where(np.isin(np.arange(len(a)), f.unrecorded), 0.0, f.mesh.edges_foldAngle)
        # how far each M/V edge is recorded the wrong way, beyond the slack
        wrong = np.select(
            [a == "M", a == "V"],
            [np.fmax(recorded - slack, 0.0), np.fmax(-recorded - slack, 0.0)],
            0.0,
        )
        misrecorded |= bool((wrong > 0).any())
        if not f.pattern:  # a folded frame: measured too
            measured = _measured(f.mesh)
            unfolded = np.isin(a, ("F", "J"))
            if f.flat:  # only whether an edge is folded through is measured: |angle| is 0 or 180
                bent = np.where(unfolded, np.fmax(np.abs(measured) - flat, 0.0), 0.0)
            else:
                # folded through (±180°, its faces on each other): the sign is not measured
                through = np.abs(measured) >= 180.0 - slack
                bent = np.select(
                    [through & ~unfolded, a == "M", a == "V", unfolded],
                    [
                        0.0,
                        np.fmax(measured - slack, 0.0),
                        np.fmax(-measured - slack, 0.0),
                        np.fmax(np.abs(measured) - flat, 0.0),
                    ],
                    0.0,
                )
            if not f.flat:  # every folded M/V edge the other way: the faces wound the other way
                sign = np.select([a == "M", a == "V"], [-1.0, 1.0], 0.0) * measured
                folded = (sign != 0) & (np.abs(measured) > slack) & ~through
                reversed_ |= bool(folded.any() and (sign[folded] < 0).all())
            # NaN stays
            wrong = np.maximum(
                wrong, np.where(np.isnan(measured) & ~np.isin(a, ("B", "U")), np.nan, bent)
            )
        results.append((f.label, wrong))
    found = judge("assignments", "°", 0.0, results, named_ids("edges"))
    if found.status == "fail" and reversed_:
        found = replace(found, where=f"{found.where}; {_WOUND}")
    if found.status == "fail" and misrecorded:
        found = replace(
            found,
            where=f"{found.where}; M or V edges record a fold angle of the other sign (FOLD: a "
            "mountain's is negative, a valley's positive)",
        )
    return found


def _measured(mesh: Mesh) -> np.ndarray:
    return dihedral_angles(mesh.vertices_coords, mesh.faces_vertices, mesh.edges_vertices)


def recorded_angles(frames: list[Frame], tolerance: float) -> FileCheck:
    if not frames:
        return not_run("fold_angles", "°", "the file holds no folded frame")
    results, recorded_any, reversed_ = [], False, False
    for f in frames:
        sides = edges_faces(f.mesh.faces_vertices, f.mesh.edges_vertices)
        # the recorded edges between two faces (a mask: np.setdiff1d would import numpy.ma)
        between = np.asarray((sides >= 0).all(axis=1))
        between[np.asarray(f.unrecorded, dtype=np.intp)] = False
        two = np.flatnonzero(between)
        recorded_any |= two.size > 0 and len(f.unrecorded) < len(f.mesh.edges_vertices)
        measured = dihedral_angles(
            f.mesh.vertices_coords,
            f.mesh.faces_vertices,
            f.mesh.edges_vertices,
            faces_of_edges=sides,
        )[two]
        recorded = f.mesh.edges_foldAngle[two]
        if f.flat:  # a flat fold's direction is not in the coordinates: compare magnitudes
            error = np.abs(np.abs(recorded) - np.abs(measured))
        else:
            error = np.abs((recorded - measured + 180.0) % 360.0 - 180.0)
            # every folded edge recorded as the negative of its measure: the faces wound the
            # other way
            folded = np.abs(recorded) > tolerance
            opposite = np.abs((recorded + measured + 180.0) % 360.0 - 180.0) <= tolerance
            reversed_ |= bool(folded.any() and (opposite[folded]).all() and error.max() > tolerance)
        results.append((f.label, _at_edges(error, two, len(f.mesh.edges_vertices))))
    if not recorded_any:
        return not_run(
            "fold_angles",
            "°",
            "the file records no fold angle of an edge with two faces (no edges_foldAngle)",
        )
    found = judge("fold_angles", "°", tolerance, results, named_ids("edges"))
    if found.status == "fail" and reversed_:
        found = replace(found, where=f"{found.where}; {_WOUND}")
    return found


#: Why every folded edge of a frame is measured the other way.
_WOUND = (
    "every folded edge of a frame is measured the other way: its faces are wound clockwise "
    "seen from the valley side (FOLD: counterclockwise)"
)


def _at_edges(values: np.ndarray, ids: np.ndarray, edges: int) -> np.ndarray:
    """Values on a subset of edges spread over all edges (0 elsewhere), so ids stay edge ids."""
    out = np.zeros(edges)
    out[ids] = values
    return out


def isometry(pattern: Mesh | None, frames: list[Frame], tolerance: float) -> FileCheck:
    if pattern is None:
        return not_run(
            "isometry",
            "relative",
            f"the file holds no crease pattern: {NEEDS_CREASE_PATTERN['isometry']}",
        )
    if not frames:
        return not_run(
            "isometry",
            "relative",
            "the file holds no folded frame to compare with its crease pattern",
        )
    base = pattern.edge_lengths()
    with np.errstate(invalid="ignore", divide="ignore"):
        results = [(f.label, np.abs(f.mesh.edge_lengths() / base - 1)) for f in frames]
    return judge("isometry", "relative", tolerance, results, named_ids("edges"))


def planarity(doc: FoldFile, frames: list[Frame], tolerance: float) -> FileCheck:
    ref = frames[0].mesh if frames else doc.crease_pattern
    assert ref is not None  # a file holds a crease pattern or a folded frame (read_fold)
    polygons = ref.faces_vertices.shape[1] > 3
    kinds_known = bool({"edges_curvefold:kind", "curvefold:edges_kind"} & doc.keys)
    joins = (ref.edges_assignment == "J").any()
    if not frames:
        return not_run("face_planarity", "°", "the file holds no folded frame")
    if not polygons and not kinds_known and not joins:
        return not_run(
            "face_planarity",
            "°",
            "every face is a triangle, planar by definition; "
            "without edges_curvefold:kind the diagonals that split ruling quads are not known",
        )
    results, skipped, straight = [], np.zeros(0, np.int64), np.zeros(0, np.int64)
    for f in frames:
        # a vertex on a straight side of its polygon (as where an edge was split) bends nothing
        # and its fan triangle has no normal: the polygon is measured without it
        mesh, on_side = _straightened(f.mesh)
        straight = distinct(np.concatenate([straight, on_side]))
        triangles = mesh.triangulated()
        fan = np.arange(len(triangles.edges_vertices)) >= len(f.mesh.edges_vertices)
        if kinds_known:
            flat = triangles.edges_kind == "diagonal"
        else:  # the reader calls every F edge a diagonal; only the fan's are, and the joins
            flat = fan.copy()
        flat |= triangles.edges_assignment == "J"
        diagonal = np.flatnonzero(flat)
        sides = edges_faces(triangles.faces_vertices, triangles.edges_vertices[diagonal])
        bend = np.abs(
            dihedral_angles(
                triangles.vertices_coords,
                triangles.faces_vertices,
                triangles.edges_vertices[diagonal],
                faces_of_edges=sides,
            )
        )
        # a fan triangle with no area (a vertex on a straight side of its polygon, as where an
        # edge was split) has no normal to bend by: its diagonal is skipped and named
        flat_triangle = _no_area(triangles)
        degenerate = fan[diagonal] & (flat_triangle[sides] & (sides >= 0)).any(axis=1)
        bend[degenerate] = 0.0
        skipped = distinct(np.concatenate([skipped, diagonal[degenerate]]))  # np.union1d: numpy.ma
        results.append((f.label, _at_edges(bend, diagonal, len(triangles.edges_vertices))))
    what = "fan diagonals (numbered after the file's edges)" if polygons else "diagonal edges"
    found = judge(
        "face_planarity",
        "°",
        tolerance,
        results,
        named_ids(what + (" and join edges" if joins else "")),
    )
    notes = [found.where] if found.where else []
    if straight.size:
        notes.append(
            f"skipped {named_ids('vertices')(straight)} on a straight side of their polygon "
            "(as where an edge was split)"
        )
    if skipped.size:
        notes.append(
            f"skipped {named_ids('fan diagonals')(skipped)} beside a triangle with no area (a "
            "vertex on a straight side of its polygon)"
        )
    return replace(found, where="; ".join(notes)) if len(notes) > bool(found.where) else found


def _straightened(mesh: Mesh) -> tuple[Mesh, np.ndarray]:
    """The mesh with every polygon corner of no area removed (a vertex on a straight side: a
    height under 1e-9 of the mesh's size), polygons kept to three corners; the vertices
    removed."""
    faces = mesh.faces_vertices
    if faces.shape[1] == 3 or not len(faces):
        return mesh, np.zeros(0, np.int64)
    x = np.asarray(mesh.vertices_coords, float)
    size = float(np.ptp(x, axis=0).max()) if len(x) else 0.0
    rows, removed = [], []
    for face in faces.tolist():
        ring = [v for v in face if v >= 0]
        changed = True
        while changed and len(ring) > 3:
            changed = False
            for k in range(len(ring)):
                a, v, b = x[ring[k - 1]], x[ring[k]], x[ring[(k + 1) % len(ring)]]
                u, w = v - a, b - a
                cross = np.linalg.norm(np.cross(np.r_[u, 0][:3], np.r_[w, 0][:3]))
                if not cross > 1e-9 * size * max(np.linalg.norm(w), np.linalg.norm(u)):
                    removed.append(ring.pop(k))
                    changed = True
                    break
        rows.append(ring)
    if not removed:
        return mesh, np.zeros(0, np.int64)
    k = max(map(len, rows))
    padded = np.array([r + [-1] * (k - len(r)) for r in rows], np.int64)
    return replace(mesh, faces_vertices=padded), distinct(np.array(removed, np.int64))


def _no_area(mesh: Mesh) -> np.ndarray:
    """Which triangles have no area: a height under 1e-9 of the mesh's size, (F,) bool."""
    corners = mesh.vertices_coords[mesh.faces_vertices]
    twice_area = np.linalg.norm(vector_areas(mesh.vertices_coords, mesh.faces_vertices), axis=-1)
    longest = np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=-1).max(axis=1)
    size = float(np.ptp(mesh.vertices_coords, axis=0).max())
    return ~(twice_area > 1e-9 * size * longest)
