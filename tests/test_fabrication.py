"""From structures to fabrication files: sheets, unrolling cross-check, FOLD, patterns, 3D.

Every claim is measured on real curvefold structures (a helix tube, a two-tube diagonal
stack and a 2 × 2 cellular block) and every file is opened by a reader curvefold did not
write: the node ``fold`` library and Rabbit Ear for FOLD, ``rsvg-convert``, ezdxf's
auditor and ``pdftoppm`` for the patterns, the Khronos validator for GLB and rhino3dm.

Discretisation tolerances. A polyline crease with chords h on a curve of curvature κ
turns by θ ≈ κh per sample; a chord is shorter than its arc by the factor θ²/24, and θ
is the same on every lattice curve at equal t (they share curve 1's frame, so κ·ds is
common). Folding changes κ = κ_2D / cos α, so edge lengths of a folded state differ from
the flat crease pattern's by at most θ²/24 relative (θ measured on the folded mesh), and
a strip developed triangle by triangle drifts by at most L·θ²/24 over its length L.
Both must fall four-fold when the samples double.
"""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from _meshes import assert_written
from _node import run_node
from curvefold import Crease, CurvefoldError, InputError, Lattice, SpaceCurve, Structure
from curvefold.geometry import fold_angles
from curvefold.geometry._sheets import (
    Bond,
    PatternSheet,
    bonds,
    flat_plane,
    folding_motion,
    sheet_vertices,
    sheets,
    unroll_strip,
)
from curvefold.io import (
    MODEL_FORMATS,
    FoldOutput,
    ModelOutput,
    PatternOutput,
    layout_pattern,
    read_fold,
    to_fold,
    write_3d,
    write_pattern,
    write_sheet_fold,
    write_structure_fold,
)
from curvefold.io._fold import ANGLE_DECIMALS


def lattice(samples=101, widths=(0.2, 0.15), fold_angle=90.0):
    """A helix crease (κ = 1, τ = 0.3, length 3) and its lattice."""
    curve = SpaceCurve.from_curvature(1.0, 0.3, 3.0, samples=samples)
    return Lattice.from_crease(Crease.from_curve(curve, fold_angle=fold_angle), *widths)


def helix_tube(samples=101):
    return Structure.tube(lattice(samples))


@pytest.fixture(scope="module")
def tube():
    return helix_tube()


@pytest.fixture(scope="module")
def stack():
    return Structure.diagonal(lattice(widths=(0.1, 0.1)), 2)


@pytest.fixture(scope="module")
def block():
    return Structure.from_cells(lattice(widths=(0.08, 0.08)), [(0, 0), (0, 1), (1, 0), (1, 1)])


@pytest.fixture(scope="module", params=["tube", "stack", "block"])
def structure(request):
    return request.getfixturevalue(request.param)


def needs(tool: str):
    return pytest.mark.skipif(shutil.which(tool) is None, reason=f"{tool} not installed")


def turning(points: np.ndarray) -> float:
    """Largest angle between consecutive chords of polylines (..., n, 3): θ ≈ κh."""
    d = np.diff(points, axis=-2)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    return float(
        np.arccos(np.clip(np.einsum("...i,...i->...", d[..., :-1, :], d[..., 1:, :]), -1, 1)).max()
    )


def signed_areas(xy: np.ndarray, faces: np.ndarray) -> np.ndarray:
    t = xy[faces]
    u, v = t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]
    return u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]


def rigid_residual(p: np.ndarray, q: np.ndarray) -> float:
    """Max distance between q and the best rotation + translation of p, both (m, 2) (no mirror)."""
    pc, qc = p - p.mean(axis=0), q - q.mean(axis=0)
    u, _, vt = np.linalg.svd(pc.T @ qc)
    d = np.sign(np.linalg.det(vt.T @ u.T))
    r = vt.T @ np.diag([1.0, d]) @ u.T
    return float(np.linalg.norm(pc @ r.T - qc, axis=1).max())


# --------------------------------------------------------------------------------------
# sheets


def test_sheet_counts_labels_and_vertex_maps(structure):
    parts = sheets(structure)
    K = len(structure.cells)
    assert len(parts) == 2 * K
    assert [p.label for p in parts] == [
        f"tube {k} · sheet {s}" for k in range(1, K + 1) for s in "AB"
    ]
    assert all(isinstance(p, PatternSheet) for p in parts)
    assert sheets(structure, name="vault")[-1].label == f"vault · tube {K} · sheet B"
    n = len(structure.lattice.s)
    maps = sheet_vertices(structure)
    flat = structure.state(0).mesh()
    for k in range(K):
        for s, corners in enumerate(((3, 0, 1), (1, 2, 3))):
            idx = maps[2 * k + s]
            assert_array_equal(
                idx, np.concatenate([(4 * k + c) * n + np.arange(n) for c in corners])
            )
            p = parts[2 * k + s]
            assert len(p.mesh.vertices_coords) == 3 * n
            assert_array_equal(p.mesh.vertices_coords[:, 2], 0.0)
            # a sheet is its flat state moved rigidly into the plane: every distance kept
            e = p.mesh.edges_vertices
            l3 = np.linalg.norm(np.diff(flat.vertices_coords[idx][e], axis=1)[:, 0], axis=-1)
            assert_allclose(p.mesh.edge_lengths(), l3, rtol=1e-12)
            assert set(p.mesh.faces_group) == {4 * k + c for c in ((3, 0), (1, 2))[s]}


