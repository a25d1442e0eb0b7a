"""FOLD files published by other tools (``tests/fold_corpus``, sources in its NOTICE.txt):
``check`` fails none that is consistent and says why of each that is not, and ``mechanism``'s
counts agree with an independent rigid-body count.

The FOLD repository's examples (a box, a three-fold, a square twist, a diagonal fold) and
Rabbit Ear's test files (folded panels, a bird base folded in space and a modified copy, a
kite, a crane, two lines) as published. Their verdicts were read by hand:

* ``fold-box.fold``: every M/V crease folds the other way round from its faces' winding (its
  faces are wound clockwise seen from the valley side), and 39 of its creases are folded flat
  (±180°, where the sign is not measured: those were 36 false alarms "180 > 0°");
* ``rabbit-ear-folded-panels.fold``: every recorded fold angle is the negative of the
  measured one, for the same reason;
* ``rabbit-ear-folded-bird-base-3d.fold``: the recorded angles are targets the coordinates do
  not reach (up to 43° off); its ``-modified`` copy is mirrored without its faces;
* ``rabbit-ear-kite.fold``: two M creases recorded at +90° (a mountain is negative);
* ``rabbit-ear-two-line.fold``: two lines and no faces (FOLD allows it; nothing to check).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from _cli import run
from curvefold.analysis import check_fold
from curvefold.analysis._fold_mechanism import analyse_fold, coordinate_precision
from curvefold.io import read_fold

CORPUS = Path(__file__).parent / "fold_corpus"

#: Consistent files: no check fails.
CONSISTENT = [
    "fold-simple.fold",
    "fold-squaretwist.fold",
    "fold-diagonal-cp.fold",
    "fold-diagonal-folded.fold",
    "rabbit-ear-crane.fold",
]

#: Inconsistent files: the check that fails and the words of its reason.
INCONSISTENT = {
    "fold-box.fold": ("assignments", "faces are wound clockwise seen from the valley side"),
    "rabbit-ear-folded-panels.fold": (
        "fold_angles",
        "faces are wound clockwise seen from the valley side",
    ),
    "rabbit-ear-folded-bird-base-3d.fold": ("fold_angles", "edges 9, 10, 11, 12, 14"),
    "rabbit-ear-bird-base-3d-modified.fold": ("assignments", "edges 8, 9, 10"),
    "rabbit-ear-kite.fold": (
        "assignments",
        "edges 6, 7; M or V edges record a fold angle of the other",
    ),
}

#: Files with a folded frame: their internal DOF (each face a rigid body).
FOLDED = [
    "fold-box.fold",
    "fold-simple.fold",
    "fold-squaretwist.fold",
    "fold-diagonal-folded.fold",
    "rabbit-ear-folded-panels.fold",
    "rabbit-ear-folded-bird-base-3d.fold",
    "rabbit-ear-bird-base-3d-modified.fold",
]


@pytest.mark.parametrize("name", CONSISTENT)
def test_a_consistent_file_fails_no_check(name):
    result = check_fold(CORPUS / name)
    assert result.ok, [(c.name, c.where) for c in result.checks if c.status == "fail"]


@pytest.mark.parametrize("name", INCONSISTENT)
def test_an_inconsistent_file_says_why(name):
    check, words = INCONSISTENT[name]
    failed = {c.name: c for c in check_fold(CORPUS / name).checks if c.status == "fail"}
    assert check in failed and words in failed[check].where, {n: c.where for n, c in failed.items()}


def test_a_file_of_lines_without_faces_is_refused_in_one_line():
    r = run("check", str(CORPUS / "rabbit-ear-two-line.fold"))
    assert r.returncode == 2 and "missing required key 'faces_vertices'" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


def test_a_flat_folded_crease_at_180_degrees_is_no_wrong_assignment(tmp_path):
    """The box's creases folded flat measure −180° whichever their assignment: their sign is
    not measured (36 of the 37 edges named before were such)."""
    doc = json.loads((CORPUS / "fold-box.fold").read_text())
    # the faces wound counterclockwise seen from the valley side, as FOLD winds them
    doc["faces_vertices"] = [face[::-1] for face in doc["faces_vertices"]]
    path = tmp_path / "box.fold"
    path.write_text(json.dumps(doc))
    checks = {c.name: c for c in check_fold(path).checks}
    assert checks["assignments"].status == "pass", checks["assignments"].where
    # a crease folded the wrong way is still caught
    valley = next(e for e, a in enumerate(doc["edges_assignment"]) if a == "V")
    doc["edges_assignment"][valley] = "M"
    path.write_text(json.dumps(doc))
    checks = {c.name: c for c in check_fold(path).checks}
    assert (
        checks["assignments"].status == "fail" and f"edges {valley}" in checks["assignments"].where
    )
    assert "wound" not in checks["assignments"].where


def rigid_body_dof(mesh, panels: list[list[int]] | None = None) -> int:
    """Internal DOF of a folded frame as rigid bodies sharing vertices, an independent count: each
    panel (a face, or the faces listed together) moves by (v, ω), every vertex of k panels has
    k − 1 equal velocities v_a + ω_a × p = v_b + ω_b × p; the nullity of that matrix (dense SVD,
    rank at 1e-9 of the largest singular value) less 6."""
    x = np.asarray(mesh.vertices_coords, float)
    x = np.c_[x, np.zeros((len(x), 3 - x.shape[1]))]
    faces = [[v for v in f if v >= 0] for f in mesh.faces_vertices.tolist()]
    bodies = panels or [[i] for i in range(len(faces))]
    owner: dict[int, list[int]] = {}
    for b, group in enumerate(bodies):
        for v in sorted({v for i in group for v in faces[i]}):
            owner.setdefault(v, []).append(b)
    rows = []
    for v, owners in owner.items():
        p = x[v]
        skew = np.array([[0, p[2], -p[1]], [-p[2], 0, p[0]], [p[1], -p[0], 0]])  # ω × p = S ω
        for b in owners[1:]:
            row = np.zeros((3, 6 * len(bodies)))
            a = owners[0]
            row[:, 6 * a : 6 * a + 3], row[:, 6 * a + 3 : 6 * a + 6] = np.eye(3), skew
            row[:, 6 * b : 6 * b + 3], row[:, 6 * b + 3 : 6 * b + 6] = -np.eye(3), -skew
            rows.append(row)
    matrix = np.concatenate(rows)
    sigma = np.linalg.svd(matrix, compute_uv=False)
    rank = int((sigma > 1e-9 * sigma[0]).sum())
    return 6 * len(bodies) - rank - 6


@pytest.mark.parametrize("name", FOLDED)
def test_mechanism_counts_as_rigid_bodies_do(name):
    doc = read_fold(CORPUS / name)
    (m,) = analyse_fold(doc)
    assert m.dof == rigid_body_dof(doc.folded[0][1]), (m.dof, m.nullity, m.note)
    r = run("mechanism", str(CORPUS / name))
    line = r.stdout.splitlines()[-1]
    assert f"{m.dof} internal DOF" in line and "∞" not in line, line


def test_the_counts_measured():
    """The counts as measured, so a change shows: a box of 16, a three-fold of 3, a square twist
    of 1, a diagonal fold of 1, five panels in a row of 4, a bird base of 5."""
    counts = {name: analyse_fold(CORPUS / name)[0].dof for name in FOLDED}
    assert list(counts.values()) == [16, 3, 1, 1, 4, 5, 5]


def test_facet_edges_of_a_simulated_sheet_are_no_hinges(tmp_path):
    """A sheet triangulated as Origami Simulator writes it: its F edges between coplanar
    triangles are no hinges, and the count is the rigid panels' (a degree-4 vertex: 1, where
    counting them as hinges gave 5), as the rigid-body count with each quad one body."""
    # a degree-4 vertex: a Miura-ori of four parallelograms folded in closed form, each quad
    # split along a diagonal
    from _fold_corpus import grid_faces, miura

    folded = miura(2, 2, height=0.6).reshape(-1, 3)
    quads = grid_faces(2, 2)
    triangles = [t for a, b, c, d in quads for t in ([a, b, d], [b, c, d])]
    edges = sorted({tuple(sorted((t[k], t[(k + 1) % 3]))) for t in triangles for k in range(3)})
    diagonals = {tuple(sorted((b, d))) for a, b, c, d in quads}
    boundary = {
        tuple(sorted(e)) for e in ([0, 1], [1, 2], [2, 5], [5, 8], [8, 7], [7, 6], [6, 3], [3, 0])
    }
    assignment = ["F" if e in diagonals else "B" if e in boundary else "M" for e in edges]
    doc = {
        "file_spec": 1.1,
        "file_creator": "Origami Simulator: http://git.amandaghassaei.com/OrigamiSimulator/",
        "frame_classes": ["foldedForm"],
        "vertices_coords": [[float(np.float32(v)) for v in p] for p in folded],
        "edges_vertices": [list(e) for e in edges],
        "edges_assignment": assignment,
        "faces_vertices": triangles,
    }
    path = tmp_path / "vertex.fold"
    path.write_text(json.dumps(doc))
    (m,) = analyse_fold(path)
    mesh = read_fold(path).folded[0][1]
    assert m.dof == 1 == rigid_body_dof(mesh, [[2 * q, 2 * q + 1] for q in range(4)])
    assert "4 F edges between coplanar faces in every frame read as no hinge" in m.note
    assert rigid_body_dof(mesh) == 5  # every triangle a body: the F edges hinges
    # an F edge bent is a hinge again
    doc["vertices_coords"][2][2] = float(np.float32(doc["vertices_coords"][2][2] + 0.05))
    path.write_text(json.dumps(doc))
    assert "3 F edges" in analyse_fold(path)[0].note


def test_exact_coordinates_are_not_read_as_rounded(tmp_path):
    """A square of integer coordinates folded in half: a frame 3× stretched, or with a residual of
    0.28, was "consistent" when integers were read as rounded to half a unit (the tolerance 100 ×
    0.5 over the shortest edge)."""
    doc = {
        "file_spec": 1.1,
        "frame_classes": ["creasePattern"],
        "vertices_coords": [[0, 0], [1, 0], [2, 0], [0, 1], [1, 1], [2, 1]],
        "edges_vertices": [[0, 1], [1, 2], [2, 5], [5, 4], [4, 3], [3, 0], [1, 4]],
        "edges_assignment": ["B"] * 6 + ["V"],
        "faces_vertices": [[0, 1, 4, 3], [1, 2, 5, 4]],
        "file_frames": [
            {
                "frame_classes": ["foldedForm"],
                "frame_parent": 0,
                "frame_inherit": True,
                "vertices_coords": [
                    [0, 0, 0],
                    [1, 0, 0],
                    [1, 0, 1],
                    [0, 1, 0],
                    [1, 1, 0],
                    [1, 1, 1],
                ],
            }
        ],
    }
    frame = doc["file_frames"][0]
    path = tmp_path / "square.fold"
    path.write_text(json.dumps(doc))
    (m,) = analyse_fold(path)
    assert m.consistent and m.dof == 1 and m.residual < 1e-15
    assert coordinate_precision(np.array(frame["vertices_coords"])) < 1e-15
    for coords, residual in (
        ([[3 * v for v in p] for p in frame["vertices_coords"]], 4.0),  # 3× stretched: (3² − 1)/2
        ([[0, 0, 0], [1, 0, 0], [1, 0, 1.25], [0, 1, 0], [1, 1, 0], [1, 1, 1.25]], 0.28),
    ):
        frame["vertices_coords"] = coords
        path.write_text(json.dumps(doc))
        (m,) = analyse_fold(path)
        assert not m.consistent and m.residual == pytest.approx(residual, abs=0.01)
        assert run("mechanism", str(path)).returncode == 1
    # digits that are no dyadic fraction still set the precision
    assert coordinate_precision(np.array([[0.5, 0.25, 0.466968]])) == 5e-7


def test_advice_for_a_large_foreign_file_speaks_of_its_mesh(tmp_path):
    """It said "use fewer panels, tubes or cells" of another tool's sheet."""
    n = 33  # 33 × 33 vertices: 3267 unknowns
    coords = [[x / 32, y / 32, 0.1 * (x % 2)] for y in range(n) for x in range(n)]
    faces = [
        [y * n + x, y * n + x + 1, (y + 1) * n + x + 1, (y + 1) * n + x]
        for y in range(n - 1)
        for x in range(n - 1)
    ]
    edges = sorted({tuple(sorted((f[k], f[(k + 1) % 4]))) for f in faces for k in range(4)})
    doc = {
        "file_spec": 1.1,
        "frame_classes": ["foldedForm"],
        "vertices_coords": coords,
        "edges_vertices": [list(e) for e in edges],
        "faces_vertices": faces,
    }
    path = tmp_path / "large.fold"
    path.write_text(json.dumps(doc))
    r = run("mechanism", str(path))
    assert r.returncode == 2 and "a coarser mesh of the same model fits" in r.stderr
    assert "panels" not in r.stderr and "tubes" not in r.stderr


