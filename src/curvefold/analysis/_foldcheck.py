"""Check a FOLD file: its topology, welds, assignments, recorded angles and every folded frame.

:func:`check_fold` reads a FOLD file (as curvefold writes it, or as another tool saved it:
:func:`curvefold.io.read_fold` says how) and verifies, in every frame, naming
the failing element ids and the frame:

``topology``
    every frame has the crease pattern's vertices, edges and faces; every face side is an
    edge, every edge lies on a face, a boundary (``B``) edge on one face and every other
    edge on two faces that run it in opposite directions (the faces are consistently
    oriented), no edge of zero length and no face of zero area or with a repeated vertex.
``welds``
    the edges glued together (``curvefold:seam_partners``, the two sides of a seam, and
    ``curvefold:bonds``, tubes glued where they touch) coincide in every folded frame.
``edge_kinds``
    a curvefold file's assignments follow from its edge kinds (``edges_curvefold:kind``):
    ``B`` on boundaries and seams, ``F`` on rulings and diagonals, ``M`` or ``V`` on folds.
``assignments``
    every ``M`` edge folds as a mountain and every ``V`` edge as a valley within
    ``fold_angle_tol``, both as recorded (``edges_foldAngle``, in every frame, the crease
    pattern's included) and as measured (the dihedral angle of a folded frame), and an
    ``F`` or ``J`` edge bends by at most ``flat_tol``. In a flat-folded frame the direction
    of a fold is not in the coordinates (its faces lie in one plane): there only ``F`` and
    ``J`` edges are checked, not to be folded through.
``fold_angles``
    the recorded ``edges_foldAngle`` of every folded frame is the dihedral angle measured
    in that frame, on every edge with two faces whose angle the frame records (in a
    flat-folded frame, its magnitude: 0 or 180).
``isometry``
    every folded frame's edge lengths against the crease pattern's.
``face_planarity``
    the dihedral angle across the diagonals that split a polygon face into a fan of
    triangles, across the diagonals of ruling quads (edges of kind ``"diagonal"``) and
    across join (``J``) edges.
``rebuild``
    with a ``reference`` (the design the file records, built again): every array of every
    frame, as :func:`read_fold` reads them: coordinates (relative to the model's size) and
    fold angles within their tolerances, edges, faces, assignments, edge kinds, face
    groups, frame classes, titles, seam partners and bonds exactly.

A check that needs what the file does not hold (a crease pattern, custom ``curvefold:``
keys another tool dropped, recorded fold angles) is "not run", with the reason. NaN never
passes: an element that cannot be measured (an edge of no length, a face of no area) fails
and is named, and the check's value is the worst over the elements that can be.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..geometry._mesh import Mesh, edges_faces, face_sides, vector_areas
from ..geometry._mesh import fold_angles as dihedral_angles
from ..geometry._topology import fold_assignment
from ..io._fold_reading import FoldFile, read_fold
from ..kernel._arrays import distinct
from ..kernel._errors import InputError
from ..kernel._validate import Spec
from ._checks import CHECKS

__all__ = ["CHECK_SPECS", "FileCheck", "FoldCheck", "check_fold", "NEEDS_CREASE_PATTERN"]

_CAP = {spec.name: spec.cap for spec in CHECKS}

#: The tolerances of :func:`check_fold` (the flags of ``curvefold check``).
CHECK_SPECS: tuple[Spec, ...] = (
    Spec(
        "isometry_tol",
        "real",
        _CAP["isometry"],
        "[0, inf)",
        help="largest relative change of an edge's length from the crease pattern (as the "
        "certificate's isometry cap)",
    ),
    Spec(
        "planarity_tol",
        "real",
        0.5,
        "[0, 180]",
        "degrees",
        help="largest fold angle across the diagonals of a polygon face or ruling quad",
    ),
    Spec(
        "fold_angle_tol",
        "real",
        0.01,
        "[0, 180]",
        "degrees",
        help="largest difference between a frame's recorded and measured dihedral angle, and "
        "the slack of the M/V signs",
    ),
    Spec(
        "flat_tol",
        "real",
        10.0,
        "[0, 180]",
        "degrees",
        help="largest dihedral angle across an F edge (a sampled curved sheet bends across its "
        "rulings by about κh)",
    ),
    Spec(
        "weld_tol",
        "real",
        1e-9,
        "[0, inf)",
        help="largest distance between glued edges, relative to the model's size",
    ),
    Spec(
        "rebuild_tol",
        "real",
        1e-9,
        "[0, inf)",
        help="largest coordinate difference from the rebuilt design, relative to the model's size",
    ),
)
_DEFAULT = {spec.name: spec.default for spec in CHECK_SPECS}
#: The checks that compare with a crease pattern, and why they need it.
NEEDS_CREASE_PATTERN = {"isometry": "edge lengths are compared with the crease pattern's"}
_CHECK_NAMES = (
    "topology",
    "welds",
    "edge_kinds",
    "assignments",
    "fold_angles",
    "isometry",
    "face_planarity",
)


@dataclass(frozen=True)
class FileCheck:
    """One check of a FOLD file.

    Attributes
    ----------
    name : str
    status : {"pass", "fail", "not run"}
    value : float or None
        The worst measured value over the elements that can be measured (NaN if none can);
        None when not run, and for ``topology`` and ``edge_kinds``, which list their
        problems in ``where``.
    tolerance : float or None
    unit : str
    where : str
        The frame and the ids of the failing elements (or of the worst one); elements that
        cannot be measured are named apart.
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
        return {
            "name": self.name,
            "status": self.status,
            "value": value,
            "tolerance": self.tolerance,
            "unit": self.unit,
            "where": self.where,
            "reason": self.reason,
        }


