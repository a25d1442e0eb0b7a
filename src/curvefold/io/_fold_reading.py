"""Reading and validating FOLD files: the crease pattern, the folded frames and curvefold's keys.

:func:`read_fold` reads any FOLD file (curvefold's, as :mod:`curvefold.io._fold` writes
them, or another tool's, FOLD 1.0 to 1.2) into a :class:`FoldFile`, bounded in bytes,
frames and items, and checks every key it reads: the message names the file, the frame and
the key. :func:`curvefold.analysis.check_fold` then checks the geometry it holds.

How the frames are read
    The crease pattern is the first frame whose ``frame_classes`` name
    ``"creasePattern"``, else the key frame when it has no ``"foldedForm"`` class and lies
    flat, else the ``vertices_flatUnfoldCoords`` of a flat-folded frame; every other frame
    is a folded frame. A file may hold no crease pattern (a folded form alone, as the FOLD
    repository's examples and Origami Simulator's exports do); what needs one is then not
    checked, and says so. A folded frame whose coordinates all lie in z = 0 is flat-folded:
    its faces lie in one plane, so the fold direction of its creases is not in its
    coordinates (it is in ``faceOrders``, which is not read).

Read leniently, and said so in :attr:`FoldFile.notes`
    a UTF-8 byte-order mark; ``null`` in ``edges_foldAngle`` (on a boundary, flat,
    unassigned or join edge it is FOLD's 0; on a mountain or valley it is not recorded);
    FOLD 1.0's ``edges_foldAngles``; a missing ``edges_assignment`` (B on one face, U
    elsewhere); the FOLD 1.2 assignments ``U`` (unassigned), ``J`` (join: its faces are one)
    and ``C`` (cut: read as one ``B`` edge per face, the vertices along a cut split as
    FOLD says); keys curvefold does not read (layer orders, arrays derived from the ones it
    reads, other tools' keys), each named with why.

Refused, with the key and the value
    anything but a JSON object; duplicated keys; numbers written as strings or booleans;
    coordinates beyond ±:data:`MAX_COORDINATE` or a model less than
    :data:`MIN_SIZE` across (lengths, areas and volumes of such a model are not
    representable); indices out of range; arrays of the wrong length.
"""

from __future__ import annotations

import json
import os
import sys
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import TypeGuard

import numpy as np

from ..geometry._mesh import EDGE_KINDS, Mesh, face_sides
from ..kernel._arrays import readonly
from ..kernel._errors import InputError
from ..kernel._validate import is_integer
from ._fold_faces import padded_faces
from ._fold_keys import SPEC_READ, ignored_keys, split_cuts, unfolded_with_targets
from ._mesh3d import check_metadata
from ._reading import read_bytes

__all__ = [
    "FoldFile",
    "read_fold",
    "parse_fold",
    "ASSIGNMENTS",
    "MAX_FOLD_BYTES",
    "MAX_FRAMES",
    "MAX_FOLD_ITEMS",
    "MAX_COORDINATE",
    "MIN_SIZE",
]

#: The assignments of FOLD 1.2 (curvefold writes M, V, B and F).
ASSIGNMENTS = ("M", "V", "B", "F", "U", "C", "J")
#: Largest FOLD file read, in bytes: parsing holds about 10 bytes per byte of JSON (measured
#: on curvefold's own files), so about 1.3 GB at the limit.
MAX_FOLD_BYTES = 128 << 20
#: Most frames read from ``file_frames``.
MAX_FRAMES = 1000
#: Most vertices, edges and faces over all frames (an inheriting frame counts what it inherits):
#: about 50 bytes each once read, 400 MB at the limit.
MAX_FOLD_ITEMS = 8_000_000
#: Largest coordinate read: the cube of a length (a planarity's volume) stays finite.
MAX_COORDINATE = 1e100
#: Smallest model read (its largest extent): the cube of a length stays a normal number.
MIN_SIZE = 1e-100
#: A folded frame with every ``|z|`` at most this fraction of its size is flat-folded.
FLAT = 1e-12
#: Edge kind assumed for files without ``edges_curvefold:kind``.
_KIND_OF_ASSIGNMENT = {
    "M": "fold",
    "V": "fold",
    "U": "fold",
    "B": "boundary",
    "F": "diagonal",
    "J": "diagonal",
}
_KIND_KEYS = ("edges_curvefold:kind", "curvefold:edges_kind")
_GROUP_KEYS = ("faces_curvefold:group", "curvefold:faces_group")
#: Assignments FOLD gives the fold angle 0.
_UNFOLDED = ("B", "F", "U", "J", "C")


