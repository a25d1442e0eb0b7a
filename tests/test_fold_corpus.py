"""FOLD files as other tools write them: read, checked, and their degrees of freedom counted.

The corpus (:mod:`_fold_corpus`) holds a Miura-ori, a square twist, a waterbomb base and a
flat-folded square in the forms of the FOLD repository's examples, Origami Simulator's
exports, ``fold-convert`` and a crease-pattern editor. Before, ``check`` refused every one of
them (a folded form alone, ``null`` fold angles, a byte-order mark, ``U``/``J``/``C``) and
``mechanism`` refused the folded forms.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from _cli import run
from _fold_corpus import KNOWN_DOF, corpus, triangulated_dof, write_corpus
from curvefold.analysis import check_fold
from curvefold.analysis._fold_mechanism import analyse_fold, coordinate_precision
from curvefold.geometry import Mesh
from curvefold.io import read_fold
from curvefold.io._fold_keys import split_cuts


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    return write_corpus(tmp_path_factory.mktemp("corpus"))


def checks(path) -> dict:
    return {c.name: c for c in check_fold(path).checks}


@pytest.mark.parametrize("name", list(corpus()))
def test_every_file_of_the_corpus_is_read_and_passes(files, name):
    result = check_fold(files[name])
    assert result.ok, [(c.name, c.where) for c in result.checks if c.status == "fail"]
    r = run("check", str(files[name]), "--json")
    assert r.returncode == 0 and json.loads(r.stdout)["ok"], r.stderr


@pytest.mark.parametrize("name", list(KNOWN_DOF))
def test_the_corpus_has_its_known_degrees_of_freedom(files, name):
    known = (
        KNOWN_DOF[name]
        if KNOWN_DOF[name] is not None
        else triangulated_dof(json.loads(files[name].read_text()))
    )
    frames = analyse_fold(files[name])
    assert [m.dof for m in frames] == [known] * len(frames)
    # single precision moves the null singular values off zero by ~1e-7 of the largest
    single = name == "miura-origami-simulator.fold"
    assert all(m.consistent and m.gap > (1e6 if single else 1e10) for m in frames), [
        (m.residual, m.gap) for m in frames
    ]
    r = run("mechanism", str(files[name]), "--json")
    assert r.returncode == 0 and [f["dof"] for f in json.loads(r.stdout)["frames"]] == [
        known
    ] * len(frames)


def test_origami_simulator_files_read_null_angles_on_boundaries_as_zero(files):
    """Origami Simulator writes ``null`` on every boundary edge; it was "edges_foldAngle must
    hold finite numbers"."""
    path = files["miura-origami-simulator.fold"]
    doc = read_fold(path)
    assert doc.crease_pattern is None and len(doc.folded) == 1 and not doc.is_flat_folded(0)
    assert any("edges_foldAngle is null on 14 B edges, read as 0" in n for n in doc.notes)
    # 14 boundary edges of a triangulated 3 × 4 Miura-ori
    assert triangulated_dof(json.loads(path.read_text())) == 11  # were its F edges hinges
    r = run("check", str(path))
    assert "note:" in r.stdout and "read as 0" in r.stdout


def test_a_folded_form_alone_runs_what_needs_no_crease_pattern(files):
    """It was "no folded frame to check (the file holds only a crease pattern)"."""
    result = checks(files["square-twist.fold"])
    assert {n for n, c in result.items() if c.status == "pass"} == {
        "topology",
        "assignments",
        "face_planarity",
    }
    assert (
        result["isometry"].status == "not run" and "no crease pattern" in result["isometry"].reason
    )
    assert (
        result["fold_angles"].status == "not run"
        and "records no fold angle" in result["fold_angles"].reason
    )
    (m,) = analyse_fold(files["square-twist.fold"])
    # 6 decimals leave the quads planar to ~1e-6
    assert "the frame's own lengths" in m.note and m.residual > 1e-7


def test_a_flat_folded_file_reads_its_crease_pattern_and_checks_magnitudes(tmp_path, files):
    path = files["diagonal-flat-folded.fold"]
    doc = read_fold(path)
    assert doc.crease_frame is None and doc.is_flat_folded(0)
    # vertices_flatUnfoldCoords
    assert doc.crease_pattern.vertices_coords[2].tolist() == [1.0, 1.0, 0.0]
    assert any(
        "faces_flatFoldTransform" in n and "derived from the crease pattern" in n for n in doc.notes
    )
    result = checks(path)
    assert result["isometry"].status == result["fold_angles"].status == "pass"
    # recorded as unfolded while the faces lie on each other: the magnitude is wrong
    data = json.loads(path.read_text())
    data["edges_foldAngle"][4] = 0
    (tmp_path / "flat.fold").write_text(json.dumps(data))
    result = checks(tmp_path / "flat.fold")
    assert (
        result["fold_angles"].status == "fail"
        and result["fold_angles"].where == "key frame ('key frame'): edges 4"
    )
    data["edges_assignment"][4] = "F"  # a flat crease folded through
    (tmp_path / "flat.fold").write_text(json.dumps(data))
    assert checks(tmp_path / "flat.fold")["assignments"].status == "fail"


def test_fold_1_2_assignments_a_byte_order_mark_and_other_keys_are_read_or_named(files):
    doc = read_fold(files["miura-cp-frames.fold"])
    notes = " | ".join(doc.notes)
    assert "a UTF-8 byte-order mark opens the file: skipped" in notes
    assert "editor:selection (another tool's key)" in notes and "faceOrders (layer order" in notes
    assert "1 cut (C) edges read as 1 boundary edges" in notes
    assert set(doc.crease_pattern.edges_assignment.tolist()) == {"M", "V", "B", "U", "J"}
    assert len(doc.folded) == 2 and doc.frame_id(1) == 2


