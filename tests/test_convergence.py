"""Elements across the strips: a plate's closed form, the cut sheet, and the response as k grows.

A strip one element wide is straight between its creases; cut into k elements across
(:func:`curvefold.mechanics._across.cut_across`) it bends across its width like a plate.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from numpy.testing import assert_allclose

from _cli import run
from _mechanics import strip
from curvefold.kernel import InputError
from curvefold.mechanics import (
    MATERIALS,
    BarHingeModel,
    StructureModel,
    analyse_load,
    static_response,
)
from curvefold.mechanics._across import cut_across
from curvefold.mechanics._convergence import observed_order, richardson
from curvefold.vault import Vault

PP = MATERIALS["polypropylene"]


def plate_deflection(k: int, *, length: float = 0.4, width: float = 0.1, t: float = 1e-3):
    """The largest deflection of a flat strip (8 rulings) cut into k across, held on its two long
    edges, under 1 Pa, over the plate's closed form 5 q b⁴ / 384 D."""
    sheet = strip(length, width, 8)
    cut, _, _ = cut_across(sheet, np.arange(len(sheet.vertices_coords)) % 2, k)
    model = BarHingeModel.from_mesh(cut, PP, t, crease_stiffness=1.0)
    y = model.nodes[:, 1]
    fixed = np.zeros((len(y), 3), bool)
    fixed[(np.abs(y) < 1e-12) | (np.abs(y - width) < 1e-12)] = True
    forces = np.zeros((len(y), 3))
    forces[:, 2] = -model.masses / model.masses.sum() * length * width  # 1 Pa, as the masses
    result, _ = static_response(model, forces, fixed)
    return result.max_displacement / (5 * width**4 / (384 * PP.bending_stiffness(t)))


def test_a_strip_cut_across_bends_as_a_plate_at_second_order():
    """Cylindrical bending between two held edges: one element across cannot bend at all; k
    elements (k − 1 hinges of D ℓ k / b, the load lumped at the lines) give 1 + 0.8 / k²
    of the closed form, an observed order of 2, and Richardson's estimate from k = 4 and 8
    the closed form itself."""
    assert plate_deflection(1) == 0.0
    ratios = np.array([plate_deflection(k) for k in (2, 4, 8, 16)])
    assert_allclose(ratios - 1, 0.8 / np.array([2, 4, 8, 16]) ** 2, rtol=1e-6)
    errors = ratios - 1
    assert_allclose(np.log2(errors[:-1] / errors[1:]), 2.0, atol=1e-5)
    assert (4 * ratios[2] - ratios[1]) / 3 == pytest.approx(1.0, abs=1e-8)


@pytest.fixture(scope="module")
def tube_state():
    return Vault.from_design(tubes=1, samples=21).structure.state()


def test_cutting_across_keeps_the_sheet_its_weight_and_its_folding(tube_state):
    one = StructureModel.from_state(tube_state, PP, 1e-3)
    three = one.with_across(3)
    assert len(three.model.nodes) == len(one.model.nodes) + 2 * 21 * 4  # two per ruling
    # the same area to 1e-9: a ruling quad is planar to O(h²), and a quad's area is that of
    # its two triangles, which its pieces split otherwise
    assert three.model.masses.sum() == pytest.approx(one.model.masses.sum(), rel=1e-8)
    assert three.model.membrane_area.sum() == pytest.approx(one.model.membrane_area.sum(), rel=1e-8)
    # a node inside a strip is on its ruling, where node_ends and node_weight put it
    a, b = three.node_ends.T
    w = three.node_weight[:, None]
    x = three.model.nodes
    assert_allclose(x, (1 - w) * x[a] + w * x[b], atol=1e-12)
    inner = three.node_curve < 0
    assert inner.sum() == 2 * 21 * 4 and set(np.round(three.node_weight[inner], 12)) == {
        round(1 / 3, 12),
        round(2 / 3, 12),
    }
    # the rigid folding stretches the cut sheet's bars no more than the whole strips'
    stretch = [
        np.abs(m.model.compatibility() @ m.fold_velocity().ravel()).max()
        / np.abs(m.fold_velocity()).max()
        for m in (one, three)
    ]
    assert stretch[1] <= 1.01 * stretch[0]
    # the feet: every node of the end rulings on the ground, those inside the strips too
    assert len(three.feet) > len(one.feet)
    assert np.isin(three.node_sample[three.feet], (0, 20)).all()
    # the lattice's fields ignore the nodes inside the strips
    assert_allclose(three.field(x[:, 2]), one.field(one.model.nodes[:, 2]))


@pytest.mark.parametrize("across", [0, 65, 1.5, True, "2"])
def test_across_out_of_range_is_told_with_the_value(tube_state, across):
    with pytest.raises(InputError, match=r"^across must be an integer in \[1, 64\] .*got"):
        StructureModel.from_state(tube_state, PP, 1e-3, across=across)


