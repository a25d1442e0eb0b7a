"""Collapse (``curvefold.mechanics.collapse``, ``curvefold load --nonlinear``): the collapse factor
of an imperfect structure against a closed form, its limit as the imperfection vanishes, the
imperfection's amplitude, the CSV, a path that stops, and the command line's checks."""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from curvefold.app.cli import main
from curvefold.mechanics import BarHingeModel, analyse_load, assess, collapse
from curvefold.mechanics import _path as path_module
from curvefold.mechanics._collapse import follow_collapse, judged
from curvefold.vault import Vault

# Koiter's strut: a rigid bar of length L pinned at its foot, its head held sideways by a
# spring c that stays horizontal (a bar D ≫ L long) and pressed down by λ. Perfect, it
# buckles at λ_cr = c L and its load falls as c L cos θ (an unstable symmetric bifurcation);
# tilted by θ₀ (the spring unstressed there), λ(θ) = c L cos θ (1 − sin θ₀ / sin θ), whose
# maximum is the collapse load. The spring's Green–Lagrange law moves it by the head's
# displacement over 2D (< 3e-5 here).
L, D, C = 1.0, 1.0e4, 100.0


def strut(c: float = C) -> tuple[BarHingeModel, np.ndarray, np.ndarray, np.ndarray]:
    nodes = np.array([[0.0, 0, 0], [0, 0, L], [D, 0, L]])
    model = BarHingeModel(nodes, [[0, 1], [1, 2]], [1e9, c], np.zeros((0, 4), int), [], [1, 1, 1])
    fixed = np.ones((3, 3), bool)
    fixed[1, [0, 2]] = False
    forces, mode = np.zeros((3, 3)), np.zeros((3, 3))
    forces[1, 2], mode[1, 0] = -1.0, 1.0
    return model, forces, fixed, mode


def strut_collapse(imperfection: float) -> float:
    """The strut's exact collapse load for a tilt of ``imperfection`` L."""
    t0 = np.arcsin(imperfection)
    best = minimize_scalar(
        lambda t: -C * L * np.cos(t) * (1 - np.sin(t0) / np.sin(t)),
        bounds=(t0 * (1 + 1e-6), 1.0),
        method="bounded",
        options={"xatol": 1e-14},
    )
    return float(-best.fun)


def strut_path(imperfection: float, c: float = C):
    model, forces, fixed, mode = strut(c)
    return follow_collapse(
        model, forces, fixed, linear_factor=C * L, mode=mode, span=L, imperfection=imperfection
    )


def test_the_strut_collapses_at_its_closed_form_from_below():
    # measured: -1.6e-4, -4.5e-5, -3.9e-5 (the last stable state and the tangent's eigenvalue
    # crossing zero, interpolated: the path's steps are the error, from below)
    for a, tolerance in ((1e-2, 4e-4), (1e-3, 1e-4), (1e-4, 8e-5)):
        found, exact = strut_path(a), strut_collapse(a)
        assert found.limit_reached and found.reason.startswith("a limit point")
        assert -tolerance < (found.factor - exact) / exact <= 3e-5, (a, found.factor, exact)
    # a spring 1 % stiffer is a different strut: the check sees it
    damaged = strut_path(1e-3, c=1.01 * C).factor
    assert abs(damaged - strut_collapse(1e-3)) / strut_collapse(1e-3) > 5e-3


def test_the_knock_down_vanishes_as_the_imperfection_to_the_two_thirds():
    # Koiter: 1 − λ_s/λ_cr ∝ (tilt)^(2/3) for an unstable symmetric bifurcation; measured
    # 0.0150, 0.00327, 0.00070 for tilts 1e-3, 1e-4, 1e-5: ratios 4.59 and 4.67 (10^(2/3) = 4.64)
    knock = [1 - strut_path(a).factor / (C * L) for a in (1e-3, 1e-4, 1e-5)]
    ratios = np.array(knock[:-1]) / np.array(knock[1:])
    assert np.all(np.abs(ratios / 10 ** (2 / 3) - 1) < 0.02), ratios
    # without an imperfection the path meets the bifurcation itself: the linear factor
    perfect = strut_path(0.0)
    assert perfect.reason.startswith("a bifurcation")
    assert abs(perfect.factor / (C * L) - 1) < 1e-3, perfect.factor


