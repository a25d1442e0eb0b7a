"""Collapse against OpenSees co-rotational shells (``tests/_opensees.py``) on a small vault.

Three tubes on 21 samples, polypropylene 1 mm, pinned at the feet, ULS 1.35 G: curvefold's
collapse path (:func:`curvefold.mechanics.collapse`, one element across each strip, the
imperfection span / 300 in the shape of the first buckling mode) and the same structure in
OpenSees: ASDShellQ4 with co-rotational kinematics, one shell across each ruling quad (the
same nodes as the bar-and-hinge model), the same imperfect shape, the same lumped weight
× 1.35, followed by displacement control of the same DOF (the node curvefold's first step
moves most, downwards).

The two codes share nothing but the geometry and the material. What is compared, and the
margins:

* the linear response about the imperfect shape at the control DOF (per unit λ): mesh for
  mesh the two agree to 6.7e-4 (2.4e-4 on the perfect shape; 0.5 % at converged meshes in
  ``tests/test_shell_agreement.py``): asked 2e-3;
* the shape of the curve, up to 0.65 λ_c (curvefold's collapse factor): the amplification
  w(λ) / (λ w_lin) of each code over its own linear response at the same λ, which takes the
  linear stiffness difference out and leaves the geometric nonlinearity, +0.2, +0.8, +1.3,
  +1.7 % at λ/λ_c = 0.16, 0.39, 0.55, 0.65 (asked 2 %); λ at the same control displacement
  −0.1, −0.7, −1.1, −1.4 % (asked 1.5 %);
* to the limit point: curvefold's vault is the softer, λ at the same displacement 4.2 %
  below the shells' at its limit (5.1 % one state past it; asked 6 %). Its collapse factor
  is 222.3 (0.586 × its linear 379.7, at 56.2 mm); the shells still carry 237.7 at 60.6 mm.
  The difference grows with the displacement. Both models have one element across each
  strip (the mesh a test affords; one triangle pair bending on one diagonal hinge, one shell
  by its full plate bending), where curvefold's own buckling factor is far from converged
  (379.7, 181.8 at two across, its collapse factor 101.3): the two discretisations part
  there, and which is nearer the converged curve is not measured here.

A doubled imperfection (span / 150) in curvefold's model against the shells' span / 300
falls outside both early margins. The shells' path takes 24 displacement steps of about
2.6 mm (about 30 CPU-s).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

pytest.importorskip("openseespy.opensees")

import _opensees  # noqa: E402
from curvefold.mechanics import analyse_load, assess, collapse  # noqa: E402
from curvefold.mechanics._collapse import governing_combination  # noqa: E402
from curvefold.mechanics._response import static_response  # noqa: E402
from curvefold.vault import Vault  # noqa: E402

G = 9.80665


def ours(imperfection: float = 1 / 300):
    """curvefold's collapse of the small vault, its linear control displacement per unit λ
    about the imperfect shape, the load's factor on the weight, and the structure."""
    result = analyse_load(Vault.from_design(tubes=3, samples=21), "polypropylene", 1e-3)
    verdict = assess(result)
    found = collapse(result, verdict, imperfection=imperfection)
    _, forces = governing_combination(result, verdict)
    model = result.structure.model
    factor = float(-forces[:, 2].sum() / (model.masses.sum() * G))
    imperfect = replace(model, nodes=model.nodes + found.shape)
    static, _ = static_response(imperfect, forces, result.supports.fixed(result.structure))
    linear = float(static.displacements.reshape(-1)[found.path.control])
    return found, linear, factor, result.structure


#: The shells' displacement-control steps, to 1.1 times curvefold's last control displacement.
STEPS = 24
#: The states compared at the tighter margins: λ up to this fraction of curvefold's collapse factor.
EARLY = 0.65


@pytest.fixture(scope="module")
def paths():
    found, linear, factor, sm = ours()
    lam, w, their_linear = _opensees.load_path(
        sm,
        (1, 1),
        shift=found.shape,
        factor=factor,
        control=found.path.control,
        increment=1.1 * float(found.path.control_displacement[-1]) / STEPS,
        steps=STEPS,
    )
    return found, linear, factor, sm, (lam, w, their_linear)


def compared(found, linear: float, theirs) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """At curvefold's states past the unloaded one: λ / λ_c, λ over the shells' λ at the same
    control displacement − 1, and the amplification w / (λ w_lin) over the shells' at the
    same λ − 1 (the shells' curve interpolated linearly between its states)."""
    lam_s, w_s, linear_s = theirs
    lam, w = found.path.factors[1:], found.path.control_displacement[1:]
    same_w = lam / np.interp(-w, -w_s, lam_s) - 1
    same_lam = (w / (lam * linear)) / np.interp(
        lam, lam_s[1:], w_s[1:] / (lam_s[1:] * linear_s)
    ) - 1
    return lam / found.factor, same_w, same_lam


def test_the_shells_linear_response_is_ours(paths):
    found, linear, factor, _, (_, _, theirs) = paths
    assert factor == pytest.approx(1.35, rel=1e-12)  # ULS 1.35 G
    # measured 6.7e-4 (the perfect shapes' 2.4e-4)
    assert abs(theirs / linear - 1) < 2e-3, (theirs, linear)


def test_the_collapse_path_follows_the_shells(paths):
    found, linear, _, _, theirs = paths
    assert found.limit_reached and found.reason.startswith("a limit point")
    lam_s, w_s, _ = theirs
    assert abs(w_s[-1]) >= abs(found.path.control_displacement[-1])  # the shells went as far
    ratio, same_w, same_lam = compared(found, linear, theirs)
    early = ratio <= EARLY
    assert early.sum() >= 4
    # measured at λ/λ_c = 0.16, 0.39, 0.55, 0.65: λ at the same displacement −0.1, −0.7, −1.1,
    # −1.4 %; the amplification +0.2, +0.8, +1.3, +1.7 %
    assert np.all(np.abs(same_w[early]) < 0.015), same_w
    assert np.all(np.abs(same_lam[early]) < 0.02), same_lam
    # to the limit point the bar-and-hinge vault is the softer, by up to 4.2 % at its limit
    # (5.1 % one state past it)
    assert np.all(same_w < 0.002) and np.all(same_w > -0.06), same_w
    # the shells carry more than curvefold's collapse factor: their limit is past its own
    assert lam_s.max() > found.factor


def test_a_doubled_imperfection_leaves_the_shells(paths):
    # curvefold's vault imperfect by span / 150 against the shells' span / 300: measured
    # early −1.1 to −2.6 % at the same displacement, +0.4 to +2.3 % in the amplification
    found, _, _, _, theirs = paths
    doubled, linear, _, _ = ours(2 / 300)
    assert doubled.path.control == found.path.control
    ratio, same_w, same_lam = compared(doubled, linear, theirs)
    early = ratio <= EARLY
    assert np.abs(same_w[early]).max() > 0.015 and np.abs(same_lam[early]).max() > 0.02
