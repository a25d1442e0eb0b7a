"""The bar-and-hinge model: nodes, bars, membranes and hinges, and its sparse matrices.

A model is a value (:class:`BarHingeModel`); its matrices are pure functions of it. The
unknowns are the displacements u (3P,) of its P nodes, node by node (x, y, z). The
compatibility matrix C (B, 3P) gives the bars' elongations δ = C u, the hinge matrix
J (H, 3P) the changes of the hinges' dihedral angles Δθ = J u. The elastic energy is

    U = ½ δᵀ S δ + ½ Δθᵀ diag(k) Δθ,    so    K = Cᵀ S C + Jᵀ diag(k) J,

with S the bars' stiffness: each membrane's block (:mod:`._elements`) on its bars (a
triangle's exact constant-strain stiffness on its three sides; a quad's incompatible-mode
stiffness on its four sides and its diagonal, which for a planar quad determine its
in-plane deformation exactly), plus the axial stiffness EA/L of bars of their own on the
diagonal. The reference state carries no stress: a linear analysis about the state as it
is built.

Build a model from any sheet of triangles and quads with :meth:`BarHingeModel.from_mesh`
(FOLD arrays with curvefold's edge kinds), or from its parts with the constructor (a
single bar, a single hinge). A quad keeps one bar along its diagonal from its first corner.
The hinge stiffness of every kind of edge, with ``D = E t³ / 12(1 − ν²)`` and ℓ the edge's
length:

* ``fold``, ``seam``: a crease, ``k = k_c ℓ`` with k_c the crease stiffness per length;
* ``ruling``, ``within`` (a line inside a strip cut across its width, :mod:`._across`) and
  any other edge between two faces: the sheet bending about it, ``k = D ℓ / s`` with s the
  mean width of its two faces across it (a quad's area over ℓ, a triangle's height): exact
  for the cylindrical bending of a strip about its rulings, whose hinge angle is the
  curvature times the rulings' spacing;
* ``diagonal`` (of a quad, or an edge so named between two triangles): the twist of the
  quad, ``k = 2 D (1 − ν) A / ℓ²`` with A the quad's area: exact for a rectangular plate
  twisted by its corners (w = c x y, uniform M_xy).

An edge between two quads is measured at both its ends (two hinges of half its stiffness,
their wings the quads' corners next to that end), so that a kink that varies along it
costs bending too: with one hinge between the triangles that hold the edge, quads that
twist across their diagonals bend a strip at the price of twisting it, a spurious mode
that makes a finely sampled strip softer and softer (measured in the tests).
``boundary`` edges border one face and carry no hinge.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from ..geometry._mesh import Mesh
from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InputError
from ._across import WITHIN
from ._elements import (
    bar_rows,
    dihedral_gradient,
    dihedral_hessian,
    face_bars,
    face_membranes,
    membrane_geometric,
    plane_stress,
    triangle_areas,
)
from ._materials import Material, check_thickness
from ._sparse import assemble, rows_matrix

__all__ = ["BarHingeModel", "HINGE_KINDS", "CREASES"]

#: Edge kinds that carry a hinge, and how its stiffness is found (module notes).
HINGE_KINDS = ("fold", "seam", "ruling", WITHIN, "diagonal")
#: The hinge kinds that are creases (stiffness per length k_c).
CREASES = ("fold", "seam")


@dataclass(frozen=True, eq=False)
class BarHingeModel(FrozenArrays):
    """A bar-and-hinge model in its reference (stress-free) state. SI units; arrays read-only.

    Attributes
    ----------
    nodes : (P, 3) ndarray
        Node positions, m.
    bars : (B, 2) ndarray of int
        Node pairs.
    bar_stiffness : (B,) ndarray
        Axial stiffness EA/L of bars of their own, N/m (0 for bars that carry only the
        membranes they border).
    hinges : (H, 4) ndarray of int
        Nodes i, j (the edge), k, l (the wings of faces A and B) of every hinge.
    hinge_stiffness : (H,) ndarray
        Rotational stiffness, N·m/rad.
    masses : (P,) ndarray
        Lumped nodal mass, kg.
    membranes : (T, 4) ndarray of int
        Membrane faces: quads, or triangles padded with -1 (may be empty).
    membrane_bars : (T, 5) ndarray of int
        The bars of every face: its sides from corner m to m + 1, then a quad's diagonal
        from corner 0 to 2; -1 pads a triangle's.
    membrane_stiffness : (T, 5, 5) ndarray
        Every face's stiffness on its bars' elongations, N/m (zero where padded).
    membrane_strain : (T, 3, 5) ndarray
        Voigt strain at the face's centre, in its own frame, from its bars' elongations, 1/m.
    membrane_area : (T,) ndarray
        Face areas, m².
    elasticity : (3, 3) ndarray
        Plane-stress matrix D of the membranes, Pa.
    thickness : float
        Sheet thickness t of the membranes, m (0 without membranes).
    hinge_kind : (H,) ndarray of str
        ``"fold"``, ``"seam"``, ``"ruling"``, ``"diagonal"`` (default ``"hinge"``, for hinges
        given as they are).
    hinge_length : (H,) ndarray
        The length of edge every hinge stands for, m: half the edge for the two hinges at
        the ends of an edge between quads (default: the edge).
    hinge_faces : (H, 2) ndarray of int
        The membranes of faces A and B of every hinge (default -1: none).

    Examples
    --------
    >>> import numpy as np
    >>> square = BarHingeModel(
    ...     np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]),
    ...     [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
    ...     np.ones(5),
    ...     [[0, 2, 1, 3]],
    ...     [1.0],
    ...     np.ones(4),
    ... )  # four bars, a diagonal and its hinge
    >>> square.dofs, square.hinge_kind.tolist(), len(square.membranes)  # no membranes: bars alone
    (12, ['hinge'], 0)
    >>> BarHingeModel(np.zeros((2, 2)), [[0, 1]], [1.0], np.zeros((0, 4), int), [], np.ones(2))
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: nodes must be finite positions (P, 3), got shape (2, 2)
    """

    nodes: np.ndarray
    bars: np.ndarray
    bar_stiffness: np.ndarray
    hinges: np.ndarray
    hinge_stiffness: np.ndarray
    masses: np.ndarray
    membranes: np.ndarray = field(default_factory=lambda: np.zeros((0, 4), np.int64))
    membrane_bars: np.ndarray = field(default_factory=lambda: np.zeros((0, 5), np.int64))
    membrane_stiffness: np.ndarray = field(default_factory=lambda: np.zeros((0, 5, 5)))
    membrane_strain: np.ndarray = field(default_factory=lambda: np.zeros((0, 3, 5)))
    membrane_area: np.ndarray = field(default_factory=lambda: np.zeros(0))
    elasticity: np.ndarray = field(default_factory=lambda: np.zeros((3, 3)))
    thickness: float = 0.0
    hinge_kind: np.ndarray | None = None
    hinge_length: np.ndarray | None = None
    hinge_faces: np.ndarray | None = None

    def __post_init__(self) -> None:
        nodes = np.asarray(self.nodes, float)
        if nodes.ndim != 2 or nodes.shape[1] != 3 or not np.isfinite(nodes).all():
            raise InputError(f"nodes must be finite positions (P, 3), got shape {nodes.shape}")
        H = len(np.asarray(self.hinges).reshape(-1, 4))
        if self.hinge_kind is None:
            object.__setattr__(self, "hinge_kind", np.full(H, "hinge"))
        if self.hinge_faces is None:
            object.__setattr__(self, "hinge_faces", np.full((H, 2), -1, np.int64))
        object.__setattr__(self, "nodes", nodes)
        object.__setattr__(self, "bars", np.asarray(self.bars, np.int64).reshape(-1, 2))
        object.__setattr__(self, "hinges", np.asarray(self.hinges, np.int64).reshape(-1, 4))
        for name in ("bar_stiffness", "hinge_stiffness", "masses"):
            object.__setattr__(self, name, np.asarray(getattr(self, name), float))
        P, B = len(nodes), len(self.bars)
        for name, shape in (
            ("bar_stiffness", (B,)),
            ("hinge_stiffness", (H,)),
            ("masses", (P,)),
            ("hinge_kind", (H,)),
        ):
            if np.shape(getattr(self, name)) != shape:
                raise InputError(
                    f"{name} must have shape {shape}, got {np.shape(getattr(self, name))}"
                )
        for name in ("bars", "hinges", "membranes"):
            index = np.asarray(getattr(self, name))
            index = index[index >= 0] if name == "membranes" else index
            if index.size and (index.min() < 0 or index.max() >= P):
                raise InputError(
                    f"{name} must index the {P} nodes, got indices in "
                    f"[{index.min()}, {index.max()}]"
                )
        for name in ("bar_stiffness", "hinge_stiffness", "masses"):
            values = getattr(self, name)
            if not (np.isfinite(values).all() and (values >= 0).all()):
                raise InputError(
                    f"{name} must be finite and ≥ 0, got a minimum of "
                    f"{values.min() if values.size else 0:g}"
                )
        if self.hinge_length is None:
            x = nodes[self.hinges[:, :2]]
            object.__setattr__(self, "hinge_length", np.linalg.norm(x[:, 1] - x[:, 0], axis=-1))
        super().__post_init__()

    # -- construction from a sheet -------------------------------------------------------------
    @classmethod
    def from_mesh(
        cls,
        mesh: Mesh,
        material: Material,
        thickness: float,
        *,
        crease_stiffness: float,
        weld: np.ndarray | None = None,
    ) -> BarHingeModel:
        """The model of a sheet mesh of triangles and quads: membranes, and hinges on its edges by
        kind.

        A face is a membrane on its bars (a quad's four sides and its diagonal from its
        first corner), and a quad has a ``"diagonal"`` hinge across that diagonal (its
        twist). Masses are lumped equally at a face's corners. An edge between two
        quads carries two hinges of half its stiffness, one at each end of the edge, whose
        wings are the quads' corners next to that end: the kink between the quads is
        measured where it is, so a kink that varies along the edge (the quads twisting)
        costs what it should. An edge next to a triangle carries one hinge on the
        triangle's third corner. Edges are hinged as the mesh gives them, before welding:
        two tubes sharing a crease each keep their own crease hinges on the shared nodes.

        Parameters
        ----------
        mesh : Mesh
            Vertex positions in metres; faces of three or four vertices, oriented
            consistently or not.
        material : Material
        thickness : float
            t, m.
        crease_stiffness : float, keyword-only
            k_c, the rotational stiffness of the creases per length, N·m/rad/m.
        weld : (V,) array_like of int, optional, keyword-only
            The node of every vertex, 0 … P − 1 (default: every vertex its own node).
            Welded vertices must coincide.

        Raises
        ------
        InputError
            For a face of more than four vertices, a weld joining vertices apart, an edge
            with more than two faces, or a degenerate triangle.

        Examples
        --------
        >>> from curvefold import Mesh
        >>> sheet = Mesh(
        ...     vertices_coords=[[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
        ...     edges_vertices=[[0, 1], [1, 2], [2, 3], [3, 0]],
        ...     edges_assignment=["B"] * 4,
        ...     edges_foldAngle=[0.0] * 4,
        ...     faces_vertices=[[0, 1, 2, 3]],
        ...     edges_kind=["boundary"] * 4,
        ...     faces_group=[0],
        ... )
        >>> model = BarHingeModel.from_mesh(
        ...     sheet, MATERIALS["aluminium"], 1e-3, crease_stiffness=1.0
        ... )  # 1 m², 1 mm of aluminium
        >>> (
        ...     model.bars.shape,
        ...     model.hinge_kind.tolist(),
        ...     round(float(model.masses.sum()), 6),
        ... )  # 4 sides and a diagonal; 2.7 kg
        ((5, 2), ['diagonal'], 2.7)
        """
        t = check_thickness(thickness)
        x = np.asarray(mesh.vertices_coords, float)
        faces = np.asarray(mesh.faces_vertices, np.int64)
        sizes = (faces >= 0).sum(axis=1)
        if (sizes > 4).any():
            raise InputError(
                "the model takes faces of three or four vertices; face "
                f"{int(np.argmax(sizes > 4))} has {sizes.max()}"
            )
        faces = np.concatenate(
            [faces, np.full((len(faces), 4 - faces.shape[1]), -1, np.int64)], axis=1
        )[:, :4]
        V = len(x)
        weld = np.arange(V) if weld is None else np.asarray(weld, np.int64)
        if weld.shape != (V,) or weld.min(initial=0) < 0:
            raise InputError(
                f"weld must give a node ≥ 0 for each of the {V} vertices, got shape {weld.shape}"
            )
        P = int(weld.max()) + 1
        nodes = np.zeros((P, 3))
        nodes[weld] = x
        size = float(np.ptp(x, axis=0).max()) if V else 0.0
        apart = np.linalg.norm(nodes[weld] - x, axis=1)
        if apart.size and apart.max() > 1e-9 * size:
            v = int(np.argmax(apart))
            raise InputError(
                f"weld joins vertices that are {apart[v]:.3g} m apart (vertex {v}); "
                "welded vertices must coincide"
            )

        # membranes: the faces; a quad's bars are its sides and its diagonal from corner 0
        quads = sizes == 4
        # triangles of the faces (for areas)
        split = np.concatenate([faces[:, :3], faces[quads][:, [0, 2, 3]]])
        tri_area = triangle_areas(x[split])
        if not (tri_area > 1e-14 * size**2).all():
            raise InputError(
                f"a face of the mesh is degenerate (a triangle of area {tri_area.min():.3g} m²)"
            )
        face_area = tri_area[: len(faces)].copy()
        face_area[quads] += tri_area[len(faces) :]
        S, strain = face_membranes(
            x, faces, sizes, face_area, material.youngs_modulus, material.poisson, t
        )

        # sides of the faces: side m of a face runs from its corner m to m + 1
        m = np.arange(faces.shape[1])
        corner = np.where(m[None] < sizes[:, None], faces, -1)
        nxt = np.where(m[None] + 1 < sizes[:, None], np.roll(faces, -1, axis=1), faces[:, :1])
        prev = np.where(
            m[None] > 0, np.roll(faces, 1, axis=1), faces[np.arange(len(faces)), sizes - 1][:, None]
        )
        after = np.take_along_axis(faces, (m[None] + 2) % sizes[:, None], axis=1)
        keep = corner >= 0
        side_face = np.broadcast_to(np.arange(len(faces))[:, None], faces.shape)[keep]
        p, q = corner[keep], nxt[keep]
        # corners next to p and to q
        near_p, near_q = prev[keep], np.where(sizes[side_face] == 3, prev[keep], after[keep])
        side_tri = side_face
        key = np.sort(np.stack([p, q], axis=1), axis=1)
        order = np.lexsort((key[:, 1], key[:, 0]))
        sk = key[order]
        start = (
            np.flatnonzero(np.r_[True, (sk[1:] != sk[:-1]).any(axis=1)])
            if len(sk)
            else np.zeros(0, np.int64)
        )
        counts = np.diff(np.r_[start, len(sk)])
        if counts.max(initial=0) > 2:
            g = int(np.argmax(counts))
            raise InputError(
                f"edge {sk[start[g]].tolist()} borders {counts[g]} faces; a sheet's "
                "edge borders one or two (join sheets by welding their vertices)"
            )
        first, second = order[start[counts == 2]], order[start[counts == 2] + 1]
        kinds = _kinds_of(key[first], mesh)
        hinged = np.isin(kinds, HINGE_KINDS)
        first, second, kinds = first[hinged], second[hinged], kinds[hinged]
        a, b = p[first], q[first]
        # the corners of the second face next to a and to b (its side may run either way)
        same = p[second] == a
        near_a2 = np.where(same, near_p[second], near_q[second])
        near_b2 = np.where(same, near_q[second], near_p[second])
        quad_pair = (sizes[side_face[first]] == 4) & (sizes[side_face[second]] == 4)
        ends = np.concatenate(
            [
                np.stack([a, b, near_p[first], near_a2], 1),
                np.stack([a, b, near_q[first], near_b2], 1)[quad_pair],
            ]
        )
        length = np.linalg.norm(x[b] - x[a], axis=1)
        f1, f2 = side_face[first], side_face[second]
        pair_area = face_area[f1] + face_area[f2]
        # the faces' widths across the edge (a quad's area over the edge, a triangle's height)
        spacing = (
            0.5
            * (
                (face_area * np.where(sizes == 3, 2.0, 1.0))[f1]
                + (face_area * np.where(sizes == 3, 2.0, 1.0))[f2]
            )
            / length
        )
        D, nu = material.bending_stiffness(t), material.poisson
        k_edge = np.select(
            [np.isin(kinds, CREASES), kinds == "diagonal"],
            [crease_stiffness * length, 2 * D * (1 - nu) * pair_area / length**2],
            D * length / spacing,
        )
        share = np.where(quad_pair, 0.5, 1.0)
        edge_faces = np.stack([side_tri[first], side_tri[second]], axis=1)
        # the quads' diagonal hinges: twist
        quad_faces = np.flatnonzero(quads)
        corners4 = faces[quads][:, :4]
        d = np.linalg.norm(x[corners4[:, 2]] - x[corners4[:, 0]], axis=1)
        Q = len(quad_faces)
        corners = np.concatenate([ends, corners4[:, [0, 2, 1, 3]]])
        pairs = face_bars(faces, sizes)  # (F, 5, 2), -1 padded
        valid = pairs[..., 0] >= 0
        bars, inverse = np.unique(np.sort(weld[pairs[valid]], axis=1), axis=0, return_inverse=True)
        membrane_bars = np.full(valid.shape, -1)
        membrane_bars[valid] = inverse.ravel()
        share_mass = np.where(faces >= 0, (material.density * t * face_area / sizes)[:, None], 0.0)
        return cls(
            nodes=nodes,
            bars=bars,
            bar_stiffness=np.zeros(len(bars)),
            hinges=weld[corners],
            hinge_stiffness=np.concatenate(
                [
                    k_edge * share,
                    (k_edge * share)[quad_pair],
                    2 * D * (1 - nu) * face_area[quads] / d**2,
                ]
            ),
            masses=np.bincount(
                weld[np.where(faces >= 0, faces, 0)].ravel(), share_mass.ravel(), minlength=P
            ),
            membranes=np.where(faces >= 0, weld[np.where(faces >= 0, faces, 0)], -1),
            membrane_bars=membrane_bars,
            membrane_stiffness=S,
            membrane_strain=strain,
            membrane_area=face_area,
            elasticity=plane_stress(material.youngs_modulus, material.poisson),
            thickness=t,
            hinge_kind=np.concatenate([kinds, kinds[quad_pair], np.full(Q, "diagonal")]).astype(
                "<U8"
            ),
            hinge_length=np.concatenate([length * share, (length * share)[quad_pair], d]),
            hinge_faces=np.concatenate(
                [edge_faces, edge_faces[quad_pair], np.stack([quad_faces, quad_faces], 1)]
            ),
        )

    # -- sizes ---------------------------------------------------------------------------------
    @property
    def dofs(self) -> int:
        """3P, the unknowns."""
        return 3 * len(self.nodes)

    @cached_property
    def size(self) -> float:
        """The largest extent of the nodes along x, y or z, m."""
        return float(np.ptp(self.nodes, axis=0).max()) if len(self.nodes) else 0.0

    # -- matrices ------------------------------------------------------------------------------
    @cached_property
    def _bar_rows(self) -> np.ndarray:
        return readonly(bar_rows(self.nodes[self.bars]))

    @cached_property
    def _hinge_rows(self) -> np.ndarray:
        return readonly(dihedral_gradient(self.nodes[self.hinges]))

    def compatibility(self) -> sp.csr_matrix:
        """C, the bars' elongations per nodal displacement, shape (B, 3P), dimensionless.

        Examples
        --------
        >>> import numpy as np
        >>> square = BarHingeModel(
        ...     np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]),
        ...     [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
        ...     np.ones(5),
        ...     [[0, 2, 1, 3]],
        ...     [1.0],
        ...     np.ones(4),
        ... )  # four bars, a diagonal and its hinge
        >>> (
        ...     square.compatibility().shape,
        ...     square.compatibility().toarray()[0].tolist(),
        ... )  # bar 0–1 along x
        ((5, 12), [-1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
        """
        return rows_matrix(self._bar_rows, self.bars, self.dofs)

    def hinge_matrix(self) -> sp.csr_matrix:
        """J, the hinges' rotations per nodal displacement, shape (H, 3P), rad/m.

        Examples
        --------
        >>> import numpy as np
        >>> square = BarHingeModel(
        ...     np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]),
        ...     [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
        ...     np.ones(5),
        ...     [[0, 2, 1, 3]],
        ...     [1.0],
        ...     np.ones(4),
        ... )  # four bars, a diagonal and its hinge
        >>> square.hinge_matrix().toarray().round(6)[
        ...     0, 2::3
        ... ].tolist()  # only the z displacements turn the flat hinge
        [-1.414214, 1.414214, -1.414214, 1.414214]
        """
        return rows_matrix(self._hinge_rows, self.hinges, self.dofs)

    def bar_stiffness_matrix(self) -> sp.csr_matrix:
        """S, the bars' stiffness on their elongations (membrane blocks and EA/L), shape (B, B),
        N/m.

        Examples
        --------
        >>> import numpy as np
        >>> square = BarHingeModel(
        ...     np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]),
        ...     [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
        ...     np.ones(5),
        ...     [[0, 2, 1, 3]],
        ...     [1.0],
        ...     np.ones(4),
        ... )  # four bars, a diagonal and its hinge
        >>> # no membranes: the bars' own EA/L
        >>> square.bar_stiffness_matrix().toarray().diagonal().tolist()
        [1.0, 1.0, 1.0, 1.0, 1.0]
        """
        B = len(self.bars)
        mb = self.membrane_bars
        k = mb.shape[1] if mb.ndim == 2 else 0
        rows, cols = np.repeat(mb, k, axis=1).ravel(), np.tile(mb, (1, k)).ravel()
        vals = self.membrane_stiffness.reshape(-1)
        ok = (rows >= 0) & (cols >= 0)
        return sp.csr_matrix(
            (
                np.concatenate([vals[ok], self.bar_stiffness]),
                (
                    np.concatenate([rows[ok], np.arange(B)]),
                    np.concatenate([cols[ok], np.arange(B)]),
                ),
            ),
            shape=(B, B),
        )

    def triangles(self) -> tuple[np.ndarray, np.ndarray]:
        """The membranes as triangles (a quad split along its bar diagonal): nodes (n, 3) and the
        membrane of each (n,).

        Examples
        --------
        >>> import numpy as np
        >>> square = BarHingeModel(
        ...     np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]),
        ...     [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
        ...     np.ones(5),
        ...     [[0, 2, 1, 3]],
        ...     [1.0],
        ...     np.ones(4),
        ... )  # four bars, a diagonal and its hinge
        >>> [a.shape for a in square.triangles()]  # no membranes, no triangles
        [(0, 3), (0,)]
        """
        faces = self.membranes
        quads = np.flatnonzero(faces[:, 3] >= 0) if len(faces) else np.zeros(0, np.int64)
        return (
            np.concatenate([faces[:, :3], faces[quads][:, [0, 2, 3]]]),
            np.concatenate([np.arange(len(faces)), quads]),
        )

    @cached_property
    def stiffness(self) -> sp.csr_matrix:
        """K = Cᵀ S C + Jᵀ diag(k) J, shape (3P, 3P), N/m (symmetric, positive semi-definite)."""
        C, J = self.compatibility(), self.hinge_matrix()
        K = (
            C.T @ self.bar_stiffness_matrix() @ C + J.T @ sp.diags(self.hinge_stiffness) @ J
        ).tocsr()
        K = 0.5 * (K + K.T)
        K.sort_indices()
        return K

    @cached_property
    def mass(self) -> sp.dia_matrix:
        """The lumped mass matrix, diagonal, shape (3P, 3P), kg."""
        return sp.diags(np.repeat(self.masses, 3))

    def bar_forces(self, u: np.ndarray) -> np.ndarray:
        """Axial force of every bar for displacements u (3P,), N (tension positive), shape (B,).

        Examples
        --------
        >>> import numpy as np
        >>> square = BarHingeModel(
        ...     np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]),
        ...     [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
        ...     np.ones(5),
        ...     [[0, 2, 1, 3]],
        ...     [1.0],
        ...     np.ones(4),
        ... )  # four bars, a diagonal and its hinge
        >>> u = np.zeros(12)
        >>> u[3] = 0.01  # node 1 moves 1 cm along x
        >>> square.bar_forces(u).round(6).tolist(), square.bar_forces(np.zeros(12)).tolist()
        ([0.01, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0, 0.0])
        """
        return self.bar_stiffness_matrix() @ (self.compatibility() @ u)

    def membrane_stress(self, u: np.ndarray) -> np.ndarray:
        """(σ_xx, σ_yy, τ_xy) at every membrane's centre, in its own frame, for displacements u
        (3P,), Pa, shape (T, 3).

        Examples
        --------
        >>> import numpy as np
        >>> square = BarHingeModel(
        ...     np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]),
        ...     [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
        ...     np.ones(5),
        ...     [[0, 2, 1, 3]],
        ...     [1.0],
        ...     np.ones(4),
        ... )  # four bars, a diagonal and its hinge
        >>> square.membrane_stress(np.ones(12)).shape  # bars alone: no membrane
        (0, 3)
        """
        delta = self.compatibility() @ np.asarray(u, float).ravel()
        mb = self.membrane_bars
        return (
            np.einsum("tij,tj->ti", self.membrane_strain, np.where(mb >= 0, delta[mb], 0.0))
            @ self.elasticity.T
        )

    def geometric_stiffness(self, u: np.ndarray, *, hinges: bool = True) -> sp.csr_matrix:
        """K_G of the internal forces of displacements u (3P,), shape (3P, 3P), N/m.

        The membranes' ``t ∫ ∇N · σ · ∇N dA`` of their centre stress
        (2 × 2 Gauss points on a quad); a bar of its own's
        ``(N/ℓ)(I − ê êᵀ)`` (its force N times the Hessian of its length); with ``hinges``,
        every hinge's moment times the Hessian of its angle.

        Examples
        --------
        >>> import numpy as np
        >>> square = BarHingeModel(
        ...     np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]),
        ...     [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
        ...     np.ones(5),
        ...     [[0, 2, 1, 3]],
        ...     [1.0],
        ...     np.ones(4),
        ... )  # four bars, a diagonal and its hinge
        >>> int(
        ...     square.geometric_stiffness(np.zeros(12)).count_nonzero()
        ... )  # no internal force, no geometric stiffness
        0
        """
        u = np.asarray(u, float).ravel()
        P = len(self.nodes)
        stress = self.membrane_stress(u)
        quads = self.membranes[:, 3] >= 0
        rows, cols, vals = [], [], []
        for keep, k in ((~quads, 3), (quads, 4)):  # the same scalar matrix for x, y and z
            if keep.any():
                corners = self.membranes[keep][:, :k]
                vals.append(
                    membrane_geometric(self.nodes[corners], stress[keep], self.thickness).ravel()
                )
                rows.append(np.repeat(corners, k, axis=1).ravel())
                cols.append(np.tile(corners, (1, k)).ravel())
        scalar = (
            sp.csr_matrix(
                (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(P, P)
            )
            if vals
            else sp.csr_matrix((P, P))
        )
        KG = sp.kron(scalar, sp.identity(3), format="csr")
        plain = np.flatnonzero(self.bar_stiffness)
        if plain.size:
            x = self.nodes[self.bars[plain]]
            d = x[:, 1] - x[:, 0]
            ell = np.linalg.norm(d, axis=1)
            e = d / ell[:, None]
            forces = self.bar_stiffness[plain] * (self.compatibility()[plain] @ u)
            block = (forces / ell)[:, None, None] * (np.eye(3) - e[:, :, None] * e[:, None, :])
            KG = KG + assemble(
                np.einsum("ab,nij->naibj", np.array([[1.0, -1.0], [-1.0, 1.0]]), block).reshape(
                    -1, 6, 6
                ),
                self.bars[plain],
                self.dofs,
            )
        if hinges:
            moments = self.hinge_stiffness * (self.hinge_matrix() @ u)
            moving = np.flatnonzero(moments)
            KG = KG + assemble(
                moments[moving, None, None] * dihedral_hessian(self.nodes[self.hinges[moving]]),
                self.hinges[moving],
                self.dofs,
            )
        return (0.5 * (KG + KG.T)).tocsr()


def _kinds_of(edges: np.ndarray, mesh: Mesh) -> np.ndarray:
    """The kind of every edge (N, 2) (sorted vertex pairs) in a mesh's edges, ``"diagonal"`` if
    it is not one of them."""
    known = np.sort(np.asarray(mesh.edges_vertices, np.int64), axis=1)
    width = int(max(known.max(initial=0), edges.max(initial=0))) + 1
    table = known[:, 0] * width + known[:, 1]
    order = np.argsort(table)
    wanted = edges[:, 0] * width + edges[:, 1]
    pos = np.clip(np.searchsorted(table[order], wanted), 0, max(len(table) - 1, 0))
    found = table[order][pos] == wanted if len(table) else np.zeros(len(wanted), bool)
    return np.where(
        found, np.asarray(mesh.edges_kind)[order][pos] if len(table) else "diagonal", "diagonal"
    ).astype("<U8")
