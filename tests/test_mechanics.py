"""The bar-and-hinge model against closed forms: a bar, a hinge, a strip in bending and buckling, a
twisted plate, a Miura-ori cell.

Every static test also checks equilibrium: the reactions carry exactly the applied load
(to rounding, relative to the load: ``equilibrium_error``). Every check is shown failing
on a damaged model.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from numpy.testing import assert_allclose

from _mechanics import dihedral, mesh_of, miura_cell, miura_mesh, strip
from curvefold.kernel import InputError
from curvefold.mechanics import (
    BarHingeModel,
    Material,
    buckling,
    free_modes,
    soft_modes,
    static_response,
)
from curvefold.mechanics._elements import (
    dihedral_angle,
    dihedral_gradient,
    dihedral_hessian,
    dihedral_hessian_action,
    triangle_strain,
)
from curvefold.mechanics._materials import MATERIALS, material

ALUMINIUM = MATERIALS["aluminium"]
EQUILIBRIUM = 1e-14  # |Σ R + Σ f| over the forces K u − f adds up: rounding (measured ≤ 2e-16 here)


def held(P: int, rows: dict[int, str]) -> np.ndarray:
    """A (P, 3) mask holding the given nodes' axes ("xyz", "yz", …)."""
    fixed = np.zeros((P, 3), bool)
    for node, axes in rows.items():
        fixed[node, ["xyz".index(a) for a in axes]] = True
    return fixed


# -- the elements --------------------------------------------------------------------------------


def test_hinge_gradient_and_hessian_match_finite_differences_and_move_nothing_rigidly():
    rng = np.random.default_rng(3)
    x = rng.normal(size=(20, 4, 3))
    g = dihedral_gradient(x)
    h = 1e-6
    fd = np.zeros_like(g)
    for a in range(4):
        for c in range(3):
            step = np.zeros_like(x)
            step[:, a, c] = h
            fd[:, a, c] = (dihedral_angle(x + step) - dihedral_angle(x - step)) / (2 * h)
    # central differences: O(h²) ~ 1e-12, rounding ε/h ~ 1e-10
    assert np.abs(fd - g).max() < 1e-8 * np.abs(g).max()
    assert np.abs(g.sum(axis=1)).max() < 1e-14 * np.abs(g).max() * 10  # translations
    # rotations
    assert np.abs(np.cross(x, g).sum(axis=1)).max() < 1e-13 * np.abs(g).max() * np.abs(x).max()
    H = dihedral_hessian(x)
    fdH = np.stack(
        [
            (dihedral_gradient(x + s) - dihedral_gradient(x - s)).reshape(20, 12) / (2 * h)
            for s in np.eye(12).reshape(12, 1, 4, 3) * h
        ],
        axis=-1,
    )
    assert np.abs(fdH - H).max() < 1e-7 * np.abs(H).max()
    v = rng.normal(size=x.shape)
    assert_allclose(
        dihedral_hessian_action(x, v).reshape(20, 12),
        np.einsum("hij,hj->hi", H, v.reshape(20, 12)),
        atol=1e-12 * np.abs(H).max(),
    )
    # damaged: a wing term with the wrong sign breaks the rigid invariance
    bad = g.copy()
    bad[:, 2] *= -1
    assert np.abs(bad.sum(axis=1)).max() > 1e-2


def test_triangle_strain_recovers_a_uniform_strain_exactly():
    rng = np.random.default_rng(5)
    x = rng.normal(size=(10, 3, 3))
    G, frame = triangle_strain(x)
    eps = rng.normal(size=(10, 3))
    for k in range(10):
        local = (x[k] - x[k, 0]) @ frame[k].T  # (3, 2)
        F = np.array([[eps[k, 0], 0.5 * eps[k, 2]], [0.5 * eps[k, 2], eps[k, 1]]])
        u = local @ F.T
        e, du = np.roll(local, -1, 0) - local, np.roll(u, -1, 0) - u
        delta = (e * du).sum(axis=1) / np.linalg.norm(e, axis=1)
        assert_allclose(G[k] @ delta, eps[k], atol=1e-12 * np.abs(eps[k]).max())


# -- a bar, a hinge -------------------------------------------------------------------------------


