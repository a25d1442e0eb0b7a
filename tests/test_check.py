"""``curvefold check``: a FOLD file is checked in every frame, and real damage is caught by name.

Every damage edits a written file the way a tool or a hand might (JSON in, JSON out); the
test says which check must fail, and that the frame and the element ids are named.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from _cli import run
from curvefold.analysis._foldcheck import CHECK_SPECS, check_fold
from curvefold.app import default_design
from curvefold.app._build import build
from curvefold.io import FoldFile, FoldOutput, write_structure_fold

ANGLES = [0.0, 45.0, 90.0]


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    """A tube FOLD file with the flat, 45° and 90° frames and the design it was built from."""
    design = default_design("tube").overrides(samples=61)
    path = tmp_path_factory.mktemp("check") / "tube.fold"
    write_structure_fold(
        path,
        build(design).structure,
        fold_angles=ANGLES,
        output=FoldOutput(design=design.to_dict()),
    )
    return path, json.loads(path.read_text())


def damaged(tmp_path, doc: dict, edit) -> str:
    doc = json.loads(json.dumps(doc))
    edit(doc)
    path = tmp_path / "damaged.fold"
    path.write_text(json.dumps(doc))
    return str(path)


def verdict(path, **kw) -> dict[str, object]:
    return {c.name: c for c in check_fold(path, **kw).checks}


def failing(path, **kw) -> set[str]:
    return {name for name, c in verdict(path, **kw).items() if c.status == "fail"}


def sheet_b(doc: dict) -> np.ndarray:
    """The vertices of the tube's sheet B (strips 2 and 3: face groups 1 and 2)."""
    faces = [
        f for f, g in zip(doc["faces_vertices"], doc["faces_curvefold:group"]) if g % 4 in (1, 2)
    ]
    return np.unique(np.concatenate(faces))


def edit_frame(doc: dict, frame: int, change) -> None:
    x = np.array(doc["file_frames"][frame]["vertices_coords"])
    change(x)
    doc["file_frames"][frame]["vertices_coords"] = x.tolist()


def test_the_written_file_passes_every_check(written):
    path, _ = written
    result = check_fold(path)
    assert result.ok and result.frames == 3
    assert [c.name for c in result.checks] == [
        "topology",
        "welds",
        "edge_kinds",
        "assignments",
        "fold_angles",
        "isometry",
        "face_planarity",
        "record",
        "crease_angles",
    ]
    assert all(c.status == "pass" for c in result.checks)
    # the file records the dihedral angles it has, up to its coordinates' rounding (to 1e-12 of the
    # size, which turns a face of width h by about 1e-12 · size / h radians)
    assert result.max_fold_angle_error < 1e-8


def test_every_frame_records_the_dihedral_angle_of_every_edge(written):
    """Rulings and diagonals bend too (about κh each): their angles are recorded, B edges get 0."""
    _, doc = written
    kind, assignment = np.array(doc["edges_curvefold:kind"]), np.array(doc["edges_assignment"])
    bends = np.abs(np.array(doc["file_frames"][2]["edges_foldAngle"]))[
        np.isin(kind, ("ruling", "diagonal"))
    ]
    assert (
        1.0 < bends.max() < 10.0
        and (np.abs(np.array(doc["file_frames"][0]["edges_foldAngle"])) < 1e-9).all()
    )
    assert (np.array(doc["edges_foldAngle"])[assignment == "B"] == 0).all()
    assert (
        doc["curvefold:design"]["fold_angles"] == ANGLES
        and doc["curvefold:design"]["design"]["samples"] == 61
    )


def test_write_fold_refuses_bad_bonds_and_designs(tmp_path):
    from curvefold.kernel import InputError

    design = default_design("tube").overrides(samples=21)
    structure = build(design).structure
    with pytest.raises(InputError, match="design must be JSON data"):
        write_structure_fold(
            tmp_path / "x.fold", structure, output=FoldOutput(design={"when": object()})
        )
    from curvefold.io import to_fold, write_fold

    model = to_fold(structure)
    with pytest.raises(InputError, match=r"bonds must be edge indices in \[0, "):
        write_fold(
            tmp_path / "x.fold",
            FoldFile(crease_pattern=model.crease_pattern, folded=model.folded, bonds=[[0, 10**9]]),
        )
    assert not (tmp_path / "x.fold").exists()


