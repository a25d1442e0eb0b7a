"""The mechanism of a structure of rigid panels: constraint Jacobian, singular values, degrees of
freedom.

A panel structure moves as its vertices x (V, 3) do, under these constraints
(a :class:`Framework`), each a length that vanishes on the constraint:

* every edge and both diagonals of every quad keep their length ℓ from the crease pattern:
  ``(|x_i − x_j|² − ℓ²) / 2ℓ ≈ |x_i − x_j| − ℓ``;
* every quad (a, b, c, d) stays planar: ``det[c − a, d − b, b − a] / (ℓ_ac ℓ_bd)``, zero when
  its two diagonal lines meet (polygons of more sides: every pair of their vertices keeps
  its distance, and each vertex past the third stays in the plane of the first three);
* welded seams and bonds between tubes share one vertex: their vertices are merged, so
  the unknowns are the distinct points.

The Jacobian J of these constraints (dimensionless rows: a bar's is the unit vector along
it) has the first-order motions as its null space, the 6 rigid motions of space among
them. Its singular values come from a dense SVD (LAPACK), so the size is bounded
(:data:`MAX_UNKNOWNS`). The nullity counts the singular values at or below
``tol = rtol · σ_max``, with ``rtol = 1e-9`` by default: the states curvefold builds satisfy
the constraints to rounding (relative ~1e-15), which puts the singular values of true
motions below 1e-15 σ_max, while the smallest of the others stays above 2e-4 σ_max up to
the size bound (measured: 5e-3 for a tube of 24 panels, 2.8e-4 for 240); the tolerance
sits between them in log scale. The gap (smallest singular value above the tolerance over
the largest below) and the clearance (how near the tolerance the nearest one lies) show
how clear the count is. Internal degrees of freedom are nullity − 6.

The flat state is special: out of its plane lengths change only at second order, so every
lift of the flat sheets that keeps each panel planar is a first-order motion, and its
nullity is larger (N + 1 extra for a tube of N panels, measured; reported, not hidden). A state
whose residual is not at rounding level (:attr:`Mechanism.consistent`) does not satisfy its own
constraints; its count says little and is reported as such.

The certificate (:func:`certified_mechanism`) analyses a structure at flat, half and full
design angle within :data:`CERTIFY_UNKNOWNS`: its first tubes, or the first panels of a
longer tube, which fold exactly as they do in the whole.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import cast

import numpy as np

from ..geometry._mesh import Mesh, edges_faces
from ..geometry._panels import PanelLattice
from ..geometry._structure import Structure
from ..geometry._topology import lattice_corners
from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InputError
from ..kernel._lie import cross
from ..kernel._threads import on_one_blas_thread

__all__ = [
    "MAX_UNKNOWNS",
    "CERTIFY_UNKNOWNS",
    "RTOL",
    "RESIDUAL_TOL",
    "Framework",
    "Mechanism",
    "CertifiedMechanism",
    "mechanism",
    "analyse",
    "certified_mechanism",
    "follow",
]

#: Largest number of unknowns (3 per distinct vertex) of a dense SVD: about a minute on one
#: core at the bound (49 s measured for a tube of 240 panels, 2892 unknowns); the Jacobian
#: then holds about 120 MB.
MAX_UNKNOWNS = 3000
#: Unknowns of the certificate's analysis (:func:`certified_mechanism`): about a second for
#: its three states (1.4 s measured for a tube of 80 panels, 972 unknowns, one core).
CERTIFY_UNKNOWNS = 1000
#: Default rank tolerance, relative to the largest singular value (see the module notes).
RTOL = 1e-9
#: Largest relative constraint residual of a consistent state: rounding of coordinates
#: written with 17 digits is ~1e-15; states off their constraints by more are reported.
RESIDUAL_TOL = 1e-9


@dataclass(frozen=True, eq=False)
class Framework(FrozenArrays):
    """Bars and planar panels on shared vertices: the constraints of a panel structure.

    Build it with :meth:`from_mesh`, :meth:`from_structure` or :meth:`from_fold`.

    Attributes
    ----------
    points : int
        Number of distinct vertices V (welded vertices are one).
    bars : (B, 2) ndarray of int
        Vertex pairs that keep their distance: edges and the diagonals of the panels.
    lengths : (B,) ndarray
        Their lengths in the crease pattern.
    quads : (Q, 4) ndarray of int
        Vertex quadruples (a, b, c, d) that stay coplanar.
    diagonals : (Q,) ndarray
        ``ℓ_ac ℓ_bd`` of every quadruple in the crease pattern.
    sides : (Q,) ndarray
        ``ℓ_ab`` of every quadruple in the crease pattern (its scale).
    """

    points: int
    bars: np.ndarray
    lengths: np.ndarray
    quads: np.ndarray
    diagonals: np.ndarray
    sides: np.ndarray

    @classmethod
    def from_mesh(
        cls,
        reference: np.ndarray,
        edges_vertices: np.ndarray,
        faces_vertices: np.ndarray,
        weld: np.ndarray,
        *,
        joins: np.ndarray | None = None,
    ) -> Framework:
        """The framework of a polygon mesh whose vertex v is the point ``weld[v]``.

        Parameters
        ----------
        reference : (V, 3) ndarray
            Crease-pattern position of every mesh vertex (sheets may lie apart: lengths are
            taken within each edge's and face's own sheet).
        edges_vertices : (E, 2) ndarray of int
        faces_vertices : (F, k) ndarray of int
            Polygons, -1 padded; a face of m > 3 vertices adds the bars between all its
            vertex pairs that are not edges and m − 3 coplanar quadruples.
        weld : (V,) ndarray of int
            The point of every mesh vertex, 0 … P − 1 (welded vertices share one).
        joins : (J,) ndarray of int, optional, keyword-only
            Edges whose two faces are one panel (FOLD's join edges): a vertex of each face off
            the edge keeps its distance, and the four stay coplanar.
        """
        x = np.asarray(reference, float)
        weld = np.asarray(weld, np.int64)
        faces = np.asarray(faces_vertices)
        pieces, quads = [np.asarray(edges_vertices)], []
        for m in range(4, faces.shape[1] + 1):
            rows = faces[(faces >= 0).sum(axis=1) == m][:, :m]
            i, j = np.triu_indices(m, 1)
            pieces.append(rows[:, np.stack([i, j], axis=1)].reshape(-1, 2))
            quads += [rows[:, [0, 1, 2, q]] for q in range(3, m)]
        pairs = np.concatenate(pieces)
        welded = np.sort(weld[pairs], axis=1)
        # one bar per welded pair (edges come first)
        bars, first = np.unique(welded, axis=0, return_index=True)
        lengths = np.linalg.norm(x[pairs[first, 0]] - x[pairs[first, 1]], axis=1)
        if joins is not None and len(joins):
            quads.append(_join_quads(faces, np.asarray(edges_vertices)[joins]))
            pairs = np.concatenate([pairs, quads[-1][:, [1, 3]]])
            welded = np.sort(weld[pairs], axis=1)
            bars, first = np.unique(welded, axis=0, return_index=True)
            lengths = np.linalg.norm(x[pairs[first, 0]] - x[pairs[first, 1]], axis=1)
        q = np.concatenate(quads) if quads else np.zeros((0, 4), np.int64)
        a, b, c, d = (x[q[:, i]] for i in range(4))
        diagonals = np.linalg.norm(c - a, axis=1) * np.linalg.norm(d - b, axis=1)
        return cls(
            int(weld.max()) + 1, bars, lengths, weld[q], diagonals, np.linalg.norm(b - a, axis=1)
        )

    @classmethod
    def from_structure(cls, structure: Structure) -> tuple[Framework, np.ndarray]:
        """The framework of a structure's mesh, welded where vertices are one lattice point.

        Seams (one vertex in a tube's mesh already) and bonds between tubes (a lattice curve
        shared by two tubes) become shared points; the reference is the flat state.

        Returns
        -------
        Framework
        points : (P,) ndarray of int
            Row of every point in a state's curves flattened to (M·n, 3).
        """
        topology = structure.topology()
        key = topology.vertex_curve * len(structure.lattice.s) + topology.vertex_sample
        points, weld = np.unique(key, return_inverse=True)
        flat = topology.coords(structure.state(0.0).vertices)
        return cls.from_mesh(flat, topology.edges_vertices, topology.faces_vertices, weld), points

    @classmethod
    def from_fold(
        cls,
        crease_pattern: Mesh,
        folded: Sequence[Mesh],
        *,
        tol: float = 1e-9,
        joins: np.ndarray | None = None,
        glued: np.ndarray | None = None,
    ) -> tuple[Framework, np.ndarray]:
        """The framework of a FOLD file's crease pattern, welded where its folded frames agree.

        Vertices that coincide (within ``tol`` times the frame's size) in every folded frame
        are one point: the seams and the bonds between tubes. With ``glued`` (the vertices
        of the edges the file says are glued), only those are welded.

        Returns
        -------
        Framework
        first : (P,) ndarray of int
            A vertex of the file at every point.
        """
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components
        from scipy.spatial import cKDTree

        V = len(crease_pattern.vertices_coords)
        common = None
        for mesh in folded:
            x = mesh.vertices_coords
            size = float(np.ptp(x, axis=0).max()) if V else 0.0
            found = {
                tuple(p)
                for p in cKDTree(x)
                .query_pairs(tol * max(size, 1e-300), output_type="ndarray")
                .tolist()
            }
            common = found if common is None else common & found
        pairs = np.array(sorted(common or ()), np.int64).reshape(-1, 2)
        if glued is not None:
            pairs = pairs[np.isin(pairs, glued).all(axis=1)]
        graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(V, V))
        _, weld = connected_components(graph, directed=False)
        first = np.unique(weld, return_index=True)[1]
        return cls.from_mesh(
            crease_pattern.vertices_coords,
            crease_pattern.edges_vertices,
            crease_pattern.faces_vertices,
            weld,
            joins=joins,
        ), first

    @property
    def unknowns(self) -> int:
        """3 × the number of points."""
        return 3 * self.points

    @property
    def constraints(self) -> int:
        """Rows of the Jacobian: bars and coplanar quadruples."""
        return len(self.bars) + len(self.quads)

    @property
    def shortest(self) -> float:
        """The shortest bar, model units."""
        return float(self.lengths.min()) if len(self.lengths) else 0.0

    @property
    def scales(self) -> np.ndarray:
        """Reference length of every constraint, shape (B + Q,): a bar's length, a quad's side
        ab."""
        return np.concatenate([self.lengths, self.sides])

    def residual(self, x: np.ndarray) -> np.ndarray:
        """Every constraint at positions x (P, 3), in model units, shape (B + Q,).

        A bar's ``(|x_i − x_j|² − ℓ²) / 2ℓ`` (its length change, to first order) and a quad's
        ``det[c − a, d − b, b − a] / (ℓ_ac ℓ_bd)`` (zero when its diagonal lines meet);
        divided by :attr:`scales` they are relative.
        """
        x = np.asarray(x, float).reshape(-1, 3)
        d = x[self.bars[:, 0]] - x[self.bars[:, 1]]
        a, b, c, dd = (x[self.quads[:, i]] for i in range(4))
        volume = np.einsum("ij,ij->i", cross(c - a, dd - b), b - a)
        return np.concatenate(
            [
                (np.einsum("ij,ij->i", d, d) - self.lengths**2) / (2 * self.lengths),
                volume / self.diagonals,
            ]
        )

    def jacobian(self, x: np.ndarray) -> np.ndarray:
        """The Jacobian (B + Q, 3P) of :meth:`residual`: dimensionless rows, a bar's the unit
        vector along it."""
        x = np.asarray(x, float).reshape(-1, 3)
        P, B, Q = len(x), len(self.bars), len(self.quads)
        J = np.zeros((B + Q, P, 3))
        i, j = self.bars[:, 0], self.bars[:, 1]
        row = (x[i] - x[j]) / self.lengths[:, None]
        J[np.arange(B), i] += row
        J[np.arange(B), j] -= row
        a, b, c, d = (x[self.quads[:, k]] for k in range(4))
        u, v, w = c - a, d - b, b - a
        uv, vw, wu = cross(u, v), cross(v, w), cross(w, u)
        rows = B + np.arange(Q)
        for col, grad in zip(self.quads.T, (-(vw + uv), uv - wu, vw, wu)):
            np.add.at(J, (rows, col), grad / self.diagonals[:, None])
        return J.reshape(B + Q, 3 * P)


@dataclass(frozen=True, eq=False)
class Mechanism(FrozenArrays):
    """The first-order mobility of a framework at one state.

    Attributes
    ----------
    label : str
        Which state (``"2α = 90°"``, a FOLD frame's title).
    singular_values : (min(rows, 3V),) ndarray
        Of the Jacobian, descending.
    tolerance : float
        The rank tolerance ``rtol · σ_max``.
    nullity : int
        Dimension of the first-order motions, rigid motions included.
    dof : int
        Internal degrees of freedom, nullity − 6.
    gap : float
        Smallest singular value above the tolerance over the largest at or below it
        (``inf`` when the null ones are exactly zero).
    residual : float
        Largest constraint residual of the state relative to its scale
        (:attr:`Framework.scales`).
    unknowns, constraints : int
        Columns and rows of the Jacobian.
    residual_tol : float
        The largest :attr:`residual` of a consistent state (:data:`RESIDUAL_TOL`, or what
        the coordinates' precision allows).
    note : str
        What to know to read the count (a flat-folded frame, no crease pattern, a tolerance
        raised to the file's precision); empty when nothing.
    """

    label: str
    singular_values: np.ndarray
    tolerance: float
    nullity: int
    dof: int
    gap: float
    residual: float
    unknowns: int
    constraints: int
    residual_tol: float = RESIDUAL_TOL
    note: str = ""

    @property
    def clearance(self) -> float:
        """How near the rank tolerance the nearest singular value lies: ``max min(σ/tol, tol/σ)`` ≤
        1.

        1e-3 means every singular value is at least a thousand times above or below the
        tolerance, so the count does not depend on where in that range the tolerance is.
        """
        ratio = self.singular_values / self.tolerance
        with np.errstate(divide="ignore"):
            return float(np.minimum(ratio, 1.0 / ratio).max())

    @property
    def consistent(self) -> bool:
        """Whether the state satisfies its constraints to rounding (:attr:`residual_tol`)."""
        return self.residual <= self.residual_tol

    def to_dict(self, smallest: int = 12) -> dict:
        """JSON-ready summary: the counts, σ_max and the ``smallest`` singular values
        (ascending)."""
        return {
            "label": self.label,
            "dof": self.dof,
            "nullity": self.nullity,
            "gap": None if math.isinf(self.gap) else self.gap,
            "clearance": self.clearance,
            "tolerance": self.tolerance,
            "sigma_max": float(self.singular_values[0]),
            "smallest_singular_values": self.singular_values[::-1][:smallest].tolist(),
            "residual": self.residual,
            "consistent": self.consistent,
            "unknowns": self.unknowns,
            "constraints": self.constraints,
            "note": self.note,
        }


def _join_quads(faces: np.ndarray, joins: np.ndarray) -> np.ndarray:
    """(p, r, q, t) for every join edge (p, q) with its faces' vertices r and t off it: coplanar,
    r–t a bar."""
    sides = edges_faces(faces, joins)
    two = (sides >= 0).all(axis=1)
    out = []
    for (p, q), (f, g) in zip(joins[two].tolist(), sides[two].tolist()):
        r = next(v for v in faces[f] if v >= 0 and v not in (p, q))
        t = next(v for v in faces[g] if v >= 0 and v not in (p, q))
        out.append((p, r, q, t))
    return np.array(out, np.int64).reshape(-1, 4)


def _check_size(framework: Framework, advice: str = "use fewer panels, tubes or cells") -> None:
    """Refuse a framework beyond :data:`MAX_UNKNOWNS`, with ``advice`` (a curvefold design's
    by default; another tool's file gets its own)."""
    if framework.unknowns > MAX_UNKNOWNS:
        raise InputError(
            "the mechanism analysis takes a dense SVD of the constraint Jacobian and is bounded "
            f"to {MAX_UNKNOWNS} unknowns ({MAX_UNKNOWNS // 3} vertices); this structure "
            f"has {framework.unknowns} ({framework.points} vertices): {advice}"
        )


@on_one_blas_thread  # small dense SVDs: threads only wait (curvefold.kernel._threads)
def mechanism(
    framework: Framework,
    x: np.ndarray,
    *,
    rtol: float = RTOL,
    label: str = "",
    residual_tol: float = RESIDUAL_TOL,
) -> Mechanism:
    """Singular values and degrees of freedom of a framework at positions x (V, 3).

    Raises
    ------
    InputError
        Beyond :data:`MAX_UNKNOWNS`, for a tolerance outside (0, 1), or a state whose
        Jacobian is not finite (a degenerate panel).
    """
    _check_size(framework)
    if not 0 < rtol < 1:
        raise InputError(f"rtol must be in (0, 1), got {rtol!r}")
    x = np.asarray(x, float).reshape(-1, 3)
    with np.errstate(all="ignore"):
        J = framework.jacobian(x)
    if not np.isfinite(J).all():
        raise InputError(
            f"{label or 'the state'}: the constraint Jacobian is not finite (a panel of no size)"
        )
    sigma = np.linalg.svd(J, compute_uv=False)
    tol = rtol * float(sigma[0])
    null = int(np.count_nonzero(sigma <= tol)) + max(0, J.shape[1] - J.shape[0])
    above, below = sigma[sigma > tol], sigma[sigma <= tol]
    gap = (
        math.inf
        if not below.size or below[0] == 0
        else float(above[-1] / below[0])
        if above.size
        else 1.0
    )
    residual = float(np.abs(framework.residual(x) / framework.scales).max())
    return Mechanism(
        label,
        readonly(sigma),
        tol,
        null,
        null - 6,
        gap,
        residual,
        J.shape[1],
        J.shape[0],
        residual_tol,
    )


@lru_cache(maxsize=4)
def _analysed(
    structure: Structure, angles: tuple[float, ...], rtol: float
) -> tuple[Mechanism, ...]:
    framework, points = Framework.from_structure(structure)
    _check_size(framework)
    motion = structure.lattice.fold_points(structure.curves_uv, np.array(angles))  # (A, M, n, 3)
    return tuple(
        mechanism(
            framework,
            m.reshape(-1, 3)[points],
            rtol=rtol,
            label=f"2α = {a:g}°" + (" (flat)" if a == 0 else ""),
        )
        for a, m in zip(angles, motion)
    )


def analyse(
    structure: Structure, fold_angles: Sequence[float] | None = None, *, rtol: float = RTOL
) -> tuple[Mechanism, ...]:
    """The mechanism of a structure at several fold angles (default: flat, half the design angle,
    the design angle).

    Its framework is :meth:`Framework.from_structure`; results are cached for the last
    few structures (they are immutable).

    Raises
    ------
    InputError
        Beyond :data:`MAX_UNKNOWNS`.
    """
    own = structure.lattice.crease.fold_angle
    angles = (0.0, 0.5 * own, own) if fold_angles is None else tuple(float(f) for f in fold_angles)
    return _analysed(structure, angles, float(rtol))


@dataclass(frozen=True, eq=False)
class CertifiedMechanism:
    """The mechanism the certificate reports: of a structure, or of the part of it the bound allows.

    Attributes
    ----------
    part : Structure
        What was analysed: the structure, its first tubes, or the first panels of its first tube.
    scope : str
        Which part, in words ("" for the whole structure).
    states : tuple of Mechanism
        Flat, half the design angle, the design angle.
    """

    part: Structure
    scope: str
    states: tuple[Mechanism, ...]

    def to_dict(self) -> dict:
        """JSON-ready: the scope and every state's :meth:`Mechanism.to_dict`."""
        return {"scope": self.scope, "states": [m.to_dict() for m in self.states]}


def _unknowns(structure: Structure, cells: int) -> int:
    """Unknowns of the analysis of a structure's first ``cells`` cells: 3 per lattice point."""
    return 3 * len(structure.lattice.s) * len(lattice_corners(structure.cells[:cells])[0])


@lru_cache(maxsize=4)
def certified_mechanism(structure: Structure, budget: int = CERTIFY_UNKNOWNS) -> CertifiedMechanism:
    """The mechanism of a panel structure at flat, half and full design angle, within ``budget``
    unknowns.

    The longest run of its first tubes that fits is analysed; if one tube does not fit, its
    first panels (:meth:`PanelLattice.head <curvefold.geometry.PanelLattice.head>`),
    which fold exactly as they do in the tube. Cached: the certificate and the report's
    picture share it.
    """
    K, lattice = len(structure.cells), structure.lattice
    k = next((k for k in range(K, 0, -1) if _unknowns(structure, k) <= budget), 1)
    part, scope = structure, ""
    if k < K:
        part, scope = (
            Structure.from_cells(lattice, structure.cells[:k]),
            f"the first {k} of the {K} tubes",
        )
    if _unknowns(part, 1) > budget:
        n = max(1, budget // 12 - 1)  # 4 lattice polylines of n + 1 vertices, 3 unknowns each
        # a tube too large for the budget is one of panels
        part = Structure.from_cells(cast(PanelLattice, lattice).head(n), structure.cells[:1])
        scope = f"the first {n} of the {len(lattice.s) - 1} panels of tube 1"
    return CertifiedMechanism(part, scope, analyse(part))


def _rigid_motions(x: np.ndarray) -> np.ndarray:
    """Orthonormal basis (6, 3V) of the infinitesimal rigid motions of points x (V, 3)."""
    c = x - x.mean(axis=0)
    basis = [np.tile(e, len(x)) for e in np.eye(3)] + [
        cross(np.broadcast_to(e, c.shape), c).ravel() for e in np.eye(3)
    ]
    q, _ = np.linalg.qr(np.stack(basis, axis=1))
    return q.T


@on_one_blas_thread
def follow(
    framework: Framework,
    start: np.ndarray,
    *,
    steps: int,
    step: float,
    toward: np.ndarray | None = None,
    tol: float = 1e-13,
    rtol: float = RTOL,
) -> np.ndarray:
    """Follow a one-dimensional motion from a state by predictor–corrector continuation.

    Each step predicts along the null vector of the Jacobian (rigid motions removed by six
    gauge rows fixed at the start), then corrects by Gauss–Newton on the constraints with
    the step's pseudo-arclength condition, to a residual below ``tol``.

    Parameters
    ----------
    framework : Framework
    start : (V, 3) ndarray
        A state satisfying the constraints.
    steps : int, keyword-only
    step : float, keyword-only
        Arclength of a step in the coordinates (model units).
    toward : (3V,) ndarray, optional, keyword-only
        Direction the first step should take (the sign of the null vector).

    Returns
    -------
    (steps + 1, V, 3) ndarray
        The states, the start first.

    Raises
    ------
    ConvergenceError
        If the motion is not one-dimensional at a step (a bifurcation or a rigid state),
        or the corrector does not converge.
    """
    from ..kernel._errors import ConvergenceError

    _check_size(framework)
    x0 = np.asarray(start, float).ravel()
    gauge = _rigid_motions(x0.reshape(-1, 3))
    x, previous = x0.copy(), None if toward is None else np.asarray(toward, float).ravel()
    out = [x0.reshape(-1, 3)]
    for k in range(steps):
        A = np.concatenate([framework.jacobian(x), gauge])
        _, sigma, vt = np.linalg.svd(A, full_matrices=True)
        sigma = np.concatenate([sigma, np.zeros(A.shape[1] - len(sigma))])
        if sigma[-2] <= rtol * sigma[0]:
            raise ConvergenceError(
                f"step {k}: the motion is not one-dimensional here (two "
                f"singular values ≤ {rtol:g} σ_max)"
            )
        tangent = vt[-1] if previous is None or vt[-1] @ previous >= 0 else -vt[-1]
        y = x + step * tangent
        for _ in range(20):
            F = np.concatenate(
                [framework.residual(y), gauge @ (y - x0), [tangent @ (y - x) - step]]
            )
            if np.abs(F).max() <= tol:
                break
            y = (
                y
                - np.linalg.lstsq(
                    np.concatenate([framework.jacobian(y), gauge, tangent[None]]), F, rcond=None
                )[0]
            )
        else:
            raise ConvergenceError(
                f"step {k}: the corrector did not converge (residual {np.abs(F).max():.3g})"
            )
        x, previous = y, tangent
        out.append(y.reshape(-1, 3))
    return np.stack(out)
