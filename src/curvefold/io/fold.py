"""FOLD 1.1 files: a crease pattern with its folded states, a single sheet, and a reader.

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
``edges_foldAngle`` in degrees as the target angles, maps 2D coordinates ``(x, y)`` to its
``(x, 0, y)`` and starts from the given 3D coordinates otherwise; every ``M``/``V``/``F``
edge must have a face on each side.
"""

from __future__ import annotations

import json
import os
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Literal

import numpy as np

from ..geometry.mesh import EDGE_KINDS, Mesh, edges_faces, face_sides, vector_areas
from ..geometry.mesh import fold_angles as dihedral_angles
from ..geometry.sheets import _angles, _check_structure, _design_angle, _develop, bonds, folding_motion
from ..geometry.structure import Structure
from ..geometry.topology import Topology, fold_assignment
from ..kernel.arrays import readonly
from ..kernel.errors import InputError, InternalError
from ..kernel.text import one_line
from ..kernel.validate import is_integer
from .atomic import atomic_write
from .mesh3d import check_metadata
from .reading import read_bytes
from .tables import CREATOR

__all__ = ["FoldFile", "fold_assignments", "read_fold", "to_fold", "write_fold", "write_sheet_fold", "write_structure_fold"]

FILE_SPEC = 1.1
#: Assignments curvefold writes and reads.
ASSIGNMENTS = ("M", "V", "B", "F")
#: Largest FOLD file read, in bytes: parsing holds about 10 bytes per byte of JSON (measured
#: on curvefold's own files), so about 1.3 GB at the limit.
MAX_FOLD_BYTES = 128 << 20
#: Most frames read from ``file_frames``.
MAX_FRAMES = 1000
#: Most vertices, edges and faces over all frames (an inheriting frame counts what it inherits):
#: about 50 bytes each once read, 400 MB at the limit.
MAX_FOLD_ITEMS = 8_000_000
#: Edge kind assumed for files without ``edges_curvefold:kind``.
_KIND_OF_ASSIGNMENT = {"M": "fold", "V": "fold", "B": "boundary", "F": "diagonal"}
_KIND_KEYS = ("edges_curvefold:kind", "curvefold:edges_kind")
_GROUP_KEYS = ("faces_curvefold:group", "curvefold:faces_group")


def fold_assignments(edges_kind: np.ndarray, edges_foldAngle: np.ndarray, edges_assignment: np.ndarray) -> np.ndarray:
    """FOLD assignment of every edge of a cut-open crease pattern from its kind.

    :func:`curvefold.geometry.topology.fold_assignment` with the seams open: ``B`` for
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
    >>> fold_assignments(np.array(["fold", "fold", "seam", "ruling"]), np.array([30., 0., 5., 0.]),
    ...                  np.array(["M", "M", "V", "F"])).tolist()
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
        raise InputError(f"{what}: face {side_face[i]} side {sides[i].tolist()} is not an edge in edges_vertices")
    return np.bincount(order[pos], minlength=len(keys))


def _check_sheet(mesh: Mesh, assignment: np.ndarray, what: str) -> None:
    """Mesh indices in range, M/V/F edges with two faces, B edges with one."""
    V, E = len(mesh.vertices_coords), len(mesh.edges_vertices)
    faces = mesh.faces_vertices
    for name, idx in (("edges_vertices", mesh.edges_vertices), ("faces_vertices", faces[faces >= 0])):
        if idx.size and (idx.min() < 0 or idx.max() >= V):
            raise InputError(f"{what}.{name} refers to vertices outside [0, {V}), got {int(idx.min())}..{int(idx.max())}")
    if not np.isfinite(mesh.vertices_coords).all():
        raise InputError(f"{what}.vertices_coords must be finite")
    angle = np.asarray(mesh.edges_foldAngle, float)
    if not (np.isfinite(angle) & (np.abs(angle) <= 180)).all():
        raise InputError(f"{what}.edges_foldAngle must be finite degrees in [-180, 180]")
    bad_kind = ~np.isin(mesh.edges_kind, EDGE_KINDS)
    if bad_kind.any():
        e = int(np.flatnonzero(bad_kind)[0])
        raise InputError(f"{what}.edges_kind[{e}] must be one of {EDGE_KINDS}, got {mesh.edges_kind[e]!r}")
    counts = _edge_face_counts(mesh, what)
    want = np.where(assignment == "B", 1, 2)
    wrong = counts != want
    if wrong.any():
        e = int(np.flatnonzero(wrong)[0])
        hint = "; a seam must be two boundary edges, one per sheet, paired in seam_partners" if mesh.edges_kind[e] == "seam" else ""
        raise InputError(
            f"{what}: edge {e} ({mesh.edges_kind[e]}, assignment {assignment[e]}) has {counts[e]} faces, "
            f"expected {want[e]} ({int(wrong.sum())} of {E} edges are wrong){hint}"
        )


def _flat_ccw_coords(mesh: Mesh, what: str, flat_tol: float, mirror_clockwise: bool) -> np.ndarray:
    """2D coordinates (V, 2) of a flat mesh with every sheet counter-clockwise.

    A sheet (a set of faces connected through shared vertices) whose triangles are all
    clockwise is mirrored, y → 2·c − y about its centre c, when ``mirror_clockwise``;
    that is the same sheet seen from the side its normals point to.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    x = np.asarray(mesh.vertices_coords, float)
    V = len(x)
    size = float(np.ptp(x, axis=0).max()) if V else 0.0
    zmax = float(np.abs(x[:, 2]).max()) if V else 0.0
    if zmax > flat_tol * max(size, 1e-300):
        raise InputError(f"{what} must be flat (z = 0): max |z| = {zmax:.3g}, allowed {flat_tol:g} x size {size:.3g}")
    xy = x[:, :2].copy()
    f = np.asarray(mesh.faces_vertices)
    if len(f) == 0:
        return xy
    area2 = vector_areas(xy, f)[:, 2]
    pairs = face_sides(f)[0]
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(V, V))
    _, vertex_sheet = connected_components(graph, directed=False)
    face_sheet = vertex_sheet[f[:, 0]]
    for sheet in np.unique(face_sheet):
        faces = np.flatnonzero(face_sheet == sheet)
        cw = area2[faces] < 0
        if mirror_clockwise and cw.all():
            verts = np.unique(f[faces][f[faces] >= 0])
            centre = 0.5 * (xy[verts, 1].min() + xy[verts, 1].max())
            xy[verts, 1] = 2 * centre - xy[verts, 1]
            area2[faces] = -area2[faces]
    bad = area2 <= 0
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise InputError(
            f"{what}: FOLD needs counter-clockwise faces in the crease pattern, but {int(bad.sum())} of "
            f"{len(area2)} faces are clockwise or degenerate (first: face {i}, signed area {area2[i] / 2:.3g})"
            + ("; a sheet with both orientations cannot be fixed by mirroring" if mirror_clockwise else "")
        )
    return xy


