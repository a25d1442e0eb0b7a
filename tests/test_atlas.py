"""The design atlas: invalid designs recorded, grid order, files, agreement with Vault, sweeps.

Sweeps run in this process, on a local Dask cluster of 2 processes (``workers=2``) and on
an existing cluster reached by its address (``scheduler=``, a LocalCluster on 127.0.0.1):
all three must give the same records, bit for bit.
"""

import csv
import json
import logging
import math
import os
import signal
import subprocess
import sys
import time
from concurrent.futures import Future
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_array_equal

from _cli import run
from curvefold import InputError
from curvefold.io._records import csv_records, json_records
from curvefold.vault import A_MAX, Vault, VaultDesign
from curvefold.vault import _atlas as atlas_module
from curvefold.vault import _cluster as cluster_module
from curvefold.vault import _sweep as sweep_module
from curvefold.vault._atlas import FIELDS, METRICS, Atlas, AtlasGrid
from curvefold.vault._sweep import run_atlas, sweep

pytest.importorskip("matplotlib")
distributed = pytest.importorskip("distributed")
psutil = pytest.importorskip("psutil")

# Rows a = 0.3, 0.8 and 1.3 ≥ A_MAX (no standing arch); at a = 0.8 the proportion
# p_xy = 4 with width 0.08 puts the base tube past regression.
P_XY = [0.75, 1.5, 4.0]
A_VALUES = [0.3, 0.8, 1.3]
KW = dict(width=0.08, samples=61)


def _run(**where) -> tuple[Atlas, list]:
    calls: list = []
    result = run_atlas(
        P_XY, A_VALUES, progress=lambda done, total: calls.append((done, total)), **where, **KW
    )
    return result, calls


@pytest.fixture(scope="module")
def cluster():
    """An existing Dask cluster: 2 single-thread workers in this process, reached over TCP on
    127.0.0.1."""
    with distributed.LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=False,
        protocol="tcp://",
        host="127.0.0.1",
        dashboard_address=":0",
        silence_logs=logging.ERROR,
    ) as c:
        yield c


@pytest.fixture(scope="module")
def serial_run() -> tuple[Atlas, list]:
    return _run(workers=1)


@pytest.fixture(scope="module")
def parallel_run() -> tuple[Atlas, list]:
    return _run(workers=2)  # a local cluster of 2 worker processes


@pytest.fixture(scope="module")
def scheduler_run(cluster) -> tuple[Atlas, list]:
    return _run(scheduler=cluster.scheduler_address)


@pytest.fixture(scope="module")
def serial(serial_run) -> Atlas:
    return serial_run[0]


def test_grid_order_and_keys(serial):
    assert serial.shape == (3, 3)
    assert serial.grid.p_xy_values == tuple(P_XY) and serial.grid.a_values == tuple(A_VALUES)
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
    assert (
        bad["valid"] is False
        and bad["error"] == "InputError"
        and "p_xy must be in" in bad["reason"]
    )
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


@pytest.mark.parametrize("which", ["parallel_run", "scheduler_run"])
def test_cluster_records_are_identical_to_serial(which, serial, request):
    other = request.getfixturevalue(which)[0]
    assert other.records == serial.records  # floats compared exactly
    assert [r["valid"] for r in other.records].count(True) == 5
    damaged = [dict(r) for r in other.records]
    damaged[0]["span"] = math.nextafter(damaged[0]["span"], math.inf)
    assert damaged != list(serial.records)  # one ulp apart is a difference
    for a, b in zip(serial.sketches, other.sketches):
        assert (a is None) == (b is None)
        if a is not None:
            for x, y in (
                (a.curves, b.curves),
                (a.cells, b.cells),
                (a.feet, b.feet),
                (a.apex, b.apex),
            ):
                assert_array_equal(x, y, strict=True)
            assert a.kinds == b.kinds


