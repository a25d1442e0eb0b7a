"""Arches and vaults: Eq. (20), the paper's example, placement, max tubes, folding motion."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from curvefold import ConvergenceError, InputError, RegressionError
from curvefold.analysis._measure import derivative
from curvefold.vault import Vault, VaultDesign, max_tubes
from curvefold.vault._arch import (
    A_MAX,
    HALF_STEPS,
    proportion_change,
    solve_general_arch,
    solve_symmetric_arch,
    symmetric_arch_condition,
)

PAPER_KAPPA0_S0 = 3.305  # printed in the paper for a = 0.3


def ivp_condition(x: float, a: float) -> float:
    """T(s₀/2)·T(0) from scipy's DOP853 on the plain Frenet ODE: an independent integrator."""
    from scipy.integrate import solve_ivp

    def rhs(s, y):
        T, N, B = y[0:3], y[3:6], y[6:9]
        t = a * np.sin(2 * np.pi * s / x)
        return np.concatenate([N, -T + t * B, -t * N])

    sol = solve_ivp(rhs, (0, x / 2), np.eye(3).ravel(), method="DOP853", rtol=1e-13, atol=1e-14)
    return float(sol.y[0, -1])


@pytest.fixture(scope="module")
def paper_vault():
    return Vault.from_design(VaultDesign(a=0.3, p_xy=0.75, fold_angle=90.0))


def test_circle_arch_is_pi():
    assert_allclose(solve_symmetric_arch(0.0).kappa0_s0, np.pi, rtol=0, atol=1e-14)
    assert_allclose(symmetric_arch_condition([1.0, 2.0], 0.0), np.cos([0.5, 1.0]), atol=1e-15)


def test_paper_example_against_an_independent_integrator():
    from scipy.optimize import brentq

    ours = solve_symmetric_arch(0.3)
    theirs = brentq(lambda x: ivp_condition(x, 0.3), 3.0, 3.3, xtol=1e-14)
    assert abs(ours.kappa0_s0 - theirs) < 1e-10
    assert_allclose(ours.kappa0_s0, 3.16571746805, atol=5e-12)
    assert ours.residual < 1e-12  # |T·T| at the ends of the final bracket, ~|f'| × 1e-13
    # converged in the step count: halving the steps changes the root below 1e-13
    assert abs(solve_symmetric_arch(0.3, steps=200).kappa0_s0 - ours.kappa0_s0) < 1e-13


@pytest.mark.parametrize("a", [0.3, 1.15, 1.25, 1.27, 1.2707])
def test_the_arch_root_is_converged_in_its_steps_across_the_family(a):
    """Near the end of the family the torsion term grows: the root meets Eq. (20) integrated with
    8× the steps to 2e-14 at every a (1.8e-15 at a = 0.3, 1.0e-14 at 1.2707, where the 128
    steps' own error is largest; 64 steps left 1.6e-13 to 6.8e-13 from a = 1.15 on, which a
    vault's built curve 1 shows as a failed arch_condition). The root itself moves more as the
    slope of the condition vanishes at A_MAX."""
    ours = solve_symmetric_arch(a).kappa0_s0
    assert abs(float(symmetric_arch_condition(ours, a, steps=8 * HALF_STEPS))) < 2e-14


def test_erratum_paper_kappa0_s0_does_not_solve_eq20():
    """The paper's κ₀s₀ ≈ 3.305 leaves T(s₀/2)·T(0) far from 0; its 1.37 and 1.41 follow from it."""
    assert abs(ivp_condition(PAPER_KAPPA0_S0, 0.3)) > 0.05
    assert abs(float(symmetric_arch_condition(PAPER_KAPPA0_S0, 0.3))) > 0.05
    assert round(proportion_change(0.3, PAPER_KAPPA0_S0), 2) == 1.37
    assert round(0.75 * proportion_change(0.3, PAPER_KAPPA0_S0) ** 2, 2) == 1.41
    exact = solve_symmetric_arch(0.3).kappa0_s0
    assert round(proportion_change(0.3, exact), 3) == 1.353
    assert round(0.75 * proportion_change(0.3, exact) ** 2, 3) == 1.373


