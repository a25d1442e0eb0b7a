"""A vault from its span, rise and apex proportion (curvefold.vault._targets), in the API and on
the command line."""

import math
import re

import numpy as np
import pytest

from _cli import run
from curvefold.app import _build as build_module
from curvefold.app import default_design
from curvefold.kernel import InputError, InternalError
from curvefold.vault import Vault, VaultDesign, fit_targets, proportion_change, solve_symmetric_arch
from curvefold.vault import _targets as targets_module

#: Brent's method stops at 1e-13 in a; rise/span moves by O(1) per unit of a and the radius is a
#: quotient of two measured lengths, so the targets are met to ~1e-12: 1e-9 is the fit's own
#: tolerance.
RTOL = 1e-9
SAMPLES = 201


def _measured(design: VaultDesign) -> tuple[float, float, float]:
    s = Vault.from_design(design).summary()
    return s["span"], s["rise"], s["p_xz"]


def test_targets_measured_on_random_vaults_are_met_again():
    """Manufactured solutions: build random vaults, measure them, fit vaults to those numbers."""
    rng = np.random.default_rng(11)
    for a, p_xy, radius in zip(
        rng.uniform(0.0, 0.25, 3), rng.uniform(0.5, 1.0, 3), rng.uniform(0.5, 3.0, 3)
    ):
        truth = VaultDesign(a=a, p_xy=p_xy, radius=radius, tubes=5, samples=SAMPLES)
        span, rise, p_xz = _measured(truth)
        fit = fit_targets(
            VaultDesign(a=a + 0.01, tubes=5, samples=SAMPLES), span=span, rise=rise, p_xz=p_xz
        )
        assert fit.reached and fit.message == ""
        np.testing.assert_allclose([fit.span, fit.rise, fit.p_xz], [span, rise, p_xz], rtol=RTOL)
        # what it reports is what the design measures
        assert _measured(fit.design) == (fit.span, fit.rise, fit.p_xz)
        # at one p_xz, rise/span can take a value at two a: the fit takes the one nearest the a it
        # starts from
        np.testing.assert_allclose(
            [fit.design.a, fit.design.p_xy, fit.design.radius], [a, p_xy, radius], rtol=1e-8
        )


def test_one_target_sets_one_parameter():
    base = VaultDesign(tubes=9, samples=SAMPLES)
    span1, rise1, _ = _measured(base)
    by_span = fit_targets(base, span=3.0)
    assert (
        math.isclose(by_span.design.radius, 3.0 / span1, rel_tol=1e-14)
        and by_span.design.a == base.a
    )
    by_rise = fit_targets(base, rise=2.0)
    assert math.isclose(by_rise.design.radius, 2.0 / rise1, rel_tol=1e-14)
    by_p_xz = fit_targets(base, p_xz=1.1)
    change = proportion_change(
        base.a, solve_symmetric_arch(base.a).kappa0_s0, fold_angle=base.fold_angle
    )
    assert (
        math.isclose(by_p_xz.design.p_xy, 1.1 / change**2, rel_tol=1e-14)
        and by_p_xz.design.radius == 1.0
    )
    assert fit_targets(base).design == base


def test_out_of_reach_gives_the_nearest_design_and_says_so():
    base = VaultDesign(tubes=9, samples=SAMPLES)
    fit = fit_targets(base, span=3.0, rise=2.9)
    assert not fit.reached
    assert fit.message.startswith(
        "rise/span = 0.966667 is out of reach for width = 0.08 and 9 tubes"
    )
    assert (
        "the nearest vault has a = " in fit.message and "(asked: span 3, rise 2.9)" in fit.message
    )
    with pytest.raises(InputError, match="out of reach"):
        fit.require()
    # the nearest meets the span exactly and no scanned vault of the family comes closer to the
    # ratio
    assert math.isclose(fit.span, 3.0, rel_tol=RTOL)
    ratios = []
    for a in np.linspace(0.0, 1.27, targets_module.SCAN_POINTS):
        try:
            s, r, _ = _measured(VaultDesign(a=a, tubes=9, samples=SAMPLES))
        except ValueError:
            continue
        ratios.append(r / s)
    assert abs(fit.rise / fit.span - 2.9 / 3.0) <= min(abs(np.array(ratios) - 2.9 / 3.0)) + 1e-12


def test_a_fit_that_misses_its_targets_is_reported_as_a_bug(monkeypatch):
    """The fit measures the design it returns: a wrong proportion law makes it miss p_xz and say
    so."""
    monkeypatch.setattr(
        targets_module,
        "proportion_change",
        lambda a, k, fold_angle: 1.01 * proportion_change(a, k, fold_angle=fold_angle),
    )
    with pytest.raises(InternalError, match="the target fit measures"):
        fit_targets(VaultDesign(tubes=5, samples=SAMPLES), p_xz=1.2)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"span": -1.0}, r"span must be > 0 model units, got -1.0"),
        ({"p_xz": 500.0}, r"p_xz must be in \(0, 100\], got 500.0"),
    ],
)
def test_refused_targets(kwargs, message):
    with pytest.raises(InputError, match=message):
        fit_targets(VaultDesign(samples=SAMPLES), **kwargs)


