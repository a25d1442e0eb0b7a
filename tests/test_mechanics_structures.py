"""The mechanics of curvefold's structures: the model of a state, loads, supports, the vault under
load, convergence.

Sizes stay small where the check allows (a vault of 3 tubes, 101 samples has 2,020
nodes); the paper's vault at full resolution is analysed once.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest
from numpy.testing import assert_allclose
from shapely.geometry import Polygon
from shapely.ops import unary_union

from _mechanics import strip
from curvefold import Crease, Lattice, SpaceCurve, Structure
from curvefold.geometry import PanelLattice
from curvefold.geometry._mesh import vector_areas
from curvefold.kernel import InputError
from curvefold.mechanics import (
    MATERIALS,
    BarHingeModel,
    Loads,
    PointLoad,
    Snow,
    StructureModel,
    Supports,
    analyse_load,
    correlation,
    free_modes,
    model_samples,
    span_correlation,
    static_response,
)
from curvefold.mechanics._loads import G, apex, snow_areas
from curvefold.vault import Vault

PP = MATERIALS["polypropylene"]
EQUILIBRIUM = 1e-14  # |Σ R + Σ f| over the forces K u − f adds up: rounding


@pytest.fixture(scope="module")
def small_vault():
    return Vault.from_design(a=0.3, p_xy=0.75, tubes=3, samples=101)


@pytest.fixture(scope="module")
def lattice():
    curve = SpaceCurve.from_curvature(
        lambda s: 1 + 0.3 * np.sin(s), lambda s: 0.2 + 0.3 * np.cos(s), 3.0, samples=41
    )
    return Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.08)


def test_the_model_of_a_vault_shares_seams_and_bonds_and_weighs_its_sheets(small_vault):
    state = small_vault.structure.state()
    sm = StructureModel.from_state(state, PP, 1e-3)
    M, n = state.vertices.shape[:2]
    # every (curve, sample) once: seams welded, shared creases shared
    assert len(sm.model.nodes) == M * n
    assert_allclose(sm.model.nodes, state.vertices[sm.node_curve, sm.node_sample], atol=0)
    assert_allclose(sm.field(sm.model.nodes), state.vertices, atol=0)
    mesh = state.mesh()
    area = (
        0.5 * np.linalg.norm(vector_areas(mesh.vertices_coords, mesh.faces_vertices), axis=1).sum()
    )
    # O(h³) non-planarity of the ruling quads
    assert_allclose(sm.model.masses.sum(), PP.density * 1e-3 * area, rtol=1e-9)
    # two crease hinges on every shared curve's edges (one per tube), one on the others
    tubes_on = np.bincount(small_vault.structure.cell_curves.ravel(), minlength=M)
    shared = np.isin(sm.node_curve, np.flatnonzero(tubes_on == 2))
    creases = sm.model.hinges[np.isin(sm.model.hinge_kind, ("fold", "seam"))][:, :2]
    on_shared = shared[creases].all(axis=1)
    assert on_shared.sum() == 2 * 2 * 2 * (n - 1)  # 2 junctions × 2 tubes × 2 ends × (n − 1) edges
    # the vault's ground error, ~2e-14
    assert len(sm.feet) == 2 * M and np.abs(sm.model.nodes[sm.feet, 2]).max() < 1e-13


def test_a_single_fold_is_one_sheet_of_a_tube(lattice):
    tube = Structure.tube(lattice)
    fold = StructureModel.from_state(tube.state(), PP, 1e-3, sheets=(0,))
    # corners 4, 1, 2
    assert sorted(set(fold.node_curve.tolist())) == sorted(tube.cell_curves[0][[3, 0, 1]].tolist())
    # no seam: the seams are its boundary
    assert set(fold.model.hinge_kind.tolist()) == {"fold", "ruling", "diagonal"}
    with pytest.raises(InputError, match=r"^sheets must be indices in \[0, 2\)"):
        StructureModel.from_state(tube.state(), PP, 1e-3, sheets=(2,))
    with pytest.raises(InputError, match="^end sections need whole tubes"):
        fold.end_sections()


def test_the_fold_velocity_is_the_derivative_of_the_states(lattice):
    tube = Structure.tube(lattice)
    sm = StructureModel.from_state(tube.state(60.0), PP, 1e-3)
    h = 0.01
    a, b = (tube.state(60.0 + d).vertices[sm.node_curve, sm.node_sample] for d in (-h, h))
    # fold_points and state() are the same motion (anchored at the start): central differences agree
    # to O(h²)
    assert_allclose(
        sm.fold_velocity(),
        (b - a) / np.radians(2 * h),
        atol=1e-6 * np.abs(sm.fold_velocity()).max(),
    )


def test_the_paper_vault_stands_under_its_weight(small_vault):
    result = analyse_load(small_vault, "polypropylene", 1e-3)
    s = result.static
    assert result.total_weight == pytest.approx(G * result.structure.model.masses.sum(), rel=1e-15)
    assert_allclose(s.total_reaction, [0, 0, result.total_weight], atol=1e-12 * result.total_weight)
    assert s.equilibrium_error < EQUILIBRIUM
    assert np.all(s.reactions[~s.fixed] == 0) and np.all(s.fixed[result.structure.feet])
    assert 0 < s.max_displacement < 1e-3 and 0 < result.utilisation < 1
    assert 1 < result.buckling.factor < math.inf
    assert result.soft.count == 1  # the folding motion, alone
    # the first mode is mostly the kinematics' folding (0.981: creases of L* = 1000 t)
    assert result.fold_correlation > 0.97
    d = result.to_dict()
    assert {
        "total_weight",
        "reactions",
        "max_displacement",
        "max_stress",
        "utilisation",
        "fold_mode_gap",
        "soft_modes",
        "buckling_factor",
        "modes",
    } <= set(d)
    json.dumps(d, allow_nan=False)
    assert d["reactions"][2] == pytest.approx(d["total_weight"], rel=1e-12) and d["soft_modes"] == 1
    assert d["fold_mode_gap"] == pytest.approx(d["modes"][1] / d["modes"][0])


def test_the_first_mode_is_the_folding_motion_and_a_wrong_motion_is_told_apart(small_vault):
    """With creases that fold freely (k_c = D / 10⁴ t: a tape or fabric hinge) the first mode is the
    folding motion.

    Stiffer creases mix the folding with the strips' bending (correlation 0.981 at the
    default L* = 1000 t, 0.992 at 3000 t, 0.998 at 10⁴ t, measured on the paper's vault).
    """
    sm = StructureModel.from_state(
        small_vault.structure.state(), PP, 1e-3, crease_stiffness=PP.bending_stiffness(1e-3) / 10.0
    )
    modes = free_modes(sm.model, 3)
    velocity = sm.fold_velocity()
    assert correlation(sm.model, modes.shapes[0], velocity) > 0.99
    assert max(correlation(sm.model, s, velocity) for s in modes.shapes[1:]) < 0.2
    # damaged: the folding of another fold angle, and the folding with one tube left still
    # the same nodes
    other = StructureModel.from_state(small_vault.structure.state(60.0), PP, 1e-3).fold_velocity()
    assert correlation(sm.model, modes.shapes[0], other) < 0.99
    still = velocity.copy()
    still[np.isin(sm.node_curve, small_vault.structure.cell_curves[0])] = 0.0
    assert correlation(sm.model, modes.shapes[0], still) < 0.99


def test_the_folding_motion_is_two_soft_modes_and_the_first_nears_it_as_the_sheet_thins():
    """Why the first free mode of the paper's vault correlates 0.981 with the rigid folding, and
    what holds above 0.99.

    Both are compared in the mass metric, rigid motions removed. The folding velocity lies in
    the span of the first and third free modes, both symmetric (the antisymmetric second,
    fourth and sixth hold none of it): they hold it to 1.2e-6 at 1 mm. Stiff creases (95 %
    of the folding's energy) make the lowest mode trade some crease rotation for stretching
    (9 % of its energy) and bending near the free end sections: the folding is 96 % mode 1
    and 4 % mode 3. It is the sheet's physics, not the samples (the same to 5 digits at 201
    samples): as the sheet thins, stretching stiffens against bending and creases, and the
    first mode becomes the folding (0.981, 0.987, 0.993 at 1, 0.5, 0.25 mm).
    """
    vault = Vault.from_design(a=0.3, p_xy=0.75, samples=101)
    first = []
    for t in (1e-3, 5e-4, 2.5e-4):
        sm = StructureModel.from_state(vault.structure.state(), PP, t)
        modes = free_modes(sm.model, 6)
        velocity = sm.fold_velocity()
        each = [correlation(sm.model, shape, velocity) for shape in modes.shapes]
        # 1 − 1.3e-6 at 1 mm
        assert span_correlation(sm.model, modes.shapes[[0, 2]], velocity) > 1 - 2e-6
        # symmetry: 0 to ARPACK's 1e-8
        assert (
            max(each[1::2]) < 1e-6 and span_correlation(sm.model, modes.shapes[1:], velocity) < 0.2
        )
        first.append(each[0])
    assert 0.975 < first[0] < 0.99 and np.all(np.diff(first) > 0.004) and first[-1] > 0.99, first
    # damaged: another fold angle's folding, the folding with one tube left still: outside the
    # modes' span
    other = StructureModel.from_state(vault.structure.state(60.0), PP, 1e-3).fold_velocity()
    still = velocity.copy()
    still[np.isin(sm.node_curve, vault.structure.cell_curves[0])] = 0.0
    # 0.70, 0.77
    assert max(span_correlation(sm.model, modes.shapes, v) for v in (other, still)) < 0.8


def test_what_the_first_mode_misses_of_the_folding_falls_as_the_square_of_the_thickness():
    """1 − correlation of the first free mode with the rigid folding, the paper's vault at 0.1,
    0.03 and 0.01 mm: 1.88e-3, 2.33e-4, 2.87e-5 (orders 1.73, 1.91), as the ratio of bending
    to stretching stiffness, t²; a folding of another fold angle stays apart however thin the
    sheet."""
    vault = Vault.from_design(a=0.3, p_xy=0.75, samples=101)
    missed = []
    for t in (1e-4, 3e-5, 1e-5):
        sm = StructureModel.from_state(vault.structure.state(), PP, t)
        first = free_modes(sm.model, 2).shapes[0]
        missed.append(1 - correlation(sm.model, first, sm.fold_velocity()))
    orders = np.log(np.divide(missed[:-1], missed[1:])) / np.log([10 / 3, 3])
    assert missed[-1] < 5e-5 and np.all((orders > 1.6) & (orders < 2.1)), (missed, orders)
    other = StructureModel.from_state(vault.structure.state(60.0), PP, 1e-5).fold_velocity()
    assert correlation(sm.model, first, other) < 0.8  # 0.59


def test_the_graded_samples_give_the_answer_of_every_sample_and_the_ends_need_them():
    """A 3-tube vault built on 801 samples: its model on the 261 graded samples
    (:func:`model_samples`) and on all 801.

    Measured differences: eigenvalues 1.2e-4, deflection 1.9e-4, largest stress 5e-5,
    buckling factor 2.3e-4, at a fifth of the CPU time. Every fourth sample without the ends'
    misses the stress concentrated at the feet by 15 %.
    """
    vault = Vault.from_design(a=0.3, p_xy=0.75, tubes=3, samples=801)
    i = np.arange(801)
    graded, full, coarse = (
        analyse_load(vault, samples=s) for s in ("graded", "all", i[(i % 4 == 0)])
    )
    assert len(graded.structure.samples) == 261 and np.array_equal(
        graded.structure.samples, model_samples(801)
    )
    for r in (graded, coarse):
        assert np.abs(r.modes.eigenvalues / full.modes.eigenvalues - 1).max() < 2e-3
    figures = lambda r: np.array(
        [r.static.max_displacement, r.static.max_stress, r.buckling.factor]
    )  # noqa: E731
    assert np.abs(figures(graded) / figures(full) - 1).max() < 5e-4
    assert figures(coarse)[1] / figures(full)[1] < 0.9
    assert graded.static.equilibrium_error < EQUILIBRIUM and graded.soft.count == 1
    # the field on every sample: at the kept ones the nodes' values, linear in t between
    u = graded.structure.interpolate(graded.static.displacements)
    assert_allclose(
        u[graded.structure.node_curve, graded.structure.node_sample],
        graded.static.displacements,
        atol=0,
    )
    assert_allclose(u[:, 42], 0.5 * (u[:, 40] + u[:, 44]), rtol=1e-12)


def test_a_buckling_mode_finer_than_the_samples_is_told_apart():
    """The first buckling mode of a 3-tube vault on 401 samples alternates from sample to sample
    at the feet of the first tube's outer seam: the samples do not resolve it and its factor
    (388) is 20 % below what 801 and 1601 samples find (486.5, the same to 4e-5). The paper's
    vault does the same (user guide's Mechanics page)."""
    coarse = analyse_load(Vault.from_design(a=0.3, p_xy=0.75, tubes=3, samples=401), samples="all")
    fine = analyse_load(Vault.from_design(a=0.3, p_xy=0.75, tubes=3, samples=801))
    assert not coarse.buckling_resolved and coarse.buckling_sample_correlation < -0.3  # −0.45
    assert fine.buckling_resolved and fine.buckling_sample_correlation > 0.5
    assert coarse.buckling.factor < 0.85 * fine.buckling.factor
    assert coarse.to_dict()["buckling_resolved"] is False


def test_a_structure_still_a_mechanism_is_told_which_motion_is_free(small_vault, lattice):
    sm = StructureModel.from_state(small_vault.structure.state(), PP, 1e-3)
    foot = int(sm.feet[0])
    with pytest.raises(
        InputError,
        match=r"^the structure is still a mechanism under these "
        r"supports: a rigid motion \(rotation about the axis along \[.*\] through \[.*\] m\) "
        r"is free",
    ):
        analyse_load(sm, supports=Supports(nodes=(foot,)))
    # a strip whose middle ruling has lost its hinge: its halves turn about it, a motion of their
    # own
    sheet = strip(1.0, 0.1, 8)
    broken = BarHingeModel.from_mesh(
        replace(
            sheet,
            edges_kind=np.where(
                np.arange(len(sheet.edges_kind)) == 16 + 4, "boundary", sheet.edges_kind
            ),
        ),
        PP,
        1e-3,
        crease_stiffness=1.0,
    )
    with pytest.raises(
        InputError,
        match=r"^the structure is still a mechanism under these "
        r"supports: a motion of its own, largest at node 1[67] ",
    ):
        static_response(broken, Loads().forces(broken), Supports(nodes=(0, 1, 2, 3)).fixed(broken))
    with pytest.raises(InputError, match="^no support"):
        static_response(
            sm.model, Loads().forces(sm.model), np.zeros((len(sm.model.nodes), 3), bool)
        )
    lifted = StructureModel.from_state(
        Structure.tube(PanelLattice.from_lattice(lattice, 8).moved(np.eye(3), [0, 0, 1])).state(),
        PP,
        1e-3,
    )
    with pytest.raises(
        InputError,
        match=r"^no foot: no end section of this structure lies on "
        r"the ground z = 0 \(the lowest end point",
    ):
        analyse_load(lifted)


def test_rollers_let_the_feet_slide_and_carry_only_the_vertical(small_vault):
    pinned = analyse_load(small_vault)
    rolling = analyse_load(small_vault, supports=Supports("roller"))
    r = rolling.static
    assert_allclose(
        r.total_reaction, [0, 0, rolling.total_weight], atol=1e-10 * rolling.total_weight
    )
    horizontal = r.fixed[:, :2].sum()
    # determinate: they carry nothing
    assert horizontal == 3 and np.abs(r.reactions[:, :2]).max() < 1e-9 * rolling.total_weight
    assert r.equilibrium_error < EQUILIBRIUM
    # the feet spread: the vault opens by folding
    assert r.max_displacement > 10 * pinned.static.max_displacement
    assert rolling.buckling.factor < pinned.buckling.factor


def test_snow_falls_on_the_footprint_once(small_vault, lattice):
    sm = StructureModel.from_state(small_vault.structure.state(), PP, 1e-3)
    m = sm.model
    areas = snow_areas(m)
    footprint = unary_union([Polygon(p) for p in m.nodes[m.triangles()[0]][..., :2]]).area
    # each triangle whole, seen or not, at the occlusion edges
    assert areas.sum() == pytest.approx(footprint, rel=1e-3)
    snow = Loads((Snow(500.0),)).forces(m)
    assert snow[:, :2].max() == 0 and -snow[:, 2].sum() == pytest.approx(
        500.0 * areas.sum(), rel=1e-14
    )
    # a closed tube: every vertical line through it meets it twice, and the snow falls on the upper
    # meeting only
    tube = StructureModel.from_state(Structure.tube(lattice).state(), PP, 1e-3).model
    xy = tube.nodes[tube.triangles()[0]][..., :2]
    top = unary_union([Polygon(p) for p in xy]).area
    u, v = xy[:, 1] - xy[:, 0], xy[:, 2] - xy[:, 0]
    everything = 0.5 * np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]).sum()
    assert snow_areas(tube).sum() == pytest.approx(top, rel=1e-2)
    # damaged: with no occlusion test the tube carries its snow twice
    assert everything == pytest.approx(2 * top, rel=5e-2)


