"""Elements across the width of a strip: a sheet's quads cut into k along their rulings.

A structure's quads (:meth:`Topology.mesh` in ``"quads"``) each run between two lattice
curves, two of their sides along the curves (creases and seams), two across (rulings, or
the fold lines of rigid panels). With one element across, a strip is straight between its
creases: it cannot bend or wave across its width, so the model is too stiff under load and
misses the plate buckling of a strip between its creases. :func:`cut_across` cuts every quad
into k quads by k − 1 lines between its two curves, at the fractions j / k of its sides
across; every point on those sides is on a straight segment of the sheet (a ruling or a
panel's edge), so the cut sheet is the same surface. The new lines inside a strip are edges
of kind :data:`WITHIN`, hinged with the sheet's bending stiffness (``D ℓ / s``, as a
ruling); the pieces of the sides across keep their side's kind; creases and seams stay as
they are.

A new vertex is made once per side across and fraction, so the quads on either side of a
ruling share it; every new vertex is the point ``(1 − w) x_a + w x_b`` of the side's ends
a and b, which the model uses to carry any field of the curves' points onto it (a rigid
folding moves a ruling's points linearly).
"""

from __future__ import annotations

import numpy as np

from ..geometry._mesh import Mesh
from ..kernel._errors import InputError
from ..kernel._validate import Interval, Spec

__all__ = ["WITHIN", "ACROSS", "check_across", "cut_across"]

#: The kind of the edges that cut a strip or panel along its length, inside the sheet.
WITHIN = "within"
#: Elements across each ruling strip or panel of a structure's model: one parameter, its range
#: and its meaning (the design files' ``[loads] across``, ``--across``; :func:`analyse_load`
#: takes one element across unless told, the bar-and-hinge model of the literature).
ACROSS = Spec(
    "across",
    "integer",
    4,
    Interval.parse("[1, 64]"),
    "elements",
    help="elements across each ruling strip or panel: k > 1 lets the sheet bend and buckle "
    "across its width; every figure's error is estimated against k / 2 (default 4: the "
    "paper's vault within 1 % of its converged figures)",
    why="each element across multiplies the model's size",
    typical=Interval.parse("[1, 8]"),
    label="elements across each strip",
)


def check_across(across: object) -> int:
    """``across`` checked against :data:`ACROSS` (an :class:`InputError` names it and the value).

    Examples
    --------
    >>> check_across(4)
    4
    >>> check_across(0)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: across must be an integer in [1, 64] elements (each
    element across multiplies the model's size), got 0
    """
    return int(ACROSS.check(across))