def test_arch_family_ends_at_a_max():
    assert solve_symmetric_arch(A_MAX - 1e-4).kappa0_s0 > np.pi
    # the refusal past A_MAX hides no root: the condition stays positive over (π/2, 2π)
    x = np.linspace(0.5 * np.pi, 2 * np.pi, 4001)
    assert (
        symmetric_arch_condition(x, A_MAX + 1e-4).min()
        > 0
        > symmetric_arch_condition(x, A_MAX - 1e-4).min()
    )
    for a in (A_MAX + 1e-4, 1.5, 3.0):
        with pytest.raises(
            ConvergenceError, match=rf"no standing arch for a = {a:g}: .* only " r"for a < 1\.2707"
        ):
            solve_symmetric_arch(a)
    with pytest.raises(
        InputError, match=r"a \(torsion amplitude\) must be a finite number ≥ 0, " r"got nan"
    ):
        solve_symmetric_arch(float("nan"))


def test_a_root_that_fails_its_residual_is_never_returned(monkeypatch):
    import scipy.optimize

    from curvefold.vault import _arch as arch

    monkeypatch.setattr(arch, "_chebyshev_root", lambda *args: None)  # take the Brent fallback
    assert abs(solve_symmetric_arch(0.3).kappa0_s0 - 3.16571746805) < 1e-10
    # off by 1e-6: |f| ≈ slope 0.486 × 1e-6
    monkeypatch.setattr(scipy.optimize, "brentq", lambda f, lo, hi, **kw: 3.16571746805 + 1e-6)
    with pytest.raises(
        ConvergenceError,
        match=r"for a = 0\.3 was not solved: at κ0·s0 = "
        r"3\.16571846805, \|T\(s0/2\)·T\(0\)\| = 4\.86e-07 exceeds 1e-12",
    ):
        solve_symmetric_arch(0.3)


def test_erratum_end_condition_sign(paper_vault):
    """The ends face opposite ways: T(0) + T(s₁) = 0 holds; the printed T(0) − T(s₁) = 0 does
    not."""
    F = paper_vault.lattice.crease.curve.frames
    x = paper_vault.lattice.crease.curve.points
    assert np.abs(F[0, :, 0] + F[-1, :, 0]).max() < 1e-12
    assert np.linalg.norm(F[0, :, 0] - F[-1, :, 0]) > 1.99
    assert abs((x[-1] - x[0]) @ F[0, :, 0]) < 1e-12


def test_general_arch_without_symmetry():
    # the symmetric family is a special case: only the length is free
    L0 = solve_symmetric_arch(0.3).kappa0_s0
    sym = solve_general_arch(lambda s, p: 1.0, lambda s, p: 0.3 * np.sin(2 * np.pi * s / L0), 3.0)
    assert abs(sym.length - L0) < 1e-9 and np.linalg.norm(sym.residuals) < 1e-10
    # A family with no reflection symmetry: κ grows along s, torsion τ = p₀ s² + p₁ s³.
    # Generically three unknowns (s₁, p₀, p₁) meet the three independent end conditions.
    gen = solve_general_arch(
        lambda s, p: 1.0 + 0.05 * s, lambda s, p: p[0] * s**2 + p[1] * s**3, 3.0, (0.2, 0.0)
    )
    assert np.linalg.norm(gen.residuals) < 1e-12
    # check the solution with an independent integrator
    from scipy.integrate import solve_ivp

    p0, p1 = gen.params

    def rhs(s, y):
        T, N, B = y[0:3], y[3:6], y[6:9]
        k, t = 1.0 + 0.05 * s, p0 * s**2 + p1 * s**3
        return np.concatenate([k * N, -k * T + t * B, -t * N, T])

    y = solve_ivp(
        rhs,
        (0, gen.length),
        np.concatenate([np.eye(3).ravel(), np.zeros(3)]),
        method="DOP853",
        rtol=1e-13,
        atol=1e-14,
    ).y[:, -1]
    assert np.abs(y[0:3] + [1, 0, 0]).max() < 1e-9  # T(s₁) = −T(0)
    assert abs(y[9]) < 1e-9  # (x(s₁) − x(0))·T(0) = 0
    with pytest.raises(
        ConvergenceError, match=r"general arch did not converge: residual norm .* " r"> tol"
    ):
        solve_general_arch(lambda s, p: 1.0, lambda s, p: 0.0, 0.5, tol=1e-30)


