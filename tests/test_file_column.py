"""The certificate's file column: the checks measured on the FOLD file that ships.

The certificate's model column measures the internal model at the design's samples; the file
column measures the FOLD file as written and read back, against the tolerances the file promises
(its recorded mesh tolerance and written precision), and ``curvefold check`` on that file gives
the same numbers.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from _cli import run
from curvefold.analysis._foldcheck import check_fold
from curvefold.analysis._promises import promised_tolerances, written_precision
from curvefold.app import default_design
from curvefold.app._build import build
from curvefold.app._folder import check_output
from curvefold.app._outputs import write_outputs
from curvefold.io import read_fold

#: A tube thinned by the file's sampling (801 computed samples, 161 written per crease).
TUBE = ("tube", "--formats", "fold", "--samples", "401")


@pytest.fixture(scope="module")
def shipped(tmp_path_factory):
    """A tube's output folder, its report.json and its summary."""
    out = tmp_path_factory.mktemp("shipped") / "tube"
    result = run(*TUBE, "--out", str(out))
    assert result.returncode == 0, result.stdout + result.stderr
    return out, json.loads((out / "report.json").read_text()), result.stdout


def test_check_on_the_shipped_file_reproduces_the_file_column(shipped):
    out, report, _ = shipped
    checked = run("check", str(out / "tube.fold"), "--json")
    assert checked.returncode == 0
    assert report["certificate_file"] == {"file": "tube.fold"} | json.loads(checked.stdout)


def test_report_and_summary_say_which_column_is_which(shipped):
    _, report, summary = shipped
    assert set(report["certificate_columns"]) == {"model", "file"}
    assert "FOLD file as written" in report["certificate_columns"]["file"]
    assert "internal model" in report["certificate_columns"]["model"]
    assert "shipped file" in summary and "the file column" in summary
    assert "the line above: the model" in summary
    html = (shipped[0] / "report.html").read_text()
    assert "The file column: tube.fold as written" in html


def test_the_file_column_measures_the_thinned_mesh_not_the_model(shipped):
    """The file's isometry error is the thinned mesh's, which the model column does not see."""
    _, report, _ = shipped
    model = {c["name"]: c for c in report["certificate"]}["isometry"]["value"]
    file = {c["name"]: c for c in report["certificate_file"]["checks"]}["isometry"]
    meta = read_fold(shipped[0] / "tube.fold").metadata
    assert meta["mesh_samples_per_crease"] != str(meta["samples_computed"])  # thinned
    assert file["value"] > 5 * model  # the written mesh, far coarser
    assert file["value"] == pytest.approx(meta["mesh_stretch"], rel=1e-6)
    assert file["tolerance"] == pytest.approx(meta["mesh_tolerance"], rel=1e-3)


def test_the_tolerances_are_what_the_file_promises(shipped):
    out, report, _ = shipped
    doc = read_fold(out / "tube.fold")
    tolerances, sources = promised_tolerances(doc)
    assert (
        report["certificate_file"]["tolerances"] | tolerances
        == report["certificate_file"]["tolerances"]
    )
    assert set(sources) == set(tolerances) == set(report["certificate_file"]["tolerance_sources"])
    # coordinates are written to 1e-12 of the size: half that unit is the precision
    size = float(np.ptp(doc.folded[-1][1].vertices_coords, axis=0).max())
    assert written_precision(doc.folded[-1][1].vertices_coords) == 0.5 * 10.0 ** math.floor(
        math.log10(1e-12 * size)
    )
    # far tighter than the defaults a foreign file is held to
    assert tolerances["isometry_tol"] < 1e-3 and tolerances["fold_angle_tol"] < 1e-6


def test_a_file_without_the_promise_keeps_the_defaults(shipped, tmp_path):
    out, _, _ = shipped
    doc = json.loads((out / "tube.fold").read_text())
    del doc["curvefold:metadata"]["mesh_tolerance"]
    path = tmp_path / "plain.fold"
    path.write_text(json.dumps(doc))
    result = check_fold(path)
    assert result.tolerances["isometry_tol"] == 1e-3 and not result.sources


