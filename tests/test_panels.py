"""Rigid planar panels (curvefold.geometry._panels): the construction proved at rounding level.

Error model of the rigidity checks: a panel state is built by rigid motions of the flat
panels, so a panel's sides and diagonals change only by the rounding of its vertex
coordinates, about ε · size; relative to a side of length ℓ that is ε · size / ℓ. The
tolerance below is 64 ε · size / ℓ_min (the measured errors stay under 3 ε · size / ℓ_min).
"""

from __future__ import annotations

import json
import pickle

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.optimize import least_squares

from _cli import run
from _node import run_node
from curvefold import Crease, Lattice, SpaceCurve, Structure
from curvefold.app import parse_design
from curvefold.app._build import build, vault_design
from curvefold.geometry import PanelLattice, choose_sampling, fold_angles
from curvefold.geometry._panel_pattern import PanelPattern, fold_line_angle
from curvefold.geometry._sheets import sheets
from curvefold.io import PatternOutput, layout_pattern, to_fold, write_3d, write_structure_fold
from curvefold.kernel import InputError, RegressionError
from curvefold.vault import Vault, VaultDesign, solve_panel_arch, solve_symmetric_arch
from curvefold.vault._assembly import standing

EPS = np.finfo(float).eps
ANGLES = (0.0, 1e-6, 0.5, 30.0, 90.0, 150.0, 179.0)


def varying_lattice(samples: int) -> Lattice:
    """A crease of varying curvature and torsion, folded at 90°, with its unit cell."""
    curve = SpaceCurve.from_curvature(
        lambda s: 1 + 0.3 * np.sin(s), lambda s: 0.2 + 0.3 * np.cos(s), 3.0, samples=samples
    )
    return Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.08)


@pytest.fixture(scope="module")
def smooth():
    return varying_lattice(1281)


@pytest.fixture(scope="module")
def tube(smooth):
    return Structure.tube(PanelLattice.from_lattice(smooth, 12))


@pytest.fixture(scope="module")
def block(smooth):
    return Structure.from_cells(PanelLattice.from_lattice(smooth, 10), [(0, 0), (0, 1), (1, 1)])


@pytest.fixture(scope="module")
def vault():
    return Vault.from_design(VaultDesign(panels=12, tubes=3))


def panel_shapes(mesh) -> tuple[np.ndarray, np.ndarray]:
    """The six distances between the corners of every quad (F, 6), and its non-planarity (F,).

    Non-planarity: distance of the fourth corner from the plane of the first three over the
    quad's diagonal.
    """
    p = mesh.vertices_coords[mesh.faces_vertices]
    i, j = np.triu_indices(4, 1)
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    height = np.einsum("ij,ij->i", p[:, 3] - p[:, 0], n) / np.linalg.norm(n, axis=1)
    return np.linalg.norm(p[:, i] - p[:, j], axis=-1), np.abs(height) / np.linalg.norm(
        p[:, 2] - p[:, 0], axis=1
    )


def rigidity(
    structure: Structure, angle: float, *, anchor: str = "start"
) -> tuple[float, float, float]:
    """(largest relative change of sides and diagonals, largest non-planarity, tolerance) of a
    state."""
    flat, _ = panel_shapes(structure.state(0.0).mesh())
    mesh = structure.state(angle, anchor=anchor).mesh()
    shape, planarity = panel_shapes(mesh)
    size = float(np.ptp(mesh.vertices_coords, axis=0).max())
    return (
        float(np.abs(shape / flat - 1).max()),
        float(planarity.max()),
        64 * EPS * size / float(flat.min()),
    )


# -- the flat-foldable vertex
# ------------------------------------------------------------------------


def _rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def vertex_closure(turning: float, beta: float, crease: float, folds: np.ndarray) -> np.ndarray:
    """Going round a degree-4 vertex: the rotation about each crease ray in turn, minus identity.

    Rays in the flat pattern, counter-clockwise: T_k at φ/2, the left fold line at β, −T_{k−1}
    at π − φ/2, the right fold line at −β; fold angles (crease, ρ_L, ρ_3, ρ_R) on them.
    """
    rays = [
        np.array([np.cos(a), np.sin(a), 0.0])
        for a in (turning / 2, beta, np.pi - turning / 2, -beta)
    ]
    M = np.eye(3)
    for ray, angle in zip(rays[1:] + rays[:1], list(folds) + [crease]):
        M = M @ _rotation(ray, angle)
    return (M - np.eye(3)).ravel()