@dataclass(frozen=True, eq=False)
class FoldFile:
    """A FOLD file read by :func:`read_fold`.

    Attributes
    ----------
    crease_pattern : Mesh or None
        The crease pattern (z = 0 added to 2D coordinates), None when the file holds none.
    folded : tuple of (str, Mesh)
        Title and state of every folded frame, inheritance resolved.
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
    notes : tuple of str
        What was read leniently or not read, and why (module notes).
    flat_folded : tuple of bool
        For every folded frame, whether it is flat-folded (empty: none is).
    unrecorded : tuple of (k,) ndarray of int
        For every folded frame, the edges whose fold angle it does not record (empty: all
        are recorded).
    classes : tuple of tuple of str
        ``frame_classes`` of the file's frames as written, the key frame first.
    frame_ids : tuple of int
        The FOLD frame id of every folded frame (0 the key frame, i + 1 ``file_frames[i]``);
        empty: 1, 2, … (the key frame is the crease pattern).
    crease_frame : int or None
        The FOLD frame id of the crease pattern; None when the file holds none, or when it
        is a flat-folded frame's ``vertices_flatUnfoldCoords``.
    """

    crease_pattern: Mesh | None
    folded: tuple[tuple[str, Mesh], ...]
    metadata: dict = field(default_factory=dict)
    unit: str = "unit"
    seam_partners: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), np.int64))
    bonds: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), np.int64))
    design: dict | None = None
    keys: frozenset = frozenset()
    notes: tuple[str, ...] = ()
    flat_folded: tuple[bool, ...] = ()
    unrecorded: tuple[np.ndarray, ...] = ()
    classes: tuple[tuple[str, ...], ...] = ()
    frame_ids: tuple[int, ...] = ()
    crease_frame: int | None = 0

    def is_flat_folded(self, frame: int) -> bool:
        """Whether folded frame ``frame`` (0-based) is flat-folded."""
        return bool(self.flat_folded and self.flat_folded[frame])

    def unrecorded_edges(self, frame: int) -> np.ndarray:
        """The edges whose fold angle folded frame ``frame`` (0-based) does not record."""
        return self.unrecorded[frame] if self.unrecorded else np.zeros(0, np.int64)

    def frame_id(self, frame: int) -> int:
        """The FOLD frame id of folded frame ``frame`` (0-based)."""
        return self.frame_ids[frame] if self.frame_ids else frame + 1


def _fail(where: str, msg: str) -> InputError:
    return InputError(f"{where}: {msg}")


def _is_number(v: object) -> TypeGuard[float]:
    return type(v) is float or (type(v) is int)


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
        out = padded_faces(value, key, where)  # rows of any length, -1 padded
    except OverflowError:
        raise _fail(where, f"{key} holds an integer too large for an index") from None
    return out


