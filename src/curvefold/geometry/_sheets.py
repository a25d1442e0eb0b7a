"""The developed sheets of a structure: its crease pattern, seams, bonds and folding motion.

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
vertex to its index in ``State.mesh()``, so any state can be put on the sheets'
topology; the FOLD file uses that to give its crease pattern and folded frames one
topology. Which strips, corners, edges and seam ids make each sheet is
:meth:`Structure.topology`'s (:mod:`curvefold.geometry._topology`); this module develops
them into the plane.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from ..kernel._arrays import FrozenArrays
from ..kernel._errors import InputError, InternalError
from ..kernel._lie import cross
from ._fold_angle import check_fold_angle, check_fold_angles
from ._mesh import Mesh, vector_areas
from ._mesh import fold_angles as dihedral_angles
from ._structure import State, Structure, check_structure
from ._topology import SHEETS, Topology, corner_members, fold_assignment

__all__ = [
    "SHEET_NAMES",
    "Bond",
    "FlatPlane",
    "PatternSheet",
    "bonds",
    "develop",
    "flat_plane",
    "folding_motion",
    "sheet_vertices",
    "sheets",
    "unroll_strip",
]

#: Names of a tube's two sheets, in order.
SHEET_NAMES = tuple(name for name, _ in SHEETS)


# --------------------------------------------------------------------------------------
# sheets


@dataclass(frozen=True, eq=False)
class PatternSheet(FrozenArrays):
    """One developed sheet to fabricate.

    Attributes
    ----------
    label : str
        Printed on the sheet, e.g. ``"vault · tube 2 · sheet B"``.
    mesh : Mesh
        The developed sheet: ``vertices_coords`` with z = 0 (model units), triangles.
        ``edges_kind`` says what each edge is: ``"fold"`` creases (assignment ``M`` or
        ``V``), ``"seam"`` edges on the outline glued to a partner sheet, ``"boundary"``
        edges on the rest of the outline, ``"ruling"`` and ``"diagonal"`` interior lines.
        ``edges_foldAngle`` is the dihedral angle of the target state on every inner edge
        (a sampled curved sheet bends across its rulings and diagonals too, by about κh),
        0 on the outline.
    edges_seam : (E,) ndarray of int
        -1, or the seam id of a seam edge; the partner edges on the other sheet carry the
        same id.

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice, Structure
    >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
    >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
    >>> tube = Structure.tube(lat)
    >>> a, b = sheets(tube)
    >>> a.label, a.mesh.vertices_coords.shape, float(np.abs(a.mesh.vertices_coords[:, 2]).max())
    ('tube 1 · sheet A', (15, 3), 0.0)
    >>> sorted(set(a.edges_seam.tolist())) == sorted(
    ...     set(b.edges_seam.tolist())
    ... )  # partners share seam ids
    True
    """

    label: str
    mesh: Mesh
    edges_seam: np.ndarray

    def __post_init__(self) -> None:
        if not isinstance(self.label, str):
            raise InputError(f"label must be a str, got {type(self.label).__name__}")
        if not isinstance(self.mesh, Mesh):
            raise InputError(
                f"sheet {self.label!r}: mesh must be a Mesh, got {type(self.mesh).__name__}"
            )
        mesh = self.mesh
        E = len(mesh.edges_vertices)
        seam = np.asarray(self.edges_seam)
        if seam.shape != (E,):
            raise InputError(
                f"sheet {self.label!r}: edges_seam must have shape ({E},), got {seam.shape}"
            )
        if seam.size and not np.array_equal(seam, np.round(seam)):
            raise InputError(
                f"sheet {self.label!r}: edges_seam must hold integers, got {seam.dtype} values"
            )
        seam = seam.astype(np.int64)
        object.__setattr__(self, "edges_seam", seam)
        if seam.size and seam.min() < -1:
            raise InputError(
                f"sheet {self.label!r}: edges_seam must be -1 or a seam id >= 0, got {seam.min()}"
            )
        is_seam = mesh.edges_kind == "seam"
        bad = np.flatnonzero(is_seam != (seam >= 0))
        if bad.size:
            i = bad[0]
            raise InputError(
                f"sheet {self.label!r}: edges_seam must be >= 0 exactly on edges of kind 'seam'; "
                f"{bad.size} edges disagree, e.g. edge {i} of kind "
                f"{str(mesh.edges_kind[i])!r} has seam id {seam[i]}"
            )
        xyz = mesh.vertices_coords
        if len(xyz) and not np.isfinite(xyz).all():
            raise InputError(f"sheet {self.label!r}: vertices_coords must be finite")
        if len(xyz):
            extent = float(np.ptp(xyz[:, :2], axis=0).max())
            zmax = float(np.abs(xyz[:, 2]).max())
            if zmax > 1e-6 * max(extent, 1e-300):
                raise InputError(
                    f"sheet {self.label!r}: a developed sheet must lie in z = 0, got |z| up to "
                    f"{zmax:.3g} for a sheet {extent:.3g} across"
                )
        fold = mesh.edges_kind == "fold"
        odd = np.flatnonzero(fold & ~np.isin(mesh.edges_assignment, ("M", "V")))
        if odd.size:
            raise InputError(
                f"sheet {self.label!r}: fold edges must be assigned 'M' or 'V'; edge {odd[0]} is "
                f"{str(mesh.edges_assignment[odd[0]])!r} ({odd.size} such edges)"
            )
        if len(mesh.faces_vertices) == 0:
            raise InputError(f"sheet {self.label!r}: the mesh has no faces")
        super().__post_init__()


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
    >>> lat = Lattice.from_crease(
    ...     Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=3)), 0.1, 0.1
    ... )
    >>> [v.tolist() for v in sheet_vertices(Structure.tube(lat))]
    [[9, 10, 11, 0, 1, 2, 3, 4, 5], [3, 4, 5, 6, 7, 8, 9, 10, 11]]
    """
    check_structure(structure)
    return tuple(sheet.vertices for sheet in structure.topology().sheets)


