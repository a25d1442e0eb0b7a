"""The soft modes of the conjecture's structures at finite amplitude
(:mod:`curvefold.mechanics._finite_modes`).

Every soft mode stretches as ε⁴ along its straight line (it leaves the curved path at second
order); relaxed over the other directions, a motion's stretching falls to rounding, a mode
rigid at second order keeps ε⁴ (the closed form: a taut bar pushed sideways) and a stiff
direction ε².
"""

from __future__ import annotations

import numpy as np
import pytest

from curvefold import Crease, Lattice, SpaceCurve, Structure
from curvefold.geometry import PanelLattice
from curvefold.kernel._errors import InputError
from curvefold.mechanics import MATERIALS, BarHingeModel, StructureModel, conjecture_counts
from curvefold.mechanics._finite_modes import (
    FINITE,
    mode_energy_exponent,
    rigid_motions,
    stretching_energy,
)

PP = MATERIALS["polypropylene"]
AMPLITUDES = np.geomspace(1e-4, 3e-2, 4)  # m, on structures 1.56 m across


def taut_bar(kink: float = 0.0) -> BarHingeModel:
    """Two bars end to end, 1 m each, EA/L = 5 N/m; the midpoint raised by ``kink``."""
    return BarHingeModel(
        np.array([[0.0, 0, 0], [1, kink, 0], [2, 0, 0]]),
        [[0, 1], [1, 2]],
        [5.0, 5.0],
        np.zeros((0, 4), int),
        [],
        np.ones(3),
    )


#: Both ends pinned, the midpoint held out of the plane z = 0: free along the bar and sideways.
PINNED = np.eye(9)[[0, 1, 2, 6, 7, 8, 5]]


def test_a_taut_bar_pushed_sideways_stretches_as_the_fourth_power_exactly():
    """U_s = EA ε⁴ / 4 L³ (module example), along the mode and relaxed: a mode of the first
    order, rigid at the second; to 1e-12 relative, the exponents 4 to 1e-9."""
    eps = np.geomspace(1e-4, 1e-1, 4)
    exponents, energies = mode_energy_exponent(taut_bar(), np.eye(9)[4], eps, held=PINNED)
    exact = 5.0 / 4 * eps**4
    assert np.abs(energies / exact - 1).max() < 1e-12
    assert np.abs(exponents - 4).max() < 1e-9
    # damaged: the bar kinked (by 10 mm) stretches at first order when pushed sideways
    exponents, _ = mode_energy_exponent(taut_bar(0.01), np.eye(9)[4], eps[:2] * 1e-3, held=PINNED)
    assert np.abs(exponents - 2).max() < 1e-2, exponents


@pytest.fixture(scope="module")
def tube() -> tuple[StructureModel, np.ndarray, np.ndarray]:
    """The conjecture's tube (8 panels), its folding and its other soft mode (the end warp)."""
    curve = SpaceCurve.from_curvature(
        lambda s: 1 + 0.3 * np.sin(s), lambda s: 0.2 + 0.3 * np.cos(s), 3.0, samples=161
    )
    lattice = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.08)
    sm = StructureModel.from_state(
        Structure.tube(PanelLattice.from_lattice(lattice, 8)).state(), PP, 1e-3
    )
    return (sm, *_split(sm))


def _split(sm: StructureModel) -> tuple[np.ndarray, np.ndarray]:
    """The folding in the null space, and an orthonormal basis of the null space's rest, both
    free of rigid motions."""
    free = conjecture_counts(sm)["free"]
    rigid = rigid_motions(sm.model.nodes)
    null = free.shapes.reshape(len(free.shapes), -1).T
    null = null - rigid.T @ (rigid @ null)
    basis = np.linalg.svd(null, full_matrices=False)[0][:, : free.count]
    folding = basis @ (basis.T @ sm.fold_velocity().ravel())
    folding /= np.linalg.norm(folding)
    rest = np.linalg.svd(basis - np.outer(folding, folding @ basis), full_matrices=False)[0]
    return folding, rest[:, : free.count - 1].T


