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

    return build(design_from_dict({"kind": "tube", "samples": 33, "curve": {"panels": 8}, "output": {"formats": ["fold"]}}))


def test_the_mechanism_decomposes_on_one_thread(two_threads, monkeypatch):
    seen = []
    svd = np.linalg.svd
    monkeypatch.setattr(np.linalg, "svd", lambda *a, **k: (seen.append(_blas_threads()), svd(*a, **k))[1])
    structure = _panel_tube().structure
    framework, points = m.Framework.from_structure(structure)
    m.mechanism(framework, structure.state().vertices.reshape(-1, 3)[points])
    assert seen and all(set(threads) == {1} for threads in seen)


def test_the_pictures_job_reads_the_mechanism_the_certificate_computed(tmp_path, monkeypatch):
    """The output folder of a panel structure: the mechanism is analysed before the jobs fork, in this process only."""
    from curvefold.app import write_outputs
    from curvefold.app._folder import check_output

    log = tmp_path / "analyses"
    analyse = m.mechanism

    def counted(*args, **kwargs):
        with open(log, "a") as f:
            f.write(f"{os.getpid()}\n")
        return analyse(*args, **kwargs)

    monkeypatch.setattr(m, "mechanism", counted)
    result = write_outputs(_panel_tube(), check_output(tmp_path / "out", force=False), show_progress=False)
    assert "singular-values.png" in result["files"]
    pids = log.read_text().split()
    assert pids == [str(os.getpid())] * 3  # flat, half and the design angle, all here
