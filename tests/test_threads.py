"""BLAS threads: the mechanism's SVDs run on one thread, and the output jobs share them."""

import os

import numpy as np
import pytest
from threadpoolctl import threadpool_info, threadpool_limits

from curvefold.analysis import _mechanism as m
from curvefold.kernel import one_blas_thread


def _blas_threads() -> list[int]:
    return [pool["num_threads"] for pool in threadpool_info() if pool["user_api"] == "blas"]


@pytest.fixture
def two_threads():
    """BLAS on two threads, as OpenBLAS starts on two CPUs (the test session runs on one)."""
    with threadpool_limits(limits=2, user_api="blas"):
        assert set(_blas_threads()) == {2}
        yield


def test_one_blas_thread_limits_the_block_and_restores_the_pools(two_threads):
    with one_blas_thread():
        assert set(_blas_threads()) == {1}
    assert set(_blas_threads()) == {2}


def _panel_tube():
    from curvefold.app import design_from_dict
    from curvefold.app._build import build

    return build(
        design_from_dict(
            {"kind": "tube", "samples": 33, "curve": {"panels": 8}, "output": {"formats": ["fold"]}}
        )
    )


def test_the_mechanism_decomposes_on_one_thread(two_threads, monkeypatch):
    seen = []
    svd = np.linalg.svd
    monkeypatch.setattr(
        np.linalg, "svd", lambda *a, **k: (seen.append(_blas_threads()), svd(*a, **k))[1]
    )
    structure = _panel_tube().structure
    framework, points = m.Framework.from_structure(structure)
    m.mechanism(framework, structure.state().vertices.reshape(-1, 3)[points])
    assert seen and all(set(threads) == {1} for threads in seen)


def test_the_pictures_job_reads_the_mechanism_the_certificate_computed(tmp_path, monkeypatch):
    """The output folder of a panel structure: the mechanism is analysed before the jobs fork, in
    this process only."""
    from curvefold.app import write_outputs
    from curvefold.app._folder import check_output

    log = tmp_path / "analyses"
    analyse = m.mechanism

    def counted(*args, **kwargs):
        with open(log, "a") as f:
            f.write(f"{os.getpid()}\n")
        return analyse(*args, **kwargs)

    monkeypatch.setattr(m, "mechanism", counted)
    result = write_outputs(
        _panel_tube(), check_output(tmp_path / "out", force=False), show_progress=False
    )
    assert "singular-values.png" in result["files"]
    pids = log.read_text().split()
    assert pids == [str(os.getpid())] * 3  # flat, half and the design angle, all here


def _blas_threads_of(code: str) -> tuple[list[int], bool]:
    """The BLAS libraries' threads after ``code`` runs in a fresh interpreter whose environment
    sets none of :data:`~curvefold.kernel._threads.BLAS_THREAD_VARIABLES`, and whether it sets
    one afterwards."""
    import json
    import subprocess
    import sys

    from curvefold.kernel._threads import BLAS_THREAD_VARIABLES

    probe = (
        f"{code}\nimport json, os\nfrom threadpoolctl import "
        "threadpool_info\nprint(json.dumps([[p['num_threads'] for p in threadpool_info() if "
        "p['user_api'] == 'blas'], any(name in os.environ for name in "
        f"{BLAS_THREAD_VARIABLES!r})]))"
    )
    env = {name: value for name, value in os.environ.items() if name not in BLAS_THREAD_VARIABLES}
    done = subprocess.run(
        [sys.executable, "-c", probe],
        capture_output=True,
        text=True,
        timeout=120,
        env=env,
        check=True,
    )
    threads, variable_set = json.loads(done.stdout.splitlines()[-1])
    return threads, variable_set


def test_the_command_line_loads_numpy_with_one_blas_thread_and_leaves_the_environment():
    """OpenBLAS starts no thread of its own (each would spin for a tenth of a CPU-second), and the
    processes the command starts inherit the environment it was given."""
    assert _blas_threads_of("import curvefold.app.cli") == ([1], False)
    if (os.cpu_count() or 1) > 1:  # the probe sees NumPy loaded otherwise: a thread per CPU
        threads, _ = _blas_threads_of("import numpy")
        assert threads and min(threads) > 1
