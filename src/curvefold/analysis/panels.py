"""The certificate of a structure of rigid panels: panel rigidity over its motion, and its mechanism.

:func:`panel_checks` measures what the panel construction claims (:mod:`curvefold.geometry.panels`):

* every panel keeps its four sides and both diagonals, and stays planar, in every frame the
  output folder holds (flat to the design angle) and at the vault's first contact;
* a vault's end sections lie on the ground at the design angle;
* the assembly is a mechanism of one internal degree of freedom at generic states, with a
  clear gap in the singular values of its constraint Jacobian (:mod:`curvefold.analysis.mechanism`).

Its rows are the fields of :class:`curvefold.analysis.certificate.Check`, which the
certificate turns into checks. The panel states are built by rigid motions of the flat
panels, so a panel's sides change only by the rounding of its vertex coordinates: about
ε · size relative to the structure's size, ε · size / ℓ relative to a side of length ℓ.
The tolerance is that model with a factor of 64 (measured: below 3 ε · size / ℓ_min over tubes of
4 to 640 panels, a block and vaults, from flat to nearly closed).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..geometry.panels import PanelLattice
from ..geometry.structure import Structure
from ..geometry.topology import lattice_corners
from ..vault.assembly import Vault
from .mechanism import MAX_UNKNOWNS, Framework, Mechanism, analyse

__all__ = ["CERTIFY_UNKNOWNS", "MOTION_FRAMES", "certified_mechanism", "panel_checks", "panel_rigidity"]

#: Unknowns the certificate's mechanism analysis takes at most: the longest prefix of the
#: cells that fits is analysed (a single tube always, up to :data:`MAX_UNKNOWNS`).
CERTIFY_UNKNOWNS = 1500
#: Frames of the motion measured, flat to the design angle (those of the output folder's files).
MOTION_FRAMES = 10
#: Factor of the rounding model of the panel-rigidity tolerances.
ROUNDING_FACTOR = 64.0


def panel_rigidity(structure: Structure, fold_angles: np.ndarray) -> tuple[float, float, float]:
    """Largest change of every panel's sides and diagonals, and largest non-planarity, over states.

    Parameters
    ----------
    structure : Structure
        On a :class:`~curvefold.geometry.panels.PanelLattice`.
    fold_angles : (A,) array_like
        2α in degrees.

    Returns
    -------
    isometry : float
        Largest |ℓ − ℓ_flat| / ℓ_flat over the sides and diagonals of every panel.
    planarity : float
        Largest ``det[c − a, d − b, b − a] / (ℓ_ac ℓ_bd ℓ_ab)`` over the panels (a, b, c, d).
    tolerance : float
        The rounding model ``64 ε · size / ℓ_min`` (size: the largest extent of the states).
    """
    framework, points = Framework.from_structure(structure)
    motion = structure.lattice.fold_points(structure.curves_uv, fold_angles).reshape(len(np.atleast_1d(fold_angles)), -1, 3)[:, points]
    relative = np.abs(np.stack([framework.residual(x) for x in motion]) / framework.scales)
    bars = len(framework.bars)
    size = float(np.ptp(motion.reshape(-1, 3), axis=0).max())
    tolerance = ROUNDING_FACTOR * np.finfo(float).eps * size / float(framework.scales.min())
    return float(relative[:, :bars].max()), float(relative[:, bars:].max()), tolerance


def _unknowns(structure: Structure, cells: int | None = None) -> int:
    """Unknowns of the mechanism analysis of a structure's first ``cells`` cells (all by default)."""
    return 3 * len(structure.lattice.s) * len(lattice_corners(structure.cells[:cells])[0])


def _prefix(structure: Structure, budget: int) -> Structure:
    """The structure of its longest prefix of cells within ``budget`` unknowns (one cell at least)."""
    k = len(structure.cells)
    while k > 1 and _unknowns(structure, k) > budget:
        k -= 1
    return structure if k == len(structure.cells) else Structure.from_cells(structure.lattice, structure.cells[:k])


