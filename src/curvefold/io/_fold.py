"""Writing FOLD 1.1 files: a crease pattern with its folded states, and a single sheet.

Layout written by :func:`write_fold` (one shared vertex/edge/face topology):

* key frame (frame 0): the crease pattern, 2D ``vertices_coords`` (every sheet seen from
  the side its normals point to, so faces are counter-clockwise as FOLD requires),
  ``frame_classes`` ``["creasePattern"]``, ``edges_foldAngle`` at the design state;
* ``file_frames[i]``: folded state i, ``frame_classes`` ``["foldedForm"]``,
  ``frame_parent: 0``, ``frame_inherit: true``, overriding only ``vertices_coords`` (3D)
  and ``edges_foldAngle``;
* ``edges_assignment``: ``M``/``V`` on fold creases, ``B`` on boundaries and seams, ``F``
  on rulings and triangulating diagonals; ``edges_foldAngle`` in degrees, valley
  positive, the dihedral angle measured in that frame on every edge with two faces
  (the sheets of a curved fold bend a little across rulings and diagonals too, so a
  folder that follows the angles lands on the frame), 0 on ``B`` edges;
* custom keys (namespaced per the FOLD spec): ``edges_curvefold:kind`` (the edge kind,
  named like a per-edge property so that FOLD tools that renumber edges keep it in step),
  ``faces_curvefold:group``, ``curvefold:seam_partners`` (pairs of edge indices glued
  together: the two sides of a seam), ``curvefold:bonds`` (pairs of edge indices of
  different tubes glued together where the tubes touch), ``curvefold:metadata`` (design
  parameters) and, when the design is known, ``curvefold:design`` (the design, as a
  design file holds it, with the fold angles, anchor and faces of the frames: enough to
  build the file again, ``curvefold check --rebuild``).

:func:`write_sheet_fold` writes one sheet in the form Origami Simulator loads: it needs
``vertices_coords``, ``edges_vertices``, ``edges_assignment`` and ``faces_vertices``, takes
``edges_foldAngle`` in degrees as the target angles (the sheet's own, on its ``F`` rulings
and diagonals too, so that it folds onto the design and not onto a sheet flat between its
creases), maps 2D coordinates ``(x, y)`` to its
``(x, 0, y)`` and starts from the given 3D coordinates otherwise; every ``M``/``V``/``F``
edge must have a face on each side.

A structure's arrays come from :func:`curvefold.geometry._fold_arrays.fold_arrays` (the
conversion is geometry's); this module serialises them. Files are read back, and checked
key by key, by :func:`curvefold.io.read_fold`.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from ..geometry._fold_arrays import FoldArrays, fold_arrays, structure_metadata
from ..geometry._mesh import EDGE_KINDS, Mesh, face_sides, vector_areas
from ..geometry._standing import standing_frames
from ..geometry._structure import Structure
from ..geometry._topology import fold_assignment
from ..kernel._arrays import distinct
from ..kernel._errors import InputError
from ..kernel._text import one_line
from ._atomic import atomic_write
from ._decimals import Decimals, Integers, dumps, plain
from ._fold_reading import FoldFile
from ._mesh3d import check_metadata
from ._output import FoldOutput
from ._tables import CREATOR

__all__ = [
    "fold_assignments",
    "fold_document",
    "fold_model",
    "model_document",
    "to_fold",
    "write_fold",
    "write_model",
    "write_sheet_fold",
    "write_structure_fold",
]

FILE_SPEC = 1.1
#: Coordinates are written to this fraction of their sheet's size (the crease pattern's, a
#: frame's): far below what the checks of a file resolve (``curvefold check``: welds and
#: rebuilt coordinates to 1e-9 of the size, isometry to 1e-3) and above the rounding of
#: the geometry (about 1e-15 of the size), with no digits beyond it.
COORDINATE_RTOL = 1e-12
#: Decimal places of a fold angle written, in degrees (the checks resolve 1e-9° and more).
ANGLE_DECIMALS = 10


def fold_assignments(
    edges_kind: np.ndarray, edges_foldAngle: np.ndarray, edges_assignment: np.ndarray
) -> np.ndarray:
    """FOLD assignment of every edge of a cut-open crease pattern from its kind.

    :func:`curvefold.geometry._topology.fold_assignment` with the seams open: ``B`` for
    boundaries and seams, ``F`` for rulings and diagonals; a fold crease is ``V`` where its
    angle is positive, ``M`` where negative, and where the angle is 0 it keeps its given
    ``M``/``V`` (``F`` if it has neither).

    Parameters
    ----------
    edges_kind : (E,) array of str
    edges_foldAngle : (E,) array of float
        Degrees, valley positive.
    edges_assignment : (E,) array of str

    Returns
    -------
    (E,) ndarray of str

    Examples
    --------
    >>> fold_assignments(
    ...     np.array(["fold", "fold", "seam", "ruling"]),
    ...     np.array([30.0, 0.0, 5.0, 0.0]),
    ...     np.array(["M", "M", "V", "F"]),
    ... ).tolist()
    ['V', 'M', 'B', 'F']
    """
    kind = np.asarray(edges_kind)
    angle = np.asarray(edges_foldAngle, float)
    given = np.asarray(edges_assignment)
    keep = (kind == "fold") & (angle == 0) & np.isin(given, ("M", "V"))
    return np.where(keep, given, fold_assignment(kind, angle, seams_open=True)).astype("<U1")


def _edge_face_counts(mesh: Mesh, what: str) -> np.ndarray:
    """Number of faces on every edge (either direction), shape (E,); checks face sides are edges."""
    V = len(mesh.vertices_coords)
    ev = np.sort(mesh.edges_vertices.astype(np.int64), axis=1)
    keys = ev[:, 0] * V + ev[:, 1]
    sides, side_face = face_sides(mesh.faces_vertices)
    sides = np.sort(sides, axis=1)
    side_keys = sides[:, 0] * V + sides[:, 1]
    order = np.argsort(keys)
    pos = np.clip(np.searchsorted(keys[order], side_keys), 0, max(len(keys) - 1, 0))
    found = keys[order][pos] == side_keys if len(keys) else np.zeros(len(side_keys), bool)
    if not found.all():
        i = int(np.flatnonzero(~found)[0])
        raise InputError(
            f"{what}: face {side_face[i]} side {sides[i].tolist()} is not an edge in edges_vertices"
        )
    return np.bincount(order[pos], minlength=len(keys))


def _check_sheet(mesh: Mesh, assignment: np.ndarray, what: str) -> None:
    """Mesh indices in range, M/V/F edges with two faces, B edges with one."""
    V, E = len(mesh.vertices_coords), len(mesh.edges_vertices)
    faces = mesh.faces_vertices
    for name, idx in (
        ("edges_vertices", mesh.edges_vertices),
        ("faces_vertices", faces[faces >= 0]),
    ):
        if idx.size and (idx.min() < 0 or idx.max() >= V):
            raise InputError(
                f"{what}.{name} refers to vertices outside [0, {V}), got "
                f"{int(idx.min())}..{int(idx.max())}"
            )
    if not np.isfinite(mesh.vertices_coords).all():
        raise InputError(f"{what}.vertices_coords must be finite")
    angle = np.asarray(mesh.edges_foldAngle, float)
    if not (np.isfinite(angle) & (np.abs(angle) <= 180)).all():
        raise InputError(f"{what}.edges_foldAngle must be finite degrees in [-180, 180]")
    bad_kind = ~np.isin(mesh.edges_kind, EDGE_KINDS)
    if bad_kind.any():
        e = int(np.flatnonzero(bad_kind)[0])
        raise InputError(
            f"{what}.edges_kind[{e}] must be one of {EDGE_KINDS}, got {mesh.edges_kind[e]!r}"
        )
    counts = _edge_face_counts(mesh, what)
    want = np.where(assignment == "B", 1, 2)
    wrong = counts != want
    if wrong.any():
        e = int(np.flatnonzero(wrong)[0])
        hint = (
            "; a seam must be two boundary edges, one per sheet, paired in seam_partners"
            if mesh.edges_kind[e] == "seam"
            else ""
        )
        raise InputError(
            f"{what}: edge {e} ({mesh.edges_kind[e]}, assignment {assignment[e]}) has "
            f"{counts[e]} faces, expected {want[e]} ({int(wrong.sum())} of {E} edges are "
            f"wrong){hint}"
        )


def _flat_ccw_coords(mesh: Mesh, what: str, flat_tol: float, mirror_clockwise: bool) -> np.ndarray:
    """2D coordinates (V, 2) of a flat mesh with every sheet counter-clockwise.

    A sheet (a set of faces connected through shared vertices) whose triangles are all
    clockwise is mirrored, y → 2·c − y about its centre c, when ``mirror_clockwise``;
    that is the same sheet seen from the side its normals point to. The sheets are found
    only when a face is clockwise (a mesh of counter-clockwise faces is left as it is).
    """
    x = np.asarray(mesh.vertices_coords, float)
    V = len(x)
    size = float(np.ptp(x, axis=0).max()) if V else 0.0
    zmax = float(np.abs(x[:, 2]).max()) if V else 0.0
    if zmax > flat_tol * max(size, 1e-300):
        raise InputError(
            f"{what} must be flat (z = 0): max |z| = {zmax:.3g}, allowed "
            f"{flat_tol:g} x size {size:.3g}"
        )
    xy = x[:, :2].copy()
    f = np.asarray(mesh.faces_vertices)
    if len(f) == 0:
        return xy
    area2 = vector_areas(xy, f)[:, 2]
    if mirror_clockwise and (area2 < 0).any():
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components

        pairs = face_sides(f)[0]
        graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(V, V))
        face_sheet = connected_components(graph, directed=False)[1][f[:, 0]]
        for sheet in distinct(face_sheet):
            faces = np.flatnonzero(face_sheet == sheet)
            if (area2[faces] < 0).all():
                verts = distinct(f[faces][f[faces] >= 0])
                centre = 0.5 * (xy[verts, 1].min() + xy[verts, 1].max())
                xy[verts, 1] = 2 * centre - xy[verts, 1]
                area2[faces] = -area2[faces]
    bad = area2 <= 0
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise InputError(
            f"{what}: FOLD needs counter-clockwise faces in the crease pattern, but "
            f"{int(bad.sum())} of {len(area2)} faces are clockwise or degenerate (first: "
            f"face {i}, signed area {area2[i] / 2:.3g})"
            + (
                "; a sheet with both orientations cannot be fixed by mirroring"
                if mirror_clockwise
                else ""
            )
        )
    return xy


def _coordinate_lists(x: np.ndarray) -> Decimals | list:
    """Coordinates (V, d) to :data:`COORDINATE_RTOL` of the sheet's size: rounded to the power
    of ten at or below it, so a number has no more digits than that holds."""
    x = np.asarray(x, float)
    size = float(np.ptp(x, axis=0).max()) if x.size else 0.0
    if not size > 0:
        return x.tolist()
    return Decimals.round(x, int(-np.floor(np.log10(COORDINATE_RTOL * size))))


def _angle_lists(angles: np.ndarray, zero: np.ndarray) -> Decimals:
    """Fold angles in degrees to :data:`ANGLE_DECIMALS` places, 0 where ``zero``."""
    return Decimals.round(np.where(zero, 0.0, np.asarray(angles, float)), ANGLE_DECIMALS)


def _face_lists(faces: np.ndarray) -> Integers | list:
    """Faces (F, k), -1 padded, as FOLD's lists of vertex ids, each as long as its polygon."""
    if not (faces < 0).any():
        return Integers(faces)
    return [[v for v in row if v >= 0] for row in faces.tolist()]