@dataclass(frozen=True, eq=False)
class FlatPlane(FrozenArrays):
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

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice, Structure
    >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
    >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
    >>> tube = Structure.tube(lat)
    >>> plane = flat_plane(tube.state(0))
    >>> plane.origin.tolist(), plane.axes.round(6).tolist(), plane.residual
    ([0.0, 0.0, 0.0], [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], 0.0)
    """

    origin: np.ndarray
    axes: np.ndarray
    residual: float

    def coords(self, points: np.ndarray, *, flip: bool = False) -> np.ndarray:
        """In-plane coordinates (..., 2) of points (..., 3), seen from +n (or from −n if ``flip``).

        Examples
        --------
        >>> plane = FlatPlane(np.zeros(3), np.eye(3), 0.0)  # the plane z = 0
        >>> (
        ...     plane.coords(np.array([[1.0, 2, 3]])).tolist(),
        ...     plane.coords(np.array([[1.0, 2, 3]]), flip=True).tolist(),
        ... )
        ([[1.0, 2.0]], [[1.0, -2.0]])
        >>> plane.coords(np.zeros((0, 3))).shape  # no points
        (0, 2)
        """
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
    InputError
        If the state is not at fold angle 0.
    InternalError
        If the flat state is not planar within ``tol`` (curvefold guarantees it).

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice, Structure
    >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
    >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
    >>> tube = Structure.tube(lat)
    >>> flat_plane(tube.state(0)).residual
    0.0
    >>> flat_plane(tube.state())
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: state must be the flat state structure.state(0), got one at
    fold angle 90° (taken as a flat state is not planar)
    """
    if not isinstance(state, State):
        raise InputError(
            f"state must be a State (e.g. structure.state(0)), got {type(state).__name__}"
        )
    if state.fold_angle != 0:
        raise InputError(
            "state must be the flat state structure.state(0), got one at fold "
            f"angle {state.fold_angle:g}° (taken as a flat state is not planar)"
        )
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
    if not residual <= tol * max(size, 1e-300):
        raise InternalError(
            f"the flat state is not planar: a vertex lies {residual:.3g} from "
            f"the fitted plane (allowed {tol:g} × size {size:.3g})"
        )
    return FlatPlane(origin, np.stack([e1, cross(normal, e1), normal]), residual)