@pytest.mark.parametrize("which", ["serial_run", "parallel_run", "scheduler_run"])
def test_progress_reports_every_design(which, request):
    calls = request.getfixturevalue(which)[1]
    assert calls[0] == (0, 9) and calls[-1] == (9, 9)
    assert [d for d, _ in calls] == list(range(10))
    assert {t for _, t in calls} == {9}


def test_values_of_a_field(serial):
    g = serial.values("slope_xy_deg")
    assert g.shape == (3, 3)
    assert np.isnan(g[2]).all() and np.isnan(g[1, 2])
    assert g[0, 0] == serial.record(0, 0)["slope_xy_deg"]
    assert serial.values("valid").tolist()[2] == [0.0, 0.0, 0.0]
    with pytest.raises(InputError, match="numeric field"):
        serial.values("reason")


@pytest.fixture(scope="module")
def written(tmp_path_factory) -> tuple[dict, Path]:
    """The output folder of the 3 × 3 atlas (serial) and write_atlas's summary."""
    from curvefold.app import write_atlas
    from curvefold.app._folder import check_output

    out = tmp_path_factory.mktemp("atlas") / "out"
    summary = write_atlas(
        P_XY, A_VALUES, out=check_output(out, force=False), workers=1, show_progress=False, **KW
    )
    return summary, out


def test_written_summary_and_files(written):
    from curvefold.app._folder import MARKER

    summary, out = written
    assert summary == {
        "shape": [3, 3],
        "designs": 9,
        "valid": 5,
        "invalid": {"ConvergenceError": 3, "RegressionError": 1},
        "files": ["atlas.csv", "atlas.json", "atlas.png", "atlas.svg"],
    }
    assert sorted(set(os.listdir(out)) - {MARKER}) == summary["files"]  # no temporary file left


def test_csv_round_trip(serial, written):
    with open(written[1] / "atlas.csv", newline="", encoding="utf-8") as f:
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


def test_json_round_trip(serial, written):
    doc = json.loads((written[1] / "atlas.json").read_text(encoding="utf-8"))
    assert (
        doc["format"] == "curvefold-atlas" and doc["version"] == 1 and doc["fields"] == list(FIELDS)
    )
    assert doc["p_xy_values"] == P_XY and doc["a_values"] == A_VALUES
    assert (doc["width"], doc["fold_angle"], doc["samples"], doc["tubes"]) == (0.08, 90.0, 61, None)
    assert doc["records"] == list(serial.records)


def test_record_files_are_written_whole_or_not_at_all(tmp_path):
    records = [
        {"x": 0.1, "ok": True, "why": None},
        {"x": math.nan, "ok": False, "why": 'a, "quoted"\nreason'},
    ]
    for name in ("t.csv", "t.json"):
        (tmp_path / name).write_text("old")
    with (
        pytest.raises(RuntimeError, match="stopped"),
        csv_records(tmp_path / "t.csv", ("x", "ok", "why")) as write,
    ):
        write(records[0])
        raise RuntimeError("stopped")
    with (
        pytest.raises(RuntimeError, match="stopped"),
        json_records(tmp_path / "t.json", {"format": "t"}, ("x", "ok", "why")) as write,
    ):
        write(records[0])
        raise RuntimeError("stopped")
    assert sorted(os.listdir(tmp_path)) == ["t.csv", "t.json"]  # no temporary file left
    assert (tmp_path / "t.csv").read_text() == (tmp_path / "t.json").read_text() == "old"
    with (
        csv_records(tmp_path / "t.csv", ("x", "ok", "why")) as write_csv,
        json_records(tmp_path / "t.json", {"format": "t"}, ("x", "ok", "why")) as write_json,
    ):
        for r in records:
            write_csv(r)
            write_json(r)
    with open(tmp_path / "t.csv", newline="", encoding="utf-8") as f:
        assert list(csv.reader(f)) == [
            ["x", "ok", "why"],
            ["0.1", "True", ""],
            ["nan", "False", records[1]["why"]],
        ]
    assert json.loads((tmp_path / "t.json").read_text()) == {
        "format": "t",
        "records": [records[0], {**records[1], "x": None}],
    }
    with (
        pytest.raises(InputError, match="must not have a 'records' key"),
        json_records(tmp_path / "u.json", {"records": 1}, ("x",)),
    ):
        pass