@lru_cache(maxsize=4)
def certified_mechanism(structure: Structure) -> tuple[Structure, tuple[Mechanism, ...] | None]:
    """The mechanism the certificate reports: flat, half and full design angle.

    Returns the analysed structure (the longest prefix of the cells within
    :data:`CERTIFY_UNKNOWNS`) and its :class:`~curvefold.analysis.mechanism.Mechanism` at
    each angle, or None when a single tube exceeds :data:`MAX_UNKNOWNS`. Cached: the
    certificate and the report's plot share it.
    """
    part = _prefix(structure, CERTIFY_UNKNOWNS)
    return part, None if _unknowns(part) > MAX_UNKNOWNS else analyse(part)


def panel_checks(structure: Structure, vault: Vault | None = None) -> list[dict]:
    """The panel-rigidity and mechanism checks of a panel structure, as :class:`Check` fields.

    Parameters
    ----------
    structure : Structure
        On a :class:`~curvefold.geometry.panels.PanelLattice`.
    vault : Vault, optional
        Adds the first contact to the states measured, and the ground plane.

    Returns
    -------
    list of dict
        Each with the keys ``name, value, tolerance, unit, passed, meaning``.
    """
    if not isinstance(structure.lattice, PanelLattice):
        raise TypeError("panel_checks needs a structure on a PanelLattice")
    design = structure.lattice.crease.fold_angle
    angles = np.linspace(0.0, design, MOTION_FRAMES)
    contact = vault.first_contact() if vault is not None else None
    if contact is not None:
        angles = np.append(angles, contact)
    where = f"at {len(angles)} fold angles from 0° to {angles.max():.4g}°" + (" (the first contact)" if contact is not None else "")
    isometry, planarity, tolerance = panel_rigidity(structure, angles)
    rows = [
        _row("panel_isometry", isometry, tolerance, "relative",
             f"largest change of the four sides and both diagonals of every panel against the crease pattern, {where}; "
             "rounding of the vertex coordinates: 64 ε · size / shortest side"),
        _row("panel_planarity", planarity, tolerance, "relative",
             f"largest distance between the diagonal lines of a panel (times the sine of their angle to a side) over "
             f"its sides, {where}; rounding, as the isometry"),
    ]
    if vault is not None:
        size = float(np.ptp(vault.vertices.reshape(-1, 3), axis=0).max())
        rows.append(_row("ground_plane", vault.ground_error() / size, 16 * np.finfo(float).eps, "relative",
                         "largest |z| of every end section at the design angle, over the vault's size: the discrete Eq. (20) "
                         "holds to its root's residual (≤ 6 ε measured), which lifts the far feet by that times the span"))
    part, mechanisms = certified_mechanism(structure)
    if mechanisms is None:
        return rows + [_row("mechanism_unknowns", _unknowns(part), MAX_UNKNOWNS, "",
                            "the degrees of freedom are measured by a dense SVD of the constraint Jacobian, bounded in size; "
                            "one tube here is larger: not measured (use fewer panels)")]
    flat, generic = mechanisms[0], mechanisms[1:]
    scope = "" if part is structure else f" (measured on the first {len(part.cells)} of the {len(structure.cells)} tubes: the SVD is bounded)"
    dof = max(generic, key=lambda m: abs(m.dof - 1))
    clearance = max(m.clearance for m in generic)
    rows += [
        dict(name="mechanism_dof", value=float(dof.dof), tolerance=1.0, unit="", passed=all(m.dof == 1 and m.consistent for m in generic),
             meaning=f"internal degrees of freedom (nullity − 6 of the constraint Jacobian: edges, panel diagonals, panel "
                     f"planarity, welded seams and bonds) at {', '.join(m.label for m in generic)}; must be exactly 1{scope}. "
                     f"The flat state has {flat.dof}: lifts of the flat sheets that keep every panel planar, first-order only"),
        _row("mechanism_clearance", clearance, 1e-3, "",
             "nearest singular value to the rank tolerance (1e-9 σ_max) at those states, as a ratio ≤ 1 either way: "
             "the count holds for any tolerance a thousand times larger or smaller"),
    ]
    return rows


def _row(name: str, value: float, tolerance: float, unit: str, meaning: str) -> dict:
    return dict(name=name, value=float(value), tolerance=float(tolerance), unit=unit, passed=bool(value <= tolerance), meaning=meaning)
