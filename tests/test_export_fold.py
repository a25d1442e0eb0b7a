"""FOLD writer and reader: structure, round trip, errors, atomicity, independent readers."""

from __future__ import annotations

import json
import pathlib
import re
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

import curvefold
from _meshes import (
    assert_written,
    measured_fold_angles,
    oblique_motion,
    strip_motion,
    two_sheet_tube,
)
from _node import run_node
from curvefold.geometry import Mesh
from curvefold.io import FoldFile, fold_assignments, read_fold, write_fold, write_sheet_fold
from curvefold.io._fold import ANGLE_DECIMALS, COORDINATE_RTOL
from curvefold.kernel import InputError


def _write_tube(path: Path, **kw) -> tuple:
    motion = strip_motion(4, 2, seam=True)
    kwargs = dict(
        crease_pattern=motion.crease_pattern,
        folded=motion.folded,
        metadata={"length": 4.0, "panels": 4, "name": "square tube"},
        unit="mm",
        seam_partners=motion.seam_partners,
    )
    kwargs.update(kw)
    title = kwargs.pop("title", "")
    write_fold(path, FoldFile(**kwargs), title=title)
    return motion, json.loads(path.read_text())


def test_numbers_are_written_to_their_tolerance_and_no_more(tmp_path):
    motion = oblique_motion()
    write_fold(
        tmp_path / "m.fold", FoldFile(crease_pattern=motion.crease_pattern, folded=motion.folded)
    )
    text = (tmp_path / "m.fold").read_text()
    doc = json.loads(text)
    errors = []
    for frame, (_, mesh) in zip(doc["file_frames"], motion.folded):
        want = np.asarray(mesh.vertices_coords, float)
        errors.append(
            np.abs(np.array(frame["vertices_coords"]) - want).max() / np.ptp(want, axis=0).max()
        )
        assert (
            np.abs(np.array(frame["edges_foldAngle"]) - mesh.edges_foldAngle).max()
            <= 0.5 * 10.0**-ANGLE_DECIMALS
        )
    assert 0 < max(errors) <= 0.5 * COORDINATE_RTOL  # rounded, to half the quantum
    decimals = [
        len(number.partition(".")[2]) for number in re.findall(r"-?\d+\.\d+(?![\de])", text)
    ]
    assert max(decimals) <= 13  # 17 before: every digit of a double


# --- structure of the written file ------------------------------------------------------


def test_file_layout(tmp_path):
    motion, doc = _write_tube(tmp_path / "tube.fold", title="tube")
    cp = motion.crease_pattern
    assert doc["file_spec"] == 1.1
    assert doc["file_creator"] == f"curvefold {curvefold.__version__}"
    assert doc["file_classes"] == ["singleModel"]
    assert doc["file_title"] == "tube"
    assert doc["frame_classes"] == ["creasePattern"]
    assert doc["frame_unit"] == "mm"
    assert all(len(c) == 2 for c in doc["vertices_coords"])
    assert len(doc["faces_vertices"]) == len(cp.faces_vertices)
    assert doc["curvefold:metadata"] == {"length": 4.0, "panels": 4, "name": "square tube"}
    assert doc["curvefold:seam_partners"] == motion.seam_partners.tolist()
    assert len(doc["file_frames"]) == len(motion.angles_deg)
    for frame, (title, mesh) in zip(doc["file_frames"], motion.folded):
        assert set(frame) == {
            "frame_title",
            "frame_classes",
            "frame_parent",
            "frame_inherit",
            "vertices_coords",
            "edges_foldAngle",
        }
        assert frame["frame_title"] == title
        assert frame["frame_classes"] == ["foldedForm"]
        assert frame["frame_parent"] == 0 and frame["frame_inherit"] is True
        assert all(len(c) == 3 for c in frame["vertices_coords"])
        assert_written(frame["vertices_coords"], mesh.vertices_coords)


