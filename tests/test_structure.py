"""Tubes, cellular blocks and stacks: topology, meshes, fold angles, isometry to the flat state."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from curvefold import Crease, InputError, Lattice, RegressionError, SpaceCurve, Structure, measure
from curvefold.geometry._mesh import edges_faces


def make_lattice(samples=201, fold_angle=60.0, widths=(0.2, 0.15)):
    curve = SpaceCurve.from_curvature(
        lambda s: 1 + 0.3 * np.sin(s), lambda s: 0.3 * np.cos(1.5 * s), 3.0, samples=samples
    )
    return Lattice.from_crease(Crease.from_curve(curve, fold_angle=fold_angle), *widths)


@pytest.fixture(scope="module")
def tube():
    return Structure.tube(make_lattice())


def test_tube_topology(tube):
    assert tube.curves_uv.tolist() == [[0, 0], [0, 1], [1, 0], [1, 1]]
    assert tube.curve_kinds == ("fold", "seam", "seam", "fold")
    mesh = tube.state().mesh()
    n = len(tube.lattice.s)
    assert mesh.faces_vertices.shape == (4 * 2 * (n - 1), 3)
    # a closed strip: every curve and ruling edge has one face on each side
    ef = edges_faces(mesh.faces_vertices, mesh.edges_vertices)
    interior = mesh.edges_kind != "boundary"
    assert (ef[interior] >= 0).all()
    assert ((ef[~interior] >= 0).sum(axis=1) == 1).all()  # the end rulings border one face


def test_normals_point_out_of_the_tube(tube):
    state = tube.state()
    mesh = state.mesh()
    n = len(tube.lattice.s)
    centre = state.vertices.mean(axis=0)  # (n, 3) centre of every section
    faces = mesh.faces_vertices
    sample = np.minimum(faces[:, 0] % n, n - 2)
    outward = mesh.vertices_coords[faces].mean(axis=1) - centre[sample]
    assert (np.einsum("ij,ij->i", mesh.face_normals(), outward) > 0).all()


@pytest.mark.parametrize("fold_angle", [0.0, 30.0, 60.0, 120.0, 170.0])
def test_fold_angles_and_assignments(tube, fold_angle):
    state = tube.state(fold_angle)
    mesh = state.mesh()
    # The crease is a polyline: its edges' angles are within O((κh)²) of the smooth fold angle;
    # κ = κ_2D / cos α grows as the tube closes, so the bound is scaled by it.
    kh = state.lattice.crease.curve.kappa(tube.lattice.s).max() * tube.lattice.s[1]
    assert measure.fold_angle_error(mesh, fold_angle) < 0.01 + 10 * kh**2
    creases = np.isin(mesh.edges_kind, ("fold", "seam"))
    # convex tube
    assert set(mesh.edges_assignment[creases & (np.abs(mesh.edges_foldAngle) > 1e-9)]) <= {"M"}
    assert set(mesh.edges_assignment[mesh.edges_kind == "boundary"]) == {"B"}
    assert set(mesh.edges_assignment[np.isin(mesh.edges_kind, ("ruling", "diagonal"))]) == {"F"}
    assert_allclose(
        tube.dihedral_angles(fold_angle)[0],
        np.radians([180 - fold_angle, fold_angle, 180 - fold_angle, fold_angle]),
    )


def test_every_state_is_isometric_to_the_flat_crease_pattern():
    """Edge lengths and corner angles of all strips match the flat state; errors fall as h²."""
    errors, bounds = [], []
    for samples in (101, 201, 401):
        st = Structure.tube(make_lattice(samples=samples))
        flat = st.state(0).mesh()
        worst = max(
            measure.isometry_error(st.state(f).mesh(), flat).max_relative_edge_error
            for f in (40.0, 100.0, 170.0)
        )
        errors.append(worst)
        # a chord of an arc of curvature κ is shorter by the factor (κh)²/24: the polyline
        # curves' edges change as κ changes between states; the rulings are exact
        kappa = max(
            st.state(f).lattice.crease.curve.kappa(st.lattice.s).max() for f in (0.0, 170.0)
        )
        bounds.append((kappa * st.lattice.s[1] * 1.5) ** 2 / 24)
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(orders > 1.9), orders
    assert np.all(np.array(errors) < np.array(bounds)), (errors, bounds)


def test_ruling_quads_are_planar_to_discretisation():
    values = [
        measure.ruling_quad_planarity(Structure.tube(make_lattice(samples=n)).state())
        for n in (101, 201, 401)
    ]
    orders = np.log2(np.array(values[:-1]) / np.array(values[1:]))
    assert np.all(orders > 2.8), orders  # third order: consecutive rulings are coplanar
    assert values[-1] < 1e-7


def test_cellular_block_and_diagonal_stack():
    lat = make_lattice(widths=(0.05, 0.05))
    block = Structure.from_cells(lat, [(0, 0), (0, 1), (1, 0), (1, 1)])
    assert len(block.curves_uv) == 9
    assert block.curve_kinds[list(map(tuple, block.curves_uv.tolist())).index((1, 1))] == "junction"
    stack = Structure.diagonal(lat, 3)
    assert stack.cells.tolist() == [[0, 0], [1, 1], [2, 2]]
    # curve 3 of one tube is curve 1 of the next
    assert set(map(tuple, stack.curves_uv[stack.cell_curves[:-1, 2]].tolist())) == set(
        map(tuple, stack.curves_uv[stack.cell_curves[1:, 0]].tolist())
    )
    assert all(k in ("fold", "seam") for k in stack.curve_kinds)
    down = Structure.diagonal(lat, 2, direction=-1, layers=2)
    assert sorted(down.cells.tolist()) == [[-2, -2], [-2, -1], [-1, -1], [-1, 0]]
    mesh = block.state().mesh()
    # each tube keeps its own copy of shared curves
    assert len(mesh.vertices_coords) == 4 * 4 * len(lat.s)


def test_structure_refusals():
    lat = make_lattice()
    lam = float(lat.domain.extent([1, 1]))
    with pytest.raises(
        RegressionError,
        match=r"cells: lattice curve \(u, v\) = .* passes the " r"curve of regression",
    ):
        Structure.diagonal(lat, int(np.ceil(lam)) + 1)
    with pytest.raises(InputError, match="cells must be distinct"):
        Structure.from_cells(lat, [(0, 0), (0, 0)])
    with pytest.raises(
        InputError, match=r"cells must be a non-empty list of \(i, j\) integer " r"pairs"
    ):
        Structure.from_cells(lat, [])
    with pytest.raises(InputError, match="cells must hold integers"):
        Structure.from_cells(lat, [(0.5, 0)])
    with pytest.raises(InputError, match=r"count \(tubes\) must be an integer ≥ 1, got 0"):
        Structure.diagonal(lat, 0)


def test_erratum_quadrants_follow_the_construction_order(tube):
    """The paper names the quadrants inconsistently; the construction fixes them.

    Curve 1 → 2 along +r_R, 2 → 3 along +r_L, 3 → 4 along −r_R, 4 → 1 along −r_L. Seen from
    each crease, its two strips then lie in quadrants L+R+ (crease 1), L+R− (2), L−R− (3)
    and L−R+ (4): folds where both signs agree, seams where they differ, with interior
    angles π − 2α and 2α measured on the built tube.
    """
    from curvefold.geometry._crease import QUADRANTS
    from curvefold.geometry._topology import CORNER_KINDS

    corners = [(0, 0), (0, 1), (1, 1), (1, 0)]
    lat = tube.lattice
    X = {c: lat.points(np.array(c, float)) for c in corners}
    rl, rr = lat.crease.rulings()
    T = lat.crease.curve.tangent
    j = len(lat.s) // 3
    for k, c in enumerate(corners):
        prev, nxt = corners[k - 1], corners[(k + 1) % 4]
        signs = {}
        for other in (prev, nxt):
            d = X[other][j] - X[c][j]
            for side, r in (("L", rl[j]), ("R", rr[j])):
                if abs(abs(d @ r) / np.linalg.norm(d) - 1) < 1e-12:  # the strip runs along ±r
                    signs[side] = "+" if d @ r > 0 else "-"
        name = f"L{signs['L']}R{signs['R']}"
        assert name == ("L+R+", "L+R-", "L-R-", "L-R+")[k]
        assert QUADRANTS[name][2] == CORNER_KINDS[k]
        a, b = (X[prev][j] - X[c][j]), (X[nxt][j] - X[c][j])
        a, b = a - (a @ T[j]) * T[j], b - (b @ T[j]) * T[j]  # in the section plane
        angle = np.arccos(a @ b / np.linalg.norm(a) / np.linalg.norm(b))
        assert_allclose(angle, tube.dihedral_angles(60.0)[0, k], atol=1e-12)
