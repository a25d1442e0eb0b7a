"""Running the design atlas: every design of a grid, streamed in grid order.

:func:`sweep` yields every design's record and sketch (:mod:`curvefold.vault._atlas`) in
grid order while later designs are still running, holding a few chunks of results at
most, so a grid of any size runs in flat memory (the command line writes each record to
disk as it comes); :func:`run_atlas` keeps them all in an :class:`~curvefold.vault.Atlas`.
Designs run in this process, on a local Dask cluster of worker processes, or on an
existing Dask cluster; every way gives the same records, bit for bit (each design is
computed by the same code from the same numbers). Dask is optional (``pip install
'curvefold[dask]'``) and imported only when a cluster is used.
"""

from __future__ import annotations

import math
import pickle
from collections.abc import Callable, Generator, Iterator, Sequence
from contextlib import closing
from typing import Any

from ..kernel._errors import CurvefoldError, InputError
from ._arch import check_standing
from ._atlas import GRID_A, Atlas, AtlasGrid, Measure, Sketch, check_step, evaluate_design
from ._cluster import batched, cluster_plan, in_order
from ._cluster import client as cluster_client

__all__ = ["sweep", "run_atlas", "task_sizes", "CHUNK", "MIN_CHUNK", "LOAD_CHUNKS", "IN_FLIGHT"]

#: Designs per task sent to a cluster at most. Tasks shrink as the grid runs out (each takes
#: a 1/(2 × worker threads) share of the designs left, down to :data:`MIN_CHUNK`), so a
#: sweep has few tasks, each costing the client and scheduler milliseconds of CPU that the
#: workers share on a small machine, and ends on small ones, which keep every worker busy to
#: the end. A task holds whole rows (one arch each) unless a row is larger.
CHUNK = 400
#: Designs per task at least, where a row holds as many (the grid's last task may be smaller).
MIN_CHUNK = 40
#: Designs per task at most and at least when every design is analysed under load (an
#: :class:`~curvefold.mechanics.AtlasLoad`): a design then costs 0.03–0.9 CPU-s, not 0.7 ms, so a
#: task's milliseconds at the client and scheduler no longer count, and small last tasks keep
#: both workers busy to the end.
LOAD_CHUNKS = (40, 2)
#: Tasks queued or running per worker thread; results wait, in grid order, for at most
#: this many tasks per thread (the sweep's memory bound).
IN_FLIGHT = 3


def task_sizes(
    size: int, row: int, threads: int, *, most: int = CHUNK, least: int = MIN_CHUNK
) -> Iterator[int]:
    """Designs of each task of a sweep of ``size`` designs in rows of ``row``, for ``threads``
    worker threads.

    Guided self-scheduling: every task takes a 1/(2 × ``threads``) share of the designs
    left, within [``least``, ``most``] (default [:data:`MIN_CHUNK`, :data:`CHUNK`]), rounded
    to whole rows; a row larger than that is cut into equal parts, so that no task straddles
    two rows.

    Examples
    --------
    >>> list(task_sizes(1600, 40, 2))  # 40 × 40 on 2 workers: 12 tasks, 10 rows first, 1 row last
    [400, 320, 240, 160, 120, 80, 80, 40, 40, 40, 40, 40]
    >>> sizes = list(task_sizes(40_000, 200, 2))  # 200 × 200: two rows a task, the last row cut
    >>> len(sizes), sizes[:2], sizes[-4:], sum(sizes)
    (107, [400, 400], [50, 40, 40, 70], 40000)
    >>> list(task_sizes(7, 7, 2)), list(task_sizes(0, 5, 2))
    ([7], [])
    >>> sizes = list(task_sizes(400, 20, 2, most=40, least=2))  # 20 × 20 under load
    >>> len(sizes), sizes[:3], sizes[-6:]
    (21, [40, 40, 40], [4, 3, 2, 2, 2, 2])
    """
    done = 0
    while done < size:
        want = min(most, max(least, math.ceil((size - done) / (2 * threads))))
        offset = done % row
        if want >= row and offset == 0:
            n = round(want / row) * row
        else:  # an equal part of the row, or all that is left of it when less would remain
            n = min(math.ceil(row / math.ceil(row / want)), row - offset)
            n = row - offset if row - offset - n < least else n
        n = min(n, size - done)
        yield n
        done += n


