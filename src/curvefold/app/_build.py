"""From a validated design (:mod:`curvefold.app._design`) to the objects it describes."""

from __future__ import annotations

from collections.abc import Collection, Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from ..geometry._crease import Crease
from ..geometry._curve import SpaceCurve
from ..geometry._kinds import StructureLattice
from ..geometry._lattice import Lattice
from ..geometry._panels import PanelLattice
from ..geometry._sampling import Sampling, choose_sampling
from ..geometry._single_fold import SingleFold
from ..geometry._structure import Structure
from ..io._formats import FORMATS
from ..io._layout import Layout
from ..kernel._errors import InputError
from ..vault._assembly import Vault, VaultDesign, arch_crease, vault_panels, vault_samples
from ._design import Design
from ._kinds import BlockParams, CreaseParams, CurveParams, TubeParams, VaultParams

if TYPE_CHECKING:  # pragma: no cover
    from ..geometry._thick import ThickPanels
    from ..io._output import PatternOutput
    from ._loading import Loaded

__all__ = [
    "Built",
    "BuiltStructure",
    "BuiltVault",
    "BuiltCrease",
    "build",
    "build_vault",
    "build_tube",
    "build_block",
    "build_lattice_structure",
    "build_crease",
    "vault_design",
    "fit_vault_targets",
    "design_motion",
    "exported_fold_angles",
    "MOTION_STEPS",
]

#: States of the folding motion from flat to the design angle (the GLB's; the FOLD file's continue
#: to the first contact).
MOTION_STEPS = 7


@dataclass(frozen=True, eq=False)
class Built:
    """What a design builds: the base of one type per kind of what it builds
    (:class:`BuiltStructure`, :class:`BuiltVault`, :class:`BuiltCrease`).

    Its derived values are computed when first read, once; :meth:`prepare` computes, in this
    process, those that the output folder's jobs share before they fork.

    Attributes
    ----------
    design : Design
    crease : Crease
        Curve 1's smooth crease (the one the panels sample, for a design with panels), or the
        single curved fold's.
    """

    design: Design
    crease: Crease

    @property
    def fold_angle(self) -> float:
        """2α of the design state (degrees; a single fold's at its start)."""
        raise NotImplementedError

    @property
    def mechanics(self) -> Loaded | None:
        """The structure under the design's material and loads, when the design gives them
        (:func:`curvefold.app._loading.analyse`); None otherwise."""
        return None

    @property
    def layout(self) -> Layout:
        """The crease pattern laid out on the output's pages
        (:func:`~curvefold.io.layout_pattern`)."""
        raise NotImplementedError

    def prepare(self) -> None:
        """Compute, in this process, what every job of the output folder shares (the drawings too)
        before any of them forks, so that they inherit it rather than each computing it."""

    def prepare_files(self, formats: Collection[str]) -> None:
        """Compute, in this process, what the output folder's file jobs writing ``formats``
        share before they fork (the drawings need none of it, and start first): the first
        contact (the FOLD file's motion, and the certificate's) and the crease patterns'
        layout (the patterns, the assembly guide and the 3dm draw it, the STL takes its scale)."""
        exported_fold_angles(self)
        families = {FORMATS[name].family for name in formats if name in FORMATS}
        if {"3dm", "stl"} & set(formats) or families & {"pattern", "guide"}:
            self.layout  # noqa: B018 (computed once, here)

    def _pattern_output(self) -> PatternOutput:
        """The page, units, scale and cutting of the crease patterns, as the layouts take them."""
        from ..io._output import PatternOutput
        from ..io._tables import mm_per_unit

        o = self.design.output
        mm = mm_per_unit(o.units)  # a page's sides are in mm
        page = o.page if isinstance(o.page, str) else (o.page[0] / mm, o.page[1] / mm)
        perforation = None if o.perforation is None else (o.perforation, o.perforation_gap)
        return PatternOutput(
            page=page,
            units=o.units,
            scale=o.scale,
            glue_tabs=o.glue_tabs,
            rulings=o.rulings,
            cutter=o.cutter,
            perforation=perforation,
            kerf=o.kerf,
            name=self.design.kind,
        )


