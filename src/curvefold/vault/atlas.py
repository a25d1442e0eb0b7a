"""The design atlas of composite vaults: a grid over (p_xy, a) (the paper's Fig. 10, extended).

For every pair of section proportion p_xy = w_R(0)/w_L(0) and torsion amplitude a, the
vault is built with :meth:`curvefold.vault.Vault.from_design` and its
:meth:`~curvefold.vault.Vault.summary` metrics are recorded. A design that cannot be built
(no standing arch, regression, a parameter out of range: any
:class:`~curvefold.kernel.errors.CurvefoldError` raised while building it) is recorded as
invalid with the reason, and the sweep goes on. Any error past that point (measuring or
drawing a built vault) is a bug and propagates. Each valid design also keeps a small
:class:`Sketch` of its geometry so the atlas figure needs no vault rebuilt.

Records are flat dicts with the keys of :data:`FIELDS`; the grid is stored row-major,
rows = a, columns = p_xy, whatever order the designs finish in.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..io.atomic import atomic_write
from ..kernel.errors import CurvefoldError, InputError

if TYPE_CHECKING:  # pragma: no cover
    from .assembly import Vault

__all__ = ["Atlas", "Sketch", "run_atlas", "evaluate_design", "FIELDS", "METRICS"]

#: Metrics taken from :meth:`Vault.summary` (footprint split into x and y), model units and degrees.
METRICS = (
    "kappa0_s0",
    "proportion_change",
    "p_xz",
    "tubes",
    "max_tubes",
    "span",
    "rise",
    "footprint_x",
    "footprint_y",
    "slope_xy_deg",
    "slope_zx_deg",
    "regression_margin",
    "ground_error",
)
#: Keys of every record, in CSV column order. ``row``/``col`` index ``a_values``/``p_xy_values``;
#: ``error`` is the exception class and ``reason`` its message (both None for a valid design);
#: the metrics are None for an invalid design.
FIELDS = ("row", "col", "a", "p_xy", "width", "fold_angle", "valid", "error", "reason") + METRICS
_INTEGER = {"row", "col", "tubes", "max_tubes"}

#: Parallel runs send each worker about this many chunks of designs (progress granularity).
CHUNKS_PER_WORKER = 16
#: Samples along t and tubes kept in a sketch (the apex and both feet are always samples);
#: SKETCH_TUBES matches the vault's default cap, so default stacks are drawn whole.
SKETCH_SAMPLES = 17
SKETCH_TUBES = 24


@dataclass(frozen=True, eq=False)
class Sketch:
    """Light-weight geometry of a vault at its design angle, for drawing.

    Attributes
    ----------
    curves : (M, k, 3) ndarray of float32
        Lattice curves of the drawn tubes, subsampled to k points along t (feet, apex kept).
    cells : (K, 4) ndarray of int32
        Rows of ``curves`` at corners 1–4 of every drawn tube (evenly thinned for long stacks).
    kinds : tuple of str
        "fold", "seam" or "junction" for every row of ``curves``.
    feet : (2, 3) ndarray
        Ends of the section feature line at t = 0 (in the ground, xy plane): the corners
        (j, j) of the first and last tube of the whole stack.
    apex : (2, 3) ndarray
        Ends of the section feature line at t = ½ (in the zx plane).
    """

    curves: np.ndarray
    cells: np.ndarray
    kinds: tuple[str, ...]
    feet: np.ndarray
    apex: np.ndarray

    @classmethod
    def from_vault(cls, vault: Vault, *, samples: int = SKETCH_SAMPLES, tubes: int = SKETCH_TUBES) -> Sketch:
        """Subsample a vault's curves at its design angle (at most ``tubes`` tubes, ~``samples`` points)."""
        from ..geometry.structure import drawable

        structure = vault.structure
        V = vault.vertices  # (M, n, 3)
        curves, cells, kinds = drawable(structure, V, segments=samples - 1, max_cells=tubes)
        uv = structure.curves_uv
        diag = np.flatnonzero(uv[:, 0] == uv[:, 1])
        ends = diag[[np.argmin(uv[diag, 0]), np.argmax(uv[diag, 0])]]
        m = vault.apex_index
        out = cls(curves.astype(np.float32), cells.astype(np.int32), kinds, V[ends, 0].copy(), V[ends, m].copy())
        for arr in (out.curves, out.cells, out.feet, out.apex):
            arr.flags.writeable = False
        return out