def test_a_pattern_saved_with_its_target_angles_is_read_as_a_crease_pattern(tmp_path):
    """Origami Simulator saves a crease pattern as one frame classed foldedForm, in its plane
    y = 0, unfolded, with the target fold angles (its five box-pleat files in its assets, 180°
    at most): every one failed `fold_angles` ("180 > 0.01°"), a state it does not claim to be."""
    from _fold_corpus import assignment_of, edges_of, grid_faces, miura

    faces = grid_faces(3, 4)
    edges = edges_of(faces)
    assignment, angles = assignment_of(miura(3, 4, height=0.6).reshape(-1, 3), faces, edges)
    flat = miura(3, 4).reshape(-1, 3)
    doc = {
        "file_spec": 1.1,
        "file_creator": "Origami Simulator: http://git.amandaghassaei.com/OrigamiSimulator/",
        "frame_classes": ["foldedForm"],
        "frame_attributes": ["3D"],
        "vertices_coords": [[float(np.float32(v)) for v in (p[0], 0.0, p[1])] for p in flat],
        "edges_vertices": edges,
        "edges_assignment": assignment,
        "edges_foldAngle": [
            None if a == "B" else round(float(v), 2) for a, v in zip(assignment, angles)
        ],
        "faces_vertices": faces,
    }
    path = tmp_path / "pattern.fold"
    path.write_text(json.dumps(doc))
    fold = read_fold(path)
    assert fold.crease_pattern is not None and not fold.folded
    assert any("read as a crease pattern with its target angles" in n for n in fold.notes)
    assert check_fold(path).ok
    # its targets are still checked against its assignments
    doc["edges_foldAngle"][assignment.index("M")] *= -1
    path.write_text(json.dumps(doc))
    assert {c.name for c in check_fold(path).checks if c.status == "fail"} == {"assignments"}