def _check_pairs(value, edges: int, name: str, rows: str) -> np.ndarray:
    """Pairs of edge indices in [0, edges), shape (``rows``, 2); none for None."""
    if value is None:
        return np.zeros((0, 2), np.int64)
    try:
        pairs = np.asarray(value, dtype=np.int64).reshape(-1, 2)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name} must be ({rows}, 2) edge indices, got {value!r}") from exc
    if pairs.size and (pairs.min() < 0 or pairs.max() >= edges):
        raise InputError(
            f"{name} must be edge indices in [0, {edges}), got "
            f"{int(pairs.min())}..{int(pairs.max())}"
        )
    return pairs


def _check_seam_partners(seam_partners, assignment: np.ndarray) -> np.ndarray:
    pairs = _check_pairs(seam_partners, len(assignment), "seam_partners", "P")
    if (pairs[:, 0] == pairs[:, 1]).any():
        raise InputError("seam_partners pairs an edge with itself")
    not_b = pairs.size and (assignment[pairs] != "B").any()
    if not_b:
        e = int(pairs[assignment[pairs] != "B"][0])
        raise InputError(
            f"seam_partners: edge {e} is not a boundary (B) edge, so it cannot be glued"
        )
    return pairs


def _document(title: str, frame: dict) -> dict:
    """A FOLD document: curvefold's file keys, the title if any, then ``frame``'s keys."""
    return {
        "file_spec": FILE_SPEC,
        "file_creator": CREATOR,
        "file_classes": ["singleModel"],
        **({"file_title": one_line(title)} if title else {}),
        **frame,
    }


