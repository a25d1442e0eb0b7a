"""The memory budget: the estimate of each job against the peak it reaches.

Each design runs through the command line in a process of its own (``python -m
curvefold``, with a budget large enough to let it run); its peak resident memory comes
from ``resource.getrusage(RUSAGE_CHILDREN).ru_maxrss`` after it exits, and is compared
with :func:`curvefold.app._budget.estimate` of the same design. The estimate must never be
below the peak (ratio ≥ 1); how far above it is the price of estimating from the design
alone (``tubes = "max"`` counts as 24 tubes, the crease patterns' cost is fitted on tubes).

Target: estimate / peak ≥ 1 for every design.

``--parts`` measures what the estimate's costs stand on: each part of each design of
:data:`PART_DESIGNS` in a process of its own (the interpreter, the built design with its
certificate, then that one part written in the same process), and prints the interpreter's
peak, the built design's peak over it and the part's peak over that (MiB).
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

from _bench import SummaryRow, markdown_table, verdict

#: (label, command-line arguments, design given to the estimate)
DESIGNS = (
    (
        "crease, 20001 samples, pictures",
        ["crease", "--samples", "20001"],
        {"kind": "crease", "samples": 20001},
    ),
    (
        "tube, 20001 samples, --json",
        ["tube", "--samples", "20001", "--json"],
        {"kind": "tube", "samples": 20001},
    ),
    (
        "tube, 2001 samples, SVG",
        ["tube", "--samples", "2001", "--formats", "svg"],
        {"kind": "tube", "samples": 2001, "output": {"formats": ["svg"]}},
    ),
    (
        "tube, 8001 samples, FOLD and 3D",
        ["tube", "--samples", "8001", "--formats", "fold,glb,obj,stl,ply,3dm"],
        {
            "kind": "tube",
            "samples": 8001,
            "output": {"formats": ["fold", "glb", "obj", "stl", "ply", "3dm"]},
        },
    ),
    (
        "block, 2001 samples, all formats",
        ["block", "--samples", "2001"],
        {"kind": "block", "samples": 2001},
    ),
    ("vault, 801 samples, all formats", ["vault"], {"kind": "vault"}),
    (
        "vault, 801 samples, 9 tubes, all formats",
        ["vault", "--tubes", "9"],
        {"kind": "vault", "vault": {"tubes": 9}},
    ),
    (
        "vault, 3001 samples, 9 tubes, FOLD",
        ["vault", "--samples", "3001", "--tubes", "9", "--formats", "fold"],
        {"kind": "vault", "samples": 3001, "vault": {"tubes": 9}, "output": {"formats": ["fold"]}},
    ),
    (
        "tube, 100000 panels, --json",
        ["tube", "--panels", "100000", "--json"],
        {"kind": "tube", "curve": {"panels": 100000}},
    ),
    (
        "vault, 20000 panels, 9 tubes, --json",
        ["vault", "--panels", "20000", "--tubes", "9", "--json"],
        {"kind": "vault", "vault": {"panels": 20000, "tubes": 9}},
    ),
)


#: Designs whose parts ``--parts`` measures (small to large, each kind).
PART_DESIGNS = (
    {"kind": "crease", "samples": 2001},
    {"kind": "crease", "samples": 20001},
    {"kind": "tube", "samples": 2001},
    {"kind": "tube", "samples": 8001},
    {"kind": "tube", "samples": 20001},
    {"kind": "tube", "samples": 32001},
    {"kind": "block", "samples": 2001},
    {"kind": "vault", "samples": 201, "vault": {"tubes": 9}},
    {"kind": "vault", "samples": 801, "vault": {"tubes": 9}},
    {"kind": "vault", "samples": 3001, "vault": {"tubes": 9}},
    {"kind": "vault", "samples": 801},
    {"kind": "vault", "samples": 1601},
)


def peak_of(argv: list[str]) -> tuple[float, float]:
    """Peak resident bytes and seconds of ``curvefold *argv`` in a fresh process."""
    with tempfile.TemporaryDirectory() as folder:
        out = [] if "--json" in argv else ["--out", os.path.join(folder, "out")]
        env = dict(os.environ, CURVEFOLD_MEMORY_BUDGET="1000G")
        t0 = time.perf_counter()
        # one process per design, so ru_maxrss of the children is this design's peak
        code = subprocess.run(
            [sys.executable, "-c", _CHILD, *argv, *out], env=env, capture_output=True, text=True
        )
        elapsed = time.perf_counter() - t0
    if code.returncode not in (0, 1):
        raise RuntimeError(f"curvefold {' '.join(argv)} failed: {code.stderr}")
    return float(code.stdout.strip()), elapsed


# Runs curvefold in a child of its own and prints that child's peak, in bytes.
_CHILD = """
import resource, subprocess, sys
subprocess.run([sys.executable, "-m", "curvefold", *sys.argv[1:]], capture_output=True)
unit = 1 if sys.platform == "darwin" else 1024  # ru_maxrss: bytes on macOS, KiB elsewhere
print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * unit)
"""


# Builds a design and writes one part of it in this process; prints the peaks (bytes) after the
# imports, after the built design and its certificate, and after the part.
_PART = """
import json, resource, sys, tempfile
from pathlib import Path
unit = 1 if sys.platform == "darwin" else 1024  # ru_maxrss: bytes on macOS, KiB elsewhere
peak = lambda: resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * unit
import curvefold.app.cli, curvefold.app._build, curvefold.app._outputs
interpreter = peak()
from curvefold.app import design_from_dict, _products as products
from curvefold.app._build import build
from curvefold.app._outputs import structure_payload
from curvefold.io._formats import FORMATS
data, part = json.loads(sys.argv[1]), sys.argv[2]
built = build(design_from_dict(data))
structure_payload(built)
geometry = peak()
if part != "geometry":
    formats = [] if part == "pictures" else [
        name for name in built.design.output.formats if FORMATS[name].family == part
    ]
    jobs = dict(products.jobs(built, formats))
    others = (label for label in jobs if label != "pictures")
    label = "pictures" if part == "pictures" else next(others)
    with tempfile.TemporaryDirectory() as folder:
        if label != "pictures":
            built.prepare()
            built.prepare_files(formats)
        jobs[label](Path(folder))
