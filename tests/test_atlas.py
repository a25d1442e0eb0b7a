"""The design atlas: invalid designs recorded, grid order, files, agreement with Vault, parallel runs."""

import csv
import json
import math

import numpy as np
import pytest
from numpy.testing import assert_array_equal

from curvefold import InputError
from curvefold.vault import Vault, VaultDesign
from curvefold.vault import atlas as atlas_module
from curvefold.vault.arch import A_MAX
from curvefold.vault.atlas import FIELDS, METRICS, Atlas, run_atlas

pytest.importorskip("matplotlib")

# Rows a = 0.3, 0.8 and 1.3 ≥ A_MAX (no standing arch); at a = 0.8 the proportion
# p_xy = 4 with width 0.08 puts the base tube past regression.
P_XY = [0.75, 1.5, 4.0]
A_VALUES = [0.3, 0.8, 1.3]
KW = dict(width=0.08, samples=61)


def _run(workers: int) -> tuple[Atlas, list]:
    calls: list = []
    result = run_atlas(P_XY, A_VALUES, workers=workers, progress=lambda done, total: calls.append((done, total)), **KW)
    return result, calls


@pytest.fixture(scope="module")
def serial_run() -> tuple[Atlas, list]:
    return _run(1)


@pytest.fixture(scope="module")
def parallel_run() -> tuple[Atlas, list]:
    return _run(2)


@pytest.fixture(scope="module")
def serial(serial_run) -> Atlas:
    return serial_run[0]


@pytest.fixture(scope="module")
def parallel(parallel_run) -> Atlas:
    return parallel_run[0]


def test_grid_order_and_keys(serial):
    assert serial.shape == (3, 3)
    assert serial.p_xy_values == tuple(P_XY) and serial.a_values == tuple(A_VALUES)
    assert len(serial.records) == len(serial.sketches) == 9
    for k, r in enumerate(serial.records):
        assert tuple(r) == FIELDS
        assert (r["row"], r["col"]) == divmod(k, 3)
        assert (r["a"], r["p_xy"]) == (A_VALUES[r["row"]], P_XY[r["col"]])
        assert serial.record(r["row"], r["col"]) is r
    with pytest.raises(InputError, match=r"\(row, col\) must be in"):
        serial.record(3, 0)


def test_invalid_designs_are_recorded_and_the_grid_goes_on(serial):
    assert 1.3 > A_MAX
    for col in range(3):
        r = serial.record(2, col)
        assert r["valid"] is False and r["error"] == "ConvergenceError"
        assert "no standing arch for a = 1.3" in r["reason"]
    r = serial.record(1, 2)
    assert r["valid"] is False and r["error"] == "RegressionError"
    assert "past regression" in r["reason"] and "width = 0.08" in r["reason"]
    invalid = [(1, 2), (2, 0), (2, 1), (2, 2)]
    for row in range(3):
        for col in range(3):
            r, sketch = serial.record(row, col), serial.sketches[row * 3 + col]
            if (row, col) in invalid:
                assert sketch is None and all(r[m] is None for m in METRICS)
            else:
                assert r["valid"] is True and r["error"] is None and r["reason"] is None
                assert sketch is not None and all(isinstance(r[m], (int, float)) for m in METRICS)
    # the design after the regressing one (in grid order) was still built
    assert serial.record(1, 1)["valid"]


def test_input_errors_of_a_grid_value_are_recorded():
    result = run_atlas([-1.0, 0.75], [0.3], workers=1, **KW)
    bad, good = result.records
    assert bad["valid"] is False and bad["error"] == "InputError" and "p_xy must be in" in bad["reason"]
    assert good["valid"] is True


def test_valid_records_agree_with_vault_summary(serial):
    for r in serial.records:
        if not r["valid"]:
            continue
        summary = Vault.from_design(VaultDesign(a=r["a"], p_xy=r["p_xy"], **KW)).summary()
        expected = {k: summary[k] for k in METRICS if k in summary}
        expected["footprint_x"], expected["footprint_y"] = summary["footprint"]
        assert {k: r[k] for k in METRICS} == pytest.approx(expected, rel=1e-12, abs=1e-15)
        assert isinstance(r["tubes"], int) and r["tubes"] == summary["design"]["tubes"]


def test_sketch_is_small_and_matches_the_vault(serial):
    r = serial.record(0, 0)
    sketch = serial.sketches[0]
    vault = Vault.from_design(VaultDesign(a=r["a"], p_xy=r["p_xy"], **KW))
    assert sketch.curves.dtype == np.float32 and sketch.curves.shape[1] <= 25
    assert sketch.curves.nbytes < 100_000
    assert sketch.cells.shape == (r["tubes"], 4)
    assert not sketch.curves.flags.writeable
    # the feature lines: corners (j, j) at the feet and at the apex; their slopes are the record's
    d0, dm = sketch.feet[1] - sketch.feet[0], sketch.apex[1] - sketch.apex[0]
    assert abs(sketch.feet[:, 2]).max() < 1e-9  # on the ground
    slope_xy = (math.degrees(math.atan2(d0[1], d0[0])) + 90) % 180 - 90
    slope_zx = (math.degrees(math.atan2(dm[2], dm[0])) + 90) % 180 - 90
    assert slope_xy == pytest.approx(r["slope_xy_deg"], abs=1e-9)
    assert slope_zx == pytest.approx(r["slope_zx_deg"], abs=1e-9)
    # the sketch samples are samples of the vault (feet, apex and far feet included)
    assert_array_equal(sketch.curves[0, [0, -1]], vault.vertices[0, [0, -1]].astype(np.float32))


