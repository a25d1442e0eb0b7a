"""A single curved fold as its files hold it: the crease pattern, the folding motion and their
meshes.

A single curved fold (the paper's Fig. 08) is a crease with a ruled strip on each side. Its
crease pattern, everything folding keeps, is the planar crease of curvature κ_2D(s), the
ruling angles β_L(s), β_R(s) and the strips' widths; folding it to another start angle 2α(0)
gives the same pattern in space (:meth:`Crease.from_pattern
<curvefold.geometry.Crease.from_pattern>` integrates Eq. 3 again), so the motion from
flat to the design angle is one family of creases. Each state is three curves, the crease and
the two strips' edges at their widths from its tangent lines (the ruling lengths ``w / sin β``
are the pattern's, so every state is isometric to it up to the sampling), on the mesh of
:meth:`SingleFold.topology`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from ..kernel._errors import InputError
from ..kernel._functions import ScalarFunction
from ._crease import Crease
from ._curve import SpaceCurve
from ._fold_angle import check_fold_angle
from ._mesh import Mesh
from ._sheets import PatternSheet
from ._topology import SheetTopology, Topology, fold_assignment

__all__ = ["SingleFold", "default_widths", "REFOLD_RTOL"]

#: Relative tolerance of α(s) in a refolded state: at 1e-12 (the builders' default) a refolded state
#: of a fold built from α(s) was developable to 4.5e-11 only, above its rounding floor of 2.5e-11;
#: at 1e-13, to 6e-12 (measured at 801 samples).
REFOLD_RTOL = 1e-13


def default_widths(crease: Crease) -> tuple[float, float]:
    """Widths of the strips of a single fold drawn without given ones: 15 % of the crease's length,
    kept to 60 % of the regression limit on each side.

    Examples
    --------
    >>> [
    ...     round(w, 12)
    ...     for w in default_widths(
    ...         Crease.from_pattern(0.5, 90.0, 90.0, 3.0, fold_angle=60.0, samples=41)
    ...     )
    ... ]
    [0.45, 0.45]
    """
    length = crease.curve.length
    left, right = (min(0.15 * length, 0.6 * float(np.min(w))) for w in crease.regression_limits())
    return left, right


@dataclass(frozen=True, eq=False)
class SingleFold:
    """A single curved fold: its crease at the design angle, its pattern's curvature and the strips'
    widths.

    Attributes
    ----------
    crease : Crease
        The fold as built, at its design start angle 2α(0).
    kappa_2d : ScalarFunction
        κ_2D(s) of the crease pattern, per model unit.
    width_left, width_right : float
        The strips' widths from the crease's tangent lines, model units.
    fold_angle : float
        The design start angle 2α(0), degrees.

    Examples
    --------
    >>> crease = Crease.from_pattern(0.5, 90.0, 90.0, 3.0, fold_angle=60.0, samples=41)
    >>> fold = SingleFold.of(
    ...     crease, crease.curve.kappa.scaled(np.cos(np.radians(30))), fold_angle=60.0
    ... )
    >>> round(fold.width_left, 12), fold.fold_angle, fold.samples
    (0.45, 60.0, 41)
    """

    crease: Crease
    kappa_2d: ScalarFunction
    width_left: float
    width_right: float
    fold_angle: float

    @classmethod
    def of(
        cls,
        crease: Crease,
        kappa_2d: ScalarFunction,
        widths: tuple[float | None, float | None] = (None, None),
        *,
        fold_angle: float | None = None,
    ) -> SingleFold:
        """The single fold of a built crease and its pattern's κ_2D; a width left None is
        :func:`default_widths`'.

        ``fold_angle`` is the design's start angle 2α(0) in degrees, as the design gives it
        (default: measured from the crease's α(0)).

        Raises
        ------
        InputError
            A width that is not positive, or that reaches a curve of regression.

        Examples
        --------
        >>> crease = Crease.from_pattern(0.5, 90.0, 90.0, 3.0, fold_angle=60.0, samples=41)
        >>> fold = SingleFold.of(
        ...     crease, crease.curve.kappa.scaled(np.cos(np.radians(30))), fold_angle=60.0
        ... )
        >>> SingleFold.of(crease, fold.kappa_2d, (0.2, None)).width_left
        0.2
        >>> SingleFold.of(crease, fold.kappa_2d, (0.0, None))
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: the strips' widths must be positive, got (0.0,
        0.44999999999999996)
        """
        default = default_widths(crease)
        w_left, w_right = (float(d if g is None else g) for g, d in zip(widths, default))
        w = (w_left, w_right)
        if not all(np.isfinite(w)) or min(w) <= 0:
            raise InputError(f"the strips' widths must be positive, got {w}")
        crease.surface(width=w)  # refuses a width past a curve of regression, naming it
        design = (
            float(np.degrees(2 * crease.alpha(crease.s[:1])[0]))
            if fold_angle is None
            else float(fold_angle)
        )
        return cls(crease, kappa_2d, *w, design)

    @property
    def samples(self) -> int:
        return len(self.crease.s)

    def at(self, fold_angle: float) -> Crease:
        """The crease pattern folded to the start angle 2α(0) = ``fold_angle`` (degrees, in (0°,
        180°)).

        α(s) is integrated to a relative tolerance of :data:`REFOLD_RTOL`.

        Raises
        ------
        InputError
            Where α(s) leaves (0°, 90°) along the crease at that start angle.

        Examples
        --------
        >>> crease = Crease.from_pattern(0.5, 90.0, 90.0, 3.0, fold_angle=60.0, samples=41)
        >>> fold = SingleFold.of(
        ...     crease, crease.curve.kappa.scaled(np.cos(np.radians(30))), fold_angle=60.0
        ... )
        >>> (
        ...     fold.at(60.0) is crease,
        ...     fold.at(90.0).fold_angle,
        ... )  # α varies along a refolded crease in general
        (True, None)
        >>> fold.at(0.0)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: fold_angle must be in (0°, 180°), got 0.0
        """
        fold_angle = check_fold_angle(fold_angle)
        if fold_angle == self.fold_angle:
            return self.crease
        c = self.crease
        return Crease.from_pattern(
            self.kappa_2d,
            c.beta_left,
            c.beta_right,
            c.curve.length,
            fold_angle=np.radians(fold_angle),
            samples=self.samples,
            degrees=False,
            rtol=REFOLD_RTOL,
        )

    @cached_property
    def _flat(self) -> np.ndarray:
        """The three curves of the crease pattern (z = 0), (3, n, 3): the planar crease of
        curvature κ_2D."""
        c = self.crease
        plane = SpaceCurve.from_curvature(self.kappa_2d, 0.0, c.curve.length, samples=self.samples)
        T, N = plane.frames[:, :, 0], plane.frames[:, :, 1]
        bl, br = c.beta_left(c.s)[:, None], c.beta_right(c.s)[:, None]
        left = plane.points + self.width_left / np.sin(bl) * (np.cos(bl) * T + np.sin(bl) * N)
        right = plane.points + self.width_right / np.sin(br) * (np.cos(br) * T - np.sin(br) * N)
        return np.stack([plane.points, left, right])

    def curves(self, fold_angle: float) -> np.ndarray:
        """The crease and the two strips' edges at start angle 2α(0) (degrees; 0 the crease
        pattern), (3, n, 3).

        Examples
        --------
        >>> crease = Crease.from_pattern(0.5, 90.0, 90.0, 3.0, fold_angle=60.0, samples=41)
        >>> fold = SingleFold.of(
        ...     crease, crease.curve.kappa.scaled(np.cos(np.radians(30))), fold_angle=60.0
        ... )
        >>> fold.curves(60.0).shape, float(np.abs(fold.curves(0)[..., 2]).max())  # 0: flat
        ((3, 41, 3), 0.0)
        """
        if fold_angle == 0:
            return self._flat
        # (2 sides, 2, n, 3)
        surface = self.at(fold_angle).surface(width=(self.width_left, self.width_right))
        return np.stack([surface[0, 0], surface[0, 1], surface[1, 1]])

    def topology(self, faces: Literal["triangles", "quads"] = "triangles") -> Topology:
        """The mesh of the fold: vertex j·n + i is sample i of curve j (0 the crease, 1 the left
        edge, 2 the right); the left strip (group 0) and the right one (group 1), each ruled
        quads or two triangles per quad, one sheet.

        Edges: the crease (``"fold"``), the strips' edges and end rulings (``"boundary"``), the
        inner rulings and the diagonals. Faces are counter-clockwise in the crease pattern, each
        strip's quads ``(a_j, a_{j+1}, b_{j+1}, b_j)`` as :meth:`Topology.tubes` orders them (the
        left strip from the crease, the right one from its edge).

        Examples
        --------
        >>> crease = Crease.from_pattern(0.5, 90.0, 90.0, 3.0, fold_angle=60.0, samples=41)
        >>> fold = SingleFold.of(
        ...     crease, crease.curve.kappa.scaled(np.cos(np.radians(30))), fold_angle=60.0
        ... )
        >>> (
        ...     fold.topology().faces_vertices.shape,
        ...     fold.topology("quads").faces_vertices.shape,
        ...     len(fold.topology().sheets),
        ... )
        ((160, 3), (80, 4), 1)
        >>> fold.topology("hexagons")
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: faces must be 'triangles' or 'quads', got 'hexagons'
        """
        if faces not in ("triangles", "quads"):
            raise InputError(f"faces must be 'triangles' or 'quads', got {faces!r}")
        n = self.samples
        j, i = np.arange(n - 1), np.arange(n)
        c, left, right = 0, n, 2 * n
        # (a_j, a_{j+1}, b_{j+1}, b_j) from curve a to curve b, counter-clockwise: the left strip
        # (toward N) from the crease, the right one (toward −N) from its edge
        quads = [
            np.stack([c + j, c + j + 1, left + j + 1, left + j], axis=1),
            np.stack([right + j, right + j + 1, c + j + 1, c + j], axis=1),
        ]
        if faces == "quads":
            rows = np.concatenate(quads)
            diagonals = np.zeros((0, 2), np.int64)
        else:
            rows = np.concatenate(
                [np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]]) for q in quads]
            )
            diagonals = np.concatenate([q[:, [0, 2]] for q in quads])
        group = np.repeat([0, 1], len(rows) // 2)
        ends = np.isin(i, (0, n - 1))
        edges = np.concatenate(
            [
                np.stack([c + j, c + j + 1], axis=1),
                np.stack([left + j, left + j + 1], axis=1),
                np.stack([right + j, right + j + 1], axis=1),
                np.stack([c + i, left + i], axis=1),
                np.stack([c + i, right + i], axis=1),
                diagonals,
            ]
        )
        kind = np.concatenate(
            [
                np.full(n - 1, "fold"),
                np.full(2 * (n - 1), "boundary"),
                np.tile(np.where(ends, "boundary", "ruling"), 2),
                np.full(len(diagonals), "diagonal"),
            ]
        ).astype("<U8")
        seam = np.full(len(edges), -1, np.int64)
        vertices = np.arange(3 * n)
        sheet = SheetTopology(
            "single fold",
            vertices,
            np.arange(len(rows)),
            np.arange(len(edges)),
            rows,
            _oriented(edges, rows),
            seam,
        )
        return Topology(
            vertex_curve=np.repeat([0, 1, 2], n),
            vertex_sample=np.tile(i, 3),
            faces_vertices=rows,
            faces_group=group,
            edges_vertices=edges,
            edges_kind=kind,
            edges_seam=seam,
            sheets=(sheet,),
        )

    def mesh(self, fold_angle: float, faces: Literal["triangles", "quads"] = "triangles") -> Mesh:
        """The fold at start angle 2α(0) (degrees; 0 the crease pattern), the crease's fold angle
        measured.

        Examples
        --------
        >>> crease = Crease.from_pattern(0.5, 90.0, 90.0, 3.0, fold_angle=60.0, samples=41)
        >>> fold = SingleFold.of(
        ...     crease, crease.curve.kappa.scaled(np.cos(np.radians(30))), fold_angle=60.0
        ... )
        >>> mesh = fold.mesh(60.0)
        >>> round(float(np.median(np.abs(mesh.edges_foldAngle[mesh.edges_kind == "fold"]))), 1)
        60.0
        >>> float(np.abs(fold.mesh(0).edges_foldAngle).max())  # the crease pattern is flat
        0.0
        """
        return self.topology(faces).mesh(self.curves(fold_angle))

    def arrays(
        self, fold_angles: ArrayLike, faces: Literal["triangles", "quads"] = "triangles"
    ) -> tuple[Mesh, tuple[tuple[str, Mesh], ...]]:
        """The crease pattern (z = 0, the design state's fold angles) and the folded frames at
        ``fold_angles`` (degrees, titled ``"fold angle 30°"``), every frame with the dihedral
        angle it has at every edge with two faces.

        Examples
        --------
        >>> crease = Crease.from_pattern(0.5, 90.0, 90.0, 3.0, fold_angle=60.0, samples=41)
        >>> fold = SingleFold.of(
        ...     crease, crease.curve.kappa.scaled(np.cos(np.radians(30))), fold_angle=60.0
        ... )
        >>> pattern, folded = fold.arrays([30, 90])
        >>> [title for title, _ in folded], float(np.abs(pattern.vertices_coords[:, 2]).max())
        (['fold angle 30°', 'fold angle 90°'], 0.0)
        >>> fold.arrays([])[1]  # no frames asked
        ()
        """
        from ._mesh import fold_angles as dihedral

        top = self.topology(faces)

        def framed(x: np.ndarray, design: np.ndarray | None = None) -> Mesh:
            measured = (
                dihedral(x, top.faces_vertices, top.edges_vertices) if design is None else design
            )
            return Mesh(
                vertices_coords=x,
                edges_vertices=top.edges_vertices,
                edges_assignment=fold_assignment(top.edges_kind, measured, seams_open=True),
                edges_foldAngle=measured,
                faces_vertices=top.faces_vertices,
                edges_kind=top.edges_kind,
                faces_group=top.faces_group,
            )

        design = framed(top.coords(self.curves(self.fold_angle)))
        pattern = framed(top.coords(self._flat), design.edges_foldAngle)
        folded = tuple(
            (f"fold angle {float(a):g}°", framed(top.coords(self.curves(float(a)))))
            for a in np.asarray(fold_angles, float)
        )
        return pattern, folded

    def pattern_sheet(self, name: str = "") -> PatternSheet:
        """The crease pattern as a sheet to fabricate (no seams), M/V of the design state.

        Examples
        --------
        >>> crease = Crease.from_pattern(0.5, 90.0, 90.0, 3.0, fold_angle=60.0, samples=41)
        >>> fold = SingleFold.of(
        ...     crease, crease.curve.kappa.scaled(np.cos(np.radians(30))), fold_angle=60.0
        ... )
        >>> sheet = fold.pattern_sheet("demo")
        >>> sheet.label, sheet.mesh.vertices_coords.shape, int(sheet.edges_seam.max())
        ('demo · single fold', (123, 3), -1)
        """
        pattern, _ = self.arrays([self.fold_angle])
        return PatternSheet(
            f"{name} · single fold" if name else "single fold",
            pattern,
            np.full(len(pattern.edges_vertices), -1),
        )


def _oriented(edges: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Every edge oriented as the first face that runs it (the sheets' convention)."""
    from ._mesh import edges_faces

    ef = edges_faces(faces, edges)
    big = np.iinfo(np.int64).max
    fwd, rev = np.where(ef[:, 0] >= 0, ef[:, 0], big), np.where(ef[:, 1] >= 0, ef[:, 1], big)
    return np.where((rev < fwd)[:, None], edges[:, ::-1], edges)