# --------------------------------------------------------------------------------------------
# damages, each caught by a named check


def test_tube_torn_open_by_translating_sheet_b(tmp_path, written):
    path, doc = written

    def tear(doc):
        edit_frame(doc, 2, lambda x: x.__setitem__(sheet_b(doc), x[sheet_b(doc)] + [0.5, 0.0, 0.0]))

    result = verdict(damaged(tmp_path, doc, tear))
    # a rigid motion of a sheet keeps its shape
    assert {n for n, c in result.items() if c.status == "fail"} == {"welds"}
    assert result["welds"].where.startswith("frame 3 ('fold angle 90°'): edges seam partners")


def test_tube_torn_open_by_rotating_sheet_b(tmp_path, written):
    path, doc = written

    def turn(doc):
        c, s = np.cos(np.radians(40)), np.sin(np.radians(40))

        def rotate(x):
            b = sheet_b(doc)
            centre = x[b].mean(axis=0)
            x[b] = (x[b] - centre) @ np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]).T + centre

        edit_frame(doc, 1, rotate)

    assert failing(damaged(tmp_path, doc, turn)) == {"welds"}


def test_two_tubes_pulled_apart_break_their_bonds(tmp_path):
    """Tubes glued where they touch: moving the second tube whole keeps every seam closed and
    breaks only the bonds."""
    design = default_design("vault").overrides(samples=41, tubes=2)
    path = write_structure_fold(
        tmp_path / "vault.fold",
        build(design).structure,
        fold_angles=[90.0],
        output=FoldOutput(design=design.to_dict()),
    )
    doc = json.loads(path.read_text())
    assert len(doc["curvefold:bonds"]) == 40 and not failing(str(path))
    second = np.unique(
        np.concatenate(
            [f for f, g in zip(doc["faces_vertices"], doc["faces_curvefold:group"]) if g >= 4]
        )
    )
    result = verdict(
        damaged(
            tmp_path,
            doc,
            lambda d: edit_frame(
                d, 0, lambda x: x.__setitem__(second, x[second] + [0.0, 0.0, 0.1])
            ),
        )
    )
    assert {n for n, c in result.items() if c.status == "fail"} == {"welds"}
    assert result["welds"].where.startswith("frame 1 ('fold angle 90°'): edges bonds ")


def _folds(doc) -> np.ndarray:
    return np.flatnonzero(np.array(doc["edges_curvefold:kind"]) == "fold")


def test_one_mountain_flipped_to_valley(tmp_path, written):
    path, doc = written
    edge = int(_folds(doc)[7])
    result = verdict(damaged(tmp_path, doc, lambda d: d["edges_assignment"].__setitem__(edge, "V")))
    # the crease pattern records it as a mountain, and it folds as one
    assert result["assignments"].status == "fail"
    assert result["assignments"].where == (
        f"key frame (crease pattern): edges {edge}; M or V edges record a fold angle of the "
        "other sign (FOLD: a mountain's is negative, a valley's positive)"
    )


@pytest.mark.parametrize("to", ["V", "F"])
def test_every_mountain_reassigned(tmp_path, written, to):
    path, doc = written

    def reassign(d):
        for e in _folds(d):
            d["edges_assignment"][e] = to

    assert "assignments" in failing(damaged(tmp_path, doc, reassign))


def test_a_face_deleted_next_to_a_seam(tmp_path, written):
    path, doc = written
    seam = int(np.flatnonzero(np.array(doc["edges_curvefold:kind"]) == "seam")[5])
    a, b = doc["edges_vertices"][seam]
    face = next(i for i, f in enumerate(doc["faces_vertices"]) if a in f and b in f)

    def delete(d):
        del d["faces_vertices"][face], d["faces_curvefold:group"][face]

    result = verdict(damaged(tmp_path, doc, delete))
    assert result["topology"].status == "fail"
    assert result["topology"].where.startswith(
        f"key frame (crease pattern): edges on no face {seam}; M/V/F edges on one face "
    )


def test_the_90_degree_frame_replaced_by_the_crease_pattern(tmp_path, written):
    path, doc = written

    def flatten(d):
        d["file_frames"][2]["vertices_coords"] = [[x, y, 0.0] for x, y in d["vertices_coords"]]

    result = verdict(damaged(tmp_path, doc, flatten))
    assert {"fold_angles", "welds"} <= {n for n, c in result.items() if c.status == "fail"}
    assert result["fold_angles"].where.startswith("frame 3 ('fold angle 90°')")
    assert result["isometry"].status == "pass"  # the crease pattern is isometric to itself


