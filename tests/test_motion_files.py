"""The files of the motion: sheets that fold onto the design, a single curved fold written like the
other kinds.

Before, the sheet files set every F angle to 0 while a sampled curved sheet bends across its
rulings; ``curvefold crease`` wrote only its report and one picture; ``crease --alpha 30`` was
refused because the default of beta_right was carried as if it had been given.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from _cli import run
from _node import run_node
from curvefold.analysis import check_fold
from curvefold.app import default_design
from curvefold.app._build import build
from curvefold.geometry._sheets import sheet_vertices, sheets
from curvefold.io import read_fold, write_sheet_fold


def _sheet_with_its_design_state(tmp_path, structure, index: int, *, flat_rulings: bool) -> str:
    """Sheet ``index`` as its file holds it, with the design state's coordinates as a folded
    frame (to fold onto)."""
    sheet = sheets(structure)[index]
    path = write_sheet_fold(tmp_path / f"sheet{index}.fold", sheet.mesh)
    doc = json.loads(path.read_text())
    if flat_rulings:  # as the files were: every F edge at 0
        doc["edges_foldAngle"] = [
            0.0 if a == "F" else v for a, v in zip(doc["edges_assignment"], doc["edges_foldAngle"])
        ]
    design = structure.state().mesh().vertices_coords[sheet_vertices(structure)[index]]
    doc["file_frames"] = [
        {
            "frame_title": "design",
            "frame_classes": ["foldedForm"],
            "frame_parent": 0,
            "frame_inherit": True,
            "vertices_coords": design.tolist(),
        }
    ]
    path.write_text(json.dumps(doc))
    return str(path)


def test_the_sheet_files_carry_the_bends_of_their_rulings(tmp_path):
    structure = build(default_design("tube").overrides(samples=61)).structure
    sheet = sheets(structure)[0]
    f = np.isin(sheet.mesh.edges_kind, ("ruling", "diagonal"))
    # a sampled curved sheet bends by about κh
    assert 0.5 < np.abs(sheet.mesh.edges_foldAngle[f]).max() < 10
    doc = json.loads(write_sheet_fold(tmp_path / "s.fold", sheet.mesh).read_text())
    angles = np.array(doc["edges_foldAngle"])[np.array(doc["edges_assignment"]) == "F"]
    assert np.abs(angles).max() > 0.5  # were all 0


@pytest.mark.node
def test_a_folder_following_the_sheets_angles_lands_on_the_design(tmp_path):
    """Rabbit Ear folds each sheet by its file's angles: onto the design state within the chords'
    error with the rulings' bends, far from it with them at 0 (as the sheet files had them)."""
    structure = build(default_design("tube").overrides(samples=61)).structure
    size = float(np.ptp(structure.state().vertices.reshape(-1, 3), axis=0).max())
    for index in range(2):
        true = run_node(
            "check_fold.mjs",
            _sheet_with_its_design_state(tmp_path, structure, index, flat_rulings=False),
        )
        flat = run_node(
            "check_fold.mjs",
            _sheet_with_its_design_state(tmp_path, structure, index, flat_rulings=True),
        )
        (landed,), (missed,) = true["rabbit_ear"]["frames"], flat["rabbit_ear"]["frames"]
        assert landed["max_distance"] < 1e-3 * size < 0.05 * size < missed["max_distance"], (
            landed,
            missed,
            size,
        )


@pytest.fixture(scope="module")
def crease_folder(tmp_path_factory):
    out = tmp_path_factory.mktemp("crease") / "out"
    r = run("crease", "--samples", "201", "--out", str(out))
    assert r.returncode == 0, r.stderr
    return out


def test_a_single_fold_writes_its_pattern_fold_file_and_models(crease_folder):
    names = {p.name for p in crease_folder.iterdir()}
    assert {
        "crease-pattern.svg",
        "crease-pattern.dxf",
        "crease-pattern.pdf",
        "crease.fold",
        "crease.glb",
        "crease.obj",
        "crease.stl",
        "crease.ply",
        "crease.3dm",
        "sheets",
        "report.json",
        "report.html",
    } <= names
    report = json.loads((crease_folder / "report.json").read_text())
    assert report["certificate_frames"]["fold_angles"] == [10, 20, 30, 40, 50, 60]
    assert all(c["passed"] for c in report["certificate"]) and {
        c["frames"] for c in report["certificate"]
    } == {6}
    svg = (crease_folder / "crease-pattern.svg").read_text()
    # the crease, the scale bar
    assert (
        "<polyline" in svg.split('id="layer-valley"')[1].split("</g>")[0]
        and "10 mm: print at 100 %" in svg
    )


def test_the_single_folds_fold_file_holds_its_motion_and_passes_check(crease_folder):
    doc = read_fold(crease_folder / "crease.fold")
    assert [t for t, _ in doc.folded] == [f"fold angle {a}°" for a in (0, 10, 20, 30, 40, 50, 60)]
    result = check_fold(doc)
    assert result.ok and result.max_isometry_error < 1e-6, [
        (c.name, c.where) for c in result.checks if c.status == "fail"
    ]
    rebuilt = run("check", str(crease_folder / "crease.fold"), "--rebuild", "--json")
    assert rebuilt.returncode == 0 and json.loads(rebuilt.stdout)["ok"]
    sheet = check_fold(crease_folder / "sheets" / "single-fold.fold")
    assert sheet.ok and sheet.frames == 0


def test_the_single_folds_models_hold_its_design_state(crease_folder):
    obj = (crease_folder / "crease.obj").read_text().splitlines()
    assert (
        sum(line.startswith("v ") for line in obj) == 3 * 201
        and sum(line.startswith("f ") for line in obj) == 2 * 200
    )
    pytest.importorskip("trimesh")
    import trimesh

    mesh = trimesh.load(crease_folder / "crease.stl")
    assert len(mesh.faces) == 4 * 200


def test_the_strips_widths_of_a_single_fold_are_its_design_and_checked(tmp_path):
    r = run(
        "crease",
        "--samples",
        "101",
        "--width-left",
        "0.2",
        "--width-right",
        "0.1",
        "--formats",
        "fold",
        "--out",
        str(tmp_path / "w"),
    )
    assert r.returncode == 0, r.stderr
    meta = json.loads((tmp_path / "w" / "crease.fold").read_text())["curvefold:metadata"]
    assert (meta["width_left"], meta["width_right"]) == (0.2, 0.1)
    r = run("crease", "--samples", "101", "--width-left", "-1", "--json")
    assert r.returncode == 2 and "width_left must be > 0" in r.stderr


def test_crease_alpha_alone_is_accepted_and_replaces_beta_right():
    """The default of beta_right was carried as if given: "give beta_right or alpha, not both"."""
    r = run("crease", "--alpha", "30", "--samples", "101", "--json")
    assert r.returncode == 0, r.stderr
    design = json.loads(r.stdout)["design"]["crease"]
    assert design["alpha"] == 30 and "beta_right" not in design and design["fold_angle"] == 60
    r = run("crease", "--alpha", "30", "--beta-right", "80", "--json")
    assert r.returncode == 2 and "give beta_right or alpha, not both" in r.stderr
    from curvefold.app.designer.api import request_design

    # /api/crease?alpha=30 answered 422
    assert request_design("crease", [("alpha", "30")]).crease.alpha == 30
    alpha = default_design("crease").overrides(alpha=25.0)
    assert alpha.overrides(beta_right=70.0).crease.alpha is None  # and back
