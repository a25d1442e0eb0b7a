"""What the geometry of a FOLD file means, up to its numbering and a rigid motion.

``check --rebuild`` compares a file with the design it records, built again. Two files of the
same geometry may number their vertices, edges and faces differently, start a face's list at
another corner, list glued pairs in another order, or stand moved rigidly: none of that changes
what the geometry is. :func:`renumbered` brings a file's meshes into the rebuilt numbering (the
vertices matched by position in the first frame, the edges by their ends, the faces by their
corners in cyclic order), :func:`unsplit` joins an edge split at a vertex on its straight
line back into one, and :func:`rigid_residual` measures coordinates after the best rigid
motion (Kabsch), so that only a change of the geometry differs.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..geometry._mesh import Mesh
from ..io._fold_reading import FoldFile

__all__ = ["renumbered", "rigid_residual", "canonical_pairs", "turned_over", "unsplit"]


def rigid_residual(moved: np.ndarray, fixed: np.ndarray) -> np.ndarray:
    """Per vertex, the largest coordinate difference of ``moved`` (V, d) from ``fixed`` (V, d)
    after the proper rigid motion that best lays the one on the other (least squares).

    Examples
    --------
    >>> square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    >>> turned = square @ np.array([[0, -1], [1, 0]]) + 5.0
    >>> bool(rigid_residual(turned, square).max() < 1e-12)
    True
    """
    a, b = np.asarray(moved, float), np.asarray(fixed, float)
    ca, cb = a.mean(axis=0), b.mean(axis=0)
    u, _, vt = np.linalg.svd((a - ca).T @ (b - cb))
    flip = np.ones(a.shape[1])
    flip[-1] = np.sign(np.linalg.det(u @ vt)) or 1.0
    rotation = (u * flip) @ vt
    return np.abs((a - ca) @ rotation + cb - b).max(axis=1)


def canonical_pairs(pairs: np.ndarray) -> np.ndarray:
    """Pairs of ids (P, 2), each sorted and all in order: the same set of pairs, listed once."""
    pairs = np.sort(np.asarray(pairs, np.int64).reshape(-1, 2), axis=1)
    return pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))] if len(pairs) else pairs


def _laid_on(moved: np.ndarray, fixed: np.ndarray):
    """``moved`` as it stands, then laid on ``fixed`` by each proper rigid motion that takes its
    principal axes onto theirs (the axes' signs: 4 choices), then refined by the best rigid
    motion (Kabsch) on the nearest points: a frame renumbered and moved is found again."""
    from scipy.spatial import cKDTree

    a, b = np.asarray(moved, float), np.asarray(fixed, float)
    yield a
    ca, cb = a.mean(axis=0), b.mean(axis=0)
    _, ea = np.linalg.eigh((a - ca).T @ (a - ca))
    _, eb = np.linalg.eigh((b - cb).T @ (b - cb))
    tree = cKDTree(b)
    d = a.shape[1]
    for signs in np.array(np.meshgrid(*[[1.0, -1.0]] * d)).T.reshape(-1, d):
        rotation = (eb * signs) @ ea.T
        if np.linalg.det(rotation) < 0:
            continue
        guess = (a - ca) @ rotation.T + cb
        _, nearest = tree.query(guess)
        target = b[nearest]
        u, _, vt = np.linalg.svd((a - ca).T @ (target - target.mean(axis=0)))
        flip = np.ones(d)
        flip[-1] = np.sign(np.linalg.det(u @ vt)) or 1.0
        yield (a - ca) @ ((u * flip) @ vt) + target.mean(axis=0)


def _face_keys(faces: np.ndarray) -> list[tuple[int, ...]]:
    """Each face's corners in its own cyclic order, from its smallest corner."""
    keys = []
    for row in faces.tolist():
        corners = [c for c in row if c >= 0]
        start = corners.index(min(corners))
        keys.append(tuple(corners[start:] + corners[:start]))
    return keys


def renumbered(
    meshes: list[Mesh], pairs: list[np.ndarray], reference: Mesh, tolerance: float
) -> tuple[list[Mesh], list[np.ndarray]] | None:
    """The meshes (and pairs of edge ids) in the numbering of ``reference``, or None.

    The vertices are matched by position in the first mesh (each within ``tolerance`` of one
    reference vertex, one to one), the edges by their two ends, the faces by their corners in
    cyclic order (from any corner: a face list started elsewhere is the same face). None when
    they do not all match: the geometry differs, and the arrays are compared as they are.
    """
    from scipy.spatial import cKDTree

    first = meshes[0]
    if first.vertices_coords.shape != reference.vertices_coords.shape:
        return None
    tree = cKDTree(reference.vertices_coords)
    for x in _laid_on(first.vertices_coords, reference.vertices_coords):
        distance, vertex = tree.query(x)
        if (distance <= tolerance).all() and len(np.unique(vertex)) == len(vertex):
            break
    else:
        return None
    inverse = np.argsort(vertex)
    ends = np.sort(vertex[first.edges_vertices], axis=1)
    theirs = {(int(a), int(b)): e for e, (a, b) in enumerate(np.sort(reference.edges_vertices, 1))}
    edge = np.array([theirs.get((int(a), int(b)), -1) for a, b in ends], np.int64)
    if len(edge) != len(theirs) or (edge < 0).any() or len(np.unique(edge)) != len(edge):
        return None
    their_faces = {key: f for f, key in enumerate(_face_keys(reference.faces_vertices))}
    mapped = np.where(first.faces_vertices >= 0, vertex[first.faces_vertices], -1)
    face = np.array([their_faces.get(key, -1) for key in _face_keys(mapped)], np.int64)
    if len(face) != len(their_faces) or (face < 0).any():
        return None
    edge_order, face_order = np.argsort(edge), np.argsort(face)
    moved = [
        replace(
            mesh,
            vertices_coords=mesh.vertices_coords[inverse],
            edges_vertices=reference.edges_vertices,
            edges_assignment=mesh.edges_assignment[edge_order],
            edges_foldAngle=mesh.edges_foldAngle[edge_order],
            edges_kind=mesh.edges_kind[edge_order],
            faces_vertices=reference.faces_vertices,
            faces_group=mesh.faces_group[face_order],
        )
        for mesh in meshes
    ]
    return moved, [edge[p] if len(p) else p for p in pairs]


def unsplit(
    meshes: list[Mesh], pairs: list[np.ndarray], tolerance: float
) -> tuple[list[Mesh], list[np.ndarray], np.ndarray]:
    """The meshes (of one topology) with every split edge joined again: a vertex on exactly two
    edges of one assignment and kind, on the straight segment between their other ends (within
    ``tolerance``) in every mesh, is removed and its two edges are one; the pairs of edge ids
    follow. Returns the meshes, the pairs and the vertices removed (ids of the input)."""
    ev = meshes[0].edges_vertices
    V = len(meshes[0].vertices_coords)
    degree = np.bincount(ev.ravel(), minlength=V)
    at: dict[int, list[int]] = {}
    for e, (p, q) in enumerate(ev.tolist()):
        for v in (p, q):
            if degree[v] == 2:
                at.setdefault(v, []).append(e)
    removed: list[int] = []
    drop: set[int] = set()
    joined: dict[int, int] = {}
    ends = ev.copy()
    for v, (e, f) in sorted(at.items()):
        if e in drop or f in drop or e in joined.values() or f in joined.values():
            continue
        a, b = (int(w) for w in (*ends[e], *ends[f]) if w != v)
        mesh0 = meshes[0]
        if (
            mesh0.edges_assignment[e] != mesh0.edges_assignment[f]
            or mesh0.edges_kind[e] != mesh0.edges_kind[f]
        ):
            continue
        straight = True
        for mesh in meshes:
            x = mesh.vertices_coords
            t = x[b] - x[a]
            s = float(np.dot(x[v] - x[a], t) / max(float(np.dot(t, t)), 1e-300))
            if not (0 < s < 1 and np.linalg.norm(x[a] + s * t - x[v]) <= tolerance):
                straight = False
                break
        if straight:
            removed.append(v)
            drop.add(f)
            joined[f] = e
            ends[e] = (a, b)
    if not removed:
        return meshes, pairs, np.zeros(0, np.int64)
    keep_v = np.ones(V, bool)
    keep_v[removed] = False
    new_v = np.cumsum(keep_v) - 1
    keep_e = np.ones(len(ev), bool)
    keep_e[list(drop)] = False
    new_e = np.cumsum(keep_e) - 1
    edge_of = np.arange(len(ev))
    for f, e in joined.items():
        edge_of[f] = e
    faces = meshes[0].faces_vertices
    rows = [[int(new_v[c]) for c in row if c >= 0 and keep_v[c]] for row in faces.tolist()]
    k = max(map(len, rows))
    faces_new = np.array([r + [-1] * (k - len(r)) for r in rows], np.int64)
    out = [
        replace(
            mesh,
            vertices_coords=mesh.vertices_coords[keep_v],
            edges_vertices=new_v[ends[keep_e]],
            edges_assignment=mesh.edges_assignment[keep_e],
            edges_foldAngle=mesh.edges_foldAngle[keep_e],
            edges_kind=mesh.edges_kind[keep_e],
            faces_vertices=faces_new,
        )
        for mesh in meshes
    ]
    moved = [new_e[edge_of[p]] if len(p) else p for p in pairs]
    return out, moved, np.array(removed, np.int64)


def turned_over(doc: FoldFile) -> FoldFile:
    """The same sheet seen from its other side: every face wound the other way, M and V swapped
    and every fold angle negated, the crease pattern mirrored (x → −x) in its plane; the folded
    coordinates unchanged."""

    def turned(mesh: Mesh, pattern: bool) -> Mesh:
        faces = mesh.faces_vertices
        rows = [[c for c in row if c >= 0][::-1] for row in faces.tolist()]
        x = mesh.vertices_coords.copy()
        if pattern:
            x[:, 0] *= -1
        swap = {"M": "V", "V": "M"}
        return replace(
            mesh,
            vertices_coords=x,
            faces_vertices=np.array(
                [r + [-1] * (faces.shape[1] - len(r)) for r in rows], np.int64
            ).reshape(faces.shape),
            edges_assignment=np.array(
                [swap.get(a, a) for a in mesh.edges_assignment.tolist()],
                mesh.edges_assignment.dtype,
            ),
            edges_foldAngle=-mesh.edges_foldAngle,
        )

    cp = doc.crease_pattern
    return replace(
        doc,
        crease_pattern=None if cp is None else turned(cp, True),
        folded=tuple((title, turned(mesh, False)) for title, mesh in doc.folded),
    )
