"""From a validated design (:mod:`curvefold.app._design`) to the objects it describes."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from ..geometry._crease import Crease
from ..geometry._curve import SpaceCurve
from ..geometry._lattice import Lattice
from ..geometry._panels import PanelLattice
from ..geometry._sampling import Sampling, choose_sampling
from ..geometry._single_fold import SingleFold
from ..geometry._structure import Structure
from ..io._layout import Layout
from ..kernel._errors import InputError
from ..vault._arch import ArchRoot
from ..vault._assembly import Vault, VaultDesign, arch_crease, vault_panels, vault_samples
from ._design import Design

if TYPE_CHECKING:  # pragma: no cover
    from ._loading import Loaded

__all__ = ["Built", "build", "vault_design", "fit_vault_targets", "design_motion", "exported_fold_angles", "MOTION_STEPS"]

#: States of the folding motion from flat to the design angle (the GLB's; the FOLD file's continue to the first contact).
MOTION_STEPS = 7


@dataclass(frozen=True, eq=False)
class Built:
    """What a design builds: a vault, another structure, or a single crease.

    Attributes
    ----------
    design : Design
    vault : Vault or None
        Set for kind "vault".
    structure : Structure or None
        Set for kinds "vault", "tube" and "block" (on a
        :class:`~curvefold.geometry.PanelLattice` for a design with panels).
    crease : Crease or None
        Set for kind "crease" (a single curved fold); for the others, curve 1's smooth
        crease (the one the panels sample, for a design with panels).
    """

    design: Design
    vault: Vault | None
    structure: Structure | None
    crease: Crease

    @cached_property
    def sampling(self) -> Sampling | None:
        """The samples the files' meshes keep (:func:`choose_sampling`), None for a single crease."""
        return None if self.structure is None else choose_sampling(self.structure)

    @cached_property
    def mechanics(self) -> Loaded | None:
        """The structure under the design's material and loads (:func:`curvefold.app._loading.analyse`), when the
        design gives them; None otherwise. A vault stands on its feet, a tube or block is held at both end sections.
        Computed once, before the output folder's jobs fork."""
        if not self.design.mechanics or self.structure is None:
            return None
        from ._loading import analyse

        return analyse(self.structure, self.design.material, self.design.loads, supported="feet" if self.vault is not None else "ends")

    @cached_property
    def single_fold(self) -> SingleFold | None:
        """The single curved fold of a design of kind "crease", with the strips' widths its files draw;
        None for a structure."""
        if self.structure is not None:
            return None
        c = self.design.crease
        return SingleFold.of(self.crease, self.design.function("kappa_2d"), (c.width_left, c.width_right), fold_angle=c.fold_angle)

    @cached_property
    def layout(self) -> Layout:
        """The crease pattern laid out on the output's pages, at its scale, in its cutter's convention,
        perforated and kerf-compensated as asked (:func:`~curvefold.io.layout_pattern`), on the
        files' samples; a single fold's pattern at its scale or as large as the page takes it. The
        crease-pattern files, the 3dm and the assembly guide are drawn from it."""
        from ..io._output import PatternOutput
        from ..io._pattern import layout_pattern
        from ..io._tables import mm_per_unit

        o = self.design.output
        mm = mm_per_unit(o.units)
        # mm -> units
        page = o.page if isinstance(o.page, str) else (o.page[0] / mm, o.page[1] / mm)
        perforation = None if o.perforation is None else (o.perforation, o.perforation_gap)
        output = PatternOutput(page=page, units=o.units, scale=o.scale, glue_tabs=o.glue_tabs,
                               rulings=o.rulings, cutter=o.cutter,
                               perforation=perforation, kerf=o.kerf, name=self.design.kind)
        if self.structure is None:
            from ..io._single_fold import layout_single_fold

            return layout_single_fold(self.single_fold, output)
        return layout_pattern(self.structure, output, keep=self.sampling.keep)


