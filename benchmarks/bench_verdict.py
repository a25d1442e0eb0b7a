"""Will the paper's vault stand, at the accuracy the verdict needs: ``curvefold load`` against an
OpenSees shell model of the same vault.

- ours: ``curvefold load examples/paper-vault.toml --json`` in a child process, as a user
  runs it (801 samples, polypropylene 1 mm, its own weight, the feet pinned): the model on
  4 elements across each strip and again on 2 to estimate every figure's error, the verdict
  under EN 1990's combinations; the CPU seconds (user + system) and the peak resident
  memory of the child;
- OpenSees: the shells of ``tests/_opensees.py`` (ASDShellQ4, m = 4 across each ruling quad,
  one along, the creases as springs; within 1.4 % of their limit in deflection on the
  guide's tables), what an engineer would otherwise build, on the same vault modelled on
  41 samples (the shells' solves grow past CPU-minutes on more), beside our model of the
  same samples at 4 across: the static response to its own weight and the six lowest free
  eigenvalues, CPU seconds of each. OpenSees has no linear buckling analysis here.

Targets: ours ≤ 10 CPU-s and ≤ 1 GB, every figure's estimated error ≤ 5 %; the deflection of
both on the same samples within 5 %.
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from _bench import SummaryRow, markdown_table, verdict  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
CPU_TARGET, MEMORY_TARGET, ERROR_TARGET, AGREEMENT = 10.0, 1.0e9, 0.05, 0.05
SHELLS_ACROSS = 4


def ours(*flags: str) -> tuple[float, float, dict]:
    """CPU-s and peak bytes of ``curvefold load`` (with ``flags``) on the paper's vault in a
    child, and its JSON."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(
        [sys.executable, "-m", "curvefold", "load", str(ROOT / "examples" / "paper-vault.toml")]
        + [*flags, "--json"],
        capture_output=True,
        text=True,
        check=False,
    )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode not in (0, 1):
        raise RuntimeError(out.stderr)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, after.ru_maxrss * 1024.0, json.loads(out.stdout)


def same_samples(samples: int = 41) -> tuple[float, float, float, float, np.ndarray]:
    """CPU-s, deflection and eigenvalues of OpenSees shells and of ours (4 across) on the paper's
    vault modelled on ``samples`` samples: shells CPU, ours CPU, shells' and our deflection, and
    the shells' eigenvalues."""
    sys.path.insert(0, str(ROOT / "tests"))
    import _opensees
    from curvefold.mechanics import MATERIALS, StructureModel, analyse_load
    from curvefold.vault import Vault

    state = Vault.from_design(a=0.3, p_xy=0.75, samples=samples).structure.state()
    sm = StructureModel.from_state(state, MATERIALS["polypropylene"], 1e-3, samples="all")
    start = time.process_time()
    ours = analyse_load(sm.with_across(SHELLS_ACROSS))
    ours_cpu = time.process_time() - start
    start = time.process_time()
    u = _opensees.static_deflection(sm, (SHELLS_ACROSS, 1))
    P = len(sm.model.nodes)
    ground = np.array([[0, 0], [0, 1], [0, 2], [P // 2, 0], [P // 2, 2], [1, 2]])
    values = _opensees.free_eigenvalues(sm, (SHELLS_ACROSS, 1), 6, ground, 1e-3)
    shells_cpu = time.process_time() - start
    deflection = float(np.linalg.norm(u, axis=1).max())
    return shells_cpu, ours_cpu, deflection, ours.static.max_displacement, values


def run() -> list[SummaryRow]:

    cpu, peak, d = ours()
    worst = max(float(np.max(e)) for e in d["errors"].values())
    shells_cpu, same_cpu, shell_deflection, our_deflection, values = same_samples()
    print(
        markdown_table(
            ["paper's vault", "CPU s", "deflection (µm)", "ω₁² (rad²/s²)", "verdict"],
            [
                [
                    "curvefold load, 801 samples (4 across, errors from 2)",
                    f"{cpu:.1f}",
                    f"{d['max_displacement'] * 1e6:.2f} ± {d['errors']['max_displacement']:.1%}",
                    f"{d['modes'][0]:.3f} ± {d['errors']['modes'][0]:.1%}",
                    d["verdict_text"],
                ],
                [
                    f"ours, 41 samples, {SHELLS_ACROSS} across",
                    f"{same_cpu:.1f}",
                    f"{our_deflection * 1e6:.2f}",
                    "",
                    "",
                ],
                [
                    f"OpenSees shells, 41 samples, {SHELLS_ACROSS} × 1 per ruling quad",
                    f"{shells_cpu:.1f}",
                    f"{shell_deflection * 1e6:.2f}",
                    f"{values[0]:.3f}",
                    "(no buckling analysis)",
                ],
            ],
        )
    )
    print(
        f"\npeak memory of curvefold load: {peak / 1e9:.2f} GB; largest estimated error {worst:.1%}"
    )
    agreement = abs(our_deflection / shell_deflection - 1)
    return [
        SummaryRow(
            "verdict",
            "curvefold load, paper's vault at the verdict's accuracy (CPU s)",
            f"{cpu:.1f}",
            f"≤ {CPU_TARGET:g}",
            verdict(cpu <= CPU_TARGET),
        ),
        SummaryRow(
            "verdict",
            "its peak memory (GB)",
            f"{peak / 1e9:.2f}",
            f"≤ {MEMORY_TARGET / 1e9:g}",
            verdict(peak <= MEMORY_TARGET),
        ),
        SummaryRow(
            "verdict",
            "largest estimated error of a printed figure",
            f"{worst:.1%}",
            f"≤ {ERROR_TARGET:.0%}",
            verdict(worst <= ERROR_TARGET),
        ),
        SummaryRow(
            "verdict",
            "OpenSees shells / ours, same 41 samples (CPU s)",
            f"{shells_cpu / same_cpu:.0f}×",
            "> 1",
            verdict(shells_cpu > same_cpu),
        ),
        SummaryRow(
            "verdict",
            "deflection, ours against the shells (41 samples)",
            f"{agreement:.1%}",
            f"≤ {AGREEMENT:.0%}",
            verdict(agreement <= AGREEMENT),
        ),
    ]


def main() -> None:
    from _bench import summary_table

    print(summary_table(run()))


if __name__ == "__main__":
    main()