def _write_document(path: str | os.PathLike, doc: dict) -> Path:
    """Write a document whose number arrays are :class:`~curvefold.io._decimals.Decimals` (JSON
    as their lists)."""
    return atomic_write(path, dumps(doc) + "\n")


def write_fold(
    path: str | os.PathLike,
    model: FoldFile,
    *,
    title: str = "",
    flat_tol: float = 1e-9,
    mirror_clockwise: bool = True,
) -> Path:
    """Write a crease pattern and its folded states as one FOLD 1.1 file: :func:`fold_document`,
    atomically.

    Parameters
    ----------
    path : path-like
    model : FoldFile
        The crease pattern, its folded frames and what the file records with them
        (:func:`to_fold`, :func:`~curvefold.io._single_fold.single_fold_model`, or a
        :class:`~curvefold.io.FoldFile` made or read).
    title, flat_tol, mirror_clockwise : keyword-only
        As in :func:`fold_document`.

    Returns
    -------
    Path
    """
    return _write_document(path, _fold_frames(model, title, flat_tol, mirror_clockwise))


def fold_document(
    model: FoldFile, *, title: str = "", flat_tol: float = 1e-9, mirror_clockwise: bool = True
) -> dict:
    """A crease pattern and its folded states as one FOLD 1.1 document (JSON data, as
    :func:`write_fold` writes it).

    Parameters
    ----------
    model : FoldFile
        What the file holds:

        ``crease_pattern``
            The flat crease pattern (z = 0, counter-clockwise faces) with the fold angles
            of the design state. Seams are cut open: each seam is two boundary edges, one
            per sheet, paired in ``seam_partners``.
        ``folded``
            Title and state (Mesh) of each folded frame; each Mesh has the crease
            pattern's topology (same ``edges_vertices``, ``faces_vertices``, ``edges_kind``).
        ``metadata``
            Design parameters (str to number or str), stored under ``curvefold:metadata``.
        ``unit``
            Length unit (``frame_unit``), e.g. ``"m"``, ``"mm"``, ``"unit"``.
        ``seam_partners``
            (P, 2) pairs of boundary edge indices glued together in the folded structure.
        ``bonds``
            (Q, 2) pairs of edge indices of different sheets that coincide in the folded
            structure (tubes glued where they touch).
        ``design``
            The design and how the frames were made (:func:`to_fold`), stored as
            ``curvefold:design``; JSON data, or None.
    title : str, keyword-only
        ``file_title`` (omitted when empty), on one line without control characters.
    flat_tol : float, keyword-only
        Allowed ``max |z|`` of the crease pattern relative to its size.
    mirror_clockwise : bool, keyword-only
        Mirror (y → −y about its centre) every sheet of the crease pattern whose
        triangles are all clockwise, so that it is seen from the side its normals point
        to, as FOLD requires; the folded frames and fold angles are unchanged. If False,
        such a sheet is an error.

    Returns
    -------
    dict

    Raises
    ------
    InputError
        On a missing or non-flat crease pattern, a sheet with both clockwise and
        counter-clockwise (or degenerate) triangles, topology that differs between frames,
        a crease edge without two faces, a non-boundary seam partner, bad metadata or a
        design that is not JSON data.
    """
    return plain(_fold_frames(model, title, flat_tol, mirror_clockwise))