@pytest.mark.parametrize("seed", range(6))
def test_fold_line_angle_closes_the_vertex_and_agrees_with_a_numerical_solve(seed):
    rng = np.random.default_rng(seed)
    turning, alpha = rng.uniform(0.01, 0.6), rng.uniform(0.05, 1.5)
    beta = rng.uniform(turning / 2 + 0.05, np.pi - turning / 2 - 0.05)
    rho = float(fold_line_angle(turning, beta, alpha))
    closed = vertex_closure(turning, beta, 2 * alpha, [-rho, 2 * alpha, rho])
    assert np.abs(closed).max() < 1e-14
    # an independent solve from a small-angle guess finds the same branch: the two crease edges
    # equal
    solved = least_squares(
        lambda f: vertex_closure(turning, beta, 2 * alpha, f),
        [0.0, 2 * alpha + 0.01, 0.0],
        xtol=1e-15,
        ftol=1e-15,
        gtol=1e-15,
    )
    assert_allclose(solved.x, [-rho, 2 * alpha, rho], atol=1e-10)
    # the closure can fail: the same formula with cos(φ/2) in place of sin(φ/2) leaves the vertex
    # open
    wrong = 2 * np.arctan(np.cos(turning / 2) / np.sin(beta) * np.tan(alpha))
    assert np.abs(vertex_closure(turning, beta, 2 * alpha, [-wrong, 2 * alpha, wrong])).max() > 1e-2


def test_straight_crease_keeps_its_fold_lines_flat():
    assert fold_line_angle(0.0, 0.7, np.array([0.1, 1.0])).tolist() == [0.0, 0.0]


# -- every panel is rigid and planar in every state ----------------------------------------------


