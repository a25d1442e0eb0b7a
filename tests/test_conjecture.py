"""The paper's conjecture measured: the inextensional motions of a single fold, a tube, a block and
the vault.

The paper (section Kinematics) conjectures that a tube whose boundary curves are straight
quads, with no cone apex, has the rigid folding motion as its only motion, while a single
curved fold has excess freedom (rulings that drift, its Fig. 08). Measured here by the
null space of the bars (:func:`curvefold.mechanics.conjecture_counts`): the motions that
stretch no bar at first order, the sheet free to bend at its rulings and across its
panels' diagonals (the discrete form of drifting rulings), on the exact panel structures
and on the smooth ones, at growing resolution. The counts are exact integers with a gap
of orders of magnitude in the singular values; the spectrum of the stiffness confirms
them (as many eigenvalues below a gap that widens as the sheet thins).
"""

from __future__ import annotations

import numpy as np
import pytest

from curvefold import Crease, Lattice, SpaceCurve, Structure
from curvefold.geometry import Mesh, PanelLattice
from curvefold.mechanics import (
    MATERIALS,
    BarHingeModel,
    StructureModel,
    conjecture_counts,
    free_modes,
    soft_modes,
)
from curvefold.vault import Vault

PP = MATERIALS["polypropylene"]
BLOCK = [(0, 0), (0, 1), (1, 0), (1, 1)]


def lattice(samples: int = 161) -> Lattice:
    curve = SpaceCurve.from_curvature(
        lambda s: 1 + 0.3 * np.sin(s), lambda s: 0.2 + 0.3 * np.cos(s), 3.0, samples=samples
    )
    return Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.08)


def structures(lat, vault_resolution: dict) -> dict[str, StructureModel]:
    def model(structure, sheets=None):
        return StructureModel.from_state(structure.state(), PP, 1e-3, sheets=sheets)

    return {
        "single fold": model(Structure.tube(lat), (0,)),
        "tube": model(Structure.tube(lat)),
        "block": model(Structure.from_cells(lat, BLOCK)),
        "vault": model(Vault.from_design(**vault_resolution).structure),
    }


def counts(structure: StructureModel, *, drop: tuple[str, ...] = ()) -> dict[str, int]:
    found = {name: soft for name, soft in conjecture_counts(structure).items() if name not in drop}
    for name, soft in found.items():
        s = soft.singular_values
        # a gap around rtol = 1e-6
        assert s[: soft.count + 6].max() < 3e-8 and s[soft.count + 6] > 5e-6, (
            name,
            s[: soft.count + 8],
        )
    return {name: soft.count for name, soft in found.items()}


#: What the panel structures give at N = 8, 16, 32, 64 panels (N + 1 vertices along each crease).
def expected(n: int) -> dict[str, dict[str, int]]:
    whole = {"end planar": 1, "end diagonals": 0, "rulings fixed": 1}
    return {
        "single fold": {"free": 2 * n - 1, "rulings fixed": 1},
        "tube": {"free": 2, **whole},
        "block": {"free": 1, **whole},
        "vault": {"free": 1, **whole},
    }


@pytest.mark.parametrize("panels", [8, 16, 32, 64])
def test_the_conjecture_on_panel_structures(panels):
    """Exact rigid panels: a single fold drifts in 2N + 1 ways; a tube has one motion besides
    folding, gone once an end is planar."""
    lat = PanelLattice.from_lattice(lattice(), panels)
    found = {name: counts(s) for name, s in structures(lat, {"panels": panels}).items()}
    assert found == expected(panels + 1)