def test_assignments_and_angles_follow_edge_kind(tmp_path):
    motion, doc = _write_tube(tmp_path / "tube.fold")
    kind = np.array(doc["edges_curvefold:kind"])
    assignment = np.array(doc["edges_assignment"])
    assert_array_equal(kind, motion.crease_pattern.edges_kind)
    assert set(assignment[kind == "fold"]) == {"V"}
    assert set(assignment[np.isin(kind, ("seam", "boundary"))]) == {"B"}
    assert set(assignment[np.isin(kind, ("ruling", "diagonal"))]) == {"F"}
    flat = np.isin(assignment, ("B", "F"))
    for angles in [doc["edges_foldAngle"]] + [f["edges_foldAngle"] for f in doc["file_frames"]]:
        assert_array_equal(np.array(angles)[flat], 0.0)
    # the 90-degree frame closes the tube: every fold is a 90-degree valley
    assert_allclose(
        np.array(doc["file_frames"][-1]["edges_foldAngle"])[kind == "fold"], 90.0, atol=1e-9
    )


def test_fold_assignments_mountain_valley_from_sign():
    kind = np.array(["fold", "fold", "fold", "fold", "boundary", "seam", "ruling", "diagonal"])
    angle = np.array([-10.0, 10.0, 0.0, 0.0, 0.0, 30.0, 0.0, 5.0])
    given = np.array(["V", "M", "M", "F", "B", "B", "F", "F"])
    assert fold_assignments(kind, angle, given).tolist() == ["M", "V", "M", "F", "B", "B", "F", "F"]


# --- round trip through our own reader ---------------------------------------------------


def _assert_same_mesh(a: Mesh, b: Mesh, *, coords=True):
    if coords:
        assert_written(a.vertices_coords, b.vertices_coords)
    for name in ("edges_vertices", "faces_vertices", "edges_kind", "faces_group"):
        assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)


@pytest.mark.parametrize(
    "make",
    [lambda: strip_motion(4, 2, seam=True), oblique_motion, two_sheet_tube],
    ids=["tube", "oblique", "two-sheets"],
)
def test_round_trip(tmp_path, make):
    motion = make()
    path = tmp_path / "m.fold"
    write_fold(
        path,
        FoldFile(
            crease_pattern=motion.crease_pattern,
            folded=motion.folded,
            metadata={"a": 1.25, "ok": True},
            unit="m",
            seam_partners=motion.seam_partners,
        ),
    )
    back = read_fold(path)
    cp = motion.crease_pattern
    _assert_same_mesh(back.crease_pattern, cp)
    assert back.crease_pattern.vertices_coords.shape == (len(cp.vertices_coords), 3)
    assert_array_equal(
        back.crease_pattern.edges_assignment,
        fold_assignments(cp.edges_kind, cp.edges_foldAngle, cp.edges_assignment),
    )
    assert_array_equal(back.crease_pattern.edges_foldAngle, cp.edges_foldAngle)
    assert [t for t, _ in back.folded] == [t for t, _ in motion.folded]
    for (_, got), (_, want) in zip(back.folded, motion.folded):
        _assert_same_mesh(got, want)
        assert_array_equal(got.edges_assignment, back.crease_pattern.edges_assignment)  # inherited
        flat = np.isin(got.edges_assignment, ("B", "F"))
        assert_allclose(
            got.edges_foldAngle[~flat],
            want.edges_foldAngle[~flat],
            rtol=0,
            atol=10.0**-ANGLE_DECIMALS,
        )
        assert_allclose(got.edges_foldAngle[~flat], measured_fold_angles(got)[~flat], atol=1e-9)
    assert back.metadata == {"a": 1.25, "ok": True}
    assert back.unit == "m"
    assert_array_equal(back.seam_partners, motion.seam_partners.reshape(-1, 2))


@pytest.mark.parametrize(
    "make", [lambda: strip_motion(4, 2, seam=True), two_sheet_tube], ids=["tube", "two-sheets"]
)
def test_round_trip_seams_close_in_the_tube(tmp_path, make):
    motion = make()
    write_fold(
        tmp_path / "tube.fold",
        FoldFile(
            crease_pattern=motion.crease_pattern,
            folded=motion.folded,
            seam_partners=motion.seam_partners,
        ),
    )
    back = read_fold(tmp_path / "tube.fold")
    assert len(back.seam_partners) == len(motion.seam_partners) > 0
    _, closed = back.folded[-1]
    ev = closed.edges_vertices
    for a, b in back.seam_partners:
        ends_a = closed.vertices_coords[ev[a]]
        ends_b = closed.vertices_coords[ev[b]][::-1]  # glued edges run opposite ways
        assert_allclose(ends_a, ends_b, atol=1e-12)