def test_figure_renders(serial, tmp_path):
    from PIL import Image

    from curvefold.figures import atlas_figure, save_figure

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
        # shared parameters fail once, not per design
        run_atlas([0.75], [0.3], width=-1.0, workers=1)
    with pytest.raises(InputError, match="samples must be odd"):
        run_atlas([0.75], [0.3], samples=60, workers=1)
    with pytest.raises(InputError, match="progress must be a callable"):
        run_atlas([0.75], [0.3], progress=3, workers=1)


@pytest.mark.parametrize("where", ["serial", "scheduler"])
def test_bugs_are_not_swallowed(where, cluster, monkeypatch):
    def broken(*args, **kwargs):
        raise RuntimeError("a bug, not an invalid design")

    # the cluster's workers run in this process
    monkeypatch.setattr(sweep_module, "evaluate_design", broken)
    with pytest.raises(RuntimeError, match="a bug"):
        run_atlas(
            [0.75],
            [0.3],
            **({"workers": 1} if where == "serial" else {"scheduler": cluster.scheduler_address}),
        )


def test_boundary_validation_of_where_the_sweep_runs(cluster):
    cpus = cluster_module._cpus()
    with pytest.raises(
        InputError,
        match=rf"workers must be an integer in \[1, {cpus}\] \(the "
        rf"{cpus} CPUs? this process may use\), got {cpus + 1}",
    ):
        run_atlas([0.75], [0.3], workers=cpus + 1)
    with pytest.raises(
        InputError,
        match="workers sizes a local cluster; the cluster at "
        "scheduler 'tcp://.*' has its own workers, got workers = 2",
    ):
        run_atlas([0.75], [0.3], workers=2, scheduler=cluster.scheduler_address)
    with pytest.raises(InputError, match="scheduler must be the address of a Dask scheduler"):
        run_atlas([0.75], [0.3], scheduler=8786)
    with pytest.raises(InputError, match="grid must be an AtlasGrid"):
        sweep([0.75], workers=1)


def _closed_port() -> int:
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.mark.parametrize(
    ("address", "message"),
    [
        (
            "nonsense://x:1",
            "scheduler must be a Dask scheduler address such as 'tcp://host:8786', "
            "got 'nonsense://x:1' (unknown address scheme",
        ),
        ("tcp://localhost", "got 'tcp://localhost' (missing port number"),
        ("inproc://x", "scheduler must be a network address"),
        (
            "tcp://no-such-host.invalid:8786",
            "scheduler 'tcp://no-such-host.invalid:8786': cannot resolve the host",
        ),
        ("closed", "cannot connect to a Dask scheduler there"),
    ],
)
def test_a_scheduler_that_cannot_be_reached_is_a_user_error(address, message):
    import dask

    address = f"tcp://127.0.0.1:{_closed_port()}" if address == "closed" else address
    with (
        dask.config.set({"distributed.comm.timeouts.connect": "1s"}),
        pytest.raises(InputError, match=message.replace("(", r"\(").replace(")", r"\)")),
    ):
        run_atlas([0.75], [0.3], scheduler=address)


def test_a_cluster_without_workers_is_a_user_error():
    import dask

    with (
        distributed.LocalCluster(
            n_workers=0,
            processes=False,
            protocol="tcp://",
            host="127.0.0.1",
            dashboard_address=":0",
            silence_logs=logging.ERROR,
        ) as empty,
        dask.config.set({"distributed.comm.timeouts.connect": "0.5s"}),
        pytest.raises(
            InputError,
            match=r"scheduler 'tcp://127\.0\.0\.1:\d+' has no worker " r"\(waited 0\.5 s\)",
        ),
    ):
        run_atlas([0.75], [0.3], scheduler=empty.scheduler_address)


