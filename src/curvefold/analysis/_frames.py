"""What the certificate's measurements read: a crease, or a structure in one folded state.

A :class:`Frame` is one subject of the checks of :mod:`curvefold.analysis._checks`: a single
curved fold, or a structure refolded to one angle (or as built), with the vault whose
parameters the vault checks compare with. What every frame of one structure shares (its
meshes' topology, its flat state, its bars and creases) is computed once, in
:class:`Shared`. Every quantity is measured on the built geometry
(:mod:`curvefold.analysis._measure`), never taken from the formula that built it.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import cast

import numpy as np

from ..geometry._crease import Crease
from ..geometry._kinds import FoldedCrease
from ..geometry._lattice import Lattice
from ..geometry._lattice_pattern import constant_alpha
from ..geometry._mesh import edges_along, edges_faces, vector_areas
from ..geometry._structure import State, Structure
from ..geometry._topology import CORNER_KINDS, CORNERS, STRIPS, Topology, is_tube_numbering
from ..vault._assembly import Vault
from . import _measure as measure

__all__ = ["Frame", "Shared", "ROUNDING", "STRIP_SIDES"]

#: Units in the last place of the largest coordinate that a built sample may carry as rounding:
#: twice the largest noise measured in built rulings (16 ulps, tests/test_properties.py).
ROUNDING = 32.0
_EPS = float(np.finfo(float).eps)
#: The ruling family of every strip of a tube: "L" where it steps in u, "R" where in v.
STRIP_SIDES = np.array(["L" if (CORNERS[b] - CORNERS[a])[0] else "R" for a, b in STRIPS])
#: Which of corners 1–4 are folds (the others seams), broadcasting against (K, 4, m).
_FOLD_CORNERS = np.array([kind == "fold" for kind in CORNER_KINDS])[:, None]


@dataclass(frozen=True, eq=False)
class Shared:
    """What every frame of one structure shares: its meshes' topology and its flat state.

    Attributes
    ----------
    structure : Structure
    """

    structure: Structure

    @cached_property
    def flat(self) -> State:
        """The flat state: the crease pattern."""
        return self.structure.state(0.0)

    @cached_property
    def topology(self) -> Topology:
        """The structure's topology (corners, strips, vertex numbering)."""
        return self.structure.topology()

    @cached_property
    def tube_mesh(self) -> bool:
        """Whether the mesh is :meth:`Topology.tubes`'s triangles of the structure's cells at every
        sample.

        Vertex (4k + c)·n + j is then sample j of corner c of tube k (its curves at the tubes'
        corners, in order); the edges are the curve edges of every strip (the folds and seams), then
        its rulings, then its diagonals (a_j, b_(j+1)); the faces are every strip's triangles (a_j,
        b_(j+1), b_j), then its (a_j, a_(j+1), b_(j+1)). A frame then reads every edge, face, quad
        and crease off the tubes' curves (:attr:`Frame.strip_edges`), the same numbers as it gathers
        otherwise.
        """
        top, cells = self.topology, self.structure.cell_curves
        K, n = len(cells), len(self.structure.lattice.s)
        if not is_tube_numbering(top, cells, n):
            return False
        # curve edges, rulings, diagonals
        kinds = np.split(top.edges_kind, [4 * K * (n - 1), 4 * K * (2 * n - 1)])
        return bool(
            np.isin(kinds[0], ("fold", "seam")).all()
            and (kinds[2] == "diagonal").all()
            and not np.isin(kinds[1], ("fold", "seam", "diagonal")).any()
        )

    @cached_property
    def quads(self) -> np.ndarray:
        """The ruling quads (F, 4), in the vertex numbering of :attr:`Shared.topology`: as
        ``structure.topology("quads")`` numbers them, each the two triangles across its
        diagonal (p, q), the one running p → q → r and the other q → p → s, read as (p, s, q,
        r); a panel structure's faces are its quads."""
        top = self.topology
        if top.faces_vertices.shape[1] == 4:
            return top.faces_vertices
        ids, sides = self._edges_faces
        diagonal = top.edges_kind[ids] == "diagonal"
        diagonals, sides = top.edges_vertices[ids[diagonal]], sides[diagonal]
        if (sides < 0).any():  # a diagonal without its two triangles: the quad mesh itself
            return self.structure.topology("quads").faces_vertices
        triangles = top.faces_vertices[sides]  # (D, 2, 3)
        p, q = diagonals.T
        r, s = (triangles.sum(axis=-1) - (p + q)[:, None]).T  # the third corner of each
        return np.stack([p, s, q, r], axis=1)

    def coords(self, curves: np.ndarray) -> np.ndarray:
        """The mesh vertices (V, 3) of a state's curves (M, n, 3): :meth:`Topology.coords` as one
        take of rows."""
        rows, samples = self._vertex_rows
        if curves.shape[-2] != samples:
            top = self.topology
            rows = top.vertex_curve * curves.shape[-2] + top.vertex_sample
        return np.take(curves.reshape(-1, 3), rows, axis=0)

    @cached_property
    def _vertex_rows(self) -> tuple[np.ndarray, int]:
        """The row of every mesh vertex in a state's curves flattened (V,), and their samples n."""
        top, n = self.topology, len(self.structure.lattice.s)
        return top.vertex_curve * n + top.vertex_sample, n

    @cached_property
    def edge_rows(self) -> tuple[np.ndarray, np.ndarray]:
        """The row of every edge's first and second vertex in a state's curves (M, n, 3)
        flattened (as :meth:`coords` reads them), (E,) each."""
        rows, _ = self._vertex_rows
        ends = self.topology.edges_vertices
        return np.take(rows, ends[:, 0]), np.take(rows, ends[:, 1])

    @cached_property
    def crease_folds(self) -> np.ndarray:
        """Whether every edge of :attr:`creases` is a fold (else a seam), (C,)."""
        return self.crease_kinds == "fold"

    @cached_property
    def face_sides(self) -> tuple[np.ndarray, np.ndarray] | None:
        """For triangles, the edges along the sides p0 → p1 and p0 → p2 of every face (F,) each
        (their :func:`~curvefold.geometry.vector_areas` is the cross product of those edges'
        vectors); None otherwise."""
        if self.topology.faces_vertices.shape[1] != 3 or self._side_edges is None:
            return None
        edge, forward = self._side_edges
        # p0 → p1 along its edge, p2 → p0 against
        if not (forward[:, 0].all() and not forward[:, 2].any()):
            return None
        return np.ascontiguousarray(edge[:, 0]), np.ascontiguousarray(edge[:, 2])

    @cached_property
    def quad_sides(self) -> tuple[np.ndarray, ...] | None:
        """The edges along p0 → p1, p0 → p3 and p0 → p2 of every quad of :attr:`quads` (F,) each,
        or None."""
        return self._edges_from_first_corner(self.quads, (1, 3, 2))

    def _edges_from_first_corner(
        self, faces: np.ndarray, corners: tuple[int, ...]
    ) -> tuple[np.ndarray, ...] | None:
        """The edges from corner 0 of every face to each of its ``corners``, as they run (F,)
        each; None unless every one is an edge run that way."""
        pairs = np.stack(
            [np.repeat(faces[:, :1], len(corners), axis=1), faces[:, corners]], axis=-1
        )
        edge, forward = edges_along(self.topology.edges_vertices, pairs)
        return tuple(np.ascontiguousarray(e) for e in edge.T) if forward.all() else None

    @cached_property
    def flat_coords(self) -> np.ndarray:
        """Vertex coordinates of the crease pattern (the flat state), (V, 3) model units."""
        return self.coords(self.flat.vertices)

    @cached_property
    def flat_lengths(self) -> np.ndarray:
        """Edge lengths of the crease pattern, (E,)
        (:func:`~curvefold.analysis._measure.edge_lengths`' numbers)."""
        return Frame(self.flat.lattice.crease, self, self.flat).edge_lengths

    @property
    def shortest_edge(self) -> float:
        """Length of the crease pattern's shortest edge, model units."""
        return float(self.flat_lengths.min())

    @cached_property
    def width_law(self) -> tuple[np.ndarray, np.ndarray]:
        """Every strip's width at t = 0 and the log-width law ``∓∫₀^s κ_2D cot β ds`` it follows
        (− for a left strip, :func:`~curvefold.analysis._measure.width_integral`), (1, 4, 1)
        and (1, 4, n): of the pattern every frame folds."""
        lattice = cast(Lattice, self.structure.lattice)  # the width law of a smooth lattice
        pattern = lattice.pattern
        law = measure.width_integral(pattern.kappa_2d, pattern.beta, pattern.s)
        left = (STRIP_SIDES == "L")[None, :, None]
        return np.where(left, pattern.width_left[0], pattern.width_right[0]), np.where(
            left, -law, law
        )

    @cached_property
    def speed_factors(self) -> np.ndarray:
        """The Eq. (17) speed factor of every curve of the structure at its samples (M, n): of
        the pattern's regression domain."""
        return self.structure.lattice.domain.factor(self.structure.curves_uv.astype(float))

    @cached_property
    def bars(self) -> np.ndarray:
        """Every edge, then both diagonals of every quad, (E + 2F, 2): what keeps a rigid panel's
        shape."""
        q = self.quads
        return np.concatenate([self.topology.edges_vertices, q[:, [0, 2]], q[:, [1, 3]]])

    @cached_property
    def bar_lengths(self) -> np.ndarray:
        """Lengths of :attr:`bars` in the crease pattern, (E + 2F,)."""
        return measure.edge_lengths(self.flat_coords, self.bars)

    @cached_property
    def creases(self) -> tuple[np.ndarray, np.ndarray]:
        """The fold and seam edges, and the two faces on each, (C,) and (C, 2)."""
        # every strip's curve edges: its second triangles run them, the previous strip's first ones
        # back
        if self.tube_mesh:
            K, n = len(self.structure.cell_curves), len(self.structure.lattice.s)
            strip, j = np.arange(4 * K)[:, None], np.arange(n - 1)
            previous = strip - strip % 4 + (strip - 1) % 4
            sides = np.stack(
                [strip * 2 * (n - 1) + n - 1 + j, previous * 2 * (n - 1) + j], axis=-1
            ).reshape(-1, 2)
            return np.arange(len(sides)), sides
        ids, sides = self._edges_faces
        crease = self.topology.edges_kind[ids] != "diagonal"
        return ids[crease], sides[crease]

    @cached_property
    def crease_kinds(self) -> np.ndarray:
        """The kind of every edge of :attr:`creases`, "fold" or "seam", (C,)."""
        return self.topology.edges_kind[self.creases[0]]

    @cached_property
    def _edges_faces(self) -> tuple[np.ndarray, np.ndarray]:
        """The fold, seam and diagonal edges, and the two faces on each (:func:`edges_faces`),
        (S,) and (S, 2): from :attr:`_side_edges` where it gives every one two faces, else by
        :func:`edges_faces` itself."""
        top = self.topology
        ids = np.flatnonzero(np.isin(top.edges_kind, ("fold", "seam", "diagonal")))
        if self._side_edges is not None:
            edge, forward = self._side_edges
            found = edge >= 0
            # a → b on side 0, b → a on side 1; the last face wins
            faces_of = np.full((len(top.edges_vertices), 2), -1, np.int64)
            faces_of[edge[found], (~forward[found]).astype(np.int64)] = np.nonzero(found)[0]
            # else a side missing, or an edge listed twice (its twin gets none)
            if (faces_of[ids] >= 0).all():
                return ids, faces_of[ids]
        return ids, edges_faces(top.faces_vertices, top.edges_vertices[ids])

    @cached_property
    def _side_edges(self) -> tuple[np.ndarray, np.ndarray] | None:
        """The edge along every side p_i → p_(i+1) of every face and whether it runs that way
        (:func:`edges_along`), (F, k) each; None for padded faces."""
        top = self.topology
        faces = top.faces_vertices
        if (faces < 0).any():
            return None
        return edges_along(
            top.edges_vertices, np.stack([faces, np.roll(faces, -1, axis=1)], axis=-1)
        )


