"""Curved creases: developable rulings, the paper's errata on signs, single folds, regression."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from curvefold import Crease, InputError, RegressionError, SpaceCurve
from curvefold.analysis._measure import derivative, developability_residual
from curvefold.geometry._crease import QUADRANTS
from curvefold.geometry._crease_laws import ruling_vectors
from curvefold.geometry._fold_angle import check_fold_angle, check_fold_angles, half_angle

KAPPA = lambda s: 1.0 + 0.3 * np.sin(s)  # noqa: E731
TAU = lambda s: 0.4 * np.cos(1.5 * s)  # noqa: E731


@pytest.fixture(scope="module")
def curve():
    return SpaceCurve.from_curvature(KAPPA, TAU, 3.0, samples=1201)


def residual_with_beta(crease: Crease, beta: np.ndarray) -> float:
    """Developability residual |r'·p| of rulings at angle β (both sides) on this crease."""
    a = crease.alpha(crease.s)
    rl, rr = ruling_vectors(crease.curve.frames, a, beta, beta)
    pl, pr = crease.normals()
    h = crease.s[1]
    return max(
        np.abs(np.einsum("ij,ij->i", derivative(r, h), p[2:-2])).max()
        for r, p in ((rl, pl), (rr, pr))
    )


@pytest.mark.parametrize("fold_angle", [20.0, 90.0, 150.0])
def test_constant_fold_angle_surfaces_are_developable(curve, fold_angle):
    crease = Crease.from_curve(curve, fold_angle=fold_angle)
    # 4th-order differences of rulings at h = 2.5e-3: truncation ~1e-10
    assert developability_residual(crease) < 1e-9


def test_varying_fold_angle_surfaces_are_developable(curve):
    crease = Crease.from_curve(curve, fold_angle=lambda s: 70 + 25 * np.sin(2 * s))
    assert crease.fold_angle is None
    assert developability_residual(crease) < 1e-8
    # the two sides now have different ruling angles (Eq. 3: α' splits them)
    assert np.abs(crease.beta_left(crease.s) - crease.beta_right(crease.s)).max() > 0.1


def test_erratum_eq9_printed_torsion_sign_is_not_developable(curve):
    """Eq. (9) prints cot β = −τ/(κ_2D tan α); the surfaces it gives are not developable."""
    crease = Crease.from_curve(curve, fold_angle=90.0)
    a = 0.25 * np.pi
    k2 = curve.kappa(curve.s) * np.cos(a)
    printed = np.arctan2(k2 * np.tan(a), -curve.tau(curve.s))
    corrected = np.arctan2(k2 * np.tan(a), curve.tau(curve.s))
    assert residual_with_beta(crease, corrected) < 1e-9
    assert residual_with_beta(crease, printed) > 0.1
    # the tangent plane turns by tens of degrees along a ruling of the printed surface
    assert np.degrees(np.abs(printed - corrected).max()) > 20


def test_erratum_eq4_sign_and_eq3_as_printed():
    """Eq. (3) holds as printed; Eq. (4) holds with τ/tan α = +½ κ_2D (cot β_L + cot β_R)."""
    curve = SpaceCurve.from_curvature(KAPPA, TAU, 3.0, samples=601)
    crease = Crease.from_curve(curve, fold_angle=lambda s: 80 + 20 * np.cos(s))
    s = crease.s[5:-5]
    a, da = crease.alpha(s), crease.alpha.derivative(s)
    k2 = curve.kappa(s) * np.cos(a)
    cl, cr = 1 / np.tan(crease.beta_left(s)), 1 / np.tan(crease.beta_right(s))
    assert_allclose(da / np.tan(a), 0.5 * k2 * (cl - cr), atol=1e-9)  # Eq. (3)
    assert_allclose(curve.tau(s) / np.tan(a), 0.5 * k2 * (cl + cr), atol=1e-9)  # Eq. (4) corrected
    assert np.abs(curve.tau(s) / np.tan(a) + 0.5 * k2 * (cl + cr)).max() > 0.5  # Eq. (4) as printed


def test_single_fold_from_pattern_has_excess_freedom():
    """One crease pattern (κ_2D, length) with two ruling layouts folds into two shapes (Fig. 08)."""
    L = 2.5
    a = Crease.from_pattern(0.8, 90.0, 90.0, L, fold_angle=60.0, samples=801)
    b = Crease.from_pattern(
        0.8, lambda s: 75 + 10 * s, lambda s: 95 - 5 * s, L, fold_angle=60.0, samples=801
    )
    for c in (a, b):
        assert developability_residual(c) < 1e-8
        assert_allclose(c.kappa_2d, 0.8, rtol=1e-10)  # same crease pattern
        assert_allclose(np.diff(c.curve.s), L / 800, rtol=1e-12)
    # layout a: β = 90° on both sides → α constant, τ = 0: a planar circular arc
    assert_allclose(np.degrees(2 * a.alpha(a.s)), 60.0, atol=1e-10)
    assert np.abs(a.curve.points[:, 2]).max() < 1e-12
    # layout b: the fold angle drifts and the crease twists out of plane
    assert np.abs(np.degrees(2 * b.alpha(b.s)) - 60).max() > 5
    assert np.abs(b.curve.points - a.curve.points).max() > 0.02  # vs ~1e-12 agreement above


def test_single_fold_refuses_fold_angle_leaving_range():
    with pytest.raises(InputError, match=r"fold angle 2α leaves \(0°, 180°\) at s = "):
        Crease.from_pattern(1.0, 30.0, 150.0, 20.0, fold_angle=170.0)


