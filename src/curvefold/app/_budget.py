"""The memory budget of a run, and an estimate of each job from its design before it starts.

A design names how much it asks for: samples along the creases, tubes or cells, the files
to write. The command line estimates the peak memory of the job from the design alone
and refuses, before any work, a job whose estimate exceeds the budget, with the estimate
and what to lower.

The budget is :data:`DEFAULT_BUDGET` (2 GiB) unless the environment variable
``CURVEFOLD_MEMORY_BUDGET`` sets another (``4G``, ``512M``, ``1.5G`` or a number of bytes).

The estimate (:func:`estimate`) counts the size of the job as *strip samples*: samples
along the creases times the strips of the structure (four per cell; a single crease has
two surfaces). A structure of N rigid panels holds its smooth crease's samples and the
N + 1 vertices of every polyline besides, so each vertex counts as a sample. Each part of the job
costs a fixed amount, an amount per strip sample and, for the crease patterns, an amount per squared
sample (:data:`COSTS`), measured on curvefold's own runs (``benchmarks/bench_budget.py`` compares
the estimate with the measured peak and prints the ratio). The parts run one after the other, so the
peak is the interpreter, plus the geometry (the structure, its state and the certificate), plus the
largest of the file jobs. A design under load (:attr:`Design.mechanics
<curvefold.app.Design.mechanics>`) adds its bar-and-hinge model, its solves and its result, held
while the files are written, counted per strip sample the model keeps
(:func:`curvefold.mechanics.model_samples`; every panel vertex). A structure of thick panels
(rigid panels with a material) adds their work, held in the main process: the contact search of
their range of motion, and the dense DOF count of their linkage (:func:`thick_work`, which
also estimates its time).
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..io._formats import FAMILIES, FORMATS
from ..kernel._errors import InputError
from ..vault._tubes import DEFAULT_TUBES_CAP
from ._design import Design

if TYPE_CHECKING:  # pragma: no cover
    from ..mechanics import AtlasLoad

__all__ = [
    "DEFAULT_BUDGET",
    "ENVIRONMENT",
    "Estimate",
    "memory_budget",
    "parse_size",
    "estimate",
    "require_budget",
    "require_atlas_budget",
    "atlas_mechanics",
    "require_rebuild_budget",
    "require_deploy_budget",
    "ThickWork",
    "thick_work",
]

#: Memory a run may use, in bytes, unless :data:`ENVIRONMENT` says otherwise.
DEFAULT_BUDGET = 2 << 30
#: The largest budget: 1 PiB, far above any machine, far below where a byte count stops being exact.
MAX_BUDGET = 1 << 50
#: The environment variable that sets the budget.
ENVIRONMENT = "CURVEFOLD_MEMORY_BUDGET"

_MB = 1 << 20
#: The interpreter with NumPy and the command line loaded (bytes): 37.2 MiB measured (every library
#: a part imports, SciPy and Pillow among them, counts in that part's fixed cost), rounded up.
BASE = 40 * _MB
#: (fixed bytes, bytes per strip sample, bytes per squared sample) of each part of a job:
#: the geometry with the certificate, each family of formats, the report's pictures.
#: Measured with ``benchmarks/bench_budget.py --parts``: the peak of each part in a process of its
#: own, over the interpreter (the geometry) or over the estimate of the built design (each file
#: part), on a crease (2001 and 20001 samples), tubes (2001 to 32001), a block (2001), vaults of 9
#: tubes (201 to 3001) and of 24 (801 and 1601), and rounded up. The geometry's fixed cost is the
#: crease's SciPy (49 MiB at 2001 samples); per strip sample the tubes cost most (2390-2420 bytes
#: between 8001 and 32001 samples; vaults 700-1900). A single crease's FOLD file and 3D models cost
#: 4.8 and 4.1 kB per strip sample (187 and 165 MiB at 20001 samples), the file parts of the
#: structures 3-41 MiB above the built design whatever their size. Nothing grows with the square
#: of the samples any more (the crease patterns did, 1.6 GB at 8001 samples, until their glue tabs
#: were checked against nearby segments only and a sheet's bounding box found by rotating
#: calipers); the third number stays for a part that would.
COSTS: dict[str, tuple[float, float, float]] = {
    "geometry": (46 * _MB, 2450.0, 0.0),
    "pattern": (25 * _MB, 500.0, 0.0),
    "guide": (5 * _MB, 300.0, 0.0),
    "fold": (30 * _MB, 5000.0, 0.0),
    "model": (20 * _MB, 5400.0, 0.0),
    "motion": (45 * _MB, 400.0, 0.0),
    "pictures": (40 * _MB, 300.0, 0.0),
    # the STEP file of thick panels, written only for them (_parts): OpenCascade loaded and the
    # 16 solids of a tube written peak 282 MiB above the built design, the 576 of the paper's
    # vault at 16 panels 322-392 MiB, its 1728 at 48 panels 566 MiB; they grow with the solids,
    # not the samples (STEP_PER_SOLID)
    "solids": (280 * _MB, 0.0, 0.0),
    # measured: the peak of `curvefold load --json` over the geometry's estimate, 86 MiB for the
    # paper's vault (801 samples, 261 kept × 36 strips), 105 MiB at 3201 samples, 180 MiB at 12801,
    # 70 MiB with 256 panels, rounded up; measured again with the estimates above: the vault's load
    # peaks at 221, 357 and 884 MiB (801, 3201, 12801 samples) and 234 MiB (256 panels), below the
    # estimate of its geometry alone
    "mechanics": (40 * _MB, 8000.0, 0.0),
}
#: What ``--nonlinear`` adds to the part of the mechanics that grows with the model, as a share
#: of it: the path's tangents (the hinges' blocks made a chunk at a time), their factors, the
#: states kept (``curvefold.mechanics._collapse.STEPS`` at most). Measured on the paper's
#: vault (801 samples, 4 across): the command peaked at 1.72 GiB (2.07 GB before the chunks),
#: 0.82 GiB above the 0.90 GiB estimate of ``load``, 1.37 times the 0.60 GiB this share
#: multiplies; 1.5 makes the estimate 1.80 GiB, under the default budget.
COLLAPSE_SHARE = 1.5
#: Bytes of the atlas: its figure, each drawn design's record and sketch (0.46 MB measured on
#: 10 × 10 to 30 × 30 grids; records are streamed to disk, so only the designs the figure
#: shows, at most MAX_VIEWS² of them, are held), and per worker process an interpreter with what
#: a sweep imports (80 MiB, the interpreter with SciPy when it was measured; the largest worker of a
#: 200 × 200 atlas peaked at 110 MiB at 201 samples) and the geometry of a vault of up to
#: :data:`DEFAULT_TUBES_CAP` tubes per sample.
ATLAS_FIGURE, ATLAS_PER_DESIGN = 130 * _MB, 0.5 * _MB
ATLAS_PER_WORKER, ATLAS_PER_SAMPLE = 80 * _MB, COSTS["geometry"][1] * 4 * DEFAULT_TUBES_CAP
#: Bytes of a vault of the atlas under load (:func:`atlas_mechanics`), over a worker's: measured
#: on the 24-tube vault a = 0, p_xy = 1.5 (the peak of a process that analysed it over that of
#: one that built it at 201 samples with SciPy loaded): 118 MiB at 41 samples, 195 MiB at 81 and
#: 314 MiB at 41 with two elements across (k^1.8), rounded up to 45 MiB and 2 MiB per sample
#: kept, times k^2.
ATLAS_LOAD_FIXED, ATLAS_LOAD_PER_SAMPLE = 45 * _MB, 2 * _MB


#: Bytes of the STEP file per solid, over :data:`COSTS`' fixed part (see there).
STEP_PER_SOLID = 0.2 * _MB
#: The thick panels' work (:func:`thick_work`), fitted on the paper's vault (9 tubes) with
#: ``benchmarks/bench_thick_budget.py``, one process per design, CPU seconds: 16 panels at
#: t = 0.01 (576 solids, stops at 70.9°; measured 16 MiB, 2.2 s, STEP 3.5 s) and 48 at
#: t = 0.002 (1728 solids, stops at 67.3°; 27 MiB, 7.1-8.3 s, STEP 8.6 s). Memory: a fixed
#: part and a part per solid (the contact search's pairs a chunk at a time, the DOF count's
#: Jacobian of about 8 bars a panel: 1540 × 1164 at 48 panels, 14 MB).
THICK_FIXED, THICK_PER_SOLID = 10 * _MB, 10e3
#: Seconds: per solid and state of the contact search (the solids' pairs found by their boxes,
#: the faces' axes, the edges' only where those leave a pair deeper than the tolerance:
#: 2.1-3.1e-5 measured), per solid of the rest (the solids, the stack, the cut list's files),
#: per bar × unknown² of each SVD of the DOF count (1.6-2.0e-10), per solid of the STEP file
#: (OpenCascade: 5.0-6.1e-3).
THICK_PER_SOLID_STATE, THICK_PER_SOLID_FILE = 2.6e-5, 3e-4
THICK_PER_SVD, THICK_STEP_PER_SOLID = 1.8e-10, 5.5e-3
#: States the contact search tests: the range's two ends scanned 1° at a time from the design
#: angle (25 states, for a fold that stops within 25° of it as the measured vaults do: 72 and
#: 75 states in all with the bisections; one that folds flat from 90° scans up to 90, and takes
#: up to twice as long), bisected to 1e-7° (24 each), and the checks' 10 states.
THICK_STATES = 25 + 2 * 24 + 2 + 10


@dataclass(frozen=True)
class ThickWork:
    """The estimate of the thick panels' work before it starts.

    Attributes
    ----------
    memory : float
        Bytes above the built design, at the peak (the DOF count).
    seconds : float
        CPU seconds of the solids, their range, checks and cut list.
    step_seconds : float
        CPU seconds of the STEP file (written when the ``step`` format is asked for).
    unknowns : int
        Unknowns of the DOF count's linkage (its first tubes within
        :data:`~curvefold.analysis.CERTIFY_UNKNOWNS`).
    """

    memory: float
    seconds: float
    step_seconds: float
    unknowns: int


def _built_strips(design: Design) -> int:
    """The strips of the structure a design builds: a vault's ``tubes = "max"`` resolved on a
    coarse build (41 samples, 20 ms; the cap if that fails: the build will say why), as the
    thick work grows with the solids it has (9 tubes for the paper's vault, not 24)."""
    from ._design import VaultParams

    if design.design_kind.name != "vault" or design.params(VaultParams).tubes != "max":
        return _strips(design)
    from dataclasses import replace

    from ..vault import Vault
    from ._build import vault_design

    try:
        coarse = Vault.from_design(replace(vault_design(design), samples=41, panels=0))
    except InputError:
        return _strips(design)
    return 4 * len(coarse.structure.cells)


def thick_work(design: Design) -> ThickWork:
    """The thick panels' work of a design of rigid panels with a material, from the design
    alone (zeros for any other design).

    Its solids are N × strips (N panels per crease); the DOF count takes the first k tubes of
    at most 1000 unknowns (at least one), 3 per point: 4k (N + 1) hinge corners (every
    strip's crease points, an upper bound of the lattice's) and 4kN top points, with 8 bars
    per panel (its corners and top point welded to its neighbours': 1016 and 1540 bars
    measured for 128 and 192 panels); it is solved at :data:`RANGE_STATES` + 1 states.

    Examples
    --------
    >>> from curvefold.app import design_from_dict
    >>> w = thick_work(design_from_dict({"kind": "vault", "vault": {"panels": 48}, "material": {}}))
    >>> w.unknowns, round(w.memory / 2**20), round(w.seconds, 1), round(w.step_seconds, 1)
    (1164, 26, 8.1, 9.5)
    """
    from ..analysis._mechanism import CERTIFY_UNKNOWNS
    from ..analysis._thick_checks import RANGE_STATES

    panels = design.design_kind.panels(design)
    if design.material is None or not panels:
        return ThickWork(0.0, 0.0, 0.0, 0)
    strips = _built_strips(design)
    tubes = max(1, strips // 4)
    per_tube = 3 * (4 * (panels + 1) + 4 * panels)
    k = max(1, min(tubes, CERTIFY_UNKNOWNS // per_tube))
    unknowns, bars = k * per_tube, 8 * 4 * k * panels
    solids = panels * strips
    svd = bars * float(unknowns) ** 2 * (RANGE_STATES + 1)
    return ThickWork(
        THICK_FIXED + THICK_PER_SOLID * solids,
        (THICK_PER_SOLID_STATE * THICK_STATES + THICK_PER_SOLID_FILE) * solids
        + THICK_PER_SVD * svd,
        THICK_STEP_PER_SOLID * solids,
        unknowns,
    )


def memory_budget() -> int:
    """The budget in bytes: ``CURVEFOLD_MEMORY_BUDGET`` if set (see :func:`parse_size`),
    else :data:`DEFAULT_BUDGET`.

    Raises
    ------
    InputError
        The variable is not a size.
    """
    text = os.environ.get(ENVIRONMENT)
    return DEFAULT_BUDGET if text is None else parse_size(text, ENVIRONMENT)


def parse_size(text: str, name: str) -> int:
    """A memory size in bytes: a positive number with an optional K, M, G or T (powers of 1024).

    Examples
    --------
    >>> (
    ...     parse_size("1.5G", "budget") == 3 << 29,
    ...     parse_size("512 MiB", "budget"),
    ...     parse_size("4096", "budget"),
    ... )
    (True, 536870912, 4096)
    """
    match = re.fullmatch(r"\s*(\d+(?:\.\d*)?|\.\d+)\s*([KMGT]?)i?B?\s*", text, re.IGNORECASE)
    size = (
        float(match.group(1)) * 1024 ** "BKMGT".index(match.group(2).upper() or "B")
        if match
        else math.nan
    )
    if not 0 < size <= MAX_BUDGET:
        shown = repr(text) if len(text) <= 40 else f"{text[:20]!r}… ({len(text)} characters)"
        raise InputError(
            f"{name} must be a memory size such as 2G, 512M or a number of bytes, "
            f"at most {_size(MAX_BUDGET)}, got {shown}"
        )
    return int(size)


@dataclass(frozen=True)
class Estimate:
    """The estimated peak memory of a job.

    Attributes
    ----------
    total : float
        Bytes at the peak.
    strip_samples : int
        Size of the job: samples times strips.
    largest : str
        The costliest part of the job (``"geometry"``, ``"mechanics"``, a family of formats,
        ``"pictures"``).
    """

    total: float
    strip_samples: int
    largest: str


def _strips(design: Design) -> int:
    """Strips of the structure a design builds, as its kind counts them (a vault's
    ``tubes = "max"`` counts as its cap)."""
    return design.design_kind.strips(design)


def _samples(design: Design) -> int:
    """Points along each crease: the samples, and the N + 1 vertices of a structure of N panels."""
    panels = design.design_kind.panels(design)
    return design.samples + (panels + 1 if panels else 0)


def _parts(design: Design, files: bool) -> list[str]:
    if not files:
        return []
    parts = [*dict.fromkeys(FORMATS[name].family for name in design.output.formats), "pictures"]
    thick = design.material is not None and design.design_kind.panels(design)
    return parts if thick else [part for part in parts if part != "solids"]


def _cost(part: str, samples: int, n: int) -> float:
    fixed, linear, square = COSTS[part]
    return fixed + linear * n + square * float(samples) ** 2


def _mechanics(design: Design) -> float:
    """The mechanics of a design under load (0 for one that is not): its model keeps every panel
    vertex, or the samples of :func:`curvefold.mechanics.model_samples` of its k elements across
    each strip, which cost 0.4 k² times the part that grows with the strips for k ≥ 2 (k times
    the nodes, a band k times wider, a sparser factor than the band of one across: the
    paper's vault peaks at 0.22, 0.25, 0.70 and 2.45 GB with k = 1, 2, 4, 8 on 261, 131, 131
    and 131 samples). The model on k / 2 that estimates the errors is solved after it,
    in less."""
    if not design.mechanics:
        return 0.0
    from ..mechanics import ACROSS, model_samples

    across = design.loads.across if design.loads is not None else ACROSS.default
    panels = design.design_kind.panels(design)
    kept = panels + 1 if panels else len(model_samples(design.samples, across))
    fixed = _cost("mechanics", 0, 0)
    scale = 1.0 if across == 1 else 0.4 * across**2
    grows = (_cost("mechanics", kept, kept * _strips(design)) - fixed) * scale
    nonlinear = design.loads is not None and design.loads.nonlinear
    return fixed + grows * (1 + COLLAPSE_SHARE if nonlinear else 1)


def estimate(design: Design, *, files: bool) -> Estimate:
    """The peak memory of building ``design`` (and, with ``files``, writing its formats
    and pictures), from the design alone: the interpreter, the geometry, the mechanics of
    a design under load, its thick panels' work (:func:`thick_work`) and the costliest file
    job (they run one after the other)."""
    samples = _samples(design)
    n = samples * _strips(design)
    jobs = {part: _cost(part, samples, n) for part in _parts(design, files)}
    if "solids" in jobs:  # the STEP file grows with the solids
        jobs["solids"] += STEP_PER_SOLID * design.design_kind.panels(design) * _built_strips(design)
    mechanics = _mechanics(design)
    largest = max(
        jobs, key=lambda part: jobs[part], default="mechanics" if mechanics else "geometry"
    )
    held = BASE + _cost("geometry", samples, n) + mechanics + thick_work(design).memory
    return Estimate(held + jobs.get(largest, 0.0), n, largest)


def require_budget(design: Design, *, files: bool) -> Estimate:
    """The estimate of a job, or :class:`InputError` if it exceeds the budget.

    The message gives the estimate, the budget, the largest sample count that fits and
    what else to lower.
    """
    budget = memory_budget()
    found = estimate(design, files=files)
    if found.total <= budget:
        return found
    strips = _strips(design)
    fits = _samples_that_fit(design, files, budget)
    what = design.design_kind.lower
    lower = [f"samples (at most {fits} fit)" if fits else "samples", *([what] if what else [])]
    if _samples(design) > design.samples:
        lower.insert(1, "panels")
    if found.largest not in ("geometry", "mechanics"):
        lower.append(f"the formats written ({_FAMILY_NAMES[found.largest]} cost most)")
    raise InputError(
        f"{design.source}: this job needs about {_size(found.total)} of memory "
        f"({_points(design)} × {strips} strips{_thick_words(design)}), more than the budget of "
        f"{_size(budget)} "
        f"({ENVIRONMENT}); lower " + ", ".join(lower)
    )


def _thick_words(design: Design) -> str:
    """``", thick panels 16 MiB and 2.6 CPU-s"``: the thick work's part (:func:`thick_work`)."""
    work = thick_work(design)
    if not work.memory:
        return ""
    return f", thick panels {_size(work.memory)} and {work.seconds:.2g} CPU-s"


def _points(design: Design) -> str:
    extra = _samples(design) - design.samples
    return f"{design.samples} samples" + (f" + {extra} panel vertices" if extra else "")


def _samples_that_fit(design: Design, files: bool, budget: int) -> int | None:
    """The largest sample count whose job fits the budget (the estimate grows with it), or None."""
    from dataclasses import replace

    fits = lambda m: estimate(replace(design, samples=m), files=files).total <= budget  # noqa: E731
    if not fits(9):
        return None
    lo, hi = 9, design.samples  # fits(lo), not fits(hi)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        lo, hi = (mid, hi) if fits(mid) else (lo, mid)
    return lo


def require_atlas_budget(
    designs: int, *, samples: int, workers: int | None, load: AtlasLoad | None = None
) -> float:
    """The estimate of an atlas of ``designs`` designs, or :class:`InputError` over budget.

    With ``load``, every process also holds the mechanics of one vault of up to
    :data:`DEFAULT_TUBES_CAP` tubes at the load's samples and elements across
    (:func:`atlas_mechanics`).
    """
    budget = memory_budget()
    processes = workers or min(2, os.cpu_count() or 1)
    from ..figures._atlas import MAX_VIEWS

    held = min(designs, MAX_VIEWS**2)
    mechanics = 0.0 if load is None else atlas_mechanics(load.samples, load.across)
    total = (
        BASE
        + ATLAS_FIGURE
        + ATLAS_PER_DESIGN * held
        + processes * (ATLAS_PER_WORKER + ATLAS_PER_SAMPLE * samples + mechanics)
    )
    if total > budget:
        lower = "" if load is None else ", --load-samples or --across"
        raise InputError(
            f"this atlas needs about {_size(total)} of memory ({designs} designs, {samples} "
            f"samples, {processes} processes"
            + ("" if load is None else f", mechanics on {load.samples} samples × {load.across}")
            + f"), more than the budget of {_size(budget)} "
            f"({ENVIRONMENT}); lower the grid's counts, --samples or --workers{lower}"
        )
    return total


def atlas_mechanics(samples: int, across: int) -> float:
    """Bytes of the mechanics of one vault of an atlas: the vault rebuilt at ``samples`` and its
    model and solves, for the most tubes a vault of the atlas has (:data:`DEFAULT_TUBES_CAP`),
    :data:`ATLAS_LOAD_FIXED` and :data:`ATLAS_LOAD_PER_SAMPLE` per sample the model keeps, times
    ``across`` squared.

    Examples
    --------
    >>> round(atlas_mechanics(41, 1) / 2**20), round(atlas_mechanics(41, 4) / 2**20)
    (127, 1357)
    """
    from ..mechanics import model_samples

    kept = len(model_samples(samples))
    return ATLAS_LOAD_FIXED + ATLAS_LOAD_PER_SAMPLE * kept * across**2


#: Bytes per strip sample and frame of a FOLD file built again and read (``curvefold check
#: --rebuild``): its coordinates and fold angles as arrays, as JSON data and read back. Measured:
#: the peak of ``check --rebuild`` over that of ``check`` grew by 225–250 bytes per strip sample and
#: frame (tubes of 201 and 801 samples, 10 to 100 frames), rounded up.
REBUILD_PER_FRAME = 300.0


def require_rebuild_budget(design: Design, frames: int) -> float:
    """The estimate of building ``design`` again with ``frames`` FOLD frames, or
    :class:`InputError` over budget."""
    budget = memory_budget()
    found = estimate(design, files=False)
    total = found.total + REBUILD_PER_FRAME * frames * found.strip_samples
    if total > budget:
        raise InputError(
            f"{design.source}: rebuilding this design needs about {_size(total)} of memory "
            f"({design.samples} samples × {_strips(design)} strips, {frames} frames), more "
            f"than the budget of {_size(budget)} ({ENVIRONMENT})"
        )
    return total


#: What each part writes, as the subject of a sentence ("the crease patterns").
_FAMILY_NAMES = {
    **{family: text.rsplit(" ", 1)[0] for family, text in FAMILIES.items()},
    "pictures": "the pictures",
}


def _size(n: float) -> str:
    return (
        f"{n / (1 << 50):.0f} PiB"
        if n >= 1 << 50
        else f"{n / (1 << 30):.1f} GiB"
        if n >= 1 << 30
        else f"{n / _MB:.0f} MiB"
    )


#: Bytes a deployment keeps per state and per model node: its displacements and kinematic
#: positions (two (P, 3) float arrays), the rest of its state dropped after each step.
DEPLOY_PER_STATE = 48.0


def require_deploy_budget(design: Design, states: int) -> float:
    """The estimate of deploying ``design`` through ``states`` fold angles: the design under
    load (its geometry and one model, the solve of every step in place of the load's), plus
    every state kept (:data:`DEPLOY_PER_STATE` per node, one node per kept strip sample),
    or :class:`InputError` over budget."""
    from ..mechanics import model_samples

    budget = memory_budget()
    loaded = design.with_mechanics()
    found = estimate(loaded, files=False)
    panels = design.design_kind.panels(design)
    kept = panels + 1 if panels else len(model_samples(design.samples))
    total = found.total + DEPLOY_PER_STATE * states * kept * _strips(design)
    if total > budget:
        raise InputError(
            f"{design.source}: this deployment needs about {_size(total)} of memory "
            f"({design.samples} samples × {_strips(design)} strips, {states} states), more "
            f"than the budget of {_size(budget)} ({ENVIRONMENT}); lower samples or raise --step"
        )
    return total
