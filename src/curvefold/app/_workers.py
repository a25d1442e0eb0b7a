"""Jobs in worker processes that stop when told: a bounded pool of pre-started processes.

A :class:`Pool` holds a fixed number of worker processes, each running one job at a time.
:meth:`Pool.run` sends a job (a module-level function and its arguments, pickled) to an
idle worker and waits for its answer; a job that overruns its time limit, outgrows its
memory limit, is cancelled by its caller or is running when the pool closes kills its
worker and the processes the job started (SIGKILL to the worker's process group), and the
worker is replaced by a fresh one. So a stopped job stops at once,
whatever it computes, and holds no memory afterwards; a worker that a job leaves larger
than ``recycle_above`` bytes is replaced too, so idle workers stay small.

Workers start from a fork server with the ``preload`` modules imported (a clean process
with no threads inherited, started in milliseconds), ignore SIGINT (the terminal sends it
to the whole process group: their parent decides), die with their parent (Linux:
``PR_SET_PDEATHSIG``) and write temporary files in a folder of their own under ``scratch``
(``worker-<pid>``), removed as soon as the worker is killed (a job stopped for its time, its
memory or its vanished client leaves nothing behind); ``scratch`` itself the owner removes.
A job's exception comes back as a :class:`JobError`: ``refused`` for a
:class:`~curvefold.kernel.CurvefoldError` (what the user asked), not for a bug.

Jobs waiting for memory share one :class:`Reservations`: a job runs when its estimate fits
beside those running (or runs alone), so the jobs running at once stay within a budget.
"""

from __future__ import annotations

import asyncio
import ctypes
import multiprocessing
import os
import shutil
import signal
import sys
import tempfile
import threading
import warnings
from collections.abc import Awaitable, Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

from ..kernel._errors import CurvefoldError

__all__ = ["JobError", "Pool", "Reservations", "Stopped", "resident_bytes"]

#: How often a running job's worker is checked (its memory, the time, the pool closing), seconds.
WATCH_PERIOD = 0.05


class JobError(Exception):
    """A job raised an exception: its one-line message, whether it was a refusal (a
    :class:`~curvefold.kernel.CurvefoldError`) or a bug, and the parameter a
    refusal is about (its :attr:`~curvefold.kernel.CurvefoldError.parameter`)."""

    def __init__(self, message: str, *, refused: bool, parameter: str | None = None) -> None:
        super().__init__(message)
        self.refused, self.parameter = refused, parameter


class Stopped(Exception):
    """A job stopped before it finished; ``reason`` is ``"time"``, ``"memory"``, ``"cancelled"``,
    ``"closed"`` (the pool closed) or ``"died"`` (its worker ended by itself)."""

    def __init__(self, reason: str, message: str) -> None:
        super().__init__(message)
        self.reason = reason


def resident_bytes(pid: int) -> int:
    """Resident memory of a process in bytes (0 if it is gone or the platform has no ``/proc``)."""
    try:
        with open(f"/proc/{pid}/statm", "rb") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return 0


class Reservations:
    """Memory held by the jobs running at once: :meth:`hold` waits until an amount fits
    within ``capacity`` beside them, or until nothing runs (a job larger than the capacity
    is refused before it comes here)."""

    def __init__(self, capacity: float) -> None:
        self.capacity, self.held = float(capacity), 0.0
        self._changed: asyncio.Condition | None = None

    async def hold(self, amount: float, timeout: float) -> None:
        """Reserve ``amount`` bytes; :class:`Stopped` (``"time"``) after ``timeout`` seconds of
        waiting."""
        if self._changed is None:
            self._changed = asyncio.Condition()
        async with self._changed:
            fits = lambda: self.held == 0 or self.held + amount <= self.capacity  # noqa: E731
            try:
                await asyncio.wait_for(self._changed.wait_for(fits), timeout)
            except TimeoutError:
                raise Stopped(
                    "time", f"waited {timeout:.0f} s for memory that the running jobs hold"
                ) from None
            self.held += amount

    async def release(self, amount: float) -> None:
        if self._changed is None:  # nothing was held
            self._changed = asyncio.Condition()
        async with self._changed:
            self.held -= amount
            self._changed.notify_all()


class _Worker:
    """One worker process and its end of the pipe; ``stop`` says why it was killed."""

    def __init__(self, process, conn) -> None:
        self.process, self.conn = process, conn
        self.stop: str | None = None

    def call(self, fn: Callable, args: tuple) -> tuple:
        self.conn.send((fn, args))
        return self.conn.recv()

    def kill(self, reason: str) -> None:
        """Kill the process and any it started, now (safe in a signal handler: a flag and
        ``killpg``)."""
        self.stop = self.stop or reason
        pid = self.process.pid
        if pid is not None:
            try:
                # its own process group: the processes a job forked too
                os.killpg(pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError, AttributeError):
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass

    def reap(self) -> None:
        self.process.join(timeout=5)
        self.conn.close()