def test_paper_vault_proportions_from_built_geometry(paper_vault):
    """exp(a κ₀ s₀ / π) against widths measured between parallel tangent lines."""
    p_xy, change = paper_vault.measured_proportions()
    assert_allclose(p_xy, 0.75, rtol=1e-13)
    assert_allclose(change, np.exp(0.3 * paper_vault.kappa0_s0 / np.pi), rtol=1e-12)
    assert_allclose(paper_vault.p_xz, 0.75 * change**2, rtol=1e-12)


def test_vault_stands_on_the_ground(paper_vault):
    V = paper_vault.vertices
    assert paper_vault.ground_error() < 1e-13  # every end section on z = 0
    assert V[:, 1:-1, 2].min() > 0  # everything else above it
    s = paper_vault.summary()
    assert s["rise"] > 0 and s["span"] > 0 and s["tubes"] == s["max_tubes"] >= 2
    assert s["regression_margin"] > 0


def test_lift_off_away_from_the_design_angle(paper_vault):
    angles = [0.0, 45.0, 89.0, 90.0, 91.0, 120.0]
    base = paper_vault.lift_off(angles, anchor="start")
    assert np.abs(base[:, 0]).max() < 1e-13  # the held feet stay down
    # the far feet lift except at 90°
    assert base[3, 1] < 1e-13 and (np.delete(base[:, 1], 3) > 1e-3).all()
    apex = paper_vault.lift_off(angles, anchor="middle")
    assert_allclose(apex[:, 0], apex[:, 1], atol=1e-12)  # symmetric motion
    assert apex[3].max() < 1e-13 and (np.delete(apex[:, 0], 3) > 1e-3).all()
    flat = paper_vault.motion([0.0])[0]
    n = flat.reshape(-1, 3) - flat.reshape(-1, 3).mean(axis=0)
    assert np.linalg.svd(n, compute_uv=False)[-1] < 1e-10  # the flat state lies in a plane


def brute_force_max_tubes(lattice, limit):
    n = 0
    while n < limit:
        corners = n + np.array([[0, 0], [0, 1], [1, 0], [1, 1]])
        if not lattice.domain.contains(corners).all():
            break
        n += 1
    return n


@pytest.mark.parametrize(
    "a,p_xy,width", [(0.3, 0.75, 0.08), (0.0, 1.0, 0.05), (0.8, 0.5, 0.03), (0.3, 2.0, 0.1)]
)
def test_max_tubes_follows_its_definition(a, p_xy, width):
    vault = Vault.from_design(VaultDesign(a=a, p_xy=p_xy, width=width, tubes=1, samples=201))
    # a = 0, p_xy = 1 never regresses along the diagonal: the search stops at its limit
    assert min(vault.max_tubes, 300) == brute_force_max_tubes(vault.lattice, 300)
    assert max_tubes(vault.lattice) == vault.max_tubes


def test_regression_past_max_tubes_is_a_finite_difference_cusp(paper_vault):
    n = paper_vault.max_tubes
    lat = paper_vault.lattice
    corners = n + np.array([[0, 0], [0, 1], [1, 0], [1, 1]], float)
    bad = corners[~lat.domain.contains(corners)]
    assert len(bad)  # tube n (the (n+1)-th) regresses
    h = lat.t[1]
    T = lat.crease.curve.tangent[2:-2]
    for uv in bad:
        x = lat.points(uv)
        # the crease runs backwards: a cusp
        assert np.einsum("ij,ij->i", derivative(x, h), T).min() < 0
    for uv in corners[lat.domain.contains(corners)] - 1:
        x = lat.points(uv)
        assert np.einsum("ij,ij->i", derivative(x, h), T).min() > 0