def test_a_join_edge_must_stay_flat(tmp_path, files):
    data = json.loads(files["miura-cp-frames.fold"].read_bytes()[3:])
    join = data["edges_assignment"].index("J")
    a, b = data["edges_vertices"][join]
    apex = next(v for v in data["faces_vertices"][0] if v not in (a, b))
    # one triangle of the joined panel bent
    data["file_frames"][1]["vertices_coords"][apex][2] += 0.05
    (tmp_path / "bent.fold").write_text(json.dumps(data))
    result = checks(tmp_path / "bent.fold")
    assert (
        result["face_planarity"].status == "fail" and "join edges" in result["face_planarity"].where
    )
    assert analyse_fold(tmp_path / "bent.fold")[1].consistent is False


def test_a_cut_from_the_outline_splits_its_vertices():
    """A slit from the outline to the centre of a square of four quads: the outline vertex is
    two."""
    xy = np.array([(x, y, 0.0) for y in range(3) for x in range(3)], float)
    faces = np.array([[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]])
    edges = np.array(
        [
            [0, 1],
            [1, 2],
            [2, 5],
            [5, 8],
            [8, 7],
            [7, 6],
            [6, 3],
            [3, 0],
            [1, 4],
            [4, 7],
            [3, 4],
            [4, 5],
        ]
    )
    mesh = Mesh(
        xy,
        edges,
        np.array(["B"] * 8 + ["C", "V", "M", "F"]),
        np.zeros(12),
        faces,
        np.array(["boundary"] * 12),
        np.zeros(4, int),
    )
    notes = []
    cut, _ = split_cuts(mesh, (), "square", notes)
    assert notes == [
        "square: 1 cut (C) edges read as 2 boundary edges, one per face, 1 vertices "
        "split along the cuts (FOLD 1.2)"
    ]
    assert len(cut.vertices_coords) == 10 and cut.vertices_coords[9].tolist() == [1.0, 0.0, 0.0]
    # one copy per face
    assert cut.edges_vertices[8].tolist() == [1, 4] and cut.edges_vertices[12].tolist() == [9, 4]
    assert cut.faces_vertices[1].tolist() == [9, 2, 5, 4] and cut.edges_vertices[1].tolist() == [
        9,
        2,
    ]
    assert set(cut.edges_assignment.tolist()) == {"B", "V", "M", "F"}


def test_coordinates_rounded_as_written_raise_the_tolerance_to_their_precision(tmp_path, files):
    """Folded frames written with 6 decimals break their lengths by ~1e-6: the count is made at that
    precision (1 DOF), not at rounding (which found 0 and called the frame inconsistent)."""
    data = json.loads(files["miura-cp-frames.fold"].read_bytes()[3:])
    for frame in data["file_frames"]:
        frame["vertices_coords"] = [[round(v, 6) for v in p] for p in frame["vertices_coords"]]
    (tmp_path / "rounded.fold").write_text(json.dumps(data))
    frames = analyse_fold(tmp_path / "rounded.fold")
    assert [m.dof for m in frames] == [1, 1] and all(m.consistent for m in frames)
    assert all(1e-7 < m.residual < 1e-5 and "rank tolerance raised" in m.note for m in frames)
    # whatever the rtol asked
    assert analyse_fold(tmp_path / "rounded.fold", rtol=1e-9)[0].tolerance > 1e-6
    # dyadic fractions of few digits are exact as written, others set the precision
    assert coordinate_precision(np.array([[0.5, 0.25]])) < 1e-15
    assert coordinate_precision(np.array([[0.5, 0.25, 0.125001]])) == 5e-7
    assert (
        coordinate_precision(np.array([[float(np.float32(0.1)), 1.0]]))
        == float(np.spacing(np.float32(1.0))) / 2
    )


def test_a_damaged_folded_form_is_caught(tmp_path, files):
    data = json.loads(files["miura-mathematica.fold"].read_text())
    data["vertices_coords"][6][2] += 0.05  # an inner vertex lifted: its quads bend
    (tmp_path / "bent.fold").write_text(json.dumps(data))
    assert checks(tmp_path / "bent.fold")["face_planarity"].status == "fail"
    (m,) = analyse_fold(tmp_path / "bent.fold")
    assert not m.consistent


def test_a_second_crease_pattern_frame_is_no_folded_frame(tmp_path, files):
    """A crease pattern and another one of fewer vertices (a design's second state, as an editor
    keeps it): it was checked as a folded frame, "4 vertices fewer"."""
    data = json.loads(files["miura-cp-frames.fold"].read_bytes()[3:])
    n = len(data["vertices_coords"]) - 4
    data["file_frames"].append(
        {
            "frame_title": "a smaller pattern",
            "frame_classes": ["creasePattern"],
            "vertices_coords": [[x, y] for x, y in [p[:2] for p in data["vertices_coords"][:n]]],
            "edges_vertices": [e for e in data["edges_vertices"] if max(e) < n],
            "faces_vertices": [f for f in data["faces_vertices"] if max(f) < n],
            "edges_assignment": [
                a for a, e in zip(data["edges_assignment"], data["edges_vertices"]) if max(e) < n
            ],
        }
    )
    (tmp_path / "two.fold").write_text(json.dumps(data))
    doc = read_fold(tmp_path / "two.fold")
    assert len(doc.folded) == 2
    assert any("another crease pattern (frame_classes creasePattern)" in n for n in doc.notes)
    assert check_fold(tmp_path / "two.fold").ok
    assert [m.dof for m in analyse_fold(tmp_path / "two.fold")] == [1, 1]
