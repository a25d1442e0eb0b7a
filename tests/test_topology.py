"""One owner for the tube conventions; polygon meshes; quad faces through every writer.

The topology derives the crease kinds, quadrants, sheets and seam ids from the corner
order and numbers the mesh; every consumer (State.mesh, the developed sheets, the FOLD
writer, the measurements) reads it. The checks that guard what curvefold guarantees by
construction raise InternalError, and each is shown failing on damaged data.
"""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from _meshes import assert_written
from _node import run_node
from curvefold import (
    Crease,
    InputError,
    InternalError,
    Lattice,
    Mesh,
    SpaceCurve,
    State,
    Structure,
    measure,
)
from curvefold.analysis import check_fold
from curvefold.geometry._crease import QUADRANTS
from curvefold.geometry._mesh import edges_faces, face_sides, fold_angles, vector_areas
from curvefold.geometry._sheets import flat_plane, sheets
from curvefold.geometry._topology import (
    CORNER_KINDS,
    CORNER_QUADRANTS,
    CORNERS,
    SHEETS,
    STRIPS,
    Topology,
    _sheet,
    fold_assignment,
    seam_id,
    tube_strips,
)
from curvefold.io import (
    FoldOutput,
    fold_assignments,
    read_fold,
    to_fold,
    write_obj,
    write_stl,
    write_structure_fold,
)


def lattice(samples=81, widths=(0.2, 0.15), fold_angle=90.0):
    """A helix crease (κ = 1, τ = 0.3, length 3) and its lattice."""
    curve = SpaceCurve.from_curvature(1.0, 0.3, 3.0, samples=samples)
    return Lattice.from_crease(Crease.from_curve(curve, fold_angle=fold_angle), *widths)


@pytest.fixture(scope="module")
def tube():
    return Structure.tube(lattice())


@pytest.fixture(scope="module")
def block():
    return Structure.from_cells(lattice(widths=(0.08, 0.08)), [(0, 0), (0, 1), (1, 0), (1, 1)])


# --------------------------------------------------------------------------------------
# conventions


def test_conventions_follow_from_the_corner_order():
    assert CORNERS.tolist() == [[0, 0], [0, 1], [1, 1], [1, 0]]
    assert CORNER_QUADRANTS == ("L+R+", "L+R-", "L-R-", "L-R+")
    assert CORNER_KINDS == ("fold", "seam", "fold", "seam")
    for quadrant, kind in zip(CORNER_QUADRANTS, CORNER_KINDS):
        assert QUADRANTS[quadrant][2] == kind
    # every strip on exactly one sheet; the sheets' crease corners are the folds
    assert sorted(s for _, strips in SHEETS for s in strips) == [0, 1, 2, 3]
    for _, (first, second) in SHEETS:
        assert STRIPS[first][1] == STRIPS[second][0] and CORNER_KINDS[STRIPS[first][1]] == "fold"
    assert seam_id(np.array([0, 0, 3, 3]), np.array([1, 3, 1, 3])).tolist() == [0, 1, 6, 7]
    cells = np.array([[0, 1, 3, 2], [3, 4, 6, 5]])
    assert_array_equal(
        tube_strips(cells), [[0, 1], [1, 3], [3, 2], [2, 0], [3, 4], [4, 6], [6, 5], [5, 3]]
    )


def test_one_assignment_rule_for_states_sheets_and_fold_files(tube):
    kinds = np.array(["fold", "fold", "fold", "seam", "seam", "boundary", "ruling", "diagonal"])
    angles = np.array([30.0, -30.0, 0.0, -150.0, 20.0, 5.0, -5.0, 1.0])
    assert fold_assignment(kinds, angles).tolist() == ["V", "M", "F", "M", "V", "B", "F", "F"]
    assert fold_assignment(kinds, angles, seams_open=True).tolist() == [
        "V",
        "M",
        "F",
        "B",
        "B",
        "B",
        "F",
        "F",
    ]
    # no angle, no fold
    assert fold_assignment(np.array(["fold"]), np.array([np.nan])).tolist() == ["F"]
    for angle in (0.0, 60.0, 120.0):
        mesh = tube.state(angle).mesh()
        assert_array_equal(
            mesh.edges_assignment, fold_assignment(mesh.edges_kind, mesh.edges_foldAngle)
        )
    for sheet in sheets(tube):
        m = sheet.mesh
        assert_array_equal(
            m.edges_assignment, fold_assignment(m.edges_kind, m.edges_foldAngle, seams_open=True)
        )
        assert_array_equal(
            fold_assignments(m.edges_kind, m.edges_foldAngle, m.edges_assignment),
            m.edges_assignment,
        )
    # the FOLD writer only adds: a fold at angle 0 keeps an M/V it was given
    assert fold_assignments(
        np.array(["fold", "fold"]), np.zeros(2), np.array(["M", "B"])
    ).tolist() == ["M", "F"]


