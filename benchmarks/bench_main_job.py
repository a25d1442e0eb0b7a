"""The main job stage by stage: the paper's vault written to an output folder.

``curvefold vault`` on the built-in design (a = 0.3, p_xy = 0.75, 9 tubes, 801 samples per
crease) writes every format. Its stages are timed one by one in this process, as the
command runs them: building the vault and its certificate, choosing the meshes' samples,
then each job of the output folder and the report. The contender is what the files cost
with a mesh on every computed sample (what curvefold wrote before it chose the samples):
the same jobs, run right after, with every sample kept. One run of each, garbage
collector on; the folder sizes are summed on disk. Each stage is timed in CPU seconds
too (this process's, steadier than wall time on a shared machine). A last line times the
whole command in a fresh process (best of :data:`REPEATS`), imports included, in wall and CPU
seconds (the command and the processes it starts), beside the CPU seconds a fresh process takes only
to import the libraries the command uses (:data:`LIBRARIES`: each job process imports its own), and
the machine's speed (:func:`_bench.machine_speed`).

Targets: the whole command ≤ 2 s wall and ≤ 3 CPU-s, the folder under 10 MB.
"""

from __future__ import annotations

import dataclasses
import json
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from _bench import (
    SummaryRow,
    bytecode_env,
    children_cpu,
    machine_speed,
    markdown_table,
    summary_table,
    timed,
    verdict,
)

TARGET_SECONDS = 2.0
TARGET_CPU = 3.0
TARGET_MB = 10.0
#: Runs of the whole command in a fresh process (its best wall and CPU seconds are reported):
#: on a machine others share, one run can take a third longer than the next.
REPEATS = 3
#: What the main job imports besides curvefold: NumPy, Pillow (pictures and GIF), rhino3dm
#: (3dm), ezdxf (DXF), and the command line's threadpoolctl (no SciPy, matplotlib or pygltflib:
#: tests/test_startup.py holds it to that; rich only for a progress bar in a terminal). NumPy is
#: loaded on one BLAS thread, as the command line loads it.
LIBRARIES = (
    "numpy",
    "PIL.Image",
    "PIL.ImageDraw",
    "PIL.ImageFont",
    "rhino3dm",
    "ezdxf",
    "threadpoolctl",
)


def _folder_bytes(folder: Path) -> int:
    return sum(p.stat().st_size for p in folder.rglob("*") if p.is_file())


def _cpu_timed(fn):
    """(wall seconds, CPU seconds of this process, result) of one call of ``fn``."""
    cpu = time.process_time()
    wall, result = timed(fn, pause_gc=False)
    return wall, time.process_time() - cpu, result


def _run_stages(built, folder: Path) -> tuple[dict[str, float], dict[str, float]]:
    """Wall and CPU seconds of every job of the output folder, and of the report (as
    write_outputs runs them)."""
    from curvefold.app import _products as products
    from curvefold.figures import report_html

    wall: dict[str, float] = {}
    cpu: dict[str, float] = {}
    # the crease patterns are laid out once (for their files, the 3dm and the assembly guide) before
    # the jobs start
    wall["crease-pattern layout"], cpu["crease-pattern layout"], _ = _cpu_timed(
        lambda: built.layout
    )
    for label, job in products.jobs(built, built.design.output.formats):
        wall[label], cpu[label], _ = _cpu_timed(lambda job=job: job(folder))
    wall["report"], cpu["report"], _ = _cpu_timed(
        lambda: (folder / "report.html").write_text(report_html({"certificate": [], "files": []}))
    )
    return wall, cpu


