"""Will it stand: the load combinations, the checks and the verdict, each held against its own
computation, each made to fail, and ``curvefold load``'s first line and exit status."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

from _cli import run
from curvefold.kernel import InputError
from curvefold.mechanics import (
    MATERIALS,
    Check,
    Combination,
    Criteria,
    Loads,
    Material,
    PointLoad,
    SelfWeight,
    Snow,
    Supports,
    Verdict,
    Wind,
    analyse_load,
    assess,
    buckling,
    combinations,
    static_response,
)
from curvefold.vault import Vault

EXAMPLES = Path(__file__).parent.parent / "examples"
PP = MATERIALS["polypropylene"]


@pytest.fixture(scope="module")
def vault():
    return Vault.from_design(tubes=1, panels=4, samples=21)


@pytest.fixture(scope="module")
def weighed(vault):
    """The small vault under its own weight, and its verdict."""
    result = analyse_load(vault, PP, 1e-3)
    return result, assess(result)


@pytest.fixture(scope="module")
def snowed(vault):
    """The small vault under its own weight and snow, and its verdict."""
    result = analyse_load(vault, PP, 1e-3, Loads((SelfWeight(), Snow(500.0))))
    return result, assess(result)


def by_name(verdict: Verdict, name: str) -> list[Check]:
    return [c for c in verdict.checks if c.name == name]


# -- the combinations --------------------------------------------------------------------------


def test_the_combinations_are_en_1990_s_6_10_each_variable_action_leading_in_turn():
    cases = (SelfWeight(), Snow(500.0), Wind(600.0, -0.8), PointLoad(10.0))
    uls = [c for c in combinations(cases) if c.limit_state == "ULS"]
    # ψ0 of EN 1990 Table A1.1: snow 0.5, wind 0.6, imposed loads 0.7
    assert [c.factors for c in uls] == [
        (1.35, 1.5, 1.5 * 0.6, 1.5 * 0.7),
        (1.35, 1.5 * 0.5, 1.5, 1.5 * 0.7),
        (1.35, 1.5 * 0.5, 1.5 * 0.6, 1.5),
    ]
    (sls,) = [c for c in combinations(cases) if c.limit_state == "SLS"]
    assert sls.factors == (1.0,) * 4 and sls.cases == cases
    # the user's factors
    assert combinations(cases[:2], gamma_g=1.2, gamma_q=1.6)[0].factors == (1.2, 1.6)
    # no variable action: the permanent load alone
    assert [c.name for c in combinations((SelfWeight(),))] == ["ULS 1.35 G", "SLS G"]


def test_a_combination_s_forces_are_its_cases_forces_times_their_factors(vault):
    sm = analyse_load(vault, PP, 1e-3).structure
    combo = Combination((SelfWeight(), Snow(500.0)), (1.35, 0.75))
    expected = 1.35 * SelfWeight().forces(sm) + 0.75 * Snow(500.0).forces(sm)
    assert_allclose(combo.forces(sm), expected, rtol=1e-15, atol=0)


@pytest.mark.parametrize(
    ("make", "match"),
    [
        (lambda: Combination((SelfWeight(),), (1.0, 2.0)), r"one per case, got \(1.0, 2.0\)"),
        (lambda: Combination((SelfWeight(),), (-1.0,)), r"finite and > 0"),
        (lambda: Combination(("snow",), (1.0,)), r"needs load cases"),
        (lambda: Combination((SelfWeight(),), (1.0,), "ALS"), r"limit_state must be one of"),
        (lambda: combinations(()), r"^no load"),
        (lambda: combinations((SelfWeight(),), gamma_g=0.9), r"gamma_g must be in \[1, 10\]"),
        (lambda: Criteria(buckling_safety=0.5), r"buckling_safety must be in \[1, 1000\].*got 0.5"),
        (lambda: Criteria(deflection_limit=0.0), r"deflection_limit must be in \(0, 1000\] m"),
        (lambda: Criteria(gamma_m=0.8), r"gamma_m must be in \[1, 10\].*got 0.8"),
    ],
)
def test_bad_combinations_and_criteria_are_one_line_naming_the_value(make, match):
    with pytest.raises(InputError, match=match) as err:
        make()
    assert "\n" not in str(err.value)


# -- each check equals its own computation ------------------------------------------------------


def test_the_buckling_factor_of_the_factored_load_is_the_unfactored_over_the_factor(weighed):
    result, verdict = weighed
    (stability,) = by_name(verdict, "stability")
    assert stability.combination == "ULS 1.35 G" and stability.limit == 10.0
    assert_allclose(stability.value, result.buckling.factor / 1.35, rtol=1e-9)
    assert_allclose(stability.utilisation, 10.0 / stability.value, rtol=1e-15)


def test_the_factored_reactions_carry_the_factored_load(snowed):
    result, verdict = snowed
    sm = result.structure
    weight, snow = SelfWeight().forces(sm).sum(axis=0), Snow(500.0).forces(sm).sum(axis=0)
    for combo, total, reaction in zip(
        verdict.combinations, verdict.totals, verdict.reactions, strict=True
    ):
        g, s = combo.factors
        assert_allclose(total, g * weight + s * snow, rtol=1e-12, atol=1e-12 * abs(total[2]))
        assert_allclose(reaction, -total, rtol=1e-9, atol=1e-9 * abs(total[2]))
    assert [c.factors for c in verdict.combinations] == [(1.35, 1.5), (1.0, 1.0)]


def test_the_stress_and_the_deflection_checks_are_their_own_computations(snowed):
    result, verdict = snowed
    sm = result.structure
    static, factor = static_response(
        sm.model,
        1.35 * SelfWeight().forces(sm) + 1.5 * Snow(500.0).forces(sm),
        Supports().fixed(sm),
    )
    (strength,) = by_name(verdict, "strength")
    assert strength.value == pytest.approx(static.max_stress, rel=1e-12)
    assert strength.limit == PP.strength / PP.partial_factor == 31e6 / 1.5
    (stability,) = by_name(verdict, "stability")
    assert_allclose(stability.value, buckling(sm.model, static, factor).factor, rtol=1e-9)
    (deflection,) = by_name(verdict, "deflection")
    assert deflection.value == result.static.max_displacement and deflection.unit == "m"
    feet = sm.model.nodes[sm.feet]
    first = sm.node_sample[sm.feet] == 0
    span = np.linalg.norm(feet[~first].mean(axis=0) - feet[first].mean(axis=0))
    assert_allclose(deflection.limit, span / 250, rtol=1e-12)
    # the governing check is the one of largest utilisation; it stands when every one passes
    assert verdict.governing.utilisation == max(c.utilisation for c in verdict.checks)
    assert verdict.stands == all(c.utilisation <= 1 for c in verdict.checks)


# -- each check made to fail --------------------------------------------------------------------


def test_each_check_fails_on_damaged_input(vault, weighed):
    result, verdict = weighed
    assert verdict.stands
    (stability,) = by_name(verdict, "stability")
    # a required factor above the structure's
    failing = assess(result, Criteria(buckling_safety=min(1000.0, 2 * stability.value)))
    assert not failing.stands and failing.governing.name == "stability"
    # a sheet of almost no strength
    weak = Material.from_values(PP.youngs_modulus, PP.poisson, PP.density, 1e3)
    failing = assess(analyse_load(vault, weak, 1e-3))
    assert not failing.stands and failing.governing.name == "strength"
    assert failing.governing.limit == 1e3 / 1.5
    # a deflection limit below the deflection
    (deflection,) = by_name(verdict, "deflection")
    failing = assess(result, Criteria(deflection_limit=deflection.value / 2))
    assert not failing.stands and failing.governing.name == "deflection"
    assert failing.governing.utilisation == pytest.approx(2.0, rel=1e-12)


def test_a_material_s_factor_is_its_own_with_its_source_or_the_user_s(vault):
    alu = MATERIALS["aluminium"]
    assert alu.partial_factor == 1.1 and "EN 1999-1-1" in alu.partial_factor_source
    assert MATERIALS["paperboard"].partial_factor == 1.3
    result = analyse_load(vault, alu, 1e-3)
    (strength,) = by_name(assess(result), "strength")
    assert strength.limit == alu.strength / 1.1
    (strength,) = by_name(assess(result, Criteria(gamma_m=2.0)), "strength")
    assert strength.limit == alu.strength / 2.0
    # no strength: no strength check, and a note that says so
    soft = Material.from_values(PP.youngs_modulus, PP.poisson, PP.density)
    unmeasured = assess(analyse_load(vault, soft, 1e-3))
    assert not by_name(unmeasured, "strength") and any("no strength" in n for n in unmeasured.notes)


def test_a_load_that_only_stiffens_passes_the_stability_check():
    check = Check("stability", float("inf"), 10.0, "", "ULS 1.5 W", at_least=True)
    assert check.passed and check.utilisation == 0.0 and check.to_dict()["value"] is None


# -- the command line ---------------------------------------------------------------------------


def test_the_tube_example_fails_the_stability_check_in_its_first_line():
    r = run("load", str(EXAMPLES / "tube.toml"), "--samples", "201")
    assert r.returncode == 1 and r.stderr == "", r.stderr
    first = r.stdout.splitlines()[0]
    assert first.startswith("fails: stability under ULS 1.35 G (buckling factor "), first
    d = json.loads(run("load", str(EXAMPLES / "tube.toml"), "--samples", "201", "--json").stdout)
    assert d["verdict"] == "fails" and d["governing"]["name"] == "stability"
    assert_allclose(d["governing"]["value"], d["buckling_factor"] / 1.35, rtol=1e-9)
    for check in d["checks"]:
        assert {"value", "limit", "unit", "utilisation", "combination", "passed"} <= set(check)
    # the load per combination, the weight one line among them
    uls, sls = d["combinations"]
    assert_allclose(uls["applied_load"][2], -1.35 * d["total_weight"], rtol=1e-12)
    assert_allclose(sls["reactions"], d["reactions"], rtol=1e-12, atol=1e-9 * d["total_weight"])


def test_a_thin_vault_under_snow_fails_the_stability_check():
    argv = ("--tubes", "3", "--samples", "201", "--thickness", "0.0003", "--snow", "0.5")
    r = run("load", *argv)
    assert r.returncode == 1 and r.stderr == "", r.stderr
    assert r.stdout.splitlines()[0].startswith("fails: stability under ULS 1.35 G + 1.5 S")
    # the same vault 2 mm thick, asked for a factor it reaches (and 1 cm of deflection), stands
    thick = (*argv[:-3], "0.002", *argv[-2:])
    r = run("load", *thick, "--buckling-safety", "1", "--deflection-limit", "0.01")
    assert r.returncode == 0 and r.stdout.startswith("stands: "), r.stdout


@pytest.mark.parametrize(
    ("argv", "match"),
    [
        (["--deflection-limit", "0"], r"deflection_limit must be in \(0, 1000\] m .*got 0$"),
        (["--buckling-safety", "0.5"], r"buckling_safety must be in \[1, 1000\] .*got 0.5$"),
        (["--gamma-q", "0.9"], r"gamma_q must be in \[1, 10\] .*got 0.9$"),
        (["--gamma-m", "0"], r"gamma_m must be in \[1, 10\] .*got 0$"),
    ],
)
def test_bad_criteria_on_the_command_line_are_one_line(argv, match):
    r = run("load", "--tubes", "3", "--samples", "201", *argv)
    lines = r.stderr.splitlines()
    assert r.returncode == 2 and r.stdout == "" and len(lines) == 1, r.stderr
    assert re.search(match, lines[0]), lines[0]


def test_bad_criteria_in_a_design_file_are_one_line(tmp_path):
    (tmp_path / "design.toml").write_text(
        'kind = "vault"\nsamples = 201\n[vault]\ntubes = 3\n[loads]\ndeflection_limit = 0.0\n'
    )
    r = run("load", "design.toml", cwd=tmp_path)
    lines = r.stderr.splitlines()
    assert r.returncode == 2 and len(lines) == 1, r.stderr
    assert "[loads] deflection_limit must be in (0, 1000] m" in lines[0], lines[0]


def test_the_report_answers_will_it_stand_first(tmp_path):
    argv = ("--tubes", "3", "--samples", "201", "--thickness", "0.0003", "--snow", "0.5")
    r = run("load", *argv, "--out", str(tmp_path / "v"), "--formats", "svg")
    assert r.returncode == 1, r.stderr
    report = (tmp_path / "v" / "report.html").read_text()
    section = report[report.index("<h2>Under load: will it stand?</h2>") :]
    first = section[section.index("<p") : section.index("</p>")]
    assert "It fails</strong>: stability under ULS 1.35 G + 1.5 S" in first, first
    # every check's row, then the load and reactions of every combination
    assert section.index('<td data-label="check">deflection') < section.index("SLS G + S</td>")


def test_the_supported_frequencies_are_the_held_structure_s_own(vault):
    import scipy.linalg as la

    result = analyse_load(vault, PP, 1e-3)
    model, free = result.structure.model, np.flatnonzero(~result.static.fixed.ravel())
    K = model.stiffness.toarray()[np.ix_(free, free)]
    M = model.mass.toarray()[np.ix_(free, free)]
    dense = la.eigh(K, M, eigvals_only=True)[:3]
    assert_allclose(result.supported_eigenvalues, dense, rtol=1e-6)
    # held on its feet it is stiffer than free: its first frequency above the free one
    d = result.to_dict()
    assert d["supported_frequencies"][0] > d["frequencies"][0]
    assert_allclose(d["supported_frequencies"], np.sqrt(dense) / (2 * np.pi), rtol=1e-6)