def test_a_single_bar_stretches_by_f_l_over_ea_and_a_free_end_is_named():
    L, EA, F = 2.5, 3.0e6, 120.0
    e = np.array([1.0, 2.0, -2.0]) / 3.0
    model = BarHingeModel(
        np.array([[0.0, 0, 0], L * e]), [[0, 1]], [EA / L], np.zeros((0, 4)), [], [1.0, 1.0]
    )
    # node 1 slides along x only; the bar carries the load along itself
    fixed = held(2, {0: "xyz", 1: "yz"})
    result, _ = static_response(model, np.array([[0, 0, 0], F * e]), fixed)
    assert_allclose(result.bar_forces, [F], rtol=1e-14)
    assert_allclose(result.displacements[1] @ e, F * L / EA, rtol=1e-14)  # the elongation F L / EA
    assert result.equilibrium_error < EQUILIBRIUM
    # the free end turns about the fixed one: named, not solved
    with pytest.raises(
        InputError,
        match=r"^the structure is still a mechanism under these "
        r"supports: a rigid motion \(rotation about the axis along \[.*\] through \[0, 0, 0\] "
        r"m\) is free \(it stretches no bar and turns no hinge\)",
    ):
        static_response(model, np.array([[0, 0, 0], [1.0, 0, 0]]), held(2, {0: "xyz"}))


def test_a_single_hinge_turns_by_moment_over_stiffness():
    # two triangles on the edge 0–1 (along x), wings 2 (y > 0) and 3 (y < 0), flat
    x = np.array([[0.0, 0, 0], [1.0, 0, 0], [0.3, 0.4, 0], [0.6, -0.5, 0]])
    k, F = 7.0, 0.01
    bars = [[0, 1], [0, 2], [1, 2], [0, 3], [1, 3]]
    model = BarHingeModel(x, bars, np.full(5, 1e3), [[0, 1, 2, 3]], [k], np.ones(4))
    fixed = held(4, {0: "xyz", 1: "xyz", 2: "xyz"})
    f = np.zeros((4, 3))
    f[3, 2] = F
    result, _ = static_response(model, f, fixed)
    arm = 0.5  # distance of node 3 from the hinge line
    # out of the plane: no bar stretches at first order
    assert_allclose(result.displacements[3], [0, 0, F * arm**2 / k], atol=1e-15)
    assert_allclose(abs(result.hinge_moments[0]), F * arm, rtol=1e-12)
    assert result.equilibrium_error < EQUILIBRIUM
    damaged = BarHingeModel(x, bars, np.full(5, 1e3), [[0, 1, 2, 3]], [2 * k], np.ones(4))
    assert (
        abs(static_response(damaged, f, fixed)[0].displacements[3, 2] / (F * arm**2 / k) - 1) > 0.4
    )


# -- a strip: bending, buckling ----------------------------------------------------------------


def simply_supported(model: BarHingeModel, quads: int) -> np.ndarray:
    """Both end rulings held in z and y; one end in x too (a hinge about each end ruling)."""
    return held(len(model.nodes), {0: "xyz", 1: "xyz", 2 * quads: "yz", 2 * quads + 1: "yz"})


@pytest.mark.parametrize("nu", [0.0, 0.33])
def test_a_strip_bends_as_euler_bernoulli_at_second_order(nu):
    """Midspan deflection of a simply supported strip under its weight against 5 w L⁴ / 384 D b.

    The plate strip bends cylindrically (its rulings stay straight), so its stiffness is
    D b, with D = E t³ / 12(1 − ν²). The hinges at the rulings make a chain of rigid links
    with springs D b / h; its error is 0.8 / N² exactly for N links (second order).
    """
    mat = Material.from_values(70e9, nu, 2700.0, 200e6)
    t, L, b = 1e-3, 1.0, 0.1
    errors = []
    for quads in (8, 16, 32, 64):
        model = BarHingeModel.from_mesh(strip(L, b, quads), mat, t, crease_stiffness=1.0)
        f = np.zeros((len(model.nodes), 3))
        f[:, 2] = -9.80665 * model.masses
        result, _ = static_response(model, f, simply_supported(model, quads))
        w = -f[:, 2].sum() / L
        exact = 5 * w * L**4 / (384 * mat.bending_stiffness(t) * b)
        errors.append(abs(result.displacements[:, 2]).max() / exact - 1)
        assert result.equilibrium_error < EQUILIBRIUM
    assert_allclose(errors, 0.8 / np.array([8, 16, 32, 64]) ** 2, rtol=1e-6)
    orders = np.log2(np.array(errors[:-1]) / errors[1:])
    assert np.all(np.abs(orders - 2) < 1e-3), orders