@pytest.mark.parametrize("name", ["tube", "block", "vault"])
def test_every_panel_keeps_its_sides_diagonals_and_plane_in_every_state(name, request):
    """Flat, nearly flat, folded, nearly closed, and (for the vault) the first contact."""
    built = request.getfixturevalue(name)
    structure, contact = (
        (built.structure, built.first_contact()) if name == "vault" else (built, None)
    )
    for angle in ANGLES + ((contact,) if contact else ()):
        for anchor in ("start", "middle"):
            isometry, planarity, tolerance = rigidity(structure, angle, anchor=anchor)
            assert isometry <= tolerance and planarity <= tolerance, (
                angle,
                anchor,
                isometry,
                planarity,
                tolerance,
            )
    # the measure can fail: one vertex moved by 1e-9 of the size
    mesh = structure.state(90.0).mesh()
    moved = mesh.vertices_coords.copy()
    moved[len(moved) // 2] += 1e-9 * np.ptp(moved, axis=0).max()
    shape, planarity = panel_shapes(mesh.with_coords(moved))
    flat, _ = panel_shapes(structure.state(0.0).mesh())
    assert np.abs(shape / flat - 1).max() > tolerance and planarity.max() > tolerance


def test_a_pattern_without_flat_foldable_vertices_does_not_fold_rigidly(tube):
    """Damaged pattern: the left fold lines turned by 1e-3 rad off the mirror of the right ones."""
    p = tube.lattice.pattern
    c, s = np.cos(1e-3), np.sin(1e-3)
    left = p.left @ np.array([[c, s], [-s, c]])
    damaged = PanelPattern(p.s, p.points, p.tangents, p.beta, left, p.right)
    lattice = PanelLattice(damaged, tube.lattice.alpha, np.eye(3), np.zeros(3))
    isometry, planarity, tolerance = rigidity(Structure.tube(lattice), 90.0)
    assert isometry > 1e3 * tolerance or planarity > 1e3 * tolerance


def test_the_flat_state_is_the_crease_pattern(tube):
    x = tube.state(0.0).vertices.reshape(-1, 3)
    # b̃ at vertex 0: the pattern's normal when flat
    normal = tube.lattice.refold(0.0).crease.curve.frames[0][:, 2]
    assert np.abs((x - x[0]) @ normal).max() < 4 * EPS * np.ptp(x, axis=0).max()
    # sheet A (corners 4, 1, 2: x + L, x, x + R) developed is the pattern, up to a rigid motion
    p = tube.lattice.pattern
    pattern = np.concatenate([p.points + p.left, p.points, p.points + p.right])
    sheet = sheets(tube)[0].mesh.vertices_coords[:, :2]

    def distances(q):
        return np.linalg.norm(q[:, None] - q[None], axis=-1)

    assert (
        np.abs(distances(sheet) - distances(pattern)).max()
        < 8 * EPS * np.ptp(pattern, axis=0).max()
    )


def test_fold_angle_is_the_same_along_every_crease_and_the_fold_lines_follow_the_closed_form(tube):
    topology, p = tube.topology(), tube.lattice.pattern
    ends = topology.edges_vertices
    curve_a, curve_b = topology.vertex_curve[ends[:, 0]], topology.vertex_curve[ends[:, 1]]
    sample = topology.vertex_sample[ends[:, 0]]
    c1, c2, c4 = tube.cell_curves[0, [0, 1, 3]]
    inner = (sample > 0) & (sample < p.panels) & (curve_a != curve_b)
    for angle in (20.0, 90.0, 160.0):
        mesh = tube.state(angle).mesh()
        measured = fold_angles(mesh.vertices_coords, mesh.faces_vertices, mesh.edges_vertices)
        creases = (curve_a == curve_b) & (mesh.edges_kind == "fold")
        assert_allclose(measured[creases], -angle, atol=1e-11)  # creases 1 and 3: mountains of 2α
        assert_allclose(measured[mesh.edges_kind == "seam"], -(180.0 - angle), atol=1e-11)
        # the fold lines of crease 1 at its inner vertices: ± the closed form, opposite on its two
        # sides
        rho = np.degrees(fold_line_angle(p.turning, p.beta, np.radians(angle / 2)))[1:-1]
        signs = []
        for other in (c2, c4):
            pick = inner & (
                ((curve_a == c1) & (curve_b == other)) | ((curve_b == c1) & (curve_a == other))
            )
            got = measured[pick][np.argsort(sample[pick])]
            assert_allclose(np.abs(got), np.abs(rho), atol=1e-10)
            signs.append(np.sign(got))
        assert (signs[0] == -signs[1]).all() and len(set(signs[0].tolist())) == 1


def test_vertex_frames_are_orthonormal_and_the_fold_lines_symmetric_about_them(tube):
    for angle in ANGLES:
        lattice = tube.lattice.refold(angle)
        F = lattice.crease.curve.frames
        assert np.abs(np.swapaxes(F, 1, 2) @ F - np.eye(3)).max() < 8 * EPS
        assert (np.linalg.det(F) > 0).all()
        lhat = lattice.left / np.linalg.norm(lattice.left, axis=1, keepdims=True)
        rhat = lattice.right / np.linalg.norm(lattice.right, axis=1, keepdims=True)
        # l̂ and r̂ make equal angles with t̃ and mirror each other across the (t̃, b̃) plane
        assert_allclose(
            np.einsum("ki,ki->k", lhat, F[:, :, 0]),
            np.einsum("ki,ki->k", rhat, F[:, :, 0]),
            atol=1e-14,
        )


def test_anchors_keep_their_frame_and_the_vectorised_motion_agrees(tube):
    lattice = tube.lattice
    for anchor, k in (("start", 0), ("middle", lattice.pattern.panels // 2)):
        for angle in (0.0, 37.0, 120.0):
            other = lattice.refold(angle, anchor=anchor)
            assert_allclose(
                other.crease.curve.frames[k], lattice.crease.curve.frames[k], atol=1e-14
            )
            assert_allclose(
                other.crease.curve.points[k], lattice.crease.curve.points[k], atol=1e-15
            )
        batch = lattice.fold_points(tube.curves_uv, [0.0, 37.0, 120.0], anchor=anchor)
        one = np.stack(
            [lattice.refold(a, anchor=anchor).points(tube.curves_uv) for a in (0.0, 37.0, 120.0)]
        )
        assert_allclose(batch, one, atol=1e-14)


def test_discrete_width_law_and_regression_domain(tube):
    p = tube.lattice.pattern
    T = p.chords[1:-1]

    def height(v):  # distance of the tip of v from the line along T
        return T[:, 0] * v[:, 1] - T[:, 1] * v[:, 0]

    for side in (p.left, p.right):  # trapezoids: one height at both ends of every panel
        assert_allclose(height(side[1:]), height(side[:-1]), rtol=4 * EPS * p.panels)
    # the polyline (u, v) has edge k of length h_k (1 − u a_k − v b_k): the domain's factor,
    # measured
    for uv in ([1.0, 0.0], [0.0, 1.0], [1.0, 1.0], [2.0, -1.0]):
        line = tube.lattice.points(np.array(uv))
        measured = np.linalg.norm(np.diff(line, axis=0), axis=1) / p.edge_lengths
        assert_allclose(measured, p.domain.factor(np.array(uv)), rtol=1e-13)


def test_too_few_panels_and_regression_are_refused(smooth):
    with pytest.raises(InputError, match=r"panels must be ≥ 1 for a panel lattice"):
        PanelLattice.from_lattice(smooth, 0)
    with pytest.raises(
        InputError,
        match=r"^panels must be an integer in \[0, 100000\] \(memory " r"bound\), got 1000000$",
    ):
        PanelLattice.from_lattice(smooth, 10**6)
    # rulings 41° off the crease, which turns by 86° per panel: the fold lines would cross it (τ = 1
    # at 10° left widths below what coordinates resolve)
    tight = Lattice.from_crease(
        Crease.from_curve(SpaceCurve.from_curvature(3.0, 0.3, 2.0, samples=65), fold_angle=10),
        0.005,
        0.005,
    )
    with pytest.raises(
        InputError,
        match=r"^too few panels: at vertex 0 \(s = 0\) the crease "
        r"turns by 85.\d+° and its fold lines leave at 41.\d+°",
    ):
        PanelLattice.from_lattice(tight, 4)
    assert PanelLattice.from_lattice(tight, 16).pattern.panels == 16
    panel = PanelLattice.from_lattice(smooth, 12)
    limit = float(panel.domain.extent(np.array([1.0, 1.0])))
    with pytest.raises(
        RegressionError, match=r"lattice curve \(u, v\) = \(.*\) passes the curve " r"of regression"
    ):
        Structure.from_cells(panel, [(int(limit), int(limit))])
    with pytest.raises(InputError, match="lattice must be a Lattice"):
        PanelLattice.from_lattice(panel, 12)


# -- convergence to the smooth structure
# -------------------------------------------------------------


def orders(errors: list[float]) -> np.ndarray:
    return np.log2(np.array(errors[:-1]) / np.array(errors[1:]))


def test_panel_tube_converges_to_the_smooth_one_at_second_order(smooth):
    """Vertex positions at equal t, both placed by curve 1's frame at t = 0 (measured orders
    1.99–2.00)."""
    uv = Structure.tube(smooth).curves_uv
    for angle in (90.0, 40.0, 0.0):
        exact = smooth.refold(angle).points(uv)
        errors = []
        for n in (16, 32, 64, 128):
            panel = PanelLattice.from_lattice(smooth, n).refold(angle)
            errors.append(
                float(np.abs(panel.points(uv) - exact[:, :: (len(smooth.s) - 1) // n]).max())
            )
        assert ((orders(errors) > 1.95) & (orders(errors) < 2.05)).all(), (
            angle,
            errors,
            orders(errors),
        )


def test_panel_vault_stands_on_the_ground_and_converges_to_the_smooth_vault():
    smooth = Vault.from_design(VaultDesign(samples=641, tubes=2))
    errors, roots = [], []
    for n in (10, 20, 40, 80):
        vault = Vault.from_design(VaultDesign(panels=n, tubes=2))
        size = float(np.ptp(vault.vertices.reshape(-1, 3), axis=0).max())
        # both feet of every polyline on z = 0: the far one off by the arch condition's residual (≤
        # 6 ε measured) × span
        assert vault.ground_error() < 16 * EPS * size
        assert vault.lift_off([60.0]).max() > 1e-2  # and off it at another angle
        errors.append(float(np.abs(vault.vertices - smooth.vertices[:, :: 640 // n]).max()))
        roots.append(vault.kappa0_s0 - smooth.kappa0_s0)
    assert ((orders(errors) > 1.9) & (orders(errors) < 2.1)).all(), (errors, orders(errors))
    assert ((orders(roots) > 1.95) & (orders(roots) < 2.05)).all(), (roots, orders(roots))


def test_panel_vault_motion_keeps_its_feet_or_its_symmetry(vault):
    angles = [0.0, 45.0, 90.0, 120.0]
    held = vault.lift_off(angles, anchor="start")
    assert (
        held[:, 0].max() < 1e-15 and held[2, 1] < 1e-14 and (np.delete(held[:, 1], 2) > 0.5).all()
    )
    # the apex vertex's frame held: a motion symmetric about it
    apex = vault.lift_off(angles, anchor="middle")
    assert_allclose(apex[:, 0], apex[:, 1], atol=1e-14)
    assert apex[2].max() < 1e-14 and (np.delete(apex[:, 0], 2) > 0.1).all()


def test_the_smooth_arch_root_does_not_stand_a_panel_vault():
    """The discrete Eq. (20) matters: the same panels on the smooth κ0 s0 lift a foot."""
    vault = Vault.from_design(VaultDesign(panels=12, tubes=1))
    smooth = Vault.from_design(VaultDesign(tubes=1, samples=vault.design.samples))
    lifted = standing(PanelLattice.from_lattice(smooth.lattice, 12))
    far = lifted.points(np.array([[1.0, 1.0]]))[0, -1, 2]
    assert abs(far) > 1e-3 > 1e6 * vault.ground_error()
    assert abs(solve_panel_arch(0.3, 12).kappa0_s0 - solve_symmetric_arch(0.3).kappa0_s0) > 1e-3


# -- exporters
# ---------------------------------------------------------------------------------------------


def test_fold_file_has_planar_quads_without_diagonals_and_welded_seams(tube):
    model = to_fold(tube, fold_angles=[0.0, 45.0, 90.0])
    cp = model.crease_pattern
    assert cp.faces_vertices.shape[1] == 4 and (cp.faces_vertices >= 0).all()
    assert set(cp.edges_kind.tolist()) == {"fold", "seam", "boundary"}
    # creases and fold lines
    assert set(cp.edges_assignment[cp.edges_kind == "fold"].tolist()) == {"M", "V"}
    for _, mesh in model.folded:
        x = mesh.vertices_coords
        a, b = model.seam_partners.T
        ends = np.stack([mesh.edges_vertices[a], mesh.edges_vertices[b][:, ::-1]])
        assert np.abs(x[ends[0]] - x[ends[1]]).max() < 4 * EPS * np.ptp(x, axis=0).max()


def test_crease_pattern_draws_every_panel_edge_as_one_straight_segment(tube):
    layout = layout_pattern(tube, PatternOutput(glue_tabs=False))
    for placed, sheet in zip(layout.sheets(), sheets(tube)):
        mesh = sheet.mesh
        page = mesh.vertices_coords[:, :2] @ placed.transform[:, :2].T + placed.transform[:, 2]
        folds = {tuple(sorted(e)) for e in mesh.edges_vertices[mesh.edges_kind == "fold"].tolist()}
        drawn = set()
        for line in placed.on_layer("mountain") + placed.on_layer("valley"):
            index = [int(np.argmin(np.linalg.norm(page - q, axis=1))) for q in line.points]
            # every drawn point is a panel corner
            assert np.abs(page[index] - line.points).max() < 1e-9
            drawn |= {tuple(sorted(pair)) for pair in zip(index[:-1], index[1:])}
        assert drawn == folds


@pytest.mark.node
def test_fold_libraries_rebuild_the_panels_and_rabbit_ear_folds_them_to_every_frame(tmp_path, tube):
    """Rabbit Ear folds the crease pattern by each frame's fold angles: the panel motion is
    consistent."""
    path = write_structure_fold(tmp_path / "tube.fold", tube, fold_angles=[0.0, 45.0, 90.0, 150.0])
    report = run_node("check_fold.mjs", str(path))
    fold, ear = report["fold"], report["rabbit_ear"]
    faces = len(to_fold(tube).crease_pattern.faces_vertices)
    assert (
        fold["same_vertex_sets"] and fold["same_orientation"] and fold["faces_rebuilt"] == faces
    ), fold
    assert ear["summary"] == "valid" and ear["faces_ccw"] == faces and ear["sheets"] == 2, ear
    assert len(ear["frames"]) == 4 and max(f["max_distance"] for f in ear["frames"]) < 1e-9, ear[
        "frames"
    ]


@pytest.mark.node
def test_3d_files_hold_the_planar_panels(tmp_path, tube):
    rhino3dm = pytest.importorskip("rhino3dm")
    files = write_3d(tmp_path / "tube", tube, [0.0, 45.0, 90.0], formats=("glb", "obj", "3dm"))
    faces = len(tube.topology().faces_vertices)
    obj = [
        line.split()[1:]
        for line in (tmp_path / "tube.obj").read_text().splitlines()
        if line.startswith("f ")
    ]
    assert len(obj) == faces and {len(f) for f in obj} == {4}
    report = run_node("validate_gltf.mjs", str(tmp_path / "tube.glb"))
    assert report["errors"] == 0 and report["info"]["totalTriangleCount"] == 2 * faces, report[
        "messages"
    ]
    # Rhino: one quad per panel in the sheets' meshes (rhino3dm reads the vertices back in single
    # precision, ~6e-8 relative), the creases as polylines, and the strips ruled between them: their
    # panels exactly
    model = rhino3dm.File3dm.Read(str(tmp_path / "tube.3dm"))
    meshes = [o.Geometry for o in model.Objects if isinstance(o.Geometry, rhino3dm.Mesh)]
    quads = np.array(
        [
            [f[0], f[1], f[2], f[3]]
            for m in meshes
            for f in (m.Faces[i] for i in range(m.Faces.Count))
        ]
    )
    assert len(meshes) == 2 and len(quads) == faces and (quads[:, 2] != quads[:, 3]).all()
    for m in meshes:
        p = np.array([[v.X, v.Y, v.Z] for v in m.Vertices])[
            [[f[k] for k in range(4)] for f in (m.Faces[i] for i in range(m.Faces.Count))]
        ]
        n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
        height = np.abs(np.einsum("ij,ij->i", p[:, 3] - p[:, 0], n)) / np.linalg.norm(n, axis=1)
        assert height.max() < 1e-6 * np.ptp(p.reshape(-1, 3), axis=0).max()
    creases = {
        o.Attributes.Name: o.Geometry
        for o in model.Objects
        if o.Attributes.Name.startswith(("fold", "seam"))
    }
    assert sorted(creases) == ["fold 1", "fold 2", "seam 1", "seam 2"]
    n = len(tube.lattice.s)
    assert all(c.Degree == 1 and len(c.Points) == n for c in creases.values())
    strips = [o.Geometry for o in model.Objects if isinstance(o.Geometry, rhino3dm.NurbsSurface)]
    assert len(strips) == 4 and all(s.Degree(0) == s.Degree(1) == 1 for s in strips)
    assert len(files) == 3


# -- design files and the command line
# --------------------------------------------------------------------


def test_panels_in_design_files_flags_and_the_api():
    tube = build(parse_design('kind = "tube"\n[curve]\npanels = 8', source="tube.toml"))
    assert (
        isinstance(tube.structure.lattice, PanelLattice)
        and tube.structure.lattice.pattern.panels == 8
    )
    # the smooth crease the panels sample, for the crease checks
    assert isinstance(tube.crease, Crease)
    # the apex is a vertex
    assert vault_design(parse_design('kind = "vault"\n[vault]\npanels = 7')).panels == 8
    with pytest.raises(
        InputError,
        match=r"^tube\.toml: \[curve\] panels must be an integer in "
        r"\[0, 100000\] \(memory bound\), got -1$",
    ):
        parse_design('kind = "tube"\n[curve]\npanels = -1', source="tube.toml")
    with pytest.raises(
        InputError,
        match=r"^panels must be 0 \(smooth\) or even for a vault "
        r"\(the apex is a vertex\), got 7$",
    ):
        VaultDesign(panels=7)
    single = run("crease", "--panels", "4")
    assert single.returncode == 2 and "unrecognized arguments: --panels" in single.stderr
    coarse = run("tube", "--panels", "1", "--json")
    assert (
        coarse.returncode == 2
        and coarse.stderr.count("\n") == 1
        and "too few panels" in coarse.stderr
    )


def test_panel_vault_output_folder_passes_check_and_mechanism(tmp_path):
    """The folder's FOLD file (its motion from flat to the first contact) passes `curvefold
    check` (welds of seams and bonds, and the rebuild from its recorded design) and `curvefold
    mechanism`; the report shows the certificate's mechanism."""
    out = tmp_path / "out"
    result = run("vault", "--panels", "8", "--tubes", "3", "--formats", "fold", "--out", str(out))
    assert result.returncode == 0, result.stderr
    assert "checks pass in every frame, and up to 2α = 135° (rigid panels)" in result.stdout
    assert (
        "motion             flat to 2α = 136°, where it first touches itself (first contact)"
        in result.stdout
    )
    report = json.loads((out / "report.json").read_text())
    checks = {c["name"]: c for c in report["certificate"]}
    assert {
        "panel_isometry",
        "panel_planarity",
        "panel_ground_plane",
        "mechanism_dof",
        "mechanism_clearance",
    } <= set(checks)
    assert all(c["passed"] for c in checks.values()), checks
    # every panel vertex
    assert report["mesh"]["mesh_samples_per_crease"] == [9, 9]
    assert report["mesh"]["mesh_deviation"] == 0
    assert [m["dof"] for m in report["mechanism"]["states"]] == [15, 1, 1] and report["mechanism"][
        "scope"
    ] == ""
    html = (out / "report.html").read_text()
    assert (
        "singular-values.png" in report["files"]
        and "<h2>Mechanism</h2>" in html
        and "smooth crease the panels sample" in html
    )
    checked = run("check", str(out / "vault.fold"), "--rebuild", "--json")
    assert checked.returncode == 0, checked.stdout
    result = json.loads(checked.stdout)
    angles = report["certificate_frames"]["fold_angles"]
    # flat, half and full design angle among them
    assert angles == [0, 15, 30, 45, 60, 75, 90, 105, 120, 135]
    assert (
        result["frames"] == len(angles)
        and result["not_run"] == []
        and all(c["status"] == "pass" for c in result["checks"])
    )
    # the tubes are glued, and the welds hold them
    assert json.loads((out / "vault.fold").read_text())["curvefold:bonds"]
    frames = run("mechanism", str(out / "vault.fold"), "--json")
    assert frames.returncode == 0 and [f["dof"] for f in json.loads(frames.stdout)["frames"]] == [
        15
    ] + [1] * (len(angles) - 1)


def test_files_keep_every_panel_vertex(vault):
    """Sampling does not thin a panel mesh (two panels joined into one quad are not planar); a
    thinning keep is refused."""
    sampling = choose_sampling(vault.structure)
    n = len(vault.lattice.s)
    assert all(np.array_equal(k, np.arange(n)) for k in sampling.keep) and sampling.deviation == 0
    # flat panels: arccos of a unit dot product resolves √(2ε)
    assert sampling.bend <= 4 * np.degrees(np.sqrt(2 * EPS))
    shortest = float(vault.structure.state().mesh().edge_lengths().min())
    # rounding: the folded panels keep their edges
    assert sampling.stretch <= 64 * EPS * sampling.size / shortest
    assert np.array_equal(
        vault.structure.topology(keep=sampling.keep).faces_vertices,
        vault.structure.topology().faces_vertices,
    )
    # the walk would keep 7 of the 13 vertices here
    loose = choose_sampling(vault.structure, tolerance=0.1, max_bend=30.0)
    assert all(len(k) == n for k in loose.keep)
    thinned = [np.arange(0, n, 2)] * len(vault.structure.cells)
    with pytest.raises(
        InputError,
        match=r"^keep: a panel mesh keeps every vertex of its "
        r"polylines \(13 per tube, 3 tubes\); two panels ",
    ):
        vault.structure.topology(keep=thinned)


def test_panel_values_are_frozen_and_pickle():
    smooth = Lattice.from_crease(
        Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.3, 3.0, samples=65), fold_angle=70),
        0.1,
        0.1,
    )
    # constant κ and τ pickle; a user's lambda does not
    tube = Structure.tube(PanelLattice.from_lattice(smooth, 8))
    again = pickle.loads(pickle.dumps(tube))
    assert_allclose(again.state(60.0).vertices, tube.state(60.0).vertices, rtol=0, atol=0)
    for array in (
        tube.lattice.pattern.left,
        tube.lattice.rotation,
        tube.lattice.crease.curve.frames,
        again.lattice.right,
    ):
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 0.0