def test_vault_refusals():
    with pytest.raises(
        RegressionError,
        match=r"tubes must be ≤ 9 \(the maximum before "
        r"regression for a = 0\.3, p_xy = 0\.75, width = 0\.08\), got 10",
    ):
        Vault.from_design(VaultDesign(tubes=10))
    with pytest.raises(RegressionError, match=r"width = 5 is past regression for the base tube"):
        Vault.from_design(VaultDesign(width=5.0))
    with pytest.raises(ConvergenceError, match="no standing arch for a = 1.5"):
        solve_symmetric_arch(1.5)
    with pytest.raises(
        InputError, match=r"^a must be in \[0, 1\.2707093728\) \(no arch stands " r"beyond it"
    ):
        VaultDesign(a=1.5)
    for kwargs, match in (
        (dict(fold_angle=180.0), r"fold_angle must be in \(0°, 180°\), got 180.0"),
        (dict(p_xy=-1.0), r"p_xy must be in \(0, 100\], got -1.0"),
        (dict(samples=400), r"samples must be odd and ≥ 21"),
        (
            dict(tubes=0),
            r"tubes must be an integer in \[1, 1000\] \(or None for the maximum\), " r"got 0$",
        ),
        (dict(tubes=True), r"tubes must be an integer .*, got boolean True$"),
        (dict(width=float("inf")), r"width must be a finite number, got inf"),
    ):
        with pytest.raises(InputError, match=match):
            VaultDesign(**kwargs)


def test_the_ranges_of_a_come_from_where_the_arch_family_ends():
    """A design's a stops at A_MAX, with the reason, in design files and the Python API alike;
    the atlas's rows reach twice as far, and record past A_MAX that no arch stands, in the
    solver's words."""
    from curvefold.app._design import SCHEMA, parse_design
    from curvefold.vault._arch import A_MAX, A_STANDING, check_standing
    from curvefold.vault._atlas import GRID_A, evaluate_design

    spec = SCHEMA["vault"]["a"]
    assert spec.range == A_STANDING and (A_STANDING.lo, A_STANDING.hi, A_STANDING.hi_closed) == (
        0.0,
        A_MAX,
        False,
    )
    assert (GRID_A.range.lo, GRID_A.range.hi, GRID_A.range.hi_closed) == (0.0, 2 * A_MAX, True)
    # the designer's slider stops short of it, at 1.2
    assert spec.typical.hi < A_MAX < spec.typical.hi + 0.1
    below = A_MAX * (1 - 1e-12)
    assert (
        parse_design(f'kind = "vault"\n[vault]\na = {below!r}').vault.a
        == below
        == VaultDesign(a=below).a
        == check_standing(below)
    )
    with pytest.raises(
        InputError,
        match=r"^t\.toml: \[vault\] a must be in \[0, 1\.2707093728\) "
        r"\(no arch stands beyond it: .*\), got 1\.2707093728$",
    ) as err:
        parse_design(f'kind = "vault"\n[vault]\na = {A_MAX!r}', source="t.toml")
    assert err.value.parameter == "a"
    with pytest.raises(InputError, match=r"^a must be in \[0, 1\.2707093728\)"):
        VaultDesign(a=A_MAX)
    record, sketch = evaluate_design(A_MAX, 0.75, samples=41)
    assert (record["error"], sketch) == ("ConvergenceError", None) and record["reason"].startswith(
        "no standing arch for a = 1.2707"
    )
    record, _ = evaluate_design(2 * A_MAX * (1 + 1e-12), 0.75, samples=41)
    assert record["error"] == "InputError" and record["reason"].startswith(
        "a must be in [0, 2.5414187456] (up to twice 1.2707"
    )