def _fold_frames(model: FoldFile, title: str, flat_tol: float, mirror_clockwise: bool) -> dict:
    """:func:`fold_document` with its number arrays as :class:`~curvefold.io._decimals.Decimals`."""
    cp = model.crease_pattern
    if not isinstance(cp, Mesh):
        raise InputError(
            f"the model's crease_pattern must be a Mesh, got {type(cp).__name__}",
            parameter="crease_pattern",
        )
    assignment = fold_assignments(cp.edges_kind, cp.edges_foldAngle, cp.edges_assignment)
    _check_sheet(cp, assignment, "crease_pattern")
    cp_xy = _flat_ccw_coords(cp, "crease_pattern", flat_tol, mirror_clockwise)
    pairs = _check_seam_partners(model.seam_partners, assignment)
    glued = _check_pairs(model.bonds, len(assignment), "bonds", "Q")
    meta = check_metadata(model.metadata)
    design = model.design
    if design is not None:
        try:
            json.dumps(dict(design), allow_nan=False)
        except (TypeError, ValueError) as exc:
            raise InputError(
                f"design must be JSON data (numbers, strings, lists, objects): {exc}"
            ) from None
    zero = assignment == "B"  # one face: no dihedral angle

    frames = []
    for i, item in enumerate(model.folded):
        try:
            frame_title, mesh = item
        except (TypeError, ValueError) as exc:
            raise InputError(f"folded[{i}] must be a (title, Mesh) pair, got {item!r}") from exc
        for name in ("edges_vertices", "faces_vertices", "edges_kind"):
            if not np.array_equal(getattr(mesh, name), getattr(cp, name)):
                raise InputError(
                    f"folded[{i}] ({frame_title!r}): {name} differs from the crease "
                    "pattern's; all frames must share one topology"
                )
        x = np.asarray(mesh.vertices_coords, float)
        angle = np.asarray(mesh.edges_foldAngle, float)
        if not np.isfinite(x).all() or x.shape != cp.vertices_coords.shape:
            raise InputError(
                f"folded[{i}] ({frame_title!r}): vertices_coords must be finite "
                f"with shape {cp.vertices_coords.shape}"
            )
        if not (np.isfinite(angle) & (np.abs(angle) <= 180)).all():
            raise InputError(
                f"folded[{i}] ({frame_title!r}): edges_foldAngle must be finite "
                "degrees in [-180, 180]"
            )
        frames.append(
            {
                "frame_title": one_line(frame_title),
                "frame_classes": ["foldedForm"],
                "frame_parent": 0,
                "frame_inherit": True,
                "vertices_coords": _coordinate_lists(x),
                "edges_foldAngle": _angle_lists(angle, zero),
            }
        )

    return _document(
        title,
        {
            "frame_title": "crease pattern",
            "frame_classes": ["creasePattern"],
            "frame_unit": model.unit,
            "vertices_coords": _coordinate_lists(cp_xy),
            "edges_vertices": Integers(cp.edges_vertices),
            "edges_assignment": assignment.tolist(),
            "edges_foldAngle": _angle_lists(cp.edges_foldAngle, zero),
            "faces_vertices": _face_lists(cp.faces_vertices),
            "edges_curvefold:kind": cp.edges_kind.tolist(),
            "faces_curvefold:group": Integers(np.asarray(cp.faces_group)),
            "curvefold:seam_partners": Integers(pairs),
            "curvefold:bonds": Integers(glued),
            "curvefold:metadata": meta,
            **({"curvefold:design": dict(design)} if design is not None else {}),
            "file_frames": frames,
        },
    )


