"""From a structure to fabrication and interchange files: sheets, FOLD, patterns, 3D.

The flat state ``structure.state(0)`` *is* the crease pattern (DESIGN.md §2): every lattice
curve lies in one plane, the folds (creases 1 and 3) are flat and the seams (2 and 4) are
closed, so each tube is two plies. Each tube is cut into two sheets:

* sheet A: strips 4→1 and 1→2 around fold crease 1 (``faces_group`` 4k + 3 and 4k);
* sheet B: strips 2→3 and 3→4 around fold crease 3 (``faces_group`` 4k + 1 and 4k + 2).

The two sheets of a tube are welded along seams 2 and 4: both carry the same seam curve
as an outline edge with a shared seam id (tube k: seam 2 has id 2k, seam 4 has id 2k + 1).
Tubes that share a lattice curve (curve 3 of tube k is curve 1 of tube k + 1 in a
diagonal stack; neighbours of a cellular block share whole walls) are glued along it; such
a glue line is a :class:`Bond`, not a cut.

Conventions
    Sheets are in model units, in the plane of the flat state, each seen from the outside
    of its tube: triangles are counter-clockwise and fold angles follow FOLD's sign (valley
    positive) with outward normals, so at a design angle 2α the folds are mountains of
    about −2α. Angles are in degrees unless ``degrees=False``. Tube numbers in labels are
    1-based ("tube 1"), tube indices in the API 0-based.

Sheet vertices are the tube mesh's vertices: :func:`sheet_vertices` maps every sheet
vertex to its index in ``State.mesh()`` (vertex ``(4k + c)·n + j`` is sample j of corner
c + 1 of tube k), so any state can be put on the sheets' topology; the FOLD file uses
that to give its crease pattern and folded frames one topology.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .crease import half_angle
from .errors import CurvefoldError, InputError
from .lie import cross
from .mesh import Mesh, edges_faces
from .structure import State, Structure

if TYPE_CHECKING:  # the exporters are imported when used
    from .export.fold import FoldFile
    from .export.layout import Layout, PatternSheet

__all__ = [
    "PATTERN_FORMATS",
    "MODEL_FORMATS",
    "SHEET_NAMES",
    "Bond",
    "FlatPlane",
    "bonds",
    "flat_plane",
    "folding_motion",
    "layout_pattern",
    "sheet_vertices",
    "sheets",
    "to_fold",
    "unroll_strip",
    "write_3d",
    "write_pattern",
    "write_structure_fold",
]

#: Crease-pattern formats :func:`write_pattern` writes.
PATTERN_FORMATS = ("svg", "dxf", "pdf")
#: 3D formats :func:`write_3d` writes.
MODEL_FORMATS = ("glb", "obj", "stl", "ply", "3dm")
#: Names of a tube's two sheets, in order.
SHEET_NAMES = ("A", "B")

# Strips of sheets A and B (strip c runs from corner index c to c + 1, 0-based).
_SHEET_STRIPS = ((3, 0), (1, 2))
# Seam corner index (1: seam 2, 3: seam 4) → offset of its seam id (tube k: 2k + offset).
_SEAM_OFFSET = {1: 0, 3: 1}
#: Print scales are rounded down to one of these times a power of ten.
_NICE = (1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0)


# --------------------------------------------------------------------------------------
# validation


def _check_structure(structure: Structure) -> Structure:
    if not isinstance(structure, Structure):
        raise InputError(f"structure must be a Structure, got {type(structure).__name__}")
    return structure


def _design_angle(structure: Structure, fold_angle: float | None, degrees: bool) -> float:
    """The fold angle 2α in degrees: the given one (validated, > 0) or the lattice's own."""
    if fold_angle is None:
        return math.degrees(structure.lattice.crease.fold_angle)
    half_angle(fold_angle, degrees=degrees)
    return float(fold_angle) if degrees else math.degrees(fold_angle)


def _angles(values, degrees: bool, name: str) -> np.ndarray:
    """A non-empty 1D array of fold angles in degrees, each in [0°, 180°)."""
    try:
        arr = np.atleast_1d(np.asarray(values, float))
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a sequence of numbers, got {values!r}") from None
    if arr.ndim != 1 or arr.size == 0:
        raise InputError(f"{name} must be a non-empty sequence of fold angles, got shape {np.shape(values)}")
    for a in arr:
        half_angle(a, degrees=degrees, name=name, allow_flat=True)
    return arr if degrees else np.degrees(arr)