@dataclass(frozen=True)
class FoldCheck:
    """The result of :func:`check_fold`.

    Attributes
    ----------
    frames : int
        Number of folded frames checked.
    checks : tuple of FileCheck
    tolerances : dict
    notes : tuple of str
        What the reader read leniently or left, and why (:attr:`FoldFile.notes`).
    max_isometry_error : float
        Largest ``|ℓ_folded / ℓ_pattern − 1|`` over all measurable edges and frames (0 when
        that check did not run).
    max_face_planarity_error : float
        Largest fold angle, degrees, across face and ruling-quad diagonals (0 when that
        check did not run).
    max_fold_angle_error : float
        Largest ``|recorded − measured|`` dihedral angle, degrees.
    ok : bool
        Every check that ran passed.
    """

    frames: int
    checks: tuple[FileCheck, ...]
    tolerances: dict
    notes: tuple[str, ...] = ()

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
        """The result as strict JSON (non-finite numbers are null), as ``curvefold check --json``
        prints it."""

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
            "notes": list(self.notes),
            "tolerances": self.tolerances,
        }


@dataclass(frozen=True)
class _Frame:
    """A frame as the checks read it."""

    label: str
    mesh: Mesh
    flat: bool = False  # flat-folded: the direction of its folds is not in its coordinates
    # edges whose fold angle it does not record
    unrecorded: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    # the crease pattern: flat by definition, its recorded angles those of a folded state
    pattern: bool = False


