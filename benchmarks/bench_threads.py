"""BLAS threads: the mechanism's dense SVDs on one thread, and the SVDs the output jobs share.

The mechanism analysis (the certificate of a panel structure, ``curvefold mechanism``)
takes dense SVDs of constraint Jacobians of at most a few thousand columns; curvefold runs
them on one BLAS thread (``curvefold.kernel._threads``). The contenders:

- commands, each in a fresh process, with OpenBLAS left at its default threads (one per
  CPU, what a user gets) and with ``OPENBLAS_NUM_THREADS=1``: ``curvefold vault --panels 64
  --json`` and ``curvefold mechanism`` of a 16-panel vault's FOLD file. Interleaved, best of
  k, wall and CPU seconds (the process and its children);
- the SVD itself, in this process: ``numpy.linalg.svd`` of the certificate's Jacobian of the
  16-panel vault on OpenBLAS's default threads (what the mechanism ran before) against
  :func:`curvefold.analysis._mechanism.mechanism` (one thread);
- the output folder of the 16-panel vault (``write_outputs``): which processes compute the
  mechanism's SVDs. The certificate computes them before the jobs fork, so the pictures
  job (its singular values) reads them instead of computing them again.

Targets: the default threads no slower than one, in CPU seconds within 15% (they were 3.4×
slower for ``vault --panels 64 --json``); the job processes compute no mechanism.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from _bench import (
    CPU,
    WALL,
    SummaryRow,
    best_of_interleaved,
    markdown_table,
    summary_table,
    verdict,
)

ROUNDS = 5
WITHIN = 1.15  # default threads / one thread, CPU seconds: the noise of a shared machine
CURVEFOLD = [sys.executable, "-m", "curvefold"]


def _command(args: list[str], threads: int | None) -> tuple[float, float]:
    """(wall, CPU) seconds of one run of ``curvefold args`` in a fresh process (its children
    included)."""
    env = dict(os.environ)
    env.pop("OPENBLAS_NUM_THREADS", None)
    if threads is not None:
        env["OPENBLAS_NUM_THREADS"] = str(threads)
    before = os.times()
    t0 = time.perf_counter()
    subprocess.run(
        CURVEFOLD + args, env=env, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    wall = time.perf_counter() - t0
    after = os.times()
    return wall, (after.children_user - before.children_user) + (
        after.children_system - before.children_system
    )


def _compare_command(label: str, args: list[str]) -> tuple[tuple, SummaryRow]:
    best = {name: [float("inf"), float("inf")] for name in ("default", "one")}
    for r in range(ROUNDS):
        for name in ("default", "one") if r % 2 == 0 else ("one", "default"):
            wall, cpu = _command(args, None if name == "default" else 1)
            best[name] = [min(best[name][0], wall), min(best[name][1], cpu)]
    (dw, dc), (ow, oc) = best["default"], best["one"]
    ok = dc <= WITHIN * oc
    row = (
        label,
        f"{dw:.2f} / {dc:.2f}",
        f"{ow:.2f} / {oc:.2f}",
        f"{dw / ow:.2f} / {dc / oc:.2f}",
        verdict(ok),
    )
    return row, SummaryRow(
        "threads",
        f"{label}: OpenBLAS's default threads vs one (wall / CPU, best of {ROUNDS})",
        f"{dw:.2f} / {dc:.2f} s vs {ow:.2f} / {oc:.2f} s ({dw / ow:.2f}× / {dc / oc:.2f}×)",
        f"CPU ≤ {WITHIN:g}×",
        verdict(ok),
    )


def _svd_rows(structure) -> tuple[list[tuple], list[SummaryRow]]:
    from curvefold.analysis._mechanism import Framework, certified_mechanism, mechanism

    part = certified_mechanism(structure).part
    framework, points = Framework.from_structure(part)
    x = part.state().vertices.reshape(-1, 3)[points]
    J = framework.jacobian(x)
    contenders = {
        "svd, default threads": lambda: np.linalg.svd(J, compute_uv=False),
        "mechanism (one thread)": lambda: mechanism(framework, x),
    }
    rows, summary = [], []
    for clock, name in ((WALL, "wall"), (CPU, "CPU")):
        best, _ = best_of_interleaved(contenders, 5, clock=clock)
        a, b = best["svd, default threads"], best["mechanism (one thread)"]
        rows.append(
            (
                f"SVD of the certificate's Jacobian {J.shape[0]} × {J.shape[1]} ({name})",
                f"{a:.3f}",
                f"{b:.3f}",
                f"{a / b:.2f} ({name})",
                "—",
            )
        )
        summary.append(
            SummaryRow(
                "threads",
                f"the certificate's SVD, {J.shape[0]} × "
                f"{J.shape[1]}, default threads vs one ({name}, best of 5)",
                f"{a * 1e3:.0f} ms vs {b * 1e3:.0f} ms ({a / b:.2f}×)",
                "—",
                "—",
            )
        )
    return rows, summary


def _svd_processes(folder: Path) -> tuple[int, int]:
    """Mechanism analyses (one SVD each) computed by this process and by the job processes while
    the 16-panel vault's folder is written."""
    from curvefold.analysis import _mechanism as m
    from curvefold.app import write_outputs
    from curvefold.app._folder import check_output

    log = folder / "svd.log"
    analyse = m.mechanism

    def counted(*args, **kwargs):
        with open(log, "a") as f:
            f.write(f"{os.getpid()}\n")
        return analyse(*args, **kwargs)

    m.mechanism = counted
    try:
        write_outputs(_built(16), check_output(folder / "out", force=False), show_progress=False)
    finally:
        m.mechanism = analyse
    pids = log.read_text().split()
    here = sum(p == str(os.getpid()) for p in pids)
    return here, len(pids) - here


def _built(panels: int):
    from curvefold.app import design_from_dict
    from curvefold.app._build import build

    return build(design_from_dict({"kind": "vault", "vault": {"panels": panels}}))


def run() -> list[SummaryRow]:
    rows, summary = [], []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        subprocess.run(
            CURVEFOLD
            + ["vault", "--panels", "16", "--formats", "fold", "--out", str(folder / "v16")],
            check=True,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        for label, args in (
            ("vault --panels 64 --json", ["vault", "--panels", "64", "--json"]),
            ("mechanism of a 16-panel vault", ["mechanism", str(folder / "v16" / "vault.fold")]),
        ):
            row, line = _compare_command(label, args)
            rows.append(row)
            summary.append(line)
        svd_rows, svd_summary = _svd_rows(_built(16).structure)
        here, jobs = _svd_processes(folder)
    print(f"BLAS threads (load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs)")
    print(
        markdown_table(
            [
                "run",
                "default threads: wall / CPU [s]",
                "one thread: wall / CPU [s]",
                "default / one",
                f"CPU ≤ {WITHIN:g}×",
            ],
            rows + svd_rows,
        )
    )
    print(
        f"\n16-panel vault's output folder: mechanism analyses in the main process {here}, in "
        f"the job processes {jobs}"
    )
    summary += svd_summary
    summary.append(
        SummaryRow(
            "threads",
            "16-panel vault's output folder: mechanism analyses in "
            "the main process, in the job processes",
            f"{here}, {jobs}",
            "0 in the jobs",
            verdict(jobs == 0),
        )
    )
    return summary


def main() -> None:
    print("\n" + summary_table(run()))


if __name__ == "__main__":
    main()