class Pool:
    """A fixed number of worker processes for jobs with a time limit, a memory limit and
    cancellation.

    Parameters
    ----------
    size : int
        Worker processes, started at once.
    name : str
        Names the processes (``curvefold-<name>-<i>``) and the messages.
    scratch : path-like
        Folder for the workers' temporary files.
    preload : sequence of str, keyword-only
        Modules the fork server imports before starting workers (only the first pool of a
        process sets them).
    niceness : int, keyword-only
        Added to the workers' nice value (heavy work yields the CPU to quick work).
    recycle_above : int, keyword-only
        A worker that a job leaves with more resident bytes is replaced by a fresh one.
    """

    def __init__(
        self,
        size: int,
        *,
        name: str,
        scratch: str | os.PathLike,
        preload: Sequence[str] = (),
        niceness: int = 0,
        recycle_above: int = 512 << 20,
    ) -> None:
        self.name, self.scratch, self.niceness, self.recycle_above = (
            name,
            str(scratch),
            niceness,
            recycle_above,
        )
        self._context = _context(preload)
        self._closing = False
        self._lock = threading.Lock()
        self._threads = ThreadPoolExecutor(max_workers=size, thread_name_prefix=f"curvefold-{name}")
        self._all: list[_Worker] = [self._start() for _ in range(size)]
        self._idle: asyncio.Queue | None = None  # made in the event loop that runs the jobs
        self.counts = {
            "done": 0,
            "refused": 0,
            "bug": 0,
            **{reason: 0 for reason in ("time", "memory", "cancelled", "closed", "died")},
            "recycled": 0,
        }

    @property
    def size(self) -> int:
        return len(self._all)

    @property
    def busy(self) -> int:
        """Workers running a job now."""
        return self.size - (self._idle.qsize() if self._idle is not None else self.size)

    def pids(self) -> list[int]:
        """Process ids of the current workers."""
        with self._lock:
            return [w.process.pid for w in self._all]

    def _start(self) -> _Worker:
        mine, theirs = self._context.Pipe()
        process = self._context.Process(
            target=_serve,
            args=(theirs, self.scratch, self.niceness),
            daemon=True,
            name=f"curvefold-{self.name}",
        )
        process.start()
        theirs.close()
        os.makedirs(self._folder(process.pid), exist_ok=True)
        return _Worker(process, mine)

    def _folder(self, pid: int | None) -> str:
        """The temporary folder of the worker of process ``pid``."""
        return os.path.join(self.scratch, f"worker-{pid}")

    async def run(
        self,
        fn: Callable,
        *args: Any,
        timeout: float,
        memory_limit: float | None = None,
        cancelled: Callable[[], Awaitable[Any]] | None = None,
    ) -> Any:
        """Run ``fn(*args)`` in a worker and return its result.

        Parameters
        ----------
        fn : callable
            A module-level function (it is pickled by name).
        timeout : float, keyword-only
            Seconds for the job, waiting for a worker included.
        memory_limit : float, optional, keyword-only
            Resident bytes the worker may reach while the job runs.
        cancelled : async callable, optional, keyword-only
            Returns when the caller no longer wants the answer (its client went away).

        Raises
        ------
        JobError
            ``fn`` raised.
        Stopped
            The job was stopped: time limit, memory limit, cancelled, the pool closing, or
            its worker died.
        """
        loop = asyncio.get_running_loop()
        deadline = loop.time() + timeout
        if self._idle is None:
            self._idle = asyncio.Queue()
            for worker in self._all:
                self._idle.put_nowait(worker)
        if self._closing:
            raise Stopped("closed", "the designer is stopping")
        try:
            worker = await asyncio.wait_for(self._idle.get(), timeout)
        except TimeoutError:
            raise Stopped(
                "time", f"every {self.name} worker stayed busy for the {timeout:g} s time limit"
            ) from None
        watch = asyncio.ensure_future(cancelled()) if cancelled is not None else None
        answer = loop.run_in_executor(self._threads, worker.call, fn, args)
        try:
            while not answer.done():
                waiting = [answer, watch] if watch is not None else [answer]
                await asyncio.wait(
                    waiting,
                    timeout=max(0.0, min(WATCH_PERIOD, deadline - loop.time())),
                    return_when=asyncio.FIRST_COMPLETED,
                )
                if answer.done():
                    break
                if self._closing:
                    worker.kill("closed")
                elif watch is not None and watch.done():
                    worker.kill("cancelled")
                elif loop.time() >= deadline:
                    worker.kill("time")
                elif memory_limit is not None and resident_bytes(worker.process.pid) > memory_limit:
                    worker.kill("memory")
                if worker.stop is not None:
                    await asyncio.wait([answer])
            return self._result(worker, answer, timeout, memory_limit)
        finally:
            if watch is not None:
                watch.cancel()
            await self._give_back(worker)

    def _result(self, worker: _Worker, answer, timeout: float, memory_limit: float | None) -> Any:
        error = answer.exception()
        if worker.stop is None and error is not None:
            # the job could not be sent (not picklable): ours, a bug
            if not isinstance(error, (EOFError, OSError)):
                worker.kill("bug")
                self.counts["bug"] += 1
                raise JobError(" ".join(f"{type(error).__name__}: {error}".split()), refused=False)
            worker.stop = "died"
        if worker.stop is not None:
            self.counts[worker.stop] += 1
            code = worker.process.exitcode
            raise Stopped(
                worker.stop,
                {
                    "time": f"took longer than the time limit of {timeout:g} s",
                    "memory": f"grew past its memory limit of {(memory_limit or 0) / 2**20:.0f} "
                    "MiB",
                    "cancelled": "cancelled: the client went away",
                    "closed": "the designer is stopping",
                    "died": f"its worker process ended by itself (exit code {code})",
                }[worker.stop],
            )
        kind, *rest = answer.result()
        if kind == "ok":
            self.counts["done"] += 1
            return rest[0]
        self.counts["refused" if kind == "refused" else "bug"] += 1
        raise JobError(rest[0], refused=kind == "refused", parameter=rest[1])

    async def _give_back(self, worker: _Worker) -> None:
        """Put the worker back, or a fresh one in its place if it was killed or grew too large."""
        if (
            worker.stop is None
            and not self._closing
            and resident_bytes(worker.process.pid) > self.recycle_above
        ):
            worker.kill("recycled")
            self.counts["recycled"] += 1
        idle = self._idle
        if idle is None:  # made by run(), which gave this worker out
            raise RuntimeError("a worker given back to a pool that gave none out")
        if worker.stop is None:
            idle.put_nowait(worker)
            return
        loop = asyncio.get_running_loop()
        await loop.run_in_executor(self._threads, worker.reap)
        # what the killed job had written
        folder = self._folder(worker.process.pid)
        await loop.run_in_executor(self._threads, shutil.rmtree, folder, True)
        if self._closing:
            return
        fresh = await loop.run_in_executor(self._threads, self._start)
        with self._lock:
            self._all[self._all.index(worker)] = fresh
        if self._closing:  # closed while the fresh one started
            fresh.kill("closed")
        idle.put_nowait(fresh)

    def close(self) -> None:
        """Kill every worker now (callable from a signal handler); running jobs raise
        :class:`Stopped`."""
        self._closing = True
        for worker in list(self._all):
            worker.kill("closed")

    def join(self) -> None:
        """Close, then wait for the workers to be gone."""
        self.close()
        for worker in list(self._all):
            worker.reap()
        self._threads.shutdown(wait=False, cancel_futures=True)