def evaluate_design(
    a: float,
    p_xy: float,
    *,
    width: float = 0.08,
    fold_angle: float = 90.0,
    tubes: int | None = None,
    samples: int = 201,
) -> tuple[dict, Sketch | None]:
    """Build one vault and return its flat record and sketch; an invalid design is a record too.

    Returns
    -------
    record : dict
        Keys of :data:`FIELDS` except ``row`` and ``col``.
    sketch : Sketch or None
        None for an invalid design.
    """
    from .assembly import Vault, VaultDesign

    record: dict[str, Any] = {"a": _number(a), "p_xy": _number(p_xy), "width": float(width), "fold_angle": float(fold_angle)}
    try:
        vault = Vault.from_design(VaultDesign(a=a, p_xy=p_xy, width=width, fold_angle=fold_angle, tubes=tubes, samples=samples))
    except CurvefoldError as err:  # the design is refused: a record, not an error
        record.update(valid=False, error=type(err).__name__, reason=str(err))
        record.update(dict.fromkeys(METRICS))
        return record, None
    # A built vault that cannot be measured or drawn is a bug: it propagates.
    record.update(valid=True, error=None, reason=None)
    record.update(metrics_of(vault.summary()))
    return record, Sketch.from_vault(vault)


def metrics_of(summary: dict) -> dict:
    """The :data:`METRICS` of a :meth:`Vault.summary` dict, as plain Python numbers."""
    out = {k: summary[k] for k in METRICS if k in summary}
    out["footprint_x"], out["footprint_y"] = summary["footprint"]
    return {k: int(out[k]) if k in _INTEGER else float(out[k]) for k in METRICS}


def _number(x: Any) -> Any:
    """A grid value as a plain float when it is a real number (kept as is otherwise, for the record)."""
    try:
        return float(x)
    except (TypeError, ValueError):
        return x


def _task(args: tuple) -> tuple[int, dict, Sketch | None]:
    """(index, record, sketch) of one grid point."""
    index, a, p, kwargs = args
    record, sketch = evaluate_design(a, p, **kwargs)
    return index, record, sketch


def _chunk(tasks: list) -> list[tuple[int, dict, Sketch | None]]:
    """Worker entry point: several grid points in one round trip (per-task overhead ~ a design)."""
    return [_task(t) for t in tasks]