def test_serial_and_parallel_records_are_identical(serial, parallel):
    assert parallel.records == serial.records
    for a, b in zip(serial.sketches, parallel.sketches):
        assert (a is None) == (b is None)
        if a is not None:
            assert_array_equal(a.curves, b.curves)
            assert_array_equal(a.cells, b.cells)
            assert a.kinds == b.kinds


@pytest.mark.parametrize("which", ["serial_run", "parallel_run"])
def test_progress_reports_every_design(which, request):
    calls = request.getfixturevalue(which)[1]
    assert calls[0] == (0, 9) and calls[-1] == (9, 9)
    assert [d for d, _ in calls] == list(range(10))
    assert {t for _, t in calls} == {9}


def test_grid_of_a_metric(serial):
    g = serial.grid("slope_xy_deg")
    assert g.shape == (3, 3)
    assert np.isnan(g[2]).all() and np.isnan(g[1, 2])
    assert g[0, 0] == serial.record(0, 0)["slope_xy_deg"]
    assert serial.grid("valid").tolist()[2] == [0.0, 0.0, 0.0]
    with pytest.raises(InputError, match="numeric field"):
        serial.grid("reason")


def test_csv_round_trip(serial, tmp_path):
    path = serial.to_csv(tmp_path / "atlas.csv")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["atlas.csv"]  # no temporary file left
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 9 and tuple(rows[0]) == FIELDS
    for row, rec in zip(rows, serial.records):
        for key in FIELDS:
            value, cell = rec[key], row[key]
            if value is None:
                assert cell == ""
            elif isinstance(value, bool):
                assert cell == str(value)
            elif isinstance(value, int):
                assert int(cell) == value
            elif isinstance(value, float):
                assert float(cell) == value  # exactly: floats are written with repr
            else:
                assert cell == value


def test_json_round_trip(serial, tmp_path):
    path = serial.to_json(tmp_path / "atlas.json")
    doc = json.loads(path.read_text(encoding="utf-8"))
    assert doc["format"] == "curvefold-atlas" and doc["fields"] == list(FIELDS)
    assert doc["p_xy_values"] == P_XY and doc["a_values"] == A_VALUES
    assert (doc["width"], doc["samples"], doc["tubes"]) == (0.08, 61, None)
    assert doc["records"] == list(serial.records)


def test_files_are_replaced_atomically(serial, tmp_path):
    target = tmp_path / "atlas.json"
    target.write_text("old")
    serial.to_json(target)
    assert json.loads(target.read_text())["format"] == "curvefold-atlas"
    serial.to_csv(tmp_path / "atlas.csv")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["atlas.csv", "atlas.json"]


def test_figure_renders(serial, tmp_path):
    from PIL import Image

    from curvefold.figures.atlas import atlas_figure
    from curvefold.figures.plots import save_figure

    fig = atlas_figure(serial, cell_size=1.2)
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert any(t.startswith("no arch") for t in texts)
    assert any(t.startswith("regression") for t in texts)
    assert any("a = 0.8" in t for t in texts) and any("= 1.5" in t for t in texts)
    slope = f"{serial.record(0, 0)['slope_xy_deg']:.1f}°"
    assert slope in texts
    png, svg = save_figure(fig, tmp_path / "atlas", dpi=80)
    with Image.open(png) as im:
        w, h = im.size
        assert np.allclose((w, h), fig.get_size_inches() * 80, atol=1)
        assert len(np.unique(np.asarray(im.convert("RGB")).reshape(-1, 3), axis=0)) > 50
    assert svg.stat().st_size < 2_000_000


def test_boundary_validation():
    with pytest.raises(InputError, match="p_xy_values must be a non-empty"):
        run_atlas([], [0.3], workers=1)
    with pytest.raises(InputError, match="a_values must be a non-empty"):
        run_atlas([0.75], [["x"]], workers=1)
    with pytest.raises(InputError, match="workers must be an integer"):
        run_atlas([0.75], [0.3], workers=0)
    with pytest.raises(InputError, match="width must be"):
        run_atlas([0.75], [0.3], width=-1.0, workers=1)  # shared parameters fail once, not per design
    with pytest.raises(InputError, match="samples must be odd"):
        run_atlas([0.75], [0.3], samples=60, workers=1)
    with pytest.raises(InputError, match="progress must be a callable"):
        run_atlas([0.75], [0.3], progress=3, workers=1)


def test_bugs_are_not_swallowed(monkeypatch):
    def broken(*args, **kwargs):
        raise RuntimeError("a bug, not an invalid design")

    monkeypatch.setattr(atlas_module, "evaluate_design", broken)
    with pytest.raises(RuntimeError, match="a bug"):
        run_atlas([0.75], [0.3], workers=1)