def test_read_foreign_file_without_curvefold_keys(tmp_path):
    path = tmp_path / "plain.fold"
    path.write_text(
        json.dumps(
            {
                "file_spec": 1.1,
                "vertices_coords": [[0, 0], [1, 0], [1, 1], [0, 1]],
                "edges_vertices": [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
                "edges_assignment": ["B", "B", "B", "B", "V"],
                "faces_vertices": [[0, 1, 2], [0, 2, 3]],
                "file_frames": [
                    {
                        "frame_title": "moved",
                        "frame_inherit": True,
                        "frame_parent": 0,
                        "vertices_coords": [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]],
                    }
                ],
            }
        )
    )
    back = read_fold(path)
    assert back.crease_pattern.edges_kind.tolist() == ["boundary"] * 4 + ["fold"]
    assert back.crease_pattern.edges_foldAngle.tolist() == [0, 0, 0, 0, 180]
    assert_array_equal(back.crease_pattern.faces_group, 0)
    assert back.unit == "unit" and back.metadata == {} and back.seam_partners.shape == (0, 2)
    assert back.folded[0][0] == "moved"
    assert_array_equal(back.folded[0][1].vertices_coords[:, 2], 1.0)


# --- sheet for Origami Simulator ----------------------------------------------------------


def test_sheet_fold_flat_is_2d_crease_pattern(tmp_path):
    motion = oblique_motion()
    write_sheet_fold(tmp_path / "sheet.fold", motion.crease_pattern, "mm", title="sheet")
    doc = json.loads((tmp_path / "sheet.fold").read_text())
    for key in (
        "vertices_coords",
        "edges_vertices",
        "edges_assignment",
        "edges_foldAngle",
        "faces_vertices",
    ):
        assert key in doc
    assert doc["frame_classes"] == ["creasePattern"] and doc["frame_unit"] == "mm"
    assert all(len(c) == 2 for c in doc["vertices_coords"])
    assert set(doc["edges_assignment"]) <= {"M", "V", "B", "F"}
    assert {"M", "V"} <= set(doc["edges_assignment"])
    assert "file_frames" not in doc
    back = read_fold(tmp_path / "sheet.fold")
    assert_array_equal(back.crease_pattern.edges_foldAngle, motion.crease_pattern.edges_foldAngle)


def test_sheet_fold_folded_is_3d(tmp_path):
    motion = oblique_motion()
    write_sheet_fold(tmp_path / "sheet.fold", motion.state(2))
    doc = json.loads((tmp_path / "sheet.fold").read_text())
    assert doc["frame_classes"] == ["foldedForm"]
    assert_written(doc["vertices_coords"], motion.coords[2])


# --- writer errors --------------------------------------------------------------------------


def _replace(mesh: Mesh, **kw) -> Mesh:
    from dataclasses import replace

    return replace(mesh, **kw)


def test_write_rejects_folded_crease_pattern(tmp_path):
    m = strip_motion()
    with pytest.raises(InputError, match="crease_pattern must be flat"):
        write_fold(tmp_path / "x.fold", FoldFile(crease_pattern=m.state(2), folded=[]))


def test_write_rejects_a_model_without_crease_pattern(tmp_path):
    """A FoldFile read from a file of folded frames only has no crease pattern to write."""
    m = strip_motion()
    with pytest.raises(InputError, match="the model's crease_pattern must be a Mesh, got NoneType"):
        write_fold(tmp_path / "x.fold", FoldFile(crease_pattern=None, folded=m.folded))
    assert list(tmp_path.iterdir()) == []


def _mirrored(motion):
    """The same motion with a crease pattern whose triangles are all clockwise (seen from below)."""
    cp = motion.crease_pattern
    return _replace(cp, vertices_coords=cp.vertices_coords * [1, -1, 1])


