"""The design atlas: throughput and scaling of a sweep, and the CPU and memory of a large one.

Throughput: a 40 × 40 grid (p_xy in [0.5, 1.5] × a in [0, 1.2], 1600 designs, width 0.08,
201 samples per crease), from the call to the last record:

- serial: ``workers=1``, in this process (what the other ways are measured against), best of 3;
  every way sketches the designs ``curvefold atlas`` draws, every k-th row and column;
- process pool: the sweep as the atlas ran it before Dask (a ``ProcessPoolExecutor`` of 2
  processes, interleaved chunks, every result held until the end);
- Dask, local cluster: ``workers=2``, starting and closing the cluster included;
- Dask, running cluster of 1, 2 and 4 workers: ``scheduler=`` the address of a cluster
  started as one starts one's own, a ``dask scheduler`` process and a ``dask worker`` process
  of single-thread workers, under the environment the README gives
  (``curvefold.vault._cluster.worker_environment``), and one of 2 with Dask's defaults; every
  worker warmed by one design (its imports), then the sweep, best of 3. The serial sweeps
  alternate with those of the cluster of 2, so both see the machine alike. Wall time, the CPU
  seconds of a sweep in the workers, the scheduler and this process, and the workers' page
  faults a sweep.

What a cluster of 2 spends idle, a second, with Dask's defaults and with the atlas's settings,
CPU seconds of its workers and of this process (the scheduler's) over 3 s.

Every way must return the same records (compared exactly); the speed-ups are printed as
measured, with the machine's load average and how many CPUs' worth of work two busy processes
got from it just after (``_bench.parallel_throughput``: 2 on two free CPUs, 1.3–2 measured on a
shared host), whose inverse is the best time / serial two workers could reach then.
Target: two workers of a running cluster in at most 0.6× the serial time.

Mechanics (``python benchmarks/bench_atlas.py --load [--load-side N]``, a few minutes): the
atlas with ``--load`` (polypropylene 1 mm under its own weight, the default model: 41 samples,
one element across) on a 20 × 20 grid of the same ranges at 41 samples: the CPU seconds per
design of the serial sweep (target ≤ 0.5) and the costliest design (24 tubes); a local Dask
cluster of two workers, its start included, against the serial sweep (target ≤ 0.6×, wall
time; the records compared exactly). And the accuracy of that model on a few designs of the
grid: its buckling factor, deflection and mass against the same model at 161 samples, and
against four elements across at 81 samples (where a strip can bend across its width).

Memory and CPU (``python benchmarks/bench_atlas.py --memory``, several minutes):
``curvefold atlas --workers 2`` (records streamed to disk, figure of every k-th row and
column) for a 24 × 24 and a 200 × 200 grid, each in a fresh process on a local cluster of 2
(the default from 5000 designs, whose scheduler lives in the calling process): its CPU
seconds, its workers' included, and the peak resident memory of the process and of its
largest worker. 24 × 24 is the largest grid whose figure draws every design, 576 views
against the 200 × 200's 23 × 23, so the two differ in the designs streamed, not in the
figure or the processes. Target: ≤ 60 CPU-s for 200 × 200, and the same memory for both.
"""

from __future__ import annotations

import argparse
import math
import os
import resource
import subprocess
import sys
import time
from collections.abc import Iterator, Mapping
from concurrent.futures import ProcessPoolExecutor, as_completed
from contextlib import contextmanager

import numpy as np
from _bench import SummaryRow, markdown_table, parallel_throughput, summary_table, verdict

from curvefold.figures._atlas import MAX_VIEWS
from curvefold.vault._cluster import CLUSTER_SETTINGS, local_cluster, worker_environment

SIDE = 40
WIDTH = 0.08
SAMPLES = 201
WORKERS = 2
SCALING = (1, 2, 4)
REPEATS = 3  # sweeps timed for the serial run and each running cluster, best kept
TARGET_TWO = 0.6  # two running workers / serial, wall time
MEMORY_SIDES = (MAX_VIEWS, 200)  # the first: the largest grid whose figure draws every design
TARGET_CPU = 60.0  # CPU seconds of the 200 × 200 atlas


def _grid():
    from curvefold.vault import AtlasGrid

    return AtlasGrid.of(
        np.linspace(0.5, 1.5, SIDE), np.linspace(0.0, 1.2, SIDE), width=WIDTH, samples=SAMPLES
    )