def test_coordinates_edited_slightly_are_caught_by_rebuild(tmp_path, written):
    path, doc = written
    # on a fold crease: not glued to anything
    inner = int(doc["edges_vertices"][int(_folds(doc)[20])][0])

    def nudge(d):
        edit_frame(d, 2, lambda x: x.__setitem__((inner, 2), x[inner, 2] + 1e-7))

    edited = damaged(tmp_path, doc, nudge)
    assert not failing(edited)  # below every other check's tolerance
    r = run("check", edited, "--rebuild", "--json")
    out = json.loads(r.stdout)
    assert r.returncode == 1 and not out["ok"]
    (rebuild,) = [c for c in out["checks"] if c["name"] == "rebuild"]
    assert (
        rebuild["status"] == "fail"
        and rebuild["where"] == f"frame 3 ('fold angle 90°'): vertices {inner}"
    )
    assert 1e-9 < rebuild["value"] < 1e-6
    r = run("check", str(path), "--rebuild", "--json")
    assert r.returncode == 0 and json.loads(r.stdout)["ok"]


def test_a_face_turned_over(tmp_path, written):
    path, doc = written
    result = verdict(damaged(tmp_path, doc, lambda d: d["faces_vertices"][12].reverse()))
    assert (
        result["topology"].status == "fail"
        and "not consistently oriented" in result["topology"].where
    )


def test_a_vertex_collapsed_onto_its_neighbour_is_a_nan_that_fails(tmp_path, written):
    """A zero-length edge gives faces without a normal: NaN dihedral angles must fail, not vanish
    in a maximum."""
    path, doc = written
    a, b = doc["edges_vertices"][int(_folds(doc)[3])]
    result = verdict(
        damaged(tmp_path, doc, lambda d: edit_frame(d, 2, lambda x: x.__setitem__(a, x[b])))
    )
    assert (
        result["topology"].status == "fail" and "edges of zero length" in result["topology"].where
    )
    # the faces on the collapsed edge have no normal: named, and the others still measured
    fold_angles = result["fold_angles"]
    assert (
        fold_angles.status == "fail"
        and np.isfinite(fold_angles.value)
        and "not measurable (no length or no normal): edges" in fold_angles.where
    )


def test_a_vertex_moved_off_the_sheet(tmp_path, written):
    path, doc = written
    result = verdict(
        damaged(
            tmp_path,
            doc,
            lambda d: edit_frame(d, 1, lambda x: x.__setitem__((40, 2), x[40, 2] + 0.05)),
        )
    )
    assert {"isometry", "fold_angles"} <= {n for n, c in result.items() if c.status == "fail"}
    assert "frame 2 ('fold angle 45°'): edges" in result["isometry"].where


def test_recorded_angles_of_another_frame(tmp_path, written):
    path, doc = written
    result = verdict(
        damaged(
            tmp_path,
            doc,
            lambda d: d["file_frames"][1].update(
                edges_foldAngle=d["file_frames"][2]["edges_foldAngle"]
            ),
        )
    )
    assert {n for n, c in result.items() if c.status == "fail"} == {"fold_angles"}


def test_plain_fold_without_curvefold_keys_passes_what_can_run(tmp_path, written):
    """As another tool saves it: the custom keys dropped. Ruling bends are not taken for
    non-planar faces; what needs the custom keys says so."""
    path, doc = written

    def strip(d):
        for key in [k for k in d if "curvefold:" in k]:
            del d[key]

    result = check_fold(damaged(tmp_path, doc, strip))
    assert result.ok
    checks = {c.name: c for c in result.checks}
    assert {n for n, c in checks.items() if c.status == "not run"} == {
        "welds",
        "edge_kinds",
        "face_planarity",
        "record",
        "crease_angles",
    }
    assert (
        "curvefold:seam_partners" in checks["welds"].reason
        and "edges_curvefold:kind" in checks["face_planarity"].reason
    )
    assert result.to_dict()["not_run"] == [
        "welds",
        "edge_kinds",
        "face_planarity",
        "record",
        "crease_angles",
    ]


