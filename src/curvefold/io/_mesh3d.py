"""Plain 3D mesh files (OBJ, binary STL, binary PLY) of one structure state.

All three are written here with NumPy (binary STL and PLY are a header and one packed
record per vertex or triangle; importing a mesh library to write them cost the output
folder's 3D job a quarter of its time); OBJ also carries the crease lines as ``l``
polylines in named groups. All files are written atomically.

Precision: STL and PLY store vertex coordinates as 32-bit floats (about 7 significant
digits); OBJ stores them with 17 significant digits. None of the three formats has a
unit field: the OBJ header comment states it, and the STL can be written in a length unit
of its own (millimetres, which slicers assume) with the unit in its 80-byte header text.

Axes: curvefold's models are z-up. OBJ readers (Blender, three.js, most viewers) take
+Y as up, so OBJ files are written Y-up by default, turned by ``(x, y, z) → (x, z, −y)``
(a rotation: faces keep their orientation), and the header comment says so. STL and PLY,
read mostly by slicers and CAD tools that take +Z as up, stay z-up.

The helpers :func:`crease_polylines` and :func:`check_metadata` are shared by the other
exporters.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import replace
from pathlib import Path
from types import MappingProxyType

import numpy as np

from ..geometry._mesh import EDGE_KINDS, Mesh
from ..kernel._arrays import readonly
from ..kernel._errors import InputError
from ..kernel._lie import cross
from ..kernel._text import one_line
from ._atomic import atomic_write
from ._tables import CREATOR, UNITS

__all__ = [
    "Y_UP",
    "check_metadata",
    "crease_polylines",
    "write_obj",
    "write_ply",
    "write_stl",
    "stl_records",
    "ply_bytes",
]

#: Rotation from the model's axes to a file's, for a file whose up axis is y or z.
Y_UP = MappingProxyType(
    {"y": readonly(np.array([[1.0, 0, 0], [0, 0, 1], [0, -1, 0]])), "z": readonly(np.eye(3))}
)


def check_metadata(metadata: Mapping | None) -> dict:
    """Validate design parameters and return them as a plain JSON-ready dict.

    Parameters
    ----------
    metadata : mapping of str to (int, float, str, bool) or None
        Design parameters. NumPy scalars are converted to Python numbers.

    Returns
    -------
    dict
        A new dict; ``{}`` for ``None``. Keys and strings are on one line, without control
        characters (:func:`curvefold.kernel._text.one_line`), whatever format they go to.

    Raises
    ------
    InputError
        If a key is not a string, or a value is not a finite number, a string or a bool.

    Examples
    --------
    >>> check_metadata({"length": np.float64(2.5), "name": "vault"})
    {'length': 2.5, 'name': 'vault'}
    >>> check_metadata({"title": "vault\\nv 999 999 999"})
    {'title': 'vault v 999 999 999'}
    >>> check_metadata(None)
    {}
    """
    if metadata is None:
        return {}
    if not isinstance(metadata, Mapping):
        raise InputError(
            f"metadata must be a mapping of str to number/str, got {type(metadata).__name__}"
        )
    out: dict = {}
    for key, value in metadata.items():
        if not isinstance(key, str):
            raise InputError(f"metadata keys must be str, got {key!r}")
        key = one_line(key)
        if isinstance(value, (str, bool, np.bool_)):
            out[key] = one_line(value) if isinstance(value, str) else bool(value)
        elif isinstance(value, (int, np.integer)):
            out[key] = int(value)
        elif isinstance(value, (float, np.floating)):
            if not math.isfinite(value):
                raise InputError(f"metadata[{key!r}] must be finite, got {value}")
            out[key] = float(value)
        else:
            raise InputError(
                f"metadata[{key!r}] must be a number or a str, got {type(value).__name__} {value!r}"
            )
    return out


def _check_kinds(kinds: Sequence[str], name: str = "kinds") -> tuple[str, ...]:
    kinds = (kinds,) if isinstance(kinds, str) else tuple(kinds)
    bad = [k for k in kinds if k not in EDGE_KINDS]
    if bad:
        raise InputError(f"{name} must be among {EDGE_KINDS}, got {bad}")
    return kinds


def crease_polylines(
    mesh: Mesh,
    kinds: str | Sequence[str] = "fold",
    *,
    split_angle_deg: float | None = None,
) -> list[np.ndarray]:
    """Chain the edges of the given kinds into polylines.

    Edges are joined at vertices where exactly two of the selected edges meet; every other
    vertex (an end, a junction of three or more) starts a new polyline. A closed loop is
    returned with its first vertex repeated at the end.

    Parameters
    ----------
    mesh : Mesh
    kinds : str or sequence of str
        Edge kinds to chain (see :data:`curvefold.geometry._mesh.EDGE_KINDS`).
    split_angle_deg : float, optional
        Also split where the polyline turns by more than this angle (degrees) in the
        mesh's state. Use a small value (e.g. 1e-3) for rulings, so that rulings of the two
        strips meeting at a crease vertex are not joined. ``None`` never splits on angle.

    Returns
    -------
    list of (n_i,) ndarray of int
        Vertex indices of each polyline (n_i >= 2), in a deterministic order.

    Examples
    --------
    >>> from curvefold.geometry import Mesh
    >>> m = Mesh(
    ...     vertices_coords=np.zeros((0, 3)),
    ...     edges_vertices=np.zeros((0, 2), int),
    ...     edges_assignment=np.zeros(0, str),
    ...     edges_foldAngle=np.zeros(0),
    ...     faces_vertices=np.zeros((0, 3), int),
    ...     edges_kind=np.zeros(0, str),
    ...     faces_group=np.zeros(0, int),
    ... )
    >>> crease_polylines(m)
    []
    """
    kinds = _check_kinds(kinds)
    chosen = np.flatnonzero(np.isin(mesh.edges_kind, kinds)).tolist()
    # Python ints: the walk below is one step at a time
    ends = dict(zip(chosen, mesh.edges_vertices[chosen].tolist()))
    incident: dict[int, list[int]] = {}
    for e in chosen:
        a, b = ends[e]
        incident.setdefault(a, []).append(e)
        incident.setdefault(b, []).append(e)

    cos_split = None if split_angle_deg is None else math.cos(math.radians(split_angle_deg))
    x = mesh.vertices_coords

    def other(e: int, v: int) -> int:
        a, b = ends[e]
        return b if v == a else a

    def passes_through(v: int) -> bool:
        edges = incident[v]
        if len(edges) != 2:
            return False
        if cos_split is None:
            return True
        d0 = x[v] - x[other(edges[0], v)]
        d1 = x[other(edges[1], v)] - x[v]
        n = np.linalg.norm(d0) * np.linalg.norm(d1)
        return bool(n > 0 and np.dot(d0, d1) >= cos_split * n)

    used: set[int] = set()
    out: list[np.ndarray] = []

    def walk(start: int, first_edge: int) -> np.ndarray:
        chain = [start]
        v, e = start, first_edge
        while True:
            used.add(e)
            v = other(e, v)
            chain.append(v)
            if v == start or not passes_through(v):
                break
            nxt = [f for f in incident[v] if f not in used]
            if not nxt:
                break
            e = nxt[0]
        return np.array(chain, dtype=np.int64)

    for v in sorted(incident):
        if not passes_through(v):
            for e in incident[v]:
                if e not in used:
                    out.append(walk(v, e))
    for e in chosen:  # what is left are closed loops through pass-through vertices only
        if e not in used:
            out.append(walk(ends[e][0], e))
    return out


def _fmt_rows(prefix: str, rows: np.ndarray, fmt: str) -> str:
    if len(rows) == 0:
        return ""
    line = prefix + " " + " ".join([fmt] * rows.shape[1]) + "\n"
    return (line * len(rows)) % tuple(rows.ravel().tolist())  # every row at once


def write_obj(
    path: str | os.PathLike,
    mesh: Mesh,
    *,
    crease_kinds: Sequence[str] = ("fold", "seam", "boundary"),
    unit: str = "unit",
    metadata: Mapping | None = None,
    name: str = "curvefold",
    up: str = "y",
) -> Path:
    """Write one state as a Wavefront OBJ with the crease lines as polylines.

    The file holds the vertices (``v``, 17 significant digits), the faces in group
    ``surface`` (``f``, polygons as in the mesh, counter-clockwise) and, for each kind in
    ``crease_kinds``, a group of that name with the chained crease lines (``l``). The unit
    and the design parameters are written as ``#`` comments, strings quoted as JSON strings
    on one line (a title can neither start a statement nor continue a line).

    Parameters
    ----------
    path : path-like
    mesh : Mesh
        The state to write (V vertices, F polygon faces).
    crease_kinds : sequence of str
        Edge kinds written as line groups, in this order.
    unit : str
        Length unit of the coordinates (recorded in a comment only).
    metadata : mapping, optional
        Design parameters (recorded as comments).
    name : str
        Object name (``o`` statement).
    up : {"y", "z"}
        The file's up axis: ``"y"`` turns the model's +z onto +y (see the module notes),
        ``"z"`` writes the coordinates as they are.

    Returns
    -------
    Path
        The written path.
    """
    crease_kinds = _check_kinds(crease_kinds, "crease_kinds")
    meta = check_metadata(metadata)
    if up not in Y_UP:
        raise InputError(f"up must be 'y' or 'z', got {up!r}")
    x = np.asarray(mesh.vertices_coords, float) @ Y_UP[up].T
    if not np.isfinite(x).all():
        raise InputError("mesh.vertices_coords must be finite")
    axes = (
        "+Y up: (x, y, z) of the model written as (x, z, -y)"
        if up == "y"
        else "+Z up, as in the model"
    )
    parts = ["# written by curvefold\n", f"# unit: {_line_end(unit)}\n", f"# axes: {axes}\n"]
    parts += [f"# {k}: {_comment(v)}\n" for k, v in meta.items()]
    parts.append(f"o {_line_end(name)}\n")
    parts.append(_fmt_rows("v", x, "%.17g"))
    parts.append("g surface\n")
    faces = mesh.faces_vertices
    if (faces < 0).any():  # polygons of mixed sizes
        parts.append(
            "".join(
                "f " + " ".join(str(v + 1) for v in row if v >= 0) + "\n" for row in faces.tolist()
            )
        )
    else:
        parts.append(_fmt_rows("f", faces + 1, "%d"))
    for kind in crease_kinds:
        lines = crease_polylines(mesh, kind)
        if lines:
            parts.append(f"g {kind}\n")
            parts += ["l " + " ".join(str(i + 1) for i in line.tolist()) + "\n" for line in lines]
    return atomic_write(path, "".join(parts))


def _comment(value) -> str:
    """A metadata value for an OBJ comment: a string quoted as JSON on one line, never
    ending in a backslash (which continues a line for some readers)."""
    return json.dumps(one_line(value), ensure_ascii=False) if isinstance(value, str) else str(value)


def _line_end(text: str) -> str:
    """Text that ends an OBJ line: one line, without a trailing backslash."""
    return one_line(text).rstrip("\\")


def _triangles(mesh: Mesh) -> tuple[np.ndarray, Mesh]:
    """The finite vertex coordinates (V, 3) and the triangulated mesh of a state."""
    x = np.asarray(mesh.vertices_coords, float)
    if not np.isfinite(x).all():
        raise InputError("mesh.vertices_coords must be finite")
    return x, mesh.triangulated()


def stl_records(x: np.ndarray, triangles: np.ndarray) -> bytes:
    """The triangle count and records of a binary STL (what follows its 80-byte header).

    Each record: the unit normal (zero for a degenerate triangle), the three corners as
    32-bit floats, and a zero attribute count.

    Examples
    --------
    >>> body = stl_records(np.eye(3), np.array([[0, 1, 2]]))
    >>> (
    ...     len(body),
    ...     int(np.frombuffer(body[:4], "<u4")[0]),
    ...     np.frombuffer(body[4:16], "<f4").astype(float).round(4).tolist(),
    ... )
    (54, 1, [0.5774, 0.5774, 0.5774])
    """
    corners = x[triangles]  # (T, 3, 3)
    normal = cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    length = np.linalg.norm(normal, axis=1, keepdims=True)
    record = np.zeros(
        len(triangles),
        dtype=[("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")],
    )
    record["normal"] = np.divide(normal, length, out=np.zeros_like(normal), where=length > 0)
    record["corners"] = corners
    return np.uint32(len(triangles)).astype("<u4").tobytes() + record.tobytes()


def ply_bytes(x: np.ndarray, triangles: np.ndarray, groups: np.ndarray) -> bytes:
    r"""A binary little-endian PLY: vertices as 32-bit floats, triangles with the face property
    ``group``.

    Examples
    --------
    >>> text = ply_bytes(np.eye(3), np.array([[0, 1, 2]]), np.array([7]))
    >>> text.split(b"end_header\n")[0].decode().splitlines()[:4]
    ['ply', 'format binary_little_endian 1.0', 'comment curvefold', 'element vertex 3']
    >>> len(text.split(b"end_header\n")[1])  # 3 vertices of 12 bytes, a face of 1 + 12 + 4
    53
    """
    header = "\n".join(
        [
            "ply",
            "format binary_little_endian 1.0",
            "comment curvefold",
            f"element vertex {len(x)}",
            "property float x",
            "property float y",
            "property float z",
            f"element face {len(triangles)}",
            "property list uchar int vertex_indices",
            "property int group",
            "end_header",
            "",
        ]
    )
    face = np.zeros(
        len(triangles), dtype=[("count", "u1"), ("vertices", "<i4", 3), ("group", "<i4")]
    )
    face["count"], face["vertices"], face["group"] = 3, triangles, groups
    return header.encode("ascii") + np.asarray(x, "<f4").tobytes() + face.tobytes()


def write_stl(
    path: str | os.PathLike,
    mesh: Mesh,
    *,
    unit: str = "unit",
    to_unit: str | None = None,
    scale: float | None = None,
) -> Path:
    """Write one state as a binary STL (polygons triangulated, 32-bit floats: :func:`stl_records`).

    Parameters
    ----------
    path : path-like
    mesh : Mesh
        The state to write.
    unit : str
        Length unit of the mesh's coordinates, a name in :data:`curvefold.io._tables.UNITS`
        (``"unit"``, the model unit, counts as one metre).
    to_unit : str, optional
        Length unit of the file (``"mm"`` for slicers, which read millimetres); default
        ``unit``. The 80-byte header says it: ``curvefold 0.1.0, unit mm, z up``.
    scale : float, optional
        A print scale: millimetres in the file per ``unit`` of the mesh (a crease pattern's
        :attr:`~curvefold.io.Layout.scale`, so that the model prints as large as its pattern);
        the header says it: ``curvefold 0.1.0, unit mm, 1 model unit = 80 mm, z up``. Default
        the true size (a model unit counts as one metre).

    Returns
    -------
    Path

    Notes
    -----
    The file is a surface, each sheet's mid-surface without thickness, open along its
    boundary: not a closed solid a slicer could fill.

    Examples
    --------
    >>> from curvefold.io._tables import UNITS
    >>> UNITS["unit"].metres / UNITS["mm"].metres  # a model unit in the file when to_unit="mm"
    1000.0
    """
    to_unit = unit if to_unit is None else to_unit
    for name, value in (("unit", unit), ("to_unit", to_unit)):
        if value not in UNITS:
            raise InputError(
                f"{name} must be one of {', '.join(UNITS)}, got {value!r}", parameter="units"
            )
    if scale is not None and not (math.isfinite(scale) and scale > 0):
        raise InputError(f"scale must be a positive number of mm, got {scale!r}", parameter="scale")
    factor = (
        UNITS[unit].metres / UNITS[to_unit].metres
        if scale is None
        else scale * UNITS["mm"].metres / UNITS[to_unit].metres
    )
    scaled = (
        mesh
        if factor == 1.0
        else replace(mesh, vertices_coords=np.asarray(mesh.vertices_coords) * factor)
    )
    x, triangles = _triangles(scaled)
    words = "model units (1 model unit = 1 m)" if to_unit == "unit" else to_unit
    if scale is not None:
        one = "model unit" if unit == "unit" else unit
        words += f", 1 {one} = {factor:.6g} {'model units' if to_unit == 'unit' else to_unit}"
    header = (
        one_line(f"{CREATOR}, unit {words}, z up").encode("ascii", "replace")[:80].ljust(80, b" ")
    )
    return atomic_write(path, header + stl_records(x, triangles.faces_vertices))


def write_ply(path: str | os.PathLike, mesh: Mesh) -> Path:
    """Write one state as a binary little-endian PLY (:func:`ply_bytes`).

    Vertices are 32-bit floats; polygons are triangulated and each triangle carries the
    strip index of its face as the face property ``group`` (``mesh.faces_group``).

    Parameters
    ----------
    path : path-like
    mesh : Mesh
        The state to write.

    Returns
    -------
    Path
    """
    x, triangles = _triangles(mesh)
    return atomic_write(path, ply_bytes(x, triangles.faces_vertices, triangles.faces_group))
