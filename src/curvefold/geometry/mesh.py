"""Triangle meshes held in FOLD's parallel arrays.

Every structure state, crease pattern and sheet is a :class:`Mesh`; the exporters share
it. Key names follow the FOLD format (``vertices_coords``, ``edges_vertices``,
``edges_assignment``, ``edges_foldAngle``, ``faces_vertices``). Fold angles are in degrees
with FOLD's sign: positive is a valley as seen from the side the face normals point to
(faces are counter-clockwise seen from that side).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..kernel.errors import InputError
from ..kernel.lie import cross

__all__ = ["Mesh", "EDGE_KINDS", "fold_angles", "edges_faces"]

#: What an edge is: a fold crease, a seam (two sheets welded, two-ply when flat), the outer
#: boundary, a ruling (a straight segment on a developable strip) or a triangulating diagonal.
EDGE_KINDS = ("fold", "seam", "boundary", "ruling", "diagonal")


def _readonly(a: np.ndarray) -> np.ndarray:
    a = np.array(a)  # own copy
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class Mesh:
    """A triangle mesh with crease information, in FOLD's parallel arrays.

    Attributes
    ----------
    vertices_coords : (V, 3) ndarray of float
        Vertex positions (z = 0 for a crease pattern).
    edges_vertices : (E, 2) ndarray of int
        Each edge's two vertices, oriented as in the first face that uses it.
    edges_assignment : (E,) ndarray of str
        FOLD assignment: ``"M"`` mountain, ``"V"`` valley, ``"B"`` boundary, ``"F"`` flat.
    edges_foldAngle : (E,) ndarray of float
        Fold angle in degrees, FOLD sign (valley positive); 0 on flat and boundary edges.
    faces_vertices : (F, 3) ndarray of int
        Triangles, counter-clockwise seen from the side their normal points to.
    edges_kind : (E,) ndarray of str
        One of :data:`EDGE_KINDS`.
    faces_group : (F,) ndarray of int
        Which strip (or sheet) each face belongs to.
    """

    vertices_coords: np.ndarray
    edges_vertices: np.ndarray
    edges_assignment: np.ndarray
    edges_foldAngle: np.ndarray
    faces_vertices: np.ndarray
    edges_kind: np.ndarray
    faces_group: np.ndarray

    def __post_init__(self) -> None:
        for name in ("vertices_coords", "edges_vertices", "edges_assignment", "edges_foldAngle", "faces_vertices", "edges_kind", "faces_group"):
            object.__setattr__(self, name, _readonly(getattr(self, name)))
        V, E, F = len(self.vertices_coords), len(self.edges_vertices), len(self.faces_vertices)
        if self.vertices_coords.shape != (V, 3):
            raise InputError(f"vertices_coords must have shape (V, 3), got {self.vertices_coords.shape}")
        for name, shape in (("edges_vertices", (E, 2)), ("faces_vertices", (F, 3)), ("edges_assignment", (E,)),
                            ("edges_foldAngle", (E,)), ("edges_kind", (E,)), ("faces_group", (F,))):
            if getattr(self, name).shape != shape:
                raise InputError(f"{name} must have shape {shape}, got {getattr(self, name).shape}")

    def with_coords(self, vertices_coords: np.ndarray, *, fold_angles_from_geometry: bool = True) -> Mesh:
        """The same topology at other vertex positions (fold angles re-measured by default)."""
        mesh = replace(self, vertices_coords=np.asarray(vertices_coords, float))
        if not fold_angles_from_geometry:
            return mesh
        angles = fold_angles(mesh.vertices_coords, self.faces_vertices, self.edges_vertices)
        keep = np.isin(self.edges_kind, ("fold", "seam"))
        return replace(mesh, edges_foldAngle=np.where(keep, angles, 0.0))

    def edge_lengths(self) -> np.ndarray:
        """Length of every edge, shape (E,)."""
        a, b = self.vertices_coords[self.edges_vertices[:, 0]], self.vertices_coords[self.edges_vertices[:, 1]]
        return np.linalg.norm(b - a, axis=-1)

    def face_normals(self) -> np.ndarray:
        """Unit normals of the triangles, shape (F, 3)."""
        x = self.vertices_coords[self.faces_vertices]
        n = cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0])
        return n / np.linalg.norm(n, axis=-1, keepdims=True)

    def to_fold(self, *, frame_title: str = "", unit: str = "unit", classes: tuple[str, ...] = ("foldedForm",)) -> dict:
        """One FOLD frame as a JSON-ready dict (standard keys plus ``curvefold:edges_kind``)."""
        return {
            "frame_title": frame_title,
            "frame_classes": list(classes),
            "frame_unit": unit,
            "vertices_coords": self.vertices_coords.tolist(),
            "edges_vertices": self.edges_vertices.tolist(),
            "edges_assignment": self.edges_assignment.tolist(),
            "edges_foldAngle": self.edges_foldAngle.tolist(),
            "faces_vertices": self.faces_vertices.tolist(),
            "curvefold:edges_kind": self.edges_kind.tolist(),
        }


def edges_faces(faces_vertices: np.ndarray, edges_vertices: np.ndarray) -> np.ndarray:
    """For each edge the face that traverses it a→b and the face that traverses it b→a.

    Parameters
    ----------
    faces_vertices : (F, 3) ndarray of int
    edges_vertices : (E, 2) ndarray of int

    Returns
    -------
    (E, 2) ndarray of int
        Face indices, -1 where there is none on that side. Where more than one face
        traverses an edge the same way (a junction of several strips), the last one is kept.
    """
    E = len(edges_vertices)
    F = len(faces_vertices)
    nv = int(max(edges_vertices.max(initial=-1), faces_vertices.max(initial=-1))) + 1
    fwd = edges_vertices[:, 0].astype(np.int64) * nv + edges_vertices[:, 1]
    rev = edges_vertices[:, 1].astype(np.int64) * nv + edges_vertices[:, 0]
    half = np.stack([faces_vertices, np.roll(faces_vertices, -1, axis=1)], axis=-1).reshape(-1, 2).astype(np.int64)
    half_key = half[:, 0] * nv + half[:, 1]
    half_face = np.repeat(np.arange(F), 3)
    out = np.full((E, 2), -1, dtype=np.int64)
    for side, keys in enumerate((fwd, rev)):
        order = np.argsort(keys)
        pos = np.clip(np.searchsorted(keys[order], half_key), 0, max(E - 1, 0))
        hit = keys[order][pos] == half_key if E else np.zeros(len(half_key), bool)
        out[order[pos[hit]], side] = half_face[hit]
    return out


def fold_angles(vertices_coords: np.ndarray, faces_vertices: np.ndarray, edges_vertices: np.ndarray) -> np.ndarray:
    """Signed fold angle of every edge in degrees, FOLD sign (valley positive).

    The angle between the normals of the two faces on the edge, positive when the faces
    turn toward the side their normals point to. Edges with fewer than two faces get 0.

    Parameters
    ----------
    vertices_coords : (V, 3) ndarray
    faces_vertices : (F, 3) ndarray of int
    edges_vertices : (E, 2) ndarray of int

    Returns
    -------
    (E,) ndarray
    """
    ef = edges_faces(faces_vertices, edges_vertices)
    x = np.asarray(vertices_coords, float)
    tri = x[faces_vertices]
    n = cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    ok = (ef >= 0).all(axis=1)
    n1, n2 = n[ef[ok, 0]], n[ef[ok, 1]]
    e = x[edges_vertices[ok, 1]] - x[edges_vertices[ok, 0]]
    e /= np.linalg.norm(e, axis=-1, keepdims=True)
    out = np.zeros(len(edges_vertices))
    out[ok] = np.degrees(np.arctan2(-np.einsum("ij,ij->i", cross(n1, n2), e), np.einsum("ij,ij->i", n1, n2)))
    return out