def _context(preload: Sequence[str]):
    """The fork server's context (a spawning one where there is none), with ``preload`` set
    before it starts."""
    if "forkserver" not in multiprocessing.get_all_start_methods():
        return multiprocessing.get_context("spawn")
    context = multiprocessing.get_context("forkserver")
    if preload:
        context.set_forkserver_preload(list(preload))
    return context


def _die_with_parent() -> None:
    """On Linux, ask for SIGKILL when the parent process ends (``prctl(PR_SET_PDEATHSIG)``)."""
    if sys.platform.startswith("linux"):
        try:
            ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG = 1
        except (OSError, AttributeError):
            pass


def _serve(conn, scratch: str, niceness: int) -> None:
    """A worker's loop: run each job received and send back ``("ok", result)``, ``("refused",
    message, parameter)`` or ``("bug", message, None)``, until the pipe closes."""
    _die_with_parent()
    if hasattr(os, "setpgrp"):
        os.setpgrp()  # a group of its own, which a kill ends whole
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    for name in ("SIGTERM", "SIGHUP"):
        if hasattr(signal, name):
            signal.signal(getattr(signal, name), signal.SIG_DFL)
    if niceness:
        os.nice(niceness)
    own = os.path.join(scratch, f"worker-{os.getpid()}")  # removed when the worker is killed
    tempfile.tempdir = own
    os.environ["TMPDIR"] = own
    warnings.simplefilter("ignore")  # a job's warnings are not the server's output
    Path(own).mkdir(parents=True, exist_ok=True)
    while True:
        try:
            fn, args = conn.recv()
        except (EOFError, OSError):
            return
        answer: tuple[str, Any] | tuple[str, str, str | None]
        try:
            answer = ("ok", fn(*args))
        except CurvefoldError as err:
            answer = ("refused", " ".join(str(err).split()), err.parameter)
        except MemoryError:
            answer = (
                "refused",
                "out of memory; lower samples, the number of tubes, cells or "
                "panels, or the formats",
                None,
            )
        except Exception as err:  # a bug: one line for the caller
            answer = ("bug", " ".join(f"{type(err).__name__}: {err}".split()), None)
        conn.send(answer)
