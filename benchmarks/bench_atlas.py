"""The design atlas: throughput of a sweep, and the memory of a large one.

Throughput: a 40 × 40 grid (p_xy in [0.5, 1.5] × a in [0, 1.2], 1600 designs, width 0.08,
201 samples per crease) run once each way, from the call to the last record:

- serial: ``workers=1``, in this process;
- process pool: the sweep as the atlas ran it before Dask (a ``ProcessPoolExecutor`` of 2
  processes, interleaved chunks, every result held until the end), what a user would write;
- Dask, local cluster: ``workers=2``, starting and closing the cluster included;
- Dask, running cluster: ``scheduler=`` the address of a 2-process LocalCluster started
  beforehand (what a sweep on one's own cluster costs once it is up).

Every way must return the same records (compared exactly); the speed-ups are printed as
measured, with the machine's load average (the runs are whole programs, timed once each).

Memory (``python benchmarks/bench_atlas.py --memory``, several minutes): the peak resident
memory of the process that runs the sweep alone, and ``curvefold atlas`` (records streamed
to disk, figure thinned to every k-th row and column), for a 20 × 20 and a 200 × 200 grid
on 2 workers.
"""

from __future__ import annotations

import argparse
import logging
import os
import subprocess
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed

import numpy as np

from _bench import SummaryRow, markdown_table, summary_table, verdict

SIDE = 40
WIDTH = 0.08
SAMPLES = 201
WORKERS = 2
MEMORY_SIDES = (20, 200)


def _grid():
    from curvefold.vault.atlas import AtlasGrid

    return AtlasGrid.of(np.linspace(0.5, 1.5, SIDE), np.linspace(0.0, 1.2, SIDE), width=WIDTH, samples=SAMPLES)


def _process_pool(grid) -> list[dict]:
    """The atlas's sweep before Dask: a process pool, interleaved chunks, all results held, sorted at the end."""
    from curvefold.vault.atlas import _evaluate_chunk

    points = list(grid.points())
    count = min(len(points), WORKERS * 16)
    with ProcessPoolExecutor(max_workers=WORKERS) as pool:
        futures = [pool.submit(_evaluate_chunk, points[k::count], grid.shared) for k in range(count)]
        results = [pair for future in as_completed(futures) for pair in future.result()]
    results.sort(key=lambda pair: (pair[0]["row"], pair[0]["col"]))
    return [record for record, _ in results]


def _records(grid, **where) -> list[dict]:
    from curvefold.vault.atlas import sweep

    return [record for record, _ in sweep(grid, **where)]


SERIAL = "serial (workers=1)"
POOL = f"process pool, {WORKERS} processes"
LOCAL = f"Dask, local cluster (workers={WORKERS}, start included)"
RUNNING = f"Dask, running cluster ({WORKERS} workers, scheduler=)"


def run() -> list[SummaryRow]:
    import distributed

    from curvefold.vault.atlas import AtlasGrid

    grid = _grid()
    times: dict[str, float] = {}
    records: dict[str, list[dict]] = {}

    def once(name: str, fn) -> None:
        t0 = time.perf_counter()
        records[name] = fn()
        times[name] = time.perf_counter() - t0

    once(SERIAL, lambda: _records(grid, workers=1))
    once(POOL, lambda: _process_pool(grid))
    once(LOCAL, lambda: _records(grid, workers=WORKERS))
    with distributed.LocalCluster(n_workers=WORKERS, threads_per_worker=1, dashboard_address=":0", silence_logs=logging.ERROR) as cluster:
        _records(AtlasGrid.of([0.75], [0.3]), scheduler=cluster.scheduler_address)  # the workers load curvefold
        once(RUNNING, lambda: _records(grid, scheduler=cluster.scheduler_address))

    serial, pool, local, running = (times[k] for k in (SERIAL, POOL, LOCAL, RUNNING))
    same = all(r == records[SERIAL] for r in records.values())
    print(f"atlas: {SIDE} × {SIDE} designs, width {WIDTH}, {SAMPLES} samples; one run each (load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs)")
    rows = [(name, f"{t:.2f}", f"{grid.size / t:.0f}", f"{serial / t:.2f}") for name, t in times.items()]
    print(markdown_table(["run", "time [s]", "designs/s", "speed-up vs serial"], rows))
    print(f"valid designs: {sum(r['valid'] for r in records[SERIAL])} of {grid.size}; records identical in every run: {same}")
    return [
        SummaryRow("atlas", f"{SIDE} × {SIDE} designs, running Dask cluster of {WORKERS} workers (serial {serial:.1f} s, process pool {pool:.1f} s)",
                   f"{running:.1f} s ({serial / running:.2f}× serial, {pool / running:.2f}× the process pool)", "records identical to serial", verdict(same)),
        SummaryRow("atlas", f"{SIDE} × {SIDE} designs, local Dask cluster (start included)", f"{local:.1f} s ({serial / local:.2f}× serial)", "—", "—"),
    ]


_PEAK = """
import resource, sys, time
import numpy as np
from curvefold.app.outputs import write_atlas
from curvefold.vault.atlas import AtlasGrid, sweep
side, what, out = int(sys.argv[1]), sys.argv[2], sys.argv[3]
p_xy, a = np.linspace(0.5, 1.5, side), np.linspace(0.0, 1.2, side)
t0 = time.perf_counter()
if what == "sweep":
    valid = sum(record["valid"] for record, _ in sweep(AtlasGrid.of(p_xy, a, width={width}, samples={samples}), workers={workers}))
else:
    valid = write_atlas(p_xy, a, out=out, force=True, width={width}, samples={samples}, workers={workers}, show_progress=False)["valid"]
print(time.perf_counter() - t0, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, valid)
"""


def memory() -> None:
    """Peak resident memory of the process running the atlas (its workers not counted), per grid size.

    Two programs: the sweep alone (records handed out and dropped) and ``curvefold atlas``
    (records written to disk, the figure drawn).
    """
    import tempfile

    script = _PEAK.format(width=WIDTH, samples=SAMPLES, workers=WORKERS)
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for what in ("sweep", "curvefold atlas"):
            for side in MEMORY_SIDES:
                done = subprocess.run([sys.executable, "-c", script, str(side), what, f"{folder}/atlas-{side}"], capture_output=True, text=True, check=True)
                seconds, peak, valid = done.stdout.split()
                rows.append((what, f"{side} × {side}", f"{side * side}", valid, f"{float(seconds):.0f}", f"{float(peak):.0f}", f"{os.getloadavg()[0]:.1f}"))
                print(" ".join(rows[-1]), flush=True)
    print(markdown_table(["program", "grid", "designs", "valid", "time [s]", "peak RSS of the client [MiB]", "load average"], rows))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--memory", action="store_true", help=f"measure the client's peak memory for {' and '.join(f'{s} × {s}' for s in MEMORY_SIDES)} grids instead")
    if parser.parse_args().memory:
        memory()
    else:
        print("\n" + summary_table(run()))


if __name__ == "__main__":
    main()