def cut_across(
    mesh: Mesh, vertex_curve: np.ndarray, across: int
) -> tuple[Mesh, np.ndarray, np.ndarray]:
    """The mesh with every quad cut into ``across`` quads between its two curves (module notes).

    Parameters
    ----------
    mesh : Mesh
        Quads, each with two opposite sides along lattice curves (corners 0, 1 on one curve
        and 2, 3 on another, or corners 1, 2 and 3, 0).
    vertex_curve : (V,) array_like of int
        The lattice curve of every vertex of the mesh.
    across : int
        k, elements across, in :data:`ACROSS`'s range.

    Returns
    -------
    mesh : Mesh
        The cut mesh: the V vertices of ``mesh`` first, then the new ones.
    ends : (V', 2) ndarray of int
        For every vertex, the two vertices of ``mesh`` it lies between (a vertex of
        ``mesh``: itself twice).
    weight : (V',) ndarray
        w of every vertex, at ``(1 − w) x_a + w x_b`` of its ends (0 for a vertex of
        ``mesh``).

    Raises
    ------
    InputError
        For ``across`` out of range or a face that is not a quad between two curves.

    Examples
    --------
    A square between curves 0 (vertices 0, 1) and 1 (vertices 2, 3), cut in two:

    >>> sheet = Mesh(
    ...     vertices_coords=[[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
    ...     edges_vertices=[[0, 1], [1, 2], [2, 3], [3, 0]],
    ...     edges_assignment=["M", "F", "M", "B"],
    ...     edges_foldAngle=[0.0] * 4,
    ...     faces_vertices=[[0, 1, 2, 3]],
    ...     edges_kind=["fold", "ruling", "seam", "boundary"],
    ...     faces_group=[0],
    ... )
    >>> cut, ends, w = cut_across(sheet, [0, 0, 1, 1], 2)
    >>> cut.faces_vertices.tolist(), cut.vertices_coords[4:].tolist(), w.tolist()
    ([[0, 1, 5, 4], [4, 5, 2, 3]], [[0.0, 0.5, 0.0], [1.0, 0.5, 0.0]],
     [0.0, 0.0, 0.0, 0.0, 0.5, 0.5])
    >>> sorted(zip(cut.edges_kind.tolist(), cut.edges_vertices.tolist()))[-1]
    ('within', [4, 5])
    """
    k = check_across(across)
    x = np.asarray(mesh.vertices_coords, float)
    faces = np.asarray(mesh.faces_vertices, np.int64)
    curve = np.asarray(vertex_curve, np.int64)
    V = len(x)
    if k == 1:
        return mesh, np.repeat(np.arange(V)[:, None], 2, axis=1), np.zeros(V)
    if faces.ndim != 2 or faces.shape[1] != 4 or (faces < 0).any():
        raise InputError(f"cut_across takes quads, got faces of shape {faces.shape}")
    c = curve[faces]
    along01 = (c[:, 0] == c[:, 1]) & (c[:, 2] == c[:, 3]) & (c[:, 1] != c[:, 2])
    along12 = (c[:, 1] == c[:, 2]) & (c[:, 3] == c[:, 0]) & (c[:, 0] != c[:, 1])
    if not (along01 | along12).all():
        f = int(np.argmax(~(along01 | along12)))
        raise InputError(
            f"face {f} is not a quad between two curves (its corners' curves are {c[f].tolist()})"
        )
    # corners a0, a1 on one curve, b1, b0 on the other: sides across a0-b0 and a1-b1
    quad = np.where(along01[:, None], faces, np.roll(faces, -1, axis=1))
    a0, a1, b1, b0 = quad.T

    # a new vertex per side across (sorted pair) and inner fraction j / k, j = 1 … k − 1
    sides = np.concatenate([np.stack([a0, b0], 1), np.stack([a1, b1], 1)])
    key = np.sort(sides, axis=1)
    unique, inverse = np.unique(key, axis=0, return_inverse=True)
    inverse = inverse.ravel()
    j = np.arange(1, k)
    new_ends = np.repeat(unique, k - 1, axis=0)  # (S (k − 1), 2), from the lower vertex
    new_w = np.tile(j / k, len(unique))
    F = len(faces)

    def point(side: slice, frac: int) -> np.ndarray:
        """The vertex at j = frac of the sides across (0 at a, k at b)."""
        if frac in (0, k):
            return sides[side, 0 if frac == 0 else 1]
        flipped = sides[side, 0] != key[side, 0]
        jj = np.where(flipped, k - frac, frac)
        return V + inverse[side] * (k - 1) + jj - 1

    first, second = slice(0, F), slice(F, 2 * F)
    columns = [
        np.stack(
            [
                point(first, m),
                point(second, m),
                point(second, m + 1),
                point(first, m + 1),
            ],
            axis=1,
        )
        for m in range(k)
    ]
    # keep each face's orientation: a face given as 1, 2, 3, 0 comes back in that order
    cut_faces = np.stack(columns, axis=1)  # (F, k, 4)
    cut_faces = np.where(along01[:, None, None], cut_faces, np.roll(cut_faces, 1, axis=2)).reshape(
        -1, 4
    )

    # edges: the old ones not across, the pieces of the sides across, the lines within
    ev = np.sort(np.asarray(mesh.edges_vertices, np.int64), axis=1)
    width = V + 1
    side_code = unique[:, 0] * width + unique[:, 1]
    order = np.argsort(side_code)
    code = ev[:, 0] * width + ev[:, 1]
    pos = np.clip(np.searchsorted(side_code[order], code), 0, len(side_code) - 1)
    is_side = side_code[order][pos] == code
    side_of_edge = order[pos]
    keep = ~is_side
    chain = np.concatenate(
        [unique[:, :1], V + np.arange(len(unique) * (k - 1)).reshape(-1, k - 1), unique[:, 1:]],
        axis=1,
    )  # (S, k + 1): a side's vertices from its lower end
    pieces = np.stack([chain[:, :-1], chain[:, 1:]], axis=2)  # (S, k, 2)
    e_side = np.flatnonzero(is_side)
    s_of = side_of_edge[e_side]
    lines = np.concatenate(
        [np.stack([point(first, m), point(second, m)], axis=1) for m in range(1, k)]
    )
    lines = np.unique(np.sort(lines, axis=1), axis=0)
    n_lines = len(lines)
    out_edges = np.concatenate([ev[keep], pieces[s_of].reshape(-1, 2), lines])
    repeat = lambda a: np.repeat(np.asarray(a)[e_side], k)  # noqa: E731
    cut = Mesh(
        vertices_coords=np.concatenate(
            [x, (1 - new_w)[:, None] * x[new_ends[:, 0]] + new_w[:, None] * x[new_ends[:, 1]]]
        ),
        edges_vertices=out_edges,
        edges_assignment=np.concatenate(
            [
                np.asarray(mesh.edges_assignment)[keep],
                repeat(mesh.edges_assignment),
                np.full(n_lines, "F"),
            ]
        ),
        edges_foldAngle=np.concatenate(
            [
                np.asarray(mesh.edges_foldAngle, float)[keep],
                repeat(mesh.edges_foldAngle),
                np.zeros(n_lines),
            ]
        ),
        faces_vertices=cut_faces,
        edges_kind=np.concatenate(
            [np.asarray(mesh.edges_kind)[keep], repeat(mesh.edges_kind), np.full(n_lines, WITHIN)]
        ).astype("<U8"),
        faces_group=np.repeat(np.asarray(mesh.faces_group), k),
    )
    ends = np.concatenate([np.repeat(np.arange(V)[:, None], 2, axis=1), new_ends])
    return cut, ends, np.concatenate([np.zeros(V), new_w])