def vault_design(design: Design) -> VaultDesign:
    """The :class:`VaultDesign` of a design of kind "vault" (an even sample count and an odd panel
    count are raised by one).

    Raises
    ------
    InputError
        Fewer samples than a vault needs; the message names the design's source.
    """
    v = design.vault
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


def fit_vault_targets(design: Design, *, source: str | None = None, **targets: float) -> tuple[Design, str]:
    """A vault design with the parameters the targets replace solved for them (see :mod:`curvefold.vault._targets`),
    never one that fails its own certificate.

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
    found = design.overrides(source=source, a=fitted.a, p_xy=fitted.p_xy, radius=fitted.radius, **chosen)
    built = build(found)
    failed = [c for c in certify(built.crease, built.structure, built.vault, fold_angles=exported_fold_angles(built)).checks if not c.passed]
    if failed:
        c = failed[0]
        need = f"; use ≥ {c.samples_needed} samples" if c.samples_needed else ""
        raise InputError(f"the vault that meets these targets (a = {fitted.a:.6g}, p_xy = {fitted.p_xy:.6g}) fails its "
                         f"certificate: {c.name} {c.status} at {c.where}{need}")
    return found, fit.note


def design_motion(built: Built, fold_angle: float | None = None) -> np.ndarray:
    """2α of the states of the folding motion from flat to the design angle, or to ``fold_angle``
    (degrees): the GLB's (a single fold's start angle 2α(0))."""
    if fold_angle is None:
        fold_angle = built.single_fold.fold_angle if built.structure is None else built.structure.lattice.crease.fold_angle
    return np.linspace(0.0, fold_angle, MOTION_STEPS)


def exported_fold_angles(built: Built) -> np.ndarray:
    """2α of the frames the FOLD file holds and the certificate certifies (degrees): the folding motion from
    flat to the design angle, and on by the same step while nothing touches, when the structure meets
    itself before 180° (:func:`curvefold.geometry.first_contact`: where its motion ends)."""
    from ..geometry._contact import first_contact

    motion = design_motion(built)
    contact = None if built.structure is None else first_contact(built.structure)
    if contact is None:
        return motion
    step = motion[1] - motion[0]
    return np.concatenate([motion, np.arange(motion[-1] + step, contact - 1e-9, step)])


def build(design: Design, *, arch_root: ArchRoot | None = None) -> Built:
    """Build the structure a design describes.

    ``arch_root``: a vault's arch root when the caller has it (the same design built at other
    samples: :func:`curvefold.vault._assembly.arch_crease`).

    Raises
    ------
    CurvefoldError
        Whatever the builders refuse (regression, no arch, bad curvature), with its message.
    """
    if design.kind == "vault":
        v = vault_design(design)
        arch = None if arch_root is None else arch_crease(v.a, v.panels, v.radius, v.fold_angle, v.samples, root=arch_root)
        vault = Vault.from_design(v, arch=arch)
        return Built(design, vault, vault.structure, vault.lattice.smooth.crease)
    if design.kind == "crease":
        c = design.crease
        k2, beta_left = design.function("kappa_2d"), design.function("beta_left")
        if c.alpha is not None:
            crease = Crease.from_alpha(k2, beta_left, design.function("alpha"), c.length, samples=design.samples)
        else:
            crease = Crease.from_pattern(k2, beta_left, design.function("beta_right"), c.length, fold_angle=c.fold_angle, samples=design.samples)
        return Built(design, None, None, crease)
    c = design.curve
    curve = SpaceCurve.from_curvature(design.function("kappa"), design.function("tau"), c.length, samples=design.samples)
    crease = Crease.from_curve(curve, fold_angle=c.fold_angle)
    params = design.tube if design.kind == "tube" else design.block
    lattice = Lattice.from_crease(crease, params.width_left, params.width_right)
    if c.panels:
        lattice = PanelLattice.from_lattice(lattice, c.panels)
    structure = Structure.tube(lattice) if design.kind == "tube" else Structure.from_cells(lattice, params.cells)
    return Built(design, None, structure, crease)
