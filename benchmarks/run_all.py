"""Run every benchmark, print one markdown summary table and record the run.

Usage: ``python benchmarks/run_all.py [--results DIR | --no-save] [name ...]`` with names from
integrator folding arch atlas budget designer main_job mechanics verdict collapse
collapse_opensees merlin woodruff virtual_thickness thick_budget deploy threads startup
(default: all).

Each run is recorded in ``benchmarks/results/`` (or ``--results DIR``) as two files named by
its start time: ``<stamp>.txt``, everything the benchmarks printed, and ``<stamp>.json``, the
summary rows with the machine, the versions and the load average. ``benchmarks/README.md``
quotes the figures of a recorded run and names it; nothing is pasted from a terminal.
"""

from __future__ import annotations

import argparse
import contextlib
import datetime
import importlib
import io
import json
import os
import platform
import sys
import time
from collections.abc import Sequence
from dataclasses import asdict
from pathlib import Path
from typing import Any, TextIO

NAMES = (
    "integrator",
    "folding",
    "arch",
    "atlas",
    "budget",
    "designer",
    "main_job",
    "mechanics",
    "verdict",
    "collapse",
    "collapse_opensees",
    "merlin",
    "woodruff",
    "virtual_thickness",
    "thick_budget",
    "deploy",
    "threads",
    "startup",
)
RESULTS = Path(__file__).resolve().parent / "results"


class _Tee(io.TextIOBase):
    """A text stream that writes to each of its streams (the terminal and the run's record)."""

    def __init__(self, *streams: TextIO) -> None:
        self._streams = streams

    def write(self, text: str) -> int:
        for stream in self._streams:
            stream.write(text)
        return len(text)

    def flush(self) -> None:
        for stream in self._streams:
            stream.flush()


def environment() -> dict[str, Any]:
    """The versions and the machine a run's figures belong to."""
    import numpy as np
    import scipy

    import curvefold

    return {
        "curvefold": curvefold.__version__,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "machine": platform.machine(),
        "cpus": os.cpu_count(),
        "load_average": list(os.getloadavg()),
    }


def save_results(
    folder: Path,
    started: datetime.datetime,
    names: Sequence[str],
    rows: Sequence[Any],
    printed: str,
    env: dict[str, Any],
    seconds: float,
) -> tuple[Path, Path]:
    """Write a run's record: ``<stamp>.txt`` (what it printed) and ``<stamp>.json`` (its figures).

    Parameters
    ----------
    folder : Path
        Where the records go (made if missing).
    started : datetime.datetime
        When the run started (UTC); it names the files, ``2026-12-04T201514``.
    names : sequence of str
        The benchmarks run.
    rows : sequence of SummaryRow
        The summary rows (dataclasses: benchmark, measure, value, target, status).
    printed : str
        Everything the benchmarks printed.
    env : dict
        :func:`environment` at the start of the run.
    seconds : float
        Wall time of the run.

    Returns
    -------
    (Path, Path)
        The text and the JSON file.
    """
    folder.mkdir(parents=True, exist_ok=True)
    stamp = started.strftime("%Y-%m-%dT%H%M%S")
    text, data = folder / f"{stamp}.txt", folder / f"{stamp}.json"
    text.write_text(printed, encoding="utf-8")
    record = {
        "started": started.isoformat(timespec="seconds"),
        "seconds": round(seconds, 1),
        "benchmarks": list(names),
        **env,
        "rows": [asdict(row) for row in rows],
    }
    data.write_text(json.dumps(record, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    return text, data


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "names",
        nargs="*",
        metavar="name",
        help=f"benchmarks to run: {', '.join(NAMES)} (default: all)",
    )
    parser.add_argument(
        "--results",
        type=Path,
        default=RESULTS,
        help="folder of the run's record (default: benchmarks/results)",
    )
    parser.add_argument("--no-save", action="store_true", help="print only; record nothing")
    args = parser.parse_args(argv)
    names = args.names or list(NAMES)
    unknown = [n for n in names if n not in NAMES]
    if unknown:
        parser.error(f"unknown benchmark {unknown[0]!r}; choose from {', '.join(NAMES)}")
    from _bench import summary_table

    started, env = datetime.datetime.now(datetime.UTC), environment()
    printed = io.StringIO()
    rows = []
    start = time.perf_counter()
    with contextlib.redirect_stdout(_Tee(sys.stdout, printed)):
        for name in names:
            print(f"\n## {name}\n", flush=True)
            t0 = time.perf_counter()
            rows += importlib.import_module(f"bench_{name}").run()
            print(f"({name}: {time.perf_counter() - t0:.0f} s)", flush=True)
        seconds = time.perf_counter() - start
        print(f"\n## summary ({seconds:.0f} s)\n")
        print(
            f"curvefold {env['curvefold']}, Python {env['python']}, NumPy {env['numpy']}, "
            f"SciPy {env['scipy']}, {env['machine']} with {env['cpus']} CPUs, load average "
            f"{env['load_average'][0]:.1f} at the start; best of k interleaved rounds, "
            "ratios from the same run.\n"
        )
        print(summary_table(rows))
    if not args.no_save:
        paths = save_results(args.results, started, names, rows, printed.getvalue(), env, seconds)
        print(f"\nrecorded in {paths[0]} and {paths[1]}")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