def write_sheet_fold(
    path: str | os.PathLike,
    sheet: Mesh,
    unit: str = "unit",
    *,
    title: str = "",
    flat_tol: float = 1e-9,
    mirror_clockwise: bool = True,
) -> Path:
    """Write one sheet as a single-frame FOLD file that Origami Simulator can load.

    A flat sheet (all z within ``flat_tol`` of 0) is written with 2D coordinates as a
    ``creasePattern`` frame; its ``edges_foldAngle`` are then the simulator's target
    angles. A non-flat sheet is written with 3D coordinates as a ``foldedForm`` frame.

    Parameters
    ----------
    path : path-like
    sheet : Mesh
        One connected sheet: every fold/ruling/diagonal edge has two faces, every
        boundary/seam edge one.
    unit : str
        ``frame_unit``.
    title : str
        ``file_title`` (omitted when empty), on one line without control characters.
    flat_tol : float
        Allowed ``max |z|`` relative to the sheet's size to count as flat.
    mirror_clockwise : bool
        As in :func:`write_fold`, for a flat sheet.

    Returns
    -------
    Path
    """
    assignment = fold_assignments(sheet.edges_kind, sheet.edges_foldAngle, sheet.edges_assignment)
    _check_sheet(sheet, assignment, "sheet")
    x = np.asarray(sheet.vertices_coords, float)
    size = float(np.ptp(x, axis=0).max()) if len(x) else 0.0
    flat = len(x) == 0 or float(np.abs(x[:, 2]).max()) <= flat_tol * max(size, 1e-300)
    if flat:
        x = _flat_ccw_coords(sheet, "sheet", flat_tol, mirror_clockwise)
    return _write_document(
        path,
        _document(
            title,
            {
                "frame_classes": ["creasePattern" if flat else "foldedForm"],
                "frame_unit": unit,
                "vertices_coords": _coordinate_lists(x),
                "edges_vertices": Integers(sheet.edges_vertices),
                "edges_assignment": assignment.tolist(),
                "edges_foldAngle": _angle_lists(sheet.edges_foldAngle, assignment == "B"),
                "faces_vertices": _face_lists(sheet.faces_vertices),
                "edges_curvefold:kind": sheet.edges_kind.tolist(),
            },
        ),
    )


