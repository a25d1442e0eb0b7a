"""Composite deployable vaults: tubed arches stacked along the lattice diagonal.

The arch curve has constant curvature κ₀ and harmonic torsion τ = a κ₀ sin(2π s/s₀) at the
design fold angle, with κ₀ s₀ from Eq. (20) (:mod:`curvefold.vault._arch`). Tubes are the cells
[j, j+1]² of its lattice, so curve 3 of one tube is curve 1 of the next. At the design
angle the vault stands on the ground plane z = 0 (z up): every end section lies on it.

Coordinates: z is up, the span (from one foot of curve 1 to the other) runs along +y,
and the tubes stack roughly along x. The paper's section feature lines then lie in the
xy plane (at the feet) and in the zx plane (at the apex).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace
from functools import cached_property
from typing import Literal, cast

import numpy as np

from ..geometry._crease import Crease
from ..geometry._curve import SpaceCurve, check_samples
from ..geometry._fold_angle import half_angle
from ..geometry._kinds import StructureLattice
from ..geometry._lattice import Lattice
from ..geometry._panel_pattern import PANELS
from ..geometry._panels import PanelLattice
from ..geometry._structure import Structure
from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InputError, RegressionError
from ..kernel._lie import cross
from ..kernel._validate import Interval, Spec, check_integer
from ._arch import (
    A_MAX,
    A_STANDING,
    ArchRoot,
    HarmonicTorsion,
    proportion_change,
    solve_panel_arch,
    solve_symmetric_arch,
)
from ._tubes import DEFAULT_TUBES_CAP, design_tubes, panel_structure

__all__ = [
    "VaultDesign",
    "Vault",
    "standing",
    "HarmonicTorsion",
    "VAULT_SPECS",
    "MIN_SAMPLES",
    "vault_samples",
    "vault_panels",
]

#: Fewest samples along a vault's creases (the apex is the middle sample).
MIN_SAMPLES = 21

#: Lengths a design may give (the vault's radius, a curve's length), in model units, and
#: why: far outside it coordinates, widths and their squares leave the float64 range.
LENGTHS, LENGTHS_WHY = "[1e-3, 1e6]", "numerical range"

#: The parameters of a vault, in design-file order. ``tubes`` is ``"max"`` or a count and
#: ``direction`` ``"+"`` or ``"-"`` here; :class:`VaultDesign` holds None and ±1 for them.
VAULT_SPECS: tuple[Spec, ...] = (
    Spec(
        "a",
        "real",
        0.3,
        A_STANDING,
        help="torsion amplitude a in tau = a kappa0 sin(2 pi s/s0)",
        why="no arch stands beyond it: Eq. (20) has no root next to π there",
        # a slider of round steps
        typical=Interval(0.0, math.floor(10 * A_MAX) / 10, True, True),
        label="torsion amplitude",
    ),
    Spec(
        "p_xy",
        "real",
        0.75,
        "(0, 100]",
        help="section proportion w_R(0)/w_L(0) at the feet",
        label="section proportion at the feet",
    ),
    Spec(
        "width",
        "real",
        0.08,
        "(0, 10]",
        help="width scale w_L(0) kappa0, dimensionless",
        label="tube width at the feet, in radii",
    ),
    Spec(
        "tubes",
        "count",
        "max",
        "[1, 1000]",
        help=f'number of tubes, or "max" before regression (at most {DEFAULT_TUBES_CAP})',
        label="tubes",
    ),
    Spec(
        "fold_angle",
        "real",
        90.0,
        "(0, 180)",
        "degrees",
        help="design fold angle 2 alpha, at which the vault stands on z = 0",
        label="design fold angle",
    ),
    Spec(
        "radius",
        "real",
        1.0,
        LENGTHS,
        "model units",
        help="1/kappa0",
        why=LENGTHS_WHY,
        label="radius of the arch curve",
    ),
    Spec(
        "layers",
        "integer",
        1,
        "[1, 50]",
        help="parallel diagonals of tubes",
        label="layers of tubes",
    ),
    Spec(
        "direction",
        "choice",
        "+",
        choices=("+", "-"),
        help="stack the tubes in +u+v or -u-v",
        label="stacking direction",
    ),
    PANELS,
)
_SPEC = {spec.name: spec for spec in VAULT_SPECS}


def vault_samples(samples: int, *, where: str = "samples") -> int:
    """The sample count a vault is built with for a requested count: the next odd count.

    Raises
    ------
    InputError
        Below :data:`MIN_SAMPLES`; the message starts with ``where``.

    Examples
    --------
    >>> vault_samples(800), vault_samples(801)
    (801, 801)
    """
    if samples < MIN_SAMPLES:
        raise InputError(
            f"{where} must be ≥ {MIN_SAMPLES} for a vault (the apex is the middle "
            f"sample), got {samples}",
            parameter="samples",
        )
    return samples | 1


def vault_panels(panels: int) -> int:
    """The panel count a vault is built with for a requested count: the next even count.

    Examples
    --------
    >>> vault_panels(0), vault_panels(23), vault_panels(24)
    (0, 24, 24)
    """
    return panels + panels % 2


@dataclass(frozen=True)
class VaultDesign:
    """Design parameters of a vault, checked against :data:`VAULT_SPECS`.

    Attributes
    ----------
    a : float
        Torsion amplitude, τ = a κ₀ sin(2π s/s₀), in [0, :data:`~curvefold.vault.A_MAX`):
        the arch family stands only there (≈ 1.2707).
    p_xy : float
        Section proportion at the feet, w_R(0) / w_L(0).
    width : float
        Width scale w_L(0)·κ₀ (dimensionless).
    radius : float
        1/κ₀ in model units.
    fold_angle : float
        Design fold angle 2α in degrees, at which the vault stands on the ground.
    tubes : int or None
        Number of tubes along the diagonal; None takes the maximum before regression of
        the smooth build, at most :data:`DEFAULT_TUBES_CAP`, whatever the panels.
    layers : int
        Parallel diagonals (a band of cells (j, j + k), k < layers).
    direction : {1, -1}
        Stack in +u +v or −u −v from the base tube.
    samples : int
        Samples along each crease (odd and ≥ :data:`MIN_SAMPLES`, so that the apex is a
        sample; :func:`vault_samples` makes any count odd).
    panels : int
        0 for the smooth vault, or the number N of rigid planar panels along each crease
        (even, so that the apex is a vertex; :func:`vault_panels` makes any count even).

    Examples
    --------
    >>> VaultDesign(a=0.0).a, VaultDesign().tubes  # None: the most tubes before regression
    (0.0, None)
    >>> VaultDesign(a=2.0)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: a must be in [0, 1.2707093728) (no arch stands beyond it:
    Eq. (20) has no root next to π there), got 2.0
    """

    a: float = 0.3
    p_xy: float = 0.75
    width: float = 0.08
    radius: float = 1.0
    fold_angle: float = 90.0
    tubes: int | None = None
    layers: int = 1
    direction: int = 1
    samples: int = 401
    panels: int = 0

    def __post_init__(self) -> None:
        for name in ("a", "p_xy", "width", "radius", "layers"):
            _SPEC[name].check(getattr(self, name))
        # the range of VAULT_SPECS' fold_angle, with the geometry's message
        half_angle(self.fold_angle)
        check_samples(self.samples)
        if self.samples % 2 == 0 or self.samples < MIN_SAMPLES:
            raise InputError(
                f"samples must be odd and ≥ {MIN_SAMPLES} (the apex is the middle "
                f"sample), got {self.samples}",
                parameter="samples",
            )
        if self.tubes is not None:
            tubes = _SPEC["tubes"].range
            assert tubes is not None  # a count's spec has a range
            check_integer(self.tubes, "tubes", tubes, why="or None for the maximum")
        if self.direction not in (1, -1):
            raise InputError(
                f"direction must be +1 or -1, got {self.direction!r}", parameter="direction"
            )
        if PANELS.check(self.panels) % 2:
            raise InputError(
                "panels must be 0 (smooth) or even for a vault (the apex is a "
                f"vertex), got {self.panels}",
                parameter="panels",
            )


def standing(lattice: PanelLattice) -> PanelLattice:
    """A panel arch moved onto the ground: its first end section on z = 0, the span along +y.

    x_0 goes to the origin, the normal of the end section at vertex 0 (``L_0 × R_0``, turned
    toward the first crease edge, which rises) to +z and the span ``x_N − x_0`` to +y; with
    the discrete Eq. (20) solved the other end section lies on z = 0 too.

    Examples
    --------
    >>> vault = Vault.from_design(samples=41, panels=4, tubes=2)  # its lattice is standing(...)
    >>> feet = vault.lattice.crease.curve.points[[0, -1]]
    >>> feet[0].tolist(), bool(abs(feet[1, 2]) < 1e-12), bool(feet[1, 1] > 0)
    ([0.0, 0.0, 0.0], True, True)
    """
    points = lattice.crease.curve.points
    up = cross(lattice.left[0], lattice.right[0])
    up *= np.sign(up @ (points[1] - points[0])) / np.linalg.norm(up)
    span = points[-1] - points[0]
    ahead = span - (span @ up) * up
    ahead /= np.linalg.norm(ahead)
    rotation = np.stack([cross(ahead, up), ahead, up])
    return lattice.moved(rotation, -rotation @ points[0])


def arch_crease(
    a: float,
    panels: int,
    radius: float,
    fold_angle: float,
    samples: int,
    *,
    root: ArchRoot | None = None,
) -> tuple[ArchRoot, Crease]:
    """The arch of a vault and its crease, standing with the span along +y.

    What every vault of the same a, panels, radius, fold angle and samples shares, whatever
    its widths and tubes: a sweep over p_xy or the width builds it once per row and hands
    it to :meth:`Vault.from_design`. ``root``: the arch's root for this a, panels and fold
    angle when the caller has it (it does not depend on the samples: the same design at
    fewer samples needs no new solve); by default it is solved here.
    """
    if root is None:
        root = (
            solve_panel_arch(a, panels, fold_angle=fold_angle)
            if panels
            else solve_symmetric_arch(a)
        )
    elif root.a != a:
        raise InputError(f"the arch root given is for a = {root.a!r}, not a = {a!r}")
    arch = root
    k0 = 1.0 / radius
    s0 = arch.kappa0_s0 / k0
    # T(0) = +z, N(0) = +y: the arch rises from the ground toward its other foot.
    frame = np.array([[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])  # columns T, N, B
    curve = SpaceCurve.from_curvature(
        k0, HarmonicTorsion(a * k0, s0), s0, samples=samples, frame=frame
    )
    # Turn about z so the span (foot to foot) runs along +y: a rigid motion of the curve.
    chord = curve.points[-1] - curve.points[0]
    phi = np.arctan2(chord[0], chord[1])
    c, s = np.cos(phi), np.sin(phi)
    Rz = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    curve = SpaceCurve(
        curve.s, readonly(curve.points @ Rz.T), readonly(Rz @ curve.frames), curve.kappa, curve.tau
    )
    return arch, Crease.from_curve(curve, fold_angle=fold_angle)


@dataclass(frozen=True, eq=False)
class Vault(FrozenArrays):
    """A vault built from its design: arch, lattice, structure and placement.

    Build it with :meth:`from_design`.

    Examples
    --------
    >>> vault = Vault.from_design(samples=41, tubes=3)  # coarse, for a quick example
    >>> vault.design.tubes, vault.max_tubes, vault.structure.cells.tolist()
    (3, 9, [[0, 0], [1, 1], [2, 2]])
    """

    design: VaultDesign
    arch: ArchRoot
    lattice: StructureLattice
    structure: Structure
    max_tubes: int

    @classmethod
    def from_design(
        cls,
        design: VaultDesign | None = None,
        *,
        arch: tuple[ArchRoot, Crease] | None = None,
        **overrides,
    ) -> Vault:
        """Solve the arch, place it on the ground and stack the tubes.

        ``arch``: the design's :func:`arch_crease`, when the caller has it already (a sweep
        along p_xy); by default it is built here.

        With ``design.panels`` = N > 0 the vault is made of rigid planar panels: the smooth
        arch's crease pattern sampled with N panels along each crease
        (:class:`~curvefold.geometry.PanelLattice`), κ₀ s₀ solving the discrete
        Eq. (20) (:func:`~curvefold.vault.solve_panel_arch`) and the design state
        placed by :func:`standing`. Its tubes are those of the smooth build of the design
        (:func:`~curvefold.vault._tubes.design_tubes`), and no panel may be a sliver
        (:meth:`~curvefold.geometry.PanelLattice.check`).

        Raises
        ------
        ConvergenceError
            If the arch family has no standing arch for ``a``.
        RegressionError
            If the base tube or the requested number of tubes passes regression, or a
            panel build of them has a sliver panel; the message names the most tubes.

        Examples
        --------
        >>> vault = Vault.from_design(samples=41, tubes=3)  # coarse, for a quick example
        >>> round(vault.kappa0_s0, 6), vault.lattice.crease.fold_angle
        (3.165717, 90.0)
        >>> Vault.from_design(samples=41, tubes=1000)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.RegressionError: tubes must be ≤ 9 (the maximum before regression
        for a = 0.3, p_xy = 0.75, width = 0.08), got 1000
        """
        design = (
            replace(design or VaultDesign(), **overrides)
            if overrides
            else (design or VaultDesign())
        )
        if arch is None:
            arch = arch_crease(
                design.a, design.panels, design.radius, design.fold_angle, design.samples
            )
        root, crease = arch
        w_left = design.width * design.radius  # w_L(0) κ₀ = width
        try:
            smooth = Lattice.from_crease(crease, w_left, design.p_xy * w_left)
            # A Lattice is a StructureLattice: its crease's fold angle is constant (not Crease's)
            lattice: StructureLattice = smooth  # type: ignore[assignment]
            reference = lattice
            if design.panels:  # the tubes are the smooth build's (design_tubes)
                _, smooth_crease = arch_crease(
                    design.a,
                    0,
                    design.radius,
                    design.fold_angle,
                    design.samples,
                    root=root.smooth,
                )
                reference = cast(
                    StructureLattice,
                    Lattice.from_crease(smooth_crease, w_left, design.p_xy * w_left),
                )
                lattice = standing(PanelLattice.from_lattice(smooth, design.panels))
        except RegressionError as err:
            raise RegressionError(
                f"width = {design.width:g} is past regression for the base tube: {err}",
                parameter="width",
            ) from None
        tubes, n_max = design_tubes(
            reference,
            design.tubes,
            direction=design.direction,
            what=f"a = {design.a:g}, p_xy = {design.p_xy:g}, width = {design.width:g}",
        )
        structure = panel_structure(
            lattice,
            tubes,
            direction=design.direction,
            layers=design.layers,
            panels=design.panels,
            chosen=design.tubes is None,
        )
        return cls(replace(design, tubes=tubes), root, lattice, structure, n_max)

    # -- derived quantities -----------------------------------------------------------------
    @property
    def kappa0_s0(self) -> float:
        """κ₀ s₀, the solution of Eq. (20)."""
        return self.arch.kappa0_s0

    @property
    def proportion_change(self) -> float:
        """w_R(s₀/2) / w_R(0), predicted in closed form: exp(a κ₀ s₀ cot α / π).

        The smooth structure's (at this κ₀ s₀); a panel vault's, measured, differs from it
        at second order in 1/N.
        """
        return proportion_change(self.design.a, self.kappa0_s0, fold_angle=self.design.fold_angle)

    @property
    def p_xz(self) -> float:
        """Section proportion at the apex, w_R(s₀/2) / w_L(s₀/2) = p_xy × proportion change²."""
        return self.design.p_xy * self.proportion_change**2

    @cached_property
    def vertices(self) -> np.ndarray:
        """Every lattice curve of the vault at the design angle, shape (M, n, 3), read-only."""
        return self.structure.state().vertices

    @property
    def apex_index(self) -> int:
        """Index of the middle sample (t = ½)."""
        return (len(self.lattice.s) - 1) // 2

    def measured_proportions(self) -> tuple[float, float]:
        """(w_R/w_L at t = 0, w_R(½)/w_R(0)) measured between parallel tangent lines of the built
        creases.

        Examples
        --------
        >>> vault = Vault.from_design(samples=41, tubes=3)  # coarse, for a quick example
        >>> [
        ...     round(p, 6) for p in vault.measured_proportions()
        ... ]  # p_xy and the proportion change exp(a κ₀ s₀ / π)
        [0.75, 1.352972]
        """
        X = self.lattice.points(np.array([[0, 0], [1, 0], [0, 1]], float))
        T = self.lattice.crease.curve.tangent
        widths = []
        for k in (1, 2):
            d = X[k] - X[0]
            widths.append(np.linalg.norm(d - np.einsum("ij,ij->i", d, T)[:, None] * T, axis=1))
        wl, wr = widths
        m = self.apex_index
        return float(wr[0] / wl[0]), float(wr[m] / wr[0])

    def section_slopes(self) -> tuple[float, float]:
        """Slopes of the section feature lines, in degrees.

        The feature line joins the corners (j, j) of the stacked tubes at one t. At the feet
        (t = 0) it lies in the ground (xy) plane: its angle from the x axis toward y. At the
        apex (t = ½) it lies in the zx plane: its angle from the x axis toward z. Lines have
        no direction, so angles are in [−90°, 90°).

        Examples
        --------
        >>> vault = Vault.from_design(samples=41, tubes=3)  # coarse, for a quick example
        >>> [round(angle, 6) for angle in vault.section_slopes()]
        [-19.700413, -20.501275]
        """
        diag = np.array([[0, 0], [1, 1]], float) * self.design.direction
        X = self.lattice.points(diag)
        d0 = X[1, 0] - X[0, 0]
        dm = X[1, self.apex_index] - X[0, self.apex_index]

        def line_angle(dx: float, dy: float) -> float:  # a line's angle, in [−90°, 90°)
            return float((np.degrees(np.arctan2(dy, dx)) + 90.0) % 180.0 - 90.0)

        return line_angle(d0[0], d0[1]), line_angle(dm[0], dm[2])

    def ground_error(self) -> float:
        """Largest ``|z|`` of the end sections (t = 0 and t = 1) of every crease at the design
        angle.

        Examples
        --------
        >>> vault = Vault.from_design(samples=41, tubes=3)  # coarse, for a quick example
        >>> vault.ground_error() < 1e-9  # it stands: both ends on the ground
        True
        """
        V = self.vertices
        return float(np.abs(V[:, [0, -1], 2]).max())

    def summary(self) -> dict:
        """Design parameters and derived quantities as a JSON-ready dict (model units).

        Examples
        --------
        >>> vault = Vault.from_design(samples=41, tubes=3)  # coarse, for a quick example
        >>> summary = vault.summary()
        >>> (
        ...     summary["tubes"],
        ...     round(summary["span"], 6),
        ...     round(summary["rise"], 6),
        ...     summary["design"]["a"],
        ... )
        (3, 2.008123, 1.142157, 0.3)
        """
        V = self.vertices
        # per coordinate: NumPy reduces a (..., 3) array over its leading axes some 20× slower
        lo, hi = (np.array([f(V[..., i]) for i in range(3)]) for f in (np.min, np.max))
        xy_slope, zx_slope = self.section_slopes()
        p_xy_measured, change_measured = self.measured_proportions()
        chord = self.lattice.crease.curve.points[-1] - self.lattice.crease.curve.points[0]
        uv = self.structure.curves_uv
        tubes = self.design.tubes
        assert tubes is not None  # from_design sets the count
        return {
            "design": asdict(self.design),
            "kappa0_s0": self.kappa0_s0,
            "s0": self.kappa0_s0 * self.design.radius,
            "proportion_change": self.proportion_change,
            "proportion_change_measured": change_measured,
            "p_xy_measured": p_xy_measured,
            "p_xz": self.p_xz,
            "tubes": int(tubes),
            "panels": int(self.design.panels),
            "max_tubes": int(self.max_tubes),
            "span": float(np.linalg.norm(chord)),
            "rise": float(hi[2]),
            "footprint": [float(hi[0] - lo[0]), float(hi[1] - lo[1])],
            "bounding_box": [lo.tolist(), hi.tolist()],
            "slope_xy_deg": xy_slope,
            "slope_zx_deg": zx_slope,
            "regression_margin": self.structure.regression_margin,
            "ground_error": self.ground_error(),
            "bounding_curves": {
                "first": uv[np.argmin(uv.sum(axis=1))].tolist(),
                "last": uv[np.argmax(uv.sum(axis=1))].tolist(),
                "left_side": uv[np.argmax(uv[:, 0] - uv[:, 1])].tolist(),
                "right_side": uv[np.argmax(uv[:, 1] - uv[:, 0])].tolist(),
            },
        }

    # -- folding motion -----------------------------------------------------------------------
    def motion(
        self, fold_angles: np.ndarray, *, anchor: Literal["start", "middle"] = "start"
    ) -> np.ndarray:
        """The vault at many fold angles, shape (A, M, n, 3).

        Parameters
        ----------
        fold_angles : (A,) array_like
            2α in degrees, in [0°, 180°).
        anchor : {"start", "middle"}, keyword-only
            Hold curve 1's frame at its start (the first foot) or at its middle (the apex:
            a motion symmetric about it).

        Examples
        --------
        >>> vault = Vault.from_design(samples=41, tubes=3)  # coarse, for a quick example
        >>> motion = vault.motion([0, 90])
        >>> (
        ...     motion.shape,
        ...     float(np.abs(motion[0][..., 2]).max()) > 1,
        ... )  # flat, the sheets stand up off the ground
        ((2, 10, 41, 3), True)
        """
        return self.lattice.fold_points(self.structure.curves_uv, fold_angles, anchor=anchor)

    def lift_off(
        self, fold_angles: np.ndarray, *, anchor: Literal["start", "middle"] = "start"
    ) -> np.ndarray:
        """How far the end sections leave the ground plane, shape (A, 2): [feet at t = 0, at t = 1].

        The largest ``|z|`` over the end points of every crease; zero at the design angle.

        Examples
        --------
        >>> vault = Vault.from_design(samples=41, tubes=3)  # coarse, for a quick example
        >>> vault.lift_off([60, 90]).round(
        ...     6
        ... ).tolist()  # at 60° the far feet lift; at the design angle none
        [[0.0, 0.680359], [0.0, 0.0]]
        """
        V = self.motion(fold_angles, anchor=anchor)
        return np.abs(V[:, :, [0, -1], 2]).max(axis=1)

    def first_contact(
        self, *, step: float = 1.0, max_angle: float = 179.0, samples: int = 201
    ) -> float | None:
        """First fold angle from the design angle on where distant parts of the vault touch
        (:func:`curvefold.geometry.first_contact`): the end of its motion.

        Returns
        -------
        float or None
            2α in degrees of the first contact on a grid of ``step`` degrees, or None if
            none occurs up to ``max_angle``.

        Examples
        --------
        >>> vault = Vault.from_design(samples=41, tubes=3)  # coarse, for a quick example
        >>> (
        ...     vault.first_contact(step=5.0, samples=21),
        ...     vault.first_contact(step=5.0, max_angle=100.0, samples=21),
        ... )
        (135.0, None)
        """
        from ..geometry._contact import first_contact

        return first_contact(self.structure, step=step, max_angle=max_angle, samples=samples)