def test_topology_numbers_vertices_and_owns_its_sheets(block):
    topo = block.topology()
    K, n = len(block.cells), len(block.lattice.s)
    for name in (
        "vertex_curve",
        "vertex_sample",
        "faces_vertices",
        "faces_group",
        "edges_vertices",
        "edges_kind",
        "edges_seam",
    ):
        assert not getattr(topo, name).flags.writeable, name
    # vertex (4k + c)·n + j is sample j of the lattice curve at corner c of tube k
    k, c, j = np.unravel_index(np.arange(4 * K * n), (K, 4, n))
    assert_array_equal(topo.vertex_curve, block.cell_curves[k, c])
    assert_array_equal(topo.vertex_sample, j)
    state = block.state(70.0)
    assert_array_equal(
        topo.coords(state.vertices), state.vertices[block.cell_curves].reshape(-1, 3)
    )
    assert_array_equal(topo.faces_group, np.repeat(np.arange(4 * K), 2 * (n - 1)))
    assert [s.label for s in topo.sheets] == [
        f"tube {t} · sheet {s}" for t in range(1, K + 1) for s in "AB"
    ]
    for index, sheet in enumerate(topo.sheets):
        tube_k, which = divmod(index, 2)
        strips = SHEETS[which][1]
        assert set(topo.faces_group[sheet.faces]) == {4 * tube_k + s for s in strips}
        assert_array_equal(sheet.edges_seam, topo.edges_seam[sheet.edges])
        assert set(sheet.edges_seam[sheet.edges_seam >= 0]) == {2 * tube_k, 2 * tube_k + 1}
        assert_array_equal(topo.edges_kind[sheet.edges][sheet.edges_seam >= 0], "seam")
        for array in (
            sheet.vertices,
            sheet.faces,
            sheet.edges,
            sheet.faces_vertices,
            sheet.edges_vertices,
            sheet.edges_seam,
        ):
            assert not array.flags.writeable
        # every tube's sheet is the first tube's in its own numbering: the same as developed alone
        alone = _sheet(
            sheet.label,
            sheet.vertices,
            sheet.faces,
            sheet.edges,
            topo.faces_vertices,
            topo.edges_vertices,
            topo.edges_seam,
        )
        for field in ("faces_vertices", "edges_vertices", "edges_seam"):
            assert_array_equal(getattr(sheet, field), getattr(alone, field))
    # the quad topology numbers the vertices alike and has no diagonals
    quads = block.topology("quads")
    assert_array_equal(quads.vertex_curve, topo.vertex_curve)
    assert quads.faces_vertices.shape == (4 * K * (n - 1), 4)
    assert "diagonal" not in set(quads.edges_kind)
    with pytest.raises(InputError, match="faces must be 'triangles' or 'quads', got 'hexagons'"):
        Topology.tubes(block.cell_curves, n, faces="hexagons")


def test_quad_mesh_is_the_triangle_mesh_with_the_diagonals_merged(block):
    state = block.state(60.0)
    tri, quad = state.mesh(), state.mesh(faces="quads")
    assert_array_equal(quad.face_sizes(), 4)
    split = quad.triangulated()
    assert_array_equal(split.vertices_coords, tri.vertices_coords)

    def cycles(mesh):  # oriented triangles, each rotated to start at its smallest vertex
        return {tuple(np.roll(f, -int(np.argmin(f)))) for f in mesh.faces_vertices.tolist()}

    def edges(mesh, kind):
        return {tuple(sorted(e)) for e in mesh.edges_vertices[mesh.edges_kind == kind].tolist()}

    assert cycles(split) == cycles(tri)
    for kind in ("fold", "seam", "boundary", "ruling", "diagonal"):
        assert edges(split, kind) == edges(tri, kind), kind
    # the quads are planar to O(h³): their measured crease angles agree with the triangles'
    creases = np.isin(tri.edges_kind, ("fold", "seam"))
    lookup = {tuple(sorted(e)): a for e, a in zip(tri.edges_vertices.tolist(), tri.edges_foldAngle)}
    quad_angles = np.array(
        [
            lookup[tuple(sorted(e))]
            for e in quad.edges_vertices[np.isin(quad.edges_kind, ("fold", "seam"))].tolist()
        ]
    )
    assert_allclose(
        quad.edges_foldAngle[np.isin(quad.edges_kind, ("fold", "seam"))], quad_angles, atol=0.05
    )
    assert len(quad_angles) == creases.sum()
    assert measure.ruling_quad_planarity(state) < 1e-4