def test_a_strip_of_triangles_with_one_hinge_per_ruling_is_spuriously_soft():
    """Why edges between quads are hinged at both ends: the same strip as triangles (one hinge
    per edge) does not converge."""
    mat = Material.from_values(70e9, 0.33, 2700.0, 200e6)
    ratios = []
    for quads in (8, 32):
        model = BarHingeModel.from_mesh(
            strip(1.0, 0.1, quads, triangles=True), mat, 1e-3, crease_stiffness=1.0
        )
        f = np.zeros((len(model.nodes), 3))
        f[:, 2] = -9.80665 * model.masses
        result, _ = static_response(model, f, simply_supported(model, quads))
        exact = 5 * (-f[:, 2].sum()) / (384 * mat.bending_stiffness(1e-3) * 0.1)
        ratios.append(abs(result.displacements[:, 2]).max() / exact)
    assert ratios[1] > 2 * ratios[0] > 2  # softer and softer as it is sampled finer


def test_a_strip_buckles_at_the_euler_load_at_second_order():
    """Pinned–pinned strip under an end load P: the factor approaches π² D b / L² P (error ∝
    1/N²)."""
    t, L, b = 1e-3, 1.0, 0.1
    errors = []
    for quads in (8, 16, 32, 64):
        model = BarHingeModel.from_mesh(strip(L, b, quads), ALUMINIUM, t, crease_stiffness=1.0)
        f = np.zeros((len(model.nodes), 3))
        f[[2 * quads, 2 * quads + 1], 0] = -0.5  # P = 1 N, compressing
        result, factor = static_response(model, f, simply_supported(model, quads))
        assert result.equilibrium_error < EQUILIBRIUM
        errors.append(
            buckling(model, result, factor).factor
            / (np.pi**2 * ALUMINIUM.bending_stiffness(t) * b / L**2)
            - 1
        )
    orders = np.log2(np.abs(errors[:-1]) / np.abs(errors[1:]))
    assert np.all(np.abs(orders - 2) < 0.02), orders
    assert abs(errors[-1]) < 3e-4
    # a tension load cannot buckle it
    f = np.zeros((len(model.nodes), 3))
    f[[2 * 64, 2 * 64 + 1], 0] = 0.5
    result, factor = static_response(model, f, simply_supported(model, 64))
    assert buckling(model, result, factor).factor == np.inf


def test_a_rectangular_plate_twists_as_kirchhoff_says():
    """Three corners held, a force P at the fourth: w = P W H / 2 D (1 − ν), the plate in pure
    twist (w = c x y)."""
    W, H, P = 0.3, 0.2, 1.0
    x = np.array([[0, 0, 0], [W, 0, 0], [W, H, 0], [0, H, 0.0]])
    quad = mesh_of(
        x, np.array([[0, 1, 2, 3]]), np.array([[0, 1], [1, 2], [2, 3], [3, 0]]), ["boundary"] * 4
    )
    model = BarHingeModel.from_mesh(quad, ALUMINIUM, 1e-3, crease_stiffness=1.0)
    f = np.zeros((4, 3))
    f[2, 2] = P
    result, _ = static_response(model, f, held(4, {0: "xyz", 1: "yz", 3: "xz"}))
    D, nu = ALUMINIUM.bending_stiffness(1e-3), ALUMINIUM.poisson
    assert_allclose(result.displacements[2, 2], P * W * H / (2 * D * (1 - nu)), rtol=1e-12)
    # the corner forces of pure twist
    assert_allclose(result.reactions[:, 2], [P, -P, 0, -P], atol=1e-12)
    assert result.equilibrium_error < EQUILIBRIUM