@pytest.mark.parametrize("samples", [9, 17, 33, 65])
def test_the_conjecture_on_smooth_structures(samples):
    """The smooth strips sampled: the same counts (the vault at 23 … 163 samples), its folding
    inextensional to O(h⁴) of its size."""
    found = {
        name: counts(s, drop=("rulings fixed",))
        for name, s in structures(lattice(samples), {"samples": 5 * samples // 2 | 1}).items()
    }
    want = expected(samples)
    # the smooth ruling quads are planar to O(h³) only: held rigid, they leave nothing to fold
    for name in want:
        want[name].pop("rulings fixed")
    assert found == want


def test_the_extra_motion_of_a_tube_warps_its_end_sections():
    tube = structures(PanelLattice.from_lattice(lattice(), 16), {"panels": 16})["tube"]
    free = conjecture_counts(tube)["free"]
    folding = tube.fold_velocity().ravel()
    basis = np.concatenate([free.shapes.reshape(len(free.shapes), -1), folding[None]]).T
    # the null space holds the folding (with the rigid motions), and one motion more
    assert np.linalg.matrix_rank(basis, tol=1e-8 * np.abs(basis).max()) == free.count + 6
    from curvefold.mechanics._softmodes import planarity_rows

    ends = tube.end_sections()
    warp = np.abs(
        planarity_rows(tube.model.nodes, ends) @ free.shapes.reshape(len(free.shapes), -1).T
    )
    assert warp.max() > 1e-3  # some null motion warps the end sections out of their planes
    # folding keeps them planar
    assert (
        np.abs(planarity_rows(tube.model.nodes, ends) @ folding).max()
        < 1e-9 * np.abs(folding).max()
    )


def test_the_counts_agree_with_a_dense_svd():
    """An independent count: the nullity of the bars' compatibility matrix by LAPACK's SVD, rank
    tolerance 1e-9 σ_max."""
    for name, structure in structures(
        PanelLattice.from_lattice(lattice(), 8), {"panels": 8, "tubes": 2}
    ).items():
        s = np.linalg.svd(structure.model.compatibility().toarray(), compute_uv=False)
        nullity = int(np.count_nonzero(s <= 1e-9 * s[0])) + max(0, structure.model.dofs - len(s))
        assert nullity - 6 == soft_modes(structure.model).count, name


def test_the_spectrum_has_as_many_soft_modes_below_a_gap_that_widens_as_the_sheet_thins():
    """Free modes of the panel structures (N = 8) at t = 1 mm and 10 µm: as many eigenvalues as
    inextensional motions lie below a gap that widens as 1/t (their ω² ∝ t with the creases
    and the sheet's bending, the next ones' tends to a constant: stretching). Measured, gap at
    1 mm → 10 µm: single fold 55 → 1.0e4, tube 7.4 → 410, block 11.5 → 366, 3-tube vault 10.6
    → 61; the soft modes' share of energy in stretching 8 % at most at 1 mm, 1 % at 10 µm, the
    next mode's 87 % or more there."""
    lat = PanelLattice.from_lattice(lattice(), 8)
    cases = {
        "single fold": (Structure.tube(lat), (0,)),
        "tube": (Structure.tube(lat), None),
        "block": (Structure.from_cells(lat, BLOCK), None),
        "vault": (Vault.from_design(panels=8, tubes=3).structure, None),
    }
    for name, (structure, sheets) in cases.items():
        gaps = []
        for t, soft, stiff in ((1e-3, 0.1, 0.0), (1e-5, 0.02, 0.8)):
            sm = StructureModel.from_state(structure.state(), PP, t, sheets=sheets)
            c = soft_modes(sm.model).count
            modes = free_modes(sm.model, c + 1)
            gaps.append(modes.eigenvalues[c] / modes.eigenvalues[c - 1])
            assert modes.stretching[:c].max() < soft and modes.stretching[c] > stiff, (
                name,
                t,
                modes.stretching,
            )
        assert gaps[0] > 5 and gaps[1] > 5 * gaps[0], (name, gaps)


def test_damaged_structures_count_otherwise():
    lat = PanelLattice.from_lattice(lattice(), 8)
    tube = Structure.tube(lat)
    topology = tube.topology("quads")
    mesh = topology.mesh(tube.state().vertices)
    # the seams not welded: two single folds side by side, each drifting
    sheets = [_sheet_mesh(mesh, sheet) for sheet in topology.sheets]
    apart = BarHingeModel.from_mesh(_joined(sheets), PP, 1e-3, crease_stiffness=1.0)
    assert soft_modes(apart).count == 2 * (2 * 9 - 1) + 6
    # a block's tubes not bonded: each tube moves on its own
    block = Structure.from_cells(lat, BLOCK)
    loose = BarHingeModel.from_mesh(
        block.topology("quads").mesh(block.state().vertices), PP, 1e-3, crease_stiffness=1.0
    )
    assert soft_modes(loose).count == 4 * 2 + 3 * 6
    # a tube whose crease pattern is not flat-foldable (its vertices moved): no rigid folding left
    rng = np.random.default_rng(2)
    sm = StructureModel.from_state(tube.state(), PP, 1e-3)
    moved = BarHingeModel.from_mesh(
        mesh.with_coords(mesh.vertices_coords + _same(topology, sm, rng)),
        PP,
        1e-3,
        crease_stiffness=1.0,
        weld=np.searchsorted(
            sm.node_sample * len(tube.curves_uv) + sm.node_curve,
            topology.vertex_sample * len(tube.curves_uv) + topology.vertex_curve,
        ),
    )
    assert soft_modes(moved, held_hinges=("diagonal",)).count == 0


def _same(topology, sm: StructureModel, rng) -> np.ndarray:
    """A random move of every lattice point (5e-3 of the size), the same for every copy of the
    point in the mesh."""
    move = rng.normal(scale=5e-3 * sm.model.size, size=(len(sm.model.nodes), 3))
    key = sm.node_sample * (sm.node_curve.max() + 1) + sm.node_curve
    index = np.searchsorted(
        key, topology.vertex_sample * (sm.node_curve.max() + 1) + topology.vertex_curve
    )
    return move[index]


def _sheet_mesh(mesh: Mesh, sheet) -> Mesh:
    return Mesh(
        mesh.vertices_coords[sheet.vertices],
        sheet.edges_vertices,
        mesh.edges_assignment[sheet.edges],
        mesh.edges_foldAngle[sheet.edges],
        sheet.faces_vertices,
        mesh.edges_kind[sheet.edges],
        mesh.faces_group[sheet.faces],
    )


def _joined(meshes: list[Mesh]) -> Mesh:
    offsets = np.cumsum([0] + [len(m.vertices_coords) for m in meshes])
    return Mesh(
        np.concatenate([m.vertices_coords for m in meshes]),
        np.concatenate([m.edges_vertices + o for m, o in zip(meshes, offsets)]),
        np.concatenate([m.edges_assignment for m in meshes]),
        np.concatenate([m.edges_foldAngle for m in meshes]),
        np.concatenate([m.faces_vertices + o for m, o in zip(meshes, offsets)]),
        np.concatenate([m.edges_kind for m in meshes]),
        np.concatenate([m.faces_group for m in meshes]),
    )