@pytest.mark.parametrize(
    ("theirs", "have"),
    [
        ("0.0.1", "curvefold 0.0.1"),
        (ModuleNotFoundError("No module named 'curvefold'"), "no curvefold"),
    ],
)
def test_workers_must_run_this_curvefold(theirs, have, cluster, monkeypatch):
    from curvefold import __version__

    def worker_version():
        if isinstance(theirs, Exception):
            raise theirs
        return theirs

    # what the cluster's workers report
    monkeypatch.setattr(cluster_module, "_curvefold_version", worker_version)
    with pytest.raises(
        InputError,
        match=rf"every worker needs curvefold {__version__}, as here; "
        rf"2 of 2 differ, e.g. tcp://127\.0\.0\.1:\d+ has {have}$",
    ):
        run_atlas([0.75], [0.3], scheduler=cluster.scheduler_address)


def test_where_designs_run_by_default(monkeypatch):
    plan = cluster_module.cluster_plan
    local = min(2, cluster_module._cpus())
    assert plan(cluster_module.LOCAL_CLUSTER_FROM, None, None) == (local, None)
    # a cluster would cost more than it saves
    assert plan(cluster_module.LOCAL_CLUSTER_FROM - 1, None, None) == (1, None)
    assert plan(1, 2, None) == (1, None)  # never more workers than designs
    assert plan(5, None, " tcp://10.0.0.5:8786 ") == (0, "tcp://10.0.0.5:8786")
    # without Dask: the default runs here, and asking for a cluster says what to install
    monkeypatch.setattr(cluster_module.importlib.util, "find_spec", lambda name, *a: None)
    assert plan(cluster_module.LOCAL_CLUSTER_FROM, None, None) == (1, None)
    for workers, scheduler, what in (
        (2, None, "workers = 2"),
        (None, "tcp://10.0.0.5:8786", "scheduler 'tcp://10.0.0.5:8786'"),
    ):
        with pytest.raises(
            ModuleNotFoundError,
            match=rf"^{what} runs on Dask, which is not "
            r"installed; install it with: pip install 'curvefold\[dask\]'$",
        ):
            plan(5, workers, scheduler)


def _cluster_settings() -> tuple:
    import dask

    return tuple(dask.config.get(key) for key in cluster_module.CLUSTER_SETTINGS)


def _heap_trim() -> str | None:
    return os.environ.get("MALLOC_TRIM_THRESHOLD_")


def test_the_local_cluster_runs_quiet_and_trims_its_workers_heap_at_4_mib(monkeypatch):
    # a variable set here would outrank the settings
    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    settings = (False, "1s", 4 * 2**20)
    assert tuple(cluster_module.CLUSTER_SETTINGS.values()) == settings
    here = _cluster_settings()  # Dask's defaults, (True, "20ms", 65536)
    assert here != settings
    with cluster_module.client(2, None) as client:
        assert set(client.run(_cluster_settings).values()) == {settings}  # the worker processes
        assert client.run_on_scheduler(_cluster_settings) == settings
        # what glibc reads in the workers
        assert set(client.run(_heap_trim).values()) == {str(4 * 2**20)}
    assert _cluster_settings() == here  # the settings were the cluster's alone


def test_a_local_cluster_leaves_this_process_environment_as_it_was(monkeypatch):
    import dask

    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    before = dict(os.environ)
    # 65536
    dasks = str(dask.config.get("distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_"))
    # Dask's defaults
    with cluster_module.local_cluster(1, {}) as cluster, distributed.Client(cluster) as client:
        assert set(client.run(_heap_trim).values()) == {dasks}
        # Dask's nanny wrote it here, to spawn the worker
        assert os.environ.get("MALLOC_TRIM_THRESHOLD_") == dasks
    assert dict(os.environ) == before
    with cluster_module.client(2, None) as client:  # so the next cluster gets its own settings
        assert set(client.run(_heap_trim).values()) == {str(4 * 2**20)}
    assert dict(os.environ) == before