# -- a Miura-ori cell --------------------------------------------------------------------------


def test_the_miura_cell_matches_schenk_and_guest_geometry():
    a, b, gamma = 1.0, 1.5, np.radians(60)
    for theta in np.radians([10, 35, 60, 85]):
        x = miura_cell(a, b, gamma, theta)
        ab = x[3] - x[0]  # an a-step
        bb = x[1] - x[0]  # a b-step
        assert_allclose([np.linalg.norm(ab), np.linalg.norm(bb)], [a, b], rtol=1e-14)
        assert_allclose(np.arccos(ab @ bb / (a * b)), gamma, rtol=1e-14)
        for i in range(2):  # every panel a parallelogram, planar
            for j in range(2):
                p, q, r, s = 3 * i + j, 3 * (i + 1) + j, 3 * (i + 1) + j + 1, 3 * i + j + 1
                assert abs(np.linalg.det(np.stack([x[q] - x[p], x[s] - x[p], x[r] - x[p]]))) < 1e-14
                assert_allclose(x[r] - x[q], x[s] - x[p], atol=1e-14)
        # the facet's dihedral angle with the xy plane is θ
        n = np.cross(ab, bb)
        assert_allclose(np.arccos(abs(n[2]) / np.linalg.norm(n)), theta, rtol=1e-12)


def miura_closed_form(a, b, gamma, theta, k):
    """In-plane stiffness K_x and Poisson's ratio ν_yx of the cell from the kinematics of Schenk and
    Guest (2013).

    The folding is the only motion of rigid panels; its strain energy is that of the four
    creases' springs, ½ Σ k ℓ (dρ/dθ)² δθ², and a force F pulling the x faces apart does
    the work F d(2L)/dθ δθ; so K_x = Σ k ℓ ρ'² / (2L)'². Derivatives by complex step of the
    closed-form geometry (exact to rounding).
    """
    h = 1e-30
    x = miura_cell(a, b, gamma, theta + 1j * h)
    lengths = (a, a, b, b)
    rho = [
        dihedral(x, 4, 1, 0, 2).imag,
        dihedral(x, 4, 7, 6, 8).imag,
        dihedral(x, 4, 3, 0, 6).imag,
        dihedral(x, 4, 5, 2, 8).imag,
    ]
    Lp = (x[6, 0] - x[0, 0]).imag / h  # (2L)'
    Sp = (x[2, 1] - x[0, 1]).imag / h  # (2S)'
    energy = sum(k * ell * (r / h) ** 2 for ell, r in zip(lengths, rho))
    X, Y = (x[6, 0] - x[0, 0]).real, (x[2, 1] - x[0, 1]).real
    return energy / Lp**2, -(Sp / Y) / (Lp / X)


@pytest.mark.parametrize("theta_deg", [30.0, 55.0])
def test_the_miura_cell_in_plane_stiffness_and_poisson_ratio_match_the_closed_form(theta_deg):
    """Pull the cell's x faces apart with creases far softer than the panels: K_x and ν within 2e-6.

    The panels' own bending and stretching add compliance of the order of the crease
    stiffness over theirs (k_c a / D ~ 2e-7 here), and the solve loses ε E t / k_c ~ 1e-7
    to rounding (the ratio of the stiffest to the softest): the tolerance sits above both.
    """
    a, b, gamma, theta = 1.0, 1.5, np.radians(60), np.radians(theta_deg)
    k = 10.0
    model = BarHingeModel.from_mesh(
        miura_mesh(a, b, gamma, theta), ALUMINIUM, 0.2, crease_stiffness=k
    )
    f = np.zeros((9, 3))
    F = 1e-2
    f[[6, 7, 8], 0], f[[0, 1, 2], 0] = F / 3, -F / 3
    # a statically determinate support: holds the rigid motions, not the folding
    fixed = held(9, {4: "xyz", 1: "yz", 3: "z"})
    result, _ = static_response(model, f, fixed)
    u = result.displacements
    dX = u[[6, 7, 8], 0].mean() - u[[0, 1, 2], 0].mean()
    dY = u[[2, 5, 8], 1].mean() - u[[0, 3, 6], 1].mean()
    K_x, nu = miura_closed_form(a, b, gamma, theta, k)
    X, Y = (
        2 * a * np.sqrt(1 - np.sin(theta) ** 2 * np.sin(gamma) ** 2),
        (model.nodes[2, 1] - model.nodes[0, 1]),
    )
    assert_allclose(F / dX, K_x, rtol=2e-6)
    assert_allclose(-(dY / Y) / (dX / X), nu, rtol=2e-6)
    assert result.equilibrium_error < EQUILIBRIUM
    # damaged: one crease twice as stiff
    crease = np.flatnonzero(model.hinge_kind == "fold")[0]
    stiff = replace(
        model,
        hinge_stiffness=np.where(np.arange(len(model.hinges)) == crease, 2, 1)
        * model.hinge_stiffness,
    )
    u2 = static_response(stiff, f, fixed)[0].displacements
    assert abs(F / (u2[[6, 7, 8], 0].mean() - u2[[0, 1, 2], 0].mean()) / K_x - 1) > 0.05