def develop(
    structure: Structure, topology: Topology, fold_angle: float, *, name: str = ""
) -> tuple[PatternSheet, ...]:
    """The sheets of one of the structure's topologies, developed into the plane of the flat state.

    :func:`sheets` with the topology given, for callers that read its sheet maps too
    (:func:`curvefold.geometry._fold_arrays.fold_arrays` pairs the seams by them).

    Parameters
    ----------
    structure : Structure
    topology : Topology
        ``structure.topology(faces, keep=keep)``.
    fold_angle : float
        The target 2α whose fold angles the sheets carry, degrees, in (0°, 180°).
    name : str, keyword-only
        Prefix of the labels.

    Returns
    -------
    tuple of PatternSheet
        One per sheet of ``topology``, as :func:`sheets` returns them.

    Raises
    ------
    InputError
        For a fold angle outside (0°, 180°) or a name that is not a str.

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice
    >>> tube = Structure.tube(
    ...     Lattice.from_crease(
    ...         Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=9)), 0.1, 0.1
    ...     )
    ... )
    >>> [len(s.mesh.faces_vertices) for s in develop(tube, tube.topology("quads"), 90.0)]
    [16, 16]
    """
    check_structure(structure)
    fold_angle = check_fold_angle(fold_angle)
    if not isinstance(name, str):
        raise InputError(f"name must be a str, got {type(name).__name__}")
    flat = structure.state(0.0)
    plane = flat_plane(flat)
    flat_coords = topology.coords(flat.vertices)
    bends = dihedral_angles(
        topology.coords(structure.state(fold_angle).vertices),
        topology.faces_vertices,
        topology.edges_vertices,
    )  # rulings and diagonals bend too
    areas = vector_areas(flat_coords, topology.faces_vertices)
    normals = areas / np.linalg.norm(areas, axis=-1, keepdims=True)
    out = []
    for sheet in topology.sheets:
        # "vault · tube 1 · sheet A"; a tube's sheets name their kind already: "tube 1 · sheet A"
        plain = not name or sheet.label.startswith(f"{name} ")
        label = sheet.label if plain else f"{name} · {sheet.label}"
        facing = normals[sheet.faces] @ plane.axes[2]  # ±1: the outside faces +n or −n
        xy = plane.coords(flat_coords[sheet.vertices], flip=bool(facing.mean() < 0))
        area2 = vector_areas(xy, sheet.faces_vertices)[:, 2]
        if not (area2 > 0).all():
            raise InternalError(
                f"{label}: {int(np.count_nonzero(~(area2 > 0)))} of {len(area2)} "
                "faces of the flat state are not counter-clockwise seen from outside the tube"
            )
        kind = topology.edges_kind[sheet.edges]
        angle = np.where(kind == "seam", 0.0, bends[sheet.edges])  # a seam is cut open: one face
        mesh = Mesh(
            vertices_coords=np.column_stack([xy, np.zeros(len(xy))]),
            edges_vertices=sheet.edges_vertices,
            edges_assignment=fold_assignment(kind, angle, seams_open=True),
            edges_foldAngle=angle,
            faces_vertices=sheet.faces_vertices,
            edges_kind=kind,
            faces_group=topology.faces_group[sheet.faces],
        )
        out.append(PatternSheet(label, mesh, sheet.edges_seam))
    return tuple(out)