def test_workers_started_with_the_readmes_environment_get_the_atlas_settings(tmp_path, monkeypatch):
    """``dask worker`` under :func:`worker_environment` (the README's line) runs as the atlas's
    own workers; without it, on Dask's defaults."""
    import dask

    env = cluster_module.worker_environment()
    line = " ".join(f"{k}={v}" for k, v in env.items())
    # the line moved there from the README
    guide = Path(__file__).parents[1] / "docs" / "guide" / "atlas.md"
    assert f"`{line} dask worker ...`" in guide.read_text(encoding="utf-8")
    for key in env:
        monkeypatch.delenv(key, raising=False)
    dask_cli, file = Path(sys.executable).with_name("dask"), tmp_path / "scheduler.json"
    common = ["--scheduler-file", str(file), "--no-dashboard"]
    processes = [
        subprocess.Popen(
            [dask_cli, "scheduler", "--host", "127.0.0.1", *common], stderr=subprocess.DEVNULL
        )
    ]
    try:
        for extra in ({}, env):
            processes.append(
                subprocess.Popen(
                    [dask_cli, "worker", "--nthreads", "1", *common],
                    env=os.environ | extra,
                    stderr=subprocess.DEVNULL,
                )
            )
        with distributed.Client(scheduler_file=str(file), timeout=60) as client:
            client.wait_for_workers(2, timeout=60)
            dasks = {
                key: value
                for key, value in cluster_module.CLUSTER_SETTINGS.items()
                if "pre-spawn-environ" not in key
            }
            found = {key: set(client.run(dask.config.get, key).values()) for key in dasks}
            # what glibc reads
            trims = set(client.run(os.getenv, "MALLOC_TRIM_THRESHOLD_").values())
            client.shutdown()
    finally:
        for process in processes[::-1]:
            if process.poll() is None:
                process.terminate()
            process.wait(30)
    assert found == {key: {value, dask.config.get(key)} for key, value in dasks.items()}
    # 65536: Dask's
    assert trims == {
        str(4 * 2**20),
        str(dask.config.get("distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_")),
    }


class _Futures:
    """A submit function whose futures finish at once; it counts the futures outstanding (result
    not yet taken)."""

    def __init__(self):
        self.outstanding = 0
        self.most = 0

    def submit(self, task):
        self.outstanding += 1
        self.most = max(self.most, self.outstanding)
        future = Future()
        future.set_result(task * 10)
        taken = future.result

        def result():
            self.outstanding -= 1
            return taken()

        future.result = result
        return future


def _within_rows(sizes, cols):
    """Whether every task of these sizes holds whole rows or lies within one row."""
    starts = np.cumsum([0, *sizes[:-1]])
    return all(
        start // cols == (start + n - 1) // cols or (start % cols == 0 and n % cols == 0)
        for start, n in zip(starts, sizes)
    )


@pytest.mark.parametrize(
    ("rows", "cols", "threads"),
    [(40, 40, 2), (200, 200, 2), (24, 24, 4), (5000, 1, 2), (1, 1000, 2), (3, 7, 2), (1, 1, 1)],
)
def test_tasks_cover_the_grid_shrink_and_never_straddle_two_rows(rows, cols, threads):
    sizes = list(sweep_module.task_sizes(rows * cols, cols, threads))
    assert sum(sizes) == rows * cols and _within_rows(sizes, cols)
    assert max(sizes) <= max(sweep_module.CHUNK, min(cols, rows * cols))
    assert min(sizes[:-1], default=sweep_module.MIN_CHUNK) >= min(sweep_module.MIN_CHUNK, cols)
    if len(sizes) > 2 * threads:  # guided: the last tasks are the smallest
        assert sizes[-1] <= min(sizes[: 2 * threads])
    # the sweep's cut before: 100 designs a task on rows of 40
    assert not _within_rows([100] * 16, 40)