def test_the_miura_cell_folds_with_one_degree_of_freedom():
    model = BarHingeModel.from_mesh(
        miura_mesh(1.0, 1.5, np.radians(60), np.radians(40)), ALUMINIUM, 0.01, crease_stiffness=1.0
    )
    # rigid panels: the folding alone
    assert soft_modes(model, held_hinges=("diagonal",)).count == 1
    assert soft_modes(model).count == 1 + 4  # each panel may bend across its diagonal too


# -- modes --------------------------------------------------------------------------------------


def test_free_modes_of_a_strip_are_its_bending_modes_without_rigid_motions():
    """A free–free strip: ω² of its first bending mode against the beam's (4.730 / L)⁴ D b / (ρ t
    b), second order."""
    t, L, b = 1e-3, 1.0, 0.05
    errors = []
    for quads in (16, 32, 64):
        model = BarHingeModel.from_mesh(strip(L, b, quads), ALUMINIUM, t, crease_stiffness=1.0)
        modes = free_modes(model, 3)
        exact = (4.730040745 / L) ** 4 * ALUMINIUM.bending_stiffness(t) / (ALUMINIUM.density * t)
        bending = [lam for lam, s in zip(modes.eigenvalues, modes.stretching) if s < 1e-6]
        errors.append(bending[0] / exact - 1)
    orders = np.log2(np.abs(errors[:-1]) / np.abs(errors[1:]))
    assert np.all(np.abs(orders - 2) < 0.05), (errors, orders)
    # 8.3 / N² (measured), lumped masses and hinge springs both second order
    assert abs(errors[-1]) < 2.5e-3


def test_a_material_out_of_range_is_refused_in_one_line():
    for values, match in (
        (
            (-1e9, 0.3, 900, 3e7),
            r"^youngs_modulus must be in \[1000, 1e13\] Pa .*got -1000000000\.0$",
        ),
        ((1e9, 0.5, 900, 3e7), "^poisson must be in \\(-1, 0.5\\)"),
        ((1e9, -1.0, 900, 3e7), "^poisson must be in \\(-1, 0.5\\)"),
        ((1e9, 0.3, 0.0, 3e7), r"^density must be in \[1, 100000\] kg/m³ .*got 0\.0$"),
        ((1e9, 0.3, 900, float("nan")), "^strength must be a finite number"),
    ):
        with pytest.raises(InputError, match=match) as info:
            Material.from_values(*values)
        assert "\n" not in str(info.value)
    with pytest.raises(
        InputError, match=r"^thickness must be in \(0, 1\) m \(a sheet, not a " r"block\), got 0.0$"
    ):
        ALUMINIUM.bending_stiffness(0.0)
    with pytest.raises(
        InputError, match='^material must be one of "polypropylene", "paperboard", "aluminium"'
    ):
        material("steel")
    for mat in MATERIALS.values():
        assert Material.from_values(
            mat.youngs_modulus, mat.poisson, mat.density, mat.strength, name=mat.name
        ) == Material(
            mat.name,
            mat.youngs_modulus,
            mat.poisson,
            mat.density,
            mat.strength,
            "given by the user",
        )
        assert mat.source and mat.source != "given by the user"