def test_command_line_targets():
    import json

    result = run(
        "vault",
        "--span",
        "3",
        "--rise",
        "1.7",
        "--p-xz",
        "1.2",
        "--tubes",
        "5",
        "--samples",
        str(SAMPLES),
        "--json",
    )
    assert result.returncode == 0, result.stderr
    payload = json.loads(result.stdout)
    np.testing.assert_allclose(
        [payload["span"], payload["rise"], payload["p_xz"]], [3.0, 1.7, 1.2], rtol=RTOL
    )
    for argv, message in [
        (
            ("--span", "3", "--radius", "2"),
            "error: --span sets radius: give --span or --radius, not both",
        ),
        (
            ("--span", "3", "--rise", "2.9", "--tubes", "9"),
            "error: rise/span = 0.966667 is out of reach",
        ),
        (("--rise", "x"), "error: --rise: must be a number"),
    ]:
        result = run("vault", *argv, "--samples", str(SAMPLES), "--json")
        assert result.returncode == 2 and result.stdout == ""
        assert (
            result.stderr.startswith(f"curvefold: {message}") and result.stderr.count("\n") == 1
        ), result.stderr


def _stated_ranges(message: str) -> list[tuple[float, float]]:
    """The rise/span ranges a refusal says the family reaches."""
    reach = message.split("reach rise/span ", 1)[1].split(" (they stand", 1)[0]
    return [
        (float(lo), float(hi)) for lo, hi in re.findall(r"from ([\d.e+-]+) to ([\d.e+-]+)", reach)
    ]


def test_a_refusal_agrees_with_the_range_it_states():
    """Span 4 at p_xz 1.5 with 9 tubes: the family stands on two runs of a (regression cuts out
    the middle). A ratio inside a range the refusal states is met; one outside every stated
    range is refused."""
    base = VaultDesign(tubes=9, samples=SAMPLES)
    refused = fit_targets(base, span=4.0, rise=2.5, p_xz=1.5)
    ranges = _stated_ranges(refused.message)
    assert not refused.reached and len(ranges) == 2 and "for a in [0, 0.3" in refused.message
    assert not any(lo <= 2.5 / 4.0 <= hi for lo, hi in ranges)
    for lo, hi in ranges:  # every stated range is reached at its ends and inside
        for ratio in (lo, 0.5 * (lo + hi), hi):
            fit = fit_targets(base, span=4.0, rise=4.0 * ratio, p_xz=1.5)
            assert fit.reached, (ratio, fit.message)
            np.testing.assert_allclose(
                [fit.span, fit.rise, fit.p_xz], [4.0, 4.0 * ratio, 1.5], rtol=RTOL
            )


def test_tubes_max_with_span_and_rise_chooses_a_count_and_says_which():
    base = VaultDesign(samples=SAMPLES)  # tubes = None: the most before regression
    fit = fit_targets(base, span=4.0, rise=2.5, p_xz=1.5)  # out of reach with 9 tubes (above)
    assert fit.reached and fit.design.tubes == 6
    assert fit.note.startswith(
        'tubes = "max": 6 tubes, the most that reach these targets (at most 9'
    )
    np.testing.assert_allclose([fit.span, fit.rise, fit.p_xz], [4.0, 2.5, 1.5], rtol=RTOL)
    with pytest.raises(
        InputError,
        match='with tubes = "max" no count from 9 down to 1 reaches '
        "these targets; rise/span = 0.966667",
    ):
        fit_targets(base, span=3.0, rise=2.9).require()


def test_a_fitted_design_passes_its_own_certificate():
    """Span 6, rise 3.6, p_xz 1.3 and 9 tubes need a = 1.253, near the end of the family, where
    the arch root is solved to 1e-14; the design the fit returns passes every check at its
    samples."""
    design, note = build_module.fit_vault_targets(
        default_design("vault").overrides(tubes=9), span=6.0, rise=3.6, p_xz=1.3
    )
    assert note == "" and design.vault.a == pytest.approx(1.253, abs=1e-3)
    result = run("vault", "--span", "6", "--rise", "3.6", "--p-xz", "1.3", "--tubes", "9", "--json")
    assert result.returncode == 0, result.stderr  # exit 1 would be a failed check


def test_a_fit_failing_its_certificate_is_refused(monkeypatch):
    from curvefold.analysis import _certificate as certificate

    real = certificate.certify

    def damaged(*args, **kwargs):  # the arch condition of every design fails
        found = real(*args, **kwargs)
        from dataclasses import replace

        checks = tuple(
            replace(c, status="fail") if c.name == "arch_condition" else c for c in found.checks
        )
        return replace(found, checks=checks)

    monkeypatch.setattr(certificate, "certify", damaged)
    with pytest.raises(
        InputError,
        match=r"the vault that meets these targets \(a = [\d.]+, p_xy "
        r"= [\d.]+\) fails its certificate: arch_condition fail at ",
    ):
        build_module.fit_vault_targets(
            default_design("vault").overrides(tubes=4, samples=SAMPLES), span=3.0, rise=1.7
        )