# ---------------------------------------------------------------------------------------
# structures


def to_fold(
    structure: Structure,
    output: FoldOutput = FoldOutput(),
    *,
    fold_angles: ArrayLike | None = None,
    fold_angle: float | None = None,
    degrees: bool = True,
) -> FoldFile:
    """A structure as a FOLD model: crease pattern plus folded states on one topology.

    The arrays are :func:`curvefold.geometry._fold_arrays.fold_arrays` of the structure (every
    sheet in a row, seams cut open and paired, the folded frames on the same vertices, the
    measured fold angles of every frame); the metadata is
    :func:`~curvefold.geometry.structure_metadata` with the output's metadata over it.

    Parameters
    ----------
    structure : Structure
    output : FoldOutput
        Unit, extra metadata, anchor, faces, the samples kept and the design recorded.
    fold_angles, fold_angle, degrees : keyword-only
        As in :func:`~curvefold.geometry._fold_arrays.fold_arrays`: the frames' fold angles
        (default the design angle only) and the design angle the crease pattern carries.

    Returns
    -------
    curvefold.io.FoldFile
        What :func:`write_structure_fold` writes and :func:`curvefold.io.read_fold`
        reads back.

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice
    >>> tube = Structure.tube(
    ...     Lattice.from_crease(
    ...         Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=9)), 0.1, 0.1
    ...     )
    ... )
    >>> output = FoldOutput(unit="m", metadata={"title": "tube"})
    >>> model = to_fold(tube, output, fold_angles=[45, 90])
    >>> [title for title, _ in model.folded], model.metadata["title"], model.metadata["tubes"]
    (['fold angle 45°', 'fold angle 90°'], 'tube', 1)
    """
    _check_fold_output(output)
    arrays = fold_arrays(
        structure,
        fold_angles=fold_angles,
        fold_angle=fold_angle,
        degrees=degrees,
        anchor=output.anchor,
        faces=output.faces,
        keep=output.keep,
    )
    return fold_model(structure, arrays, output)


