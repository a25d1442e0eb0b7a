"""The designer under attack: time spent waiting counts towards the time limit, and a job
killed for its time or for its vanished client leaves nothing in the scratch folder."""

from __future__ import annotations

import asyncio
import os
import time
from pathlib import Path

import pytest

from _designer import get_json
from test_designer_service import HEAVY, open_request, until

pytest.importorskip("fastapi")
from curvefold.app.designer import server  # noqa: E402

#: A zip of the output folder: its temporary folder appears at once, the job takes 2.5 s (a quiet
#: machine) to 6 s (a loaded one).
ZIP = "api/tube.zip?samples=8001"


def leftovers(scratch: str) -> list[str]:
    """Everything in the scratch folder but the workers' own (empty) folders."""
    return sorted(
        str(p.relative_to(scratch))
        for p in Path(scratch).rglob("*")
        if not (p.parent == Path(scratch) and p.is_dir() and p.name.startswith("worker-"))
    )


def test_time_spent_waiting_for_memory_counts_towards_the_time_limit():
    with server.serving(time_limit=3.0) as url:
        reservations = url.designer.reservations
        hold = reservations.hold

        async def slow(amount: float, timeout: float) -> None:  # memory other jobs hold, 1.5 s
            await asyncio.sleep(min(1.5, timeout))
            await hold(amount, timeout - min(1.5, timeout))

        reservations.hold = slow
        start = time.perf_counter()
        status_, answer = get_json(url + HEAVY)
        took = time.perf_counter() - start
    # before: the wait, then the whole limit for the work
    assert status_ == 504 and "time limit of 3 s" in answer["error"]
    assert 2.9 < took < 4.2, took  # 4.5 s and more before


def test_a_job_killed_for_its_time_leaves_nothing_behind():
    with server.serving(time_limit=1.5) as url:  # under the job's time on any machine
        status_, answer = get_json(url + ZIP)
        assert status_ == 504, answer
        # the job's output folder was in the scratch folder until the server stopped
        assert leftovers(url.designer.scratch) == []


def test_a_job_whose_client_went_away_leaves_nothing_behind():
    with server.serving(time_limit=60.0) as url:
        scratch = url.designer.scratch
        client = open_request(url, ZIP)
        until(lambda: leftovers(scratch), "the job's temporary folder")
        client.close()
        until(lambda: not leftovers(scratch), "the temporary folder removed", tries=200)
        assert all(os.listdir(Path(scratch) / name) == [] for name in os.listdir(scratch))