def check_fold(
    path: str | os.PathLike | FoldFile, *, reference: FoldFile | None = None, **tolerances: float
) -> FoldCheck:
    """Read a FOLD file and check its topology, welds, assignments, angles and every frame.

    Parameters
    ----------
    path : path-like or FoldFile
        A FOLD file (a crease pattern, folded frames, or both), or such a file already read.
    reference : FoldFile, optional, keyword-only
        The file built again from the design it records, read as the file is: adds the
        ``rebuild`` check.
    **tolerances : float
        Any of :data:`CHECK_SPECS` by name (``isometry_tol``, ``planarity_tol``,
        ``fold_angle_tol``, ``flat_tol``, ``weld_tol``, ``rebuild_tol``); finite and ≥ 0.

    Raises
    ------
    InputError
        The file is not a FOLD file curvefold can read (the message names the key), or a
        tolerance is not a number ≥ 0.
    """
    specs = {spec.name: spec for spec in CHECK_SPECS}
    unknown = sorted(set(tolerances) - set(specs))
    if unknown:
        raise InputError(
            f"check_fold: unknown tolerance {unknown[0]!r} (allowed: {', '.join(specs)})"
        )
    tol = _DEFAULT | {name: specs[name].check(value) for name, value in tolerances.items()}
    doc = path if isinstance(path, FoldFile) else read_fold(path)
    cp = doc.crease_pattern
    folded = [
        _Frame(_label(doc, i, title), mesh, doc.is_flat_folded(i), doc.unrecorded_edges(i))
        for i, (title, mesh) in enumerate(doc.folded)
    ]
    frames = ([_Frame(_crease_label(doc), cp, pattern=True)] if cp is not None else []) + folded
    size = max(float(np.ptp(f.mesh.vertices_coords, axis=0).max()) for f in frames)
    base = frames[0].mesh
    differ = [
        f.label
        for f in frames[1:]
        if not (
            len(f.mesh.vertices_coords) == len(base.vertices_coords)
            and np.array_equal(f.mesh.edges_vertices, base.edges_vertices)
            and np.array_equal(f.mesh.faces_vertices, base.faces_vertices)
        )
    ]
    if differ:
        f = next(f for f in frames if f.label == differ[0])
        extra = len(f.mesh.vertices_coords) - len(base.vertices_coords)
        what = (
            f"{abs(extra)} vertices {'more' if extra > 0 else 'fewer'} than"
            if extra
            else "other edges or faces than"
        )
        reason = (
            f"{differ[0]} has {what} the "
            f"{frames[0].label.split(' (')[0] if cp is None else 'crease pattern'}"
        )
        checks = (FileCheck("topology", "fail", where=reason),) + tuple(
            FileCheck(name, "not run", reason="the frames do not share one topology")
            for name in _CHECK_NAMES[1:]
        )
        return FoldCheck(len(folded), checks, tol, doc.notes)
    found = [
        _topology(frames, size),
        _welds(doc, folded, size, tol["weld_tol"]),
        _edge_kinds(doc, frames[0]),
        _assignments(frames, tol["fold_angle_tol"], tol["flat_tol"]),
        _recorded_angles(folded, tol["fold_angle_tol"]),
        _isometry(cp, folded, tol["isometry_tol"]),
        _planarity(doc, folded, tol["planarity_tol"]),
    ]
    if reference is not None:
        found.append(_rebuild(doc, reference, [f.label for f in frames], size, tol))
    return FoldCheck(len(folded), tuple(found), tol, doc.notes)


def _label(doc: FoldFile, i: int, title: str) -> str:
    fid = doc.frame_id(i)
    return f"{'key frame' if fid == 0 else f'frame {fid}'} ({title!r})"


def _crease_label(doc: FoldFile) -> str:
    if doc.crease_frame is None:
        return "crease pattern (vertices_flatUnfoldCoords)"
    return (
        "key frame (crease pattern)"
        if doc.crease_frame == 0
        else f"frame {doc.crease_frame} (crease pattern)"
    )


def _not_run(name: str, unit: str, reason: str) -> FileCheck:
    return FileCheck(name, "not run", unit=unit, reason=reason)


# --------------------------------------------------------------------------------------
# the checks; each takes its frames and returns one FileCheck


def _ids(what: str) -> Callable[[np.ndarray], str]:
    """``ids -> "edges 3, 17, 40 (+12 more)"``."""

    def describe(ids: np.ndarray) -> str:
        shown = ", ".join(str(int(i)) for i in ids[:5])
        return f"{what} {shown}" + (f" (+{len(ids) - 5} more)" if len(ids) > 5 else "")

    return describe


def _judge(
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


def _topology(frames: list[_Frame], size: float) -> FileCheck:
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
        f"{label}: " + "; ".join(_ids(what)(distinct(ids)) for ids, what in listed if len(ids))
        for label, listed in problems.items()
        if any(len(ids) for ids, _ in listed)
    ]
    return FileCheck("topology", "fail" if found else "pass", where=" | ".join(found[:3]))


