"""Deployment of the paper's vault: ``curvefold deploy`` from 2α = 10° to its design
angle, 90°, at 1° steps, as a user runs it.

- ours: ``curvefold deploy examples/paper-vault.toml --json --out DIR`` in a child process
  (from 2α = 10°, its default start; 801 samples, 261 kept along each of its 28 curves,
  polypropylene 1 mm under its own weight, both feet carried along the motion, the creases
  resting at 90°): the CPU seconds (user + system) and the peak resident memory of the
  child, the peak actuation, the largest stress and distance from the rigid path it
  reports; its ``deploy.png`` is the picture of ``docs/guide/deployment.md``
  (``--picture PATH`` copies it there);
- against: the same deployment at 10° steps (9 states), the coarsest a user would try: the
  cost of a state at 1° steps beside it.

Target: ≤ 60 CPU-s (issue 46).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from _bench import SummaryRow, verdict  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
CPU_TARGET = 60.0


def deploy(step: float, folder: Path) -> tuple[float, float, dict]:
    """CPU-s and peak bytes of ``curvefold deploy`` on the paper's vault in a child, its JSON."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(
        [sys.executable, "-m", "curvefold", "deploy", str(ROOT / "examples" / "paper-vault.toml")]
        + ["--step", str(step), "--json", "--out", str(folder)],
        capture_output=True,
        text=True,
        check=False,
        env=os.environ | {"PYTHONPATH": str(ROOT / "src")},
    )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode not in (0, 1):
        raise RuntimeError(out.stderr)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, after.ru_maxrss * 1024.0, json.loads(out.stdout)


def run(picture: Path | None = None) -> list[SummaryRow]:
    with tempfile.TemporaryDirectory() as tmp:
        cpu, peak, fine = deploy(1.0, Path(tmp) / "fine")
        print(json.dumps(fine["deployment"]), flush=True)
        if picture is not None:
            shutil.copyfile(Path(tmp) / "fine" / "deploy.png", picture)
            shutil.copyfile(Path(tmp) / "fine" / "deploy.csv", picture.with_suffix(".csv"))
        coarse_cpu, _, coarse = deploy(10.0, Path(tmp) / "coarse")
    d = fine["deployment"]
    print(json.dumps(d, indent=2))
    if "error" in fine:
        print(fine["error"])
    states, coarse_states = d["states"], coarse["deployment"]["states"]
    print(
        f"1° steps: {cpu:.1f} CPU-s for {states} states ({cpu / states:.2f} s each), "
        f"{peak / 1e9:.2f} GB; 10° steps: {coarse_cpu:.1f} CPU-s for {coarse_states} states"
    )
    return [
        SummaryRow(
            "deploy",
            "paper's vault 10° → 90° at 1° steps",
            f"{cpu:.1f} CPU-s, {peak / 1e9:.2f} GB; peak actuation "
            f"{d.get('peak_actuation_Nm', float('nan')):.3g} N·m/rad",
            f"≤ {CPU_TARGET:g} CPU-s",
            verdict(cpu <= CPU_TARGET and "error" not in fine),
        )
    ]


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--picture", type=Path, help="copy the 1° run's deploy.png here")
    for row in run(parser.parse_args().picture):
        print(row)
