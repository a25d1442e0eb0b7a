"""The (u, v) lattice: shared frames, width and area laws, regression domain, rigid folding."""

from dataclasses import replace

import numpy as np
import pytest
from numpy.testing import assert_allclose

from curvefold import (
    Crease,
    InputError,
    Lattice,
    RegressionDomain,
    RegressionError,
    SpaceCurve,
    measure,
)
from curvefold.geometry import Pattern
from curvefold.kernel import ScalarFunction

KAPPA = lambda s: 1.0 + 0.3 * np.sin(s)  # noqa: E731
TAU = lambda s: 0.3 * np.cos(1.5 * s)  # noqa: E731


def make_lattice(samples=801, fold_angle=60.0, widths=(0.2, 0.15)):
    curve = SpaceCurve.from_curvature(KAPPA, TAU, 3.0, samples=samples)
    return Lattice.from_crease(Crease.from_curve(curve, fold_angle=fold_angle), *widths)


@pytest.fixture(scope="module")
def lattice():
    return make_lattice()


def test_lattice_curves_share_curve_one_frame(lattice):
    # 4th-order differences at h = 1/800: truncation ~1e-10
    assert measure.frame_agreement(lattice, [[0, 1], [1, 1], [1, 0], [2, 1], [-1, 0.5]]) < 1e-9


def test_width_and_area_laws(lattice):
    assert measure.width_law_error(lattice) < 1e-12
    assert_allclose(lattice.section_area(), 0.2 * 0.15 * np.sin(np.radians(60)), rtol=1e-13)


def test_erratum_eq12_width_law_uses_tau_cot_alpha(lattice):
    """Eq. (12) prints d ln w/dt = τ/cot α ds/dt; the built widths follow τ cot α instead."""
    X = lattice.points(np.array([[0, 0], [0, 1]], float))
    T = lattice.crease.curve.tangent
    d = X[1] - X[0]
    w_r = np.linalg.norm(d - np.einsum("ij,ij->i", d, T)[:, None] * T, axis=1)
    s = lattice.s
    a = np.radians(30)
    tau = lattice.crease.curve.tau(s)
    # trapezoid, ~1e-7
    integral = np.concatenate([[0], np.cumsum(np.diff(s) * 0.5 * (tau[1:] + tau[:-1]))])
    assert_allclose(w_r, 0.15 * np.exp(integral / np.tan(a)), rtol=1e-6)
    assert np.abs(w_r / (0.15 * np.exp(integral * np.tan(a))) - 1).max() > 0.05
    # and the width is intrinsic: the same at every fold angle
    for f in (10.0, 120.0):
        assert_allclose(lattice.refold(f).width_right, lattice.width_right, rtol=0)


def test_erratum_section_area_is_wl_wr_sin_2alpha(lattice):
    """The paper calls the section area w₁₂ w₄₁; that is only true at 2α = 90°."""
    X = lattice.points(np.array([[0, 0], [0, 1], [1, 0]], float))
    T = lattice.crease.curve.tangent
    area = np.abs(np.einsum("ij,ij->i", np.cross(X[1] - X[0], X[2] - X[0]), T))
    assert_allclose(
        area, lattice.width_left * lattice.width_right * np.sin(np.radians(60)), rtol=1e-12
    )
    assert np.abs(area / (lattice.width_left * lattice.width_right) - 1).min() > 0.1


def test_speed_of_lattice_curves_is_eq16_17(lattice):
    """ds/dt of curve (u, v) is (1 − u w_L/w_lim_L − v w_R/w_lim_R) ds₁/dt (Eq. 16 read
    correctly)."""
    uv = np.array([[0, 1], [1, 0], [1.5, 2.0]])
    X = lattice.points(uv)
    h = lattice.t[1]
    for x, expect in zip(X, lattice.speed(uv)):
        measured = np.linalg.norm(measure.derivative(x, h), axis=1)
        assert_allclose(measured, expect[2:-2], rtol=1e-9)