@dataclass(frozen=True, eq=False)
class Atlas:
    """A grid of vault designs over (p_xy, a) with their metrics.

    Build it with :func:`run_atlas`.

    Attributes
    ----------
    p_xy_values : tuple of float
        Column values (section proportion at the feet).
    a_values : tuple of float
        Row values (torsion amplitude).
    width, fold_angle : float
        Shared design parameters (w_L(0) κ₀ and 2α in degrees).
    tubes : int or None
        Tubes per vault (None: each design's maximum before regression).
    samples : int
        Samples along each crease.
    records : tuple of dict
        One record per grid point, row-major (``records[row * len(p_xy_values) + col]``).
    sketches : tuple of Sketch or None
        Geometry for drawing, parallel to ``records`` (None for an invalid design).
    """

    p_xy_values: tuple[float, ...]
    a_values: tuple[float, ...]
    width: float
    fold_angle: float
    tubes: int | None
    samples: int
    records: tuple[dict, ...]
    sketches: tuple[Sketch | None, ...] = field(repr=False)

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, columns) = (len(a_values), len(p_xy_values))."""
        return len(self.a_values), len(self.p_xy_values)

    def record(self, row: int, col: int) -> dict:
        """The record of a_values[row], p_xy_values[col]."""
        rows, cols = self.shape
        if not (0 <= row < rows and 0 <= col < cols):
            raise InputError(f"(row, col) must be in [0, {rows}) × [0, {cols}), got ({row}, {col})")
        return self.records[row * cols + col]

    def grid(self, key: str) -> np.ndarray:
        """One numeric field over the grid, shape (rows, cols); NaN for invalid designs."""
        if key not in FIELDS or key in ("error", "reason"):
            raise InputError(f"key must be a numeric field of the atlas ({', '.join(k for k in FIELDS if k not in ('error', 'reason'))}), got {key!r}")
        values = [np.nan if r[key] is None else float(r[key]) for r in self.records]
        return np.array(values, float).reshape(self.shape)

    # -- files ------------------------------------------------------------------------------
    def to_csv(self, path: str | os.PathLike) -> Path:
        """Write the records as CSV (one row per design, columns :data:`FIELDS`), atomically.

        Floats are written with ``repr`` (they read back exactly); missing metrics of an
        invalid design are empty cells; ``valid`` is ``True``/``False``.
        """
        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        writer.writerow(FIELDS)
        for r in self.records:
            writer.writerow(["" if r[k] is None else repr(r[k]) if isinstance(r[k], float) else r[k] for k in FIELDS])
        return atomic_write(path, buf.getvalue())

    def to_json(self, path: str | os.PathLike) -> Path:
        """Write the grid parameters and the records as JSON, atomically (missing metrics are null)."""
        doc = {
            "format": "curvefold-atlas",
            "version": 1,
            "units": "model units (radius 1), angles in degrees",
            "p_xy_values": list(self.p_xy_values),
            "a_values": list(self.a_values),
            "width": self.width,
            "fold_angle": self.fold_angle,
            "tubes": self.tubes,
            "samples": self.samples,
            "fields": list(FIELDS),
            "records": [{k: _json_value(r[k]) for k in FIELDS} for r in self.records],
        }
        return atomic_write(path, json.dumps(doc, indent=1, ensure_ascii=False, allow_nan=False) + "\n")


def _json_value(v: Any) -> Any:
    if isinstance(v, float) and not math.isfinite(v):
        return None
    if isinstance(v, (np.floating, np.integer)):  # pragma: no cover - records hold plain numbers
        return v.item()
    return v


def _check_values(values: Sequence[float], name: str) -> tuple[float, ...]:
    """A grid axis as a tuple of floats; each value is checked later, per design."""
    try:
        arr = np.asarray(values, dtype=float) if not isinstance(values, (str, bytes)) else np.array([])
    except (TypeError, ValueError):
        arr = np.array([])
    if arr.ndim != 1 or arr.size == 0:
        raise InputError(f"{name} must be a non-empty 1-D sequence of numbers, got {values!r}")
    return tuple(float(x) for x in arr)


def run_atlas(
    p_xy_values: Sequence[float],
    a_values: Sequence[float],
    *,
    width: float = 0.08,
    fold_angle: float = 90.0,
    tubes: int | None = None,
    samples: int = 201,
    workers: int | None = None,
    progress: Callable[[int, int], Any] | None = None,
) -> Atlas:
    """Build the vault of every (p_xy, a) of a grid and record its metrics.

    Parameters
    ----------
    p_xy_values : (C,) array_like
        Section proportions w_R(0)/w_L(0): the columns.
    a_values : (R,) array_like
        Torsion amplitudes: the rows. a ≥ :data:`curvefold.vault.arch.A_MAX` has no standing arch
        and is recorded as invalid.
    width, fold_angle, tubes, samples : keyword-only
        Shared :class:`~curvefold.vault.VaultDesign` parameters (validated once, here).
    workers : int, optional, keyword-only
        Processes; default ``min(2, os.cpu_count())``. 1 runs in this process. Designs
        run in parallel only when there are at least two of them. Where processes are
        spawned rather than forked (Windows, macOS), call this under
        ``if __name__ == "__main__":``.
    progress : callable, optional, keyword-only
        ``progress(done, total)``, called with 0 first and after every finished design.

    Returns
    -------
    Atlas
        Records in grid order (row-major, rows = a), whatever order designs finish in.

    Examples
    --------
    A grid point past the arch family is recorded, not raised:

    >>> atlas = run_atlas([0.75], [1.5], workers=1)
    >>> atlas.records[0]["valid"], atlas.records[0]["error"]
    (False, 'ConvergenceError')
    """
    from .assembly import VaultDesign

    ps = _check_values(p_xy_values, "p_xy_values")
    as_ = _check_values(a_values, "a_values")
    VaultDesign(width=width, fold_angle=fold_angle, tubes=tubes, samples=samples)  # shared parameters: fail once, here
    if workers is None:
        workers = min(2, os.cpu_count() or 1)
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1:
        raise InputError(f"workers must be an integer ≥ 1 (or None for min(2, CPUs)), got {workers!r}")
    if progress is not None and not callable(progress):
        raise InputError(f"progress must be a callable progress(done, total) or None, got {progress!r}")

    kwargs = {"width": float(width), "fold_angle": float(fold_angle), "tubes": tubes, "samples": int(samples)}
    tasks = [(i * len(ps) + j, a, p, kwargs) for i, a in enumerate(as_) for j, p in enumerate(ps)]
    total = len(tasks)
    records: list[dict | None] = [None] * total
    sketches: list[Sketch | None] = [None] * total
    if progress is not None:
        progress(0, total)

    def store(index: int, record: dict, sketch: Sketch | None, done: int) -> None:
        row, col = divmod(index, len(ps))
        records[index] = {"row": row, "col": col, **record}
        sketches[index] = sketch
        if progress is not None:
            progress(done, total)

    processes = min(int(workers), total)
    if processes <= 1:
        for done, task in enumerate(tasks, 1):
            store(*_task(task), done)
    else:
        # Interleaved chunks: balanced (cost varies along the grid) and few round trips.
        count = min(total, processes * CHUNKS_PER_WORKER)
        pool = ProcessPoolExecutor(max_workers=processes)
        try:
            futures = [pool.submit(_chunk, tasks[k::count]) for k in range(count)]
            done = 0
            for future in as_completed(futures):
                for result in future.result():
                    done += 1
                    store(*result, done)
        finally:  # on an error (a bug, an interrupt) drop the chunks not started yet
            pool.shutdown(wait=True, cancel_futures=True)
    return Atlas(ps, as_, float(width), float(fold_angle), tubes, int(samples), tuple({k: r[k] for k in FIELDS} for r in records), tuple(sketches))  # type: ignore[index]