def test_a_point_load_sits_on_the_apex(small_vault):
    sm = StructureModel.from_state(small_vault.structure.state(), PP, 1e-3)
    f = Loads((PointLoad(100.0),)).forces(sm.model)
    node = int(np.flatnonzero(f[:, 2])[0])
    assert f[node, 2] == -100.0 and np.count_nonzero(f) == 1
    assert sm.model.nodes[node, 2] == sm.model.nodes[:, 2].max()
    # the middle sample
    assert sm.node_sample[node] == (small_vault.structure.state().vertices.shape[1] - 1) // 2
    near = (0.0, 1.0, 1.1)  # 0.05 m under the crown
    placed = Loads((PointLoad(1.0, near),)).forces(sm.model)
    nearest = np.argmin(np.linalg.norm(sm.model.nodes - near, axis=1))
    assert np.flatnonzero(placed[:, 2])[0] == nearest
    with pytest.raises(
        InputError,
        match=r"^point load at \[0, 1, 0\] m is 0\.896 m from the structure's nearest node, "
        r"farther than the 0\.104 m allowed \(5% of its size, 2\.07 m\)$",
    ):
        Loads((PointLoad(1.0, (0.0, 1.0, 0.0)),)).forces(sm.model)
    with pytest.raises(InputError, match="^no load"):
        Loads(()).forces(sm.model)
    with pytest.raises(InputError, match=r"^point force must be in \[0, 1000000000\] N"):
        PointLoad(-5.0)