def test_eq19_holds_between_neighbouring_creases(lattice):
    for a, b in (([0, 0], [0, 1]), ([0, 1], [1, 1]), ([1, 1], [1, 0])):
        assert measure.eq19_residual(lattice, a, b) < 1e-8


#: The paper's construction around a tube: (crease, previous, next, side, ±r, sign of the ruling
#: toward the previous crease).
TUBE_STEPS = (
    (0, 3, 1, "R", 1.0, 1.0),
    (1, 0, 2, "L", 1.0, -1.0),
    (2, 1, 3, "R", -1.0, -1.0),
    (3, 2, 0, "L", -1.0, 1.0),
)


def test_tube_built_crease_by_crease_closes():
    """Each crease rebuilt from the one before by the construction step, from that crease's own
    measured frame, κ and β (Eqs. 5–6, 12–13 corrected), lands on the lattice curve, and the
    fourth step lands on curve 1: fourth-order differences, 16× smaller as h halves (measured
    3.7e-8, 2.3e-9, 1.6e-10 of the strip width at 201, 401, 801 samples)."""
    worst = []
    for samples in (401, 801):
        lattice = make_lattice(samples=samples)
        x = lattice.points(np.array([[0, 0], [0, 1], [1, 1], [1, 0]], float))
        T = lattice.crease.curve.frames[2:-2, :, 0]
        errors = []
        for c, prev, nxt, side, sign, back in TUBE_STEPS:
            rebuilt = measure.rebuilt_strip(
                x[c],
                back * (x[prev] - x[c]),
                x[nxt],
                lattice.s[1],
                alpha=np.radians(30),
                side=side,
                sign=sign,
            )
            errors.append(
                np.max(
                    measure.norm(rebuilt - x[nxt, 2:-2])
                    / measure.tangent_line_distance(x[c, 2:-2], x[nxt, 2:-2], T)
                )
            )
        worst.append(max(errors))
    assert worst[1] < 1e-9 and worst[0] / worst[1] > 12, worst
    # the same step taken for another fold angle (2α = 120° for 60°) misses by O(1): the measurement
    # can fail
    wrong = measure.rebuilt_strip(
        x[0], x[3] - x[0], x[1], lattice.s[1], alpha=np.radians(60), side="R", sign=1.0
    )
    assert np.max(measure.norm(wrong - x[1, 2:-2])) > 0.01


def test_regression_domain_queries(lattice):
    dom = lattice.domain
    assert dom.contains([0, 0])
    assert_allclose(dom.margin(np.zeros(2)), 1.0)
    for direction in ([1, 1], [1, 0], [0, -1], [-1, 1]):
        lam = float(dom.extent(direction))
        if np.isfinite(lam):
            d = np.asarray(direction, float)
            assert dom.contains(0.999 * lam * d) and not dom.contains(1.001 * lam * d)
            assert abs(float(dom.margin(lam * d))) < 1e-12
    poly = dom.polygon(box=50.0)
    assert poly.shape[1] == 2 and dom.contains(0.99 * poly).all()


def test_regression_refused_with_limit():
    lat = make_lattice()
    lam = float(lat.domain.extent([1, 1]))
    with pytest.raises(
        RegressionError,
        match=r"lattice curve \(u, v\) = \(\d+, \d+\) passes the "
        r"curve of regression .* the limit is \(u, v\) = ",
    ):
        lat.check([[np.ceil(lam) + 1, np.ceil(lam) + 1]])
    with pytest.raises(
        RegressionError, match=r"widths: lattice curve \(u, v\) = \([01], [01]\) " r"passes"
    ):
        make_lattice(widths=(0.2 * 3 * lam, 0.15 * 3 * lam))


