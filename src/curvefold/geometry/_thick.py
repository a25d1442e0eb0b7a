"""Thick rigid panels by the offset-panel technique: solids that fold exactly as the panels do.

The offset-panel technique (Edmondson et al. 2014; Lang et al. 2018, §3): every hinge stays on
its crease of the zero-thickness structure, and each panel becomes a solid of thickness t on
one side of it, so that the thick structure's motion is the zero-thickness one, exactly. Here
every panel of a rigid-panel structure (``panels = N``) is offset to the outside of its tube
(the faces' vertex order says where that is: counter-clockwise seen from outside), and the
edges on a hinge are bevelled (:mod:`curvefold.geometry._thick_solids`):

* around a hinge line, the panels that meet on it are rays in the plane across it; each
  solid turns from its ray toward its solid side into the gap g up to the next ray. If the
  panel there has its solid in the same gap, the two share it and each is cut at
  ``b = π/2 − g/2`` (their side faces meet when the gap closes to g); if not, ``b = π/2 − g``;
  no cut is needed where g ≥ π (a convex hinge, a square cut);
* the bevels are cut for the fold angles ``reach`` (default: flat to the design angle): the
  smallest gap over those states sets them;
* a bevel sets the top face back by ``t tan b``, which may not pass half the panel's inradius
  r: ``b ≤ atan(r / 2t)``. Where a gap closes further (tubes of a block, whose walls fold
  onto each other as the block flattens), the fold stops short of flat. *Tapered panels*
  (Lang et al. 2018, §3) trade the panels' bulk for their range: with ``setback = s`` the
  top face may be set back by s r (s < 1), ``b ≤ atan(s r / t)``, every top face kept a
  convex polygon with all its edges (checked).

How far the thick structure folds is then measured, not assumed: :meth:`ThickPanels.motion_range`
refolds it from the design angle toward flat and beyond, testing every pair of solids whose
boxes overlap for interpenetration exactly (separating axes), and finds the first contact by
bisection.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InputError
from ..kernel._lie import cross
from ..kernel._validate import Spec, check_integer
from ._contact import _overlapping_boxes
from ._structure import Structure
from ._thick_ids import assembly_order, panel_ids
from ._thick_solids import halfspaces, inradius, panel_axes, penetration, prism
from ._topology import Topology, unique_pairs

__all__ = ["THICKNESS", "PENETRATION_TOL", "ThickPanels", "ThickRange", "thickness_limit"]

#: The ``thickness`` of thick panels, in the structure's model units.
THICKNESS = Spec(
    "thickness",
    "real",
    None,
    "(0, inf)",
    "model units",
    help="panel thickness t: rigid panels become solids by the offset-panel technique",
    label="panel thickness t",
)
#: Two solids interpenetrate when their penetration depth exceeds this fraction of the
#: thickness; neighbours on a hinge touch at depth 0 to rounding (~1e-16 of the size).
PENETRATION_TOL = 1e-9
#: Pairs of solids tested at once (memory: about 1 kB each).
_CHUNK = 4096


@dataclass(frozen=True)
class ThickRange:
    """How far thick panels fold from their design angle (:meth:`ThickPanels.motion_range`).

    Attributes
    ----------
    design : float
        The design fold angle 2α, degrees.
    low, high : float
        The range, degrees: the last states clear of contact toward flat (0.0 if it folds
        flat) and beyond the design angle (``max_angle`` if no contact before it); the first
        contact lies within ``tol`` past each.
    low_pair, high_pair : (int, int) or None
        The panels (faces of the structure's topology) that touch there.

    Examples
    --------
    >>> r = ThickRange(90.0, 12.1, 90.0, (22, 62), (26, 27))  # a block that stops short of flat
    >>> r.low, r.low_pair
    (12.1, (22, 62))
    """

    design: float
    low: float
    high: float
    low_pair: tuple[int, int] | None
    high_pair: tuple[int, int] | None


@dataclass(frozen=True, eq=False)
class ThickPanels(FrozenArrays):
    """A rigid-panel structure with thick panels (the offset-panel technique).

    Build it with :meth:`offset`. Panel f is face f of ``structure.topology()``; its solid,
    bevels and hinge axes are held in the panel's own frame
    (:func:`~curvefold.geometry._thick_solids.panel_axes`), which every state of the
    zero-thickness structure places.

    Attributes
    ----------
    structure : Structure
        Of rigid panels.
    thickness : float
        t, model units.
    side : (F,) ndarray
        ±1: the solid side relative to the face's normal (+1: outside the tube).
    bevels : (F, k) ndarray
        Bevel of edge e (corner e to e + 1) of every panel, radians.
    local : (F, 2k, 3) ndarray
        The solids' vertices in their panels' frames (corners, then the top face).
    hinges : (F, k, 2, 3) ndarray
        Ends of the hinge axis on every edge, in the panel's frame: its crease.
    reach : (float, float)
        The fold angles 2α (degrees) the bevels are cut for.
    setback : float
        The largest setback of a top face, as a fraction of its panel's inradius: 0.5 for
        offset panels, more for tapered ones.

    Examples
    --------
    >>> from curvefold.geometry._lattice import _example_lattice
    >>> from curvefold.geometry import PanelLattice
    >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
    >>> thick = ThickPanels.offset(tube, 0.01)
    >>> thick.local.shape, round(float(np.degrees(thick.bevels.max())), 3)
    ((16, 8, 3), 5.045)
    """

    structure: Structure
    thickness: float
    side: np.ndarray
    bevels: np.ndarray
    local: np.ndarray
    hinges: np.ndarray
    reach: tuple[float, float]
    setback: float = 0.5

    @property
    def technique(self) -> str:
        """The technique in words: offset panels, or tapered ones (:attr:`setback` > 0.5).

        Examples
        --------
        >>> from curvefold.geometry._lattice import _example_lattice
        >>> from curvefold.geometry import PanelLattice
        >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
        >>> ThickPanels.offset(tube, 0.01, setback=0.75).technique
        'tapered panels (top faces set back up to 0.75 of the inradius), solids outside the tubes'
        """
        where = "outside" if self.side[0] > 0 else "inside"
        kind = (
            "offset panels"
            if self.setback <= 0.5
            else f"tapered panels (top faces set back up to {self.setback:g} of the inradius)"
        )
        return f"{kind}, solids {where} the tubes"

    @classmethod
    def offset(
        cls,
        structure: Structure,
        thickness: float,
        *,
        reach: tuple[float, float] | None = None,
        samples: int = 19,
        side: str = "outside",
        setback: float = 0.5,
    ) -> ThickPanels:
        """Thick panels of thickness t offset to the outside of their tubes (or the inside),
        bevelled for ``reach``.

        Parameters
        ----------
        structure : Structure
            Of rigid panels (``lattice.rigid``).
        thickness : float
            t > 0, below the smallest panel's inradius.
        reach : (float, float), keyword-only
            Fold angles 2α in degrees the bevels are cut for; default flat to the design.
        samples : int, keyword-only
            States across ``reach`` whose smallest gaps set the bevels.
        side : {"outside", "inside"}, keyword-only
            Where the solids lie: outside a tube its seams and creases are convex, and it
            folds flat; inside, its seams close on the solids as it flattens.
        setback : float, keyword-only
            The largest setback of a top face by its bevels, as a fraction of the panel's
            inradius r, in (0, 1): 0.5 offset panels, more tapered ones (module notes).

        Raises
        ------
        InputError
            For a structure of smooth sheets, a thickness out of range, or one whose bevels
            cannot reach the design angle.

        Examples
        --------
        >>> from curvefold.geometry._lattice import _example_lattice
        >>> from curvefold.geometry import PanelLattice
        >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
        >>> ThickPanels.offset(tube, 0.5)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: thickness must be in (0, 0.0498) model units (the
        smallest panel's inradius, panel 4 of tube 1: use a thinner sheet or fewer panels), got 0.5
        """
        if not structure.lattice.rigid:
            raise InputError(
                "thickness: thick panels need a structure of rigid panels (panels ≥ 1); "
                "this one is of smooth sheets"
            )
        t = THICKNESS.check(thickness)
        s = SETBACK.check(setback)
        design = float(structure.lattice.crease.fold_angle)
        lo, hi = (0.0, design) if reach is None else _check_reach(reach, design)
        samples = check_integer(samples, "samples", "[2, 10000]")
        topology = structure.topology()
        faces = topology.faces_vertices
        x = topology.coords(structure.state().vertices)
        if side not in ("outside", "inside"):
            raise InputError(f"side must be 'outside' or 'inside', got {side!r}")
        sides = np.full(len(faces), 1.0 if side == "outside" else -1.0)
        origin, axes = panel_axes(x[faces], sides)
        xy = np.einsum("fkd,fjd->fkj", x[faces] - origin[:, None], axes)[..., :2]
        r = inradius(xy)
        worst = int(np.argmin(r))
        Spec(
            "thickness",
            "real",
            range=f"(0, {float(r[worst]):.3g})",
            unit="model units",
            why=f"the smallest panel's inradius, {_panel(topology, worst)}: use a thinner "
            "sheet or fewer panels",
        ).check(t)
        need, at_design = _bevels_needed(structure, sides, np.linspace(lo, hi, samples), design)
        allowed = np.arctan(s * r / t)[:, None]
        short = at_design - allowed
        if short.max() > 0:
            f, e = np.unravel_index(int(np.argmax(short)), short.shape)
            limit = float(s * r[f] / np.tan(at_design[f, e]))
            raise InputError(
                f"thickness must be below {limit:.3g} model units to reach the design angle "
                f"2α = {design:g}° ({_panel(topology, int(f))} needs a bevel of "
                f"{np.degrees(at_design[f, e]):.3g}°, which would set its top face back by more "
                f"than {s:g} of its inradius {float(r[f]):.3g}), got {t:g}: use a thinner sheet or "
                "fewer panels"
            )
        bevels = np.minimum(need, allowed)
        local = np.concatenate([xy, np.zeros(xy.shape[:-1] + (1,))], -1)
        hinges = np.stack([local, np.roll(local, -1, axis=1)], axis=2)
        solids = prism(xy, t, bevels)
        _check_tops(solids, topology, s)
        return cls(structure, t, sides, bevels, solids, hinges, (lo, hi), s)

    # -- states ------------------------------------------------------------------------------
    @cached_property
    def _faces(self) -> np.ndarray:
        return self.structure.topology().faces_vertices

    def corners(self, fold_angles: Sequence[float] | np.ndarray) -> np.ndarray:
        """The zero-thickness panels' corners at fold angles 2α (A,) in degrees, (A, F, k, 3).

        Examples
        --------
        >>> from curvefold.geometry._lattice import _example_lattice
        >>> from curvefold.geometry import PanelLattice
        >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
        >>> ThickPanels.offset(tube, 0.01).corners([0, 90]).shape
        (2, 16, 4, 3)
        """
        s = self.structure
        motion = s.lattice.fold_points(s.curves_uv, np.atleast_1d(fold_angles))
        return s.topology().coords(motion)[:, self._faces]

    def placements(
        self, fold_angles: Sequence[float] | np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """Every panel's frame at fold angles (A,): origins (A, F, 3), axes (A, F, 3, 3).

        Examples
        --------
        >>> from curvefold.geometry._lattice import _example_lattice
        >>> from curvefold.geometry import PanelLattice
        >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
        >>> origin, axes = ThickPanels.offset(tube, 0.01).placements([45])
        >>> origin.shape, axes.shape
        ((1, 16, 3), (1, 16, 3, 3))
        """
        return panel_axes(self.corners(fold_angles), self.side)

    def solids(self, fold_angles: Sequence[float] | np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Vertices (A, F, 2k, 3) and face normals (A, F, k + 2, 3) of the solids at fold angles
        (A,) in degrees.

        Examples
        --------
        >>> from curvefold.geometry._lattice import _example_lattice
        >>> from curvefold.geometry import PanelLattice
        >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
        >>> vertices, normals = ThickPanels.offset(tube, 0.01).solids([90])
        >>> vertices.shape, normals.shape
        ((1, 16, 8, 3), (1, 16, 6, 3))
        """
        origin, axes = self.placements(fold_angles)
        vertices = origin[:, :, None] + np.einsum("fvj,afjd->afvd", self.local, axes)
        normals = np.einsum("fnj,afjd->afnd", self._halfspaces[..., :3], axes)
        return vertices, normals

    @cached_property
    def _halfspaces(self) -> np.ndarray:
        k = self.local.shape[1] // 2
        return halfspaces(self.local[:, :k, :2], self.thickness, self.bevels)

    def triangles(self, fold_angle: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """The solids as one closed triangle mesh at a fold angle (default the design angle):
        vertices (F·2k, 3) and triangles (F·(4k − 4), 3), counter-clockwise seen from outside.

        Each solid is closed on its own (every edge in two of its triangles, once each way):
        a watertight STL (:func:`curvefold.io.write_thick_stl`).

        Examples
        --------
        >>> from curvefold.geometry._lattice import _example_lattice
        >>> from curvefold.geometry import PanelLattice
        >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
        >>> x, tri = ThickPanels.offset(tube, 0.01).triangles()
        >>> x.shape, tri.shape
        ((128, 3), (192, 3))
        """
        angle = self.structure.lattice.crease.fold_angle if fold_angle is None else fold_angle
        vertices = self.solids(np.array([float(angle)]))[0][0]  # (F, 2k, 3)
        F, m = vertices.shape[:2]
        k = m // 2
        i = np.arange(k)
        j = (i + 1) % k
        one = np.concatenate(
            [
                np.stack([np.zeros(k - 2, int), i[2:], i[1:-1]], 1),  # bottom, facing away
                np.stack([np.full(k - 2, k), k + i[1:-1], k + i[2:]], 1),  # top
                np.stack([i, j, k + j], 1),  # sides
                np.stack([i, k + j, k + i], 1),
            ]
        )
        xy = self.local[:, :k, :2]
        area = (
            xy[..., 0] * np.roll(xy[..., 1], -1, 1) - xy[..., 1] * np.roll(xy[..., 0], -1, 1)
        ).sum(1)
        per = np.where((area > 0)[:, None, None], one, one[:, ::-1])  # clockwise outlines flip
        return vertices.reshape(-1, 3), (per + m * np.arange(F)[:, None, None]).reshape(-1, 3)

    @cached_property
    def hinged(self) -> np.ndarray:
        """Whether edge e of panel f is on a hinge (shared with another panel), (F, k) bool.

        Examples
        --------
        >>> from curvefold.geometry._lattice import _example_lattice
        >>> from curvefold.geometry import PanelLattice
        >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
        >>> ThickPanels.offset(tube, 0.01).hinged[0].tolist()  # the tube's start is free
        [True, True, True, False]
        """
        topology = self.structure.topology()
        faces = topology.faces_vertices
        key = topology.vertex_curve * len(self.structure.lattice.s) + topology.vertex_sample
        ends = np.sort(np.stack([key[faces], np.roll(key[faces], -1, axis=1)], -1), -1)
        _, group = unique_pairs(ends.reshape(-1, 2))
        return readonly(np.bincount(group)[group].reshape(faces.shape) > 1)

    def labels(self) -> tuple[str, ...]:
        """Every panel's id, by face (:func:`~curvefold.geometry._thick_ids.panel_ids`).

        Examples
        --------
        >>> from curvefold.geometry._lattice import _example_lattice
        >>> from curvefold.geometry import PanelLattice
        >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
        >>> ThickPanels.offset(tube, 0.01).labels()[5]
        'tube 1 · sheet B · strip 2 · panel 2'
        """
        return panel_ids(self.structure.topology().faces_group)

    @cached_property
    def order(self) -> np.ndarray:
        """The panels (faces) in the order they are assembled, (F,): the cut list's rows and the
        assembly guide's (:func:`~curvefold.geometry._thick_ids.assembly_order`)."""
        return readonly(assembly_order(self.structure.topology().faces_group))

    def cut_list(self) -> tuple[dict, ...]:
        """What a router or a saw needs of every panel, in the order of assembly (:attr:`order`),
        JSON-ready: its id, outline (corners in its plane, model units), edge lengths, bevel of
        every edge (degrees; 0 a square cut), which edges are on a hinge (``hinged``; the others
        are free) and the hinge axes' ends (in the outline's plane, on the zero-thickness face).

        Examples
        --------
        >>> from curvefold.geometry._lattice import _example_lattice
        >>> from curvefold.geometry import PanelLattice
        >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
        >>> row = ThickPanels.offset(tube, 0.01).cut_list()[13]
        >>> row["panel"], row["bevels"]
        ('tube 1 · sheet B · strip 3 · panel 2', [0.0, 5.045, 0.0, 5.045])
        """
        k = self.local.shape[1] // 2
        outline = self.local[:, :k, :2]
        edges = np.linalg.norm(np.roll(outline, -1, axis=1) - outline, axis=-1)
        labels = self.labels()
        return tuple(
            {
                "panel": labels[f],
                "thickness": self.thickness,
                "outline": outline[f].round(9).tolist(),
                "edges": edges[f].round(9).tolist(),
                "bevels": np.degrees(self.bevels[f]).round(3).tolist(),
                "hinged": self.hinged[f].tolist(),
                "hinges": self.hinges[f, :, :, :2].round(9).tolist(),
            }
            for f in self.order.tolist()
        )

    # -- contact -----------------------------------------------------------------------------
    def deepest(self, fold_angle: float) -> tuple[float, tuple[int, int] | None]:
        """The largest penetration depth between two solids at one fold angle, and which two.

        Every pair of solids whose bounding boxes overlap is tested exactly
        (:func:`~curvefold.geometry._thick_solids.penetration`); the depth is ≤ 0 when no two
        interpenetrate (neighbours on a hinge touch: 0 to rounding).

        Examples
        --------
        >>> from curvefold.geometry._lattice import _example_lattice
        >>> from curvefold.geometry import PanelLattice
        >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
        >>> depth, pair = ThickPanels.offset(tube, 0.01).deepest(60)
        >>> bool(depth <= 1e-15)
        True
        """
        a, b, depth = (np.concatenate(x) for x in zip(*self._depths(fold_angle)))
        if not len(a):
            return -np.inf, None
        k = int(np.argmax(depth))
        pair = (int(min(a[k], b[k])), int(max(a[k], b[k])))
        return float(depth[k]), pair

    def _depths(
        self, fold_angle: float, above: float = 0.0
    ) -> Iterator[tuple[np.ndarray, np.ndarray, np.ndarray]]:
        """The pairs of solids whose boxes overlap and their depths
        (:func:`~curvefold.geometry._thick_solids.penetration` with ``above``), a chunk at a
        time: (a, b, depth), each (≤ :data:`_CHUNK`,); one empty chunk when there are none."""
        vertices, normals = (v[0] for v in self.solids(np.array([float(fold_angle)])))
        a, b = _overlapping_boxes(vertices.min(axis=1), vertices.max(axis=1), 1e-12)
        a, b = a[a != b], b[a != b]
        for i in range(0, max(len(a), 1), _CHUNK):
            p, q = a[i : i + _CHUNK], b[i : i + _CHUNK]
            depth = penetration(vertices[p], vertices[q], normals[p], normals[q], above=above)
            yield p, q, depth

    def interpenetrate(self, fold_angle: float) -> bool:
        """Whether two solids overlap deeper than :data:`PENETRATION_TOL` × t at a fold angle:
        :meth:`deepest`'s verdict, a chunk of pairs at a time, stopping at the first deeper
        pair, the edges' axes tried only where the faces' leave a pair deeper than that.

        Examples
        --------
        >>> from curvefold.geometry._lattice import _example_lattice
        >>> from curvefold.geometry import PanelLattice
        >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
        >>> thick = ThickPanels.offset(tube, 0.01)
        >>> thick.interpenetrate(90), thick.interpenetrate(95)
        (False, True)
        """
        tol = PENETRATION_TOL * self.thickness
        return any(bool((d > tol).any()) for _, _, d in self._depths(fold_angle, above=tol))

    def motion_range(
        self, *, step: float = 1.0, max_angle: float = 179.0, tol: float = 1e-7
    ) -> ThickRange:
        """How far the thick panels fold from the design angle: the first contact toward flat
        and beyond.

        Fold angles on a grid of ``step`` degrees are tested from the design angle both ways
        (:meth:`interpenetrate`); the first interval with a contact is bisected to ``tol``
        degrees. Measured: 1.2 CPU-s for the paper's vault of 16 panels at t = 0.01 (576 solids,
        72 states), 2.7 CPU-s at 48 panels, t = 0.002 (1728 solids; 6.3 s when the pairs
        touching on a hinge had their edges' axes tried too).

        Raises
        ------
        InputError
            If the solids interpenetrate at the design angle.

        Examples
        --------
        >>> from curvefold.geometry._lattice import _example_lattice
        >>> from curvefold.geometry import PanelLattice
        >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
        >>> r = ThickPanels.offset(tube, 0.01).motion_range()
        >>> r.low, round(r.high, 6)
        (0.0, 90.0)
        """
        design = float(self.structure.lattice.crease.fold_angle)
        depth, pair = self.deepest(design)
        if depth > PENETRATION_TOL * self.thickness and pair is not None:
            topology = self.structure.topology()
            raise InputError(
                f"thickness: at the design angle 2α = {design:g}° the solids of "
                f"{_panel(topology, pair[0])} and {_panel(topology, pair[1])} interpenetrate by "
                f"{depth:.3g} ({depth / self.thickness:.2g} t), got t = {self.thickness:g}: offset "
                "to the outside of their tubes these panels overlap at any thickness (a wall "
                "two tubes share puts one ply's solid inside the other tube); build the cells "
                "along one diagonal"
            )
        ends: list[tuple[float, tuple[int, int] | None]] = []
        for stop in (0.0, max_angle):
            grid = np.append(np.arange(design, stop, step if stop > design else -step)[1:], stop)
            clear, found = design, None
            for angle in grid:
                if self.interpenetrate(angle):
                    found = angle
                    break
                clear = angle
            if found is None:
                ends.append((float(stop), None))
                continue
            while abs(found - clear) > tol:
                mid = 0.5 * (found + clear)
                clear, found = (clear, mid) if self.interpenetrate(mid) else (mid, found)
            ends.append((float(clear), self.deepest(found)[1]))
        (low, low_pair), (high, high_pair) = ends
        return ThickRange(design, low, high, low_pair, high_pair)

    def stack_height(self) -> float:
        """Height of the flat-folded stack (2α = 0): the solids' extent across the flat plane.

        Examples
        --------
        >>> from curvefold.geometry._lattice import _example_lattice
        >>> from curvefold.geometry import PanelLattice
        >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
        >>> round(ThickPanels.offset(tube, 0.01).stack_height(), 12)  # two plies
        0.02
        """
        flat = self.corners(np.zeros(1))[0].reshape(-1, 3)
        # the thin SVD: the full one's (F k)² left factor took 0.7 GB and 2.5 s at 1728 solids
        normal = np.linalg.svd(flat - flat.mean(axis=0), full_matrices=False)[2][-1]
        vertices = self.solids(np.zeros(1))[0][0]
        return float(np.ptp(vertices.reshape(-1, 3) @ normal))


def thickness_limit(structure: Structure, *, side: str = "outside", setback: float = 0.5) -> float:
    """The thickness :meth:`ThickPanels.offset` takes up to, model units: below the smallest
    panel's inradius r, and below ``s r / tan b`` for the bevel b each edge needs at the
    design angle (s the ``setback``). Lengths scale with the structure, so does the limit.

    Examples
    --------
    >>> from curvefold.geometry._lattice import _example_lattice
    >>> from curvefold.geometry import PanelLattice
    >>> tube = Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4))
    >>> round(thickness_limit(tube), 4)  # its inradius: a tube's bevels need no setback
    0.0498
    """
    if side not in ("outside", "inside"):
        raise InputError(f"side must be 'outside' or 'inside', got {side!r}")
    topology = structure.topology()
    faces = topology.faces_vertices
    x = topology.coords(structure.state().vertices)
    sides = np.full(len(faces), 1.0 if side == "outside" else -1.0)
    origin, axes = panel_axes(x[faces], sides)
    xy = np.einsum("fkd,fjd->fkj", x[faces] - origin[:, None], axes)[..., :2]
    r = inradius(xy)
    design = float(structure.lattice.crease.fold_angle)
    _, at_design = _bevels_needed(structure, sides, np.array([design]), design)
    tangent = np.tan(at_design)
    s = SETBACK.check(setback)
    limit = np.where(tangent > 0, s * r[:, None] / np.where(tangent > 0, tangent, 1), np.inf)
    return float(min(r.min(), limit.min()))


#: The largest setback of a top face, as a fraction of its panel's inradius.
SETBACK = Spec(
    "setback",
    "real",
    0.5,
    "(0, 1)",
    why="a top face set back by its inradius shrinks to a point",
    help="largest setback of a top face by its bevels, as a fraction of the panel's inradius",
)


def _check_tops(solids: np.ndarray, topology: Topology, setback: float) -> None:
    """Every top face a polygon of all its edges, each running as its bottom edge does, or one
    line naming the panel."""
    k = solids.shape[1] // 2
    bottom, top = solids[:, :k, :2], solids[:, k:, :2]
    along = ((np.roll(bottom, -1, 1) - bottom) * (np.roll(top, -1, 1) - top)).sum(-1)
    bad = np.flatnonzero((along <= 0).any(axis=1))
    if len(bad):
        raise InputError(
            f"setback must be smaller: at {setback:g} of the inradius the top face of "
            f"{_panel(topology, int(bad[0]))} loses an edge (its bevels meet), got {setback:g}"
        )


#: One end of the fold angles thick panels are bevelled for.
REACH = Spec("reach", "real", None, "[0, 180)", "degrees", help="fold angle 2α the bevels clear")


def _check_reach(reach: tuple[float, float], design: float) -> tuple[float, float]:
    """(lo, hi) in degrees, each in [0°, 180°), around the design angle, or one line saying why
    not."""
    if len(reach) != 2:
        raise InputError(f"reach must be two fold angles (lo, hi) in degrees, got {reach!r}")
    lo, hi = (REACH.check(r, f"reach[{k}]") for k, r in enumerate(reach))
    if not lo <= design <= hi:
        raise InputError(
            f"reach must hold the design angle {design:g}° (lo ≤ {design:g} ≤ hi), got "
            f"({lo:g}, {hi:g}): the bevels are cut so that the design state is clear"
        )
    return lo, hi


def _panel(topology: Topology, face: int) -> str:
    """Panel f in words: its place along its strip and its tube."""
    group = int(topology.faces_group[face])
    per_strip = int(np.count_nonzero(topology.faces_group == group))
    return f"panel {face % per_strip + 1} of tube {group // 4 + 1}"


def _bevels_needed(
    structure: Structure, side: np.ndarray, angles: np.ndarray, design: float
) -> tuple[np.ndarray, np.ndarray]:
    """The bevel every panel edge needs over fold angles (A,), and at the design angle, (F, k)
    radians each (module notes)."""
    topology = structure.topology()
    faces = topology.faces_vertices
    F, k = faces.shape
    key = topology.vertex_curve * len(structure.lattice.s) + topology.vertex_sample
    ends = np.stack([key[faces], np.roll(key[faces], -1, axis=1)], -1).reshape(-1, 2)
    hinge_ends = np.sort(ends, axis=1)
    _, group = unique_pairs(hinge_ends)
    # ordered pairs (P, Q) of edges on one hinge
    order = np.argsort(group, kind="stable")
    starts = np.flatnonzero(np.r_[True, group[order][1:] != group[order][:-1]])
    bounds = np.r_[starts, len(order)]
    pairs = [
        (p, q)
        for s, e in zip(bounds[:-1], bounds[1:])
        for p in order[s:e]
        for q in order[s:e]
        if p != q
    ]
    p, q = np.array(pairs, np.int64).reshape(-1, 2).T
    first = np.empty(len(group), np.int64)
    first[order] = np.repeat(order[starts], np.diff(bounds))
    s = structure
    motion = s.topology().coords(
        s.lattice.fold_points(s.curves_uv, np.append(angles, design))
    )  # (A + 1, V, 3)
    lo_vertex = np.where(
        ends[:, 0] == hinge_ends[:, 0], faces.ravel(), np.roll(faces, -1, 1).ravel()
    )
    hi_vertex = np.where(lo_vertex == faces.ravel(), np.roll(faces, -1, 1).ravel(), faces.ravel())
    need = np.zeros((len(angles) + 1, F * k))
    for a, x in enumerate(motion):
        corners = x[faces]
        _, axes = panel_axes(corners, side)
        normal = np.repeat(axes[:, 2], k, axis=0)
        axis = x[hi_vertex] - x[lo_vertex]
        axis /= np.linalg.norm(axis, axis=1, keepdims=True)
        d = np.repeat(corners.mean(axis=1), k, axis=0) - x[lo_vertex]
        d -= (d * axis).sum(1, keepdims=True) * axis
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        ref = d[first]
        theta = np.arctan2((cross(ref, d) * axis).sum(1), (ref * d).sum(1))
        sigma = np.sign((cross(d, normal) * axis).sum(1))
        delta = np.mod(sigma[p] * (theta[q] - theta[p]), 2 * np.pi)
        same = np.minimum(delta, 2 * np.pi - delta) < 1e-9  # coincident panels
        delta = np.where(same, np.where(sigma[q] == sigma[p], 0.0, 2 * np.pi), delta)
        gap = np.full(F * k, 2 * np.pi)
        np.minimum.at(gap, p, delta)
        nearest = np.full(F * k, -1)
        hit = delta <= gap[p]
        nearest[p[hit]] = q[hit]
        shared = (nearest >= 0) & (sigma[np.maximum(nearest, 0)] == -sigma)
        need[a] = np.clip(np.where(shared, np.pi / 2 - gap / 2, np.pi / 2 - gap), 0, None)
    return need[:-1].max(axis=0).reshape(F, k), need[-1].reshape(F, k)