def _number_lists(a: np.ndarray) -> list:
    return np.asarray(a, float).tolist()


def _face_lists(faces: np.ndarray) -> list:
    """Faces (F, k), -1 padded, as FOLD's lists of vertex ids, each as long as its polygon."""
    if not (faces < 0).any():
        return faces.tolist()
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
        raise InputError(f"{name} must be edge indices in [0, {edges}), got {int(pairs.min())}..{int(pairs.max())}")
    return pairs


def _check_seam_partners(seam_partners, assignment: np.ndarray) -> np.ndarray:
    pairs = _check_pairs(seam_partners, len(assignment), "seam_partners", "P")
    if (pairs[:, 0] == pairs[:, 1]).any():
        raise InputError("seam_partners pairs an edge with itself")
    not_b = pairs.size and (assignment[pairs] != "B").any()
    if not_b:
        e = int(pairs[assignment[pairs] != "B"][0])
        raise InputError(f"seam_partners: edge {e} is not a boundary (B) edge, so it cannot be glued")
    return pairs


def _write_document(path: str | os.PathLike, title: str, frame: dict) -> Path:
    """Write a FOLD document: curvefold's file keys, the title if any, then ``frame``'s keys."""
    doc = {"file_spec": FILE_SPEC, "file_creator": CREATOR, "file_classes": ["singleModel"],
           **({"file_title": one_line(title)} if title else {}), **frame}
    return atomic_write(path, json.dumps(doc, allow_nan=False, separators=(",", ":")) + "\n")