def test_a_stretch_the_old_tolerance_let_through_fails_the_file(shipped, tmp_path):
    """A frame scaled by 1.0005 changes every length by 5e-4: under the default 1e-3, five times
    what the file promises."""
    out, _, _ = shipped
    doc = json.loads((out / "tube.fold").read_text())
    frame = doc["file_frames"][-1]
    frame["vertices_coords"] = (np.array(frame["vertices_coords"]) * 1.0005).tolist()
    path = tmp_path / "scaled.fold"
    path.write_text(json.dumps(doc))
    old = {c.name: c for c in check_fold(path, isometry_tol=1e-3).checks}["isometry"]
    assert old.status == "pass"  # the old tolerance
    isometry = {c.name: c for c in check_fold(path).checks}["isometry"]
    assert isometry.status == "fail" and "fold angle 90" in isometry.where


def test_the_growth_of_the_stretch_with_the_fold_angle_is_measured(tmp_path):
    """The isometry tolerance scales the mesh tolerance by tan²α / tan²α_d: the stretch of the
    written mesh, measured in every frame, grows so."""
    out = tmp_path / "tube"
    assert run(*TUBE, "--fold-angle", "60", "--out", str(out)).returncode == 0
    doc = read_fold(out / "tube.fold")
    flat = doc.crease_pattern.edge_lengths()
    stretch = {
        title: float(np.abs(mesh.edge_lengths() / flat - 1).max()) for title, mesh in doc.folded
    }
    design = math.tan(math.radians(30)) ** 2
    for title, value in stretch.items():
        angle = float(title.split()[-1].rstrip("°"))
        if angle >= 60:
            predicted = doc.metadata["mesh_stretch"] * math.tan(math.radians(angle / 2)) ** 2
            assert value == pytest.approx(predicted / design, rel=0.05), title
    assert check_fold(out / "tube.fold").ok


def test_a_file_damaged_as_written_fails_the_certificate(tmp_path, monkeypatch):
    """The writer damages one frame (a vertex moved by 1e-3 of the size): the model column
    passes, the file column fails, and so does the command."""
    from curvefold.io import _fold

    real = _fold._coordinate_lists
    calls = []

    def damaging(x):
        calls.append(1)
        x = np.array(x, float)
        if len(calls) == 4 and x.shape[1] == 3:  # a folded frame
            x[len(x) // 2] += 1e-3 * float(np.ptp(x, axis=0).max())
        return real(x)

    monkeypatch.setattr(_fold, "_coordinate_lists", damaging)
    design = default_design("tube").overrides(samples=201, formats=["fold"])
    built = build(design)
    target = check_output(tmp_path / "tube", force=False, inputs=[])
    payload = write_outputs(built, target, show_progress=False, workers=1)
    assert all(c["status"] != "fail" for c in payload["certificate"])  # the model
    shipped = payload["certificate_file"]
    assert not shipped["ok"]
    failed = {c["name"] for c in shipped["checks"] if c["status"] == "fail"}
    assert "isometry" in failed
    report = json.loads((tmp_path / "tube" / "report.json").read_text())
    assert report["certificate_file"] == shipped


def test_the_file_column_measures_the_crease_angles_against_2_alpha(shipped, tmp_path):
    """The certificate's fold_angles on the file: every fold crease against its frame's 2α."""
    out, report, _ = shipped
    model = {c["name"]: c for c in report["certificate"]}["fold_angles"]["value"]
    file = {c["name"]: c for c in report["certificate_file"]["checks"]}["crease_angles"]
    assert file["status"] == "pass" and file["value"] > model  # the coarser mesh's
    doc = json.loads((out / "tube.fold").read_text())
    doc["curvefold:design"]["fold_angles"][-1] += 2.0  # the last frame claims 92°
    path = tmp_path / "claimed.fold"
    path.write_text(json.dumps(doc))
    crease = {c.name: c for c in check_fold(path).checks}["crease_angles"]
    assert crease.status == "fail" and "fold angle 90" in crease.where