def test_flat_state_is_planar_and_isometric(lattice):
    flat = lattice.refold(0.0)
    uv = np.array([[0, 0], [0, 1], [1, 1], [1, 0]], float)
    X0 = flat.points(uv)
    normal = flat.crease.curve.binormal[0]
    assert np.abs((X0 - X0[0, 0]) @ normal).max() < 1e-13  # one common plane
    assert_allclose(flat.crease.curve.tau(flat.s), 0.0, atol=0)
    assert_allclose(flat.crease.curve.kappa(flat.s), lattice.kappa_2d(flat.s), rtol=1e-15)


def test_refold_keeps_intrinsic_quantities(lattice):
    for f in (0.0, 30.0, 120.0, 179.0):
        other = lattice.refold(f)
        assert_allclose(other.beta, lattice.beta, rtol=0)
        assert_allclose(other.crease.kappa_2d, lattice.crease.kappa_2d, rtol=1e-14)
        assert_allclose(other.domain.a, lattice.domain.a, rtol=1e-13, atol=1e-15)
        # τ = τ₀ tan α / tan α₀
        assert_allclose(
            other.crease.curve.tau(lattice.s),
            TAU(lattice.s) * np.tan(np.radians(f / 2)) / np.tan(np.radians(30)),
            atol=1e-13,
        )
    with pytest.raises(
        InputError,
        match=r"fold_angle must be in \[0°, 180°\), got 180 \(2α = "
        r"180° would need infinite curvature",
    ):
        lattice.refold(180)


def test_refold_anchors(lattice):
    start = lattice.refold(120.0, anchor="start").crease.curve
    mid = lattice.refold(120.0, anchor="middle").crease.curve
    m = (len(lattice.s) - 1) // 2
    c = lattice.crease.curve
    assert_allclose(start.frames[0], c.frames[0], atol=1e-15)
    assert_allclose(mid.frames[m], c.frames[m], atol=1e-14)
    assert_allclose(mid.points[m], c.points[m], atol=1e-14)
    # the two differ by one rigid motion
    R = mid.frames[0] @ start.frames[0].T
    assert_allclose(mid.points - mid.points[0], (start.points - start.points[0]) @ R.T, atol=1e-13)
    with pytest.raises(InputError, match="anchor must be 'start' or 'middle'"):
        lattice.refold(90, anchor="end")


def test_batched_folding_matches_refold(lattice):
    uv = np.array([[0, 0], [1, 1], [2, 0.5]])
    angles = [0.0, 45.0, 170.0]
    batch = lattice.fold_points(uv, angles, anchor="middle")
    for k, f in enumerate(angles):
        assert_allclose(batch[k], lattice.refold(f, anchor="middle").points(uv), atol=1e-15)


def test_every_corner_of_the_unit_cell_is_checked():
    """(1, 1) can be valid while (1, 0) is not: the domain is a polygon, not a box."""
    # |β'| < κ_2D everywhere: the left side regresses (a > 0), the right side never (b < 0)
    curve = SpaceCurve.from_curvature(1.0, lambda s: -0.3 * (s - 1.0), 2.0, samples=201)
    crease = Crease.from_curve(curve, fold_angle=90.0)
    unit = Lattice.from_crease(crease, 1e-3, 1e-3)
    a, b = unit.domain.a, unit.domain.b
    assert (a > 0).all() and (b < 0).all()
    f_left = 1.2 / a.max()  # (1, 0) reaches 1.2× past its limit ...
    f_right = 2 * ((f_left * a - 1).clip(0) / -b).max()  # ... while (1, 1) keeps margin
    lat = Lattice(
        crease, Pattern.from_crease(crease, unit.width_left * f_left, unit.width_right * f_right)
    )
    assert (
        lat.domain.contains([1, 1])
        and lat.domain.contains([0, 1])
        and not lat.domain.contains([1, 0])
    )
    with pytest.raises(RegressionError, match=r"widths: lattice curve \(u, v\) = \(1, 0\)"):
        Lattice.from_crease(crease, 1e-3 * f_left, 1e-3 * f_right)


