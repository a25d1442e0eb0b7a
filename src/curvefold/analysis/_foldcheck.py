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
``record``
    a curvefold file's record (``curvefold:metadata``, ``curvefold:design``, ``frame_unit``)
    against its geometry: its frames and their fold angles, seam partners and bonds, sheets,
    radius, mesh deviation and stretch (:mod:`curvefold.analysis._fold_record`).
``crease_angles``
    a smooth curvefold design's fold creases, measured in every folded frame, against the
    frame's recorded fold angle 2α (the certificate's ``fold_angles``, on the file); not
    listed for rigid panels, whose fold lines fold by their own angles.
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

import os

import numpy as np

from ..io._fold_reading import FoldFile, read_fold
from ..kernel._errors import InputError
from ..kernel._validate import Spec
from . import _fold_checks as checks
from ._checks import CHECKS
from ._fold_checks import NEEDS_CREASE_PATTERN, Frame
from ._fold_rebuild import rebuild
from ._fold_record import crease_angles, record
from ._fold_results import FileCheck, FoldCheck
from ._promises import promised_tolerances, written_precision

__all__ = ["CHECK_SPECS", "FileCheck", "FoldCheck", "check_fold", "NEEDS_CREASE_PATTERN"]

_CAP = {spec.name: spec.cap for spec in CHECKS}

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
        "crease_angle_tol",
        "real",
        1.0,
        "[0, 180]",
        "degrees",
        help="largest difference between a fold crease's dihedral angle and its frame's recorded "
        "fold angle 2α (twice the default bend bound: each triangle beside a crease tilts from "
        "the sheet by at most the fold across its diagonal)",
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
_CHECK_NAMES = (
    "topology",
    "welds",
    "edge_kinds",
    "assignments",
    "fold_angles",
    "isometry",
    "face_planarity",
    "record",
    "crease_angles",
)


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
        Those not given are what a curvefold file promises
        (:func:`~curvefold.analysis._promises.promised_tolerances`: its recorded mesh
        tolerance and written precision), else the defaults.

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
    doc = path if isinstance(path, FoldFile) else read_fold(path)
    promised, sources = promised_tolerances(doc)
    given = {name: specs[name].check(value) for name, value in tolerances.items()}
    tol = _DEFAULT | promised | given
    sources = {name: how for name, how in sources.items() if name not in given}
    cp = doc.crease_pattern
    folded = [
        Frame(_label(doc, i, title), mesh, doc.is_flat_folded(i), doc.unrecorded_edges(i))
        for i, (title, mesh) in enumerate(doc.folded)
    ]
    frames = ([Frame(_crease_label(doc), cp, pattern=True)] if cp is not None else []) + folded
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
        unshared = (FileCheck("topology", "fail", where=reason),) + tuple(
            FileCheck(name, "not run", reason="the frames do not share one topology")
            for name in _CHECK_NAMES[1:]
        )
        return FoldCheck(len(folded), unshared, tol, doc.notes, sources)
    found = [
        checks.topology(frames, size),
        checks.welds(doc, folded, size, tol["weld_tol"]),
        checks.edge_kinds(doc, frames[0]),
        checks.assignments(frames, tol["fold_angle_tol"], tol["flat_tol"]),
        checks.recorded_angles(folded, tol["fold_angle_tol"]),
        checks.isometry(cp, folded, tol["isometry_tol"]),
        checks.planarity(doc, folded, tol["planarity_tol"]),
        record(doc, max(written_precision(f.mesh.vertices_coords) for f in frames)),
    ]
    found += [c for c in (crease_angles(doc, tol["crease_angle_tol"]),) if c is not None]
    if reference is not None:
        found.append(rebuild(doc, reference, [f.label for f in frames], size, tol))
    return FoldCheck(len(folded), tuple(found), tol, doc.notes, sources)


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
