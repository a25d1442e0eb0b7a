"""The bar-and-hinge model: nodes, bars, membrane triangles and hinges, and its sparse matrices.

A model is a value (:class:`BarHingeModel`); its matrices are pure functions of it. The
unknowns are the displacements u (3P,) of its P nodes, node by node (x, y, z). The
compatibility matrix C (B, 3P) gives the bars' elongations δ = C u, the hinge matrix
J (H, 3P) the changes of the hinges' dihedral angles Δθ = J u. The elastic energy is

    U = ½ δᵀ S δ + ½ Δθᵀ diag(k) Δθ,    so    K = Cᵀ S C + Jᵀ diag(k) J,

with S the bars' stiffness: each membrane triangle's 3 × 3 block (:mod:`._elements`) on
its three bars, plus the axial stiffness EA/L of bars of their own on the diagonal. The
reference state carries no stress: a linear analysis about the state as it is built.

Build a model from any sheet of triangles and quads with :meth:`BarHingeModel.from_mesh`
(FOLD arrays with curvefold's edge kinds), or from its parts with the constructor (a
single bar, a single hinge). A quad is two membrane triangles split along its diagonal.
The hinge stiffness of every kind of edge, with ``D = E t³ / 12(1 − ν²)`` and ℓ the edge's
length:

* ``fold``, ``seam``: a crease, ``k = k_c ℓ`` with k_c the crease stiffness per length;
* ``ruling`` (and any other edge between two faces): the sheet bending about it,
  ``k = D ℓ / s`` with s the mean width of its two faces across it (a quad's area over ℓ,
  a triangle's height): exact for the cylindrical bending of a strip about its rulings,
  whose hinge angle is the curvature times the rulings' spacing;
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

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from ..geometry.mesh import Mesh
from ..kernel.arrays import FrozenArrays, readonly
from ..kernel.errors import InputError
from ._elements import bar_rows, dihedral_gradient, dihedral_hessian, plane_stress, triangle_areas, triangle_strain
from ._materials import Material, check_thickness

__all__ = ["BarHingeModel", "HINGE_KINDS", "CREASES"]

#: Edge kinds that carry a hinge, and how its stiffness is found (module notes).
HINGE_KINDS = ("fold", "seam", "ruling", "diagonal")
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
    membranes : (T, 3) ndarray of int
        Membrane triangles (may be empty).
    membrane_bars : (T, 3) ndarray of int
        The bar of edge m (corner m to corner m + 1) of every triangle.
    membrane_strain : (T, 3, 3) ndarray
        Voigt strain in the triangle's frame from its bars' elongations, 1/m.
    membrane_area : (T,) ndarray
        Triangle areas, m².
    elasticity : (3, 3) ndarray
        Plane-stress matrix D of the membranes, Pa.
    thickness : float
        Sheet thickness t of the membranes, m (0 without membranes).
    hinge_kind : (H,) ndarray of str
        ``"fold"``, ``"seam"``, ``"ruling"``, ``"diagonal"`` (or ``"hinge"`` for a hinge given
        as it is).
    hinge_length : (H,) ndarray
        Length of every hinge's edge, m.
    hinge_faces : (H, 2) ndarray of int
        The membrane triangles of faces A and B of every hinge (-1 for a hinge given as it is).
    """

    nodes: np.ndarray
    bars: np.ndarray
    bar_stiffness: np.ndarray
    hinges: np.ndarray
    hinge_stiffness: np.ndarray
    masses: np.ndarray
    membranes: np.ndarray = None  # type: ignore[assignment]
    membrane_bars: np.ndarray = None  # type: ignore[assignment]
    membrane_strain: np.ndarray = None  # type: ignore[assignment]
    membrane_area: np.ndarray = None  # type: ignore[assignment]
    elasticity: np.ndarray = None  # type: ignore[assignment]
    thickness: float = 0.0
    hinge_kind: np.ndarray = None  # type: ignore[assignment]
    hinge_length: np.ndarray = None  # type: ignore[assignment]
    hinge_faces: np.ndarray = None  # type: ignore[assignment]

    def __post_init__(self) -> None:
        nodes = np.asarray(self.nodes, float)
        if nodes.ndim != 2 or nodes.shape[1] != 3 or not np.isfinite(nodes).all():
            raise InputError(f"nodes must be finite positions (P, 3), got shape {nodes.shape}")
        defaults = {
            "membranes": np.zeros((0, 3), np.int64), "membrane_bars": np.zeros((0, 3), np.int64),
            "membrane_strain": np.zeros((0, 3, 3)), "membrane_area": np.zeros(0), "elasticity": np.zeros((3, 3)),
        }
        for name, value in defaults.items():
            if getattr(self, name) is None:
                object.__setattr__(self, name, value)
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
        for name, shape in (("bar_stiffness", (B,)), ("hinge_stiffness", (H,)), ("masses", (P,)), ("hinge_kind", (H,))):
            if np.shape(getattr(self, name)) != shape:
                raise InputError(f"{name} must have shape {shape}, got {np.shape(getattr(self, name))}")
        for name in ("bars", "hinges", "membranes"):
            index = np.asarray(getattr(self, name))
            if index.size and (index.min() < 0 or index.max() >= P):
                raise InputError(f"{name} must index the {P} nodes, got indices in [{index.min()}, {index.max()}]")
        for name in ("bar_stiffness", "hinge_stiffness", "masses"):
            values = getattr(self, name)
            if not (np.isfinite(values).all() and (values >= 0).all()):
                raise InputError(f"{name} must be finite and ≥ 0, got a minimum of {values.min() if values.size else 0:g}")
        if self.hinge_length is None:
            x = nodes[self.hinges[:, :2]]
            object.__setattr__(self, "hinge_length", np.linalg.norm(x[:, 1] - x[:, 0], axis=-1))
        super().__post_init__()

    # -- construction from a sheet -------------------------------------------------------------
    @classmethod
    def from_mesh(cls, mesh: Mesh, material: Material, thickness: float, *, crease_stiffness: float,
                  weld: np.ndarray | None = None) -> BarHingeModel:
        """The model of a sheet mesh of triangles and quads: membranes, and hinges on its edges by kind.

        A quad is split along its diagonal from its first corner into two membrane
        triangles, with a ``"diagonal"`` hinge between them (its twist). An edge between two
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
        """
        t = check_thickness(thickness)
        x = np.asarray(mesh.vertices_coords, float)
        faces = np.asarray(mesh.faces_vertices, np.int64)
        sizes = (faces >= 0).sum(axis=1)
        if faces.shape[1] > 4 and (sizes > 4).any():
            raise InputError(f"the model takes faces of three or four vertices; face {int(np.argmax(sizes > 4))} has {sizes.max()}")
        V = len(x)
        weld = np.arange(V) if weld is None else np.asarray(weld, np.int64)
        if weld.shape != (V,) or weld.min(initial=0) < 0:
            raise InputError(f"weld must give a node ≥ 0 for each of the {V} vertices, got shape {weld.shape}")
        P = int(weld.max()) + 1
        nodes = np.zeros((P, 3))
        nodes[weld] = x
        size = float(np.ptp(x, axis=0).max()) if V else 0.0
        apart = np.linalg.norm(nodes[weld] - x, axis=1)
        if apart.size and apart.max() > 1e-9 * size:
            v = int(np.argmax(apart))
            raise InputError(f"weld joins vertices that are {apart[v]:.3g} m apart (vertex {v}); welded vertices must coincide")

        # membranes: triangles, and quads split along the diagonal from their first corner
        quads = faces[sizes == 4][:, :4] if faces.shape[1] >= 4 else np.zeros((0, 4), np.int64)
        triangles = np.concatenate([faces[sizes == 3][:, :3], quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
        areas = triangle_areas(x[triangles])
        if not (areas > 1e-14 * size**2).all():
            raise InputError(f"a triangle of the mesh is degenerate (area {areas.min():.3g} m²)")
        T3, Q = int((sizes == 3).sum()), len(quads)
        face_tri = np.full((len(faces), 2), -1)  # the membrane triangles of every face
        face_tri[sizes == 3, 0] = np.arange(T3)
        face_tri[sizes == 4] = np.stack([T3 + np.arange(Q), T3 + Q + np.arange(Q)], axis=1)
        face_area = np.zeros(len(faces))
        face_area[sizes == 3] = areas[:T3]
        face_area[sizes == 4] = areas[T3:T3 + Q] + areas[T3 + Q:]

        # sides of the faces: side m of a face runs from its corner m to m + 1
        m = np.arange(faces.shape[1])
        corner = np.where(m[None] < sizes[:, None], faces, -1)
        nxt = np.where(m[None] + 1 < sizes[:, None], np.roll(faces, -1, axis=1), faces[:, :1])
        prev = np.where(m[None] > 0, np.roll(faces, 1, axis=1), faces[np.arange(len(faces)), sizes - 1][:, None])
        after = np.take_along_axis(faces, (m[None] + 2) % sizes[:, None], axis=1)
        keep = corner >= 0
        side_face = np.broadcast_to(np.arange(len(faces))[:, None], faces.shape)[keep]
        p, q = corner[keep], nxt[keep]
        near_p, near_q = prev[keep], np.where(sizes[side_face] == 3, prev[keep], after[keep])  # corners next to p and to q
        side_tri = np.where(sizes[side_face] == 3, face_tri[side_face, 0],
                            face_tri[side_face, np.where(m[None] < 2, 0, 1).repeat(len(faces), 0)[keep]])
        key = np.sort(np.stack([p, q], axis=1), axis=1)
        order = np.lexsort((key[:, 1], key[:, 0]))
        sk = key[order]
        start = np.flatnonzero(np.r_[True, (sk[1:] != sk[:-1]).any(axis=1)]) if len(sk) else np.zeros(0, np.int64)
        counts = np.diff(np.r_[start, len(sk)])
        if counts.max(initial=0) > 2:
            g = int(np.argmax(counts))
            raise InputError(f"edge {sk[start[g]].tolist()} borders {counts[g]} faces; a sheet's edge borders one or two "
                             "(join sheets by welding their vertices)")
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
        ends = np.concatenate([np.stack([a, b, near_p[first], near_a2], 1), np.stack([a, b, near_q[first], near_b2], 1)[quad_pair]])
        length = np.linalg.norm(x[b] - x[a], axis=1)
        f1, f2 = side_face[first], side_face[second]
        pair_area = face_area[f1] + face_area[f2]
        # the faces' widths across the edge (a quad's area over the edge, a triangle's height)
        spacing = 0.5 * ((face_area * np.where(sizes == 3, 2.0, 1.0))[f1] + (face_area * np.where(sizes == 3, 2.0, 1.0))[f2]) / length
        D, nu = material.bending_stiffness(t), material.poisson
        k_edge = np.select([np.isin(kinds, CREASES), kinds == "diagonal"],
                           [crease_stiffness * length, 2 * D * (1 - nu) * pair_area / length**2], D * length / spacing)
        share = np.where(quad_pair, 0.5, 1.0)
        edge_faces = np.stack([side_tri[first], side_tri[second]], axis=1)
        # the quads' diagonal hinges: twist
        d = np.linalg.norm(x[quads[:, 2]] - x[quads[:, 0]], axis=1)
        quad_area = face_area[sizes == 4]
        corners = np.concatenate([ends, quads[:, [0, 2, 1, 3]]])
        bars, inverse = np.unique(np.sort(weld[_sides(triangles)], axis=1), axis=0, return_inverse=True)
        return cls(
            nodes=nodes,
            bars=bars,
            bar_stiffness=np.zeros(len(bars)),
            hinges=weld[corners],
            hinge_stiffness=np.concatenate([k_edge * share, (k_edge * share)[quad_pair], 2 * D * (1 - nu) * quad_area / d**2]),
            masses=np.bincount(weld[triangles].ravel(), np.repeat(material.density * t * areas / 3, 3), minlength=P),
            membranes=weld[triangles],
            membrane_bars=inverse.reshape(-1, 3),
            membrane_strain=triangle_strain(x[triangles])[0],
            membrane_area=areas,
            elasticity=plane_stress(material.youngs_modulus, material.poisson),
            thickness=t,
            hinge_kind=np.concatenate([kinds, kinds[quad_pair], np.full(Q, "diagonal")]).astype("<U8"),
            hinge_length=np.concatenate([length * share, (length * share)[quad_pair], d]),
            hinge_faces=np.concatenate([edge_faces, edge_faces[quad_pair], np.stack([T3 + np.arange(Q), T3 + Q + np.arange(Q)], 1)]),
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
    def membrane_stiffness(self) -> np.ndarray:
        """t A Gᵀ D G of every membrane triangle, on its bars' elongations, shape (T, 3, 3), N/m."""
        G = self.membrane_strain
        return readonly(self.thickness * self.membrane_area[:, None, None] * np.einsum("tki,kl,tlj->tij", G, self.elasticity, G))

    @cached_property
    def _bar_rows(self) -> np.ndarray:
        return readonly(bar_rows(self.nodes[self.bars]))

    @cached_property
    def _hinge_rows(self) -> np.ndarray:
        return readonly(dihedral_gradient(self.nodes[self.hinges]))

    def compatibility(self) -> sp.csr_matrix:
        """C, the bars' elongations per nodal displacement, shape (B, 3P), dimensionless."""
        return _rows_matrix(self._bar_rows, self.bars, self.dofs)

    def hinge_matrix(self) -> sp.csr_matrix:
        """J, the hinges' rotations per nodal displacement, shape (H, 3P), rad/m."""
        return _rows_matrix(self._hinge_rows, self.hinges, self.dofs)

    def bar_stiffness_matrix(self) -> sp.csr_matrix:
        """S, the bars' stiffness on their elongations (membrane blocks and EA/L), shape (B, B), N/m."""
        B = len(self.bars)
        mb = self.membrane_bars
        rows = np.concatenate([np.repeat(mb, 3, axis=1).ravel(), np.arange(B)])
        cols = np.concatenate([np.tile(mb, (1, 3)).ravel(), np.arange(B)])
        vals = np.concatenate([self.membrane_stiffness.reshape(-1), self.bar_stiffness])
        return sp.csr_matrix((vals, (rows, cols)), shape=(B, B))

    @cached_property
    def stiffness(self) -> sp.csr_matrix:
        """K = Cᵀ S C + Jᵀ diag(k) J, shape (3P, 3P), N/m (symmetric, positive semi-definite)."""
        C, J = self.compatibility(), self.hinge_matrix()
        K = (C.T @ self.bar_stiffness_matrix() @ C + J.T @ sp.diags(self.hinge_stiffness) @ J).tocsr()
        K = 0.5 * (K + K.T)
        K.sort_indices()
        return K

    @cached_property
    def mass(self) -> sp.dia_matrix:
        """The lumped mass matrix, diagonal, shape (3P, 3P), kg."""
        return sp.diags(np.repeat(self.masses, 3))

    def bar_forces(self, u: np.ndarray) -> np.ndarray:
        """Axial force of every bar for displacements u (3P,), N (tension positive), shape (B,)."""
        return self.bar_stiffness_matrix() @ (self.compatibility() @ u)

    def geometric_stiffness(self, bar_forces: np.ndarray, hinge_moments: np.ndarray) -> sp.csr_matrix:
        """K_G: the second-order stiffness of bar forces (B,) N and hinge moments (H,) N·m, shape (3P, 3P).

        ``Σ N ∂²ℓ/∂x² + Σ M ∂²θ/∂x²``: a bar's ``(N/ℓ)(I − ê êᵀ)`` on its relative
        displacement, a hinge's moment times the Hessian of its angle.
        """
        x = self.nodes[self.bars]
        d = x[:, 1] - x[:, 0]
        ell = np.linalg.norm(d, axis=1)
        e = d / ell[:, None]
        block = (np.asarray(bar_forces) / ell)[:, None, None] * (np.eye(3) - e[:, :, None] * e[:, None, :])
        bar_k = np.einsum("ab,nij->naibj", np.array([[1.0, -1.0], [-1.0, 1.0]]), block).reshape(-1, 6, 6)
        moving = np.flatnonzero(np.asarray(hinge_moments) != 0)
        hinge_k = np.asarray(hinge_moments)[moving, None, None] * dihedral_hessian(self.nodes[self.hinges[moving]])
        KG = _assemble(bar_k, self.bars, self.dofs) + _assemble(hinge_k, self.hinges[moving], self.dofs)
        return (0.5 * (KG + KG.T)).tocsr()


def _sides(triangles: np.ndarray) -> np.ndarray:
    """The sides of triangles (T, 3), side m from corner m to m + 1, shape (3T, 2)."""
    return np.stack([triangles, np.roll(triangles, -1, axis=1)], axis=-1).reshape(-1, 2)


def _kinds_of(edges: np.ndarray, mesh: Mesh) -> np.ndarray:
    """The kind of every edge (N, 2) (sorted vertex pairs) in a mesh's edges, ``"diagonal"`` if it is not one of them."""
    known = np.sort(np.asarray(mesh.edges_vertices, np.int64), axis=1)
    width = int(max(known.max(initial=0), edges.max(initial=0))) + 1
    table = known[:, 0] * width + known[:, 1]
    order = np.argsort(table)
    wanted = edges[:, 0] * width + edges[:, 1]
    pos = np.clip(np.searchsorted(table[order], wanted), 0, max(len(table) - 1, 0))
    found = table[order][pos] == wanted if len(table) else np.zeros(len(wanted), bool)
    return np.where(found, np.asarray(mesh.edges_kind)[order][pos] if len(table) else "diagonal", "diagonal").astype("<U8")


def _dof_index(elements: np.ndarray) -> np.ndarray:
    """The DOFs of elements' nodes (N, m), node by node, shape (N, 3m)."""
    return (3 * elements[:, :, None] + np.arange(3)).reshape(len(elements), 3 * elements.shape[1])


def _rows_matrix(rows: np.ndarray, elements: np.ndarray, dofs: int) -> sp.csr_matrix:
    """A sparse matrix with one row per element from its rows (N, m, 3) on its nodes (N, m)."""
    N = len(elements)
    index = _dof_index(elements)
    return sp.csr_matrix((rows.reshape(N, index.shape[1]).ravel(), (np.repeat(np.arange(N), index.shape[1]), index.ravel())), shape=(N, dofs))


def _assemble(blocks: np.ndarray, elements: np.ndarray, dofs: int) -> sp.csr_matrix:
    """Σ of element matrices (N, 3m, 3m) on their nodes (N, m), shape (dofs, dofs)."""
    index = _dof_index(elements)
    m = index.shape[1]
    rows = np.repeat(index, m, axis=1).ravel()
    cols = np.tile(index, (1, m)).ravel()
    return sp.csr_matrix((blocks.reshape(-1), (rows, cols)), shape=(dofs, dofs))
