"""Check a FOLD file: its topology, welds, assignments, recorded angles and every folded frame.

:func:`check_fold` reads a FOLD file (as curvefold writes it, or as another tool saved it)
and verifies, in every frame, naming the failing element ids and the frame:

``topology``
    every face side is an edge, every edge lies on a face, a boundary (``B``) edge on one
    face and every other edge on two faces that run it in opposite directions (the faces
    are consistently oriented), no edge of zero length and no face of zero area or with a
    repeated vertex.
``welds``
    the edges glued together (``curvefold:seam_partners``, the two sides of a seam, and
    ``curvefold:bonds``, tubes glued where they touch) coincide in every folded frame.
``assignments``
    every ``M`` edge folds as a mountain (measured dihedral ≤ 0) and every ``V`` edge as a
    valley (≥ 0) within ``fold_angle_tol``, and an ``F`` edge bends by at most
    ``flat_tol``.
``fold_angles``
    the recorded ``edges_foldAngle`` of every frame is the dihedral angle measured in
    that frame, on every edge with two faces.
``isometry``
    every folded frame's edge lengths against the crease pattern's.
``face_planarity``
    the dihedral angle across the diagonals that split a polygon face into a fan of
    triangles, and across the diagonals of ruling quads (edges of kind ``"diagonal"``).
``rebuild``
    with a ``reference`` (the design the file records, built again): every coordinate of
    every frame, relative to the model's size.

A check that needs what the file does not hold (custom ``curvefold:`` keys another tool
dropped) is "not run", with the reason. NaN never passes.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..geometry.mesh import Mesh, edges_faces, face_sides, vector_areas
from ..geometry.mesh import fold_angles as dihedral_angles
from ..io.fold_reading import FoldFile, read_fold
from ..kernel.errors import InputError
from ..kernel.validate import Spec
from .checks import CHECKS

__all__ = ["CHECK_SPECS", "FileCheck", "FoldCheck", "check_fold"]

_CAP = {spec.name: spec.cap for spec in CHECKS}

#: The tolerances of :func:`check_fold` (the flags of ``curvefold check``).
CHECK_SPECS: tuple[Spec, ...] = (
    Spec("isometry_tol", "real", _CAP["isometry"], "[0, inf)",
         help="largest relative change of an edge's length from the crease pattern (as the certificate's isometry cap)"),
    Spec("planarity_tol", "real", 0.5, "[0, 180]", "degrees", help="largest fold angle across the diagonals of a polygon face or ruling quad"),
    Spec("fold_angle_tol", "real", 0.01, "[0, 180]", "degrees",
         help="largest difference between a frame's recorded and measured dihedral angle, and the slack of the M/V signs"),
    Spec("flat_tol", "real", 10.0, "[0, 180]", "degrees",
         help="largest dihedral angle across an F edge (a sampled curved sheet bends across its rulings by about κh)"),
    Spec("weld_tol", "real", 1e-9, "[0, inf)", help="largest distance between glued edges, relative to the model's size"),
    Spec("rebuild_tol", "real", 1e-9, "[0, inf)", help="largest coordinate difference from the rebuilt design, relative to the model's size"),
)
_DEFAULT = {spec.name: spec.default for spec in CHECK_SPECS}


@dataclass(frozen=True)
class FileCheck:
    """One check of a FOLD file.

    Attributes
    ----------
    name : str
    status : {"pass", "fail", "not run"}
    value : float or None
        The worst measured value (NaN if a measurement broke); None when not run, and for
        ``topology``, which lists its problems in ``where``.
    tolerance : float or None
    unit : str
    where : str
        The frame and the ids of the failing elements (or of the worst one).
    reason : str
        Why the check did not run, for "not run".
    """

    name: str
    status: str
    value: float | None = None
    tolerance: float | None = None
    unit: str = ""
    where: str = ""
    reason: str = ""

    def to_dict(self) -> dict:
        """The check as strict JSON (a non-finite value is null)."""
        value = None if self.value is None or not math.isfinite(self.value) else self.value
        return {"name": self.name, "status": self.status, "value": value, "tolerance": self.tolerance, "unit": self.unit,
                "where": self.where, "reason": self.reason}


@dataclass(frozen=True)
class FoldCheck:
    """The result of :func:`check_fold`.

    Attributes
    ----------
    frames : int
        Number of folded frames checked.
    checks : tuple of FileCheck
    max_isometry_error : float
        Largest ``|ℓ_folded / ℓ_pattern − 1|`` over all edges and frames.
    max_face_planarity_error : float
        Largest fold angle, degrees, across face and ruling-quad diagonals (0 when that
        check did not run).
    max_fold_angle_error : float
        Largest ``|recorded − measured|`` dihedral angle, degrees.
    ok : bool
        Every check that ran passed.
    tolerances : dict
    """

    frames: int
    checks: tuple[FileCheck, ...]
    tolerances: dict

    def _value(self, name: str) -> float:
        check = next(c for c in self.checks if c.name == name)
        return 0.0 if check.value is None else check.value

    @property
    def max_isometry_error(self) -> float:
        return self._value("isometry")

    @property
    def max_face_planarity_error(self) -> float:
        return self._value("face_planarity")

    @property
    def max_fold_angle_error(self) -> float:
        return self._value("fold_angles")

    @property
    def ok(self) -> bool:
        return all(c.status != "fail" for c in self.checks)

    def to_dict(self) -> dict:
        """The result as strict JSON (non-finite numbers are null), as ``curvefold check --json`` prints it."""

        def finite(x):
            return x if math.isfinite(x) else None

        return {
            "frames": self.frames,
            "max_isometry_error": finite(self.max_isometry_error),
            "max_face_planarity_error": finite(self.max_face_planarity_error),
            "max_fold_angle_error": finite(self.max_fold_angle_error),
            "ok": self.ok,
            "checks": [c.to_dict() for c in self.checks],
            "not_run": [c.name for c in self.checks if c.status == "not run"],
            "tolerances": self.tolerances,
        }


def check_fold(path: str | os.PathLike | FoldFile, *, reference: FoldFile | None = None, **tolerances: float) -> FoldCheck:
    """Read a FOLD file and check its topology, welds, assignments, angles and every frame.

    Parameters
    ----------
    path : path-like or FoldFile
        A FOLD file with a crease pattern (the key frame) and at least one folded frame
        sharing its topology, or such a file already read.
    reference : FoldFile, optional, keyword-only
        The file built again from the design it records: adds the ``rebuild`` check.
    **tolerances : float
        Any of :data:`CHECK_SPECS` by name (``isometry_tol``, ``planarity_tol``,
        ``fold_angle_tol``, ``flat_tol``, ``weld_tol``, ``rebuild_tol``); finite and ≥ 0.

    Raises
    ------
    InputError
        The file is not a FOLD file curvefold can read (the message names the key), has
        no folded frame, or a tolerance is not a number ≥ 0.
    """
    specs = {spec.name: spec for spec in CHECK_SPECS}
    unknown = sorted(set(tolerances) - set(specs))
    if unknown:
        raise InputError(f"check_fold: unknown tolerance {unknown[0]!r} (allowed: {', '.join(specs)})")
    tol = _DEFAULT | {name: specs[name].check(value) for name, value in tolerances.items()}
    doc = path if isinstance(path, FoldFile) else read_fold(path)
    where = "" if isinstance(path, FoldFile) else f"{os.fspath(path)}: "
    if not doc.folded:
        raise InputError(f"{where}no folded frame to check (the file holds only a crease pattern)")
    frames = [("key frame (crease pattern)", doc.crease_pattern)] + [(f"frame {i + 1} ({title!r})", m) for i, (title, m) in enumerate(doc.folded)]
    size = max(float(np.ptp(m.vertices_coords, axis=0).max()) for _, m in frames)
    differ = [label for label, m in frames[1:] if not (np.array_equal(m.edges_vertices, doc.crease_pattern.edges_vertices)
                                                      and np.array_equal(m.faces_vertices, doc.crease_pattern.faces_vertices))]
    if differ:
        reason = f"{differ[0]} has other edges or faces than the crease pattern"
        return FoldCheck(len(doc.folded), (FileCheck("topology", "fail", where=reason),) +
                         tuple(FileCheck(name, "not run", reason="the frames do not share one topology")
                               for name in ("welds", "assignments", "fold_angles", "isometry", "face_planarity")), tol)
    checks = [
        _topology(frames, size),
        _welds(doc, frames[1:], size, tol["weld_tol"]),
        _assignments(frames[1:], tol["fold_angle_tol"], tol["flat_tol"]),
        _recorded_angles(frames[1:], tol["fold_angle_tol"]),
        _isometry(doc.crease_pattern, frames[1:], tol["isometry_tol"]),
        _planarity(doc, frames[1:], tol["planarity_tol"]),
    ]
    if reference is not None:
        checks.append(_rebuild(frames, reference, size, tol["rebuild_tol"]))
    return FoldCheck(len(doc.folded), tuple(checks), tol)


# --------------------------------------------------------------------------------------
# the checks; each takes [(frame label, Mesh)] and returns one FileCheck


def _ids(what: str) -> Callable[[np.ndarray], str]:
    """``ids -> "edges 3, 17, 40 (+12 more)"``."""
    def describe(ids: np.ndarray) -> str:
        shown = ", ".join(str(int(i)) for i in ids[:5])
        return f"{what} {shown}" + (f" (+{len(ids) - 5} more)" if len(ids) > 5 else "")

    return describe


def _judge(name: str, unit: str, tolerance: float, results: list[tuple[str, np.ndarray]], describe: Callable[[np.ndarray], str]) -> FileCheck:
    """A check from per-frame values (one per element, ids = positions); NaN fails, the first failing frame is named."""
    worst, at, failing = 0.0, "", ""
    for label, values in results:
        values = np.asarray(values, float)
        if not values.size:
            continue
        bad = np.flatnonzero(~(values <= tolerance))  # NaN is bad
        if bad.size and not failing:
            failing = f"{label}: {describe(bad)}"
        v = float(np.max(values))  # NaN propagates
        if not math.isnan(worst) and (math.isnan(v) or v > worst):
            worst, at = v, f"{label}: {describe(np.array([np.argmax(np.where(np.isnan(values), np.inf, values))]))}"
    return FileCheck(name, "fail" if failing else "pass", worst, tolerance, unit, failing or at)


def _edge_use(mesh: Mesh) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For every edge the faces running it a→b and b→a (counts), and the face sides that are no edge."""
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