def write_fold(
    path: str | os.PathLike,
    *,
    crease_pattern: Mesh,
    folded: Sequence[tuple[str, Mesh]],
    metadata: Mapping | None = None,
    unit: str = "unit",
    seam_partners: np.ndarray | Sequence[Sequence[int]] | None = None,
    bonds: np.ndarray | Sequence[Sequence[int]] | None = None,
    design: Mapping | None = None,
    title: str = "",
    flat_tol: float = 1e-9,
    mirror_clockwise: bool = True,
) -> Path:
    """Write a crease pattern and its folded states as one FOLD 1.1 file.

    Parameters
    ----------
    path : path-like
    crease_pattern : Mesh
        The flat crease pattern (z = 0, counter-clockwise faces) with the fold angles of
        the design state. Seams are cut open: each seam is two boundary edges, one per
        sheet, paired in ``seam_partners``.
    folded : sequence of (str, Mesh)
        Title and state of each folded frame; each Mesh has the crease pattern's topology
        (same ``edges_vertices``, ``faces_vertices``, ``edges_kind``).
    metadata : mapping of str to number or str, optional
        Design parameters, stored under ``curvefold:metadata``.
    unit : str
        Length unit (``frame_unit``), e.g. ``"m"``, ``"mm"``, ``"unit"``.
    seam_partners : (P, 2) array_like of int, optional
        Pairs of boundary edge indices glued together in the folded structure.
    bonds : (Q, 2) array_like of int, optional
        Pairs of edge indices of different sheets that coincide in the folded structure
        (tubes glued where they touch).
    design : mapping, optional
        The design and how the frames were made (:func:`to_fold`), stored as
        ``curvefold:design``; JSON data.
    title : str
        ``file_title`` (omitted when empty), on one line without control characters.
    flat_tol : float
        Allowed ``max |z|`` of the crease pattern relative to its size.
    mirror_clockwise : bool
        Mirror (y → −y about its centre) every sheet of the crease pattern whose
        triangles are all clockwise, so that it is seen from the side its normals point
        to, as FOLD requires; the folded frames and fold angles are unchanged. If False,
        such a sheet is an error.

    Returns
    -------
    Path

    Raises
    ------
    InputError
        On a non-flat crease pattern, a sheet with both clockwise and counter-clockwise
        (or degenerate) triangles, topology that differs between frames,
        a crease edge without two faces, a non-boundary seam partner, bad metadata or a
        design that is not JSON data.
    """
    cp = crease_pattern
    assignment = fold_assignments(cp.edges_kind, cp.edges_foldAngle, cp.edges_assignment)
    _check_sheet(cp, assignment, "crease_pattern")
    cp_xy = _flat_ccw_coords(cp, "crease_pattern", flat_tol, mirror_clockwise)
    pairs = _check_seam_partners(seam_partners, assignment)
    glued = _check_pairs(bonds, len(assignment), "bonds", "Q")
    meta = check_metadata(metadata)
    if design is not None:
        try:
            json.dumps(dict(design), allow_nan=False)
        except (TypeError, ValueError) as exc:
            raise InputError(f"design must be JSON data (numbers, strings, lists, objects): {exc}") from None
    zero = assignment == "B"  # one face: no dihedral angle

    frames = []
    for i, item in enumerate(folded):
        try:
            frame_title, mesh = item
        except (TypeError, ValueError) as exc:
            raise InputError(f"folded[{i}] must be a (title, Mesh) pair, got {item!r}") from exc
        for name in ("edges_vertices", "faces_vertices", "edges_kind"):
            if not np.array_equal(getattr(mesh, name), getattr(cp, name)):
                raise InputError(f"folded[{i}] ({frame_title!r}): {name} differs from the crease pattern's; all frames must share one topology")
        x = np.asarray(mesh.vertices_coords, float)
        angle = np.asarray(mesh.edges_foldAngle, float)
        if not np.isfinite(x).all() or x.shape != cp.vertices_coords.shape:
            raise InputError(f"folded[{i}] ({frame_title!r}): vertices_coords must be finite with shape {cp.vertices_coords.shape}")
        if not (np.isfinite(angle) & (np.abs(angle) <= 180)).all():
            raise InputError(f"folded[{i}] ({frame_title!r}): edges_foldAngle must be finite degrees in [-180, 180]")
        frames.append({
            "frame_title": one_line(frame_title),
            "frame_classes": ["foldedForm"],
            "frame_parent": 0,
            "frame_inherit": True,
            "vertices_coords": _number_lists(x),
            "edges_foldAngle": np.where(zero, 0.0, angle).tolist(),
        })

    return _write_document(path, title, {
        "frame_title": "crease pattern",
        "frame_classes": ["creasePattern"],
        "frame_unit": unit,
        "vertices_coords": _number_lists(cp_xy),
        "edges_vertices": cp.edges_vertices.tolist(),
        "edges_assignment": assignment.tolist(),
        "edges_foldAngle": np.where(zero, 0.0, np.asarray(cp.edges_foldAngle, float)).tolist(),
        "faces_vertices": _face_lists(cp.faces_vertices),
        "edges_curvefold:kind": cp.edges_kind.tolist(),
        "faces_curvefold:group": np.asarray(cp.faces_group).tolist(),
        "curvefold:seam_partners": pairs.tolist(),
        "curvefold:bonds": glued.tolist(),
        "curvefold:metadata": meta,
        **({"curvefold:design": dict(design)} if design is not None else {}),
        "file_frames": frames,
    })


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
    return _write_document(path, title, {
        "frame_classes": ["creasePattern" if flat else "foldedForm"],
        "frame_unit": unit,
        "vertices_coords": _number_lists(x),
        "edges_vertices": sheet.edges_vertices.tolist(),
        "edges_assignment": assignment.tolist(),
        "edges_foldAngle": np.where(np.isin(assignment, ("B", "F")), 0.0, np.asarray(sheet.edges_foldAngle, float)).tolist(),
        "faces_vertices": _face_lists(sheet.faces_vertices),
        "edges_curvefold:kind": sheet.edges_kind.tolist(),
    })


# ---------------------------------------------------------------------------------------
# reading


