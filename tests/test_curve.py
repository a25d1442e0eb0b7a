"""Space curves: closed forms, convergence order, rounding, bad input."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from curvefold import InputError, SpaceCurve
from curvefold.geometry._curve import MAX_SAMPLES
from curvefold.kernel._lie import dual_to_motion, exp_dual, magnus6, prefix_dual

KAPPA = lambda s: 1.0 + 0.5 * np.sin(s)  # noqa: E731  manufactured smooth curvature
TAU = lambda s: 0.3 * np.cos(2.0 * s)  # noqa: E731


def helix(kappa: float, tau: float, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Closed-form helix with T(0), N(0), B(0) = e1, e2, e3: points (n, 3), frames (n, 3, 3).

    The frame turns about the fixed Darboux axis d = (τ T + κ B)/ω at rate ω = √(κ² + τ²).
    """
    ld = np.longdouble  # extended precision keeps the reference below the tested rounding
    kappa, tau, s = ld(kappa), ld(tau), np.asarray(s, ld)
    w = np.sqrt(kappa * kappa + tau * tau)
    d = np.array([tau, ld(0), kappa]) / w
    K = np.array([[0, -d[2], d[1]], [d[2], 0, -d[0]], [-d[1], d[0], 0]], dtype=ld)
    th = w * s
    R = np.eye(3) + np.sin(th)[:, None, None] * K + (1 - np.cos(th))[:, None, None] * (K @ K)
    e1 = np.array([1, 0, 0], dtype=ld)
    par = (e1 @ d) * d
    x = (
        s[:, None] * par
        + (np.sin(th) / w)[:, None] * (e1 - par)
        + ((1 - np.cos(th)) / w)[:, None] * np.cross(d, e1)
    )
    return x.astype(float), R.astype(float)


def test_circle_closes_exactly():
    c = SpaceCurve.from_curvature(0.5, 0.0, 4 * np.pi, samples=9)
    assert_allclose(c.points[-1], c.points[0], atol=1e-14)
    # every sample on the circle of radius 2 about (0, 2, 0)
    assert_allclose(np.linalg.norm(c.points - [0, 2, 0], axis=1), 2.0, rtol=1e-14)


@pytest.mark.parametrize("kappa,tau", [(1.0, 0.5), (2.0, -1.5), (0.3, 3.0)])
def test_helix_exact_to_rounding(kappa, tau):
    s = np.linspace(0, 25.0, 51)  # steps of ω h up to 1.5 rad: still exact
    c = SpaceCurve.from_curvature(kappa, tau, 25.0, samples=51)
    x, R = helix(kappa, tau, s)
    assert_allclose(c.points, x, atol=2e-14 * 25)
    assert_allclose(c.frames, R, atol=1e-14)


def test_manufactured_solution_converges_at_order_six():
    # The reference is the same method on a 64× finer grid (error there ~1e-15).
    L = 6.0
    ref = SpaceCurve.from_curvature(KAPPA, TAU, L, samples=64 * 80 + 1)
    errors = []
    for n in (11, 21, 41, 81):
        c = SpaceCurve.from_curvature(KAPPA, TAU, L, samples=n)
        errors.append(
            max(
                np.abs(c.points[-1] - ref.points[-1]).max(),
                np.abs(c.frames[-1] - ref.frames[-1]).max(),
            )
        )
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(orders > 5.7), orders  # sixth order in both frame and position
    assert errors[-1] < 1e-10


def test_agrees_with_independent_integrator():
    from scipy.integrate import solve_ivp

    def rhs(s, y):
        T, N, B = y[0:3], y[3:6], y[6:9]
        return np.concatenate([KAPPA(s) * N, -KAPPA(s) * T + TAU(s) * B, -TAU(s) * N, T])

    s = np.linspace(0, 6.0, 301)
    sol = solve_ivp(
        rhs,
        (0, 6.0),
        np.concatenate([np.eye(3).ravel(), np.zeros(3)]),
        method="DOP853",
        rtol=1e-13,
        atol=1e-13,
        t_eval=s,
    )
    c = SpaceCurve.from_curvature(KAPPA, TAU, 6.0, samples=301)
    assert_allclose(c.points, sol.y[9:].T, atol=1e-11)
    assert_allclose(c.tangent, sol.y[0:3].T, atol=1e-11)