def _process_pool(grid) -> list[dict]:
    """The atlas's sweep before Dask: a process pool, interleaved chunks, all results held,
    sorted at the end."""
    from curvefold.vault._sweep import _evaluate_chunk

    points = list(grid.points())
    count = min(len(points), WORKERS * 16)
    with ProcessPoolExecutor(max_workers=WORKERS) as pool:
        futures = [
            pool.submit(_evaluate_chunk, points[k::count], grid.shared) for k in range(count)
        ]
        results = [pair for future in as_completed(futures) for pair in future.result()]
    results.sort(key=lambda pair: (pair[0]["row"], pair[0]["col"]))
    return [record for record, _ in results]


def _records(grid, **where) -> list[dict]:
    """The records of a sweep, sketching the designs ``curvefold atlas`` draws (every k-th row
    and column)."""
    from curvefold.figures._atlas import view_step
    from curvefold.vault import sweep

    return [record for record, _ in sweep(grid, sketch_step=view_step(grid.shape), **where)]


SERIAL = "serial (workers=1)"
POOL = f"process pool, {WORKERS} processes"
LOCAL = f"Dask, local cluster (workers={WORKERS}, start included)"


def _running(workers: int, defaults: bool = False) -> str:
    return (
        f"Dask, running cluster of {workers} worker{'s' * (workers != 1)} "
        f"(scheduler=){', Dask defaults' * defaults}"
    )


def _warm() -> None:
    """A worker's first design, which imports what the designs use."""
    from curvefold.vault import evaluate_design

    evaluate_design(0.3, 0.75, width=WIDTH, samples=SAMPLES)


@contextmanager
def _cluster(workers: int, settings: Mapping) -> Iterator[tuple]:
    """(cluster, client) of a local cluster of ``workers`` single-thread processes started here
    under Dask ``settings``."""
    import distributed

    with local_cluster(workers, settings) as cluster, distributed.Client(cluster) as client:
        yield cluster, client


@contextmanager
def _running_cluster(workers: int, env: Mapping[str, str]) -> Iterator:
    """A client of a cluster started as one's own: ``dask scheduler`` and ``dask worker`` of
    ``workers`` single-thread workers under ``env``."""
    import tempfile

    import distributed

    dask = [os.path.join(os.path.dirname(sys.executable), "dask")]
    plain = {
        k: v
        for k, v in os.environ.items()
        if k not in worker_environment() and not k.startswith("DASK_")
    }
    # this module's functions
    plain["PYTHONPATH"] = os.pathsep.join(
        filter(None, [os.path.dirname(os.path.abspath(__file__)), plain.get("PYTHONPATH")])
    )
    with tempfile.TemporaryDirectory() as folder:
        common = ["--scheduler-file", f"{folder}/scheduler.json", "--no-dashboard"]
        started = [
            subprocess.Popen(
                [*dask, "scheduler", "--host", "127.0.0.1", *common],
                env=plain,
                stderr=subprocess.DEVNULL,
            )
        ]
        try:
            started.append(
                subprocess.Popen(
                    [*dask, "worker", "--nworkers", str(workers), "--nthreads", "1", *common],
                    env=plain | dict(env),
                    stderr=subprocess.DEVNULL,
                )
            )
            with distributed.Client(
                scheduler_file=f"{folder}/scheduler.json", timeout=60
            ) as client:
                client.wait_for_workers(workers, timeout=60)
                yield client
                client.shutdown()
        finally:
            for process in started[::-1]:
                if process.poll() is None:
                    process.terminate()
                process.wait(30)


def _workers_cpu(client) -> float:
    """CPU seconds the cluster's worker processes have spent so far."""
    return sum(client.run(time.process_time).values())


def _faults() -> int:
    """Minor page faults of this process so far."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt


def _workers_faults(client) -> int:
    """Page faults the cluster's worker processes have taken so far."""
    return sum(client.run(_faults).values())


def _idle(settings: Mapping, seconds: float = 3.0) -> tuple[float, float]:
    """CPU seconds a second that an idle local cluster of 2 spends under ``settings``: (workers,
    this process)."""
    with _cluster(WORKERS, settings) as (_, client):
        time.sleep(1.0)  # past the start
        workers, here = _workers_cpu(client), time.process_time()
        time.sleep(seconds)
        return (_workers_cpu(client) - workers) / seconds, (time.process_time() - here) / seconds