@dataclass(frozen=True, eq=False)
class FoldFile:
    """A FOLD file read by :func:`read_fold`.

    Attributes
    ----------
    crease_pattern : Mesh
        The key frame (z = 0 added to 2D coordinates).
    folded : tuple of (str, Mesh)
        Title and state of every further frame (``file_frames``), inheritance resolved.
    metadata : dict
        ``curvefold:metadata`` (``{}`` if absent).
    unit : str
        ``frame_unit`` of the key frame (``"unit"`` if absent).
    seam_partners : (P, 2) ndarray of int
        ``curvefold:seam_partners`` (empty if absent).
    bonds : (Q, 2) ndarray of int
        ``curvefold:bonds`` (empty if absent).
    design : dict or None
        ``curvefold:design``: the design and the frames' fold angles, anchor and faces.
    keys : frozenset of str
        The ``curvefold:`` keys the file holds (a file saved by another tool may have
        dropped them).
    """

    crease_pattern: Mesh
    folded: tuple[tuple[str, Mesh], ...]
    metadata: dict = field(default_factory=dict)
    unit: str = "unit"
    seam_partners: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), np.int64))
    bonds: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), np.int64))
    design: dict | None = None
    keys: frozenset = frozenset()


def _fail(where: str, msg: str) -> InputError:
    return InputError(f"{where}: {msg}")


def _int_rows(value, n_cols: int | None, key: str, where: str) -> np.ndarray:
    if not isinstance(value, list):
        raise _fail(where, f"{key} must be a list, got {type(value).__name__}")
    for i, row in enumerate(value):
        if not isinstance(row, list) or not all(is_integer(v) for v in row):
            raise _fail(where, f"{key}[{i}] must be a list of integers, got {row!r}")
        if n_cols is not None and len(row) != n_cols:
            raise _fail(where, f"{key}[{i}] must have {n_cols} entries, got {len(row)} ({row!r})")
    try:
        if n_cols is not None:
            return np.array(value, dtype=np.int64).reshape(len(value), n_cols)
        out = np.full((len(value), max([3] + [len(row) for row in value])), -1, np.int64)  # rows of any length, -1 padded
        for i, row in enumerate(value):
            out[i, : len(row)] = row
    except OverflowError:
        raise _fail(where, f"{key} holds an integer too large for an index") from None
    return out


def _float_array(value, key: str, where: str) -> np.ndarray:
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError, OverflowError) as exc:
        raise _fail(where, f"{key} must hold numbers only") from exc
    if not np.isfinite(a).all():
        raise _fail(where, f"{key} must hold finite numbers")
    return a


def _resolve_frames(doc: dict, frames: list, where: str) -> list[dict]:
    """Properties of every frame (0 = key frame, then ``file_frames``) with
    ``frame_inherit``/``frame_parent`` resolved, without recursion: a chain of thousands of
    frames costs one pass, and each frame is merged once."""
    n = len(frames)
    resolved: dict[int, dict] = {0: {k: v for k, v in doc.items() if not k.startswith("file_")}}
    for fid in range(1, n + 1):
        chain: list[int] = []
        f: int | None = fid
        while f is not None and f not in resolved:
            if f in chain:
                raise _fail(where, f"file_frames[{chain[-1] - 1}].frame_parent = {f} closes a cycle of inheriting frames")
            chain.append(f)
            frame = frames[f - 1]
            if not isinstance(frame, dict):
                raise _fail(where, f"file_frames[{f - 1}] must be an object")
            if not frame.get("frame_inherit", False):
                f = None
                break
            parent = frame.get("frame_parent", 0)
            if not is_integer(parent) or not 0 <= parent <= n or parent == f:
                raise _fail(where, f"file_frames[{f - 1}].frame_parent must be another frame id in [0, {n}] without cycles, got {parent!r}")
            f = parent
        merged = {} if f is None else resolved[f]
        for g in reversed(chain):
            merged = {**merged, **frames[g - 1]}
            resolved[g] = merged
    return [resolved[fid] for fid in range(n + 1)]


def _size(frame: dict) -> int:
    """Vertices, edges and faces a frame declares (before any is read)."""
    return sum(len(v) if isinstance(v := frame.get(key), list) else 0 for key in ("vertices_coords", "edges_vertices", "faces_vertices"))


