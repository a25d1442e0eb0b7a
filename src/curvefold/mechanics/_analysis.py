"""Will it stand: one call from a structure (or a vault) to its response, modes, buckling and soft
modes.

:func:`analyse_load` builds the structure's model at a fold angle (default: its own, a
vault's design angle, at which it stands on the ground), applies the loads with the
supports, and returns a :class:`LoadResult` holding everything a report or a
``--json`` output needs (:meth:`LoadResult.to_dict`, whose keys are stable).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from ..geometry._structure import State, Structure
from ..kernel._arrays import readonly
from ..kernel._errors import InputError
from ..vault._assembly import Vault
from ._loadcase import G, LoadCase
from ._loads import Loads
from ._materials import THICKNESS, Material
from ._materials import material as named
from ._modes import Modes, correlation, free_modes, span_correlation, supported_modes
from ._response import Buckling, StaticResult, buckling, static_response
from ._softmodes import SoftModes, soft_modes
from ._structures import StructureModel
from ._supports import Supports

__all__ = ["LoadResult", "analyse_load", "FOLDING"]

#: The name of the rigid folding motion in messages.
FOLDING = "the folding motion"


@dataclass(frozen=True, eq=False)
class LoadResult:
    """A structure under load: its model and every result. SI units.

    Attributes
    ----------
    structure : StructureModel
    loads : Loads
    supports : Supports
    static : StaticResult
    modes : Modes
        The lowest free modes (rigid motions removed).
    fold_correlation : float
        Correlation of the first mode with the kinematics' rigid folding velocity (mass
        metric, rigid motions removed), in [0, 1].
    fold_span_correlation : float
        Correlation of that velocity with the span of the computed modes, in [0, 1]: 1
        when the modes hold the folding motion. The first mode alone holds less of it the
        stiffer the creases are against the sheet (the user guide's Mechanics page).
    buckling : Buckling
    buckling_sample_correlation : float
        :meth:`StructureModel.sample_correlation` of the buckling mode, in [−1, 1]: at or
        below 0 the mode alternates from sample to sample, finer than the samples resolve
        (:attr:`buckling_resolved`).
    soft : SoftModes
        The inextensional motions of the free structure.
    supported_eigenvalues : (k,) ndarray
        The lowest eigenvalues ω² of the structure on its supports, rad²/s²
        (``supported_modes``).

    Examples
    --------
    >>> import numpy as np
    >>> from curvefold.vault import Vault
    >>> tube = StructureModel.from_state(
    ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
    ...     MATERIALS["aluminium"],
    ...     1e-3,
    ... )
    >>> result = analyse_load(tube)
    >>> round(result.total_weight, 6), result.soft.count, result.static.max_stress > 0
    (22.737584, 2, True)
    """

    structure: StructureModel
    loads: Loads
    supports: Supports
    static: StaticResult
    modes: Modes
    fold_correlation: float
    fold_span_correlation: float
    buckling: Buckling
    buckling_sample_correlation: float
    soft: SoftModes
    supported_eigenvalues: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def total_weight(self) -> float:
        """The structure's weight, Σ m g, N."""
        return float(G * self.structure.model.masses.sum())

    @property
    def utilisation(self) -> float | None:
        """Largest surface stress over the material's strength; None for a material without one."""
        strength = self.structure.material.strength
        return None if strength is None else self.static.max_stress / strength

    @property
    def buckling_resolved(self) -> bool:
        """Whether the samples resolve the buckling mode: it does not alternate from sample to
        sample.

        A mode at the scale of the samples is not the structure's: its factor is found too
        low, and more samples find the structure's (the user guide's Mechanics page).
        """
        return self.buckling_sample_correlation > 0

    def to_dict(self) -> dict:
        """JSON-ready results; the keys below are stable.

        ``total_weight`` (N), ``reactions`` (sum of the support reactions [x, y, z], N, z
        up), ``max_displacement`` (m), ``max_stress`` (Pa), ``utilisation`` (None without
        a strength), ``fold_mode_gap``, ``soft_modes``, ``buckling_factor`` (None when the
        load cannot buckle the structure), ``modes`` (the lowest eigenvalues ω², rad²/s²),
        and more: ``frequencies`` (Hz), ``supported_modes`` (the lowest eigenvalues ω² on the
        supports, rad²/s²) and ``supported_frequencies`` (Hz), ``stretching`` (each mode's
        share of its energy in the bars), ``fold_mode_correlation``,
        ``fold_span_correlation``, ``buckling_resolved``, ``applied_load`` (N),
        ``equilibrium_error``, ``material``, ``thickness`` (m), ``crease_stiffness``
        (N·m/rad/m), ``supports``, ``nodes``, ``samples`` (the samples the model keeps).

        Examples
        --------
        >>> import numpy as np
        >>> from curvefold.vault import Vault
        >>> tube = StructureModel.from_state(
        ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
        ...     MATERIALS["aluminium"],
        ...     1e-3,
        ... )
        >>> summary = analyse_load(tube).to_dict()
        >>> summary["nodes"], summary["supports"], summary["soft_modes"], summary["material"]
        (20, 'pinned', 2, 'aluminium')
        """
        s, m = self.structure, self.structure.model
        return {
            "total_weight": self.total_weight,
            "reactions": self.static.total_reaction.tolist(),
            "max_displacement": self.static.max_displacement,
            "max_stress": self.static.max_stress,
            "utilisation": self.utilisation,
            "fold_mode_gap": self.modes.fold_mode_gap,
            "soft_modes": self.soft.count,
            "buckling_factor": None if math.isinf(self.buckling.factor) else self.buckling.factor,
            "modes": self.modes.eigenvalues.tolist(),
            "frequencies": self.modes.frequencies.tolist(),
            "supported_modes": self.supported_eigenvalues.tolist(),
            "supported_frequencies": (
                np.sqrt(np.maximum(self.supported_eigenvalues, 0.0)) / (2 * math.pi)
            ).tolist(),
            "stretching": self.modes.stretching.tolist(),
            "fold_mode_correlation": self.fold_correlation,
            "fold_span_correlation": self.fold_span_correlation,
            "buckling_resolved": self.buckling_resolved,
            "applied_load": self.static.total_load.tolist(),
            "equilibrium_error": self.static.equilibrium_error,
            "material": s.material.name,
            "thickness": m.thickness,
            "crease_stiffness": s.crease_stiffness,
            "supports": self.supports.kind,
            "nodes": len(m.nodes),
            "samples": len(s.samples),
        }


def analyse_load(
    structure,
    material: Material | str = "polypropylene",
    thickness: float = THICKNESS.default,
    loads: Loads | Sequence[LoadCase] | None = None,
    supports: Supports | None = None,
    *,
    fold_angle: float | None = None,
    crease_stiffness: float | None = None,
    modes: int = 6,
    samples="graded",
    across: int = 1,
) -> LoadResult:
    """A structure under load, with its modes, buckling factor and soft modes.

    Parameters
    ----------
    structure : Structure, State, Vault or StructureModel
        What to analyse; a vault is taken at its design angle (where it stands on z = 0).
        Its model units are metres. A StructureModel brings its own material, thickness
        and creases: ``material``, ``thickness`` and ``crease_stiffness`` are then unused.
    material : Material or str
        A material or a name of :data:`~curvefold.mechanics.MATERIALS`.
    thickness : float
        Sheet thickness, m.
    loads : Loads or sequence of LoadCase, optional
        Default: self-weight.
    supports : Supports, optional
        Default: the feet pinned.
    fold_angle : float, optional, keyword-only
        2α in degrees (default the structure's own).
    crease_stiffness : float, optional, keyword-only
        k_c, N·m/rad/m (default the material's).
    modes : int, keyword-only
        How many lowest free modes (≥ 2, for the fold-mode gap).
    samples : {"graded", "all"} or sequence of int, keyword-only
        The samples the model keeps (:meth:`StructureModel.from_state`).
    across : int, keyword-only
        Elements across each ruling strip or panel (:meth:`StructureModel.from_state`).

    Raises
    ------
    InputError
        One line: a value out of range, a structure without feet, or a structure that is
        still a mechanism under its supports (which motion is free).

    Examples
    --------
    >>> from curvefold.vault import Vault
    >>> vault = Vault.from_design(tubes=1, panels=4, samples=21)
    >>> result = analyse_load(vault, "aluminium", 1e-3, Loads((SelfWeight(), Snow(100.0))))
    >>> round(result.total_weight, 6), result.supports.kind
    (22.737584, 'pinned')
    >>> analyse_load(Vault.from_design(tubes=1, panels=4, samples=21), "aluminium", 1.0)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: thickness must be in (0, 1) m (a sheet, not a block), got
    1.0
    """
    mat = named(material) if isinstance(material, str) else material
    if not isinstance(mat, Material):
        raise InputError(f"material must be a Material or a name, got {type(mat).__name__}")
    if isinstance(modes, bool) or not isinstance(modes, (int, np.integer)) or modes < 2:
        raise InputError(
            f"modes must be an integer ≥ 2 (the fold-mode gap needs two), got {modes!r}"
        )
    sm = _structure_model(structure, mat, thickness, fold_angle, crease_stiffness, samples, across)
    loads = Loads() if loads is None else loads if isinstance(loads, Loads) else Loads(tuple(loads))
    supports = Supports() if supports is None else supports
    model = sm.model
    folding = sm.fold_velocity()
    motions = {FOLDING: folding.ravel()}
    free = free_modes(model, modes, motions=motions)  # first: one factorisation held at a time
    result, factor = static_response(model, loads.forces(sm), supports.fixed(sm), motions=motions)
    buckled = buckling(model, result, factor)
    return LoadResult(
        structure=sm,
        loads=loads,
        supports=supports,
        static=result,
        modes=free,
        fold_correlation=correlation(model, free.shapes[0], folding),
        fold_span_correlation=span_correlation(model, free.shapes, folding),
        buckling=buckled,
        buckling_sample_correlation=sm.sample_correlation(buckled.shape),
        # the structure's mechanisms: its curves' nodes (a node inside a strip, on a straight
        # ruling, moves normal to the sheet without stretching its bars at first order)
        soft=soft_modes(model if sm.across == 1 else sm.with_across(1).model),
        supported_eigenvalues=readonly(
            supported_modes(model, result.fixed, factor, min(3, _free(result) - 2))
        ),
    )


def _free(result: StaticResult) -> int:
    return int((~result.fixed).sum())


def _structure_model(
    structure,
    mat: Material,
    thickness: float,
    fold_angle: float | None,
    crease_stiffness: float | None,
    samples,
    across: int,
) -> StructureModel:
    if isinstance(structure, StructureModel):
        return structure
    if isinstance(structure, Vault):
        structure = structure.structure
    if isinstance(structure, Structure):
        state = structure.state(fold_angle)
    elif isinstance(structure, State):
        state = structure if fold_angle is None else structure.structure.state(fold_angle)
    else:
        raise InputError(
            "analyse_load takes a Structure, State, Vault or StructureModel, got "
            f"{type(structure).__name__}"
        )
    return StructureModel.from_state(
        state, mat, thickness, crease_stiffness=crease_stiffness, samples=samples, across=across
    )