@dataclass(frozen=True, eq=False)
class BuiltStructure(Built):
    """A tube or block (a structure on a lattice; on a :class:`~curvefold.geometry.PanelLattice`
    for a design with panels), held at both end sections under load.

    Attributes
    ----------
    structure : Structure
    """

    structure: Structure

    @property
    def fold_angle(self) -> float:
        return float(self.structure.lattice.crease.fold_angle)

    @cached_property
    def sampling(self) -> Sampling:
        """The samples the files' meshes keep (:func:`choose_sampling`)."""
        return choose_sampling(self.structure)

    @cached_property
    def mechanics(self) -> Loaded | None:
        """The structure under the design's material and loads
        (:func:`curvefold.app._loading.analyse`), when the design gives them; None otherwise.
        A kind that stands on the ground (a vault: :attr:`DesignKind.grounded
        <curvefold.app._kinds.DesignKind.grounded>`) stands on its feet, a tube or block is
        held at both end sections."""
        if not self.design.mechanics:
            return None
        from ._loading import analyse

        supported = "feet" if self.design.design_kind.grounded else "ends"
        return analyse(self.structure, self.design.material, self.design.loads, supported=supported)

    @cached_property
    def layout(self) -> Layout:
        """The crease pattern laid out on the output's pages, at its scale, in its cutter's
        convention, perforated and kerf-compensated as asked
        (:func:`~curvefold.io.layout_pattern`), on the files' samples. The crease-pattern
        files, the 3dm and the assembly guide are drawn from it."""
        from ..io._pattern import layout_pattern
        from ..io._sheet_bend import sheet_bend

        m, smooth = self.design.material, not self.design.design_kind.panels(self.design)
        bend = sheet_bend(m.material, m.thickness) if m is not None and smooth else None
        output = replace(self._pattern_output(), bend=bend)  # a thick sheet's, when smooth
        return layout_pattern(self.structure, output, keep=self.sampling.keep)

    @cached_property
    def thick(self) -> ThickPanels | None:
        """Its panels made thick, for a structure of rigid panels with a ``[material]``
        (:func:`curvefold.app._thickness.thick_panels`); None otherwise."""
        from ._thickness import thick_panels

        return thick_panels(self.structure, self.design)

    def prepare(self) -> None:
        """The mechanics of a design under load (the 3D models and the pictures show it) and a rigid
        structure's certified mechanism (the certificate and the pictures share it)."""
        from ..analysis._mechanism import certified_mechanism

        self.mechanics  # noqa: B018 (computed once, here)
        if self.structure.lattice.rigid:
            certified_mechanism(self.structure)

    def prepare_files(self, formats: Collection[str]) -> None:
        """As :meth:`Built.prepare_files`, and the meshes' samples (every mesh written
        keeps them)."""
        self.sampling  # noqa: B018 (computed once, here)
        super().prepare_files(formats)


@dataclass(frozen=True, eq=False)
class BuiltVault(BuiltStructure):
    """A composite deployable vault: its structure is the vault's, and it stands on its feet.

    Attributes
    ----------
    vault : Vault
    """

    vault: Vault


@dataclass(frozen=True, eq=False)
class BuiltCrease(Built):
    """A single curved fold (its crease is the design's)."""

    @property
    def fold_angle(self) -> float:
        return self.single_fold.fold_angle

    @cached_property
    def single_fold(self) -> SingleFold:
        """The single curved fold, with the strips' widths its files draw."""
        c = self.design.params(CreaseParams)
        return SingleFold.of(
            self.crease,
            self.design.function("kappa_2d"),
            (c.width_left, c.width_right),
            fold_angle=c.fold_angle,
        )

    @cached_property
    def layout(self) -> Layout:
        """The single fold's crease pattern at its scale, or as large as the page takes it
        (:func:`curvefold.io._single_fold.layout_single_fold`)."""
        from ..io._single_fold import layout_single_fold

        return layout_single_fold(self.single_fold, self._pattern_output())


def vault_design(design: Design) -> VaultDesign:
    """The :class:`VaultDesign` of a design of kind "vault" (an even sample count and an odd panel
    count are raised by one).

    Raises
    ------
    InputError
        Fewer samples than a vault needs; the message names the design's source.
    """
    v = design.params(VaultParams)
    return VaultDesign(
        a=v.a,
        p_xy=v.p_xy,
        width=v.width,
        radius=v.radius,
        fold_angle=v.fold_angle,
        tubes=None if v.tubes == "max" else int(v.tubes),
        layers=v.layers,
        direction=1 if v.direction == "+" else -1,
        samples=vault_samples(design.samples, where=f"{design.source}: samples"),
        panels=vault_panels(v.panels),
    )


def fit_vault_targets(
    design: Design, *, source: str | None = None, **targets: float
) -> tuple[Design, str]:
    """A vault design with the parameters the targets replace solved for them (see
    :mod:`curvefold.vault._targets`), never one that fails its own certificate.

    ``targets`` are ``span``, ``rise`` and ``p_xz``; they set ``radius``, ``a`` and ``p_xy``
    (and, with ``tubes = "max"``, the number of tubes).

    Returns
    -------
    design : Design
    note : str
        What the fit chose for the user (the number of tubes), or empty.

    Raises
    ------
    InputError
        A target no vault of the family reaches (the message gives the nearest design),
        or one met only by a design whose certificate fails (the message names the check).
    """
    from ..analysis._certificate import certify
    from ..vault._targets import fit_targets

    fit = fit_targets(vault_design(design), **targets)
    fitted = fit.require()
    chosen = {} if fitted.tubes is None else {"tubes": fitted.tubes}
    found = design.overrides(
        source=source, a=fitted.a, p_xy=fitted.p_xy, radius=fitted.radius, **chosen
    )
    built = build_vault(found)
    certificate = certify(
        built.crease, built.structure, built.vault, fold_angles=list(exported_fold_angles(built))
    )
    failed = [c for c in certificate.checks if not c.passed]
    if failed:
        c = failed[0]
        need = f"; use ≥ {c.samples_needed} samples" if c.samples_needed else ""
        raise InputError(
            f"the vault that meets these targets (a = {fitted.a:.6g}, p_xy = "
            f"{fitted.p_xy:.6g}) fails its certificate: {c.name} {c.status} at {c.where}{need}"
        )
    return found, fit.note