def _coordinates(coords, where: str) -> np.ndarray:
    """``vertices_coords`` as (V, 3) floats: numbers only (a string or a boolean is refused),
    each within the bounds."""
    if not isinstance(coords, list) or any(
        not isinstance(c, list) or len(c) not in (2, 3) for c in coords
    ):
        raise _fail(where, "vertices_coords must be a list of [x, y] or [x, y, z] lists")
    x = np.zeros((len(coords), 3))
    for i, c in enumerate(coords):
        if not all(map(_is_number, c)):
            raise _fail(where, f"vertices_coords[{i}] must hold numbers only, got {c!r}")
        try:
            x[i, : len(c)] = c
        except OverflowError:
            raise _fail(
                where,
                f"vertices_coords[{i}] must hold numbers within "
                f"±{MAX_COORDINATE:g}, got an integer of {len(str(max(map(abs, c))))} digits",
            ) from None
    big = np.flatnonzero(~(np.abs(x) <= MAX_COORDINATE).all(axis=1))
    if big.size:
        raise _fail(
            where,
            f"vertices_coords[{big[0]}] = {coords[big[0]]} must lie within "
            f"±{MAX_COORDINATE:g} (lengths, areas and volumes must be representable)",
        )
    return x


def _angles(
    value, E: int, assignment: np.ndarray, key: str, where: str, notes: list[str]
) -> tuple[np.ndarray, np.ndarray]:
    """``edges_foldAngle`` (E,) in degrees and the edges it does not record: ``null`` is FOLD's 0 on
    an edge that is not a crease, and not recorded on a mountain or valley."""
    if not isinstance(value, list) or len(value) != E:
        raise _fail(where, f"{key} must be a list of {E} numbers (one per edge)")
    null = np.array([v is None for v in value], bool)
    bad = [i for i, v in enumerate(value) if v is not None and not _is_number(v)]
    if bad:
        raise _fail(where, f"{key}[{bad[0]}] must be a number or null, got {value[bad[0]]!r}")
    try:
        angle = np.array([0.0 if v is None else v for v in value], float)
    except OverflowError:
        raise _fail(where, f"{key} holds an integer too large for an angle") from None
    out = np.flatnonzero(~(np.abs(angle) <= 180))
    if out.size:
        raise _fail(
            where, f"{key} must lie in [-180, 180] degrees, got {value[out[0]]} at edge {out[0]}"
        )
    crease = np.isin(assignment, ("M", "V"))
    if (null & ~crease).any():
        kinds = ", ".join(sorted(set(assignment[null & ~crease].tolist())))
        notes.append(
            f"{where}: {key} is null on {int((null & ~crease).sum())} {kinds} edges, "
            "read as 0 (FOLD's angle of an edge that is not folded)"
        )
    if (null & crease).any():
        notes.append(
            f"{where}: {key} is null on {int((null & crease).sum())} M/V edges: their "
            "fold angle is not recorded, so it is not checked"
        )
    return angle, np.flatnonzero(null & crease)


def _assignments(
    frame: dict, ev: np.ndarray, fv: np.ndarray, where: str, notes: list[str]
) -> np.ndarray:
    E = len(ev)
    if "edges_assignment" not in frame:
        on_one = _faces_per_edge(ev, fv) == 1
        notes.append(
            f"{where}: no edges_assignment: edges on one face read as B, the others as "
            "U (unassigned)"
        )
        return np.where(on_one, "B", "U").astype("<U1")
    assignment = frame["edges_assignment"]
    if not isinstance(assignment, list) or len(assignment) != E:
        n = len(assignment) if isinstance(assignment, list) else type(assignment).__name__
        raise _fail(
            where, f"edges_assignment must be a list of {E} entries (one per edge), got {n}"
        )
    for i, a in enumerate(assignment):
        if a not in ASSIGNMENTS:
            raise _fail(where, f"edges_assignment[{i}] = {a!r} is not one of FOLD's {ASSIGNMENTS}")
    return np.array(assignment, dtype="<U1").reshape(E)


def _faces_per_edge(ev: np.ndarray, fv: np.ndarray) -> np.ndarray:
    """How many face sides run along every edge, either way, shape (E,)."""
    sides, _ = face_sides(fv)
    V = int(max(ev.max(initial=0), fv.max(initial=0))) + 1
    keys = np.sort(ev, axis=1) @ np.array([V, 1])
    side_keys = np.sort(sides, axis=1) @ np.array([V, 1])
    order = np.argsort(keys)
    pos = np.clip(np.searchsorted(keys[order], side_keys), 0, max(len(keys) - 1, 0))
    hit = keys[order][pos] == side_keys
    return np.bincount(order[pos[hit]], minlength=len(ev))


