"""The thick panels' work against its estimate before work (curvefold.app._budget.thick_work).

Each design runs in a process of its own: the vault of rigid panels is built and its
zero-thickness mechanism certified, then the thick panels' work is timed and its peak memory
read (``ru_maxrss`` over the built design's): the solids (the offset-panel technique, tapered
where needed, as ``curvefold vault`` builds them), the range of motion with thickness, the
thickness checks (hinges, contact at the range's states, the DOF count), the STL and cut
list files, then the STEP file (a job of its own in a run, timed apart). The estimate is
:func:`curvefold.app._budget.thick_work` of the same design.

Target: estimate / measured within 0.7 to 1.3 for the time and the memory on both designs.
"""

from __future__ import annotations

import json
import subprocess
import sys

from _bench import SummaryRow, markdown_table, verdict

#: (panels per crease, thickness in metres): the paper's vault of 9 tubes.
DESIGNS = ((16, 0.01), (48, 0.002))

_CHILD = """
import json, resource, sys, tempfile, time
from pathlib import Path
peak = lambda: resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
from curvefold.app import design_from_dict
from curvefold.app._build import build
from curvefold.app._thickness import thick_panels
from curvefold.analysis._mechanism import certified_mechanism
from curvefold.analysis._thick_checks import thickness_checks
from curvefold.io._solids import write_cut_list, write_cut_list_csv, write_cut_list_pdf
from curvefold.io._solids import write_thick_stl
from curvefold.io._step import write_thick_step
data = json.loads(sys.argv[1])
built = build(design_from_dict(data))
certified_mechanism(built.structure)
before, t0 = peak(), time.process_time()
thick = thick_panels(built.structure, built.design)
motion = thick.motion_range()
thickness_checks(thick, motion)
with tempfile.TemporaryDirectory() as d:
    write_thick_stl(Path(d) / "s.stl", thick, unit="m", to_unit="mm")
    write_cut_list(Path(d) / "c.json", thick)
    write_cut_list_csv(Path(d) / "c.csv", thick, unit="m")
    write_cut_list_pdf(Path(d) / "c.pdf", thick, unit="m")
    work, t1 = peak() - before, time.process_time()
    write_thick_step(Path(d) / "s.step", thick, unit="m", to_unit="mm")
    t2 = time.process_time()
print(json.dumps([work, t1 - t0, t2 - t1, motion.low, peak() - before - work]))
"""


def run() -> list[SummaryRow]:
    from curvefold.app import design_from_dict
    from curvefold.app._budget import thick_work

    rows, ratios = [], []
    for panels, t in DESIGNS:
        data = {"kind": "vault", "vault": {"panels": panels}, "material": {"thickness": t}}
        data["material"]["material"] = "plywood"
        done = subprocess.run(
            [sys.executable, "-c", _CHILD, json.dumps(data)],
            capture_output=True,
            text=True,
            check=True,
        )
        memory, seconds, step, low, step_memory = json.loads(done.stdout)
        guess = thick_work(design_from_dict(data))
        ratio = (guess.memory / memory, guess.seconds / seconds, guess.step_seconds / step)
        ratios += list(ratio)
        rows.append(
            (
                f"vault, {panels} panels, t = {t:g} m (stops at {low:.4g}°)",
                f"{memory / 2**20:.0f} / {guess.memory / 2**20:.0f}",
                f"{seconds:.1f} / {guess.seconds:.1f}",
                f"{step:.1f} / {guess.step_seconds:.1f}",
                " ".join(f"{r:.2f}" for r in ratio),
            )
        )
        print(rows[-1], flush=True)
    print(
        markdown_table(
            [
                "design",
                "memory MiB (measured / estimate)",
                "time s",
                "STEP s",
                "estimate / measured",
            ],
            rows,
        )
    )
    low, high = min(ratios), max(ratios)
    return [
        SummaryRow(
            "thick budget",
            "estimate / measured, memory and time, 16 and 48 panels",
            f"{low:.2f} to {high:.2f}",
            "0.7 to 1.3",
            verdict(0.7 <= low and high <= 1.3),
        )
    ]


if __name__ == "__main__":
    run()