def test_flat_state_is_one_plane_through_curve_1(tube):
    flat = tube.state(0)
    plane = flat_plane(flat)
    size = np.ptp(flat.vertices.reshape(-1, 3), axis=0).max()
    assert plane.residual < 1e-12 * size
    assert_allclose(plane.axes @ plane.axes.T, np.eye(3), atol=1e-14)
    # binormal at the start
    assert_allclose(plane.axes[2], tube.lattice.crease.curve.frames[0][:, 2], atol=1e-12)
    assert_allclose(plane.coords(tube.lattice.crease.curve.points[0]), [0, 0], atol=0)
    with pytest.raises(CurvefoldError, match="flat state is not planar"):
        flat_plane(tube.state(90))


def test_seams_pair_up_across_the_two_sheets_of_a_tube(structure):
    parts = sheets(structure)
    maps = sheet_vertices(structure)
    for k in range(len(structure.cells)):
        a, b = parts[2 * k], parts[2 * k + 1]
        assert (
            set(a.edges_seam[a.edges_seam >= 0])
            == set(b.edges_seam[b.edges_seam >= 0])
            == {2 * k, 2 * k + 1}
        )
        for sid in (2 * k, 2 * k + 1):
            got = []
            for p, idx in ((a, maps[2 * k]), (b, maps[2 * k + 1])):
                ids = np.flatnonzero(p.edges_seam == sid)
                key = np.sort(idx[p.mesh.edges_vertices[ids]], axis=1)
                order = np.lexsort(key.T[::-1])
                got.append((key[order], p.mesh.edge_lengths()[ids][order]))
            assert_array_equal(got[0][0], got[1][0])  # the same curve edges on both sheets
            # equal lengths: one flat curve
            assert_allclose(got[0][1], got[1][1], rtol=1e-12, atol=0)
            n = len(structure.lattice.s)
            assert len(got[0][1]) == n - 1