def _frame_mesh(
    frame: dict, where: str, notes: list[str], coords_key: str = "vertices_coords"
) -> tuple[Mesh, np.ndarray]:
    """A frame's Mesh and the M/V edges whose fold angle it does not record."""
    for key in (coords_key, "edges_vertices", "faces_vertices"):
        if key not in frame:
            raise _fail(where, f"missing required key {key!r}")
    x = _coordinates(frame[coords_key], where)
    V = len(x)
    ev = _int_rows(frame["edges_vertices"], 2, "edges_vertices", where)
    E = len(ev)
    if E == 0:
        raise _fail(where, "edges_vertices is empty: a crease pattern needs edges")
    bad = np.flatnonzero(((ev < 0) | (ev >= V)).any(axis=1))
    if bad.size:
        raise _fail(
            where,
            f"edges_vertices[{bad[0]}] = {ev[bad[0]].tolist()} refers to a vertex outside [0, {V})",
        )
    loops = np.flatnonzero(ev[:, 0] == ev[:, 1])
    if loops.size:
        raise _fail(
            where, f"edges_vertices[{loops[0]}] = {ev[loops[0]].tolist()} joins a vertex to itself"
        )

    faces = frame["faces_vertices"]
    if isinstance(faces, list):
        for i, f in enumerate(faces):
            if isinstance(f, list) and len(f) < 3:
                raise _fail(
                    where, f"faces_vertices[{i}] has {len(f)} vertices; a face needs at least 3"
                )
    fv = _int_rows(faces, None, "faces_vertices", where)  # polygons, -1 padded
    if len(fv) == 0:
        raise _fail(where, "faces_vertices is empty: a crease pattern needs faces")
    real = np.arange(fv.shape[1]) < np.array([len(f) for f in faces], dtype=np.int64).reshape(-1, 1)
    bad = np.flatnonzero((((fv < 0) | (fv >= V)) & real).any(axis=1))
    if bad.size:
        raise _fail(
            where, f"faces_vertices[{bad[0]}] = {faces[bad[0]]} refers to a vertex outside [0, {V})"
        )

    assignment = _assignments(frame, ev, fv, where, notes)
    angle_key = next((k for k in ("edges_foldAngle", "edges_foldAngles") if k in frame), None)
    if angle_key is None:  # the FOLD convention for a flat-folded M/V assignment
        angle = np.select([assignment == "V", assignment == "M"], [180.0, -180.0], 0.0)
        unrecorded = np.flatnonzero(np.isin(assignment, ("M", "V")))
    else:
        if angle_key == "edges_foldAngles":
            notes.append(f"{where}: edges_foldAngles (FOLD 1.0's name) read as edges_foldAngle")
        angle, unrecorded = _angles(frame[angle_key], E, assignment, angle_key, where, notes)

    kind_key = next((k for k in _KIND_KEYS if k in frame), None)
    if kind_key is None:
        kind = np.array(
            [_KIND_OF_ASSIGNMENT.get(a, "boundary") for a in assignment], dtype="<U8"
        ).reshape(E)
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
        if (
            not isinstance(group, list)
            or len(group) != len(fv)
            or not all(is_integer(g) for g in group)
        ):
            raise _fail(where, f"{group_key} must be a list of {len(fv)} integers (one per face)")
        group = np.array(group, dtype=np.int64).reshape(len(fv))
    mesh = Mesh(
        vertices_coords=x,
        edges_vertices=ev,
        edges_assignment=assignment,
        edges_foldAngle=angle,
        faces_vertices=fv,
        edges_kind=kind,
        faces_group=group,
    )
    return mesh, readonly(unrecorded)


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
                raise _fail(
                    where,
                    f"file_frames[{chain[-1] - 1}].frame_parent = {f} closes a "
                    "cycle of inheriting frames",
                )
            chain.append(f)
            frame = frames[f - 1]
            if not isinstance(frame, dict):
                raise _fail(where, f"file_frames[{f - 1}] must be an object")
            if not frame.get("frame_inherit", False):
                f = None
                break
            parent = frame.get("frame_parent", 0)
            if not is_integer(parent) or not 0 <= parent <= n or parent == f:
                raise _fail(
                    where,
                    f"file_frames[{f - 1}].frame_parent must be another frame id "
                    f"in [0, {n}] without cycles, got {parent!r}",
                )
            f = parent
        merged = {} if f is None else resolved[f]
        for g in reversed(chain):
            merged = {**merged, **frames[g - 1]}
            resolved[g] = merged
    return [resolved[fid] for fid in range(n + 1)]