@pytest.mark.parametrize("window", [1, 3, 50])
def test_results_come_in_order_with_at_most_window_outstanding(window):
    futures = _Futures()
    assert list(cluster_module.in_order(futures.submit, range(20), window)) == [
        10 * k for k in range(20)
    ]
    assert futures.most == min(window, 20)  # a window of 50 holds everything: the count sees it


def test_a_serial_sweep_hands_out_each_design_before_the_next_runs(monkeypatch):
    events = []
    evaluate = atlas_module.evaluate_design

    def logged(a, p, **kwargs):
        events.append(("built", a, p))
        return evaluate(a, p, **kwargs)

    monkeypatch.setattr(sweep_module, "evaluate_design", logged)
    grid = AtlasGrid.of([0.75, 1.0], [0.3, 1.5], samples=41)
    for record, _ in sweep(grid, workers=1):
        events.append(("out", record["a"], record["p_xy"]))
    points = [(a, p) for a in (0.3, 1.5) for p in (0.75, 1.0)]
    assert events == [e for a, p in points for e in (("built", a, p), ("out", a, p))]


def test_every_kth_row_and_column(serial):
    step = 2
    sub = serial.every(step)
    assert (
        sub.shape == (2, 2)
        and sub.grid.p_xy_values == (0.75, 4.0)
        and sub.grid.a_values == (0.3, 1.3)
    )
    for r in sub.records:
        original = serial.record(step * r["row"], step * r["col"])
        assert r == original | {"row": r["row"], "col": r["col"]}
    assert sub.sketches[:2] == (serial.sketches[0], serial.sketches[2]) and sub.sketches[2:] == (
        None,
        None,
    )
    assert serial.every(1).records == serial.records
    with pytest.raises(InputError, match="step must be an integer ≥ 1, got 0"):
        serial.every(0)
    with pytest.raises(
        InputError,
        match=r"results must hold one \(record, sketch\) pair per "
        r"design of the 3 × 3 grid, got 2",
    ):
        Atlas.from_results(
            AtlasGrid.of(P_XY, A_VALUES), zip(serial.records[:2], serial.sketches[:2])
        )


def test_a_wide_grid_writes_every_record_and_draws_every_kth(tmp_path, monkeypatch):
    from curvefold.app import write_atlas
    from curvefold.app._folder import check_output
    from curvefold.figures import _atlas as figure_module

    drawn = {}
    draw = figure_module.atlas_figure

    def spy(atlas, **kwargs):
        drawn.update(atlas=atlas, **kwargs)
        return draw(atlas, cell_size=0.5, **kwargs)

    monkeypatch.setattr(figure_module, "atlas_figure", spy)
    # one column too many: every 2nd is drawn
    p_xy = np.linspace(0.5, 1.5, figure_module.MAX_VIEWS + 1).tolist()
    summary = write_atlas(
        p_xy,
        [0.3],
        out=check_output(tmp_path / "out", force=False),
        width=0.08,
        samples=41,
        workers=1,
        show_progress=False,
    )
    assert summary["designs"] == 25 and summary["valid"] == 25
    records = json.loads((tmp_path / "out" / "atlas.json").read_text())["records"]
    assert [r["col"] for r in records] == list(range(25))
    shown = drawn["atlas"]
    assert shown.shape == (1, 13) and shown.grid.p_xy_values == tuple(p_xy[::2])
    assert [r["p_xy"] for r in shown.records] == p_xy[::2] and all(
        s is not None for s in shown.sketches
    )
    assert drawn["note"] == (
        "one in 2 values of a and of p_xy shown; all 1 × 25 designs are in atlas.csv and atlas.json"
    )
    with pytest.raises(
        InputError,
        match=r"atlas_figure draws at most 24 × 24 views, got a 1 × "
        r"25 atlas; draw atlas.every\(2\)",
    ):
        draw(Atlas.from_results(AtlasGrid.of(p_xy, [0.3]), [(r, None) for r in records]))


