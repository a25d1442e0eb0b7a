"""The memory budget of a run, and an estimate of each job from its design before it starts.

A design names how much it asks for: samples along the creases, tubes or cells, the files
to write. The command line estimates the peak memory of the job from the design alone
and refuses, before any work, a job whose estimate exceeds the budget, with the estimate
and what to lower.

The budget is :data:`DEFAULT_BUDGET` (2 GiB) unless the environment variable
``CURVEFOLD_MEMORY_BUDGET`` sets another (``4G``, ``512M``, ``1.5G`` or a number of bytes).

The estimate (:func:`estimate`) counts the size of the job as *strip samples*: samples
along the creases times the strips of the structure (four per cell; a single crease has
two surfaces). Each part of the job costs a fixed amount plus an amount per strip sample,
measured on curvefold's own runs (``benchmarks/bench_budget.py`` compares the estimate with
the measured peak and prints the ratio). The parts run one after the other, so the peak is
the interpreter, plus the geometry (the structure, its state and the certificate), plus
the largest of the file jobs.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass

from ..io.formats import FORMATS
from ..kernel.errors import InputError
from ..vault.assembly import DEFAULT_TUBES_CAP
from .design import Design

__all__ = ["DEFAULT_BUDGET", "ENVIRONMENT", "Estimate", "memory_budget", "estimate", "require_budget", "require_atlas_budget"]

#: Memory a run may use, in bytes, unless :data:`ENVIRONMENT` says otherwise.
DEFAULT_BUDGET = 2 << 30
#: The environment variable that sets the budget.
ENVIRONMENT = "CURVEFOLD_MEMORY_BUDGET"

_MB = 1 << 20
#: The interpreter with NumPy, SciPy and curvefold loaded (bytes).
BASE = 80 * _MB
#: (fixed bytes, bytes per strip sample) of each part of a job: the geometry and the
#: certificate, each family of formats, and the report's pictures.
COSTS: dict[str, tuple[float, float]] = {
    "geometry": (10 * _MB, 600.0),
    "pattern": (60 * _MB, 6000.0),
    "fold": (10 * _MB, 2500.0),
    "model": (40 * _MB, 3500.0),
    "motion": (40 * _MB, 2800.0),
    "pictures": (60 * _MB, 2500.0),
}
#: Bytes of one design of the atlas per sample, in a worker process, and the atlas's figure
#: and records per design.
ATLAS_PER_SAMPLE = 600.0 * 4 * DEFAULT_TUBES_CAP
ATLAS_PER_DESIGN = 2 * _MB


def memory_budget() -> int:
    """The budget in bytes: ``CURVEFOLD_MEMORY_BUDGET`` if set, else :data:`DEFAULT_BUDGET`.

    Raises
    ------
    InputError
        The variable is not a size.

    Examples
    --------
    >>> os.environ[ENVIRONMENT] = "1.5G"
    >>> memory_budget() == 3 << 29
    True
    >>> del os.environ[ENVIRONMENT]
    """
    text = os.environ.get(ENVIRONMENT)
    if text is None:
        return DEFAULT_BUDGET
    match = re.fullmatch(r"\s*(\d+(?:\.\d*)?|\.\d+)\s*([KMGT]?)i?B?\s*", text, re.IGNORECASE)
    if match is None or float(match.group(1)) <= 0:
        raise InputError(f"{ENVIRONMENT} must be a memory size such as 2G, 512M or a number of bytes, got {text!r}")
    return int(float(match.group(1)) * 1024 ** "BKMGT".index(match.group(2).upper() or "B"))


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
        The costliest part of the job (``"geometry"``, a family of formats, ``"pictures"``).
    """

    total: float
    strip_samples: int
    largest: str


def _strips(design: Design) -> int:
    """Strips of the structure a design builds (``tubes = "max"`` counts as its cap)."""
    if design.kind == "vault":
        tubes = DEFAULT_TUBES_CAP if design.vault.tubes == "max" else design.vault.tubes
        return 4 * tubes * design.vault.layers
    if design.kind == "block":
        return 4 * len(design.block.cells)
    return 4 if design.kind == "tube" else 2


def _parts(design: Design, files: bool) -> list[str]:
    if not files:
        return []
    return [*dict.fromkeys(FORMATS[name].family for name in design.output.formats), "pictures"]


def estimate(design: Design, *, files: bool) -> Estimate:
    """The peak memory of building ``design`` (and, with ``files``, writing its formats
    and pictures), from the design alone."""
    n = design.samples * _strips(design)
    costs = {part: COSTS[part][0] + COSTS[part][1] * n for part in _parts(design, files)}
    largest = max(costs, key=costs.get, default="geometry")
    geometry = COSTS["geometry"][0] + COSTS["geometry"][1] * n
    return Estimate(BASE + geometry + costs.get(largest, 0.0), n, largest)


def require_budget(design: Design, *, files: bool) -> Estimate:
    """The estimate of a job, or :class:`InputError` if it exceeds the budget.

    The message gives the estimate, the budget, the largest sample count that fits and
    what else to lower.
    """
    budget = memory_budget()
    found = estimate(design, files=files)
    if found.total <= budget:
        return found
    fixed = BASE + COSTS["geometry"][0] + (COSTS[found.largest][0] if found.largest != "geometry" else 0)
    per_strip_sample = COSTS["geometry"][1] + (COSTS[found.largest][1] if found.largest != "geometry" else 0)
    fits = int((budget - fixed) / per_strip_sample / _strips(design))
    what = {"vault": "[vault] tubes or layers (tubes = \"max\" counts as 24)", "block": "[block] cells"}.get(design.kind)
    lower = [f"samples (at most {fits} fit)" if fits >= 3 else "samples", *([what] if what else [])]
    if found.largest != "geometry":
        lower.append(f"the formats written ({_FAMILY_NAMES[found.largest]} cost most)")
    raise InputError(
        f"{design.source}: this job needs about {_size(found.total)} of memory ({design.samples} samples × "
        f"{_strips(design)} strips), more than the budget of {_size(budget)} ({ENVIRONMENT}); lower " + ", ".join(lower)
    )


def require_atlas_budget(designs: int, *, samples: int, workers: int | None) -> float:
    """The estimate of an atlas of ``designs`` designs, or :class:`InputError` over budget."""
    budget = memory_budget()
    processes = workers or min(2, os.cpu_count() or 1)
    total = BASE * (1 + processes) + processes * ATLAS_PER_SAMPLE * samples + ATLAS_PER_DESIGN * designs
    if total > budget:
        raise InputError(
            f"this atlas needs about {_size(total)} of memory ({designs} designs, {samples} samples, {processes} processes), "
            f"more than the budget of {_size(budget)} ({ENVIRONMENT}); lower the grid's counts, --samples or --workers"
        )
    return total


_FAMILY_NAMES = {"pattern": "the crease patterns", "fold": "the FOLD files", "model": "the 3D models",
                 "motion": "the folding GIF", "pictures": "the pictures"}


def _size(n: float) -> str:
    return f"{n / (1 << 30):.1f} GiB" if n >= 1 << 30 else f"{n / _MB:.0f} MiB"