def _size(frame: dict) -> int:
    """Vertices, edges and faces a frame declares (before any is read)."""
    return sum(
        len(v) if isinstance(v := frame.get(key), list) else 0
        for key in ("vertices_coords", "edges_vertices", "faces_vertices")
    )


def _classes(frame: dict, where: str, notes: list[str]) -> tuple[str, ...]:
    value = frame.get("frame_classes", [])
    if not isinstance(value, list) or not all(isinstance(c, str) for c in value):
        notes.append(f"{where}: frame_classes is not a list of strings ({value!r}): not read")
        return ()
    return tuple(value)


def _extent(x: np.ndarray) -> float:
    return float(np.ptp(x, axis=0).max()) if len(x) else 0.0


def _duplicates_refused(pairs: list[tuple[str, object]]) -> dict:
    out = {}
    for key, value in pairs:
        if key in out:
            raise ValueError(f"the key {key!r} appears twice in one object")
        out[key] = value
    return out


def _no_constant(name: str):
    raise ValueError(f"{name} is not a JSON number")


def read_fold(path: str | os.PathLike) -> FoldFile:
    """Read and validate a FOLD file (as written by :func:`write_fold` or another tool).

    The frames are read as the module notes say: a crease pattern if the file holds one,
    and every folded frame, with ``frame_inherit``/``frame_parent`` resolved (a frame may
    have its own topology, as FOLD allows; :func:`curvefold.analysis.check_fold`
    reports it). Files without the ``curvefold:`` keys get edge kinds from the assignments
    (``M``/``V``/``U`` fold, ``B`` boundary, ``F``/``J`` diagonal), face group 0, no
    metadata and no seam partners. Missing ``edges_foldAngle`` means ±180 on ``V``/``M``
    (FOLD's flat folds) and 0 elsewhere, not recorded.

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
        deeply, or repeats a key), has no edges or faces, misses a required key
        (``vertices_coords``, ``edges_vertices``, ``faces_vertices``), has arrays of the
        wrong length, numbers that are strings, coordinates out of bounds, indices out of
        range, an assignment that is not FOLD's, a face of fewer than 3 vertices or
        malformed curvefold keys. The message names the file, frame and key. Faces may be
        polygons of any size (read -1 padded, see :class:`curvefold.geometry.Mesh`).
    """
    where = str(path)
    raw = read_bytes(path, limit=MAX_FOLD_BYTES, what="FOLD file")
    notes = []
    if raw.startswith(b"\xef\xbb\xbf"):
        raw = raw[3:]
        notes.append(f"{where}: a UTF-8 byte-order mark opens the file: skipped")
    if not raw.strip():
        raise InputError(f"{where}: FOLD file is empty")
    try:
        doc = json.loads(
            raw.decode("utf-8"), object_pairs_hook=_duplicates_refused, parse_constant=_no_constant
        )
    except UnicodeDecodeError as exc:
        raise InputError(
            f"{where}: not a FOLD file: not UTF-8 text (bad byte at offset {exc.start})"
        ) from None
    except RecursionError:
        raise InputError(f"{where}: not valid JSON: nested too deeply") from None
    except json.JSONDecodeError as exc:
        raise InputError(f"{where}: not valid JSON: {exc}") from None
    # a repeated key, NaN or Infinity, or an integer past Python's digit limit
    except ValueError as exc:
        text = (
            str(exc)
            if "twice" in str(exc) or "JSON number" in str(exc)
            else f"it holds an integer of more than {sys.get_int_max_str_digits()} digits"
        )
        raise InputError(f"{where}: not a FOLD file: {text}") from None
    return parse_fold(doc, where, notes=notes)