def test_the_imperfection_is_the_mode_at_the_stated_amplitude():
    found = strut_path(2e-3)
    assert np.isclose(np.linalg.norm(found.shape, axis=1).max(), 2e-3 * L, rtol=1e-14, atol=0)
    assert found.to_dict()["imperfection"] == pytest.approx(2e-3, rel=1e-14)
    assert found.to_dict()["imperfection_ratio"] == pytest.approx(2e-3, rel=1e-14)
    # on a vault, the buckling mode of the governing combination, span / 300 by default
    result = analyse_load(Vault.from_design(tubes=3, samples=21), "polypropylene", 1e-3)
    verdict = assess(result)
    c = collapse(result, verdict)
    mode = result.buckling.shape
    cosine = np.sum(c.shape * mode) / np.linalg.norm(c.shape) / np.linalg.norm(mode)
    assert abs(abs(cosine) - 1) < 1e-12
    assert np.linalg.norm(c.shape, axis=1).max() == pytest.approx(c.span / 300, rel=1e-12)
    assert np.sum(c.shape * result.static.displacements) > 0  # adds to the deflection
    assert c.linear_factor == pytest.approx(result.buckling.factor / 1.35, rel=1e-12)
    # the verdict takes the smaller factor
    stability = next(k for k in judged(verdict, c).checks if k.name == "stability")
    assert stability.value == pytest.approx(min(c.factor, c.linear_factor), rel=1e-15)


def test_the_csv_rows_are_the_path():
    found = strut_path(1e-3)
    lines = found.csv().splitlines()
    assert lines[0] == "state,load_factor,control_displacement_mm_node_1_x,stable"
    rows = np.array([[float(v) for v in line.split(",")] for line in lines[1:]])
    assert len(rows) == len(found.path.factors)
    assert np.allclose(rows[:, 1], found.path.factors, rtol=1e-9, atol=0)
    assert np.allclose(rows[:, 2], 1e3 * found.path.control_displacement, rtol=1e-9, atol=0)
    assert np.array_equal(rows[:, 3].astype(bool), found.path.stable)


def test_a_path_that_stops_says_where_in_one_line_and_keeps_its_states(monkeypatch):
    real = path_module.internal_forces

    def broken(model, u):  # a damaged model: no equilibrium past 2 cm
        f = real(model, u)
        return f if np.abs(u).max() < 0.02 else f * np.nan

    monkeypatch.setattr(path_module, "internal_forces", broken)
    found = strut_path(1e-2)
    assert not found.limit_reached
    assert "\n" not in found.reason
    assert found.reason.startswith("the load path did not converge at load factor")
    assert len(found.path.factors) > 2 and found.factor == found.path.factors.max()
    assert f"{len(found.path.factors) - 1} states kept" in found.reason


def run(argv, capsys) -> tuple[int, str, str]:
    status = main(argv)
    out = capsys.readouterr()
    return status, out.out, out.err


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        ("0.5", "imperfection must be in [0, 0.1] (a tenth of the span is a different structure"),
        ("-1e-3", "imperfection must be in [0, 0.1] "),
        ("nan", "imperfection must be a finite number, got nan"),
        ("x", "--imperfection: must be a number, got 'x'"),
    ],
)
def test_the_imperfection_flag_is_checked_in_one_line(value, expected, capsys):
    status, out, err = run(["load", "--tubes", "1", "--nonlinear", "--imperfection", value], capsys)
    assert status == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith("curvefold: error: --imperfection")
    assert expected in err and value in err.rsplit("got ", 1)[1], err


def test_load_nonlinear_reports_the_collapse_beside_the_linear_factor(tmp_path, capsys):
    argv = ["load", "--tubes", "3", "--samples", "21", "--across", "1", "--nonlinear"]
    status, out, _ = run([*argv, "--json"], capsys)
    d = json.loads(out)
    c = d["collapse"]
    assert set(c) >= {"factor", "linear_factor", "imperfection", "steps", "limit_reached"}
    assert c["imperfection"] == pytest.approx(c["span"] / 300, rel=1e-12)
    assert c["knock_down"] == pytest.approx(c["factor"] / c["linear_factor"], rel=1e-12)
    stability = next(k for k in d["checks"] if k["name"] == "stability")
    assert stability["value"] == pytest.approx(min(c["factor"], c["linear_factor"]), rel=1e-12)
    assert status == (0 if d["verdict"] == "stands" else 1)
    # the folder: the curve as CSV and picture, the shape at collapse a morph target of the GLB
    out_dir = tmp_path / "out"
    status, out, _ = run([*argv, "--formats", "glb", "--out", str(out_dir)], capsys)
    assert "collapse_factor" in out
    lines = (out_dir / "collapse.csv").read_text().splitlines()
    assert len(lines) == c["steps"] + 2
    assert (out_dir / "collapse.png").stat().st_size > 0
    glb = (out_dir / "vault.glb").read_bytes()
    assert b"collapse at " in glb