# --------------------------------------------------------------------------------------
# polygon meshes


def hinge(angle_deg: float) -> Mesh:
    """A unit square and a triangle hinged on the edge x = 1, the triangle folded by
    ``angle_deg`` (valley +)."""
    t = np.radians(angle_deg)
    coords = np.array(
        [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [1 + np.cos(t), 0.5, np.sin(t)]], float
    )
    faces = np.array([[0, 1, 2, 3], [1, 4, 2, -1]])
    edges = np.array([[0, 1], [1, 2], [2, 3], [3, 0], [1, 4], [4, 2]])
    kinds = np.array(["boundary", "fold", "boundary", "boundary", "boundary", "boundary"])
    return Mesh(
        coords, edges, np.full(6, "F"), np.zeros(6), faces, kinds, np.array([0, 1])
    ).with_coords(coords)


def test_polygon_mesh_sides_normals_and_fold_angles():
    mesh = hinge(50.0)
    assert mesh.face_sizes().tolist() == [4, 3]
    sides, face = face_sides(mesh.faces_vertices)
    assert sides.tolist() == [
        [0, 1],
        [1, 2],
        [2, 3],
        [3, 0],
        [1, 4],
        [4, 2],
        [2, 1],
    ] and face.tolist() == [0, 0, 0, 0, 1, 1, 1]
    assert_array_equal(
        edges_faces(mesh.faces_vertices, mesh.edges_vertices),
        [[0, -1], [0, 1], [0, -1], [0, -1], [1, -1], [1, -1]],
    )
    assert_allclose(mesh.face_normals()[0], [0, 0, 1], atol=0)
    assert_allclose(mesh.edges_foldAngle[1], 50.0, rtol=1e-13)
    assert mesh.edges_assignment.tolist() == ["F"] * 6  # with_coords measures, never reassigns
    # Newell's normal of a planar hexagon tilted in space, and twice its area
    phi = np.arange(6) * np.pi / 3
    flat = np.stack([np.cos(phi), np.sin(phi), np.zeros(6)], axis=1)
    tilt = np.array([[1, 0, 0], [0, np.cos(0.7), -np.sin(0.7)], [0, np.sin(0.7), np.cos(0.7)]])
    n = vector_areas(flat @ tilt.T + [3.0, -2.0, 5.0], np.arange(6)[None])
    assert_allclose(n[0], 3 * np.sqrt(3) * tilt[:, 2], rtol=1e-14, atol=1e-14)


def test_triangulated_splits_polygons_with_diagonals():
    mesh = hinge(-40.0)
    tri = mesh.triangulated()
    assert tri.faces_vertices.tolist() == [[0, 1, 2], [0, 2, 3], [1, 4, 2]]
    assert tri.faces_group.tolist() == [0, 0, 1]
    assert tri.edges_vertices[6:].tolist() == [[0, 2]]
    assert (tri.edges_kind[6], tri.edges_assignment[6], tri.edges_foldAngle[6]) == (
        "diagonal",
        "F",
        0.0,
    )
    assert_array_equal(tri.edges_vertices[:6], mesh.edges_vertices)
    assert tri.triangulated() is tri
    assert_allclose(
        fold_angles(tri.vertices_coords, tri.faces_vertices, tri.edges_vertices)[[1, 6]],
        [-40.0, 0.0],
        atol=1e-12,
    )