@dataclass(frozen=True, eq=False)
class Frame:
    """What the measurements read: a single crease, or a structure folded to one angle.

    Attributes
    ----------
    crease : Crease or FoldedCrease
        Curve 1 in this state: a smooth :class:`Crease` (what the crease and smooth
        checks read), or the crease of another kind of lattice
        (:class:`~curvefold.geometry.FoldedCrease`, what the rigid checks read).
    shared : Shared or None
        The structure and what its frames share.
    state : State or None
        The structure at this fold angle.
    vault : Vault or None
        The vault whose parameters (a, κ₀ s₀, p_xy) the vault checks compare with.
    """

    crease: Crease | FoldedCrease
    shared: Shared | None = None
    state: State | None = None
    vault: Vault | None = None

    # The parts only some frames have, for the measurements that read them (a check runs only
    # on the frames that have what it reads: a structure's, a vault's).
    @property
    def smooth_crease(self) -> Crease:
        """:attr:`crease`, of a smooth frame (what the crease and smooth checks read)."""
        return cast(Crease, self.crease)  # a frame of a smooth crease

    @property
    def common(self) -> Shared:
        """:attr:`shared`, of a structure's frame."""
        assert self.shared is not None, "a frame of a structure"
        return self.shared

    @property
    def folded(self) -> State:
        """:attr:`state`, of a structure's frame."""
        assert self.state is not None, "a frame of a structure"
        return self.state

    @property
    def compared_vault(self) -> Vault:
        """:attr:`vault`, of a vault's frame."""
        assert self.vault is not None, "a frame of a vault"
        return self.vault

    @classmethod
    def at(cls, shared: Shared, fold_angle: float | None, vault: Vault | None = None) -> Frame:
        """The structure refolded from its pattern to 2α = ``fold_angle`` (degrees), or as built
        (None).

        Examples
        --------
        >>> from curvefold import SpaceCurve, Crease, Lattice
        >>> tube = Structure.tube(
        ...     Lattice.from_crease(
        ...         Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=9)), 0.1, 0.1
        ...     )
        ... )
        >>> shared = Shared(tube)
        >>> (
        ...     Frame.at(shared, 0.0).alpha,
        ...     Frame.at(shared, None).crease.fold_angle,
        ... )  # flat, and as built
        (0.0, 90.0)
        """
        state = shared.flat if fold_angle == 0 else shared.structure.state(fold_angle)
        return cls(state.lattice.crease, shared, state, vault)

    @property
    def structure(self) -> Structure:
        """The structure certified (shared by every frame)."""
        return self.common.structure

    @property
    def samples(self) -> int:
        """Samples along curve 1 at this sampling."""
        return len(self.crease.curve.s)

    @property
    def step(self) -> float:
        """Arc-length step h of curve 1."""
        return float(self.crease.curve.s[1] - self.crease.curve.s[0])

    @property
    def alpha(self) -> float:
        """The frame's half fold angle α, radians."""
        return float(constant_alpha(self.smooth_crease))

    @property
    def inner_t(self) -> np.ndarray:
        """t of the samples 2 … n − 3 where differences are measured, (n − 4,)."""
        return self.crease.curve.s[2:-2] / self.crease.curve.length

    @cached_property
    def ulp(self) -> float:
        """:data:`ROUNDING` units in the last place of the largest coordinate."""
        x = self.crease.curve.points if self.state is None else self.state.vertices
        return ROUNDING * _EPS * float(np.abs(x).max() + self.crease.curve.length)

    @cached_property
    def rulings(self) -> np.ndarray:
        """Ruling vectors ℓ_L r_L, ℓ_R r_R at curve 1 from its built neighbours (1, 0), (0, 1),
        (2, n, 3)."""
        if self.state is None:
            return np.stack(self.smooth_crease.rulings())
        x = self.folded.lattice.points(np.array([[0, 0], [1, 0], [0, 1]], float))
        return x[1:] - x[0]

    @cached_property
    def components(self) -> np.ndarray:
        """The state's curves stored by component, x, y and z each contiguous, (3, M, n)."""
        return np.ascontiguousarray(np.moveaxis(self.folded.vertices, -1, 0))

    @cached_property
    def tubes(self) -> np.ndarray:
        """Built curves at corners 1–4 of every tube, by component, (3, K, 4, n)."""
        return self.components[:, self.structure.cell_curves]

    @cached_property
    def curve_derivatives(self) -> tuple[np.ndarray, np.ndarray]:
        """x' and x'' of every built curve of the state at samples 2 … n − 3 (fourth-order
        differences), by component, (3, M, n − 4) each."""
        x = self.components
        return measure.derivative(x, self.step, axis=-1), measure.second_derivative(
            x, self.step, axis=-1
        )

    @cached_property
    def tube_tangents(self) -> np.ndarray:
        """x' at corners 1–4 of every tube (its curves' :attr:`curve_derivatives`), (3, K, 4, n −
        4)."""
        return np.take(self.curve_derivatives[0], self.structure.cell_curves, axis=1)

    @cached_property
    def tube_frenet(self) -> tuple[np.ndarray, ...]:
        """:func:`~curvefold.analysis._measure.frenet3` at corners 1–4 of every tube: speed, T,
        N, B, κ, ([3,] K, 4, n − 4) (of every curve once, a curve at the corners of several
        tubes)."""
        cells = self.structure.cell_curves
        return tuple(
            np.take(f, cells, axis=f.ndim - 2) for f in measure.frenet3(*self.curve_derivatives)
        )

    @cached_property
    def speeds_along_tangent(self) -> np.ndarray:
        """x'·T₁ of every built curve (its :attr:`curve_derivatives`) with curve 1's unit tangent
        at equal t, (M, n − 4)."""
        return measure.dot3(
            self.curve_derivatives[0], self.tangent_components[:, None, 2:-2], order=(0, 1, 2)
        )

    @cached_property
    def coords(self) -> np.ndarray:
        """The mesh vertices of this state, (V, 3)."""
        return self.common.coords(self.folded.vertices)

    @cached_property
    def edge_vectors(self) -> np.ndarray:
        """``x_b − x_a`` of every mesh edge (a, b) in this state, by component, (3, E)."""
        if self.common.tube_mesh:
            return np.concatenate([e.reshape(3, -1) for e in self.strip_edges], axis=1)
        if self.folded.vertices.shape[-2] != len(self.structure.lattice.s):
            coords, (a, b) = self.coords.T, self.common.topology.edges_vertices.T
        else:
            coords, (a, b) = self.components.reshape(3, -1), self.common.edge_rows
        return np.take(coords, b, axis=1) - np.take(coords, a, axis=1)

    @cached_property
    def edge_lengths(self) -> np.ndarray:
        """Length of every mesh edge in this state (of :attr:`edge_vectors`), (E,)."""
        if self.common.tube_mesh:
            return np.concatenate([length.reshape(-1) for length in self.strip_edge_lengths])
        return measure.norm3(self.edge_vectors)

    @cached_property
    def face_areas(self) -> np.ndarray:
        """:func:`~curvefold.geometry.vector_areas` of the mesh's faces in this state, by
        component, (3, F): for triangles the cross product of the vectors of their sides'
        edges (:attr:`Shared.face_sides`), the same numbers."""
        sides = self.common.face_sides
        with np.errstate(invalid="ignore"):
            if sides is None:
                return vector_areas(self.coords, self.common.topology.faces_vertices).T
            return measure.cross3(*(np.take(self.edge_vectors, side, axis=1) for side in sides))

    @property
    def tangent(self) -> np.ndarray:
        """Curve 1's unit tangent T₁ (its built frame), (n, 3)."""
        return self.crease.curve.frames[:, :, 0]

    @property
    def tangent_components(self) -> np.ndarray:
        """:attr:`tangent` by component, (3, n) (a view)."""
        return self.crease.curve.frames[:, :, 0].T

    @cached_property
    def next_corners(self) -> np.ndarray:
        """The built curve at corner c + 1 of every corner c of every tube, by component, (3, K,
        4, n)."""
        return self.tubes[:, :, [b for _, b in STRIPS]]

    @cached_property
    def strip_vectors(self) -> np.ndarray:
        """From each corner's curve to the next corner's at equal t: strip c of every tube,
        corner c → c + 1, (3, K, 4, n)."""
        return self.next_corners - self.tubes

    @cached_property
    def strip_edges(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """For a :attr:`Shared.tube_mesh`: the vectors of every strip's curve edges a_j →
        a_(j+1), rulings a_i → b_i and diagonals a_j → b_(j+1), by component, (3, K, 4, n −
        1), (3, K, 4, n), (3, K, 4, n − 1)."""
        X = self.tubes
        return (
            X[..., 1:] - X[..., :-1],
            self.strip_vectors,
            self.next_corners[..., 1:] - X[..., :-1],
        )

    @cached_property
    def strip_edge_lengths(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The lengths of :attr:`strip_edges`, (K, 4, n − 1), (K, 4, n), (K, 4, n − 1)."""
        along, ruling, diagonal = (measure.norm3(e) for e in self.strip_edges)
        return along, ruling, diagonal

    @cached_property
    def half_angles(self) -> np.ndarray:
        """α measured at corners 1–4 of every tube from its two strips, (K, 4, n − 4)."""
        inner = self.strip_vectors[..., 2:-2]
        # back along the previous strip (negation is exact)
        before = -inner[:, :, [(c - 1) % 4 for c in range(4)]]
        return measure.half_angle3(before, inner, self.tube_frenet[1], _FOLD_CORNERS)

    @cached_property
    def measured_alpha(self) -> np.ndarray:
        """α at curve 1 from its built rulings, (n − 4,)."""
        x = self.crease.curve.points
        return measure.crease_half_angle(
            x, x + self.rulings[0], x + self.rulings[1], self.step, kind="fold"
        )

    @cached_property
    def strip_widths(self) -> np.ndarray:
        """Distance between the tangent lines of the two creases of every strip, (K, 4, n)."""
        return measure.line_distance3(
            self.strip_vectors, self.tangent_components[:, None, None], order=(0, 1, 2)
        )