def _topology(frames: list[tuple[str, Mesh]], size: float) -> FileCheck:
    key_label, cp = frames[0]
    forward, backward, strays = _edge_use(cp)
    total = forward + backward
    boundary = cp.edges_assignment == "B"
    filled = np.where(cp.faces_vertices >= 0, cp.faces_vertices, -1 - np.arange(cp.faces_vertices.size).reshape(cp.faces_vertices.shape))
    problems = {key_label: [
        (strays, "faces with a side that is no edge"),
        (np.flatnonzero(total == 0), "edges on no face"),
        (np.flatnonzero(boundary & (total > 1)), "B edges on more than one face"),
        (np.flatnonzero(~boundary & (total == 1)), "M/V/F edges on one face"),
        (np.flatnonzero(~boundary & (total > 2)), "M/V/F edges on more than two faces"),
        (np.flatnonzero(~boundary & (total == 2) & (forward != 1)), "edges whose two faces run them the same way (faces not consistently oriented)"),
        (np.flatnonzero([len(set(row)) < len(row) for row in filled.tolist()]), "faces with a repeated vertex"),
    ]}
    tiny = 1e-12 * size
    for label, mesh in frames:
        area = np.linalg.norm(vector_areas(mesh.vertices_coords, mesh.faces_vertices), axis=-1)
        problems.setdefault(label, []).extend([(np.flatnonzero(~(mesh.edge_lengths() > tiny)), "edges of zero length"),
                                               (np.flatnonzero(~(area > tiny**2)), "faces of zero area")])
    found = [f"{label}: " + "; ".join(_ids(what)(np.unique(ids)) for ids, what in listed if len(ids))
             for label, listed in problems.items() if any(len(ids) for ids, _ in listed)]
    return FileCheck("topology", "fail" if found else "pass", where=" | ".join(found[:3]))