@pytest.mark.parametrize(
    ("faces", "match"),
    [
        (np.array([[0, 1]]), r"shape \(F, k\) with k ≥ 3"),
        (np.array([[0, 1, -1, -1]]), "at least 3 vertices; face 0"),
        (
            np.array([[0, -1, 1, 2]]),
            r"-1 may only pad the end of a face; face 0 is \[0, -1, 1, " r"2\]",
        ),
        (np.array([[0, 1, 2, -2]]), "-1 may only pad the end"),
    ],
)
def test_mesh_refuses_malformed_polygons(faces, match):
    with pytest.raises(InputError, match=match):
        Mesh(
            np.zeros((4, 3)),
            np.zeros((0, 2), int),
            np.zeros(0, str),
            np.zeros(0),
            faces,
            np.zeros(0, str),
            np.zeros(len(faces), int),
        )


# --------------------------------------------------------------------------------------
# quads through the writers


def test_quad_mesh_through_fold_obj_and_stl(tmp_path, tube):
    trimesh = pytest.importorskip("trimesh")
    path = write_structure_fold(
        tmp_path / "quads.fold",
        tube,
        fold_angles=[0.0, 45.0, 90.0],
        output=FoldOutput(faces="quads"),
    )
    model = to_fold(tube, fold_angles=[0.0, 45.0, 90.0], output=FoldOutput(faces="quads"))
    back = read_fold(path)
    assert back.crease_pattern.faces_vertices.shape == (4 * (len(tube.lattice.s) - 1), 4)
    assert_array_equal(back.crease_pattern.faces_vertices, model.crease_pattern.faces_vertices)
    assert_array_equal(back.seam_partners, model.seam_partners)
    for (_, got), (_, want) in zip(back.folded, model.folded):
        assert_written(got.vertices_coords, want.vertices_coords)
    report = check_fold(path)
    assert report.ok and report.frames == 3
    # the ruling quads bend by O(h³), measured across their fan diagonals
    assert 0 < report.max_face_planarity_error < 0.05
    # the same file with triangles measures the same bend across the same diagonals
    assert_allclose(
        check_fold(
            write_structure_fold(tmp_path / "tri.fold", tube, fold_angles=[0.0, 45.0, 90.0])
        ).max_face_planarity_error,
        report.max_face_planarity_error,
        rtol=1e-12,
    )

    mesh = tube.state().mesh(faces="quads")
    text = write_obj(tmp_path / "quads.obj", mesh).read_text()
    rows = [line.split()[1:] for line in text.splitlines() if line.startswith("f ")]
    assert_array_equal(np.array(rows, int) - 1, mesh.faces_vertices)
    write_stl(tmp_path / "quads.stl", mesh)
    stl = trimesh.load(tmp_path / "quads.stl", process=False)
    assert len(stl.faces) == 2 * len(mesh.faces_vertices)
    tri = mesh.triangulated()
    assert_allclose(stl.triangles, tri.vertices_coords[tri.faces_vertices], atol=1e-6, rtol=0)


@pytest.mark.node
def test_node_rebuilds_the_quad_crease_pattern(tmp_path, tube):
    """The `fold` library rebuilds the quad faces from the planar graph; Rabbit Ear finds them
    valid and counter-clockwise."""
    path = write_structure_fold(tmp_path / "quads.fold", tube, output=FoldOutput(faces="quads"))
    report = run_node("check_fold.mjs", str(path))
    fold, ear = report["fold"], report["rabbit_ear"]
    faces = 4 * (len(tube.lattice.s) - 1)
    assert (
        fold["same_vertex_sets"] and fold["same_orientation"] and fold["faces_rebuilt"] == faces
    ), fold
    assert ear["summary"] == "valid" and ear["faces_ccw"] == faces and ear["faces_cw"] == 0, ear