def test_rounding_stays_below_1e13_at_a_million_samples():
    # A helix is exact in each step, so what is left is rounding in the product of 10⁶
    # steps. Orthonormality does not drift at all; the frame's angle drifts like
    # ε × (total turning), the rounding of the steps themselves: 2e-14 over 18 turns here.
    L, n = 100.0, 1_000_001
    c = SpaceCurve.from_curvature(1.0, 0.5, L, samples=n)
    x, R = helix(1.0, 0.5, c.s[::997])
    F = c.frames[::997]
    assert np.abs(np.einsum("nji,njk->nik", F, F) - np.eye(3)).max() < 1e-14
    assert np.abs(F - R).max() < 1e-13
    assert np.abs(c.points[::997] - x).max() / L < 1e-14


def test_sampled_inputs_match_callables():
    L = 4.0
    grid = np.linspace(0, L, 401)
    a = SpaceCurve.from_curvature(KAPPA, TAU, L, samples=101)
    b = SpaceCurve.from_curvature(KAPPA(grid), TAU(grid), L, samples=101)
    # cubic-spline interpolation of 401 samples: error ~h⁴ ≈ 1e-8
    assert_allclose(b.points, a.points, atol=1e-7)


def test_initial_point_and_frame_move_the_curve_rigidly():
    rng = np.random.default_rng(3)
    Q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    Q *= np.sign(np.linalg.det(Q))
    a = SpaceCurve.from_curvature(KAPPA, TAU, 3.0, samples=61)
    b = SpaceCurve.from_curvature(KAPPA, TAU, 3.0, samples=61, origin=[1, 2, 3], frame=Q)
    assert_allclose(b.points, a.points @ Q.T + [1, 2, 3], atol=1e-14)
    assert_allclose(b.frames, Q @ a.frames, atol=1e-14)


def test_lie_building_blocks_round_trip():
    # one constant-twist step is its own Magnus expansion; prefix of equal steps = n-fold step
    h = np.full(8, 0.3)
    k, t = np.full((8, 3), 1.2), np.full((8, 3), -0.4)
    twist = magnus6(h, k, t)
    assert_allclose(
        np.stack(twist),
        np.stack(
            [0.3 * -0.4 * np.ones(8), 0 * h, 0.3 * 1.2 * np.ones(8), 0.3 * np.ones(8), 0 * h, 0 * h]
        ),
        atol=1e-16,
    )
    steps = exp_dual(twist)
    R, p = dual_to_motion(prefix_dual(steps))
    x, F = helix(1.2, -0.4, 0.3 * np.arange(1, 9))
    assert_allclose(p, x, atol=1e-14)
    assert_allclose(R, F, atol=1e-14)


@pytest.mark.parametrize(
    "kwargs,match",
    [
        (
            dict(kappa=lambda s: 1 - s, tau=0.0, length=2.0),
            r"kappa must be > 0 .* at s = 1 it is " r"0",
        ),
        (
            dict(kappa=lambda s: np.where(s > 0.5, np.nan, 1.0), tau=0.0, length=1.0),
            r"kappa must be " r"finite; at s = 0\.5\d* it is nan",
        ),
        (
            dict(kappa=1.0, tau=lambda s: np.where(s > 2, np.inf, 0.0), length=3.0),
            r"tau must be " r"finite; at s = 2\.\d* it is inf",
        ),
        (dict(kappa=-2.0, tau=0.0, length=1.0), r"kappa must be > 0 .* at s = 0 it is -2"),
        (dict(kappa=1.0, tau=0.0, length=0.0), r"length must be a finite number > 0, got 0\.0"),
        (
            dict(kappa=1.0, tau=0.0, length=1.0, samples=1),
            r"samples must be an integer in \[2, "
            r"10000000\] \(memory bound, about 1 GB\), got 1$",
        ),
        (
            dict(kappa=1.0, tau=0.0, length=1.0, samples=MAX_SAMPLES + 1),
            r"samples must be an " r"integer in \[2, 10000000\]",
        ),
        (dict(kappa=1.0, tau=0.0, length=1.0, samples=2.5), r"samples must be an integer"),
        (
            dict(kappa=1.0, tau=0.0, length=1.0, frame=np.diag([1, 1, -1.0])),
            r"frame must be a " r"rotation",
        ),
        (dict(kappa=1.0, tau=0.0, length=1.0, origin=[0, 0]), r"origin must be 3 finite numbers"),
        (
            dict(kappa=[1.0], tau=0.0, length=1.0),
            r"kappa: expected .* at least 2 samples, got " r"shape \(1,\)",
        ),
    ],
)
def test_bad_input_is_refused_with_location(kwargs, match):
    with pytest.raises(InputError, match=match):
        SpaceCurve.from_curvature(
            kwargs.pop("kappa"), kwargs.pop("tau"), kwargs.pop("length"), **kwargs
        )