def test_clockwise_sheet_is_mirrored_back(tmp_path):
    motion = two_sheet_tube()
    clockwise = _mirrored(motion)
    write_fold(tmp_path / "m.fold", FoldFile(crease_pattern=clockwise, folded=motion.folded))
    back = read_fold(tmp_path / "m.fold").crease_pattern
    assert (back.face_normals()[:, 2] > 0).all()
    # each sheet is mirrored in place, about its own centre line: same place, same lengths
    cw = clockwise.vertices_coords
    assert_allclose(back.edge_lengths(), clockwise.edge_lengths(), atol=1e-12)
    assert_allclose(back.vertices_coords[:, 0], cw[:, 0])
    assert_allclose(
        back.vertices_coords[:, 1], cw[:, 1].min() + cw[:, 1].max() - cw[:, 1], atol=1e-12
    )


def test_clockwise_sheet_rejected_without_mirroring(tmp_path):
    motion = strip_motion()
    with pytest.raises(InputError, match="counter-clockwise"):
        write_fold(
            tmp_path / "x.fold",
            FoldFile(crease_pattern=_mirrored(motion), folded=[]),
            mirror_clockwise=False,
        )


def test_sheet_with_both_orientations_rejected(tmp_path):
    cp = strip_motion(2, 1).crease_pattern
    faces = cp.faces_vertices.copy()
    faces[0] = faces[0][::-1]
    with pytest.raises(InputError, match="both orientations"):
        write_fold(
            tmp_path / "x.fold",
            FoldFile(crease_pattern=_replace(cp, faces_vertices=faces), folded=[]),
        )


def test_write_rejects_topology_mismatch(tmp_path):
    a, b = strip_motion(2), strip_motion(3)
    with pytest.raises(InputError, match=r"folded\[0\].*differs"):
        write_fold(
            tmp_path / "x.fold",
            FoldFile(crease_pattern=a.crease_pattern, folded=[("other", b.state(0))]),
        )


def test_write_rejects_crease_with_one_face(tmp_path):
    m = strip_motion(2, 1)
    cp = m.crease_pattern
    kinds = cp.edges_kind.copy()
    kinds[np.flatnonzero(kinds == "boundary")[0]] = "fold"
    with pytest.raises(InputError, match="has 1 faces, expected 2"):
        write_fold(
            tmp_path / "x.fold", FoldFile(crease_pattern=_replace(cp, edges_kind=kinds), folded=[])
        )


def test_write_rejects_missing_edge(tmp_path):
    cp = strip_motion(2, 1).crease_pattern
    keep = np.arange(1, len(cp.edges_vertices))
    short = _replace(
        cp,
        edges_vertices=cp.edges_vertices[keep],
        edges_assignment=cp.edges_assignment[keep],
        edges_foldAngle=cp.edges_foldAngle[keep],
        edges_kind=cp.edges_kind[keep],
    )
    with pytest.raises(InputError, match="is not an edge"):
        write_fold(tmp_path / "x.fold", FoldFile(crease_pattern=short, folded=[]))


@pytest.mark.parametrize(
    ("partners", "match"),
    [
        ([[0, 99]], r"edge indices in \[0, 30\)"),
        ([[4, 4]], "itself"),
        ([[1, 24]], "edge 1 is not a boundary"),
        ("xy", "seam_partners"),
    ],
)
def test_write_rejects_bad_seam_partners(tmp_path, partners, match):
    m = strip_motion(4, 2, seam=True)
    with pytest.raises(InputError, match=match):
        write_fold(
            tmp_path / "x.fold",
            FoldFile(crease_pattern=m.crease_pattern, folded=[], seam_partners=partners),
        )


@pytest.mark.parametrize(
    ("metadata", "match"),
    [
        ({"a": float("nan")}, "finite"),
        ({"a": [1]}, "number or a str"),
        ({1: 2}, "keys must be str"),
    ],
)
def test_write_rejects_bad_metadata(tmp_path, metadata, match):
    m = strip_motion()
    with pytest.raises(InputError, match=match):
        write_fold(
            tmp_path / "x.fold",
            FoldFile(crease_pattern=m.crease_pattern, folded=[], metadata=metadata),
        )
    assert not list(tmp_path.iterdir())


