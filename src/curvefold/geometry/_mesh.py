"""Polygon meshes held in FOLD's parallel arrays.

Every structure state, crease pattern and sheet is a :class:`Mesh`; the exporters share
it. Key names follow the FOLD format (``vertices_coords``, ``edges_vertices``,
``edges_assignment``, ``edges_foldAngle``, ``faces_vertices``). Faces are polygons of
three or more vertices; where sizes mix, ``faces_vertices`` is padded with -1 at the end
of the shorter rows. Fold angles are in degrees with FOLD's sign: positive is a valley as
seen from the side the face normals point to (faces are counter-clockwise seen from that
side).
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

import numpy as np

from ..kernel._arrays import FrozenArrays
from ..kernel._errors import InputError
from ..kernel._lie import cross

__all__ = [
    "Mesh",
    "EDGE_KINDS",
    "CREASE_KINDS",
    "fold_angles",
    "dihedral_angles",
    "edges_faces",
    "face_sides",
    "vector_areas",
    "edges_along",
]

#: What an edge is: a fold crease, a seam (two sheets welded, two-ply when flat), the outer
#: boundary, a ruling (a straight segment on a developable strip) or a triangulating diagonal.
EDGE_KINDS = ("fold", "seam", "boundary", "ruling", "diagonal")
#: The kinds that carry a fold angle.
CREASE_KINDS = ("fold", "seam")


@dataclass(frozen=True, eq=False)
class Mesh(FrozenArrays):
    """A polygon mesh with crease information, in FOLD's parallel arrays.

    Attributes
    ----------
    vertices_coords : (V, 3) ndarray of float
        Vertex positions (z = 0 for a crease pattern).
    edges_vertices : (E, 2) ndarray of int
        Each edge's two vertices.
    edges_assignment : (E,) ndarray of str
        FOLD assignment: ``"M"`` mountain, ``"V"`` valley, ``"B"`` boundary, ``"F"`` flat.
    edges_foldAngle : (E,) ndarray of float
        Fold angle in degrees, FOLD sign (valley positive); 0 on flat and boundary edges.
    faces_vertices : (F, k) ndarray of int
        Polygons of 3 … k vertices, counter-clockwise seen from the side their normal
        points to; rows of fewer than k vertices end in -1.
    edges_kind : (E,) ndarray of str
        One of :data:`EDGE_KINDS`.
    faces_group : (F,) ndarray of int
        Which strip (or sheet) each face belongs to.

    Examples
    --------
    >>> square = Mesh(
    ...     vertices_coords=[[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
    ...     edges_vertices=[[0, 1], [1, 2], [2, 3], [3, 0]],
    ...     edges_assignment=["B"] * 4,
    ...     edges_foldAngle=[0.0] * 4,
    ...     faces_vertices=[[0, 1, 2, 3]],
    ...     edges_kind=["boundary"] * 4,
    ...     faces_group=[0],
    ... )
    >>> square.vertices_coords.shape, square.faces_vertices.tolist()
    ((4, 3), [[0, 1, 2, 3]])
    >>> Mesh(
    ...     vertices_coords=np.zeros((3, 2)),
    ...     edges_vertices=np.zeros((0, 2), int),
    ...     edges_assignment=[],
    ...     edges_foldAngle=[],
    ...     faces_vertices=[[0, 1, 2]],
    ...     edges_kind=[],
    ...     faces_group=[0],
    ... )
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: vertices_coords must have shape (V, 3), got (3, 2)
    """

    vertices_coords: np.ndarray
    edges_vertices: np.ndarray
    edges_assignment: np.ndarray
    edges_foldAngle: np.ndarray
    faces_vertices: np.ndarray
    edges_kind: np.ndarray
    faces_group: np.ndarray

    def __post_init__(self) -> None:
        for f in fields(self):
            object.__setattr__(self, f.name, np.asarray(getattr(self, f.name)))
        super().__post_init__()
        V, E, F = len(self.vertices_coords), len(self.edges_vertices), len(self.faces_vertices)
        if self.vertices_coords.shape != (V, 3):
            raise InputError(
                f"vertices_coords must have shape (V, 3), got {self.vertices_coords.shape}"
            )
        faces = self.faces_vertices
        if faces.ndim != 2 or faces.shape[1] < 3:
            raise InputError(f"faces_vertices must have shape (F, k) with k ≥ 3, got {faces.shape}")
        for name, shape in (
            ("edges_vertices", (E, 2)),
            ("edges_assignment", (E,)),
            ("edges_foldAngle", (E,)),
            ("edges_kind", (E,)),
            ("faces_group", (F,)),
        ):
            if getattr(self, name).shape != shape:
                raise InputError(f"{name} must have shape {shape}, got {getattr(self, name).shape}")
        pad = faces < 0
        bad = np.flatnonzero((pad[:, :-1] & ~pad[:, 1:]).any(axis=1) | (faces < -1).any(axis=1))
        if bad.size:
            raise InputError(
                f"faces_vertices: -1 may only pad the end of a face; face {bad[0]} "
                f"is {faces[bad[0]].tolist()}"
            )
        short = np.flatnonzero(pad[:, 2])
        if short.size:
            raise InputError(
                f"faces_vertices: every face needs at least 3 vertices; face {short[0]} has fewer"
            )

    def with_coords(
        self, vertices_coords: np.ndarray, *, fold_angles_from_geometry: bool = True
    ) -> Mesh:
        """The same topology at other vertex positions (fold angles re-measured by default).

        Examples
        --------
        >>> book = Mesh(
        ...     vertices_coords=[[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
        ...     edges_vertices=[[0, 2], [0, 1], [1, 2], [2, 3], [3, 0]],
        ...     edges_assignment=["F", "B", "B", "B", "B"],
        ...     edges_foldAngle=[0.0] * 5,
        ...     faces_vertices=[[0, 1, 2], [0, 2, 3]],
        ...     edges_kind=["fold"] + ["boundary"] * 4,
        ...     faces_group=[0, 1],
        ... )  # two triangles hinged on the diagonal 0–2
        >>> lifted = book.with_coords([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0.5, 0.5, 1]])
        >>> lifted.edges_foldAngle.round(6).tolist()
        [90.0, 0.0, 0.0, 0.0, 0.0]
        >>> flat = book.with_coords(book.vertices_coords)
        >>> (flat.edges_foldAngle + 0.0).tolist()  # flat: no fold
        [0.0, 0.0, 0.0, 0.0, 0.0]
        """
        mesh = replace(self, vertices_coords=np.asarray(vertices_coords, float))
        if not fold_angles_from_geometry:
            return mesh
        angles = fold_angles(mesh.vertices_coords, self.faces_vertices, self.edges_vertices)
        keep = np.isin(self.edges_kind, CREASE_KINDS)
        return replace(mesh, edges_foldAngle=np.where(keep, angles, 0.0))

    def face_sizes(self) -> np.ndarray:
        """Number of vertices of every face, shape (F,).

        Examples
        --------
        >>> square = _unit_square()  # the unit square of the Mesh example
        >>> square.face_sizes().tolist(), square.triangulated().face_sizes().tolist()
        ([4], [3, 3])
        """
        return np.count_nonzero(self.faces_vertices >= 0, axis=1)

    def triangulated(self) -> Mesh:
        """The mesh with every polygon split into a fan of triangles from its first vertex.

        Triangles replace their polygon in place (the face order is kept, ``faces_group``
        repeated); the added edges come after the existing ones, of kind ``"diagonal"``,
        assignment ``"F"`` and fold angle 0. A triangle mesh is returned as it is.

        Examples
        --------
        >>> square = _unit_square()  # the unit square of the Mesh example
        >>> triangles = square.triangulated()
        >>> faces, last = triangles.faces_vertices.tolist(), str(triangles.edges_kind[-1])
        >>> faces, last, triangles.triangulated() is triangles
        ([[0, 1, 2], [0, 2, 3]], 'diagonal', True)
        """
        faces = self.faces_vertices
        if faces.shape[1] == 3:
            return self
        sizes = self.face_sizes()
        polygon = np.repeat(np.arange(len(faces)), sizes - 2)  # (T,) the polygon of each triangle
        # 1 … m − 2
        fan = np.arange(len(polygon)) - np.repeat(np.cumsum(sizes - 2) - (sizes - 2), sizes - 2) + 1
        triangles = np.stack(
            [faces[polygon, 0], faces[polygon, fan], faces[polygon, fan + 1]], axis=1
        )
        added = fan > 1  # the fan's diagonals (first vertex → vertex i, 2 ≤ i ≤ m − 2)
        diagonals = np.stack([faces[polygon[added], 0], faces[polygon[added], fan[added]]], axis=1)
        count = len(diagonals)
        return Mesh(
            vertices_coords=self.vertices_coords,
            edges_vertices=np.concatenate([self.edges_vertices, diagonals]),
            edges_assignment=np.concatenate(
                [self.edges_assignment, np.full(count, "F", self.edges_assignment.dtype)]
            ),
            edges_foldAngle=np.concatenate([self.edges_foldAngle, np.zeros(count)]),
            faces_vertices=triangles,
            edges_kind=np.concatenate([self.edges_kind, np.full(count, "diagonal", dtype="<U8")]),
            faces_group=self.faces_group[polygon],
        )

    def edge_lengths(self) -> np.ndarray:
        """Length of every edge, shape (E,).

        Examples
        --------
        >>> square = _unit_square()  # the unit square of the Mesh example
        >>> diagonal = square.triangulated().edge_lengths()[-1]
        >>> square.edge_lengths().tolist(), round(float(diagonal), 6)
        ([1.0, 1.0, 1.0, 1.0], 1.414214)
        """
        a, b = (
            self.vertices_coords[self.edges_vertices[:, 0]],
            self.vertices_coords[self.edges_vertices[:, 1]],
        )
        return np.linalg.norm(b - a, axis=-1)

    def face_normals(self) -> np.ndarray:
        """Unit normals of the faces (Newell's method for polygons), shape (F, 3).

        Examples
        --------
        >>> square = _unit_square()  # the unit square of the Mesh example
        >>> square.face_normals().tolist()  # counter-clockwise seen from +z
        [[0.0, 0.0, 1.0]]
        """
        n = vector_areas(self.vertices_coords, self.faces_vertices)
        return n / np.linalg.norm(n, axis=-1, keepdims=True)


def vector_areas(vertices_coords: np.ndarray, faces_vertices: np.ndarray) -> np.ndarray:
    """Twice the vector area of every face (Newell's method), shape (..., F, 3).

    ``Σ (p_i − p_0) × (p_{i+1} − p_0)`` over the fan of each polygon: its direction is the
    face normal (counter-clockwise faces), its length twice the area of a planar face;
    for a triangle it is ``(p_1 − p_0) × (p_2 − p_0)``. Points of shape (V, 2) are taken in
    the plane z = 0, so that the z component is twice the signed area.

    Parameters
    ----------
    vertices_coords : (..., V, 3) or (..., V, 2) ndarray
        One or more states of the vertices.
    faces_vertices : (F, k) ndarray of int
        Polygons, -1 padded.

    Examples
    --------
    >>> rectangle = np.array([[0, 0], [2, 0], [2, 1], [0, 1]], float)
    >>> vector_areas(rectangle, np.array([[0, 1, 2, 3]])).tolist()
    [[0.0, 0.0, 4.0]]
    """
    x = np.asarray(vertices_coords, float)
    if x.shape[-1] == 2:
        x = np.concatenate([x, np.zeros(x.shape[:-1] + (1,))], axis=-1)
    faces = np.asarray(faces_vertices)
    if faces.shape[1] == 3:  # one cross product per face, from its corners' rows
        p0 = np.take(x, faces[:, 0], axis=-2)
        return cross(np.take(x, faces[:, 1], axis=-2) - p0, np.take(x, faces[:, 2], axis=-2) - p0)
    filled = np.where(faces >= 0, faces, faces[:, :1])  # padding repeats the first vertex: no area
    p = x[..., filled, :]
    d = p[..., 1:, :] - p[..., :1, :]
    return cross(d[..., :-1, :], d[..., 1:, :]).sum(axis=-2)


def face_sides(faces_vertices: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The directed sides of every face: consecutive vertex pairs, closing the polygon.

    Parameters
    ----------
    faces_vertices : (F, k) ndarray of int
        Polygons, -1 padded.

    Returns
    -------
    sides : (H, 2) ndarray of int
        (a, b) for every side, face by face in vertex order.
    face : (H,) ndarray of int
        The face of every side.

    Examples
    --------
    >>> face_sides(np.array([[0, 1, 2, -1], [2, 1, 3, 4]]))[0].tolist()
    [[0, 1], [1, 2], [2, 0], [2, 1], [1, 3], [3, 4], [4, 2]]
    """
    faces = np.asarray(faces_vertices, dtype=np.int64)
    filled = np.where(faces >= 0, faces, faces[:, :1])
    # (F, k, 2)
    pairs = np.stack([filled, np.concatenate([filled[:, 1:], filled[:, :1]], axis=1)], axis=-1)
    keep = (faces >= 0) & (pairs[..., 0] != pairs[..., 1])  # drop the padding's degenerate sides
    if keep.all():
        return pairs.reshape(-1, 2), np.repeat(np.arange(len(faces)), faces.shape[1])
    return pairs[keep], np.nonzero(keep)[0]


def edges_faces(faces_vertices: np.ndarray, edges_vertices: np.ndarray) -> np.ndarray:
    """For each edge the face that traverses it a→b and the face that traverses it b→a.

    Parameters
    ----------
    faces_vertices : (F, k) ndarray of int
        Polygons, -1 padded.
    edges_vertices : (E, 2) ndarray of int

    Returns
    -------
    (E, 2) ndarray of int
        Face indices, -1 where there is none on that side. Where more than one face
        traverses an edge the same way (a junction of several strips), the last one is kept.

    Examples
    --------
    >>> faces = np.array([[0, 1, 2], [0, 2, 3]])
    >>> edges_faces(faces, np.array([[0, 2], [0, 1], [1, 3]])).tolist()  # 1–3 is no side of a face
    [[1, 0], [0, -1], [-1, -1]]
    >>> edges_faces(faces, np.array([[0, 2], [2, 0]])).tolist()  # an edge listed both ways
    [[1, 0], [0, 1]]
    """
    E = len(edges_vertices)
    half, half_face = face_sides(faces_vertices)
    nv = int(max(np.max(edges_vertices, initial=-1), np.max(faces_vertices, initial=-1))) + 1
    out = np.full((E, 2), -1, dtype=np.int64)
    if E == 0:
        return out
    a, b = edges_vertices[:, 0].astype(np.int64), edges_vertices[:, 1].astype(np.int64)
    key = np.minimum(a, b) * nv + np.maximum(a, b)  # the undirected edge
    order = np.argsort(key, kind="stable")  # the keys of a mesh come nearly sorted: a merge is fast
    ordered = key[order]
    # an edge listed twice (either way): each direction looked up alone
    if (ordered[1:] == ordered[:-1]).any():
        return _edges_faces_by_direction(
            a * nv + b, b * nv + a, half[:, 0] * nv + half[:, 1], half_face, out
        )
    half_key = np.minimum(half[:, 0], half[:, 1]) * nv + np.maximum(half[:, 0], half[:, 1])
    pos = np.minimum(np.searchsorted(ordered, half_key), E - 1)
    hit = ordered[pos] == half_key
    edge = order[pos[hit]]
    # a→b: side 0, b→a: side 1
    out[edge, (half[hit, 0] != a[edge]).astype(np.int64)] = half_face[hit]
    return out


def _edges_faces_by_direction(
    fwd: np.ndarray, rev: np.ndarray, half_key: np.ndarray, half_face: np.ndarray, out: np.ndarray
) -> np.ndarray:
    """:func:`edges_faces` from the keys of every edge a→b, b→a and every face side (a·V + b)."""
    E = len(fwd)
    for side, keys in enumerate((fwd, rev)):
        order = np.argsort(keys)
        pos = np.clip(np.searchsorted(keys[order], half_key), 0, max(E - 1, 0))
        hit = keys[order][pos] == half_key
        out[order[pos[hit]], side] = half_face[hit]
    return out


def fold_angles(
    vertices_coords: np.ndarray,
    faces_vertices: np.ndarray,
    edges_vertices: np.ndarray,
    *,
    faces_of_edges: np.ndarray | None = None,
) -> np.ndarray:
    """Signed fold angle of every edge in degrees, FOLD sign (valley positive).

    The angle between the normals of the two faces on the edge (Newell normals for
    polygons), positive when the faces turn toward the side their normals point to.
    Edges with fewer than two faces get 0; a degenerate face (no normal) gives NaN.

    Parameters
    ----------
    vertices_coords : (V, 3) ndarray
    faces_vertices : (F, k) ndarray of int
        Polygons, -1 padded.
    edges_vertices : (E, 2) ndarray of int
    faces_of_edges : (E, 2) ndarray of int, optional, keyword-only
        :func:`edges_faces` of these faces and edges, when it is known already (many
        frames of one topology).

    Returns
    -------
    (E,) ndarray

    Examples
    --------
    >>> faces, edges = np.array([[0, 1, 2], [0, 2, 3]]), np.array([[0, 2], [0, 1]])
    >>> lifted = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0.5, 0.5, 1]])
    >>> fold_angles(lifted, faces, edges).round(6).tolist()
    [90.0, 0.0]
    >>> flat = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0.0]])
    >>> (fold_angles(flat, faces, edges) + 0.0).tolist()  # flat; a boundary edge
    [0.0, 0.0]
    """
    ef = edges_faces(faces_vertices, edges_vertices) if faces_of_edges is None else faces_of_edges
    x = np.asarray(vertices_coords, float)
    with np.errstate(invalid="ignore", divide="ignore"):
        areas = vector_areas(x, faces_vertices)
    return dihedral_angles(
        areas,
        ef,
        np.take(x, edges_vertices[:, 1], axis=0) - np.take(x, edges_vertices[:, 0], axis=0),
    )


def dihedral_angles(
    face_areas: np.ndarray, faces_of_edges: np.ndarray, edge_vectors: np.ndarray
) -> np.ndarray:
    """:func:`fold_angles` from the faces' :func:`vector_areas` and the edges as vectors, degrees
    (FOLD sign).

    Parameters
    ----------
    face_areas : (F, 3) ndarray
        :func:`vector_areas` of the faces (not changed).
    faces_of_edges : (E, 2) ndarray of int
        :func:`edges_faces`: the face that runs each edge a → b and the one that runs it b → a, -1
        for none.
    edge_vectors : (E, 3) ndarray
        ``x_b − x_a`` of every edge (a, b).

    Returns
    -------
    (E,) ndarray
        0 on an edge with fewer than two faces, NaN next to a degenerate face.

    Examples
    --------
    >>> areas = np.array([[0.0, 0, 2], [0, 1, 0]])  # faces facing +z and +y
    >>> edges = np.array([[1.0, 0, 0], [1, 0, 0]])  # along the x axis
    >>> sides = np.array([[0, 1], [0, -1]])  # hinged on the first edge; one face at the second
    >>> dihedral_angles(areas, sides, edges).tolist()
    [90.0, 0.0]
    """
    ef = faces_of_edges
    ok = (ef[:, 0] >= 0) & (ef[:, 1] >= 0)
    out = np.zeros(len(ef))
    with np.errstate(invalid="ignore", divide="ignore"):
        n = face_areas / np.sqrt(np.einsum("ij,ij->i", face_areas, face_areas))[:, None]
        e = edge_vectors
        if not ok.all():
            ef, e = ef[ok], e[ok]
        n1, n2 = np.take(n, ef[:, 0], axis=0), np.take(n, ef[:, 1], axis=0)
        sine = -np.einsum("ij,ij->i", cross(n1, n2), e) / np.sqrt(np.einsum("ij,ij->i", e, e))
        out[ok] = np.degrees(np.arctan2(sine, np.einsum("ij,ij->i", n1, n2)))
    return out


def edges_along(edges_vertices: np.ndarray, pairs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The edge joining each vertex pair (a, b), and whether it runs a → b.

    Parameters
    ----------
    edges_vertices : (E, 2) ndarray of int
    pairs : (..., 2) ndarray of int

    Returns
    -------
    edge : (...) ndarray of int
        -1 where no edge joins a and b (one of them where several do).
    forward : (...) ndarray of bool
        Whether that edge is (a, b) rather than (b, a).

    Examples
    --------
    >>> edge, forward = edges_along(np.array([[0, 1], [2, 1]]), np.array([[1, 2], [0, 1], [0, 2]]))
    >>> edge.tolist(), forward.tolist()
    ([1, 0, -1], [False, True, False])
    """
    p = np.asarray(pairs, np.int64)
    ev = np.asarray(edges_vertices, np.int64).reshape(-1, 2)
    if not len(ev):
        return np.full(p.shape[:-1], -1, np.int64), np.zeros(p.shape[:-1], bool)
    nv = int(max(ev.max(), np.max(p, initial=-1))) + 1
    # the undirected edge
    key = np.minimum(ev[:, 0], ev[:, 1]) * nv + np.maximum(ev[:, 0], ev[:, 1])
    order = np.argsort(key, kind="stable")
    ordered = key[order]
    wanted = np.minimum(p[..., 0], p[..., 1]) * nv + np.maximum(p[..., 0], p[..., 1])
    pos = np.minimum(np.searchsorted(ordered, wanted), len(ev) - 1)
    edge = np.where(ordered[pos] == wanted, order[pos], -1)
    return edge, (edge >= 0) & (ev[edge, 0] == p[..., 0])


def _unit_square() -> Mesh:
    """The unit square of the :class:`Mesh` example, one quad face, for the methods' examples."""
    return Mesh(
        vertices_coords=np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]),
        edges_vertices=np.array([[0, 1], [1, 2], [2, 3], [3, 0]]),
        edges_assignment=np.array(["B"] * 4),
        edges_foldAngle=np.zeros(4),
        faces_vertices=np.array([[0, 1, 2, 3]]),
        edges_kind=np.array(["boundary"] * 4),
        faces_group=np.array([0]),
    )