def sheets(
    structure: Structure,
    *,
    fold_angle: float | None = None,
    degrees: bool = True,
    name: str = "",
    faces: Literal["triangles", "quads"] = "triangles",
    keep: Sequence[np.ndarray] | None = None,
) -> tuple[PatternSheet, ...]:
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
    faces : {"triangles", "quads"}, keyword-only
        The faces of :meth:`Structure.topology` (quads are exactly planar in the flat
        state).
    keep : sequence of (m_k,) array_like of int, optional, keyword-only
        The samples each tube's mesh keeps (:func:`curvefold.geometry.choose_sampling`);
        default every sample.

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
    InternalError
        If the flat state is not planar or a sheet is not one-sided in it (a bug).

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice
    >>> lat = Lattice.from_crease(
    ...     Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=9)), 0.1, 0.1
    ... )
    >>> [s.label for s in sheets(Structure.tube(lat))]
    ['tube 1 · sheet A', 'tube 1 · sheet B']
    """
    check_structure(structure)
    target = (
        structure.lattice.crease.fold_angle
        if fold_angle is None
        else check_fold_angle(fold_angle, degrees=degrees)
    )
    return develop(structure, structure.topology(faces, keep=keep), target, name=name)


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

    Examples
    --------
    >>> Bond((1, 1), ((0, 3), (1, 1)))
    Bond(curve=(1, 1), creases=((0, 3), (1, 1)))
    """

    curve: tuple[int, int]
    creases: tuple[tuple[int, int], ...]

    def describe(self) -> str:
        """One line for people: ``"curve (1, 1): tube 1 crease 3 + tube 2 crease 1"``.

        Examples
        --------
        >>> Bond((1, 1), ((0, 3), (1, 1))).describe()
        'curve (1, 1): tube 1 crease 3 + tube 2 crease 1'
        >>> Bond((0, 0), ()).describe()  # no creases
        'curve (0, 0): '
        """
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

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice, Structure
    >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
    >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
    >>> tube = Structure.tube(lat)
    >>> bonds(tube)  # a single tube has none
    ()
    >>> [b.describe() for b in bonds(Structure.diagonal(lat, 2))]
    ['curve (1, 1): tube 1 crease 3 + tube 2 crease 1']
    """
    check_structure(structure)
    uv = structure.curves_uv.tolist()
    members = corner_members(structure.cell_curves, len(uv))
    return tuple(
        Bond(tuple(uv[m]), tuple((k, c + 1) for k, c in on))
        for m, on in enumerate(members)
        if len(on) > 1
    )


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
    >>> (
    ...     bool(np.allclose(flat[1] - flat[0], [0, 1])),
    ...     bool(np.allclose(flat[0, -1], [8 * np.sin(np.pi / 16), 0])),
    ... )
    (True, True)
    """
    a = np.asarray(points_a, float)
    b = np.asarray(points_b, float)
    if a.ndim != 2 or a.shape[1] != 3 or a.shape != b.shape or len(a) < 2:
        raise InputError(
            "points_a and points_b must both have shape (n, 3) with n ≥ 2, got "
            f"{a.shape} and {b.shape}"
        )
    if not (np.isfinite(a).all() and np.isfinite(b).all()):
        raise InputError("points_a and points_b must be finite")
    a0, a1, b0, b1 = a[:-1], a[1:], b[:-1], b[1:]
    first = _corner_angle(a0, b1, b0)  # triangle (a_j, b_{j+1}, b_j) at a_j
    second = _corner_angle(a0, a1, b1)  # triangle (a_j, a_{j+1}, b_{j+1}) at a_j
    second_next = _corner_angle(a1, b1, a0)  # the same triangle at a_{j+1}
    # direction of the ruling a_j → b_j, and of the chord a_j → a_{j+1}
    ruling = 0.5 * np.pi + np.concatenate([[0.0], np.cumsum(np.pi - first - second - second_next)])
    along = ruling[:-1] - first - second
    step = np.linalg.norm(a1 - a0, axis=-1)[:, None] * np.stack(
        [np.cos(along), np.sin(along)], axis=-1
    )
    a2 = np.concatenate([np.zeros((1, 2)), np.cumsum(step, axis=0)])
    b2 = a2 + np.linalg.norm(b - a, axis=-1)[:, None] * np.stack(
        [np.cos(ruling), np.sin(ruling)], axis=-1
    )
    return np.stack([a2, b2])


# --------------------------------------------------------------------------------------
# folding motion


def folding_motion(
    structure: Structure,
    fold_angles: ArrayLike,
    *,
    degrees: bool = True,
    anchor: Literal["start", "middle"] = "start",
    keep: Sequence[np.ndarray] | None = None,
    topology: Topology | None = None,
) -> np.ndarray:
    """Vertex positions of ``State.mesh(keep=keep)`` at many fold angles at once, shape (A, V, 3).

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
    keep : sequence of (m_k,) array_like of int, optional, keyword-only
        The samples each tube's mesh keeps (see :meth:`Structure.topology`).
    topology : Topology, optional, keyword-only
        ``structure.topology(faces, keep=keep)`` when the caller has it (it is not made again);
        its vertices are the ones returned.

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice, Structure
    >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
    >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
    >>> tube = Structure.tube(lat)
    >>> motion = folding_motion(tube, [0, 90])
    >>> (
    ...     motion.shape,
    ...     bool(np.allclose(motion[1], tube.state(90).mesh().vertices_coords, atol=1e-12)),
    ... )
    ((2, 20, 3), True)
    >>> folding_motion(tube, [])
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: fold_angles must be a non-empty sequence of fold angles,
    got shape (0,)
    """
    check_structure(structure)
    angles = check_fold_angles(fold_angles, degrees=degrees)
    # (A, M, n, 3)
    points = structure.lattice.fold_points(structure.curves_uv, angles, anchor=anchor)
    return (structure.topology(keep=keep) if topology is None else topology).coords(points)