@pytest.mark.parametrize(
    "kwargs,match",
    [
        (dict(kappa_2d=-1.0), r"kappa_2d must be > 0 everywhere; at s = 0 it is -1"),
        (dict(beta_left=190.0), r"beta_left must be in \(0°, 180°\); at s = 0 it is 190°"),
        (
            dict(fold_angle=180.0),
            r"fold_angle must be in \(0°, 180°\), got 180.0 \(2α = 180° "
            r"would need infinite curvature",
        ),
        (dict(fold_angle=0.0), r"fold_angle must be in \(0°, 180°\), got 0.0"),
    ],
)
def test_pattern_bad_input(kwargs, match):
    args = dict(kappa_2d=1.0, beta_left=90.0, beta_right=90.0, length=1.0) | kwargs
    with pytest.raises(InputError, match=match):
        Crease.from_pattern(
            args.pop("kappa_2d"),
            args.pop("beta_left"),
            args.pop("beta_right"),
            args.pop("length"),
            **args,
        )


@pytest.mark.parametrize("value", ["ninety", None, [90.0, 45.0]])
def test_a_fold_angle_that_is_not_a_number_is_refused(value):
    with pytest.raises(InputError, match=r"^fold_angle must be a number, got "):
        half_angle(value)
    with pytest.raises(InputError, match=r"^fold_angle must be a number, got "):
        check_fold_angle(value)


def test_fold_angles_are_checked_and_given_in_degrees():
    assert check_fold_angles(np.radians([0.0, 60.0]), degrees=False).tolist() == pytest.approx(
        [0.0, 60.0], abs=1e-12
    )
    assert check_fold_angle(60.0) == 60.0 and check_fold_angle(0.0, allow_flat=True) == 0.0
    for values, match in (
        ([], "non-empty"),
        ([[1.0, 2.0]], "non-empty"),
        (["x"], "a sequence of numbers"),
        ([0.0, 180.0], r"\[0°, 180°\)"),
    ):
        with pytest.raises(InputError, match=rf"^motion must .*{match}"):
            check_fold_angles(values, name="motion")


def test_fold_angle_function_out_of_range_names_location(curve):
    with pytest.raises(
        InputError,
        match=r"fold_angle must be in \(0°, 180°\) along the whole " r"crease; at s = 2 it is 180°",
    ):
        Crease.from_curve(curve, fold_angle=lambda s: 60 + 60 * s)


def test_rulings_normals_and_quadrants(curve):
    crease = Crease.from_curve(curve, fold_angle=70.0)
    rl, rr = crease.rulings()
    pl, pr = crease.normals()
    T = curve.tangent
    for r, p in ((rl, pl), (rr, pr)):
        assert_allclose(np.linalg.norm(r, axis=1), 1, rtol=1e-14)
        assert np.abs(np.einsum("ij,ij->i", r, p)).max() < 1e-14  # p is normal to its surface
        assert np.abs(np.einsum("ij,ij->i", T, p)).max() < 1e-14
    # the angle between the surfaces at the crease: π − 2α for folds, 2α for seams
    assert_allclose(crease.dihedral_angle("L+R+"), np.radians(110), rtol=1e-14)
    assert_allclose(crease.dihedral_angle("L+R-"), np.radians(70), rtol=1e-14)
    n_l, n_r = np.cross(T, rl), np.cross(T, rr)
    cos = (
        np.einsum("ij,ij->i", n_l, n_r) / np.linalg.norm(n_l, axis=1) / np.linalg.norm(n_r, axis=1)
    )
    assert_allclose(np.arccos(cos), np.radians(110), atol=1e-12)
    assert {k for _, _, k in QUADRANTS.values()} == {"fold", "seam"}


def test_regression_limit_matches_finite_difference_cusp():
    """Just inside w_lim the ruled surface's edge curve runs forward; just past it, it reverses."""
    # τ decreasing makes β grow faster than κ_2D near s = 1: a finite limit on the right
    curve = SpaceCurve.from_curvature(1.0, lambda s: -0.8 * (s - 1.0), 2.0, samples=2001)
    crease = Crease.from_curve(curve, fold_angle=90.0)
    wr = crease.regression_limits()[1]
    w_star, i = np.min(wr), int(np.argmin(wr))
    assert np.isfinite(w_star)
    h = curve.s[1]
    T = curve.tangent
    for factor, forward in ((0.98, True), (1.02, False)):
        # the ruled surface's edge at width factor·w_lim (built by hand: surface() refuses past it)
        edge = (
            curve.points
            + (factor * w_star / np.sin(crease.beta_right(curve.s)))[:, None] * crease.rulings()[1]
        )
        speed = np.einsum("ij,ij->i", derivative(edge, h), T[2:-2])
        assert bool(speed.min() > 0) == forward, (factor, speed.min(), curve.s[i])
        assert_allclose(speed.min(), 1 - factor, atol=1e-6)  # the speed factor of Eq. 16


def test_surface_refuses_width_past_regression():
    curve = SpaceCurve.from_curvature(1.0, lambda s: -0.8 * (s - 1.0), 2.0, samples=401)
    crease = Crease.from_curve(curve, fold_angle=90.0)
    lim = np.min(crease.regression_limits()[1])
    with pytest.raises(
        RegressionError,
        match=r"width on the right must stay below the "
        r"regression limit .* \(reached at s = .*\), got",
    ):
        crease.surface("L+R+", width=(0.01, 1.5 * lim))
    with pytest.raises(InputError, match="quadrant must be one of"):
        crease.surface("L+R+R-", width=0.01)
