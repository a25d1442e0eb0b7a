"""Shared helpers for the benchmark scripts: interleaved timing, verdicts, markdown tables.

The machine these run on is shared and noisy, so no absolute time is trusted on its own:
contenders are timed in the same run, interleaved (the order rotates every round), and
each keeps the best of k rounds; the scripts report ratios next to the times. Wall time
by default; ``clock=CPU`` counts the CPU seconds of this process (all its threads), which
move less than wall time when other programs share the machine.
"""

from __future__ import annotations

import gc
import os
import resource
import subprocess
import sys
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

#: The clocks a timing can read: wall time, and the CPU time of this process.
WALL, CPU = time.perf_counter, time.process_time


@dataclass(frozen=True)
class SummaryRow:
    """One line of the summary table that ``run_all.py`` prints."""

    benchmark: str
    measure: str
    value: str
    target: str
    status: str


def timed(
    fn: Callable[[], object], *, pause_gc: bool = True, clock: Callable[[], float] = WALL
) -> tuple[float, object]:
    """Time of one call of ``fn`` on ``clock`` and its result.

    The garbage collector runs a full collection first and is paused during the call
    unless ``pause_gc`` is False (for long runs whose own collections are part of the cost).
    """
    was_enabled = gc.isenabled()
    gc.collect()
    if pause_gc:
        gc.disable()
    try:
        t0 = clock()
        result = fn()
        elapsed = clock() - t0
    finally:
        if was_enabled:
            gc.enable()
    return elapsed, result


def best_of_interleaved(
    contenders: Mapping[str, Callable[[], object]],
    repeats: int,
    *,
    pause_gc: bool = True,
    clock: Callable[[], float] = WALL,
) -> tuple[dict[str, float], dict[str, object]]:
    """Best time (on ``clock``) of each contender over ``repeats`` interleaved rounds.

    Round r runs the contenders in an order rotated by r, so neither always runs first
    (warm caches) or last. Returns the best times and the last result of each contender.
    """
    names = list(contenders)
    best = {name: float("inf") for name in names}
    results: dict[str, object] = {}
    for r in range(repeats):
        shift = r % len(names)
        for name in names[shift:] + names[:shift]:
            elapsed, results[name] = timed(contenders[name], pause_gc=pause_gc, clock=clock)
            best[name] = min(best[name], elapsed)
    return best, results


def choose_repeats(seconds_per_round: float, budget: float, *, low: int = 3, high: int = 25) -> int:
    """How many rounds fit in ``budget`` seconds, clamped to [low, high]."""
    if seconds_per_round <= 0:
        return high
    return max(low, min(high, int(budget / seconds_per_round)))


def bytecode_env(cache: str) -> dict[str, str]:
    """This environment with Python's bytecode cache written to the folder ``cache``
    (``PYTHONPYCACHEPREFIX``), even where ``PYTHONDONTWRITEBYTECODE`` is set: a command
    timed after one warm-up run starts as an installed package does, from bytecode."""
    return {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"} | {
        "PYTHONPYCACHEPREFIX": cache
    }


def children_cpu(
    command: Sequence[str], env: Mapping[str, str] | None = None
) -> tuple[float, float, subprocess.CompletedProcess]:
    """(wall seconds, CPU seconds of the command and the processes it waited for, its result) of
    one run of ``command``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run(
        list(command),
        capture_output=True,
        text=True,
        check=False,
        env=None if env is None else dict(env),
    )
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime), done


def machine_speed(env: Mapping[str, str] | None = None, repeats: int = 3) -> float:
    """CPU seconds of ``python -c "import numpy"`` in a fresh process, best of ``repeats``: the
    machine's speed beside a figure, since a CPU second here grows when others hold the
    machine's CPUs (0.13–0.15 on an idle development machine, up to 0.30 when shared)."""
    runs = [children_cpu([sys.executable, "-c", "import numpy"], env) for _ in range(repeats)]
    if any(done.returncode for _, _, done in runs):
        raise RuntimeError("python -c 'import numpy' failed: " + runs[0][2].stderr.strip())
    return min(cpu for _, cpu, _ in runs)


#: A fixed piece of pure-Python work, about half a second, for :func:`parallel_throughput`.
_SPIN = "s = 0\nfor i in range(10_000_000): s += i"


def parallel_throughput(processes: int = 2, repeats: int = 3) -> float:
    """How many CPUs' worth of work the machine gives ``processes`` busy processes at once.

    ``processes`` × (wall seconds of one fixed CPU-bound process alone) / (wall seconds of
    ``processes`` of them started together), best of ``repeats`` interleaved rounds each, at most
    ``processes``: that many on an idle machine with that many CPUs, less when others share the
    host, which bounds what a parallel run measured beside it can gain."""
    spin = [sys.executable, "-c", _SPIN]

    def together(n: int) -> float:
        t0 = time.perf_counter()
        running = [subprocess.Popen(spin) for _ in range(n)]
        if any(p.wait() for p in running):
            raise RuntimeError("the CPU-bound reference process failed")
        return time.perf_counter() - t0

    rounds = [(together(1), together(processes)) for _ in range(repeats)]
    return min(processes, processes * min(a for a, _ in rounds) / min(b for _, b in rounds))


def verdict(ok: bool) -> str:
    return "PASS" if ok else "MISS"


def markdown_table(headers: Sequence[str], rows: Sequence[Sequence[object]]) -> str:
    """A GitHub markdown table; cells are converted with ``str``."""
    cells = [[str(c) for c in headers]] + [[str(c) for c in row] for row in rows]
    widths = [max(len(row[i]) for row in cells) for i in range(len(headers))]
    line = lambda row: "| " + " | ".join(c.ljust(w) for c, w in zip(row, widths)) + " |"  # noqa: E731
    return "\n".join(
        [line(cells[0]), "|" + "|".join("-" * (w + 2) for w in widths) + "|"]
        + [line(r) for r in cells[1:]]
    )


def summary_table(rows: Sequence[SummaryRow]) -> str:
    return markdown_table(
        ["benchmark", "measure", "value", "target", "status"],
        [(r.benchmark, r.measure, r.value, r.target, r.status) for r in rows],
    )


def ms(seconds: float) -> str:
    """A time in milliseconds with three significant figures."""
    return f"{seconds * 1e3:.3g}"