def _check_formats(formats, allowed: tuple[str, ...]) -> tuple[str, ...]:
    formats = (formats,) if isinstance(formats, str) else tuple(formats)
    bad = [f for f in formats if f not in allowed]
    if bad or not formats:
        raise InputError(f"formats must be a non-empty selection of {allowed}, got {formats!r}")
    return tuple(dict.fromkeys(formats))


def _target(path_stem: str | os.PathLike, suffix: str) -> Path:
    stem = Path(path_stem)
    return stem.with_name(f"{stem.name}.{suffix}")


# --------------------------------------------------------------------------------------
# sheets


def sheet_vertices(structure: Structure) -> tuple[np.ndarray, ...]:
    """For every sheet, its vertices as indices into the vertices of ``State.mesh()``.

    Sheets are ordered tube by tube, A then B. Sheet A of tube k holds corners 4, 1, 2
    (samples of each in order, corner 4 first: the order of its vertices on the sheet),
    sheet B corners 2, 3, 4. Seam curves belong to both sheets of their tube.

    Parameters
    ----------
    structure : Structure

    Returns
    -------
    tuple of (3n,) ndarray of int
        One per sheet, ``2 K`` in all for K tubes.

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice
    >>> lat = Lattice.from_crease(Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=3)), 0.1, 0.1)
    >>> [v.tolist() for v in sheet_vertices(Structure.tube(lat))]
    [[9, 10, 11, 0, 1, 2, 3, 4, 5], [3, 4, 5, 6, 7, 8, 9, 10, 11]]
    """
    _check_structure(structure)
    n = len(structure.lattice.s)
    j = np.arange(n)
    out = []
    for k in range(len(structure.cells)):
        for strips in _SHEET_STRIPS:
            corners = (strips[0], strips[1], (strips[1] + 1) % 4)
            out.append(np.concatenate([(4 * k + c) * n + j for c in corners]))
    return tuple(out)


@dataclass(frozen=True, eq=False)
class FlatPlane:
    """The plane of the flat state with an in-plane frame.

    Attributes
    ----------
    origin : (3,) ndarray
        Curve 1's start.
    axes : (3, 3) ndarray
        Rows e1, e2, n: e1 along curve 1's tangent at its start, n the plane's unit normal
        (on the side of curve 1's binormal there), e2 = n × e1.
    residual : float
        Largest distance of a flat-state vertex from the plane.
    """

    origin: np.ndarray
    axes: np.ndarray
    residual: float

    def coords(self, points: np.ndarray, *, flip: bool = False) -> np.ndarray:
        """In-plane coordinates (..., 2) of points (..., 3), seen from +n (or from −n if ``flip``)."""
        d = np.asarray(points, float) - self.origin
        x, y = d @ self.axes[0], d @ self.axes[1]
        return np.stack([x, -y if flip else y], axis=-1)


def flat_plane(state: State, *, tol: float = 1e-9) -> FlatPlane:
    """The plane of a flat state, fitted to its vertices by SVD.

    Parameters
    ----------
    state : State
        A flat state, ``structure.state(0)``.
    tol : float, keyword-only
        Largest allowed distance of a vertex from the plane, relative to the state's size.

    Returns
    -------
    FlatPlane

    Raises
    ------
    CurvefoldError
        If the state is not planar within ``tol`` (it is not the flat state).
    """
    if not isinstance(state, State):
        raise InputError(f"state must be a State (e.g. structure.state(0)), got {type(state).__name__}")
    x = state.vertices.reshape(-1, 3)
    centre = x.mean(axis=0)
    _, _, vt = np.linalg.svd(x - centre, full_matrices=False)
    frame = state.lattice.crease.curve.frames[0]  # columns T, N, B of curve 1 at t = 0
    normal = vt[2] if vt[2] @ frame[:, 2] >= 0 else -vt[2]
    origin = np.array(state.lattice.crease.curve.points[0])
    e1 = frame[:, 0] - (frame[:, 0] @ normal) * normal
    e1 /= np.linalg.norm(e1)
    residual = float(np.abs((x - origin) @ normal).max())
    size = float(np.ptp(x, axis=0).max())
    if residual > tol * max(size, 1e-300):
        raise CurvefoldError(
            f"the flat state is not planar: a vertex lies {residual:.3g} from the fitted plane "
            f"(allowed {tol:g} × size {size:.3g}); is the state at fold angle 0?"
        )
    axes = np.stack([e1, cross(normal, e1), normal])
    for a in (origin, axes):
        a.flags.writeable = False
    return FlatPlane(origin, axes, residual)