def test_the_hinges_part_of_the_geometric_stiffness_agrees_with_the_whole(small_vault):
    """The Rayleigh correction for the hinge moments against the full eigenproblem: equal to
    1e-6."""
    from curvefold.mechanics import _response, buckling

    sm = StructureModel.from_state(small_vault.structure.state(), PP, 1e-3)
    result, factor = static_response(sm.model, Loads().forces(sm.model), Supports().fixed(sm))
    corrected = buckling(sm.model, result, factor)
    free = ~result.fixed.ravel()
    u = result.displacements.ravel()
    full, _ = _response._largest(sm.model.geometric_stiffness(u)[free][:, free], factor)
    without, _ = _response._largest(
        sm.model.geometric_stiffness(u, hinges=False)[free][:, free], factor
    )
    assert corrected.factor == pytest.approx(1 / full, rel=1e-6)
    assert abs(without * corrected.factor - 1) > 1e-5  # the correction is not nothing


def test_the_response_converges_as_samples_and_panels_double():
    """A 3-tube vault: the apex's deflection and the two lowest eigenvalues as samples (51 … 801) or
    panels (16 … 256) double.

    Measured orders (log₂ of the ratio of successive differences): smooth, λ₁ 2.00, 2.00,
    1.99; λ₂ 1.94, 1.79, 1.60; the apex 1.32, 1.34, 2.04 (second order once the strips'
    ruling quads are fine enough). Panels converge to the structure of infinitely many
    hinged panels, which is not the smooth one: its rulings bend at the creases' k_c h
    (softer as the panels get narrower), an O(h) change, so the apex converges at first
    order (1.79, 1.38, 1.23) and λ₂ at 2.03, 2.41, 3.32. The buckling factor converges (orders 1.5
    to 201 samples) until a local mode of the vault's outer strip at its feet, whose factor depends
    on how finely the feet are sampled, comes first (388 at 401 samples, 487 for the global mode at
    801): reported, not hidden.
    """

    def values(**design):  # every sample: the convergence of the model itself
        r = analyse_load(Vault.from_design(a=0.3, p_xy=0.75, tubes=3, **design), samples="all")
        return [
            r.static.displacements[apex(r.structure.model), 2],
            *r.modes.eigenvalues[:2],
            r.buckling.factor,
        ]

    def orders(rows):
        d = np.abs(np.diff(np.array(rows), axis=0))
        return np.log2(d[:-1] / d[1:])

    smooth = [values(samples=n) for n in (51, 101, 201, 401, 801)]
    o = orders(smooth)
    assert np.all(np.abs(o[:, 1] - 2) < 0.05), o  # λ₁
    assert np.all((o[:, 2] > 1.5) & (o[:, 2] < 2.1)), o  # λ₂
    assert np.all(o[:, 0] > 1.2) and 1.8 < o[-1, 0] < 2.3, o  # the apex
    assert orders([r[3:] for r in smooth[:3]])[0, 0] > 1.2  # buckling, before the feet's local mode
    panels = orders([values(panels=n) for n in (16, 32, 64, 128, 256)])
    assert np.all(panels[:, 0] > 1.0) and np.all(panels[:, 2] > 1.8), panels