def test_command_line_on_a_cluster_writes_the_same_files(cluster, written, tmp_path):
    flags = ["--p-xy", "0.75,1.5,4", "--a", "0.3,0.8,1.3", "--width", "0.08", "--samples", "61"]
    r = run(
        "atlas",
        *flags,
        "--scheduler",
        cluster.scheduler_address,
        "--out",
        str(tmp_path / "out"),
        "--json",
    )
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["valid"] == 5
    for name in ("atlas.csv", "atlas.json"):
        assert (tmp_path / "out" / name).read_bytes() == (written[1] / name).read_bytes()
    r = run(
        "atlas",
        *flags,
        "--workers",
        "2",
        "--scheduler",
        cluster.scheduler_address,
        "--out",
        str(tmp_path / "other"),
    )
    assert (
        r.returncode == 2
        and "has its own workers" in r.stderr
        and not (tmp_path / "other").exists()
    )


def test_command_line_bounds_the_workers(tmp_path):
    cpus = cluster_module._cpus()
    for value in (0, cpus + 1, 50 * cpus):
        r = run("atlas", "--workers", str(value), "--out", str(tmp_path / "out"))
        assert r.returncode == 2
        assert r.stderr.strip() == (
            f"curvefold: error: --workers {value}: workers must be an "
            f"integer in [1, {cpus}] (the {cpus} CPU{'s' * (cpus != 1)} this process may use), "
            f"got {value}"
        )
    assert os.listdir(tmp_path) == []


@pytest.mark.slow
@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT], ids=["SIGTERM", "SIGINT"])
def test_a_signal_stops_the_sweep_and_its_workers(signum, tmp_path):
    # 3600 designs: several seconds on 2 workers, stopped once a record reaches the temporary CSV
    argv = [
        sys.executable,
        "-m",
        "curvefold",
        "atlas",
        "--workers",
        "2",
        "--p-xy",
        "0.5:1.5:60",
        "--a",
        "0:1.2:60",
        "--out",
        str(tmp_path / "out"),
    ]
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    children: list = []
    try:
        deadline = time.monotonic() + 120
        while True:
            assert proc.poll() is None and time.monotonic() < deadline, (
                "the sweep ended or never started"
            )
            time.sleep(0.05)
            try:
                children = psutil.Process(proc.pid).children(recursive=True)
                workers = [p for p in children if "spawn_main" in " ".join(p.cmdline())]
                # lines after the header
                records = sum(
                    p.read_text().count("\n") - 1 for p in tmp_path.glob(".out.*/.atlas.csv.*")
                )
            # a process or file that went while looking
            except (psutil.NoSuchProcess, FileNotFoundError):
                continue
            if len(workers) == 2 and records > 0:
                break
        proc.send_signal(signum)
        _, err = proc.communicate(timeout=60)
        assert (proc.returncode, err) == (
            128 + signum,
            f"curvefold: interrupted by {signal.Signals(signum).name}\n",
        )
        _, alive = psutil.wait_procs(children, timeout=30)
        assert alive == [], f"processes left running: {alive}"
        assert os.listdir(tmp_path) == []  # neither the output folder nor its temporary one
    finally:
        if proc.poll() is None:
            proc.kill()
        for child in children:
            if child.is_running():
                child.kill()


def test_a_sweep_sketches_only_the_designs_of_every_kth_row_and_column_with_the_same_records():
    grid = AtlasGrid.of([0.6, 0.8, 1.0], [0.1, 0.3, 0.5], samples=41)
    every = list(sweep(grid, workers=1))
    some = list(sweep(grid, workers=1, sketch_step=2))
    assert [r for r, _ in some] == [r for r, _ in every]
    assert [(r["row"], r["col"]) for r, s in some if s is not None] == [
        (0, 0),
        (0, 2),
        (2, 0),
        (2, 2),
    ]
    assert all(s is not None for _, s in every)
    with pytest.raises(InputError, match="step"):
        sweep(grid, workers=1, sketch_step=0)