def _welds(doc: FoldFile, frames: list[tuple[str, Mesh]], size: float, tolerance: float) -> FileCheck:
    if not {"curvefold:seam_partners", "curvefold:bonds"} & doc.keys:
        return FileCheck("welds", "not run", unit="relative", reason="the file does not say which edges are glued "
                         "(no curvefold:seam_partners or curvefold:bonds; another tool may have dropped them)")
    pairs = np.concatenate([doc.seam_partners, doc.bonds])
    seams = len(doc.seam_partners)
    results = []
    for label, mesh in frames:
        ends = mesh.vertices_coords[mesh.edges_vertices[pairs]]  # (P, 2 edges, 2 ends, 3)
        same = np.linalg.norm(ends[:, 0] - ends[:, 1], axis=-1).max(axis=-1)
        reversed_ = np.linalg.norm(ends[:, 0] - ends[:, 1, ::-1], axis=-1).max(axis=-1)
        results.append((label, np.fmin(same, reversed_) / size))  # NaN only if both are

    def describe(ids: np.ndarray) -> str:
        kinds = ("seam partners" if i < seams else "bonds" for i in ids[:5])
        shown = ", ".join(f"{k} {pairs[i, 0]}–{pairs[i, 1]}" for k, i in zip(kinds, ids))
        return f"edges {shown}" + (f" (+{len(ids) - 5} more pairs)" if len(ids) > 5 else "")

    return _judge("welds", "relative", tolerance, results, describe)