def design_motion(built: Built, fold_angle: float | None = None) -> np.ndarray:
    """2α of the states of the folding motion from flat to the design angle, or to ``fold_angle``
    (degrees): the GLB's (a single fold's start angle 2α(0))."""
    return np.linspace(0.0, built.fold_angle if fold_angle is None else fold_angle, MOTION_STEPS)


def exported_fold_angles(built: Built) -> np.ndarray:
    """2α of the frames the FOLD file holds and the certificate certifies (degrees): the folding
    motion from flat to the design angle, and on by the same step while nothing touches, when
    the structure meets itself before 180° (:func:`curvefold.geometry.first_contact`: where
    its motion ends)."""
    from ..geometry._contact import first_contact

    motion = design_motion(built)
    contact = first_contact(built.structure) if isinstance(built, BuiltStructure) else None
    if contact is None:
        return motion
    step = motion[1] - motion[0]
    return np.concatenate([motion, np.arange(motion[-1] + step, contact - 1e-9, step)])


def build(design: Design, *, like: Built | None = None) -> Built:
    """Build the structure a design describes, as its kind builds it (:mod:`curvefold.app._kinds`).

    ``like``: the same design built at other samples, when the caller has it; what it solved
    is reused (a vault's arch root: :func:`curvefold.vault._assembly.arch_crease`).

    Raises
    ------
    CurvefoldError
        Whatever the builders refuse (regression, no arch, bad curvature), with its message.
    """
    return design.design_kind.build(design, like)


def build_vault(design: Design, like: Built | None = None) -> BuiltVault:
    """A vault design built (on the arch root of ``like``, a build of it at other samples,
    if given)."""
    v = vault_design(design)
    root = like.vault.arch if isinstance(like, BuiltVault) else None
    arch = (
        None
        if root is None
        else arch_crease(v.a, v.panels, v.radius, v.fold_angle, v.samples, root=root)
    )
    vault = Vault.from_design(v, arch=arch)
    smooth = vault.lattice.smooth
    assert smooth is not None  # a vault's panels sample its smooth arch
    return BuiltVault(design, smooth.crease, vault.structure, vault)


def build_crease(design: Design, like: Built | None = None) -> BuiltCrease:
    """A single curved fold from its crease pattern: β_R given, or α(s)."""
    c = design.params(CreaseParams)
    k2, beta_left = design.function("kappa_2d"), design.function("beta_left")
    if c.alpha is not None:
        crease = Crease.from_alpha(
            k2, beta_left, design.function("alpha"), c.length, samples=design.samples
        )
    else:
        crease = Crease.from_pattern(
            k2,
            beta_left,
            design.function("beta_right"),
            c.length,
            fold_angle=c.fold_angle,
            samples=design.samples,
        )
    return BuiltCrease(design, crease)


def build_tube(design: Design, like: Built | None = None) -> BuiltStructure:
    """A single tube around curve 1."""
    tube = design.params(TubeParams)
    return build_lattice_structure(design, (tube.width_left, tube.width_right))


def build_block(design: Design, like: Built | None = None) -> BuiltStructure:
    """A cellular block of lattice cells."""
    block = design.params(BlockParams)
    return build_lattice_structure(design, (block.width_left, block.width_right), block.cells)


def build_lattice_structure(
    design: Design, widths: tuple[float, float], cells: Sequence[tuple[int, int]] | None = None
) -> BuiltStructure:
    """A structure on the lattice of curve 1 (``[curve]``) with the given widths at s = 0: a
    single tube, or the given lattice ``cells``; on rigid panels if ``[curve]`` says so."""
    c = design.params(CurveParams)
    curve = SpaceCurve.from_curvature(
        design.function("kappa"), design.function("tau"), c.length, samples=design.samples
    )
    crease = Crease.from_curve(curve, fold_angle=c.fold_angle)
    smooth = Lattice.from_crease(crease, *widths)
    # A Lattice is a StructureLattice: its crease's fold angle is constant (not Crease's)
    lattice: StructureLattice = (
        PanelLattice.from_lattice(smooth, c.panels) if c.panels else smooth  # type: ignore[assignment]
    )
    structure = Structure.tube(lattice) if cells is None else Structure.from_cells(lattice, cells)
    return BuiltStructure(design, crease, structure)