def test_plain_quad_file_measures_its_faces_not_its_ruling_bends(tmp_path):
    """Without the edge kinds every F edge reads as a diagonal; face planarity must look only at
    the fan diagonals that split each quad, and still catch a bent quad."""
    design = default_design("tube").overrides(samples=61)
    path = write_structure_fold(
        tmp_path / "quads.fold",
        build(design).structure,
        fold_angles=ANGLES,
        output=FoldOutput(faces="quads"),
    )
    doc = json.loads(path.read_text())
    for key in [k for k in doc if "curvefold:" in k]:
        del doc[key]
    planarity = verdict(damaged(tmp_path, doc, lambda d: None))["face_planarity"]
    # quads bend by O(h³); rulings by ~κh ≈ 5°
    assert planarity.status == "pass" and 0 < planarity.value < 0.05
    face = doc["faces_vertices"][50]

    def bend(d):
        def lift(x):
            p = x[face]
            normal = np.cross(p[1] - p[0], p[3] - p[0])
            x[face[2]] += 0.05 * np.linalg.norm(p[2] - p[0]) * normal / np.linalg.norm(normal)

        edit_frame(d, 2, lift)

    planarity = verdict(damaged(tmp_path, doc, bend))["face_planarity"]
    assert (
        planarity.status == "fail"
        and planarity.value > 2
        and planarity.where.startswith("frame 3 ('fold angle 90°'): fan diagonals")
    )


def test_a_frame_with_its_own_faces_is_not_compared_edge_by_edge(tmp_path, written):
    path, doc = written

    def own_faces(d):
        for key in [k for k in d if "curvefold:" in k]:
            del d[key]
        d["file_frames"][1]["faces_vertices"] = d["faces_vertices"][::-1]

    result = check_fold(damaged(tmp_path, doc, own_faces))
    checks = {c.name: c for c in result.checks}
    assert (
        not result.ok
        and checks["topology"].where
        == "frame 2 ('fold angle 45°') has other edges or faces than the crease pattern"
    )
    assert {c.status for name, c in checks.items() if name != "topology"} == {"not run"}


# --------------------------------------------------------------------------------------------
# the command


def test_check_json_keeps_its_stable_keys(written):
    path, _ = written
    r = run("check", str(path), "--json")
    out = json.loads(r.stdout)
    assert r.returncode == 0
    assert {"max_isometry_error", "max_face_planarity_error", "ok"} <= set(out) and out[
        "ok"
    ] is True
    assert out["tolerances"] == {spec.name: spec.default for spec in CHECK_SPECS}


def test_check_names_the_failure_in_its_summary(tmp_path, written):
    path, doc = written
    edge = int(_folds(doc)[7])
    r = run("check", damaged(tmp_path, doc, lambda d: d["edges_assignment"].__setitem__(edge, "V")))
    assert r.returncode == 1
    assert (
        "FAILED" in r.stdout and "assignments     fail" in r.stdout and f"edges {edge}" in r.stdout
    )


@pytest.mark.parametrize(
    "flag,value,message",
    [
        ("--isometry-tol", "nan", "isometry_tol must be a finite number, got nan"),
        ("--fold-angle-tol", "-1", "fold_angle_tol must be in [0, 180] degrees, got -1"),
        ("--weld-tol", "x", "--weld-tol: must be a number, got 'x'"),
    ],
)
def test_check_refuses_bad_tolerances(written, flag, value, message):
    path, _ = written
    r = run("check", str(path), flag, value)
    assert (
        r.returncode == 2
        and r.stdout == ""
        and message in r.stderr
        and len(r.stderr.strip().splitlines()) == 1
    )


def test_rebuild_needs_a_recorded_design(tmp_path, written):
    path, doc = written
    r = run("check", damaged(tmp_path, doc, lambda d: d.pop("curvefold:design")), "--rebuild")
    assert (
        r.returncode == 2
        and "--rebuild needs the design the file was built from (curvefold:design)" in r.stderr
    )


# --------------------------------------------------------------------------------------------
# the damage catalogue: edits that passed before, each failing a named check or refused


def _ruling_folding_as_mountain(doc) -> int:
    """A ruling whose small bend is a mountain in every frame and in the crease pattern."""
    kind = np.array(doc["edges_curvefold:kind"])
    angles = np.array(
        [doc["edges_foldAngle"]] + [f["edges_foldAngle"] for f in doc["file_frames"][1:]]
    )
    return int(np.flatnonzero((kind == "ruling") & (angles < -0.05).all(axis=0))[0])