def _frame_mesh(frame: dict, where: str) -> Mesh:
    for key in ("vertices_coords", "edges_vertices", "edges_assignment", "faces_vertices"):
        if key not in frame:
            raise _fail(where, f"missing required key {key!r}")
    coords = frame["vertices_coords"]
    if not isinstance(coords, list) or any(not isinstance(c, list) or len(c) not in (2, 3) for c in coords):
        raise _fail(where, "vertices_coords must be a list of [x, y] or [x, y, z] lists")
    x = np.zeros((len(coords), 3))
    for i, c in enumerate(coords):
        x[i, : len(c)] = _float_array(c, f"vertices_coords[{i}]", where)
    V = len(x)

    ev = _int_rows(frame["edges_vertices"], 2, "edges_vertices", where)
    E = len(ev)
    if E == 0:
        raise _fail(where, "edges_vertices is empty: a crease pattern needs edges")
    bad = np.flatnonzero(((ev < 0) | (ev >= V)).any(axis=1))
    if bad.size:
        raise _fail(where, f"edges_vertices[{bad[0]}] = {ev[bad[0]].tolist()} refers to a vertex outside [0, {V})")
    loops = np.flatnonzero(ev[:, 0] == ev[:, 1])
    if loops.size:
        raise _fail(where, f"edges_vertices[{loops[0]}] = {ev[loops[0]].tolist()} joins a vertex to itself")

    faces = frame["faces_vertices"]
    if isinstance(faces, list):
        for i, f in enumerate(faces):
            if isinstance(f, list) and len(f) < 3:
                raise _fail(where, f"faces_vertices[{i}] has {len(f)} vertices; a face needs at least 3")
    fv = _int_rows(faces, None, "faces_vertices", where)  # polygons, -1 padded
    if len(fv) == 0:
        raise _fail(where, "faces_vertices is empty: a crease pattern needs faces")
    real = np.arange(fv.shape[1]) < np.array([len(f) for f in faces], dtype=np.int64).reshape(-1, 1)
    bad = np.flatnonzero((((fv < 0) | (fv >= V)) & real).any(axis=1))
    if bad.size:
        raise _fail(where, f"faces_vertices[{bad[0]}] = {faces[bad[0]]} refers to a vertex outside [0, {V})")

    assignment = frame["edges_assignment"]
    if not isinstance(assignment, list) or len(assignment) != E:
        n = len(assignment) if isinstance(assignment, list) else type(assignment).__name__
        raise _fail(where, f"edges_assignment must be a list of {E} entries (one per edge), got {n}")
    for i, a in enumerate(assignment):
        if a not in ASSIGNMENTS:
            raise _fail(where, f"edges_assignment[{i}] = {a!r} is not one of {ASSIGNMENTS} (curvefold reads only these)")
    assignment = np.array(assignment, dtype="<U1").reshape(E)

    if "edges_foldAngle" in frame:
        angle = frame["edges_foldAngle"]
        if not isinstance(angle, list) or len(angle) != E:
            raise _fail(where, f"edges_foldAngle must be a list of {E} numbers (one per edge)")
        angle = _float_array(angle, "edges_foldAngle", where).reshape(E)
        if (np.abs(angle) > 180).any():
            raise _fail(where, f"edges_foldAngle must lie in [-180, 180] degrees, got {angle[np.abs(angle) > 180][0]}")
    else:  # the FOLD convention for a flat-folded M/V assignment
        angle = np.select([assignment == "V", assignment == "M"], [180.0, -180.0], 0.0)

    kind_key = next((k for k in _KIND_KEYS if k in frame), None)
    if kind_key is None:
        kind = np.array([_KIND_OF_ASSIGNMENT[a] for a in assignment], dtype="<U8").reshape(E)
    else:
        kind = frame[kind_key]
        if not isinstance(kind, list) or len(kind) != E:
            raise _fail(where, f"{kind_key} must be a list of {E} entries (one per edge)")
        for i, k in enumerate(kind):
            if k not in EDGE_KINDS:
                raise _fail(where, f"{kind_key}[{i}] = {k!r} is not one of {EDGE_KINDS}")
        kind = np.array(kind, dtype="<U8").reshape(E)

    group_key = next((k for k in _GROUP_KEYS if k in frame), None)
    if group_key is None:
        group = np.zeros(len(fv), np.int64)
    else:
        group = frame[group_key]
        if not isinstance(group, list) or len(group) != len(fv) or not all(is_integer(g) for g in group):
            raise _fail(where, f"{group_key} must be a list of {len(fv)} integers (one per face)")
        group = np.array(group, dtype=np.int64).reshape(len(fv))

    return Mesh(
        vertices_coords=x,
        edges_vertices=ev,
        edges_assignment=assignment,
        edges_foldAngle=angle,
        faces_vertices=fv,
        edges_kind=kind,
        faces_group=group,
    )


