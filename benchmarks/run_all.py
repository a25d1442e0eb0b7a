"""Run every benchmark and print one markdown summary table.

Usage: ``python benchmarks/run_all.py [integrator folding arch atlas budget designer main_job mechanics threads startup]`` (default: all).
The table at the end can be pasted into the README's performance section.
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
import time

import bench_arch
import bench_atlas
import bench_budget
import bench_designer
import bench_folding
import bench_integrator
import bench_main_job
import bench_mechanics
import bench_startup
import bench_threads
import numpy as np
import scipy
from _bench import summary_table

BENCHMARKS = {
    "integrator": bench_integrator,
    "folding": bench_folding,
    "arch": bench_arch,
    "atlas": bench_atlas,
    "budget": bench_budget,
    "designer": bench_designer,
    "main_job": bench_main_job,
    "mechanics": bench_mechanics,
    "threads": bench_threads,
    "startup": bench_startup,
}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", metavar="name", help=f"benchmarks to run: {', '.join(BENCHMARKS)} (default: all)")
    names = parser.parse_args(argv).names or list(BENCHMARKS)
    unknown = [n for n in names if n not in BENCHMARKS]
    if unknown:
        parser.error(f"unknown benchmark {unknown[0]!r}; choose from {', '.join(BENCHMARKS)}")
    rows = []
    start = time.perf_counter()
    for name in names:
        print(f"\n## {name}\n", flush=True)
        t0 = time.perf_counter()
        rows += BENCHMARKS[name].run()
        print(f"({name}: {time.perf_counter() - t0:.0f} s)", flush=True)
    import curvefold

    print(f"\n## summary ({time.perf_counter() - start:.0f} s)\n")
    print(
        f"curvefold {curvefold.__version__}, Python {platform.python_version()}, NumPy {np.__version__}, SciPy {scipy.__version__}, "
        f"{platform.machine()} with {os.cpu_count()} CPUs; best of k interleaved rounds, ratios from the same run.\n"
    )
    print(summary_table(rows))
    sys.stdout.flush()


if __name__ == "__main__":
    main()