print(json.dumps([interpreter, geometry, peak()]))
"""


def parts() -> None:
    """Print the peak of each part of each of :data:`PART_DESIGNS` (MiB) and the estimate of the
    same."""
    import json

    from curvefold.app import design_from_dict
    from curvefold.app._budget import _parts, _samples, _strips, estimate

    for data in PART_DESIGNS:
        design = design_from_dict(data)
        n = _samples(design) * _strips(design)
        for part in ["geometry", *_parts(design, True)]:
            done = subprocess.run(
                [sys.executable, "-c", _PART, json.dumps(data), part],
                capture_output=True,
                text=True,
                check=True,
            )
            interpreter, geometry, peak = (x / 2**20 for x in json.loads(done.stdout))
            print(
                f"{json.dumps(data)}, {n} strip samples, {part}: interpreter "
                f"{interpreter:.1f}, built design +{geometry - interpreter:.1f}, part "
                f"+{peak - geometry:.1f}, peak {peak:.1f}; estimate "
                f"{estimate(design, files=part != 'geometry').total / 2**20:.0f}",
                flush=True,
            )


def run() -> list[SummaryRow]:
    from curvefold.app import design_from_dict
    from curvefold.app._budget import estimate

    rows, ratios = [], []
    for label, argv, data in DESIGNS:
        peak, seconds = peak_of(argv)
        guess = estimate(design_from_dict(data), files="--json" not in argv)
        ratios.append(guess.total / peak)
        rows.append(
            (
                label,
                f"{peak / 2**20:.0f}",
                f"{guess.total / 2**20:.0f}",
                f"{guess.total / peak:.2f}",
                guess.largest,
                f"{seconds:.0f}",
                verdict(guess.total >= peak),
            )
        )
        print(
            f"{label}: peak {peak / 2**20:.0f} MiB, estimate {guess.total / 2**20:.0f} MiB",
            flush=True,
        )
    print(
        markdown_table(
            [
                "design",
                "peak [MiB]",
                "estimate [MiB]",
                "estimate / peak",
                "costliest part",
                "time [s]",
                "estimate ≥ peak",
            ],
            rows,
        )
    )
    low, high = min(ratios), max(ratios)
    return [
        SummaryRow(
            "budget",
            f"estimate / measured peak over {len(DESIGNS)} designs",
            f"{low:.2f} to {high:.2f}",
            "≥ 1",
            verdict(low >= 1),
        )
    ]


def main() -> None:
    parts() if "--parts" in sys.argv[1:] else run()


if __name__ == "__main__":
    main()
