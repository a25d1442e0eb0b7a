"""Builders of the closed-form cases of the mechanics tests: flat strips, a plate, a Miura-ori cell.

Every builder returns a :class:`curvefold.geometry.Mesh` with curvefold's edge kinds,
so the cases go through :meth:`BarHingeModel.from_mesh` like a structure does.
"""

from __future__ import annotations

import numpy as np

from curvefold.geometry import Mesh


def mesh_of(x: np.ndarray, triangles: np.ndarray, edges: np.ndarray, kinds) -> Mesh:
    """A mesh of triangles with the given edges and kinds (no fold angles: the FOLD fields are
    placeholders)."""
    E = len(edges)
    return Mesh(
        vertices_coords=np.asarray(x, float),
        edges_vertices=np.asarray(edges),
        edges_assignment=np.full(E, "F"),
        edges_foldAngle=np.zeros(E),
        faces_vertices=np.asarray(triangles),
        edges_kind=np.asarray(kinds, dtype="<U8"),
        faces_group=np.zeros(len(triangles), np.int64),
    )


def strip(length: float, width: float, quads: int, *, triangles: bool = False) -> Mesh:
    """A flat strip along x in z = 0: ``quads`` rectangles between rulings across it (along y).

    Vertices: 2i at (x_i, 0), 2i + 1 at (x_i, width). The long edges are boundaries, the
    ends too; the rulings inside are ``"ruling"``. With ``triangles`` every rectangle is
    two triangles split by a ``"diagonal"`` edge from (x_i, 0) to (x_i+1, width).
    """
    xs = np.linspace(0.0, length, quads + 1)
    x = np.stack(
        [np.repeat(xs, 2), np.tile([0.0, width], quads + 1), np.zeros(2 * quads + 2)], axis=1
    )
    i = np.arange(quads)
    # (x_i, 0), (x_i+1, 0), (x_i+1, w), (x_i, w)
    a, b, c, d = 2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1
    long = np.concatenate([np.stack([a, b], 1), np.stack([d, c], 1)])
    rulings = np.stack([2 * np.arange(quads + 1), 2 * np.arange(quads + 1) + 1], 1)
    kinds = ["boundary"] * len(long) + ["boundary"] + ["ruling"] * (quads - 1) + ["boundary"]
    edges = np.concatenate([long, rulings])
    if not triangles:
        return mesh_of(x, np.stack([a, b, c, d], 1), edges, kinds)
    faces = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    return mesh_of(
        x, faces, np.concatenate([edges, np.stack([a, c], 1)]), kinds + ["diagonal"] * quads
    )


def miura_cell(a: float, b: float, gamma: float, theta: float) -> np.ndarray:
    """The 3 × 3 nodes of a Miura-ori unit cell (four parallelograms, sides a and b, acute angle γ),
    shape (9, 3).

    Schenk and Guest's (2013) dimensions at the fold angle θ (the facets' dihedral angle
    with the xy plane): H = a sin θ sin γ, L = a √(1 − sin²θ sin²γ),
    S = b cos θ tan γ / √(1 + cos²θ tan²γ), V = b / √(1 + cos²θ tan²γ). The folded cell is
    the translational surface of two zigzags: node (i, j) = (i L + V [j odd], j S, H [i odd]),
    whose steps (L, 0, ±H) and (±V, S, 0) have lengths a and b and meet at γ or π − γ.
    Node 3 i + j. Works on complex θ (for complex-step derivatives).
    """
    st, ct, sg, tg = np.sin(theta), np.cos(theta), np.sin(gamma), np.tan(gamma)
    H = a * st * sg
    L = a * np.sqrt(1 - st**2 * sg**2)
    S = b * ct * tg / np.sqrt(1 + ct**2 * tg**2)
    V = b / np.sqrt(1 + ct**2 * tg**2)
    nodes = [[i * L + V * (j % 2), j * S, H * (i % 2)] for i in range(3) for j in range(3)]
    return np.array(nodes)


def miura_mesh(a: float, b: float, gamma: float, theta: float) -> Mesh:
    """The Miura-ori cell as a mesh: its four creases at the centre node folds, the panels split
    by diagonals."""
    x = miura_cell(a, b, gamma, theta).real
    triangles, diagonals = [], []
    for i in range(2):
        for j in range(2):
            p, q, r, s = 3 * i + j, 3 * (i + 1) + j, 3 * (i + 1) + j + 1, 3 * i + j + 1
            triangles += [[p, q, r], [p, r, s]]
            diagonals.append([p, r])
    creases = [[4, 1], [4, 7], [4, 3], [4, 5]]
    boundary = [[0, 1], [1, 2], [6, 7], [7, 8], [0, 3], [3, 6], [2, 5], [5, 8]]
    edges = creases + boundary + diagonals
    kinds = ["fold"] * 4 + ["boundary"] * 8 + ["diagonal"] * 4
    return mesh_of(x, np.array(triangles), np.array(edges), kinds)


def dihedral(x: np.ndarray, i: int, j: int, k: int, m: int) -> complex:
    """Angle between the normals of faces (i, j, k) and (j, i, m) of points x, radians;
    complex-safe (no abs)."""
    e = x[j] - x[i]
    n1 = np.cross(e, x[k] - x[i])
    n2 = np.cross(x[m] - x[i], e)
    cos = (n1 @ n2) / np.sqrt((n1 @ n1) * (n2 @ n2))
    return np.arccos(cos)