def sweep(
    grid: AtlasGrid,
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: Callable[[int, int], Any] | None = None,
    sketch_step: int = 1,
) -> Generator[tuple[dict, Sketch | None], None, None]:
    """The record and sketch of every design of ``grid``, in grid order, as the designs finish.

    Parameters
    ----------
    grid : AtlasGrid
    workers : int, optional, keyword-only
        Processes of a local Dask cluster, 1 to the CPUs here; 1 runs in this process.
        Default: ``min(2, CPUs)`` for grids of at least :data:`LOCAL_CLUSTER_FROM` designs
        when Dask is installed, this process otherwise. Worker processes are spawned: call
        this under ``if __name__ == "__main__":`` in a script.
    scheduler : str, optional, keyword-only
        Address of a running Dask scheduler (``"tcp://host:8786"``): its workers run the
        designs. They need the same version of curvefold as this process (checked). Not
        with ``workers``.
    progress : callable, optional, keyword-only
        ``progress(done, total)``, called with 0 first and after every design.
    sketch_step : int, keyword-only
        Sketch the designs of every k-th row and column only (those a figure of
        :meth:`~curvefold.vault.Atlas.every` ``(k)`` draws); the others' sketch is None.
        Default 1: every design.

    Yields
    ------
    record : dict
        Keys :attr:`AtlasGrid.fields <curvefold.vault.AtlasGrid.fields>`:
        :data:`~curvefold.vault._atlas.FIELDS` and the columns of the grid's ``load``.
    sketch : Sketch or None
        None for an invalid design.

    Notes
    -----
    Designs go to the cluster in tasks of :func:`task_sizes`, which shrink from
    :data:`CHUNK` designs as the grid runs out, at most :data:`IN_FLIGHT` tasks per
    worker thread at a time; a finished task waits until the ones before it
    are handed out, so memory stays bounded whatever the grid's size. A cluster started
    here is closed when the iterator ends, is closed, or raises (close it with
    :func:`contextlib.closing` when stopping early). Connection errors and a version
    mismatch raise :class:`InputError` at the first ``next()``.

    Examples
    --------
    >>> results = list(sweep(AtlasGrid.of([0.75], [0.0, 0.3], samples=41, tubes=2), workers=1))
    >>> [(record["row"], record["valid"]) for record, _ in results]
    [(0, True), (1, True)]
    >>> sweep([0.75, 0.3])
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: grid must be an AtlasGrid (AtlasGrid.of(p_xy_values,
    a_values, ...)), got list
    """
    if not isinstance(grid, AtlasGrid):
        raise InputError(
            "grid must be an AtlasGrid (AtlasGrid.of(p_xy_values, a_values, ...)), "
            f"got {type(grid).__name__}"
        )
    if progress is not None and not callable(progress):
        raise InputError(
            f"progress must be a callable progress(done, total) or None, got {progress!r}"
        )
    check_step(sketch_step)
    return _sweep(grid, *cluster_plan(grid.size, workers, scheduler), progress, sketch_step)


def _sweep(
    grid: AtlasGrid,
    workers: int,
    scheduler: str | None,
    progress: Callable[[int, int], Any] | None,
    step: int,
) -> Generator[tuple[dict, Sketch | None], None, None]:
    design = grid.shared
    total, done = grid.size, 0
    if progress is not None:
        progress(0, total)
    with cluster_client(workers, scheduler) as client:
        if client is None:
            arches: dict = {}  # one row's arch, shared by the designs handed out one by one
            chunks: Generator[list, None, None] = (
                _evaluate_chunk([point], design, step, arches) for point in grid.points()
            )
        else:
            threads = max(1, sum(client.nthreads().values()))
            most, least = (CHUNK, MIN_CHUNK) if grid.load is None else LOAD_CHUNKS
            sizes = task_sizes(total, grid.shape[1], threads, most=most, least=least)
            submit = lambda points: client.submit(
                _evaluate_packed, points, design, step, pure=False
            )  # noqa: E731
            chunks = _unpacked(in_order(submit, batched(grid.points(), sizes), IN_FLIGHT * threads))
        with closing(chunks):  # closed before the client, when the sweep stops early
            for results in chunks:
                for result in results:
                    done += 1
                    if progress is not None:
                        progress(done, total)
                    yield result