def run() -> list[SummaryRow]:
    from curvefold.app import default_design, structure_payload
    from curvefold.app._build import build
    from curvefold.geometry import Sampling

    design = default_design("vault")
    t_build, c_build, built = _cpu_timed(lambda: build(design))
    t_cert, c_cert, _ = _cpu_timed(lambda: structure_payload(built))
    t_sampling, c_sampling, sampling = _cpu_timed(lambda: built.sampling)
    n = sampling.samples
    every = Sampling(
        tuple(np.arange(n) for _ in sampling.keep),
        n,
        sampling.tolerance,
        sampling.min_angle_bound,
        sampling.max_bend,
        0.0,
        0.0,
        0.0,
        0.0,
        sampling.size,
    )
    full = dataclasses.replace(built)  # a fresh build value: none of its derived values computed
    full.__dict__["sampling"] = every  # the same design, its meshes on every sample
    with tempfile.TemporaryDirectory() as a, tempfile.TemporaryDirectory() as b:
        chosen_dir, full_dir = Path(a), Path(b)
        (chosen, chosen_cpu), (everything, _) = (
            _run_stages(built, chosen_dir),
            _run_stages(full, full_dir),
        )
        sizes = (_folder_bytes(chosen_dir) / 1e6, _folder_bytes(full_dir) / 1e6)
    common = {"build the vault": (t_build, c_build), "certificate": (t_cert, c_cert)}
    rows = [(stage, f"{t:.2f}", f"{c:.2f}", f"{t:.2f}", "1.00") for stage, (t, c) in common.items()]
    rows.append(("choose the meshes' samples", f"{t_sampling:.2f}", f"{c_sampling:.2f}", "—", "—"))
    rows += [
        (
            stage,
            f"{chosen[stage]:.2f}",
            f"{chosen_cpu[stage]:.2f}",
            f"{everything[stage]:.2f}",
            f"{everything[stage] / chosen[stage]:.1f}",
        )
        for stage in chosen
    ]
    in_process = sum(t for t, _ in common.values()) + t_sampling + sum(chosen.values())
    in_process_cpu = sum(c for _, c in common.values()) + c_sampling + sum(chosen_cpu.values())
    in_process_full = sum(t for t, _ in common.values()) + sum(everything.values())
    rows.append(
        (
            "all stages",
            f"{in_process:.2f}",
            f"{in_process_cpu:.2f}",
            f"{in_process_full:.2f}",
            f"{in_process_full / in_process:.1f}",
        )
    )
    rows.append(
        (
            "folder size [MB]",
            f"{sizes[0]:.1f}",
            "—",
            f"{sizes[1]:.1f}",
            f"{sizes[1] / sizes[0]:.1f}",
        )
    )
    counts = sampling.vertices_per_crease
    print(
        f"main job: the paper's vault, {len(counts)} tubes, {n} samples computed per crease; "
        f"the files keep {min(counts)}–{max(counts)} (deviation "
        f"{sampling.deviation / sampling.size:.2g} of the size, edge stretch "
        f"{sampling.stretch:.2g}, smallest triangle corner {sampling.min_angle:.2f}°)"
    )
    print(
        markdown_table(
            ["stage", "chosen samples [s]", "chosen samples [CPU s]", "every sample [s]", "ratio"],
            rows,
        )
    )

    with tempfile.TemporaryDirectory() as c, tempfile.TemporaryDirectory() as cache:
        env = bytecode_env(cache)
        command = [
            str(Path(sys.executable).with_name("curvefold")),
            "vault",
            "--out",
            str(Path(c) / "warm-up"),
            "--json",
        ]
        children_cpu(command, env)  # writes the bytecode cache
        runs = []
        for k in range(REPEATS):
            command[3] = str(Path(c) / "v") + ("" if k == REPEATS - 1 else str(k))
            wall, cpu, done = children_cpu(command, env)
            if done.returncode != 0:
                raise RuntimeError(done.stderr)
            runs.append((wall, cpu))
        (wall, cpu), (wall_hi, cpu_hi) = np.min(runs, axis=0), np.max(runs, axis=0)
        size = _folder_bytes(Path(c) / "v") / 1e6
        fold_mb = (Path(c) / "v" / "vault.fold").stat().st_size / 1e6
        report = json.loads((Path(c) / "v" / "report.json").read_text())
        if not all(check["passed"] for check in report["certificate"]):
            raise RuntimeError("the certificate failed")
        timings = report["timings"]
        _, imports, _ = children_cpu(
            [sys.executable, "-c", "import " + ", ".join(LIBRARIES)],
            env | {"OPENBLAS_NUM_THREADS": "1"},
        )
        numpy = machine_speed(env)
    load = ", ".join(f"{v:.1f}" for v in os.getloadavg())
    print(f"load average of the machine during the run: {load} (on {os.cpu_count()} CPUs)")
    print(
        f"`curvefold vault` in a fresh process, best of {REPEATS}: {wall:.2f} s wall (at most "
        f"{wall_hi:.2f}), {cpu:.2f} CPU s (at most {cpu_hi:.2f}), folder {size:.1f} MB (FOLD "
        f"file {fold_mb:.2f} MB), every check passing; its own timings: "
        + ", ".join(f"{k} {v:.2f} s" for k, v in timings.items())
    )
    print(
        f"importing its libraries once in a fresh process: {imports:.2f} CPU s "
        f'({", ".join(LIBRARIES)}); the machine\'s speed: `python -c "import numpy"` takes '
        f"{numpy:.2f} CPU s"
    )
    return [
        SummaryRow(
            "main job",
            "`curvefold vault`, paper's vault, every format (fresh process): wall",
            f"{wall:.1f} s",
            f"≤ {TARGET_SECONDS:g} s",
            verdict(wall <= TARGET_SECONDS),
        ),
        SummaryRow(
            "main job",
            "the same, CPU seconds of the command and its job processes",
            f"{cpu:.1f} CPU s (importing its libraries: {imports:.1f}; NumPy alone: {numpy:.2f})",
            f"≤ {TARGET_CPU:g} CPU s",
            verdict(cpu <= TARGET_CPU),
        ),
        SummaryRow(
            "main job",
            "its folder",
            f"{size:.1f} MB ({sizes[1] / sizes[0]:.0f}× smaller than on every sample)",
            f"< {TARGET_MB:g} MB",
            verdict(size < TARGET_MB),
        ),
        SummaryRow(
            "main job",
            "all stages in one process, chosen vs every sample",
            f"{in_process:.1f} s vs {in_process_full:.1f} s",
            "—",
            "—",
        ),
    ]


def main() -> None:
    print("\n" + summary_table(run()))


if __name__ == "__main__":
    main()