def test_edge_kinds_and_mountain_valley(tube):
    n = len(tube.lattice.s)
    maps = sheet_vertices(tube)
    design = tube.state()
    alpha2 = tube.lattice.crease.fold_angle
    theta = turning(design.vertices)
    for s, (p, idx) in enumerate(zip(sheets(tube), maps)):
        m = p.mesh
        corner = (idx[m.edges_vertices] // n) % 4
        same = corner[:, 0] == corner[:, 1]
        kinds = {
            k: int(np.count_nonzero(m.edges_kind == k))
            for k in ("fold", "seam", "boundary", "ruling", "diagonal")
        }
        assert kinds == {
            "fold": n - 1,
            "seam": 2 * (n - 1),
            "boundary": 4,
            "ruling": 2 * (n - 2),
            "diagonal": 2 * (n - 1),
        }
        fold_corner = (0, 2)[s]
        assert (corner[m.edges_kind == "fold"] == fold_corner).all()  # crease 1 on A, crease 3 on B
        assert set(corner[m.edges_kind == "seam"].ravel()) == {1, 3}  # seams 2 and 4
        assert same[np.isin(m.edges_kind, ("fold", "seam"))].all()
        ends = idx[m.edges_vertices[m.edges_kind == "boundary"]] % n
        assert ((ends == 0) | (ends == n - 1)).all()  # end rulings
        fold = m.edges_kind == "fold"
        assert set(m.edges_assignment[fold]) == {"M"}  # mountains seen from outside the tube
        assert_allclose(m.edges_foldAngle[fold], -alpha2, atol=10 * theta**2)
        assert set(m.edges_assignment[np.isin(m.edges_kind, ("seam", "boundary"))]) == {"B"}
        assert set(m.edges_assignment[np.isin(m.edges_kind, ("ruling", "diagonal"))]) == {"F"}
        assert_array_equal(m.edges_foldAngle[np.isin(m.edges_kind, ("seam", "boundary"))], 0.0)
        # the design state's, small
        bends = m.edges_foldAngle[np.isin(m.edges_kind, ("ruling", "diagonal"))]
        assert 0 < np.abs(bends).max() < 10 * np.degrees(theta)
    # another target angle changes the angles, not the geometry
    at60 = sheets(tube, fold_angle=60)
    fold = at60[0].mesh.edges_kind == "fold"
    assert_allclose(at60[0].mesh.edges_foldAngle[fold], -60.0, atol=1e-2)
    assert_array_equal(at60[0].mesh.vertices_coords, sheets(tube)[0].mesh.vertices_coords)


def test_sheets_are_seen_from_outside_the_tube(structure):
    """Counter-clockwise in 2D, and the same vertex cycles as the tube mesh (outward normals)."""
    tube_faces = {
        tuple(np.roll(f, -int(np.argmin(f))))
        for f in structure.state().mesh().faces_vertices.tolist()
    }
    for p, idx in zip(sheets(structure), sheet_vertices(structure)):
        assert (signed_areas(p.mesh.vertices_coords[:, :2], p.mesh.faces_vertices) > 0).all()
        cycles = idx[p.mesh.faces_vertices]
        assert all(tuple(np.roll(f, -int(np.argmin(f)))) in tube_faces for f in cycles.tolist())
        # outline edges run as their face traverses them (interior on the left)
        outline = np.isin(p.mesh.edges_kind, ("seam", "boundary"))
        sides = {(a, b) for f in p.mesh.faces_vertices.tolist() for a, b in zip(f, f[1:] + f[:1])}
        assert all(tuple(e) in sides for e in p.mesh.edges_vertices[outline].tolist())


def _isometry_error(structure, fold_angle) -> tuple[float, float]:
    """Largest relative edge-length change sheet → folded state, and θ²/24 of that state."""
    state = structure.state(fold_angle)
    x = state.mesh().vertices_coords
    worst = 0.0
    for p, idx in zip(sheets(structure), sheet_vertices(structure)):
        e = p.mesh.edges_vertices
        l2 = p.mesh.edge_lengths()
        l3 = np.linalg.norm(x[idx[e[:, 1]]] - x[idx[e[:, 0]]], axis=-1)
        worst = max(worst, float((np.abs(l3 - l2) / l2).max()))
    return worst, turning(state.vertices) ** 2 / 24


def test_sheets_are_isometric_to_every_folded_state():
    errors, bounds = [], []
    for samples in (101, 201):
        st = helix_tube(samples)
        got = [_isometry_error(st, f) for f in (45.0, 90.0, 150.0)]
        errors.append(max(e for e, _ in got))
        bounds.append(max(b for _, b in got))
        assert all(e < b for e, b in got), got
    assert 3.6 < errors[0] / errors[1] < 4.4, errors  # second order in h


def test_stack_and_block_sheets_are_isometric(stack, block):
    for st in (stack, block):
        err, bound = _isometry_error(st, 120.0)
        assert err < bound, (err, bound)


# --------------------------------------------------------------------------------------
# independent unrolling


def _unrolling_error(samples: int, fold_angle: float = 90.0) -> tuple[float, float, float]:
    """Worst rigid-alignment residual of unrolled folded strips against the sheets, its bound
    L·θ²/24, and the residual of unrolling the flat state itself."""
    st = helix_tube(samples)
    parts, maps = sheets(st), sheet_vertices(st)
    n = len(st.lattice.s)
    folded = st.state(fold_angle).vertices[st.cell_curves[0]]  # corners 1-4, (4, n, 3)
    flat = st.state(0).vertices[st.cell_curves[0]]
    worst = flat_worst = 0.0
    for c in range(4):
        s = 0 if c in (3, 0) else 1  # strip c → c+1 lies on sheet A (4→1, 1→2) or B (2→3, 3→4)
        lookup = {v: i for i, v in enumerate(maps[s].tolist())}
        rows = [
            [lookup[c * n + j] for j in range(n)],
            [lookup[((c + 1) % 4) * n + j] for j in range(n)],
        ]
        target = parts[s].mesh.vertices_coords[np.array(rows).ravel(), :2]
        got = unroll_strip(folded[c], folded[(c + 1) % 4]).reshape(-1, 2)
        worst = max(worst, rigid_residual(got, target))
        flat_worst = max(
            flat_worst,
            rigid_residual(unroll_strip(flat[c], flat[(c + 1) % 4]).reshape(-1, 2), target),
        )
    length = max(float(np.linalg.norm(np.diff(folded, axis=1), axis=-1).sum(axis=1).max()), 1.0)
    return worst, length * turning(folded) ** 2 / 24, flat_worst


def test_unrolled_folded_strips_match_the_flat_state_crease_pattern():
    """Issue requirement: develop every ruled strip of the 90° state on its own and compare."""
    e101, bound101, flat101 = _unrolling_error(101)
    e201, bound201, flat201 = _unrolling_error(201)
    # unrolling the flat state itself reproduces the sheets to rounding
    assert flat101 < 1e-12 and flat201 < 1e-12
    # the folded state's strips develop onto the sheets to the discretisation error …
    assert e101 < bound101 and e201 < bound201, (e101, bound101, e201, bound201)
    # … which is second order: four times smaller with twice the samples
    assert 3.6 < e101 / e201 < 4.4, (e101, e201)


def test_unrolling_can_fail():
    """A mirrored target or the wrong strip is far off: the cross-check has teeth."""
    st = helix_tube(101)
    part = sheets(st)[1]  # sheet B: strips 2→3 and 3→4
    n = len(st.lattice.s)
    folded = st.state(90).vertices[st.cell_curves[0]]
    got = unroll_strip(folded[1], folded[2]).reshape(-1, 2)  # strip 2→3: sheet B rows 0..2n
    target = part.mesh.vertices_coords[: 2 * n, :2]
    assert rigid_residual(got, target) < 1e-4
    assert rigid_residual(got, target * [1, -1]) > 1e-2  # seen from the inside
    wrong = unroll_strip(folded[0], folded[1]).reshape(-1, 2)  # strip 1→2 is on sheet A
    assert rigid_residual(wrong, target) > 1e-2


def test_unroll_strip_rejects_bad_input():
    with pytest.raises(InputError, match=r"shape \(n, 3\)"):
        unroll_strip(np.zeros((3, 3)), np.zeros((4, 3)))
    with pytest.raises(InputError, match=r"shape \(n, 3\)"):
        unroll_strip(np.zeros((1, 3)), np.zeros((1, 3)))
    with pytest.raises(InputError, match="finite"):
        unroll_strip(np.full((3, 3), np.nan), np.zeros((3, 3)))


# --------------------------------------------------------------------------------------
# bonds


def test_bonds(tube, stack, block):
    assert bonds(tube) == ()
    assert bonds(stack) == (Bond((1, 1), ((0, 3), (1, 1))),)
    assert bonds(stack)[0].describe() == "curve (1, 1): tube 1 crease 3 + tube 2 crease 1"
    got = {b.curve: b.creases for b in bonds(block)}
    # the block's centre line joins four tubes
    assert got[(1, 1)] == ((0, 3), (1, 4), (2, 2), (3, 1))
    assert set(got) == {(0, 1), (1, 0), (1, 1), (1, 2), (2, 1)}


# --------------------------------------------------------------------------------------
# FOLD


def test_folding_motion_is_the_states(stack):
    angles = [0.0, 45.0, 120.0]
    motion = folding_motion(stack, angles)
    assert motion.shape == (3, 4 * 2 * len(stack.lattice.s), 3)
    for a, x in zip(angles, motion):
        assert_allclose(x, stack.state(a).mesh().vertices_coords, rtol=0, atol=1e-12)
    with pytest.raises(InputError, match="fold_angles"):
        folding_motion(stack, [180.0])


def test_fold_model_shares_one_topology_and_closes_its_seams(stack):
    model = to_fold(
        stack, FoldOutput(unit="m", metadata={"name": "stack"}), fold_angles=[0.0, 60.0, 90.0]
    )
    cp = model.crease_pattern
    parts, maps = sheets(stack), sheet_vertices(stack)
    source = np.concatenate(maps)
    # key frame: the sheets side by side, z = 0, counter-clockwise, disjoint bounding boxes
    assert_array_equal(cp.vertices_coords[:, 2], 0.0)
    assert (signed_areas(cp.vertices_coords[:, :2], cp.faces_vertices) > 0).all()
    start = np.cumsum([0] + [len(p.mesh.vertices_coords) for p in parts])
    boxes = [
        (cp.vertices_coords[a:b, 0].min(), cp.vertices_coords[a:b, 0].max())
        for a, b in zip(start[:-1], start[1:])
    ]
    assert all(hi < lo for (_, hi), (lo, _) in zip(boxes[:-1], boxes[1:]))
    for p, a, b in zip(parts, start[:-1], start[1:]):  # each sheet only translated
        assert_allclose(
            cp.vertices_coords[a:b, :2] - p.mesh.vertices_coords[:, :2],
            np.broadcast_to(cp.vertices_coords[a, :2] - p.mesh.vertices_coords[0, :2], (b - a, 2)),
            atol=1e-12,
        )
    # folded frames: the tube mesh's vertices on the sheets' topology
    assert [t for t, _ in model.folded] == ["fold angle 0°", "fold angle 60°", "fold angle 90°"]
    for (_, m), a in zip(model.folded, (0.0, 60.0, 90.0)):
        for name in ("edges_vertices", "faces_vertices", "edges_kind", "faces_group"):
            assert_array_equal(getattr(m, name), getattr(cp, name))
        assert_allclose(
            m.vertices_coords, stack.state(a).mesh().vertices_coords[source], atol=1e-12, rtol=0
        )
        ev, x = m.edges_vertices, m.vertices_coords
        # the glue check: seam partners coincide (their edges run opposite ways)
        assert_allclose(
            x[ev[model.seam_partners[:, 0]]],
            x[ev[model.seam_partners[:, 1]]][:, ::-1],
            atol=1e-12,
            rtol=0,
        )
    # every seam edge is paired once, with an edge of the other sheet of its tube
    seam = np.flatnonzero(cp.edges_kind == "seam")
    assert_array_equal(np.sort(model.seam_partners.ravel()), seam)
    sheet_of_edge = np.repeat(np.arange(len(parts)), [len(p.mesh.edges_vertices) for p in parts])
    pair_sheets = sheet_of_edge[model.seam_partners]
    assert (pair_sheets[:, 0] // 2 == pair_sheets[:, 1] // 2).all() and (
        pair_sheets[:, 0] != pair_sheets[:, 1]
    ).all()
    # bonds: crease 3 of tube 1 (sheet B) and crease 1 of tube 2 (sheet A) coincide when folded
    n = len(stack.lattice.s)
    on_b1 = start[1] + np.flatnonzero(maps[1] // n == 2)  # tube 0, corner index 2
    on_a2 = start[2] + np.flatnonzero(maps[2] // n == 4)  # tube 1, corner index 0
    for _, m in model.folded:
        assert_allclose(m.vertices_coords[on_b1], m.vertices_coords[on_a2], atol=1e-12, rtol=0)
    assert model.metadata["bonds"] == "curve (1, 1): tube 1 crease 3 + tube 2 crease 1"
    assert model.metadata["name"] == "stack" and model.metadata["tubes"] == 2
    assert model.metadata["design_fold_angle_deg"] == pytest.approx(90.0)


def test_fold_file_round_trip(tmp_path, tube):
    path = write_structure_fold(
        tmp_path / "tube.fold",
        tube,
        fold_angles=[30.0, 90.0],
        title="helix tube",
        output=FoldOutput(unit="mm"),
    )
    model = to_fold(tube, fold_angles=[30.0, 90.0], output=FoldOutput(unit="mm"))
    back = read_fold(path)
    doc = json.loads(path.read_text())
    assert doc["file_title"] == "helix tube" and doc["frame_unit"] == "mm"
    assert all(len(c) == 2 for c in doc["vertices_coords"])
    cp = model.crease_pattern
    # to 1e-12 of the size, as written
    assert_written(back.crease_pattern.vertices_coords, cp.vertices_coords)
    for name in (
        "edges_vertices",
        "faces_vertices",
        "edges_kind",
        "faces_group",
        "edges_assignment",
    ):
        assert_array_equal(getattr(back.crease_pattern, name), getattr(cp, name), err_msg=name)
    assert_allclose(
        back.crease_pattern.edges_foldAngle, cp.edges_foldAngle, rtol=0, atol=10.0**-ANGLE_DECIMALS
    )
    assert_array_equal(back.seam_partners, model.seam_partners)
    assert back.metadata == model.metadata and back.unit == "mm"
    for (t1, got), (t2, want) in zip(back.folded, model.folded):
        assert t1 == t2
        assert_written(got.vertices_coords, want.vertices_coords)
        fold = got.edges_kind == "fold"
        measured = fold_angles(got.vertices_coords, got.faces_vertices, got.edges_vertices)
        assert_allclose(got.edges_foldAngle[fold], measured[fold], atol=1e-9)
        assert (got.edges_foldAngle[fold] < 0).all()


def test_fold_rejects_bad_input(tube):
    with pytest.raises(InputError, match="structure must be a Structure"):
        to_fold("tube")
    with pytest.raises(InputError, match=r"fold_angles must be in \[0°, 180°\)"):
        to_fold(tube, fold_angles=[-5.0])
    with pytest.raises(InputError, match=r"fold_angle must be in \(0°, 180°\)"):
        sheets(tube, fold_angle=0.0)
    with pytest.raises(InputError, match="unit must be"):
        to_fold(tube, output=FoldOutput(unit=""))
    with pytest.raises(InputError, match="metadata"):
        to_fold(tube, output=FoldOutput(metadata={"bad": [1, 2]}))


@pytest.mark.node
def test_node_fold_and_rabbit_ear_check_the_structure_file(tmp_path):
    """The file is a valid FOLD graph, and its crease pattern folded by each frame's own angles
    lands on the frame.

    Every frame records the dihedral angle it has at every edge (a curved sheet bends across
    its rulings and diagonals too). Rabbit Ear folds the crease pattern by those angles and
    must land on the frame to the discretisation error (the crease pattern and the frame
    differ by the polyline chords, L·θ²/24), falling four-fold when the samples double. With
    the angles of the F edges zeroed, as the files once had them, it lands far off.
    """
    residual = []
    for samples in (101, 201):
        st = helix_tube(samples)
        path = write_structure_fold(
            tmp_path / f"t{samples}.fold", st, fold_angles=[0.0, 60.0, 120.0]
        )
        report = run_node("check_fold.mjs", str(path))
        fold, ear = report["fold"], report["rabbit_ear"]
        faces = 8 * (samples - 1)
        assert fold["same_vertex_sets"] and fold["same_orientation"], fold
        assert fold["faces_rebuilt"] == faces
        assert ear["summary"] == "valid" and ear["references_ok"], ear
        assert ear["faces_ccw"] == faces and ear["faces_cw"] == 0
        assert ear["sheets"] == 2
        assert ear["frames"][0]["max_distance"] < 1e-12  # the flat frame
        model = to_fold(st, fold_angles=[0.0, 60.0, 120.0])
        # L·θ²/24 over the frame's size L, θ measured on its first curve
        bound = max(
            np.ptp(m.vertices_coords, axis=0).max() * turning(m.vertices_coords[:samples]) ** 2 / 24
            for _, m in model.folded
        )
        residual.append(max(f["max_distance"] for f in ear["frames"]))
        assert residual[-1] < bound, (residual, bound)
    assert 3.6 < residual[0] / residual[1] < 4.4, residual
    doc = json.loads(path.read_text())
    flat = np.array(doc["edges_assignment"]) == "F"
    for frame in doc["file_frames"]:
        frame["edges_foldAngle"] = np.where(flat, 0.0, frame["edges_foldAngle"]).tolist()
    path.write_text(json.dumps(doc))
    assert (
        run_node("check_fold.mjs", str(path))["rabbit_ear"]["frames"][2]["max_distance"]
        > 100 * residual[-1]
    )


@pytest.mark.node
def test_node_single_sheet_file_for_origami_simulator(tmp_path, tube):
    sheet = sheets(tube)[0]
    path = write_sheet_fold(tmp_path / "sheet.fold", sheet.mesh, "unit", title=sheet.label)
    doc = json.loads(path.read_text())
    assert doc["frame_classes"] == ["creasePattern"] and all(
        len(c) == 2 for c in doc["vertices_coords"]
    )
    fold = np.array(doc["edges_curvefold:kind"]) == "fold"
    assert_allclose(
        np.array(doc["edges_foldAngle"])[fold],
        sheet.mesh.edges_foldAngle[fold],
        rtol=0,
        atol=10.0**-ANGLE_DECIMALS,
    )  # target angles, as written
    assert set(np.array(doc["edges_assignment"])[fold]) == {"M"}
    report = run_node("check_fold.mjs", str(path))
    assert report["fold"]["same_orientation"]
    assert report["rabbit_ear"]["summary"] == "valid" and report["rabbit_ear"]["faces_cw"] == 0


# --------------------------------------------------------------------------------------
# crease patterns on paper


def _png(path: Path) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(path).convert("RGB"), float) / 255.0


def test_default_scale_is_plain_and_fits(stack, block):
    for st in (stack, block):
        layout = layout_pattern(st)
        mant = layout.scale / 10 ** np.floor(np.log10(layout.scale))
        assert any(abs(mant - m) < 1e-9 for m in (1, 1.25, 1.5, 2, 2.5, 3, 4, 5, 6, 8)), (
            layout.scale
        )
        assert not [n for n in layout.notes if "lengths differ" in n], layout.notes  # seams match
        W, H = layout.page_size
        for s in layout.sheets():
            lo, hi = s.bounds()
            assert (
                (lo >= layout.margin - 1e-9).all()
                and hi[0] <= W - layout.margin + 1e-9
                and hi[1] <= H - layout.margin + 1e-9
            )
    # the largest sheet fills a good part of the page
    biggest = max(np.ptp(s.bounds(), axis=0).max() for s in layout_pattern(stack).sheets())
    assert biggest > 0.5 * (297 - 20)
    fixed = layout_pattern(stack, PatternOutput(scale=30.0))
    assert fixed.scale == 30.0


@pytest.fixture(scope="module")
def stack_pattern(tmp_path_factory, stack):
    folder = tmp_path_factory.mktemp("pattern")
    return folder, write_pattern(folder / "stack", stack, PatternOutput(name="vault", rulings=True))


def test_write_pattern_files(stack_pattern):
    folder, paths = stack_pattern
    svgs = [p for p in paths if p.suffix == ".svg"]
    assert [p.name for p in svgs] == [f"stack-p{i + 1}.svg" for i in range(len(svgs))]
    assert [p.name for p in paths[len(svgs) :]] == ["stack.dxf", "stack.pdf"]
    assert all(p.exists() for p in paths)
    assert all("layer-rulings" in p.read_text() for p in svgs)


def test_pattern_dxf_passes_the_ezdxf_audit(stack_pattern):
    ezdxf = pytest.importorskip("ezdxf")
    folder, _ = stack_pattern
    doc = ezdxf.readfile(folder / "stack.dxf")
    auditor = doc.audit()
    assert not auditor.has_errors, [str(e) for e in auditor.errors]
    assert doc.header["$INSUNITS"] == 4
    msp = doc.modelspace()
    assert len(msp.query('LWPOLYLINE[layer=="cut"]')) == 4
    assert (
        len(msp.query('LWPOLYLINE[layer=="score - mountain"]')) == 4
        and len(msp.query('LWPOLYLINE[layer=="score - valley"]')) == 0
    )
    assert len(msp.query('LWPOLYLINE[layer=="engrave - rulings"]')) > 0
    texts = sorted(t.dxf.text for t in msp.query('TEXT[layer=="engrave - labels"]'))
    assert [t for t in texts if t.startswith("vault")] == [
        f"vault · tube {k} · sheet {s}" for k in (1, 2) for s in "AB"
    ]
    # both partners named
    assert sorted(t for t in texts if t.startswith("S")) == sorted(["S0", "S1", "S2", "S3"] * 2)


@needs("rsvg-convert")
def test_pattern_svg_renders_with_folds_and_tabs(stack_pattern):
    folder, paths = stack_pattern
    for svg in (p for p in paths if p.suffix == ".svg"):
        png = svg.with_suffix(".png")
        subprocess.run(
            ["rsvg-convert", "-d", "100", "-p", "100", "-b", "white", str(svg), "-o", str(png)],
            check=True,
        )
        img = _png(png)
        assert abs(img.shape[1] - 210 / 25.4 * 100) <= 1  # A4 at true size
        red = (img[..., 0] > 0.7) & (img[..., 1] < 0.35) & (img[..., 2] < 0.35)
        green = (img[..., 1] > img[..., 0] + 0.08) & (img[..., 1] > img[..., 2] + 0.08)
        assert red.sum() > 50 and green.sum() > 200  # mountain folds and glue tabs drawn


@needs("pdftoppm")
def test_pattern_pdf_has_one_page_per_layout_page(stack_pattern):
    folder, paths = stack_pattern
    subprocess.run(
        ["pdftoppm", "-r", "30", "-png", str(folder / "stack.pdf"), str(folder / "page")],
        check=True,
    )
    assert len(list(folder.glob("page-*.png"))) == len([p for p in paths if p.suffix == ".svg"])


def test_write_pattern_options(tmp_path, tube):
    (svg,) = write_pattern(
        tmp_path / "tube", tube, PatternOutput(glue_tabs=False, page="A3"), formats=("svg",)
    )
    assert svg.name == "tube.svg" and sorted(p.name for p in tmp_path.iterdir()) == ["tube.svg"]
    text = svg.read_text()
    assert 'width="297mm"' in text and "layer-rulings" not in text
    with pytest.raises(InputError, match="formats must be"):
        write_pattern(tmp_path / "x", tube, formats=("png",))


# --------------------------------------------------------------------------------------
# 3D


def test_write_3d_every_format(tmp_path, stack):
    pygltflib = pytest.importorskip("pygltflib")
    rhino3dm = pytest.importorskip("rhino3dm")
    output = ModelOutput(unit="mm", metadata={"name": "stack"}, print_unit="cm")
    paths = write_3d(tmp_path / "stack", stack, [0.0, 30.0, 60.0, 90.0], output)
    assert [p.suffix for p in paths] == [f".{f}" for f in MODEL_FORMATS]
    mesh = stack.state().mesh()
    gltf = pygltflib.GLTF2.load(str(tmp_path / "stack.glb"))
    labels = [s.label for s in stack.topology().sheets]
    assert (
        [n.name for n in gltf.nodes]
        == [m.name for m in gltf.meshes]
        == labels
        == [f"tube {k} · sheet {x}" for k in (1, 2) for x in "AB"]
    )
    assert all(
        len(m.primitives[0].targets) == 3 and m.primitives[0].attributes.NORMAL is not None
        for m in gltf.meshes
    )
    assert (tmp_path / "stack.stl").read_bytes()[:80].rstrip().endswith(b", unit cm, z up")
    assert gltf.asset.extras["curvefold"]["angles_deg"] == [0.0, 30.0, 60.0, 90.0]
    assert gltf.asset.extras["curvefold"]["metadata"]["name"] == "stack"
    model = rhino3dm.File3dm.Read(str(tmp_path / "stack.3dm"))
    assert model.Settings.ModelUnitSystem == rhino3dm.UnitSystem.Millimeters
    assert model.Strings["curvefold:tubes"] == "2"
    sheets = [o.Geometry for o in model.Objects if isinstance(o.Geometry, rhino3dm.Mesh)]
    assert len(sheets) == 4  # one mesh per sheet
    vertices = np.concatenate([[[p.X, p.Y, p.Z] for p in sheet.Vertices] for sheet in sheets])
    # the design state (read back as 32-bit floats, so ~1e-7 of the size)
    assert_allclose(
        vertices,
        mesh.vertices_coords[np.concatenate([s.vertices for s in stack.topology().sheets])],
        atol=1e-6,
        rtol=0,
    )
    obj = (tmp_path / "stack.obj").read_text()
    # one quad per two triangles
    assert obj.count("\nf ") == len(mesh.faces_vertices) // 2 and "# unit: mm" in obj
    assert (tmp_path / "stack.stl").stat().st_size == 84 + 50 * len(mesh.faces_vertices)


def test_glb_first_keyframe_is_the_design_state_of_every_sheet(tmp_path, stack):
    """What an importer that applies the first keyframe shows (Blender): each sheet's node, at the
    weights of the animation's first keyframe, is the design state; a later keyframe is the flat
    state."""
    pygltflib = pytest.importorskip("pygltflib")
    from _gltf import accessor, target_position

    angles = [0.0, 30.0, 60.0, 90.0]
    (path,) = write_3d(tmp_path / "stack", stack, angles, formats=("glb",))
    gltf = pygltflib.GLTF2.load(str(path))
    blob = gltf.binary_blob()
    (anim,) = gltf.animations
    times = accessor(gltf, blob, anim.samplers[0].input)
    weights = accessor(gltf, blob, anim.samplers[0].output).reshape(len(times), -1)
    to_gltf = lambda x: np.stack([x[..., 0], x[..., 2], -x[..., 1]], axis=-1)  # noqa: E731
    faces = stack.state().mesh().faces_vertices
    # the first keyframe, and the flat state three steps on
    for key, angle in ((0, 90.0), (3, 0.0)):
        want = to_gltf(stack.state(angle).mesh().vertices_coords)
        for sheet, node in zip(stack.topology().sheets, gltf.nodes):
            prim = gltf.meshes[node.mesh].primitives[0]
            pose = accessor(gltf, blob, prim.attributes.POSITION) + sum(
                w * accessor(gltf, blob, target_position(t))
                for w, t in zip(weights[key], prim.targets)
            )
            triangles = accessor(gltf, blob, prim.indices).reshape(-1, 3)
            assert_allclose(pose[triangles], want[faces[sheet.faces]], atol=1e-6, rtol=0)
    assert times[0] == 0.0 and not weights[0].any()


@pytest.mark.node
def test_glb_of_the_folding_motion_passes_the_khronos_validator(tmp_path, tube):
    (path,) = write_3d(tmp_path / "tube", tube, output=ModelOutput(unit="m"), formats=("glb",))
    report = run_node("validate_gltf.mjs", str(path))
    assert report["errors"] == 0 and report["warnings"] == 0, report["messages"]
    assert report["info"]["hasMorphTargets"] and report["info"]["animationCount"] == 1
    assert report["info"]["totalTriangleCount"] == 8 * (len(tube.lattice.s) - 1)


def test_write_3d_rejects_bad_input(tmp_path, tube):
    with pytest.raises(InputError, match="formats must be"):
        write_3d(tmp_path / "x", tube, formats=("fbx",))
    with pytest.raises(InputError, match="fold_angles"):
        write_3d(tmp_path / "x", tube, [0.0, 200.0])
    assert list(tmp_path.iterdir()) == []


def test_the_writers_take_their_values_and_refuse_anything_else(tmp_path, tube):
    """A writer's options are one value; a value of another writer, or a bare mapping, is refused by
    name before anything is written (the keywords it replaced would otherwise be lost silently)."""
    from curvefold.io import GlbOptions, RhinoOptions, write_3dm, write_glb
    from curvefold.io._layout import LayoutRules, layout_sheets
    from curvefold.io._single_fold import layout_single_fold

    mesh = tube.state().mesh()
    quads = tube.state().mesh(faces="quads")
    wrong = {"page": "A3"}
    glb, rhino = tmp_path / "x.glb", tmp_path / "x.3dm"
    cases = [
        ("output must be a PatternOutput", lambda: write_pattern(tmp_path / "x", tube, wrong)),
        ("output must be a PatternOutput", lambda: layout_pattern(tube, ModelOutput())),
        ("output must be a PatternOutput", lambda: layout_single_fold(None, wrong)),
        ("output must be a ModelOutput", lambda: write_3d(tmp_path / "x", tube, None, wrong)),
        ("output must be a FoldOutput", lambda: to_fold(tube, ModelOutput())),
        ("output must be a FoldOutput", lambda: write_structure_fold(tmp_path / "x", tube, wrong)),
        ("options must be a GlbOptions", lambda: write_glb(glb, mesh, options=wrong)),
        (
            "options must be a RhinoOptions",
            lambda: write_3dm(rhino, quads, tube.topology("quads"), options=GlbOptions()),
        ),
        ("rules must be a LayoutRules", lambda: layout_sheets(sheets(tube), rules=wrong)),
    ]
    for match, write in cases:
        with pytest.raises(InputError, match=match):
            write()
    assert list(tmp_path.iterdir()) == []
    assert layout_sheets(sheets(tube), rules=LayoutRules(margin=12.0)).margin == 12.0
    assert RhinoOptions().version == 0 and PatternOutput().page == "A4"
