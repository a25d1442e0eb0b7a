"""Reading and validating FOLD files: the key frame, its folded frames and curvefold's keys.

:func:`read_fold` reads any FOLD 1.1 file (curvefold's, as :mod:`curvefold.io.fold` writes
them, or another tool's) into a :class:`FoldFile`, bounded in bytes, frames and items, and
checks every key it reads: the message names the file, the frame and the key.
:func:`curvefold.analysis.foldcheck.check_fold` then checks the geometry it holds.
"""

from __future__ import annotations

import json
import os
import sys
from dataclasses import dataclass, field

import numpy as np

from ..geometry.mesh import EDGE_KINDS, Mesh
from ..kernel.arrays import readonly
from ..kernel.errors import InputError
from ..kernel.validate import is_integer
from .mesh3d import check_metadata
from .reading import read_bytes

__all__ = ["FoldFile", "read_fold", "ASSIGNMENTS", "MAX_FOLD_BYTES", "MAX_FRAMES", "MAX_FOLD_ITEMS"]

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