def fold_model(
    structure: Structure, arrays: FoldArrays, output: FoldOutput = FoldOutput()
) -> FoldFile:
    """:func:`to_fold` of a structure whose FOLD arrays are made
    (:func:`curvefold.geometry._fold_arrays.fold_arrays` with the output's ``anchor``, ``faces``
    and ``keep``), so that their developed sheets serve other files too (``arrays.sheets``)."""
    extra = _check_fold_output(output)
    meta = check_metadata({**structure_metadata(structure, arrays.fold_angle), **extra})
    folded = standing_frames(arrays) if output.ground else arrays.folded
    keep = output.keep
    record = (
        None
        if output.design is None
        else {
            "design": dict(output.design),
            "fold_angles": arrays.fold_angles.tolist(),
            "anchor": output.anchor,
            "faces": output.faces,
            "keep": None if keep is None else [np.asarray(k).tolist() for k in keep],
        }
        | ({"ground": True} if output.ground else {})
    )
    return FoldFile(
        crease_pattern=arrays.crease_pattern,
        folded=folded,
        metadata=meta,
        unit=output.unit,
        seam_partners=arrays.seam_partners,
        bonds=arrays.bonds,
        design=record,
    )


def _check_fold_output(output: FoldOutput) -> dict:
    """The output's extra metadata, checked with its unit."""
    if not isinstance(output, FoldOutput):
        raise InputError(
            f"output must be a FoldOutput (unit, metadata…), got {type(output).__name__}",
            parameter="output",
        )
    if not isinstance(output.unit, str) or not output.unit:
        raise InputError(f"unit must be a non-empty str, got {output.unit!r}")
    return check_metadata(output.metadata)


def write_structure_fold(
    path: str | os.PathLike,
    structure: Structure,
    output: FoldOutput = FoldOutput(),
    *,
    title: str = "",
    fold_angles: ArrayLike | None = None,
    fold_angle: float | None = None,
    degrees: bool = True,
) -> Path:
    """Write :func:`to_fold` of a structure as a FOLD 1.1 file (via
    :func:`curvefold.io.write_fold`).

    Parameters
    ----------
    path : path-like
    structure : Structure
    output : FoldOutput
        As in :func:`to_fold`.
    title : str, keyword-only
        ``file_title``.
    fold_angles, fold_angle, degrees : keyword-only
        As in :func:`to_fold`.

    Returns
    -------
    Path
    """
    return write_fold(
        path,
        to_fold(structure, output, fold_angles=fold_angles, fold_angle=fold_angle, degrees=degrees),
        title=title,
    )


def write_model(path: str | os.PathLike, model: FoldFile, *, title: str = "") -> Path:
    """Write a FOLD model (:func:`to_fold`, or a single fold's
    :func:`curvefold.io._single_fold.single_fold_model`): :func:`write_fold` with the default
    tolerance and mirroring."""
    return write_fold(path, model, title=title)


def model_document(model: FoldFile, *, title: str = "") -> dict:
    """The FOLD document of a model (:func:`to_fold`), as :func:`write_structure_fold` writes it.

    :func:`curvefold.io._fold_reading.parse_fold` reads it back as :func:`read_fold` reads the
    file (``curvefold check --rebuild`` compares a file with the document of its design).
    """
    return fold_document(model, title=title)
