"""The processes a sweep of the atlas runs on: this one, a local Dask cluster, or a running one.

:func:`cluster_plan` decides from the grid's size and the user's ``workers`` and
``scheduler``; :func:`client` opens the Dask client (None: this process) and checks that a
running cluster's workers have this version of curvefold; :func:`in_order` hands tasks to
it a window at a time and gives their results back in order. Dask is optional
(``pip install 'curvefold[dask]'``) and imported only when a cluster is used.
"""

from __future__ import annotations

import importlib.util
import logging
import os
from collections import deque
from collections.abc import Callable, Generator, Iterable, Iterator, Mapping
from contextlib import contextmanager
from itertools import islice
from types import MappingProxyType
from typing import Any

from ..kernel._errors import InputError
from ..kernel._validate import Spec
from ..kernel._version import VERSION

__all__ = [
    "LOCAL_CLUSTER_FROM",
    "CLUSTER_SETTINGS",
    "batched",
    "client",
    "cluster_plan",
    "in_order",
    "local_cluster",
    "worker_environment",
    "workers_spec",
]

#: With ``workers=None``, grids of at least this many designs run on a local cluster. Starting
#: one, loading curvefold in its workers and closing it takes 1.2–2.6 s on 2 CPUs, and 2
#: workers save at most half of the 0.7 ms a design takes at 201 samples
#: (benchmarks/bench_atlas.py): the cluster pays from some 4000–7000 designs.
LOCAL_CLUSTER_FROM = 5000

#: Dask settings of the local cluster (benchmarks/bench_atlas.py measures each):
#:
#: - no profiler (stack samples every 10 ms for a dashboard nobody looks at) and the event
#:   loop's health check once a second instead of every 20 ms: an idle cluster of 2 spends
#:   0.04–0.05 instead of 0.12–0.15 CPU-s a second;
#: - the workers' C heap trimmed only when 4 MiB lie free at its top. Dask's nanny sets
#:   glibc's threshold to 64 KiB, which also fixes glibc's mmap threshold at 128 KiB: a
#:   design's arrays of a few hundred KiB are then mapped and faulted in afresh each time.
#:   Two workers took 62,900–65,800 page faults for 1600 designs and 1.53–1.61 CPU-s, against
#:   1,680 and 1.34–1.45 at 4 MiB (one process alone: 51,000 at 64 KiB, 4,000 with glibc's
#:   default, 1,650 at 4 MiB); the largest worker of a 200 × 200 atlas stays at 70 MiB.
CLUSTER_SETTINGS: Mapping[str, Any] = MappingProxyType(
    {
        "distributed.worker.profile.enabled": False,
        "distributed.admin.tick.interval": "1s",
        "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": 4 * 2**20,
    }
)


_NANNY_ENVIRON = "distributed.nanny.pre-spawn-environ."


def worker_environment(settings: Mapping[str, Any] = CLUSTER_SETTINGS) -> dict[str, str]:
    """The environment variables that give workers started with ``dask worker`` the Dask
    ``settings``.

    A ``pre-spawn-environ`` setting is the variable itself (the name Dask derives from a
    ``DASK_…__PRE_SPAWN_ENVIRON__…`` variable is in lower case, which glibc does not read);
    any other is Dask's ``DASK_`` form of its key.

    Examples
    --------
    >>> " ".join(f"{k}={v}" for k, v in worker_environment().items())
    'DASK_DISTRIBUTED__WORKER__PROFILE__ENABLED=False DASK_DISTRIBUTED__ADMIN__TICK__INTERVAL=1s
    MALLOC_TRIM_THRESHOLD_=4194304'
    """

    def name(key: str) -> str:
        return (
            key.removeprefix(_NANNY_ENVIRON)
            if key.startswith(_NANNY_ENVIRON)
            else "DASK_" + key.upper().replace(".", "__").replace("-", "_")
        )

    return {name(key): str(value) for key, value in settings.items()}