def test_write_rejects_non_pair_frame(tmp_path):
    m = strip_motion()
    with pytest.raises(InputError, match=r"folded\[0\] must be a \(title, Mesh\) pair"):
        write_fold(
            tmp_path / "x.fold", FoldFile(crease_pattern=m.crease_pattern, folded=[m.state(1)])
        )


def test_sheet_rejects_welded_seam(tmp_path):
    m = strip_motion(2, 1)
    cp = m.crease_pattern
    kinds = np.where(cp.edges_kind == "diagonal", "seam", cp.edges_kind)  # a "seam" with two faces
    with pytest.raises(InputError, match="a seam must be two boundary edges"):
        write_sheet_fold(tmp_path / "x.fold", _replace(cp, edges_kind=kinds))


# --- reader errors ----------------------------------------------------------------------------


def _valid_doc() -> dict:
    return {
        "file_spec": 1.1,
        "vertices_coords": [[0, 0], [1, 0], [1, 1], [0, 1]],
        "edges_vertices": [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
        "edges_assignment": ["B", "B", "B", "B", "M"],
        "edges_foldAngle": [0, 0, 0, 0, -90],
        "faces_vertices": [[0, 1, 2], [0, 2, 3]],
        "edges_curvefold:kind": ["boundary"] * 4 + ["fold"],
        "curvefold:seam_partners": [],
        "curvefold:metadata": {"w": 1},
        "file_frames": [
            {
                "frame_inherit": True,
                "frame_parent": 0,
                "vertices_coords": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
            }
        ],
    }


def _set(path: str, value):
    def edit(doc):
        *head, last = path.split("/")
        target = doc
        for key in head:
            target = target[int(key)] if isinstance(target, list) else target[key]
        if value is _DELETE:
            del target[last]
        elif isinstance(target, list):
            target[int(last)] = value
        else:
            target[last] = value
        return doc

    return edit


_DELETE = object()


@pytest.mark.parametrize(
    ("edit", "match"),
    [
        (_set("vertices_coords", _DELETE), "missing required key 'vertices_coords'"),
        (_set("edges_vertices", _DELETE), "missing required key 'edges_vertices'"),
        (_set("faces_vertices", _DELETE), "missing required key 'faces_vertices'"),
        (
            _set("edges_assignment", ["B", "B", "B", "B"]),
            "edges_assignment must be a list of 5 entries",
        ),
        (_set("edges_foldAngle", [0, 0]), "edges_foldAngle must be a list of 5 numbers"),
        (_set("edges_foldAngle/4", 270), r"\[-180, 180\]"),
        (_set("edges_foldAngle/4", "x"), r"edges_foldAngle\[4\] must be a number or null, got 'x'"),
        (
            _set("edges_vertices/2", [2, 7]),
            r"edges_vertices\[2\] = \[2, 7\] refers to a vertex " r"outside \[0, 4\)",
        ),
        (_set("edges_vertices/2", [2, 2]), "joins a vertex to itself"),
        (_set("edges_vertices/2", [2, 3, 4]), r"edges_vertices\[2\] must have 2 entries"),
        (
            _set("faces_vertices/1", [0, 2, -1]),
            r"faces_vertices\[1\] = \[0, 2, -1\] refers to a " r"vertex outside",
        ),
        (
            _set("faces_vertices/1", [0, 2]),
            r"faces_vertices\[1\] has 2 vertices; a face needs at " r"least 3",
        ),
        (_set("edges_assignment/4", "X"), r"edges_assignment\[4\] = 'X' is not one of FOLD's"),
        (_set("vertices_coords/0", [0]), r"list of \[x, y\] or \[x, y, z\] lists"),
        (
            _set("vertices_coords/0", [0, None]),
            r"vertices_coords\[0\] must hold numbers only, " r"got \[0, None\]",
        ),
        (
            _set("edges_curvefold:kind/4", "crease"),
            r"edges_curvefold:kind\[4\] = 'crease' is not " r"one of",
        ),
        (
            _set("curvefold:seam_partners", [[0, 9]]),
            r"seam_partners\[0\] = \[0, 9\] refers to an " r"edge outside",
        ),
        (_set("curvefold:metadata", {"w": [1]}), "curvefold:metadata"),
        (_set("file_frames/0/frame_parent", 1), "frame_parent must be another frame id"),
        (_set("file_frames/0/vertices_coords", [[0, 0, 0]]), "file_frames\\[0\\]"),
        (_set("file_frames", {}), "file_frames must be a list"),
        (_set("frame_unit", 3), "frame_unit must be a string"),
    ],
)
def test_read_rejects_malformed(tmp_path, edit, match):
    path = tmp_path / "bad.fold"
    path.write_text(json.dumps(edit(_valid_doc())))
    with pytest.raises(InputError, match=match):
        read_fold(path)


def test_read_valid_doc_passes(tmp_path):
    path = tmp_path / "ok.fold"
    path.write_text(json.dumps(_valid_doc()))
    back = read_fold(path)
    assert back.crease_pattern.edges_foldAngle.tolist() == [0, 0, 0, 0, -90]
    assert back.folded[0][0] == "frame 1"


@pytest.mark.parametrize(
    ("text", "match"), [("{not json", "not valid JSON"), ("[1, 2]", "must hold a JSON object")]
)
def test_read_rejects_non_fold_json(tmp_path, text, match):
    path = tmp_path / "bad.fold"
    path.write_text(text)
    with pytest.raises(InputError, match=match):
        read_fold(path)


def test_read_missing_file_names_path(tmp_path):
    with pytest.raises(InputError, match="cannot read FOLD file"):
        read_fold(tmp_path / "absent.fold")


# --- atomicity ------------------------------------------------------------------------------------


def test_failed_write_leaves_no_file_and_keeps_old(tmp_path, monkeypatch):
    m = strip_motion()
    target = tmp_path / "m.fold"
    target.write_text("old")

    def broken(self, data):
        with open(self, "wb") as fh:
            fh.write(data[: len(data) // 2])
        raise OSError("disk full")

    monkeypatch.setattr(pathlib.Path, "write_bytes", broken)
    with pytest.raises(OSError, match="disk full"):
        write_fold(target, FoldFile(crease_pattern=m.crease_pattern, folded=m.folded))
    with pytest.raises(OSError, match="disk full"):
        write_sheet_fold(tmp_path / "new.fold", m.crease_pattern)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.fold"]
    assert target.read_text() == "old"


# --- independent readers (Node.js: the `fold` library and Rabbit Ear) ---------------------------


@pytest.mark.node
@pytest.mark.parametrize(
    "make",
    [lambda: strip_motion(4, 2, seam=True), oblique_motion, two_sheet_tube],
    ids=["tube", "oblique", "two-sheets"],
)
def test_node_fold_and_rabbit_ear(tmp_path, make):
    motion = make()
    path = tmp_path / "m.fold"
    write_fold(
        path,
        FoldFile(
            crease_pattern=motion.crease_pattern,
            folded=motion.folded,
            seam_partners=motion.seam_partners,
        ),
    )
    report = run_node("check_fold.mjs", str(path))
    fold, ear = report["fold"], report["rabbit_ear"]
    assert fold["same_vertex_sets"], fold
    assert fold["same_orientation"], fold
    assert fold["faces_rebuilt"] == len(motion.crease_pattern.faces_vertices)
    assert ear["summary"] == "valid", ear
    assert ear["references_ok"]
    assert ear["faces_cw"] == 0 and ear["faces_ccw"] == len(motion.crease_pattern.faces_vertices)
    assert [f["title"] for f in ear["frames"]] == [t for t, _ in motion.folded]
    for frame in ear["frames"]:
        assert frame["max_distance"] < 1e-9, frame


@pytest.mark.node
def test_node_mirrored_crease_pattern_still_folds_to_the_frames(tmp_path):
    motion = oblique_motion()
    write_fold(
        tmp_path / "m.fold", FoldFile(crease_pattern=_mirrored(motion), folded=motion.folded)
    )
    report = run_node("check_fold.mjs", str(tmp_path / "m.fold"))
    assert report["rabbit_ear"]["faces_cw"] == 0
    assert max(f["max_distance"] for f in report["rabbit_ear"]["frames"]) < 1e-9


@pytest.mark.node
def test_node_rabbit_ear_detects_wrong_fold_sign(tmp_path):
    """The folding check can fail: flipping valley/mountain of a chiral sheet moves it far away."""
    motion = oblique_motion()
    path = tmp_path / "m.fold"
    write_fold(path, FoldFile(crease_pattern=motion.crease_pattern, folded=motion.folded))
    doc = json.loads(path.read_text())
    for frame in doc["file_frames"]:
        frame["edges_foldAngle"] = [-a for a in frame["edges_foldAngle"]]
    path.write_text(json.dumps(doc))
    frames = run_node("check_fold.mjs", str(path))["rabbit_ear"]["frames"]
    assert frames[0]["max_distance"] < 1e-9  # the flat state does not care
    assert min(f["max_distance"] for f in frames[1:]) > 0.1


@pytest.mark.node
def test_node_sheet_file(tmp_path):
    motion = oblique_motion()
    write_sheet_fold(tmp_path / "sheet.fold", motion.crease_pattern)
    report = run_node("check_fold.mjs", str(tmp_path / "sheet.fold"))
    assert report["fold"]["same_orientation"]
    assert report["rabbit_ear"]["summary"] == "valid"


# --- JSON text of the number arrays ----------------------------------------------------------


@pytest.mark.parametrize("decimals", [0, 1, 4, 10, 12, 15])
def test_number_arrays_are_written_as_json_writes_their_lists(decimals):
    """Rounded arrays of every scale and shape, zeros of both signs, exponents: the text
    json.dumps writes."""
    from curvefold.io._decimals import Decimals, array_json, dumps

    rng = np.random.default_rng(decimals)
    for shape in [(1,), (37,), (25, 3), (4, 5, 2)]:
        for scale in [1e-9, 1e-5, 1e-3, 0.7, 1.0, 3.0, 250.0, 1e6, 1e13, 1e17]:
            x = np.round(rng.normal(size=shape) * scale, decimals)
            x.reshape(-1)[:3] = [0.0, -0.0, 1.0][: x.size]
            assert array_json(x, decimals) == json.dumps(x.tolist(), separators=(",", ":"))
    # damaged: numbers not rounded to the places given are not the decimals of their rounding (repr
    # writes them)
    x = rng.normal(size=(50, 3))
    assert (
        array_json(x, 4)
        == json.dumps(x.tolist(), separators=(",", ":"))
        != json.dumps(np.round(x, 4).tolist(), separators=(",", ":"))
    )
    # a document with the arrays among other values, and one whose text holds the mark itself
    doc = {
        "a": Decimals.round(x, 6),
        "b": [{"c": Decimals.round(x[:, 0], 3), "s": "x"}],
        "n": [[1, 2]],
    }
    plain = {
        "a": np.round(x, 6).tolist(),
        "b": [{"c": np.round(x[:, 0], 3).tolist(), "s": "x"}],
        "n": [[1, 2]],
    }
    assert dumps(doc) == json.dumps(plain, separators=(",", ":"))
    marked = {"s": "\0curvefold:array\0", **doc}
    assert dumps(marked) == json.dumps({"s": "\0curvefold:array\0", **plain}, separators=(",", ":"))


def test_integer_arrays_are_written_as_json_writes_their_lists():
    """Integer arrays of every shape: the text json.dumps writes; booleans stay JSON's true and
    false."""
    from curvefold.io._decimals import Integers, dumps, integer_json

    rng = np.random.default_rng(0)
    for shape in [(1,), (37,), (25, 3), (4, 5, 2), (0, 3), (3, 0)]:
        for dtype in (np.int64, np.int32, np.uint8):
            x = rng.integers(0 if dtype == np.uint8 else -(10**6), 200, size=shape).astype(dtype)
            assert integer_json(x) == json.dumps(x.tolist(), separators=(",", ":"))
    flags = np.array([[True, False]])
    assert integer_json(flags) == "[[true,false]]"  # not formatted as numbers
    assert dumps({"e": Integers(np.array([[1, 2], [3, 4]])), "n": 1}) == '{"e":[[1,2],[3,4]],"n":1}'