def test_arrays_are_read_only():
    c = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
    with pytest.raises(ValueError):
        c.points[0, 0] = 1.0


def test_dense_output_agrees_with_stepping_every_sample():
    """Far denser than accuracy needs, samples are filled by quintic Hermite interpolation."""
    from curvefold.geometry._curve import gauss_nodes, integrate_frenet
    from curvefold.kernel._dense import dense_stride

    L, n = 20.0, 100_001
    c = SpaceCurve.from_curvature(KAPPA, TAU, L, samples=n)
    stride = dense_stride(c.kappa, c.tau, L, n)
    assert stride >= 8  # the dense path is the one under test
    nodes = gauss_nodes(c.s)
    points, frames = integrate_frenet(c.s, KAPPA(nodes), TAU(nodes))  # a Magnus step per sample
    assert np.abs(c.points - points).max() < 1e-13 * L
    assert np.abs(c.frames - frames).max() < 1e-13
    assert (
        np.abs(np.einsum("nji,njk->nik", c.frames[::101], c.frames[::101]) - np.eye(3)).max()
        < 1e-14
    )


def test_dense_output_error_falls_at_sixth_order():
    """The Hermite fill's own error, measured with growing strides on the same coarse solution."""
    from curvefold.geometry._curve import gauss_nodes, integrate_frenet, integrate_motions
    from curvefold.kernel import as_function
    from curvefold.kernel._dense import coarse_indices, frenet_rates, hermite_fill

    L, n = 6.0, 6401
    s = np.linspace(0, L, n)
    exact, _ = integrate_frenet(s, KAPPA(gauss_nodes(s)), TAU(gauss_nodes(s)))
    kf, tf = as_function(KAPPA, name="kappa", length=L), as_function(TAU, name="tau", length=L)
    errors = []
    for stride in (160, 80, 40):
        grid = s[coarse_indices(n, stride)]
        motions = integrate_motions(grid, KAPPA(gauss_nodes(grid)), TAU(gauss_nodes(grid)))
        points, _ = hermite_fill(s, stride, motions, frenet_rates(kf, tf, grid))
        errors.append(np.abs(points - exact).max())
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(orders > 5.5), (errors, orders)


def test_a_derivative_that_fails_between_the_samples_means_a_step_per_sample():
    """The Hermite fill reads κ' and τ'; where they are not finite, every sample is integrated
    instead."""
    from curvefold.geometry._curve import gauss_nodes, integrate_frenet
    from curvefold.kernel._dense import coarse_indices, dense_stride
    from curvefold.kernel._functions import as_function, difference_step

    L, n = 20.0, 20_000
    s = np.linspace(0, L, n)
    stride = lambda k: dense_stride(
        as_function(k, name="kappa", length=L), as_function(TAU, name="tau", length=L), L, n
    )  # noqa: E731
    # a node of the difference there
    bad = s[coarse_indices(n, stride(KAPPA))][50] + 2 * difference_step(L)
    kappa = lambda x: np.where(x == bad, np.nan, KAPPA(x))  # noqa: E731
    nodes = gauss_nodes(s)
    # only the derivative fails
    assert np.isfinite(kappa(s)).all() and np.isfinite(kappa(nodes)).all() and stride(kappa) > 1
    c = SpaceCurve.from_curvature(kappa, TAU, L, samples=n)
    points, frames = integrate_frenet(s, KAPPA(nodes), TAU(nodes))
    assert np.array_equal(c.points, points) and np.array_equal(c.frames, frames)