def _assignments(frames: list[tuple[str, Mesh]], slack: float, flat: float) -> FileCheck:
    results = []
    for label, mesh in frames:
        measured = _measured(mesh)
        a = mesh.edges_assignment
        # how far each M/V edge folds the wrong way, and each F edge bends, beyond what is allowed
        wrong = np.select([a == "M", a == "V", a == "F"], [np.fmax(measured - slack, 0.0), np.fmax(-measured - slack, 0.0),
                                                           np.fmax(np.abs(measured) - flat, 0.0)], 0.0)
        results.append((label, np.where(np.isnan(measured) & (a != "B"), np.nan, wrong)))
    return _judge("assignments", "°", 0.0, results, _ids("edges"))


def _measured(mesh: Mesh) -> np.ndarray:
    return dihedral_angles(mesh.vertices_coords, mesh.faces_vertices, mesh.edges_vertices)


def _recorded_angles(frames: list[tuple[str, Mesh]], tolerance: float) -> FileCheck:
    results = []
    for label, mesh in frames:
        sides = edges_faces(mesh.faces_vertices, mesh.edges_vertices)
        two = np.flatnonzero((sides >= 0).all(axis=1))
        measured = dihedral_angles(mesh.vertices_coords, mesh.faces_vertices, mesh.edges_vertices, faces_of_edges=sides)[two]
        error = np.abs((mesh.edges_foldAngle[two] - measured + 180.0) % 360.0 - 180.0)
        results.append((label, _at_edges(error, two, len(mesh.edges_vertices))))
    return _judge("fold_angles", "°", tolerance, results, _ids("edges"))


def _at_edges(values: np.ndarray, ids: np.ndarray, edges: int) -> np.ndarray:
    """Values on a subset of edges spread over all edges (0 elsewhere), so ids stay edge ids."""
    out = np.zeros(edges)
    out[ids] = values
    return out


def _isometry(pattern: Mesh, frames: list[tuple[str, Mesh]], tolerance: float) -> FileCheck:
    base = pattern.edge_lengths()
    with np.errstate(invalid="ignore", divide="ignore"):
        results = [(label, np.abs(mesh.edge_lengths() / base - 1)) for label, mesh in frames]
    return _judge("isometry", "relative", tolerance, results, _ids("edges"))


def _planarity(doc: FoldFile, frames: list[tuple[str, Mesh]], tolerance: float) -> FileCheck:
    polygons = doc.crease_pattern.faces_vertices.shape[1] > 3
    kinds_known = "edges_curvefold:kind" in doc.keys or "curvefold:edges_kind" in doc.keys
    if not polygons and not kinds_known:
        return FileCheck("face_planarity", "not run", unit="°", reason="every face is a triangle, planar by definition; without "
                         "edges_curvefold:kind the diagonals that split ruling quads are not known")
    results = []
    for label, mesh in frames:
        triangles = mesh.triangulated()
        diagonal = np.flatnonzero(triangles.edges_kind == "diagonal")
        if not kinds_known:  # the reader calls every F edge a diagonal; only the fan's are
            diagonal = diagonal[diagonal >= len(mesh.edges_vertices)]
        bend = np.abs(dihedral_angles(triangles.vertices_coords, triangles.faces_vertices, triangles.edges_vertices[diagonal]))
        results.append((label, _at_edges(bend, diagonal, len(triangles.edges_vertices))))
    return _judge("face_planarity", "°", tolerance, results, _ids("fan diagonals (numbered after the file's edges)" if polygons else "diagonal edges"))


def _rebuild(frames: list[tuple[str, Mesh]], reference: FoldFile, size: float, tolerance: float) -> FileCheck:
    rebuilt = [reference.crease_pattern] + [m for _, m in reference.folded]
    if len(rebuilt) != len(frames) or any(m.vertices_coords.shape != r.vertices_coords.shape for (_, m), r in zip(frames, rebuilt)):
        return FileCheck("rebuild", "fail", math.inf, tolerance, "relative",
                         f"the rebuilt design has {len(rebuilt) - 1} folded frames of {len(rebuilt[0].vertices_coords)} vertices; "
                         f"the file {len(frames) - 1} of {len(frames[0][1].vertices_coords)}")
    same = all(np.array_equal(m.edges_vertices, r.edges_vertices) and np.array_equal(m.faces_vertices, r.faces_vertices)
               for (_, m), r in zip(frames, rebuilt))
    if not same:
        return FileCheck("rebuild", "fail", math.inf, tolerance, "relative", "the rebuilt design has another topology (edges or faces differ)")
    results = [(label, np.abs(m.vertices_coords - r.vertices_coords).max(axis=1) / size) for (label, m), r in zip(frames, rebuilt)]
    return _judge("rebuild", "relative", tolerance, results, _ids("vertices"))
