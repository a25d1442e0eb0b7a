"""The paper's vault to collapse: ``curvefold load --nonlinear`` as a user runs it.

``curvefold load examples/paper-vault.toml --nonlinear --json`` in a child process (801
samples, polypropylene 1 mm, its own weight, the feet pinned, 4 elements across each strip as
the verdict, the errors from 2 across): the linear analysis, then ULS 1.35 G followed from zero
to its first loss of stability with an imperfection of span / 300 in the shape of the first
buckling mode. The CPU seconds (user + system) and the peak resident memory of the child, and
those of the same command without ``--nonlinear``: their difference is the path's.

Target: the path ≤ 120 CPU-s (issue 46).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("CURVEFOLD_MEMORY_BUDGET", "3G")  # headroom over its 1.80 GiB estimate

from _bench import SummaryRow, markdown_table, verdict  # noqa: E402
from bench_verdict import ours  # noqa: E402  (the same child run, with --nonlinear)

CPU_TARGET = 120.0


def run() -> list[SummaryRow]:
    linear_cpu, linear_peak, _ = ours()
    cpu, peak, d = ours("--nonlinear")
    c = d["collapse"]
    path_cpu = cpu - linear_cpu
    print(
        markdown_table(
            ["paper's vault", "CPU s", "peak (GB)", "factor", "steps", "ended"],
            [
                ["curvefold load", f"{linear_cpu:.1f}", f"{linear_peak / 1e9:.2f}", "", "", ""],
                [
                    "curvefold load --nonlinear",
                    f"{cpu:.1f}",
                    f"{peak / 1e9:.2f}",
                    f"{c['factor']:.4g} ({c['knock_down']:.3g} × linear {c['linear_factor']:.4g})",
                    str(c["steps"]),
                    c["reason"],
                ],
            ],
        )
    )
    return [
        SummaryRow(
            "collapse",
            "paper's vault to collapse, the path alone (CPU s)",
            f"{path_cpu:.1f}",
            f"≤ {CPU_TARGET:g}",
            verdict(path_cpu <= CPU_TARGET),
        ),
        SummaryRow(
            "collapse",
            "collapse factor over the linear (knock-down), span / 300",
            f"{c['knock_down']:.3g}",
            "reported",
            verdict(True),
        ),
    ]


def main() -> None:
    from _bench import summary_table

    print(summary_table(run()))


if __name__ == "__main__":
    main()
