"""What the FOLD reader reads of a file's keys, what it leaves and why, and FOLD 1.2's cut edges.

:func:`ignored_keys` names the keys of a file's frames that
:func:`curvefold.io.read_fold` does not read, each with the reason;
:func:`split_cuts` reads FOLD 1.2's cut edges (``C``) as the specification says: one
boundary edge per face, the vertices along a cut split.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from ..geometry._mesh import Mesh, face_sides
from ..geometry._mesh import fold_angles as dihedral_angles

__all__ = ["SPEC_READ", "READ_KEYS", "ignored_keys", "split_cuts"]

#: The FOLD version read.
SPEC_READ = 1.2
#: Frame keys the reader reads, or that only describe (titles, authors, attributes).
READ_KEYS = frozenset(
    {
        "frame_title",
        "frame_classes",
        "frame_attributes",
        "frame_unit",
        "frame_author",
        "frame_description",
        "frame_parent",
        "frame_inherit",
        "vertices_coords",
        "edges_vertices",
        "edges_assignment",
        "edges_foldAngle",
        "edges_foldAngles",
        "faces_vertices",
        "vertices_flatUnfoldCoords",
    }
)
#: Keys of the specification that are not read, by the reason.
_NOT_READ = {
    "layer order (checking it needs the overlaps of faces, which curvefold does not compute)": (
        "faceOrders",
        "edgeOrders",
    ),
    "derived from the vertices, edges and faces read, and not compared with them": (
        "vertices_vertices",
        "vertices_edges",
        "vertices_faces",
        "edges_faces",
        "faces_edges",
        "faces_faces",
        "edges_length",
        "edges_lengths",
    ),
    "derived from the crease pattern and the flat-folded coordinates, which are read": (
        "faces_flatFoldTransform",
        "faces_flatFoldOrientation",
    ),
}


def ignored_keys(frames: Sequence[dict], labels: Sequence[str]) -> list[str]:
    """One note per reason naming the frame keys that are not read (every frame's, each key once).

    Examples
    --------
    >>> print(
    ...     *ignored_keys(
    ...         [{"faceOrders": [], "cpedit:page": {}, "vertices_coords": []}], ["f.fold"]
    ...     )
    ... )
    f.fold: not read: faceOrders (layer order (checking it needs the overlaps of faces, which
    curvefold does not compute)); cpedit:page (another tool's key)
    """
    reason_of = {key: reason for reason, keys in _NOT_READ.items() for key in keys}
    found: dict[str, list[str]] = {}
    for frame in frames:
        for key in frame:
            if key in READ_KEYS or key.startswith(
                ("curvefold:", "edges_curvefold:", "faces_curvefold:")
            ):
                continue
            reason = reason_of.get(
                key, "another tool's key" if ":" in key else "not a key of FOLD 1.2"
            )
            if key not in found.setdefault(reason, []):
                found[reason].append(key)
    if not found:
        return []
    return [
        f"{labels[0]}: not read: "
        + "; ".join(f"{', '.join(keys)} ({reason})" for reason, keys in found.items())
    ]


def split_cuts(
    crease_pattern: Mesh | None, folded: tuple[tuple[str, Mesh], ...], where: str, notes: list[str]
) -> tuple[Mesh | None, tuple[tuple[str, Mesh], ...]]:
    """The frames with every cut edge (``C``) read as one boundary edge per face, and each
    vertex along a cut split into one per side (FOLD 1.2: "treated as multiple B edges").

    The split is found on the first frame's topology and applied to every frame of that
    topology (a frame of another topology is left as it is; the check reports it). A cut's
    first copy keeps its edge id, further copies and split vertices come after the others.
    """
    meshes = ([crease_pattern] if crease_pattern is not None else []) + [m for _, m in folded]
    ref = meshes[0]
    if not (ref.edges_assignment == "C").any():
        return crease_pattern, folded
    split = _split(ref)
    if split is None:
        return crease_pattern, folded
    vertex_of, faces, edges, copies = split

    def apply(mesh: Mesh) -> Mesh:
        if not (
            np.array_equal(mesh.edges_vertices, ref.edges_vertices)
            and np.array_equal(mesh.faces_vertices, ref.faces_vertices)
        ):
            return mesh

        def extend(a, fill):
            return np.concatenate(
                [
                    np.where(mesh.edges_assignment == "C", fill, a),
                    np.full(len(copies), fill, a.dtype),
                ]
            )

        return replace(
            mesh,
            vertices_coords=mesh.vertices_coords[vertex_of],
            faces_vertices=faces,
            edges_vertices=edges,
            edges_assignment=extend(mesh.edges_assignment, "B"),
            edges_foldAngle=np.concatenate(
                [
                    np.where(mesh.edges_assignment == "C", 0.0, mesh.edges_foldAngle),
                    np.zeros(len(copies)),
                ]
            ),
            edges_kind=extend(mesh.edges_kind, "boundary"),
        )

    cuts = int((ref.edges_assignment == "C").sum())
    notes.append(
        f"{where}: {cuts} cut (C) edges read as {cuts + len(copies)} boundary edges, "
        f"one per face, {len(vertex_of) - len(ref.vertices_coords)} vertices split along the "
        "cuts (FOLD 1.2)"
    )
    cp = None if crease_pattern is None else apply(crease_pattern)
    return cp, tuple((title, apply(m)) for title, m in folded)


def _split(mesh: Mesh):
    """(vertex_of (V',), faces, edges (E + k, 2), copies (k,)) of the split mesh, or None when the
    faces repeat a vertex or a cut edge is on no face (the check reports both).

    A corner is a face at one of its vertices; the corners of two faces that share an edge
    which is not a cut are one copy of each of its vertices (connected components)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    faces, ev, a = mesh.faces_vertices, mesh.edges_vertices, mesh.edges_assignment
    V = len(mesh.vertices_coords)
    sides, side_face = face_sides(faces)  # side i starts at corner i; face by face, in vertex order
    if len(sides) != int((faces >= 0).sum()):
        return None
    starts = np.r_[0, np.flatnonzero(np.diff(side_face)) + 1]
    following = np.arange(1, len(sides) + 1)  # the corner at each side's second vertex
    following[np.r_[starts[1:], len(sides)] - 1] = starts
    key = np.sort(sides, axis=1) @ np.array([V, 1], np.int64)
    edge_key = np.sort(ev, axis=1) @ np.array([V, 1], np.int64)
    cut = np.isin(key, edge_key[a == "C"])
    order = np.argsort(key, kind="stable")
    pair = np.flatnonzero((key[order][1:] == key[order][:-1]) & ~cut[order][1:])
    s, t = order[pair], order[pair + 1]  # two sides along one edge that is not a cut
    at_first = np.stack([s, np.where(sides[t, 0] == sides[s, 0], t, following[t])], axis=1)  # of s
    at_second = np.stack(
        [following[s], np.where(sides[t, 0] == sides[s, 1], t, following[t])], axis=1
    )
    joins = np.concatenate([at_first, at_second])
    graph = coo_matrix(
        (np.ones(len(joins)), (joins[:, 0], joins[:, 1])), shape=(len(sides), len(sides))
    )
    _, component = connected_components(graph, directed=False)
    vertex = sides[:, 0]
    split = np.isin(vertex, ev[a == "C"])  # only the vertices on a cut are split
    # (vertex, component), by vertex
    copies_of = np.unique(np.stack([vertex[split], component[split]], axis=1), axis=0)
    first = np.r_[True, copies_of[1:, 0] != copies_of[:-1, 0]]
    ids = np.where(first, copies_of[:, 0], V + np.cumsum(~first) - 1)
    corner_vertex = vertex.copy()
    at = np.searchsorted(
        copies_of[:, 0] * len(sides) + copies_of[:, 1],
        vertex[split] * len(sides) + component[split],
    )
    corner_vertex[split] = ids[at]
    vertex_of = np.concatenate([np.arange(V), copies_of[~first, 0]])
    new_faces = faces.copy()
    new_faces[faces >= 0] = corner_vertex
    # every edge takes its ends from a face along it; a cut one copy per face
    sorted_keys = key[order]

    def ends(i: np.ndarray, e: np.ndarray) -> np.ndarray:
        pair = np.stack([corner_vertex[i], corner_vertex[following[i]]], axis=-1)
        return np.where((sides[i, 0] == ev[e, 0])[..., None], pair, pair[..., ::-1])

    first_side = order[np.clip(np.searchsorted(sorted_keys, edge_key), 0, len(order) - 1)]
    found = key[first_side] == edge_key
    if not found[a == "C"].all():
        return None
    edges = ev.copy()
    edges[found] = ends(first_side[found], np.flatnonzero(found))
    copies = []
    for e in np.flatnonzero(a == "C"):
        more = order[
            np.searchsorted(sorted_keys, edge_key[e]) + 1 : np.searchsorted(
                sorted_keys, edge_key[e], side="right"
            )
        ]
        copies += ends(more, np.full(len(more), e)).tolist()
    edges = np.concatenate([edges, np.array(copies, np.int64).reshape(-1, 2)])
    return vertex_of, new_faces, edges, np.arange(len(copies))


def unfolded_with_targets(mesh: Mesh, label: str, notes: list[str]) -> bool:
    """Whether a frame classed as folded lies in a plane unfolded (every dihedral angle 0: no
    face on another) while it records fold angles: they are a crease pattern's target angles
    (as Origami Simulator saves a pattern, in its plane y = 0), not this state's. Said in
    ``notes`` when so."""
    recorded = np.abs(mesh.edges_foldAngle)
    x = mesh.vertices_coords - mesh.vertices_coords.mean(axis=0)
    if not recorded.max(initial=0.0) > 0 or not len(x):
        return False
    spread = np.linalg.svd(x, compute_uv=False)
    if not spread[-1] <= 1e-9 * spread[0]:
        return False
    measured = dihedral_angles(mesh.vertices_coords, mesh.faces_vertices, mesh.edges_vertices)
    if not (np.abs(measured[np.isfinite(measured)]) < 1e-6).all():
        return False
    notes.append(
        f"{label}: classed foldedForm, it lies in a plane unfolded while it records fold angles up "
        f"to {recorded.max():g}°: read as a crease pattern with its target angles"
    )
    return True