def _relabel_ruling(d):
    d["edges_assignment"][_ruling_folding_as_mountain(d)] = "M"


def _negate_key_angles(d):
    d["edges_foldAngle"] = [-a for a in d["edges_foldAngle"]]


def _key_frame_folded(d):
    d["frame_classes"] = ["foldedForm"]


def _distort(d):
    """Every folded frame stretched 1.5×, and one vertex of the crease pattern collapsed onto its
    neighbour."""
    for f in d["file_frames"]:
        f["vertices_coords"] = (1.5 * np.array(f["vertices_coords"])).tolist()
    a, b = d["edges_vertices"][int(_folds(d)[3])]
    d["vertices_coords"][a] = d["vertices_coords"][b]


def _one_vertex_more(d):
    d["file_frames"][2]["vertices_coords"].append([0.0, 0.0, 0.0])


def _group_changed(d):
    d["faces_curvefold:group"][0] += 1


def _ruling_angle_changed(d):
    e = _ruling_folding_as_mountain(d)
    # 1e-4 of a small bend: below the recorded-angle tolerance
    d["file_frames"][2]["edges_foldAngle"][e] *= 1.0001


#: name -> (edit of the document, the checks that must fail, with --rebuild or not).
FILE_DAMAGES = {
    "a near-flat ruling relabelled M": (_relabel_ruling, {"edge_kinds"}, False),
    "a near-flat ruling relabelled M, rebuilt": (_relabel_ruling, {"edge_kinds", "rebuild"}, True),
    "the crease pattern's fold angles negated": (_negate_key_angles, {"assignments"}, False),
    "the crease pattern relabelled a folded form": (_key_frame_folded, {"fold_angles"}, False),
    "the crease pattern relabelled a folded form, rebuilt": (
        _key_frame_folded,
        {"fold_angles", "rebuild"},
        True,
    ),
    "a frame with one vertex more": (_one_vertex_more, {"topology"}, False),
    "distorted 1.5x with a degenerate edge": (_distort, {"isometry", "topology"}, False),
    "a face moved to another strip, rebuilt": (_group_changed, {"rebuild"}, True),
    "a ruling's recorded angle changed by 1e-4 of itself, rebuilt": (
        _ruling_angle_changed,
        {"rebuild"},
        True,
    ),
}


@pytest.mark.parametrize("name", list(FILE_DAMAGES))
def test_damage_catalogue_each_fails_a_named_check(tmp_path, written, name):
    _, doc = written
    edit, expect, rebuild = FILE_DAMAGES[name]
    path = damaged(tmp_path, doc, edit)
    r = run("check", path, "--json", *(["--rebuild"] if rebuild else []))
    out = json.loads(r.stdout)
    failed = {c["name"] for c in out["checks"] if c["status"] == "fail"}
    assert r.returncode == 1 and expect <= failed, (failed, r.stderr)


def test_the_headline_numbers_are_measured_over_what_can_be_measured(tmp_path, written):
    """One degenerate edge made max_isometry_error null for a file distorted by 1.5×."""
    _, doc = written
    out = json.loads(run("check", damaged(tmp_path, doc, _distort), "--json").stdout)
    assert np.isfinite(out["max_isometry_error"]) and out["max_isometry_error"] >= 0.5
    (isometry,) = [c for c in out["checks"] if c["name"] == "isometry"]
    assert "not measurable (no length or no normal): edges" in isometry["where"]