def test_the_tube_s_soft_modes_are_finite_motions(tube):
    """Along the line every soft mode stretches as ε⁴ (to 1e-6); relaxed over the stiff
    directions (the other soft mode held), the folding and the end warp both fall to rounding
    (≤ 1e-15 of the line's, over ε = 0.1 to 30 mm; asserted 1e-12): the warp is a motion of the
    tube with free ends, not a first-order artefact."""
    sm, folding, others = tube
    assert len(others) == 1
    for mode in (folding, others[0]):
        exponents, energies = mode_energy_exponent(sm.model, mode, AMPLITUDES)
        assert abs(exponents[0] - 4) < 1e-6, exponents
        assert np.isnan(exponents[1]) and (energies[1] / energies[0]).max() < 1e-12, energies
    # the folding keeps the end sections planar: the conjecture's case has this motion only
    from curvefold.mechanics._softmodes import planarity_rows

    ends = sm.end_sections()[0::2]
    assert np.abs(planarity_rows(sm.model.nodes, ends) @ folding).max() < 1e-9


def test_a_stiff_direction_stretches_as_the_square(tube):
    """Damaged: the folding perturbed by 1 % of a stiff direction grows as ε² along its line
    (at ε ≤ 10 µm, where the first-order term dominates), and the stiff direction itself as ε²
    relaxed (to 1/356 of its line's energy, no further); exponents 2 to 4e-5, asserted 1e-2
    and 1e-3."""
    sm, folding, others = tube
    rng = np.random.default_rng(3)
    stiff = rng.normal(size=folding.size)
    null = np.concatenate([rigid_motions(sm.model.nodes), folding[None], others])
    stiff -= null.T @ np.linalg.lstsq(null.T, stiff, rcond=None)[0]
    stiff /= np.linalg.norm(stiff)
    small = np.geomspace(1e-7, 1e-5, 3)
    exponents, _ = mode_energy_exponent(sm.model, folding + 1e-2 * stiff, small)
    assert abs(exponents[0] - 2) < 1e-2, exponents
    exponents, energies = mode_energy_exponent(sm.model, stiff, small)
    assert np.abs(exponents - 2).max() < 1e-3 and (energies[1] / energies[0]).min() > 1e-3


def test_every_soft_mode_of_a_single_fold_is_a_finite_motion():
    """The single fold at 8 panels: its 2N + 1 = 17 soft modes (the rulings' drift) all relax to
    rounding (≤ 9e-15 of the line's, asserted 1e-12) at ε = 0.1 to 10 mm. At 30 mm four of them
    stop at 1e-7 to 1e-3: past its reach the held projections no longer meet the motions."""
    curve = SpaceCurve.from_curvature(
        lambda s: 1 + 0.3 * np.sin(s), lambda s: 0.2 + 0.3 * np.cos(s), 3.0, samples=161
    )
    lattice = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.08)
    sm = StructureModel.from_state(
        Structure.tube(PanelLattice.from_lattice(lattice, 8)).state(), PP, 1e-3, sheets=(0,)
    )
    folding, others = _split(sm)
    assert len(others) == 16
    for mode in (folding, *others):
        exponents, energies = mode_energy_exponent(sm.model, mode, np.geomspace(1e-4, 1e-2, 3))
        assert abs(exponents[0] - 4) < 1e-6 and np.isnan(exponents[1]), exponents


def test_user_errors():
    bar = taut_bar()
    with pytest.raises(InputError, match="amplitudes"):
        mode_energy_exponent(bar, np.eye(9)[4], [1e-3], held=PINNED)
    with pytest.raises(InputError, match="amplitudes"):
        mode_energy_exponent(bar, np.eye(9)[4], [1e-3, -1.0], held=PINNED)
    with pytest.raises(InputError, match="not zero"):
        mode_energy_exponent(bar, np.zeros(9), [1e-3, 1e-2], held=PINNED)
    with pytest.raises(InputError, match="9 entries"):
        mode_energy_exponent(bar, np.ones(6), [1e-3, 1e-2], held=PINNED)
    assert stretching_energy(bar, np.zeros(9)) == 0.0 and FINITE < 1e-10