def _oriented_edges(faces: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """Edges (E, 2) turned to run as the first face (lowest index) that traverses them."""
    ef = edges_faces(faces, edges)
    big = np.iinfo(np.int64).max
    fwd, rev = np.where(ef[:, 0] >= 0, ef[:, 0], big), np.where(ef[:, 1] >= 0, ef[:, 1], big)
    return np.where((rev < fwd)[:, None], edges[:, ::-1], edges)


@dataclass(frozen=True, eq=False)
class _SheetTopology:
    """One sheet in the tube mesh's numbering (private)."""

    tube: int
    which: int  # 0 = A, 1 = B
    verts: np.ndarray  # (3n,) tube-mesh vertices, in sheet order
    face_mask: np.ndarray  # (F,) bool over the tube mesh's faces
    edges: np.ndarray  # (E_s, 2) tube-mesh vertices, oriented as the sheet's first face runs
    edge_ids: np.ndarray  # (E_s,) indices into the tube mesh's edges
    seam: np.ndarray  # (E_s,) seam id or -1

    @property
    def label(self) -> str:
        return f"tube {self.tube + 1} · sheet {SHEET_NAMES[self.which]}"


def _sheet_topology(mesh: Mesh, structure: Structure) -> list[_SheetTopology]:
    """Faces, edges and seam ids of every sheet in the numbering of the tube mesh ``mesh``."""
    n = len(structure.lattice.s)
    edge_tube = mesh.edges_vertices[:, 0] // (4 * n)
    out = []
    for i, verts in enumerate(sheet_vertices(structure)):
        k, which = divmod(i, 2)
        mask = np.isin(mesh.faces_group, [4 * k + c for c in _SHEET_STRIPS[which]])
        faces = mesh.faces_vertices[mask]
        candidates = np.flatnonzero(edge_tube == k)
        inside = np.isin(mesh.edges_vertices[candidates], verts).all(axis=1)
        ids = candidates[inside]
        ev = _oriented_edges(faces, mesh.edges_vertices[ids])
        if not (edges_faces(faces, ev) >= 0).any(axis=1).all():  # pragma: no cover - a topology bug
            raise CurvefoldError(f"tube {k + 1} sheet {SHEET_NAMES[which]}: an edge borders none of the sheet's faces")
        seam = np.full(len(ids), -1, np.int64)
        corner = (ev[:, 0] // n) % 4
        for c, offset in _SEAM_OFFSET.items():
            seam[(mesh.edges_kind[ids] == "seam") & (corner == c)] = 2 * k + offset
        out.append(_SheetTopology(k, which, verts, mask, ev, ids, seam))
    return out


def _develop(structure: Structure, fold_angle_deg: float, name: str) -> tuple[tuple[PatternSheet, ...], tuple[np.ndarray, ...]]:
    """The sheets (PatternSheet) and their vertex maps into the tube mesh."""
    from .export.layout import PatternSheet

    flat = structure.state(0.0)
    plane = flat_plane(flat)
    flat_mesh = flat.mesh()
    design = structure.state(fold_angle_deg).mesh()
    normals = flat_mesh.face_normals()
    out, maps = [], []
    for sh in _sheet_topology(flat_mesh, structure):
        label = f"{name} · {sh.label}" if name else sh.label
        facing = normals[sh.face_mask] @ plane.axes[2]  # ±1: the outside faces +n or −n
        xy = plane.coords(flat_mesh.vertices_coords[sh.verts], flip=bool(facing.mean() < 0))
        lookup = np.full(int(sh.verts.max()) + 1, -1, np.int64)
        lookup[sh.verts] = np.arange(len(sh.verts))
        faces = lookup[flat_mesh.faces_vertices[sh.face_mask]]
        u, v = xy[faces[:, 1]] - xy[faces[:, 0]], xy[faces[:, 2]] - xy[faces[:, 0]]
        area2 = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
        if not (area2 > 0).all():
            raise CurvefoldError(f"{label}: {int(np.count_nonzero(area2 <= 0))} of {len(area2)} triangles of the flat "
                                 "state are not counter-clockwise seen from outside the tube")
        kind = design.edges_kind[sh.edge_ids]
        angle = np.where(kind == "fold", design.edges_foldAngle[sh.edge_ids], 0.0)
        assignment = np.where(kind == "fold", np.where(angle > 0, "V", "M"),
                              np.where(np.isin(kind, ("seam", "boundary")), "B", "F"))
        mesh = Mesh(
            vertices_coords=np.column_stack([xy, np.zeros(len(xy))]),
            edges_vertices=lookup[sh.edges],
            edges_assignment=assignment.astype("<U1"),
            edges_foldAngle=angle,
            faces_vertices=faces,
            edges_kind=kind,
            faces_group=flat_mesh.faces_group[sh.face_mask],
        )
        out.append(PatternSheet(label, mesh, sh.seam))
        maps.append(sh.verts)
    return tuple(out), tuple(maps)


def sheets(structure: Structure, *, fold_angle: float | None = None, degrees: bool = True,
           name: str = "") -> tuple[PatternSheet, ...]:
    """The developed sheets of a structure: its crease pattern, two sheets per tube.

    Coordinates come from the flat state ``structure.state(0)``, in model units, in the
    plane of that state (:func:`flat_plane`: origin at curve 1's start, x along its
    tangent there), each sheet seen from the outside of its tube (triangles
    counter-clockwise; sheets seen from the plane's back are mirrored, y → −y). Sheets of
    one tube overlap there (the flat tube is two plies): :func:`layout_pattern` and
    :func:`to_fold` place them apart.

    Parameters
    ----------
    structure : Structure
    fold_angle : float, optional, keyword-only
        The target 2α whose fold angles the sheets carry; default the lattice's own.
    degrees : bool, keyword-only
    name : str, keyword-only
        Prefix of the labels (``"vault · tube 2 · sheet A"``).

    Returns
    -------
    tuple of PatternSheet
        ``2 K`` sheets for K tubes: tube 1 sheet A, tube 1 sheet B, tube 2 sheet A…
        Edge kinds: ``"fold"`` on the sheet's crease (assignment ``M``/``V`` and
        ``edges_foldAngle`` measured on the mesh of the target state: about −2α, a
        mountain seen from outside), ``"seam"`` on the two seam curves (seam ids shared
        with the partner edges of the tube's other sheet: seam 2 of tube k is 2k, seam 4
        is 2k + 1), ``"boundary"`` on the end rulings, ``"ruling"`` and ``"diagonal"``
        inside. ``faces_group`` is the strip index 4k + c of the tube mesh.

    Raises
    ------
    InputError
        For a fold angle outside (0°, 180°).
    CurvefoldError
        If the flat state is not planar or a sheet is not one-sided in it (a bug).

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice
    >>> lat = Lattice.from_crease(Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=9)), 0.1, 0.1)
    >>> [s.label for s in sheets(Structure.tube(lat))]
    ['tube 1 · sheet A', 'tube 1 · sheet B']
    """
    _check_structure(structure)
    if not isinstance(name, str):
        raise InputError(f"name must be a str, got {type(name).__name__}")
    return _develop(structure, _design_angle(structure, fold_angle, degrees), name)[0]


# --------------------------------------------------------------------------------------
# bonds


@dataclass(frozen=True)
class Bond:
    """A lattice curve shared by several tubes: a glue line between them.

    Attributes
    ----------
    curve : tuple of int
        The lattice curve (u, v).
    creases : tuple of (int, int)
        (tube index, crease number 1–4) of every tube crease on this curve, in tube order.
        A fold crease (1, 3) lies on one sheet of its tube (A, B), a seam (2, 4) on both.
    """

    curve: tuple[int, int]
    creases: tuple[tuple[int, int], ...]

    def describe(self) -> str:
        """One line for people: ``"curve (1, 1): tube 1 crease 3 + tube 2 crease 1"``."""
        parts = " + ".join(f"tube {k + 1} crease {c}" for k, c in self.creases)
        return f"curve ({self.curve[0]}, {self.curve[1]}): {parts}"


def bonds(structure: Structure) -> tuple[Bond, ...]:
    """The glue lines of a structure: every lattice curve that bounds two or more tubes.

    In a diagonal stack curve 3 of tube k is curve 1 of tube k + 1 (the tubes touch along
    that crease); in a cellular block neighbours share a wall, i.e. both curves bounding
    it are bonds. A single tube has none.

    Parameters
    ----------
    structure : Structure

    Returns
    -------
    tuple of Bond
        Sorted by curve (u, v).
    """
    _check_structure(structure)
    members: dict[int, list[tuple[int, int]]] = {}
    for k, row in enumerate(structure.cell_curves.tolist()):
        for c, m in enumerate(row):
            members.setdefault(m, []).append((k, c + 1))
    uv = structure.curves_uv.tolist()
    return tuple(Bond(tuple(uv[m]), tuple(v)) for m, v in sorted(members.items()) if len(v) > 1)


# --------------------------------------------------------------------------------------
# independent unrolling


def _corner_angle(p: np.ndarray, q: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Interior angle at p of triangles (p, q, r), each (m, 3); shape (m,)."""
    u, v = q - p, r - p
    return np.arctan2(np.linalg.norm(cross(u, v), axis=-1), np.einsum("ij,ij->i", u, v))


def unroll_strip(points_a: np.ndarray, points_b: np.ndarray) -> np.ndarray:
    """Develop a triangulated ruled strip into the plane, triangle by triangle.

    The strip between curves a and b (rulings a_j b_j) is triangulated as the tube mesh
    is, by ``(a_j, b_{j+1}, b_j)`` and ``(a_j, a_{j+1}, b_{j+1})``. Every triangle keeps its
    3D edge lengths and is laid beside the previous one, advancing along t: the direction
    of each ruling is the previous one turned by π minus the three corner angles between
    them, and a and b follow by summing edge vectors (no closure is imposed, so errors
    would show). Independent of how curvefold builds flat states.

    Parameters
    ----------
    points_a, points_b : (n, 3) array_like
        The two curves of the strip at the same samples, n ≥ 2.

    Returns
    -------
    (2, n, 2) ndarray
        Developed a and b: a_0 at the origin, b_0 on the +y axis, the triangles
        ``(a_j, b_{j+1}, b_j)`` counter-clockwise (a strip of the tube mesh from corner
        c to c + 1 comes out seen from outside the tube).

    Examples
    --------
    A quarter of a unit cylinder unrolls to a rectangle of height 1 whose length is the
    sum of the chords:

    >>> t = np.linspace(0, np.pi / 2, 5)
    >>> a = np.stack([np.cos(t), np.sin(t), 0 * t], axis=1)
    >>> flat = unroll_strip(a, a + [0, 0, 1])
    >>> bool(np.allclose(flat[1] - flat[0], [0, 1])), bool(np.allclose(flat[0, -1], [8 * np.sin(np.pi / 16), 0]))
    (True, True)
    """
    a = np.asarray(points_a, float)
    b = np.asarray(points_b, float)
    if a.ndim != 2 or a.shape[1] != 3 or a.shape != b.shape or len(a) < 2:
        raise InputError(f"points_a and points_b must both have shape (n, 3) with n ≥ 2, got {a.shape} and {b.shape}")
    if not (np.isfinite(a).all() and np.isfinite(b).all()):
        raise InputError("points_a and points_b must be finite")
    a0, a1, b0, b1 = a[:-1], a[1:], b[:-1], b[1:]
    first = _corner_angle(a0, b1, b0)  # triangle (a_j, b_{j+1}, b_j) at a_j
    second = _corner_angle(a0, a1, b1)  # triangle (a_j, a_{j+1}, b_{j+1}) at a_j
    second_next = _corner_angle(a1, b1, a0)  # the same triangle at a_{j+1}
    # direction of the ruling a_j → b_j, and of the chord a_j → a_{j+1}
    ruling = 0.5 * np.pi + np.concatenate([[0.0], np.cumsum(np.pi - first - second - second_next)])
    along = ruling[:-1] - first - second
    step = np.linalg.norm(a1 - a0, axis=-1)[:, None] * np.stack([np.cos(along), np.sin(along)], axis=-1)
    a2 = np.concatenate([np.zeros((1, 2)), np.cumsum(step, axis=0)])
    b2 = a2 + np.linalg.norm(b - a, axis=-1)[:, None] * np.stack([np.cos(ruling), np.sin(ruling)], axis=-1)
    return np.stack([a2, b2])


# --------------------------------------------------------------------------------------
# FOLD


def folding_motion(structure: Structure, fold_angles, *, degrees: bool = True, anchor: str = "start") -> np.ndarray:
    """Vertex positions of ``State.mesh()`` at many fold angles at once, shape (A, 4·K·n, 3).

    The vectorised form of ``[structure.state(f, anchor=anchor).mesh().vertices_coords for f
    in fold_angles]`` (one Frenet integration for all angles).

    Parameters
    ----------
    structure : Structure
    fold_angles : (A,) array_like
        2α values in [0°, 180°).
    degrees : bool, keyword-only
    anchor : {"start", "middle"}, keyword-only
        Which frame of curve 1 stays fixed (see :meth:`Structure.state`).
    """
    _check_structure(structure)
    angles = _angles(fold_angles, degrees, "fold_angles")
    points = structure.lattice.fold_points(structure.curves_uv, angles, anchor=anchor)  # (A, M, n, 3)
    return points[:, structure.cell_curves].reshape(len(angles), -1, 3)


def _metadata(structure: Structure, design_deg: float, extra: Mapping | None) -> dict:
    from .export.mesh3d import check_metadata

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
) -> FoldFile:
    """A structure as a FOLD model: crease pattern plus folded states on one topology.

    The crease pattern is every sheet of :func:`sheets`, laid in a row along +x (bounding
    boxes 5 % of the largest sheet apart, each sheet seen from outside, so triangles are
    counter-clockwise). Seams are cut open: each seam edge appears once per sheet as a
    boundary edge, and the two copies are paired in ``seam_partners`` (the edges run
    opposite ways, as their faces traverse them). The folded frames put the same vertices
    at their 3D positions, so partner vertices coincide there.

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

    Returns
    -------
    curvefold.export.FoldFile
        What :func:`write_structure_fold` writes and :func:`curvefold.export.read_fold`
        reads back.
    """
    from .export.fold import FoldFile

    _check_structure(structure)
    design = _design_angle(structure, fold_angle, degrees)
    angles = np.array([design]) if fold_angles is None else _angles(fold_angles, degrees, "fold_angles")
    if not isinstance(unit, str) or not unit:
        raise InputError(f"unit must be a non-empty str, got {unit!r}")
    meta = _metadata(structure, design, metadata)
    parts, maps = _develop(structure, design, "")
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
        faces_vertices=np.concatenate([p.mesh.faces_vertices + v_off[i] for i, p in enumerate(parts)]),
        edges_kind=cat("edges_kind"),
        faces_group=cat("faces_group"),
    )
    # Seam partners: the same tube-mesh edge on the two sheets of a tube.
    source = np.concatenate(maps)
    seam = np.concatenate([p.edges_seam for p in parts])
    ids = np.flatnonzero(seam >= 0)
    key = np.sort(source[cp.edges_vertices[ids]], axis=1)
    order = np.lexsort((key[:, 1], key[:, 0], seam[ids]))
    pairs = ids[order].reshape(-1, 2)
    if not (np.sort(source[cp.edges_vertices[pairs[:, 0]]], axis=1) == np.sort(source[cp.edges_vertices[pairs[:, 1]]], axis=1)).all():
        raise CurvefoldError("seam edges do not pair up between the two sheets of a tube")  # pragma: no cover - a bug
    pairs.flags.writeable = False

    coords = folding_motion(structure, angles, anchor=anchor)[:, source]  # (A, V, 3)
    folded = tuple((f"fold angle {a:g}°", cp.with_coords(x)) for a, x in zip(angles, coords))
    return FoldFile(crease_pattern=cp, folded=folded, metadata=meta, unit=unit, seam_partners=pairs)


def write_structure_fold(path: str | os.PathLike, structure: Structure, *, title: str = "", **kwargs) -> Path:
    """Write :func:`to_fold` of a structure as a FOLD 1.1 file (via :func:`curvefold.export.write_fold`).

    Parameters
    ----------
    path : path-like
    structure : Structure
    title : str, keyword-only
        ``file_title``.
    **kwargs
        Passed to :func:`to_fold` (``fold_angles``, ``fold_angle``, ``degrees``, ``unit``,
        ``metadata``, ``anchor``).

    Returns
    -------
    Path
    """
    from .export.fold import write_fold

    model = to_fold(structure, **kwargs)
    return write_fold(path, crease_pattern=model.crease_pattern, folded=model.folded, metadata=model.metadata,
                      unit=model.unit, seam_partners=model.seam_partners, title=title)


# --------------------------------------------------------------------------------------
# crease patterns on paper


def _nice_floor(value: float) -> float:
    """The largest 1, 1.25, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 × 10^k not above ``value``."""
    exp = math.floor(math.log10(value))
    mant = value / 10.0**exp
    return max(m for m in _NICE if m <= mant * (1 + 1e-12)) * 10.0**exp


def _fit_scale(parts, page, units: str, margin_mm: float, tab_mm: float) -> float:
    """Page units per model unit that fit the largest sheet (principal axes) with its tabs."""
    from .export.layout import UNITS, page_size

    W, H = page_size(page, units=units)
    room = np.array(sorted((W, H), reverse=True)) - 2 * margin_mm - 2 * tab_mm
    if (room <= 0).any():
        raise InputError(f"page {page!r} leaves no room for a sheet inside the margins and glue tabs")
    best = math.inf
    for p in parts:
        xy = p.mesh.vertices_coords[:, :2]
        xy = xy - xy.mean(axis=0)
        _, _, vt = np.linalg.svd(xy, full_matrices=False)
        ext = np.sort(np.ptp(xy @ vt.T, axis=0))[::-1]
        best = min(best, float(np.min(room / np.maximum(ext, 1e-300))))
    return _nice_floor(best / UNITS[units])


def layout_pattern(
    structure: Structure,
    *,
    fold_angle: float | None = None,
    degrees: bool = True,
    page="A4",
    units: str = "mm",
    scale: float | None = None,
    glue_tabs: bool = True,
    name: str = "",
) -> Layout:
    """The sheets of a structure placed on pages with glue tabs, layers and labels.

    Parameters
    ----------
    structure : Structure
    fold_angle : float, optional, keyword-only
        Target 2α of the folds (their M/V); default the lattice's own.
    degrees : bool, keyword-only
    page : str or (2,) tuple, keyword-only
        Page name (``"A4"``…) or (width, height) in ``units``.
    units : {"mm", "cm", "in", "pt"}, keyword-only
        Unit of ``page`` and ``scale``.
    scale : float, optional, keyword-only
        Page length in ``units`` per model unit. Default: the largest sheet (along its
        principal axes, long side along the page's long side, with room for glue tabs)
        fills the page inside its margins, rounded down to 1, 1.25, 1.5, 2, 2.5, 3, 4, 5,
        6 or 8 × 10^k so the print scale reads plainly (the PDF footer states it).
    glue_tabs : bool, keyword-only
    name : str, keyword-only
        Label prefix.

    Returns
    -------
    curvefold.export.layout.Layout
    """
    from .export.layout import layout_sheets

    _check_structure(structure)
    parts = sheets(structure, fold_angle=fold_angle, degrees=degrees, name=name)
    if scale is not None:
        return layout_sheets(parts, page=page, units=units, scale=scale, glue_tabs=glue_tabs)
    guess = _fit_scale(parts, page, units, 10.0, 6.0 if glue_tabs else 0.0)
    # The layout turns each sheet to its minimum-area rectangle, which can be longer than the
    # principal-axes box; step down the series of plain scales until it fits.
    for attempt in range(4):
        try:
            return layout_sheets(parts, page=page, units=units, scale=guess, glue_tabs=glue_tabs)
        except InputError:
            if attempt == 3:
                raise
            guess = _nice_floor(guess * (1 - 1e-9))
    raise AssertionError("unreachable")  # pragma: no cover


def write_pattern(
    path_stem: str | os.PathLike,
    structure: Structure,
    *,
    formats: Sequence[str] = PATTERN_FORMATS,
    page="A4",
    scale: float | None = None,
    units: str = "mm",
    glue_tabs: bool = True,
    rulings: bool = False,
    fold_angle: float | None = None,
    degrees: bool = True,
    name: str = "",
) -> tuple[Path, ...]:
    """Write the crease pattern of a structure, laid out on pages, as SVG, DXF and/or PDF.

    Parameters
    ----------
    path_stem : path-like
        Files are ``<stem>.svg`` (or ``<stem>-p1.svg``… for several pages), ``<stem>.dxf``
        and ``<stem>.pdf``.
    structure : Structure
    formats : sequence of {"svg", "dxf", "pdf"}, keyword-only
    page, scale, units, glue_tabs, fold_angle, degrees, name : keyword-only
        As in :func:`layout_pattern`.
    rulings : bool, keyword-only
        Also draw the rulings (thin grey, for scoring).

    Returns
    -------
    tuple of Path
        The files written, in the order of ``formats``.
    """
    from .export.pattern import DEFAULT_LAYERS, LAYERS, write_dxf, write_pdf, write_svg

    formats = _check_formats(formats, PATTERN_FORMATS)
    layout = layout_pattern(structure, fold_angle=fold_angle, degrees=degrees, page=page, units=units, scale=scale,
                            glue_tabs=glue_tabs, name=name)
    layers = LAYERS if rulings else DEFAULT_LAYERS
    out: list[Path] = []
    for fmt in formats:
        target = _target(path_stem, fmt)
        if fmt == "svg":
            out.extend(write_svg(target, layout, layers=layers))
        elif fmt == "dxf":
            out.append(write_dxf(target, layout, layers=layers))
        else:
            out.append(write_pdf(target, layout, layers=layers))
    return tuple(out)


# --------------------------------------------------------------------------------------
# 3D


def write_3d(
    path_stem: str | os.PathLike,
    structure: Structure,
    fold_angles=None,
    *,
    fold_angle: float | None = None,
    degrees: bool = True,
    formats: Sequence[str] = MODEL_FORMATS,
    unit: str = "unit",
    metadata: Mapping | None = None,
    anchor: str = "start",
    seconds_per_state: float = 1.0,
) -> tuple[Path, ...]:
    """Write the folded structure as 3D files; the GLB holds the folding motion.

    Parameters
    ----------
    path_stem : path-like
        Files are ``<stem>.glb``, ``<stem>.obj``… one per format.
    structure : Structure
    fold_angles : (A,) array_like, optional
        2α of the states of the GLB animation (morph targets), in [0°, 180°); default
        seven steps from 0° (flat) to the design angle.
    fold_angle : float, optional, keyword-only
        The state written to OBJ, STL, PLY and 3dm; default the design angle.
    degrees : bool, keyword-only
    formats : sequence of {"glb", "obj", "stl", "ply", "3dm"}, keyword-only
    unit : str, keyword-only
        Model unit (``"unit"``, ``"m"``, ``"mm"``…); GLB converts it to metres.
    metadata : mapping, optional, keyword-only
        Extra design parameters, merged over the defaults of :func:`to_fold`.
    anchor : {"start", "middle"}, keyword-only
    seconds_per_state : float, keyword-only
        GLB animation time between consecutive states.

    Returns
    -------
    tuple of Path
        The files written, in the order of ``formats``.
    """
    from .export import gltf, mesh3d, rhino

    _check_structure(structure)
    formats = _check_formats(formats, MODEL_FORMATS)
    design = _design_angle(structure, None, degrees)
    static = design if fold_angle is None else float(_angles([fold_angle], degrees, "fold_angle")[0])
    motion = np.linspace(0.0, design, 7) if fold_angles is None else _angles(fold_angles, degrees, "fold_angles")
    meta = _metadata(structure, design, metadata)
    mesh = structure.state(static, anchor=anchor).mesh()
    out: list[Path] = []
    for fmt in formats:
        target = _target(path_stem, fmt)
        if fmt == "glb":
            coords = folding_motion(structure, motion, anchor=anchor)
            out.append(gltf.write_glb(target, mesh, coords=coords, angles_deg=motion, unit=unit, metadata=meta,
                                      seconds_per_state=seconds_per_state))
        elif fmt == "obj":
            out.append(mesh3d.write_obj(target, mesh, unit=unit, metadata={**meta, "fold_angle_deg": static}))
        elif fmt == "stl":
            out.append(mesh3d.write_stl(target, mesh))
        elif fmt == "ply":
            out.append(mesh3d.write_ply(target, mesh))
        else:
            out.append(rhino.write_3dm(target, mesh, unit=unit, metadata={**meta, "fold_angle_deg": static}))
    return tuple(out)