def test_kinds_and_rebuilt_arrays_name_what_differs(tmp_path, written):
    _, doc = written
    e = _ruling_folding_as_mountain(doc)
    out = json.loads(
        run("check", damaged(tmp_path, doc, _relabel_ruling), "--json", "--rebuild").stdout
    )
    by_name = {c["name"]: c for c in out["checks"]}
    assert by_name["edge_kinds"]["where"].startswith(
        f"key frame (crease pattern): edges {e} (ruling) assigned M"
    )
    assert (
        f"key frame (crease pattern): edges_assignment at rows {e}" in by_name["rebuild"]["where"]
    )
    out = json.loads(
        run("check", damaged(tmp_path, doc, _key_frame_folded), "--json", "--rebuild").stdout
    )
    by_name = {c["name"]: c for c in out["checks"]}
    assert (
        "frame_classes [['foldedForm'], ['foldedForm'], ['foldedForm'], ['foldedForm']]"
        in by_name["rebuild"]["where"]
    )
    # the file no longer says which frame is its crease pattern
    assert by_name["isometry"]["status"] == "not run"


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (
            lambda text: text.replace('"vertices_coords":[[', '"vertices_coords":[["0.5",', 1),
            r"vertices_coords\[0\] " r"must hold numbers only, got \['0.5'",
        ),
        (
            lambda text: text.replace('"frame_unit":', '"frame_unit":"mm","frame_unit":', 1),
            r"the key " r"'frame_unit' appears twice in one object",
        ),
        (
            lambda text: text.replace('"vertices_coords":[[', '"vertices_coords":[[1e308,', 1),
            r"vertices_coords\[0\] " r"= \[1e\+308, .* must lie within ±1e\+100",
        ),
        (
            lambda text: text.replace('"vertices_coords":[[', '"vertices_coords":[[NaN,', 1),
            r"not a FOLD file: " r"NaN is not a JSON number",
        ),
        (
            lambda text: _scaled(text, 1e-310),
            r"the model is .* across; curvefold reads models at " r"least 1e-100 across",
        ),
    ],
)
def test_malformed_numbers_and_keys_are_refused_in_one_line(tmp_path, written, edit, message):
    path, _ = written
    bad = tmp_path / "bad.fold"
    bad.write_text(edit(path.read_text()))
    for command in ("check", "mechanism"):
        r = run(command, str(bad))
        assert (
            r.returncode == 2
            and len(r.stderr.strip().splitlines()) == 1
            and "internal error" not in r.stderr
        ), r.stderr
        assert re.search(message, r.stderr), r.stderr


def _scaled(text: str, factor: float) -> str:
    doc = json.loads(text)
    for frame in [doc, *doc["file_frames"]]:
        frame["vertices_coords"] = (factor * np.array(frame["vertices_coords"])).tolist()
    return json.dumps(doc)


def test_rebuild_is_estimated_before_it_is_built(tmp_path, written, monkeypatch):
    """A 66 KB file recording a vault of 200,000 samples grew to 4.6 GB when rebuilt; 100,000
    recorded fold angles took 81 s. The rebuild is estimated like any design, and a record of
    other frames is not built."""
    _, doc = written

    def huge(d):
        d["curvefold:design"]["design"] = {"kind": "vault", "samples": 200000}

    r = run("check", damaged(tmp_path, doc, huge), "--rebuild")
    assert (
        r.returncode == 2
        and "rebuilding this design needs about" in r.stderr
        and "more than the budget of 2.0 GiB" in r.stderr
    )

    def many(d):
        d["curvefold:design"]["fold_angles"] = [90.0] * 100_000

    r = run("check", damaged(tmp_path, doc, many), "--rebuild", "--json")
    (rebuild,) = [c for c in json.loads(r.stdout)["checks"] if c["name"] == "rebuild"]
    assert (
        r.returncode == 1
        and "records 100000 fold angles, the file holds 3 frames" in rebuild["where"]
    )
    # the tube itself, with its three frames, needs more
    monkeypatch.setenv("CURVEFOLD_MEMORY_BUDGET", "60M")
    r = run("check", damaged(tmp_path, doc, lambda d: None), "--rebuild")
    assert r.returncode == 2 and "more than the budget of 60 MiB" in r.stderr


def test_a_changed_design_under_rebuild_is_a_failed_check_with_the_reason(tmp_path):
    """It was exit 2 with the internal "keep must list the samples": the record's samples kept
    are not the changed design's."""
    out = tmp_path / "tube"
    assert run("tube", "--samples", "201", "--formats", "fold", "--out", str(out)).returncode == 0
    doc = json.loads((out / "tube.fold").read_text())
    doc["curvefold:design"]["design"]["samples"] = 101
    path = damaged(tmp_path, doc, lambda d: None)
    result = run("check", path, "--rebuild", "--json")
    assert result.returncode == 1, result.stderr
    rebuild = {c["name"]: c for c in json.loads(result.stdout)["checks"]}["rebuild"]
    assert rebuild["status"] == "fail"
    assert "the recorded design does not build this file" in rebuild["where"]