def run() -> list[SummaryRow]:
    grid = _grid()
    times: dict[str, float] = {SERIAL: math.inf}  # the first row
    cpu: dict[str, str] = {}
    faulted: dict[str, str] = {}  # page faults of the workers a sweep
    records: dict[str, list[dict]] = {}

    def once(name: str, fn) -> None:
        t0 = time.perf_counter()
        records[name] = fn()
        times[name] = min(times.get(name, math.inf), time.perf_counter() - t0)

    once(POOL, lambda: _process_pool(grid))
    once(LOCAL, lambda: _records(grid, workers=WORKERS))
    serial_cpu = []
    for workers, defaults in (
        [(WORKERS, False)] + [(w, False) for w in SCALING if w != WORKERS] + [(WORKERS, True)]
    ):
        name = _running(workers, defaults)
        with _running_cluster(workers, {} if defaults else worker_environment()) as client:
            address = client.scheduler.address
            client.run(_warm)
            before, faults, c0, spent = (
                _workers_cpu(client),
                _workers_faults(client),
                time.process_time(),
                0.0,
            )
            scheduler = client.run_on_scheduler(time.process_time)
            for _ in range(REPEATS):
                if name == _running(WORKERS):  # the serial sweeps alternate with these
                    s0 = time.process_time()
                    once(SERIAL, lambda: _records(grid, workers=1))
                    serial_cpu.append(time.process_time() - s0)
                    spent += serial_cpu[-1]
                once(name, lambda address=address: _records(grid, scheduler=address))
            worker_cpu = (_workers_cpu(client) - before) / REPEATS
            scheduler = (client.run_on_scheduler(time.process_time) - scheduler) / REPEATS
            cpu[name] = (
                f"{worker_cpu:.2f} + {scheduler:.2f} + "
                f"{(time.process_time() - c0 - spent) / REPEATS:.2f}"
            )
            faulted[name] = f"{(_workers_faults(client) - faults) / REPEATS:,.0f}"
    cpu[SERIAL] = f"{min(serial_cpu):.2f}"
    throughput = parallel_throughput(WORKERS)
    idle = {"Dask's defaults": _idle({}), "the atlas's": _idle(CLUSTER_SETTINGS)}

    serial = times[SERIAL]
    two = times[_running(2)]
    same = all(r == records[SERIAL] for r in records.values())
    print(
        f"atlas: {SIDE} × {SIDE} designs, width {WIDTH}, {SAMPLES} samples; serial and running "
        f"clusters best of {REPEATS}, the others one run (load average "
        f"{os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs; {WORKERS} busy processes got "
        f"{throughput:.2f} CPUs' worth of work)"
    )
    rows = [
        (
            name,
            f"{t:.2f}",
            cpu.get(name, "—"),
            faulted.get(name, "—"),
            f"{grid.size / t:.0f}",
            f"{t / serial:.2f}",
        )
        for name, t in times.items()
    ]
    print(
        markdown_table(
            [
                "run",
                "wall [s]",
                "CPU [s] (workers + scheduler + this process)",
                "workers' page faults",
                "designs/s",
                "time / serial",
            ],
            rows,
        )
    )
    print(
        "an idle cluster of 2, CPU-s a second (workers + this process): "
        + "; ".join(f"{name} {w:.3f} + {h:.3f}" for name, (w, h) in idle.items())
    )
    print(
        f"valid designs: {sum(r['valid'] for r in records[SERIAL])} of {grid.size}; records "
        f"identical in every run: {same}"
    )
    ok = two <= TARGET_TWO * serial
    scaling = ", ".join(f"{w}: {times[_running(w)] / serial:.2f}" for w in SCALING)
    return [
        SummaryRow(
            "atlas",
            f"{SIDE} × {SIDE} designs, running Dask cluster of 2 workers vs "
            f"serial ({serial:.1f} s)",
            f"{two:.2f} s ({two / serial:.2f}× the serial time; {WORKERS} busy processes "
            f"got {throughput:.2f} CPUs' worth, {1 / throughput:.2f}× at best; load "
            f"{os.getloadavg()[0]:.1f})",
            f"≤ {TARGET_TWO:g}×",
            verdict(ok),
        ),
        SummaryRow(
            "atlas",
            f"{SIDE} × {SIDE} designs, running cluster of 1, 2, 4 workers: time / serial",
            scaling,
            "records identical",
            verdict(same),
        ),
        SummaryRow(
            "atlas",
            f"{SIDE} × {SIDE} designs, local Dask cluster (start included); "
            "process pool; running cluster of 2 with Dask's defaults",
            f"{times[LOCAL]:.1f} s ({times[LOCAL] / serial:.2f}×); {times[POOL]:.1f} s "
            f"({times[POOL] / serial:.2f}×); {times[_running(WORKERS, True)]:.2f} s "
            f"({times[_running(WORKERS, True)] / serial:.2f}×)",
            "—",
            "—",
        ),
    ]