def _evaluate_chunk(
    points: Sequence[tuple[int, int, float, float]],
    design: dict,
    step: int = 1,
    arches: dict | None = None,
) -> list[tuple[dict, Sketch | None]]:
    """(record, sketch) of several grid points, in order (sketches on every ``step``-th row and
    column). ``arches`` keeps the last row's arch across calls."""
    out, arches = [], {} if arches is None else arches
    for row, col, a, p in points:
        if row not in arches:  # the row's arch, once: its designs differ in p_xy alone
            arches.clear()
            arches[row] = _row_arch(a, design)
        record, sketch = evaluate_design(
            a, p, **design, sketch=row % step == 0 and col % step == 0, arch=arches[row]
        )
        out.append(({"row": row, "col": col} | record, sketch))
    return out


def _evaluate_packed(
    points: Sequence[tuple[int, int, float, float]], design: dict, step: int
) -> bytes:
    """:func:`_evaluate_chunk` as one pickle, the task a worker runs. Dask would serialize each
    pair of a list apart: 11 ms of the worker's CPU for 400 designs and 4.7 ms of the
    client's, against 2.3 and 1.8."""
    return pickle.dumps(_evaluate_chunk(points, design, step), protocol=pickle.HIGHEST_PROTOCOL)


def _unpacked(
    packed: Generator[bytes, None, None],
) -> Generator[list[tuple[dict, Sketch | None]], None, None]:
    """The results of :func:`_evaluate_packed` tasks, as they come; closing it closes ``packed``."""
    with closing(packed):
        for blob in packed:
            yield pickle.loads(blob)


def _row_arch(a: float, design: dict) -> tuple | None:
    """The arch and crease of the designs of one ``a`` (None where there is none: each design
    records why)."""
    from ._assembly import VaultDesign, arch_crease

    shape = VaultDesign()  # the grid's vaults take its panels and radius
    try:
        return arch_crease(
            check_standing(GRID_A.check(a)),
            shape.panels,
            shape.radius,
            design["fold_angle"],
            design["samples"],
        )
    except CurvefoldError:
        return None


def run_atlas(
    p_xy_values: Sequence[float],
    a_values: Sequence[float],
    *,
    width: float = 0.08,
    fold_angle: float = 90.0,
    tubes: int | None = None,
    samples: int = 201,
    load: Measure | None = None,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: Callable[[int, int], Any] | None = None,
) -> Atlas:
    """Build the vault of every (p_xy, a) of a grid and record its metrics, in memory.

    For grids too large to hold, iterate :func:`sweep` instead (the command line does).

    Parameters
    ----------
    p_xy_values : (C,) array_like
        Section proportions w_R(0)/w_L(0): the columns.
    a_values : (R,) array_like
        Torsion amplitudes: the rows. a ≥ :data:`curvefold.vault.A_MAX` has no standing arch
        and is recorded as invalid.
    width, fold_angle, tubes, samples : keyword-only
        Shared :class:`~curvefold.vault.VaultDesign` parameters (checked once, by
        :meth:`~curvefold.vault.AtlasGrid.of`).
    load : keyword-only
        More columns of every design, such as the mechanics of
        :class:`curvefold.mechanics.AtlasLoad` (:class:`~curvefold.vault._atlas.Measure`).
    workers, scheduler, progress : keyword-only
        Where the designs run and a progress callback, as for :func:`sweep`.

    Returns
    -------
    Atlas
        Records in grid order (row-major, rows = a), whatever order designs finish in.

    Examples
    --------
    A grid point past the arch family is recorded, not raised:

    >>> atlas = run_atlas([0.75], [1.5], workers=1)
    >>> atlas.records[0]["valid"], atlas.records[0]["error"]
    (False, 'ConvergenceError')
    """
    grid = AtlasGrid.of(
        p_xy_values,
        a_values,
        width=width,
        fold_angle=fold_angle,
        tubes=tubes,
        samples=samples,
        load=load,
    )
    return Atlas.from_results(
        grid, sweep(grid, workers=workers, scheduler=scheduler, progress=progress)
    )