def test_lattice_needs_constant_fold_angle_and_positive_widths():
    curve = SpaceCurve.from_curvature(KAPPA, TAU, 3.0, samples=101)
    with pytest.raises(InputError, match="constant fold angle"):
        Lattice.from_crease(Crease.from_curve(curve, fold_angle=lambda s: 60 + s), 0.1, 0.1)
    with pytest.raises(InputError, match=r"width_left must be a finite number > 0, got -0.1"):
        Lattice.from_crease(Crease.from_curve(curve), -0.1, 0.1)


def test_defect_2_a_regression_margin_never_passes_as_nan():
    """κ = 1 + √s with widths 5: β' at s = 0 came out NaN (κ sampled at s < 0), NaN ≤ 0 is
    False, and the design was accepted. Now β' is finite there and the design is refused."""
    curve = SpaceCurve.from_curvature(lambda s: 1 + np.sqrt(s), 0.3, 2.0, samples=201)
    crease = Crease.from_curve(curve, fold_angle=90.0)
    assert np.isfinite(crease.regression_rates()).all()
    with pytest.raises(
        RegressionError,
        match=r"widths: lattice curve \(u, v\) = \(1, 1\) passes " r"the curve of regression",
    ):
        Lattice.from_crease(crease, 5.0, 5.0)


class _NanSlope(ScalarFunction):
    """A ruling angle whose derivative is damaged: NaN at s = 0."""

    def __init__(self, beta):
        self.beta = beta

    def value(self, s):
        return self.beta(s)

    def derivative(self, s):
        return np.where(s == 0, np.nan, self.beta.derivative(s))


def test_nan_fails_every_validity_test(lattice):
    crease = lattice.crease
    damaged = Crease(
        crease.curve, crease.alpha, _NanSlope(crease.beta_left), _NanSlope(crease.beta_left)
    )
    with pytest.raises(
        InputError,
        match=r"regression rate 1/w_lim on the left .* must be " r"finite; at s = 0 it is nan",
    ):
        Lattice.from_crease(damaged, 0.2, 0.15)
    with pytest.raises(
        RegressionError, match="width on the left must stay below the regression limit nan"
    ):
        damaged.surface(width=0.01)
    assert np.isnan(damaged.regression_limits()[0][0])  # not +∞ ("no limit")
    a = np.array(lattice.domain.a)
    a[5] = np.nan
    broken = Lattice(
        crease, replace(lattice.pattern, domain=RegressionDomain(lattice.t, a, lattice.domain.b))
    )
    assert not broken.domain.contains([0.5, 0.5])
    with pytest.raises(
        RegressionError, match=r"cells: lattice curve \(u, v\) = \(0.5, 0.5\) " r"passes"
    ):
        broken.check([[0.5, 0.5]])


@pytest.mark.parametrize(
    ("widths", "tau", "length", "message"),
    [
        (
            (1e-300, 0.15),
            TAU,
            3.0,
            r"width_left w\(t\) = 8.19e-301 at s = 1.05 is below 1e-09 of the "
            r"structure's size 3: ",
        ),
        ((1e-8, 0.15), TAU, 3.0, None),  # 3e-9 of the size: resolved
        (
            (0.2, 0.2),
            lambda s: np.tan(s),
            6.0,
            r"width_left w\(t\) = 2.27e-09 at s = 4.74 is below "
            r"1e-09 of the structure's size 1.76e\+07: ",
        ),
    ],
)
def test_a_strip_narrower_than_rounding_is_refused(widths, tau, length, message):
    """Coordinates of size L resolve a strip of width 1e-9 L by 10⁷ ulps; a narrower one has
    edges that round to nothing (zero-length edges broke the certificate). τ = tan s spreads
    the widths over 16 decades along t."""
    crease = Crease.from_curve(
        SpaceCurve.from_curvature(KAPPA, tau, length, samples=101), fold_angle=90.0
    )
    if message is None:
        assert Pattern.from_crease(crease, *widths).width_left.min() > 0
        return
    with pytest.raises(InputError, match=message):
        Pattern.from_crease(crease, *widths)