_PEAK = """
import resource, sys, time
from curvefold.app.cli import main
side, out = sys.argv[1], sys.argv[2]
t0 = time.perf_counter()
status = main(["atlas", "--p-xy", f"0.5:1.5:{{side}}", "--a", f"0:1.2:{{side}}",
               "--width", "{width}", "--samples", "{samples}", "--out", out, "--json",
               "--workers", "{workers}"])
assert status == 0, status
wall = time.perf_counter() - t0
me = resource.getrusage(resource.RUSAGE_SELF)
children = resource.getrusage(resource.RUSAGE_CHILDREN)
cpu = me.ru_utime + me.ru_stime + children.ru_utime + children.ru_stime
print("RESULT", wall, cpu, me.ru_maxrss / 1024, children.ru_maxrss / 1024, file=sys.stderr)
"""


def memory() -> list[SummaryRow]:
    """CPU seconds and peak resident memory of ``curvefold atlas``, per grid size, each in a
    fresh process."""
    import tempfile

    script = _PEAK.format(width=WIDTH, samples=SAMPLES, workers=WORKERS)
    rows, results = [], {}
    with tempfile.TemporaryDirectory() as folder:
        for side in MEMORY_SIDES:
            done = subprocess.run(
                [sys.executable, "-c", script, str(side), f"{folder}/atlas-{side}"],
                capture_output=True,
                text=True,
                check=True,
            )
            wall, cpu, peak, worker = (float(x) for x in done.stderr.split("RESULT")[-1].split())
            results[side] = (cpu, peak, worker)
            rows.append(
                (
                    f"{side} × {side}",
                    f"{side * side}",
                    f"{WORKERS}",
                    f"{wall:.0f}",
                    f"{cpu:.1f}",
                    f"{peak:.0f}",
                    f"{worker:.0f}" if worker else "—",
                    f"{os.getloadavg()[0]:.1f}",
                )
            )
            print(" | ".join(rows[-1]), flush=True)
    print(
        markdown_table(
            [
                "grid",
                "designs",
                "workers",
                "wall [s]",
                "CPU [s], workers included",
                "peak RSS [MiB]",
                "largest worker [MiB]",
                "load average",
            ],
            rows,
        )
    )
    small, large = results[MEMORY_SIDES[0]], results[MEMORY_SIDES[-1]]
    flat = large[1] <= 1.1 * small[1]
    return [
        SummaryRow(
            "atlas",
            f"curvefold atlas {MEMORY_SIDES[-1]} × {MEMORY_SIDES[-1]}: CPU "
            "seconds, its workers included",
            f"{large[0]:.1f} s",
            f"≤ {TARGET_CPU:g} s",
            verdict(large[0] <= TARGET_CPU),
        ),
        SummaryRow(
            "atlas",
            f"curvefold atlas: peak memory {MEMORY_SIDES[0]} × {MEMORY_SIDES[0]} "
            f"vs {MEMORY_SIDES[-1]} × {MEMORY_SIDES[-1]} (largest worker)",
            f"{small[1]:.0f} MiB vs {large[1]:.0f} MiB ({large[2]:.0f} MiB)",
            "within 10%",
            verdict(flat),
        ),
    ]


LOAD_SIDE = 20
LOAD_SAMPLES = 41  # the atlas's geometry, built at the model's samples (no rebuild)
TARGET_LOAD_CPU = 0.5  # CPU-s per design
#: (a, p_xy) of the designs whose accuracy is measured: 24, 9, 4, 3 and 2 tubes.
ACCURACY = ((0.0, 1.0), (0.3, 0.75), (0.6, 1.0), (0.9, 0.5), (1.2, 0.5))
#: The finer models: (samples, elements across), each against the atlas's (41, 1).
FINER = ((161, 1), (81, 4))


def _load_grid(side: int):
    from curvefold.mechanics import MATERIALS, AtlasLoad
    from curvefold.vault import AtlasGrid

    return AtlasGrid.of(
        np.linspace(0.5, 1.5, side),
        np.linspace(0.0, 1.2, side),
        width=WIDTH,
        samples=LOAD_SAMPLES,
        load=AtlasLoad(MATERIALS["polypropylene"], 1e-3),
    )