def parse_fold(doc, where: str = "FOLD document", *, notes: Sequence[str] = ()) -> FoldFile:
    """A FOLD document already parsed from JSON, read and validated as :func:`read_fold` does.

    ``where`` names the document in messages; ``notes`` are kept before the reader's own.

    Raises
    ------
    InputError
        As :func:`read_fold`.
    """
    notes = list(notes)
    if not isinstance(doc, dict):
        raise InputError(f"{where}: a FOLD file must hold a JSON object, got {type(doc).__name__}")
    frames = doc.get("file_frames", [])
    if not isinstance(frames, list):
        raise InputError(f"{where}: file_frames must be a list")
    if len(frames) > MAX_FRAMES:
        raise InputError(
            f"{where}: {len(frames)} frames in file_frames, more than curvefold "
            f"reads ({MAX_FRAMES})"
        )
    spec = doc.get("file_spec")
    if _is_number(spec) and spec > SPEC_READ:
        notes.append(
            f"{where}: file_spec {spec} is newer than the FOLD {SPEC_READ} curvefold "
            f"reads; read as {SPEC_READ}"
        )
    resolved = _resolve_frames(doc, frames, where)
    items = sum(map(_size, resolved))
    if items > MAX_FOLD_ITEMS:
        raise InputError(
            f"{where}: its frames hold {items} vertices, edges and faces in all "
            "(inherited ones counted in every frame), more than curvefold reads "
            f"({MAX_FOLD_ITEMS})"
        )
    labels = [f"{where} (key frame)"] + [f"{where} (file_frames[{i}])" for i in range(len(frames))]
    classes = [_classes(frame, label, notes) for frame, label in zip(resolved, labels)]
    meshes = [_frame_mesh(frame, label, notes) for frame, label in zip(resolved, labels)]
    titles = [str(doc.get("frame_title") or "key frame")] + [
        str(frames[i].get("frame_title") or f"frame {i + 1}")
        # a title is not inherited
        for i in range(len(frames))
    ]

    size = max(_extent(m.vertices_coords) for m, _ in meshes)
    if not size >= MIN_SIZE:
        raise InputError(
            f"{where}: the model is {size:.3g} across; curvefold reads models at "
            f"least {MIN_SIZE:g} across (the cube of a smaller length is not a normal number)"
        )
    flat = [
        float(np.abs(m.vertices_coords[:, 2]).max()) <= FLAT * _extent(m.vertices_coords)
        for m, _ in meshes
    ]
    cp_index = next((i for i, c in enumerate(classes) if "creasePattern" in c), None)
    if cp_index is None and (
        ("foldedForm" not in classes[0] and flat[0])
        or (len(meshes) == 1 and unfolded_with_targets(meshes[0][0], labels[0], notes))
    ):
        cp_index = 0
    crease_pattern = None if cp_index is None else meshes[cp_index][0]
    # another crease pattern is no folded frame: it is named, not checked as one
    others = [i for i, c in enumerate(classes) if "creasePattern" in c and i != cp_index]
    for i in others:
        notes.append(
            f"{labels[i]}: another crease pattern (frame_classes creasePattern): not read as a "
            "folded frame; the first crease pattern is the one checked"
        )
    chosen = [i for i in range(len(meshes)) if i != cp_index and i not in others]
    if crease_pattern is None:
        crease_pattern = _unfolded(resolved, chosen, meshes, labels, notes)
    folded = tuple((titles[i], meshes[i][0]) for i in chosen)
    if crease_pattern is None:
        notes.append(
            f"{where}: no crease pattern: the file holds a folded form only, so what "
            "compares with a crease pattern is not checked"
        )

    metadata = doc.get("curvefold:metadata", {})
    if not isinstance(metadata, dict):
        raise InputError(
            f"{where}: curvefold:metadata must be an object, got {type(metadata).__name__}"
        )
    try:
        metadata = check_metadata(metadata)
    except InputError as exc:
        raise InputError(f"{where}: curvefold:metadata: {exc}") from exc
    unit = doc.get("frame_unit", "unit")
    if not isinstance(unit, str):
        raise InputError(f"{where}: frame_unit must be a string, got {unit!r}")

    E = len(meshes[0][0].edges_vertices)
    pairs, bonds = (
        _edge_pairs(doc, key, E, where) for key in ("curvefold:seam_partners", "curvefold:bonds")
    )
    design = doc.get("curvefold:design")
    if design is not None and not isinstance(design, dict):
        raise InputError(
            f"{where}: curvefold:design must be an object, got {type(design).__name__}"
        )
    keys = frozenset(
        k for k in doc if k.startswith(("curvefold:", "edges_curvefold:", "faces_curvefold:"))
    )
    notes += ignored_keys(resolved, labels)
    crease_pattern, folded = split_cuts(crease_pattern, folded, where, notes)
    return FoldFile(
        crease_pattern=crease_pattern,
        folded=folded,
        metadata=metadata,
        unit=unit,
        seam_partners=pairs,
        bonds=bonds,
        design=design,
        keys=keys,
        notes=_collapsed(notes),
        flat_folded=tuple(flat[i] for i in chosen),
        unrecorded=tuple(meshes[i][1] for i in chosen),
        classes=tuple(classes),
        frame_ids=tuple(chosen),
        crease_frame=cp_index,
    )