def test_the_full_vault_and_its_panel_version_agree():
    """The paper's vault at full resolution (401 samples) and with 64 panels: weight, deflection,
    the folding mode."""
    smooth, panels = (analyse_load(Vault.from_design(a=0.3, p_xy=0.75, panels=p)) for p in (0, 64))
    assert smooth.total_weight == pytest.approx(panels.total_weight, rel=1e-3)
    assert smooth.static.max_displacement == pytest.approx(panels.static.max_displacement, rel=0.05)
    for r in (smooth, panels):
        assert (
            r.fold_correlation > 0.97
            and r.soft.count == 1
            and r.static.equilibrium_error < EQUILIBRIUM
        )
    assert smooth.modes.eigenvalues[0] == pytest.approx(panels.modes.eigenvalues[0], rel=0.1)


def test_a_model_of_parts_needs_its_supports_and_masses():
    model = BarHingeModel(
        np.eye(3), [[0, 1], [1, 2], [0, 2]], np.ones(3), np.zeros((0, 4)), [], [1.0, 0.0, 1.0]
    )
    with pytest.raises(InputError, match="^a model without a structure needs its supported nodes"):
        Supports().fixed(model)
    with pytest.raises(
        InputError, match="^the modes need every node to have mass; node 1 has none"
    ):
        free_modes(model, 1)
    with pytest.raises(InputError, match=r"^bar_stiffness must be finite and ≥ 0"):
        BarHingeModel(np.eye(3), [[0, 1]], [-1.0], np.zeros((0, 4)), [], np.ones(3))
    with pytest.raises(InputError, match=r"^bars must index the 3 nodes"):
        BarHingeModel(np.eye(3), [[0, 3]], [1.0], np.zeros((0, 4)), [], np.ones(3))
    with pytest.raises(InputError, match=r"^supports must be one of \"pinned\", \"roller\""):
        Supports("glued")