def test_the_load_command_takes_across_from_its_flag_and_design_file(tmp_path):
    """``--across`` and ``[loads] across`` reach the library unchanged; 0 is one line."""
    small = ("--tubes", "1", "--samples", "21")
    library = analyse_load(Vault.from_design(tubes=1, samples=21), across=3)
    flag = run("load", *small, "--across", "3", "--json")
    design = tmp_path / "vault.toml"
    design.write_text('kind = "vault"\nsamples = 21\n\n[vault]\ntubes = 1\n\n[loads]\nacross = 3\n')
    keyed = run("load", str(design), "--json")
    for r in (flag, keyed):
        assert r.returncode == 0, r.stderr
        d = json.loads(r.stdout)
        assert d["max_displacement"] == pytest.approx(library.static.max_displacement, rel=1e-9)
        assert d["buckling_factor"] == pytest.approx(library.buckling.factor, rel=1e-9)
    one = json.loads(run("load", *small, "--across", "1", "--json").stdout)
    assert one["max_displacement"] < 0.9 * library.static.max_displacement
    bad = run("load", *small, "--across", "0")
    assert bad.returncode == 2 and re.search(
        r"across must be an integer in \[1, 64\] elements .*got 0$", bad.stderr.strip()
    ), bad.stderr


def figures(structure, ks, **options):
    """The largest deflection under self-weight, the two lowest free eigenvalues and the
    buckling factor for each k across (polypropylene 1 mm, feet pinned), shape (len(ks), 4)."""
    one = StructureModel.from_state(structure.structure.state(), PP, 1e-3, **options)
    rows = []
    for k in ks:
        r = analyse_load(one.with_across(k), PP, 1e-3)
        rows.append([r.static.max_displacement, *r.modes.eigenvalues[:2], r.buckling.factor])
    return np.array(rows)


def orders(rows: np.ndarray) -> np.ndarray:
    """The observed order of every column over successive triples of rows refined by 2."""
    return np.array(
        [
            [observed_order(*rows[i : i + 3, c]) for c in range(rows.shape[1])]
            for i in range(len(rows) - 2)
        ]
    )


def test_a_tube_converges_as_the_elements_across_double():
    """A tube (41 samples): k = 1, 2, 4, 8 elements across.

    Measured: the deflection grows by 29 % from one element across to eight (a strip one
    element wide is that much too stiff) and converges at order 3.6 (k = 2, 4, 8); the
    buckling factor falls 3.5× from k = 1 (a strip that cannot buckle across its width)
    and converges at order 5; the free eigenvalues move by 2 % at most and converge at
    first order (1.0 for λ₁, 1.2 for λ₂: the mass of the nodes inside the strips). The
    bounds sit outside the measured orders by about 0.4.
    """
    rows = figures(Vault.from_design(tubes=1, samples=41), (1, 2, 4, 8), samples="all")
    deflection, lam1, lam2, factor = rows.T
    assert np.all(np.diff(deflection) > 0) and deflection[-1] / deflection[0] > 1.25
    assert factor[0] / factor[-1] > 3
    assert_allclose(rows[1:, 1:3], np.broadcast_to(rows[-1, 1:3], (len(rows) - 1, 2)), rtol=0.03)
    p = orders(rows[1:])[0]
    assert p[0] > 3.0 and 0.6 < p[1] < 1.4 and 0.6 < p[2] < 1.6 and p[3] > 4.0, p
    # Richardson from k = 4 and 8 at the observed order: the error of k = 8
    limit, error = richardson(deflection[2], deflection[3], order=p[0])
    assert error / limit < 1e-3 and abs(limit - deflection[3]) == pytest.approx(error)


def test_a_small_vault_converges_as_the_elements_across_double():
    """A vault of 3 tubes on 51 samples, k = 1, 2, 4, 8 (about 3 s).

    Measured: the deflection grows 40 % from k = 1 to 8 and converges at orders 2.8, 2.9;
    the buckling factor falls 11× from k = 1 (492 → 44) and converges at order 3.2 (k = 2,
    4, 8); λ₁ converges at first order (1.07), λ₂ at 0.6 (a change of 1.2 % from k = 2 to 8).
    """
    rows = figures(
        Vault.from_design(a=0.3, p_xy=0.75, tubes=3, samples=51), (1, 2, 4, 8), samples="all"
    )
    deflection, lam1, lam2, factor = rows.T
    assert np.all(np.diff(deflection) > 0) and deflection[-1] / deflection[0] > 1.3
    assert factor[0] / factor[-1] > 8
    p = orders(rows)
    assert p[:, 0].min() > 2.4 and 0.7 < p[1, 1] < 1.4 and p[1, 3] > 2.5, p
    assert_allclose(rows[1:, 1:3], np.broadcast_to(rows[-1, 1:3], (len(rows) - 1, 2)), rtol=0.03)


def test_the_budget_counts_the_elements_across():
    """The memory estimate of ``curvefold load`` stays above the peaks measured on the paper's
    vault (0.22, 0.25, 0.70 and 2.45 GB with k = 1, 2, 4, 8 on their default samples) and
    within three times them."""
    from pathlib import Path

    from curvefold.app import parse_design
    from curvefold.app._budget import estimate

    text = (Path(__file__).parent.parent / "examples" / "paper-vault.toml").read_text()
    totals = [
        estimate(parse_design(f"{text}\n[loads]\nacross = {k}\n").with_mechanics(), files=False)
        for k in (1, 2, 4, 8)
    ]
    assert all(e.largest == "mechanics" for e in totals)
    for e, peak in zip(totals, (0.22e9, 0.25e9, 0.70e9, 2.45e9), strict=True):
        assert peak < e.total < 3 * peak, (e.total, peak)