def read_fold(path: str | os.PathLike) -> FoldFile:
    """Read and validate a FOLD file (as written by :func:`write_fold` or another tool).

    The key frame becomes the crease pattern; every entry of ``file_frames`` becomes a
    folded state, with ``frame_inherit``/``frame_parent`` resolved (a frame may have its
    own topology, as FOLD allows; :func:`curvefold.analysis.foldcheck.check_fold` reports it). Files without the
    ``curvefold:`` keys get edge kinds from the assignments (``M``/``V`` fold, ``B``
    boundary, ``F`` diagonal), face group 0, no metadata and no seam partners. Missing
    ``edges_foldAngle`` means ±180 on ``V``/``M`` and 0 elsewhere.

    Reading is bounded: a regular file of at most :data:`MAX_FOLD_BYTES`, at most
    :data:`MAX_FRAMES` frames and :data:`MAX_FOLD_ITEMS` vertices, edges and faces in
    all; inheritance is resolved without recursion.

    Parameters
    ----------
    path : path-like

    Returns
    -------
    FoldFile

    Raises
    ------
    InputError
        If the file is not a regular file within the limits, is not JSON (or nested too
        deeply), has no edges or faces, misses a required key (``vertices_coords``,
        ``edges_vertices``, ``edges_assignment``, ``faces_vertices``), has arrays of the
        wrong length, indices out of range, an assignment other than M/V/B/F, a face of
        fewer than 3 vertices or malformed curvefold keys. The message names the file,
        frame and key. Faces may be polygons of any size (read -1 padded, see
        :class:`curvefold.geometry.mesh.Mesh`).
    """
    where = str(path)
    raw = read_bytes(path, limit=MAX_FOLD_BYTES, what="FOLD file")
    if not raw.strip():
        raise InputError(f"{where}: FOLD file is empty")
    try:
        doc = json.loads(raw.decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise InputError(f"{where}: not a FOLD file: not UTF-8 text (bad byte at offset {exc.start})") from None
    except RecursionError:
        raise InputError(f"{where}: not valid JSON: nested too deeply") from None
    except json.JSONDecodeError as exc:
        raise InputError(f"{where}: not valid JSON: {exc}") from None
    except ValueError:  # an integer past Python's digit limit
        raise InputError(f"{where}: not a FOLD file: it holds an integer of more than {sys.get_int_max_str_digits()} digits") from None
    if not isinstance(doc, dict):
        raise InputError(f"{where}: a FOLD file must hold a JSON object, got {type(doc).__name__}")
    frames = doc.get("file_frames", [])
    if not isinstance(frames, list):
        raise InputError(f"{where}: file_frames must be a list")
    if len(frames) > MAX_FRAMES:
        raise InputError(f"{where}: {len(frames)} frames in file_frames, more than curvefold reads ({MAX_FRAMES})")
    resolved = _resolve_frames(doc, frames, where)
    items = sum(map(_size, resolved))
    if items > MAX_FOLD_ITEMS:
        raise InputError(f"{where}: its frames hold {items} vertices, edges and faces in all (inherited ones counted in every frame), "
                         f"more than curvefold reads ({MAX_FOLD_ITEMS})")

    crease_pattern = _frame_mesh(resolved[0], f"{where} (key frame)")
    folded = []
    for fid in range(1, len(frames) + 1):
        frame_where = f"{where} (file_frames[{fid - 1}])"
        mesh = _frame_mesh(resolved[fid], frame_where)
        own_title = frames[fid - 1].get("frame_title")  # a title is not inherited
        title = str(own_title) if own_title else f"frame {fid}"
        folded.append((title, mesh))

    metadata = doc.get("curvefold:metadata", {})
    if not isinstance(metadata, dict):
        raise InputError(f"{where}: curvefold:metadata must be an object, got {type(metadata).__name__}")
    try:
        metadata = check_metadata(metadata)
    except InputError as exc:
        raise InputError(f"{where}: curvefold:metadata: {exc}") from exc
    unit = doc.get("frame_unit", "unit")
    if not isinstance(unit, str):
        raise InputError(f"{where}: frame_unit must be a string, got {unit!r}")

    E = len(crease_pattern.edges_vertices)
    pairs, bonds = (_edge_pairs(doc, key, E, where) for key in ("curvefold:seam_partners", "curvefold:bonds"))
    design = doc.get("curvefold:design")
    if design is not None and not isinstance(design, dict):
        raise InputError(f"{where}: curvefold:design must be an object, got {type(design).__name__}")
    keys = frozenset(k for k in doc if k.startswith(("curvefold:", "edges_curvefold:", "faces_curvefold:")))
    return FoldFile(crease_pattern=crease_pattern, folded=tuple(folded), metadata=metadata, unit=unit, seam_partners=pairs,
                    bonds=bonds, design=design, keys=keys)


def _edge_pairs(doc: dict, key: str, edges: int, where: str) -> np.ndarray:
    """A ``curvefold:`` list of edge-index pairs, checked, read-only, (P, 2)."""
    pairs = _int_rows(doc.get(key, []), 2, key, where)
    bad = np.flatnonzero(((pairs < 0) | (pairs >= edges)).any(axis=1))
    if bad.size:
        raise InputError(f"{where}: {key}[{bad[0]}] = {pairs[bad[0]].tolist()} refers to an edge outside [0, {edges})")
    return readonly(pairs)


# ---------------------------------------------------------------------------------------
# structures

def _metadata(structure: Structure, design_deg: float, extra: Mapping | None) -> dict:
    lat = structure.lattice
    meta = {
        "tubes": len(structure.cells),
        "cells": "; ".join(f"({i}, {j})" for i, j in structure.cells.tolist()),
        "samples": len(lat.s),
        "curve_length": float(lat.crease.curve.length),
        "width_left": float(lat.width_left[0]),
        "width_right": float(lat.width_right[0]),
        "design_fold_angle_deg": float(design_deg),
        "fold_crease_angle_deg": -float(design_deg),
        "seam_angle_deg": -(180.0 - float(design_deg)),
        "seams": "seam 2 of tube k has id 2k, seam 4 has id 2k + 1 (tubes from 0)",
        "bonds": " | ".join(b.describe() for b in bonds(structure)) or "none",
    }
    meta.update(check_metadata(extra))
    return check_metadata(meta)


def _row_offsets(xys: Sequence[np.ndarray], gap: float) -> list[np.ndarray]:
    """Translations (2,) placing 2D point sets in a row along +x, bounding boxes ``gap`` apart."""
    out, x = [], 0.0
    for xy in xys:
        lo, hi = xy.min(axis=0), xy.max(axis=0)
        out.append(np.array([x - lo[0], -lo[1]]))
        x += hi[0] - lo[0] + gap
    return out


def to_fold(
    structure: Structure,
    *,
    fold_angles=None,
    fold_angle: float | None = None,
    degrees: bool = True,
    unit: str = "unit",
    metadata: Mapping | None = None,
    anchor: str = "start",
    faces: Literal["triangles", "quads"] = "triangles",
    keep: Sequence[np.ndarray] | None = None,
    design: Mapping | None = None,
) -> FoldFile:
    """A structure as a FOLD model: crease pattern plus folded states on one topology.

    The crease pattern is every sheet of :func:`sheets`, laid in a row along +x (bounding
    boxes 5 % of the largest sheet apart, each sheet seen from outside, so faces are
    counter-clockwise). Seams are cut open: each seam edge appears once per sheet as a
    boundary edge, and the two copies are paired in ``seam_partners`` (the edges run
    opposite ways, as their faces traverse them). The folded frames put the same vertices
    at their 3D positions, so partner vertices coincide there, as do the crease edges of
    tubes glued where they touch (``bonds``). Every frame records the dihedral angle it
    has at every edge with two faces (the key frame those of the design state).

    Parameters
    ----------
    structure : Structure
    fold_angles : (A,) array_like, optional, keyword-only
        2α of the folded frames, in [0°, 180°); default the design angle only.
    fold_angle : float, optional, keyword-only
        The design angle whose fold angles the crease pattern carries; default the
        lattice's own.
    degrees : bool, keyword-only
    unit : str, keyword-only
        Model unit (``frame_unit``).
    metadata : mapping, optional, keyword-only
        Extra design parameters; merged over the ones recorded by default (tubes, cells,
        samples, curve length, widths at t = 0, the design, crease and seam angles, the seam
        numbering and the bonds as text).
    anchor : {"start", "middle"}, keyword-only
        Which frame of curve 1 stays fixed in the folded frames.
    faces : {"triangles", "quads"}, keyword-only
        Faces of the sheets (:func:`curvefold.geometry.sheets.sheets`).
    keep : sequence of (m_k,) array_like of int, optional, keyword-only
        The samples each tube's mesh keeps (:func:`curvefold.geometry.sampling.choose_sampling`);
        default every sample.
    design : mapping, optional, keyword-only
        The design the structure was built from, as a design file holds it
        (:meth:`curvefold.app.design.Design.to_dict`); recorded with the frames' fold
        angles, anchor and faces, so that the file can be built again and compared.

    Returns
    -------
    curvefold.io.FoldFile
        What :func:`write_structure_fold` writes and :func:`curvefold.io.read_fold`
        reads back.
    """
    _check_structure(structure)
    design_angle = _design_angle(structure, fold_angle, degrees)
    angles = np.array([design_angle]) if fold_angles is None else _angles(fold_angles, degrees, "fold_angles")
    if not isinstance(unit, str) or not unit:
        raise InputError(f"unit must be a non-empty str, got {unit!r}")
    meta = _metadata(structure, design_angle, metadata)
    topology = structure.topology(faces, keep=keep)
    parts = _develop(structure, design_angle, "", topology)
    xys = [p.mesh.vertices_coords[:, :2] for p in parts]
    size = max(float(np.ptp(xy, axis=0).max()) for xy in xys)
    offsets = _row_offsets(xys, 0.05 * size)
    v_off = np.concatenate([[0], np.cumsum([len(xy) for xy in xys])])

    def cat(name):
        return np.concatenate([getattr(p.mesh, name) for p in parts])

    cp = Mesh(
        vertices_coords=np.column_stack([np.concatenate([xy + o for xy, o in zip(xys, offsets)]), np.zeros(v_off[-1])]),
        edges_vertices=np.concatenate([p.mesh.edges_vertices + v_off[i] for i, p in enumerate(parts)]),
        edges_assignment=cat("edges_assignment"),
        edges_foldAngle=cat("edges_foldAngle"),
        faces_vertices=np.concatenate([np.where(p.mesh.faces_vertices >= 0, p.mesh.faces_vertices + v_off[i], -1) for i, p in enumerate(parts)]),
        edges_kind=cat("edges_kind"),
        faces_group=cat("faces_group"),
    )
    # Seam partners: the two sheet edges that are one edge of the structure's mesh.
    mesh_edge = np.concatenate([sheet.edges for sheet in topology.sheets])
    ids = np.flatnonzero(np.concatenate([p.edges_seam for p in parts]) >= 0)
    ordered = ids[np.argsort(mesh_edge[ids], kind="stable")]
    pairs = ordered.reshape(-1, 2) if ordered.size % 2 == 0 else np.zeros((0, 2), np.int64)
    if len(pairs) * 2 != ordered.size or not (mesh_edge[pairs[:, 0]] == mesh_edge[pairs[:, 1]]).all():
        raise InternalError("seam edges do not pair up between the two sheets of a tube")

    source = np.concatenate([sheet.vertices for sheet in topology.sheets])
    glued = _bond_pairs(cp.edges_vertices, source, topology, mesh_edge)
    # Every frame carries the dihedral angle it has at every edge; the key frame the design state's.
    coords = folding_motion(structure, np.concatenate([[design_angle], angles]), anchor=anchor, keep=keep)[:, source]  # (1 + A, V, 3)
    sides = edges_faces(cp.faces_vertices, cp.edges_vertices)
    measured = [dihedral_angles(x, cp.faces_vertices, cp.edges_vertices, faces_of_edges=sides) for x in coords]
    cp = replace(cp, edges_foldAngle=measured[0])
    folded = tuple((f"fold angle {a:g}°", replace(cp, vertices_coords=x, edges_foldAngle=m))
                   for a, x, m in zip(angles, coords[1:], measured[1:]))
    record = None if design is None else {"design": dict(design), "fold_angles": angles.tolist(), "anchor": anchor, "faces": faces,
                                          "keep": None if keep is None else [np.asarray(k).tolist() for k in keep]}
    return FoldFile(crease_pattern=cp, folded=folded, metadata=meta, unit=unit, seam_partners=readonly(pairs), bonds=glued, design=record)


def _bond_pairs(edges_vertices: np.ndarray, source: np.ndarray, topology: Topology, mesh_edge: np.ndarray) -> np.ndarray:
    """Pairs of file edges between the same two samples of one lattice curve, in different tubes' meshes.

    Every tube carries its own copy of its curves; where tubes share a lattice curve those
    copies are glued. Each crease edge is keyed by its lattice curve and both its samples
    (tubes whose meshes keep different samples share only the edges between samples both
    keep); within a key, one file edge per mesh edge (a seam's two sheet edges are one mesh
    edge: that pair is a seam partner), chained pairwise.
    """
    a, b = source[edges_vertices[:, 0]], source[edges_vertices[:, 1]]
    ids = np.flatnonzero(topology.vertex_curve[a] == topology.vertex_curve[b])  # rulings and diagonals join two curves
    n = int(topology.vertex_sample.max()) + 1
    lo = np.minimum(topology.vertex_sample[a[ids]], topology.vertex_sample[b[ids]])
    hi = np.maximum(topology.vertex_sample[a[ids]], topology.vertex_sample[b[ids]])
    key = (topology.vertex_curve[a[ids]].astype(np.int64) * n + lo) * n + hi
    order = np.lexsort((mesh_edge[ids], key))
    ids, key = ids[order], key[order]
    first = np.r_[True, (key[1:] != key[:-1]) | (mesh_edge[ids[1:]] != mesh_edge[ids[:-1]])]
    ids, key = ids[first], key[first]
    same = key[1:] == key[:-1]
    return readonly(np.stack([ids[:-1][same], ids[1:][same]], axis=1))


def write_structure_fold(path: str | os.PathLike, structure: Structure, *, title: str = "", **kwargs) -> Path:
    """Write :func:`to_fold` of a structure as a FOLD 1.1 file (via :func:`curvefold.io.write_fold`).

    Parameters
    ----------
    path : path-like
    structure : Structure
    title : str, keyword-only
        ``file_title``.
    **kwargs
        Passed to :func:`to_fold` (``fold_angles``, ``fold_angle``, ``degrees``, ``unit``,
        ``metadata``, ``anchor``, ``faces``, ``keep``, ``design``).

    Returns
    -------
    Path
    """
    model = to_fold(structure, **kwargs)
    return write_fold(path, crease_pattern=model.crease_pattern, folded=model.folded, metadata=model.metadata,
                      unit=model.unit, seam_partners=model.seam_partners, bonds=model.bonds, design=model.design, title=title)