def test_check_fold_measures_bent_polygons(tmp_path, tube):
    """A quad bent out of its plane in a folded frame fails the planarity check."""
    path = write_structure_fold(
        tmp_path / "quads.fold", tube, fold_angles=[90.0], output=FoldOutput(faces="quads")
    )
    doc = json.loads(path.read_text())
    frame = doc["file_frames"][0]
    face = doc["faces_vertices"][len(doc["faces_vertices"]) // 2]
    x = np.array(frame["vertices_coords"])
    p = x[face]
    normal = np.cross(p[1] - p[0], p[3] - p[0])
    x[face[2]] += 0.05 * np.linalg.norm(p[2] - p[0]) * normal / np.linalg.norm(normal)
    frame["vertices_coords"] = x.tolist()
    path.write_text(json.dumps(doc))
    report = check_fold(path)
    assert not report.ok and report.max_face_planarity_error > 2.0


# --------------------------------------------------------------------------------------
# invariants curvefold guarantees: InternalError, each shown failing on damaged data


def test_flat_plane_refuses_a_folded_state_and_flags_a_bent_flat_one(tube):
    with pytest.raises(
        InputError, match="must be the flat state structure.state\\(0\\), got one at fold angle 90°"
    ):
        flat_plane(tube.state(90.0))
    flat = tube.state(0.0)
    bent = np.array(flat.vertices)
    bent[0, 5, :] += 1e-3 * flat.lattice.crease.curve.frames[5, :, 2]
    with pytest.raises(InternalError, match="the flat state is not planar"):
        flat_plane(State(tube, flat.lattice, bent))


def damaged(structure: Structure, **sheet_changes) -> Structure:
    """A copy of ``structure`` whose triangle topology's first sheet is changed."""
    copy = Structure(structure.lattice, structure.cells)
    topo = structure.topology()
    first = replace(topo.sheets[0], **sheet_changes)
    copy.__dict__["_triangles"] = replace(topo, sheets=(first,) + topo.sheets[1:])
    return copy


def test_sheets_flag_clockwise_faces(tube):
    faces = np.array(tube.topology().sheets[0].faces_vertices)
    faces[3] = faces[3, ::-1]
    with pytest.raises(
        InternalError,
        match="tube 1 · sheet A: 1 of .* faces of the flat state are not counter-clockwise",
    ):
        sheets(damaged(tube, faces_vertices=faces))


def test_fold_file_flags_seams_that_do_not_pair(tube):
    sheet = tube.topology().sheets[0]
    edges = np.array(sheet.edges)
    edges[np.flatnonzero(sheet.edges_seam >= 0)[0]] += 1
    with pytest.raises(InternalError, match="seam edges do not pair up"):
        to_fold(damaged(tube, edges=edges))


def test_sheet_topology_flags_an_edge_without_faces():
    faces = np.array([[0, 1, 2]])
    edges = np.array([[0, 1], [1, 2], [2, 0], [2, 3]])  # the last edge borders no face
    with pytest.raises(InternalError, match="an edge borders none of the sheet's faces"):
        _sheet("s", np.arange(4), np.array([0]), np.arange(4), faces, edges, np.full(4, -1))


def test_unique_pairs_is_numpys_unique_of_rows():
    """One key per pair, and NumPy's own way where the keys would pass int64."""
    from curvefold.geometry._topology import unique_pairs

    rng = np.random.default_rng(7)
    for scale in (1, 10**9, 10**17):
        pairs = rng.integers(-50, 50, size=(80, 2)) * scale
        found, inverse = unique_pairs(pairs)
        expected, expected_inverse = np.unique(pairs, axis=0, return_inverse=True)
        assert np.array_equal(found, expected) and np.array_equal(
            inverse, expected_inverse.reshape(-1)
        )


def test_kept_tubes_are_each_tube_made_alone_and_renumbered():
    """Tubes keeping as many samples share one made topology; each keeps its own curves and
    samples."""
    cells = np.array([[0, 1, 3, 2], [4, 5, 7, 6], [1, 8, 9, 3]])
    keep = [np.arange(5), np.array([0, 2, 4]), np.arange(5)]  # the first and last alike in size
    kept = Topology.tubes(cells, 5, keep=keep)
    v = f = 0
    for k, picks in enumerate(keep):
        one = Topology.tubes(cells[k : k + 1], len(picks))
        rows = slice(v, v + len(one.vertex_curve))
        assert np.array_equal(kept.vertex_curve[rows], one.vertex_curve)
        assert np.array_equal(kept.vertex_sample[rows], picks[one.vertex_sample])
        assert np.array_equal(
            kept.faces_vertices[f : f + len(one.faces_vertices)], one.faces_vertices + v
        )
        v, f = v + len(one.vertex_curve), f + len(one.faces_vertices)
    assert v == len(kept.vertex_curve) and set(kept.vertex_curve[-20:].tolist()) == {1, 8, 9, 3}
