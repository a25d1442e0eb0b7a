"""The bar-and-hinge model against an independent finite-element engine: OpenSees shells
(tests/_opensees.py).

On the paper's panel tube and panel vault (aluminium 2 mm, creases of the default
stiffness): the self-weight deflection with the feet pinned and the six lowest free
eigenvalues.

* One shell element per panel is the same discretisation as the bar-and-hinge model
  (a membrane with incompatible modes, the panel bending only by its twist, the creases
  as springs): the two codes share nothing but the geometry, and they agree to 1 %.
* Shells refined within each panel (m × m per panel) bend inside a panel, which the
  bar-and-hinge model cannot: it is stiffer. Measured on the 32-panel tube: the deflection
  OpenSees gives grows by 9 %, 16 % (m = 2, 4; 23 % at m = 8 on 16 panels, still
  converging slowly: the stresses where creases meet the feet are singular), the folding
  mode stays within 1 %, the second within 3 %, the next four within 25 %. On the
  16-panel vault of 9 tubes at m = 2: deflection 11 %, eigenvalues within 9 %.

The tolerances below sit just outside these measured differences and say which way
they go; a damaged model (a wrong modulus) falls outside them.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as la
from numpy.testing import assert_allclose

import _opensees
from curvefold.mechanics import (
    MATERIALS,
    Loads,
    Material,
    StructureModel,
    Supports,
    free_modes,
    static_response,
)
from curvefold.mechanics._convergence import observed_order, richardson
from curvefold.mechanics._linear import rigid_motions
from curvefold.vault import Vault

AL = MATERIALS["aluminium"]


def ours(sm: StructureModel) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Our deflection (P, 3), six lowest eigenvalues, and the six DOFs that hold the rigid
    motions (for OpenSees's soft springs)."""
    result, _ = static_response(sm.model, Loads().forces(sm.model), Supports().fixed(sm))
    modes = free_modes(sm.model, 6)
    R = rigid_motions(sm.model.nodes, sm.model.masses)
    held = la.qr(R.T, mode="r", pivoting=True)[1][:6]
    return result.displacements, modes.eigenvalues, np.stack([held // 3, held % 3], axis=1)


def theirs(
    sm: StructureModel, refine: int, eigenvalues: np.ndarray, ground: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """OpenSees's deflection and six lowest elastic eigenvalues (soft springs a millionth of the
    folding mode's stiffness)."""
    u = _opensees.static_deflection(sm, refine)
    spring = 1e-6 * sm.model.masses.sum() * eigenvalues[0]
    return u, _opensees.free_eigenvalues(sm, refine, 6, ground, spring)


def peak(u: np.ndarray) -> float:
    return float(np.linalg.norm(u, axis=1).max())


@pytest.fixture(scope="module")
def tube():
    return StructureModel.from_state(
        Vault.from_design(a=0.3, p_xy=0.75, panels=32, tubes=1).structure.state(), AL, 2e-3
    )


def test_one_shell_per_panel_is_the_same_discretisation(tube):
    u, lam, ground = ours(tube)
    v, mu = theirs(tube, 1, lam, ground)
    assert_allclose(peak(u), peak(v), rtol=0.01)  # measured 0.5 %
    assert_allclose(lam[:4], mu[:4], rtol=0.005)  # measured ≤ 0.2 %
    assert_allclose(lam[4:], mu[4:], rtol=0.02)  # measured 1.7 %, 0.3 %
    # damaged: a modulus 30 % too high (say, a unit slip in the table) is seen
    stiff = StructureModel.from_state(
        tube.state,
        Material.from_values(1.3 * AL.youngs_modulus, AL.poisson, AL.density, AL.strength),
        2e-3,
    )
    assert abs(peak(ours(stiff)[0]) / peak(v) - 1) > 0.1


@pytest.mark.slow
def test_refined_shells_bound_the_approximation_on_the_panel_tube(tube):
    u, lam, ground = ours(tube)
    v, mu = theirs(tube, 4, lam, ground)
    # stiffer: a panel bends only across its diagonal (measured 0.86)
    assert 0.80 < peak(u) / peak(v) < 0.92
    assert_allclose(lam[0], mu[0], rtol=0.015)  # the folding mode: measured 0.8 %
    assert_allclose(lam[1], mu[1], rtol=0.04)  # measured 2.5 %
    assert_allclose(lam[2:], mu[2:], rtol=0.3)  # measured 12 %, 21 %, 7 %, 24 %


@pytest.mark.slow
def test_the_paper_panel_vault_against_refined_shells():
    vault = StructureModel.from_state(
        Vault.from_design(a=0.3, p_xy=0.75, panels=16).structure.state(), AL, 2e-3
    )
    u, lam, ground = ours(vault)
    v, mu = theirs(vault, 1, lam, ground)
    assert_allclose(peak(u), peak(v), rtol=0.02)  # the same discretisation: measured 1.1 %
    assert_allclose(lam[:3], mu[:3], rtol=0.005)  # measured ≤ 0.2 %
    v, mu = theirs(vault, 2, lam, ground)
    assert 0.85 < peak(u) / peak(v) < 0.95  # measured 0.90
    assert_allclose(lam, mu, rtol=0.1)  # measured ≤ 8.6 %


@pytest.mark.slow
def test_refined_shells_agree_with_the_model_converged_across_on_a_smooth_tube():
    """A smooth tube (41 samples, one element along each ruling quad in both models): ours as
    k = 2, 4, 8 across (Richardson), OpenSees as m = 4, 8, 16 shells across each quad.

    Measured: ours converges at order 3.5 (k = 8 within 0.01 % of its limit), the shells by
    0.3 % from m = 8 to 16, and the two agree to 0.04 % in deflection (32.71 µm and 32.70);
    the folding mode's ω² to 0.9 % at m = 8, the next to 0.6 %. The 5 % asked is held on
    the deflection and both eigenvalues; a stiffer modulus (30 %) falls outside it.
    """
    state = Vault.from_design(a=0.3, p_xy=0.75, tubes=1, samples=41).structure.state()
    one = StructureModel.from_state(state, AL, 2e-3, samples="all")
    mine = [ours(one.with_across(k)) for k in (2, 4, 8)]
    p = observed_order(*(peak(u) for u, _, _ in mine))
    limit, error = richardson(peak(mine[1][0]), peak(mine[2][0]), order=p)
    assert p > 3 and error / limit < 1e-3, (p, error / limit)
    shells = [peak(_opensees.static_deflection(one, (m, 1))) for m in (4, 8, 16)]
    assert 0 < shells[2] / shells[1] - 1 < 0.01  # measured 0.3 %
    assert shells[2] / limit == pytest.approx(1, abs=0.05)  # measured 0.9996
    lam, ground = mine[2][1], ours(one)[2]
    mu = _opensees.free_eigenvalues(one, (8, 1), 2, ground, 1e-6 * one.model.masses.sum() * lam[0])
    assert_allclose(lam[:2], mu, rtol=0.05)  # measured 1.3 %, 0.7 % at k = 8
    stiff = StructureModel.from_state(
        state,
        Material.from_values(1.3 * AL.youngs_modulus, AL.poisson, AL.density, AL.strength),
        2e-3,
        samples="all",
    )
    assert peak(ours(stiff.with_across(8))[0]) / shells[2] < 0.95
