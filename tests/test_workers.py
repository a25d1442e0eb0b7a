"""Worker processes that stop when told (curvefold.app._workers): results, refusals, bugs, and every
way a job stops.

Jobs are built-in callables (``eval``, ``exec``), which pickle by name: a worker imports nothing of
the tests.
"""

from __future__ import annotations

import asyncio
import subprocess
import sys

import psutil
import pytest

from curvefold.app._workers import JobError, Pool, Reservations, Stopped, resident_bytes

#: A job that runs until it is stopped (a minute, far past every limit below).
FOREVER = "import time; time.sleep(60)"


@pytest.fixture(scope="module")
def pool(tmp_path_factory):
    workers = Pool(
        2, name="test", scratch=tmp_path_factory.mktemp("scratch"), recycle_above=1 << 40
    )
    yield workers
    workers.join()


def run(pool: Pool, *args, **kwargs):
    return asyncio.run(pool.run(*args, **kwargs))


def gone(pids, timeout: float = 5.0) -> bool:
    """Whether every process of ``pids`` has ended within ``timeout`` seconds."""
    procs = [p for pid in pids if psutil.pid_exists(pid) for p in [psutil.Process(pid)]]
    alive = psutil.wait_procs(procs, timeout=timeout)[1]
    return not [p for p in alive if p.status() != psutil.STATUS_ZOMBIE]


def test_a_job_answers_and_errors_come_back_by_kind(pool):
    assert run(pool, eval, "6 * 7", timeout=30) == 42
    with pytest.raises(JobError) as refused:
        run(
            pool,
            exec,
            "from curvefold.kernel import InputError\nraise InputError('a must be < "
            "3, got 5', parameter='a')",
            timeout=30,
        )
    assert (str(refused.value), refused.value.refused, refused.value.parameter) == (
        "a must be < 3, got 5",
        True,
        "a",
    )
    with pytest.raises(JobError) as bug:
        run(pool, eval, "1 / 0", timeout=30)
    assert (str(bug.value), bug.value.refused) == ("ZeroDivisionError: division by zero", False)


@pytest.mark.parametrize("reason", ["time", "cancelled", "memory"])
def test_a_stopped_job_kills_its_worker_which_is_replaced(pool, reason):
    before = pool.pids()
    options = {
        "time": {"timeout": 0.5},
        "cancelled": {"timeout": 60, "cancelled": lambda: asyncio.sleep(0.3)},
        "memory": {"timeout": 60, "memory_limit": 100 << 20},
    }[reason]
    job = FOREVER if reason != "memory" else "import time; x = bytearray(400 << 20); time.sleep(60)"
    with pytest.raises(Stopped) as stopped:
        run(pool, exec, job, **options)
    assert stopped.value.reason == reason
    after = pool.pids()
    killed = set(before) - set(after)
    assert len(killed) == 1 and gone(killed) and len(after) == 2  # the one that ran it, replaced
    assert run(pool, eval, "1 + 1", timeout=30) == 2  # and the pool works on


def test_closing_stops_running_jobs_and_leaves_no_process(tmp_path):
    pool = Pool(2, name="closing", scratch=tmp_path)
    pids = pool.pids()

    async def main():
        job = asyncio.ensure_future(pool.run(exec, FOREVER, timeout=60))
        await asyncio.sleep(0.3)
        pool.close()
        with pytest.raises(Stopped) as stopped:
            await job
        assert stopped.value.reason == "closed"
        with pytest.raises(Stopped):
            await pool.run(eval, "1", timeout=60)

    asyncio.run(main())
    pool.join()
    assert gone(pids)


def test_workers_die_with_their_parent(tmp_path):
    """A server killed with SIGKILL runs no cleanup: its workers end with it (their parent, the
    fork server, exits when the server's pipe closes; the kernel kills them then)."""
    script = (
        "import os, sys\nfrom curvefold.app._workers import Pool\npool = Pool(2, "
        f"name='orphan', scratch={str(tmp_path)!r})\nprint(*pool.pids(), "
        "flush=True)\nos.kill(os.getpid(), 9)"
    )
    out = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=120
    )
    pids = [int(p) for p in out.stdout.split()]
    assert len(pids) == 2 and gone(pids)


def test_reservations_hold_the_jobs_within_a_capacity():
    async def main():
        held = Reservations(100)
        await held.hold(60, timeout=1)
        with pytest.raises(Stopped, match="waited 0 s for memory"):
            await held.hold(60, timeout=0.05)  # would pass the capacity beside the first
        await held.release(60)
        # alone, a job may use more (it was checked against the budget before)
        await held.hold(150, timeout=1)
        return held.held

    assert asyncio.run(main()) == 150


def test_resident_bytes():
    import os

    assert resident_bytes(os.getpid()) > 10 << 20 and resident_bytes(2**22 + 12345) == 0