def _accuracy() -> list[tuple]:
    """Rows (a, p_xy, tubes, then per figure the atlas's value and its ratio to each finer
    model's) of the designs of :data:`ACCURACY`."""
    from curvefold.mechanics import MATERIALS, AtlasLoad
    from curvefold.vault import Vault
    from curvefold.vault._assembly import VaultDesign

    rows = []
    for a, p in ACCURACY:
        vault = Vault.from_design(VaultDesign(a=a, p_xy=p, width=WIDTH, samples=LOAD_SAMPLES))
        if a == 0.0:  # 24 tubes: four elements across would take some 2 GB
            finer = FINER[:1]
        else:
            finer = FINER
        coarse = AtlasLoad(MATERIALS["polypropylene"], 1e-3).measure(vault)
        cells = [f"{a:g}", f"{p:g}", str(vault.design.tubes)]
        for key in ("buckling_factor", "deflection", "mass"):
            ratios = []
            for samples, across in FINER:
                if (samples, across) not in finer:
                    ratios.append("—")
                    continue
                load = AtlasLoad(MATERIALS["polypropylene"], 1e-3, across=across, samples=samples)
                fine = load.measure(vault)  # rebuilt at the finer samples
                ratios.append(f"{coarse[key] / fine[key]:.3f}")
            cells += [f"{coarse[key]:.4g}", *ratios]
        rows.append(tuple(cells))
    return rows


def _cpu_with_children() -> float:
    """CPU seconds of this process and of its children that have ended (a local cluster's
    processes, once it is closed)."""
    me, children = (resource.getrusage(w) for w in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))
    return me.ru_utime + me.ru_stime + children.ru_utime + children.ru_stime


def load(side: int) -> list[SummaryRow]:
    """CPU-s per design of the atlas with mechanics, a local cluster of two against serial, and
    the coarse model's accuracy."""
    from curvefold.mechanics import MATERIALS, AtlasLoad
    from curvefold.vault import Vault
    from curvefold.vault._assembly import VaultDesign

    grid = _load_grid(side)
    c0, t0 = time.process_time(), time.perf_counter()
    serial = _records(grid, workers=1)
    cpu, wall = time.process_time() - c0, time.perf_counter() - t0
    c0, t0 = _cpu_with_children(), time.perf_counter()
    two = _records(grid, workers=WORKERS)
    cluster, cluster_cpu = time.perf_counter() - t0, _cpu_with_children() - c0
    throughput = parallel_throughput(WORKERS)
    heavy = Vault.from_design(VaultDesign(a=0.0, p_xy=1.5, width=WIDTH, samples=LOAD_SAMPLES))
    c0 = time.process_time()
    AtlasLoad(MATERIALS["polypropylene"], 1e-3).measure(heavy)
    costliest = time.process_time() - c0
    per = cpu / grid.size
    stands = sum(r["stands"] is True for r in serial)
    print(
        f"atlas under load: {side} × {side} designs, {LOAD_SAMPLES} samples, polypropylene 1 mm, "
        f"self-weight; {sum(r['valid'] for r in serial)} valid, {stands} stand (load average "
        f"{os.getloadavg()[0]:.1f}; {WORKERS} busy processes got {throughput:.2f} CPUs' worth)"
    )
    print(
        markdown_table(
            ["a", "p_xy", "tubes"]
            + [
                f"{name}{suffix}"
                for name in ("buckling factor", "deflection [m]", "mass [kg]")
                for suffix in ("", " / 161 samples", " / 4 across, 81 samples")
            ],
            _accuracy(),
        )
    )
    return [
        SummaryRow(
            "atlas --load",
            f"CPU-s per design, serial, {side} × {side} (the costliest: 24 tubes)",
            f"{per:.3f} ({costliest:.2f})",
            f"≤ {TARGET_LOAD_CPU:g}",
            verdict(per <= TARGET_LOAD_CPU),
        ),
        SummaryRow(
            "atlas --load",
            f"{side} × {side}, local Dask cluster of 2 (start included) vs serial ({wall:.1f} s)",
            f"{cluster:.1f} s ({cluster / wall:.2f}×; {1 / throughput:.2f}× at best; "
            f"{cluster_cpu:.1f} CPU-s against {cpu:.1f}; records identical: {two == serial})",
            f"≤ {TARGET_TWO:g}×",
            verdict(cluster <= TARGET_TWO * wall and two == serial),
        ),
    ]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--memory",
        action="store_true",
        help="measure the client's peak memory "
        f"for {' and '.join(f'{s} × {s}' for s in MEMORY_SIDES)} grids instead",
    )
    parser.add_argument(
        "--load",
        action="store_true",
        help="measure the atlas with mechanics (CPU-s per design, two workers vs serial, "
        "accuracy) instead",
    )
    parser.add_argument(
        "--load-side", type=int, default=LOAD_SIDE, help="grid side of --load (default 20)"
    )
    args = parser.parse_args()
    rows = memory() if args.memory else load(args.load_side) if args.load else run()
    print("\n" + summary_table(rows))


if __name__ == "__main__":
    main()