def _welds(doc: FoldFile, frames: list[_Frame], size: float, tolerance: float) -> FileCheck:
    if not {"curvefold:seam_partners", "curvefold:bonds"} & doc.keys:
        return _not_run(
            "welds",
            "relative",
            "the file does not say which edges are glued (no "
            "curvefold:seam_partners or curvefold:bonds; another tool may have dropped them)",
        )
    if not frames:
        return _not_run(
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

    return _judge("welds", "relative", tolerance, results, describe)


def _edge_kinds(doc: FoldFile, frame: _Frame) -> FileCheck:
    """A curvefold file's assignments against the one rule of its edge kinds."""
    if not {"edges_curvefold:kind", "curvefold:edges_kind"} & doc.keys:
        return _not_run(
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


def _assignments(frames: list[_Frame], slack: float, flat: float) -> FileCheck:
    results = []
    for f in frames:
        a = f.mesh.edges_assignment
        recorded = np.where(np.isin(np.arange(len(a)), f.unrecorded), 0.0, f.mesh.edges_foldAngle)
        # how far each M/V edge is recorded the wrong way, beyond the slack
        wrong = np.select(
            [a == "M", a == "V"],
            [np.fmax(recorded - slack, 0.0), np.fmax(-recorded - slack, 0.0)],
            0.0,
        )
        if not f.pattern:  # a folded frame: measured too
            measured = _measured(f.mesh)
            unfolded = np.isin(a, ("F", "J"))
            if f.flat:  # only whether an edge is folded through is measured: |angle| is 0 or 180
                bent = np.where(unfolded, np.fmax(np.abs(measured) - flat, 0.0), 0.0)
            else:
                bent = np.select(
                    [a == "M", a == "V", unfolded],
                    [
                        np.fmax(measured - slack, 0.0),
                        np.fmax(-measured - slack, 0.0),
                        np.fmax(np.abs(measured) - flat, 0.0),
                    ],
                    0.0,
                )
            # NaN stays
            wrong = np.maximum(
                wrong, np.where(np.isnan(measured) & ~np.isin(a, ("B", "U")), np.nan, bent)
            )
        results.append((f.label, wrong))
    return _judge("assignments", "°", 0.0, results, _ids("edges"))


def _measured(mesh: Mesh) -> np.ndarray:
    return dihedral_angles(mesh.vertices_coords, mesh.faces_vertices, mesh.edges_vertices)


def _recorded_angles(frames: list[_Frame], tolerance: float) -> FileCheck:
    if not frames:
        return _not_run("fold_angles", "°", "the file holds no folded frame")
    results, recorded_any = [], False
    for f in frames:
        sides = edges_faces(f.mesh.faces_vertices, f.mesh.edges_vertices)
        two = np.setdiff1d(np.flatnonzero((sides >= 0).all(axis=1)), f.unrecorded)
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
        results.append((f.label, _at_edges(error, two, len(f.mesh.edges_vertices))))
    if not recorded_any:
        return _not_run(
            "fold_angles",
            "°",
            "the file records no fold angle of an edge with two faces (no edges_foldAngle)",
        )
    return _judge("fold_angles", "°", tolerance, results, _ids("edges"))


def _at_edges(values: np.ndarray, ids: np.ndarray, edges: int) -> np.ndarray:
    """Values on a subset of edges spread over all edges (0 elsewhere), so ids stay edge ids."""
    out = np.zeros(edges)
    out[ids] = values
    return out


def _isometry(pattern: Mesh | None, frames: list[_Frame], tolerance: float) -> FileCheck:
    if pattern is None:
        return _not_run(
            "isometry",
            "relative",
            f"the file holds no crease pattern: {NEEDS_CREASE_PATTERN['isometry']}",
        )
    if not frames:
        return _not_run(
            "isometry",
            "relative",
            "the file holds no folded frame to compare with its crease pattern",
        )
    base = pattern.edge_lengths()
    with np.errstate(invalid="ignore", divide="ignore"):
        results = [(f.label, np.abs(f.mesh.edge_lengths() / base - 1)) for f in frames]
    return _judge("isometry", "relative", tolerance, results, _ids("edges"))


def _planarity(doc: FoldFile, frames: list[_Frame], tolerance: float) -> FileCheck:
    ref = frames[0].mesh if frames else doc.crease_pattern
    assert ref is not None  # a file holds a crease pattern or a folded frame (read_fold)
    polygons = ref.faces_vertices.shape[1] > 3
    kinds_known = bool({"edges_curvefold:kind", "curvefold:edges_kind"} & doc.keys)
    joins = (ref.edges_assignment == "J").any()
    if not frames:
        return _not_run("face_planarity", "°", "the file holds no folded frame")
    if not polygons and not kinds_known and not joins:
        return _not_run(
            "face_planarity",
            "°",
            "every face is a triangle, planar by definition; "
            "without edges_curvefold:kind the diagonals that split ruling quads are not known",
        )
    results = []
    for f in frames:
        triangles = f.mesh.triangulated()
        if kinds_known:
            flat = triangles.edges_kind == "diagonal"
        else:  # the reader calls every F edge a diagonal; only the fan's are, and the joins
            flat = np.arange(len(triangles.edges_vertices)) >= len(f.mesh.edges_vertices)
        flat |= triangles.edges_assignment == "J"
        diagonal = np.flatnonzero(flat)
        bend = np.abs(
            dihedral_angles(
                triangles.vertices_coords,
                triangles.faces_vertices,
                triangles.edges_vertices[diagonal],
            )
        )
        results.append((f.label, _at_edges(bend, diagonal, len(triangles.edges_vertices))))
    what = "fan diagonals (numbered after the file's edges)" if polygons else "diagonal edges"
    return _judge(
        "face_planarity", "°", tolerance, results, _ids(what + (" and join edges" if joins else ""))
    )


def _rebuild(
    doc: FoldFile, reference: FoldFile, labels: list[str], size: float, tol: dict
) -> FileCheck:
    """Every array the rebuilt file holds against the file's (its frames named by ``labels``):
    what differs is named."""
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
                f"{_ids('rows')(np.flatnonzero((a != b).reshape(len(a), -1).any(axis=1)))}"
            )
    # fold angles as the coordinates' tolerance allows: an angle moves by about the coordinates'
    # error over the shortest edge
    angle_tol = math.degrees(tol["rebuild_tol"] * size / float(first.edge_lengths().min()))
    for (title, m), (_, r) in zip(mine, theirs):
        if m.edges_foldAngle.shape == r.edges_foldAngle.shape:
            off = np.flatnonzero(~(np.abs(m.edges_foldAngle - r.edges_foldAngle) <= angle_tol))
            if off.size:
                differ.append(
                    f"{title}: edges_foldAngle at {_ids('edges')(off)} (more than {angle_tol:.1g}°)"
                )
    if titles != [t for t, _ in reference.folded]:
        differ.append(f"frame titles {titles} (rebuilt {[t for t, _ in reference.folded]})")
    if doc.classes != reference.classes:
        differ.append(
            f"frame_classes {[list(c) for c in doc.classes]} (rebuilt "
            f"{[list(c) for c in reference.classes]})"
        )
    for what, a, b in (
        ("curvefold:seam_partners", doc.seam_partners, reference.seam_partners),
        ("curvefold:bonds", doc.bonds, reference.bonds),
    ):
        if not np.array_equal(a, b):
            differ.append(f"{what}: {len(a)} pairs, the rebuilt {len(b)}, not the same")
    results = [
        (title, np.abs(m.vertices_coords - r.vertices_coords).max(axis=1) / size)
        for (title, m), (_, r) in zip(mine, theirs)
    ]
    coords = _judge("rebuild", "relative", tol["rebuild_tol"], results, _ids("vertices"))
    if not differ:
        return coords
    where = "; ".join(([coords.where] if coords.status == "fail" else []) + differ[:4]) + (
        f" (+{len(differ) - 4} more)" if len(differ) > 4 else ""
    )
    return FileCheck("rebuild", "fail", coords.value, coords.tolerance, "relative", where)