def test_bands_and_direction():
    v = Vault.from_design(VaultDesign(tubes=3, layers=2, direction=-1, samples=201))
    assert sorted(v.structure.cells.tolist()) == [
        [-3, -3],
        [-3, -2],
        [-2, -2],
        [-2, -1],
        [-1, -1],
        [-1, 0],
    ]
    assert v.ground_error() < 1e-13


def test_motion_beyond_the_design_angle_stops_at_first_contact(paper_vault):
    """Past 90° the arch curls until distant parts meet; regression never comes (it is
    intrinsic)."""
    from scipy.spatial import cKDTree

    angle = paper_vault.first_contact(step=1.0)
    assert angle is not None and 90.0 < angle < 180.0
    lat = paper_vault.lattice
    w_min = min(lat.width_left.min(), lat.width_right.min())

    def closest_far_pair(fold_angle):
        V = paper_vault.motion([fold_angle])[0]
        n = V.shape[1]
        pts = V.reshape(-1, 3)
        d, j = cKDTree(pts).query(pts, k=60)
        t = np.tile(np.arange(n), V.shape[0])
        far = (
            np.abs(t[j] - t[:, None]) / (n - 1)
            > 4 * max(lat.width_left.max(), lat.width_right.max()) / lat.crease.curve.length
        )
        return np.where(far, d, np.inf).min()

    assert closest_far_pair(angle) < 0.5 * w_min <= closest_far_pair(angle - 1.0)
    assert lat.refold(angle).domain.contains(paper_vault.structure.curves_uv).all()


@pytest.mark.parametrize(("batch", "n"), [(16, 128), (3, 129), (1, 1), (2, 5)])
def test_the_tree_product_of_quaternions_is_the_ordered_product(batch, n):
    """The pairwise reduction against one left-multiplication matrix at a time, in order
    (rounding: ~n ε)."""
    from curvefold.kernel._lie import _L_INDEX, _L_SIGN, product_quaternions

    q = np.random.default_rng(batch * 1000 + n).normal(size=(4, batch, n))
    ordered = np.empty((4, batch))
    for b in range(batch):
        M = np.eye(4)
        for t in range(n):
            M = M @ (_L_SIGN * q[:, b, t][_L_INDEX])
        ordered[:, b] = M[:, 0]
    scale = np.abs(ordered).max()
    assert_allclose(
        np.array(product_quaternions(tuple(q))),
        ordered,
        rtol=0,
        atol=4 * n * np.finfo(float).eps * scale,
    )
    if n > 1:  # the check sees the order: the reversed product differs
        assert (
            np.abs(np.array(product_quaternions(tuple(q[..., ::-1]))) - ordered).max()
            > 1e-3 * scale
        )


def test_arch_condition_matches_the_general_magnus_rotation():
    """The arch's written-out Magnus terms equal the general so(3) Magnus step (κ = 1, τ = a
    sin)."""
    from curvefold.geometry._curve import gauss_nodes
    from curvefold.kernel._lie import exp_rotation, magnus6_rotation, product_quaternions

    x, a, steps = np.linspace(2.5, 4.5, 7), 0.7, 64
    q = np.linspace(0, 1, steps + 1)
    nodes = gauss_nodes(q)
    tau = a * np.sin(np.pi * nodes) * np.ones((len(x), 1, 1))
    speed = 0.5 * x[:, None, None] * np.ones_like(nodes)
    w, qx, y, z = product_quaternions(exp_rotation(magnus6_rotation(np.diff(q), 1.0, tau, speed)))
    general = 1 - 2 * (y * y + z * z) / (w * w + qx * qx + y * y + z * z)
    assert_allclose(symmetric_arch_condition(x, a, steps=steps), general, atol=1e-15)
    assert_allclose(general, [ivp_condition(v, a) for v in x], atol=1e-12)