def _cpus() -> int:
    """CPUs this process may run on."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1


def workers_spec() -> Spec:
    """The ``workers`` parameter: processes of the local cluster, at most one per CPU here.

    Examples
    --------
    >>> workers_spec().check(1)
    1
    >>> workers_spec().check(0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: workers must be an integer in [1, ...this process may use),
    got 0
    """
    cpus = _cpus()
    return Spec(
        "workers",
        "integer",
        None,
        f"[1, {cpus}]",
        help="processes of the local cluster (1: this process)",
        why=f"the {cpus} CPU{'s' * (cpus != 1)} this process may use",
    )


def cluster_plan(size: int, workers: int | None, scheduler: str | None) -> tuple[int, str | None]:
    """(local processes, scheduler address): (1, None) runs in this process.

    Examples
    --------
    >>> (
    ...     cluster_plan(10, None, None),
    ...     cluster_plan(1, 2, None),
    ... )  # a small grid; one design needs one process
    ((1, None), (1, None))
    >>> cluster_plan(10, 0, None)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: workers must be an integer in [1, ...this process may use),
    got 0
    """
    if scheduler is not None:
        if workers is not None:
            raise InputError(
                "workers sizes a local cluster; the cluster at scheduler "
                f"{scheduler!r} has its own workers, got workers = {workers!r}"
            )
        if not isinstance(scheduler, str) or not scheduler.strip():
            raise InputError(
                "scheduler must be the address of a Dask scheduler such as "
                f"'tcp://host:8786', got {scheduler!r}"
            )
        _require_dask(f"scheduler {scheduler!r}")
        return 0, scheduler.strip()
    if workers is None:
        workers = (
            min(2, _cpus())
            if size >= LOCAL_CLUSTER_FROM and importlib.util.find_spec("distributed")
            else 1
        )
    workers = min(workers_spec().check(workers), size)
    if workers > 1:
        _require_dask(f"workers = {workers}")
    return workers, None


def _require_dask(what: str) -> None:
    if importlib.util.find_spec("distributed") is None:
        raise ModuleNotFoundError(
            f"{what} runs on Dask, which is not installed; install it "
            "with: pip install 'curvefold[dask]'"
        )


def batched(items: Iterable, sizes: Iterable[int]) -> Iterator[list]:
    """Lists of consecutive items of any iterable, of the given sizes, read as they are needed.

    Stops when either runs out (the last list then shorter).

    Examples
    --------
    >>> list(batched(range(5), [2, 2, 2])), list(batched(range(5), [1])), list(batched([], [2]))
    ([[0, 1], [2, 3], [4]], [[0]], [])
    """
    items = iter(items)
    for size in sizes:
        if not (batch := list(islice(items, size))):
            return
        yield batch


def in_order(
    submit: Callable[[Any], Any], tasks: Iterable, window: int
) -> Generator[Any, None, None]:
    """The results of ``submit(task)`` (a future) for every task, in order, ``window`` futures at a
    time.

    The oldest future is waited for while the others run; when it is done the next task is
    submitted, so no more than ``window`` results (and the one handed out) are ever held.

    Examples
    --------
    >>> from concurrent.futures import ThreadPoolExecutor
    >>> with ThreadPoolExecutor(2) as pool:
    ...     list(in_order(lambda t: pool.submit(pow, t, 2), range(5), window=2))
    [0, 1, 4, 9, 16]
    >>> list(in_order(None, [], window=2))  # no tasks: nothing submitted
    []
    """
    tasks = iter(tasks)
    pending = deque(submit(t) for t in islice(tasks, window))
    while pending:
        result = pending[0].result()
        # the last reference: a cluster frees the result (and forgets the futures left when closed)
        pending.popleft()
        pending.extend(submit(t) for t in islice(tasks, 1))
        yield result


@contextmanager
def client(workers: int, scheduler: str | None) -> Iterator[Any]:
    """A Dask client of ``scheduler`` or of a local cluster of ``workers`` processes; None for this
    process.

    Dask's own logging is silenced meanwhile (its scheduler runs in this process for a local
    cluster): what goes wrong reaches the caller as an exception, and stderr keeps to one
    line (an interrupted sweep otherwise logs the keys it could not gather).

    Examples
    --------
    >>> with client(1, None) as c:  # one process: no cluster, no Dask
    ...     c is None
    True
    """
    if scheduler is None and workers <= 1:
        yield None
        return
    import distributed

    dask_log = logging.getLogger("distributed")
    level = dask_log.level
    dask_log.setLevel(logging.CRITICAL)
    try:
        if scheduler is not None:
            with _scheduler_client(scheduler) as client:
                yield client
        else:
            with (
                local_cluster(workers) as cluster,
                distributed.Client(cluster, set_as_default=False) as client,
            ):
                yield client
    finally:
        dask_log.setLevel(level)


@contextmanager
def local_cluster(workers: int, settings: Mapping[str, Any] = CLUSTER_SETTINGS) -> Iterator[Any]:
    """A Dask LocalCluster of ``workers`` single-thread processes under the Dask ``settings``.

    This process's environment is left as it was: Dask's nanny writes its
    ``pre-spawn-environ`` into ``os.environ`` to hand it to the worker it spawns and leaves
    it there, where it would outrank the settings of the next cluster started here (an
    environment variable overrides Dask's configuration) and reach every later subprocess.
    """
    import dask
    import distributed

    before = dict(os.environ)
    try:
        with (
            dask.config.set(settings),
            distributed.LocalCluster(
                n_workers=workers,
                threads_per_worker=1,
                processes=True,
                dashboard_address=":0",
                silence_logs=logging.CRITICAL,
            ) as cluster,
        ):
            yield cluster
    finally:
        for key in set(os.environ) - set(before):
            del os.environ[key]
        os.environ.update(
            {key: value for key, value in before.items() if os.environ.get(key) != value}
        )


def _scheduler_client(scheduler: str) -> Any:
    """A client of the running cluster at ``scheduler``, checked (see :func:`_check_workers`)."""
    import distributed

    try:  # first the address alone: a client made from a malformed one hangs when it is freed
        scheme = distributed.comm.parse_address(distributed.comm.resolve_address(scheduler))[0]
    except ValueError as err:
        raise InputError(
            "scheduler must be a Dask scheduler address such as 'tcp://host:8786', "
            f"got {scheduler!r} ({err})"
        ) from None
    except OSError as err:
        raise InputError(f"scheduler {scheduler!r}: cannot resolve the host ({err})") from None
    if scheme == "inproc":
        raise InputError(
            "scheduler must be a network address such as 'tcp://host:8786' "
            f"(inproc:// names a scheduler inside one process), got {scheduler!r}"
        )
    try:
        client = distributed.Client(scheduler, set_as_default=False)
    except OSError as err:  # refused or timed out
        raise InputError(
            f"scheduler {scheduler!r}: cannot connect to a Dask scheduler there ({err})"
        ) from None
    try:
        _check_workers(client, scheduler)
    except BaseException:
        client.close()
        raise
    return client


def _check_workers(client: Any, scheduler: str) -> None:
    """Raise unless the cluster has a worker and every worker runs this version of curvefold."""
    from dask.config import get
    from dask.utils import parse_timedelta

    timeout = parse_timedelta(get("distributed.comm.timeouts.connect"))
    try:
        client.wait_for_workers(1, timeout=timeout)
    except TimeoutError:
        raise InputError(f"scheduler {scheduler!r} has no worker (waited {timeout:g} s)") from None
    ours = VERSION
    found = client.run(_curvefold_version, on_error="return")
    wrong = {w: v for w, v in sorted(found.items()) if v != ours}
    if wrong:
        worker, theirs = next(iter(wrong.items()))
        have = f"curvefold {theirs}" if isinstance(theirs, str) else "no curvefold"
        raise InputError(
            f"scheduler {scheduler!r}: every worker needs curvefold {ours}, as "
            f"here; {len(wrong)} of {len(found)} differ, e.g. {worker} has {have}"
        )


def _curvefold_version() -> str:
    """The version of curvefold installed where this runs (on a worker)."""
    return VERSION