def test_the_analytic_hinge_hessian_is_the_complex_step_of_the_gradient():
    from curvefold.mechanics import _elements

    x = np.random.default_rng(0).standard_normal((2000, 4, 3))
    exact = _elements.dihedral_hessian_complex(x)
    scale = np.abs(exact).max(axis=(1, 2))
    error = np.abs(_elements.dihedral_hessian(x) - exact).max(axis=(1, 2)) / scale
    assert error.max() < 1e-12, error.max()  # measured 2e-15
    # a damaged block (node i's row not minus the others' sum) is seen
    damaged = _elements.dihedral_hessian(x)
    damaged[:, :3, 3:6] *= 1 + 1e-9
    assert (np.abs(damaged - exact).max(axis=(1, 2)) / scale).max() > 1e-10


def test_the_budget_counts_the_path_before_any_work():
    from dataclasses import replace

    from curvefold.app._budget import COLLAPSE_SHARE, estimate
    from curvefold.app._design import default_design

    design = default_design("vault").with_mechanics()
    linear = estimate(design, files=False).total
    nonlinear = replace(design, loads=replace(design.loads, nonlinear=True))
    grows = estimate(nonlinear, files=False).total - linear
    assert grows > 0
    # the share is of the part of the mechanics that grows with the model
    bare = replace(design, loads=None, material=None)
    assert grows < COLLAPSE_SHARE * (linear - estimate(bare, files=False).total)


def test_the_paper_vaults_collapse_is_estimated_within_the_default_budget():
    from dataclasses import replace
    from pathlib import Path

    from curvefold.app._budget import DEFAULT_BUDGET, estimate
    from curvefold.app._design import load_design

    path = Path(__file__).parents[1] / "examples" / "paper-vault.toml"
    design = load_design(path).with_mechanics()
    design = replace(design, loads=replace(design.loads, nonlinear=True))
    total = estimate(design, files=False).total
    # measured: `curvefold load examples/paper-vault.toml --nonlinear` peaked at 1.72 GiB
    assert 1.72 * 2**30 <= total <= 1.2 * 1.72 * 2**30
    assert total < DEFAULT_BUDGET


def light_vault_path():
    """The designer's light vault (41 samples, 2 tubes, aluminium 1 mm) followed to collapse."""
    from curvefold.app import default_design
    from curvefold.app._build import build
    from curvefold.app._design import design_from_dict

    d = default_design("vault").to_dict()
    d["samples"], d["vault"]["tubes"] = 41, 2
    d |= {"material": {"material": "aluminium"}, "loads": {"nonlinear": True}}
    loaded = build(design_from_dict(d, source="test").with_mechanics()).mechanics
    return loaded.collapse


def test_a_stalled_try_is_halved_not_pushed_onto_another_branch(monkeypatch):
    # The light vault's primary path stays stable to 898.6 and loses definiteness at 901.6 (1.009
    # x its linear 893.4). Pushing a stalled Newton's method on (no stall rule) once
    # converged from 388.0 to an unstable equilibrium at 486.6, 16 % of the displacement off
    # the path, and called it a collapse at 0.435 of the linear factor.
    found = light_vault_path()
    path = found.path
    assert found.factor == pytest.approx(901.583, rel=1e-5)
    assert path.stable[path.factors <= found.factor].all()
    monkeypatch.setattr(path_module, "STALLS", 10**9)
    pushed = light_vault_path().path

    def off(k: int) -> float:  # the pushed state k against the primary path at its load factor
        lam, u = pushed.factors[k], pushed.displacements[k].ravel()
        i = int(np.searchsorted(path.factors, lam)) - 1
        t = (lam - path.factors[i]) / (path.factors[i + 1] - path.factors[i])
        near = (1 - t) * path.displacements[i].ravel() + t * path.displacements[i + 1].ravel()
        return float(np.abs(u - near).max() / np.abs(u).max())

    jumped = int(np.flatnonzero(~pushed.stable)[0])
    assert off(jumped - 1) < 2e-3 < 0.1 < off(jumped)