def _collapsed(notes: list[str]) -> tuple[str, ...]:
    """The notes, each said once: the same words about several frames (inherited keys) name the
    first and count the others."""
    said: dict[str, list[str]] = {}
    for note in notes:
        where, _, words = note.partition("): ") if "): " in note else ("", "", note)
        said.setdefault(words, []).append(where + ")" if where else "")
    return tuple(
        f"{places[0]}: {words}"
        + (f" (and in {len(places) - 1} more frames)" if len(places) > 1 else "")
        if places[0]
        else words
        for words, places in said.items()
    )


def _unfolded(
    resolved: list[dict], chosen: list[int], meshes, labels: list[str], notes: list[str]
) -> Mesh | None:
    """The crease pattern of a flat-folded frame's ``vertices_flatUnfoldCoords``, on its
    topology, or None."""
    for i in chosen:
        if "vertices_flatUnfoldCoords" in resolved[i]:
            x = _coordinates(resolved[i]["vertices_flatUnfoldCoords"], labels[i])
            mesh = meshes[i][0]
            if len(x) != len(mesh.vertices_coords):
                raise _fail(
                    labels[i],
                    "vertices_flatUnfoldCoords must have one point per "
                    f"vertex ({len(mesh.vertices_coords)}), got {len(x)}",
                )
            notes.append(f"{labels[i]}: its vertices_flatUnfoldCoords read as the crease pattern")
            return replace(mesh, vertices_coords=x)
    return None


def _edge_pairs(doc: dict, key: str, edges: int, where: str) -> np.ndarray:
    """A ``curvefold:`` list of edge-index pairs, checked, read-only, (P, 2)."""
    pairs = _int_rows(doc.get(key, []), 2, key, where)
    bad = np.flatnonzero(((pairs < 0) | (pairs >= edges)).any(axis=1))
    if bad.size:
        raise InputError(
            f"{where}: {key}[{bad[0]}] = {pairs[bad[0]].tolist()} refers to an edge "
            f"outside [0, {edges})"
        )
    return readonly(pairs)
