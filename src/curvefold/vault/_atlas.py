"""The design atlas of composite vaults: a grid over (p_xy, a) (the paper's Fig. 10, extended).

For every pair of section proportion p_xy = w_R(0)/w_L(0) and torsion amplitude a, the
vault is built with :meth:`curvefold.vault.Vault.from_design` and its
:meth:`~curvefold.vault.Vault.summary` metrics are recorded. A design that cannot be built
(no standing arch, regression, a parameter out of range: any
:class:`~curvefold.kernel.CurvefoldError` raised while building it) is recorded as
invalid with the reason, and the sweep goes on. Any error past that point (measuring or
drawing a built vault) is a bug and propagates. Each valid design also keeps a small
:class:`Sketch` of its geometry so the atlas figure needs no vault rebuilt.

Records are flat dicts with the keys of :data:`FIELDS`; the grid is row-major, rows = a,
columns = p_xy. :func:`sweep` streams them: it yields every design's record and sketch in
grid order while later designs are still running, holding a few chunks of results at
most, so a grid of any size runs in flat memory (the command line writes each record to
disk as it comes). Designs run in this process, on a local Dask cluster of worker
processes, or on an existing Dask cluster; every way gives the same records, bit for bit
(each design is computed by the same code from the same numbers). Dask is optional
(``pip install 'curvefold[dask]'``) and imported only when a cluster is used.
"""

from __future__ import annotations

import math
import pickle
from collections.abc import Callable, Generator, Iterable, Iterator, Sequence
from contextlib import closing
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from ..kernel._arrays import FrozenArrays
from ..kernel._errors import CurvefoldError, InputError
from ..kernel._validate import Interval, Spec, check_integer
from ._arch import A_MAX, check_standing
from ._cluster import batched, cluster_plan, in_order
from ._cluster import client as cluster_client

if TYPE_CHECKING:  # pragma: no cover
    from ._assembly import Vault

__all__ = [
    "Atlas",
    "AtlasGrid",
    "Sketch",
    "sweep",
    "run_atlas",
    "thin",
    "evaluate_design",
    "FIELDS",
    "METRICS",
    "GRID_A",
]

#: ``a`` of the grid's rows, in [0, 2 A_MAX] (:data:`~curvefold.vault.A_MAX`): a grid reaches past
#: where the arches stop standing to show it, recording those designs as having no standing arch.
GRID_A = Spec(
    "a",
    "real",
    0.3,
    Interval(0.0, 2 * A_MAX, True, True),
    help="torsion amplitude a of a row of the grid",
    why=f"up to twice {A_MAX:.4f}, where arches stop standing",
)

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

#: Samples along t and tubes kept in a sketch (the apex and both feet are always samples);
#: SKETCH_TUBES matches the vault's default cap, so default stacks are drawn whole.
SKETCH_SAMPLES = 17
SKETCH_TUBES = 24

#: Designs per task sent to a cluster at most. Tasks shrink as the grid runs out (each takes
#: a 1/(2 × worker threads) share of the designs left, down to :data:`MIN_CHUNK`), so a
#: sweep has few tasks, each costing the client and scheduler milliseconds of CPU that the
#: workers share on a small machine, and ends on small ones, which keep every worker busy to
#: the end. A task holds whole rows (one arch each) unless a row is larger.
CHUNK = 400
#: Designs per task at least, where a row holds as many (the grid's last task may be smaller).
MIN_CHUNK = 40
#: Tasks queued or running per worker thread; results wait, in grid order, for at most
#: this many tasks per thread (the sweep's memory bound).
IN_FLIGHT = 3


def task_sizes(size: int, row: int, threads: int) -> Iterator[int]:
    """Designs of each task of a sweep of ``size`` designs in rows of ``row``, for ``threads``
    worker threads.

    Guided self-scheduling: every task takes a 1/(2 × ``threads``) share of the designs
    left, within [:data:`MIN_CHUNK`, :data:`CHUNK`], rounded to whole rows; a row larger
    than that is cut into equal parts, so that no task straddles two rows.

    Examples
    --------
    >>> list(task_sizes(1600, 40, 2))  # 40 × 40 on 2 workers: 12 tasks, 10 rows first, 1 row last
    [400, 320, 240, 160, 120, 80, 80, 40, 40, 40, 40, 40]
    >>> sizes = list(task_sizes(40_000, 200, 2))  # 200 × 200: two rows a task, the last row cut
    >>> len(sizes), sizes[:2], sizes[-4:], sum(sizes)
    (107, [400, 400], [50, 40, 40, 70], 40000)
    >>> list(task_sizes(7, 7, 2)), list(task_sizes(0, 5, 2))
    ([7], [])
    """
    done = 0
    while done < size:
        want = min(CHUNK, max(MIN_CHUNK, math.ceil((size - done) / (2 * threads))))
        offset = done % row
        if want >= row and offset == 0:
            n = round(want / row) * row
        else:  # an equal part of the row, or all that is left of it when less would remain
            n = min(math.ceil(row / math.ceil(row / want)), row - offset)
            n = row - offset if row - offset - n < MIN_CHUNK else n
        n = min(n, size - done)
        yield n
        done += n


@dataclass(frozen=True, eq=False)
class Sketch(FrozenArrays):
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

    Examples
    --------
    >>> sketch = evaluate_design(0.3, 0.75, samples=41, tubes=3)[1]
    >>> sketch.curves.dtype, sketch.kinds[:2], bool(np.abs(sketch.feet[:, 2]).max() < 1e-9)
    (dtype('float32'), ('fold', 'seam'), True)
    """

    curves: np.ndarray
    cells: np.ndarray
    kinds: tuple[str, ...]
    feet: np.ndarray
    apex: np.ndarray

    @classmethod
    def from_vault(
        cls, vault: Vault, *, samples: int = SKETCH_SAMPLES, tubes: int = SKETCH_TUBES
    ) -> Sketch:
        """Subsample a vault's curves at its design angle (at most ``tubes`` tubes, ~``samples``
        points).

        Examples
        --------
        >>> from curvefold.vault import Vault
        >>> sketch = Sketch.from_vault(Vault.from_design(samples=41, tubes=3), samples=5)
        >>> sketch.curves.shape, sketch.cells.shape  # 10 curves of 5 points; 3 tubes
        ((10, 5, 3), (3, 4))
        """
        from ..geometry._structure import drawable

        structure = vault.structure
        V = vault.vertices  # (M, n, 3)
        curves, cells, kinds = drawable(structure, V, segments=samples - 1, max_cells=tubes)
        uv = structure.curves_uv
        diag = np.flatnonzero(uv[:, 0] == uv[:, 1])
        ends = diag[[np.argmin(uv[diag, 0]), np.argmax(uv[diag, 0])]]
        m = vault.apex_index
        return cls(curves.astype(np.float32), cells.astype(np.int32), kinds, V[ends, 0], V[ends, m])


def evaluate_design(
    a: float,
    p_xy: float,
    *,
    width: float = 0.08,
    fold_angle: float = 90.0,
    tubes: int | None = None,
    samples: int = 201,
    sketch: bool = True,
    arch: tuple | None = None,
) -> tuple[dict, Sketch | None]:
    """Build one vault and return its flat record and sketch; an invalid design is a record too.

    ``sketch=False`` leaves the sketch out (the record is the same); ``arch`` is the
    design's :func:`~curvefold.vault._assembly.arch_crease` when the caller has it.

    Returns
    -------
    record : dict
        Keys of :data:`FIELDS` except ``row`` and ``col``.
    sketch : Sketch or None
        None for an invalid design, or when not asked for.

    Examples
    --------
    >>> record, sketch = evaluate_design(0.3, 0.75, samples=41, tubes=3)
    >>> record["valid"], record["tubes"], sketch is not None
    (True, 3, True)
    >>> record, sketch = evaluate_design(
    ...     1.5, 0.75, samples=41
    ... )  # past the arch family: a record, not an error
    >>> record["valid"], record["error"], sketch
    (False, 'ConvergenceError', None)
    """
    from ._assembly import Vault, VaultDesign

    record: dict[str, Any] = {
        "a": _number(a),
        "p_xy": _number(p_xy),
        "width": float(width),
        "fold_angle": float(fold_angle),
    }
    try:
        # past A_MAX the record says that no arch stands, not that a is out of range
        check_standing(GRID_A.check(a))
        vault = Vault.from_design(
            VaultDesign(
                a=a, p_xy=p_xy, width=width, fold_angle=fold_angle, tubes=tubes, samples=samples
            ),
            arch=arch,
        )
    except CurvefoldError as err:  # the design is refused: a record, not an error
        record.update(valid=False, error=type(err).__name__, reason=str(err))
        record.update(dict.fromkeys(METRICS))
        return record, None
    # A built vault that cannot be measured or drawn is a bug: it propagates.
    record.update(valid=True, error=None, reason=None)
    record.update(metrics_of(vault.summary()))
    return record, Sketch.from_vault(vault) if sketch else None


def metrics_of(summary: dict) -> dict:
    """The :data:`METRICS` of a :meth:`Vault.summary` dict, as plain Python numbers."""
    out = {k: summary[k] for k in METRICS if k in summary}
    out["footprint_x"], out["footprint_y"] = summary["footprint"]
    return {k: int(out[k]) if k in _INTEGER else float(out[k]) for k in METRICS}


def _number(x: Any) -> Any:
    """A grid value as a plain float when it is a real number (kept as is otherwise, for the
    record)."""
    try:
        return float(x)
    except (TypeError, ValueError):
        return x


# -- the grid and the atlas -------------------------------------------------------------------


@dataclass(frozen=True)
class AtlasGrid:
    """The designs of an atlas: two axes of values and the parameters every design shares.

    Build it with :meth:`of`, which checks the values.

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

    Examples
    --------
    >>> grid = AtlasGrid.of([0.5, 0.75], [0.0, 0.3, 0.6], samples=41, tubes=2)
    >>> grid.shape, grid.size
    ((3, 2), 6)
    """

    p_xy_values: tuple[float, ...]
    a_values: tuple[float, ...]
    width: float
    fold_angle: float
    tubes: int | None
    samples: int

    @classmethod
    def of(
        cls,
        p_xy_values: Sequence[float],
        a_values: Sequence[float],
        *,
        width: float = 0.08,
        fold_angle: float = 90.0,
        tubes: int | None = None,
        samples: int = 201,
    ) -> AtlasGrid:
        """The grid of ``p_xy_values`` (columns) × ``a_values`` (rows); the shared parameters fail
        once, here.

        Each grid value is checked later, per design: a value out of range is an invalid record.

        Examples
        --------
        >>> grid = AtlasGrid.of([0.5, 0.75], [0.0, 0.3, 0.6], samples=41, tubes=2)
        >>> grid.a_values, grid.tubes
        ((0.0, 0.3, 0.6), 2)
        >>> AtlasGrid.of([0.5], [0.3], samples=2)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: samples must be odd and ≥ 21 (the apex is the middle
        sample), got 2
        """
        from ._assembly import VaultDesign

        VaultDesign(width=width, fold_angle=fold_angle, tubes=tubes, samples=samples)
        return cls(
            _axis(p_xy_values, "p_xy_values"),
            _axis(a_values, "a_values"),
            float(width),
            float(fold_angle),
            tubes,
            int(samples),
        )

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, columns) = (len(a_values), len(p_xy_values))."""
        return len(self.a_values), len(self.p_xy_values)

    @property
    def size(self) -> int:
        """Number of designs."""
        return len(self.a_values) * len(self.p_xy_values)

    def points(self) -> Iterator[tuple[int, int, float, float]]:
        """(row, col, a, p_xy) of every design, in grid order (row-major).

        Examples
        --------
        >>> grid = AtlasGrid.of([0.5, 0.75], [0.0, 0.3, 0.6], samples=41, tubes=2)
        >>> list(grid.points())[:2]
        [(0, 0, 0.0, 0.5), (0, 1, 0.0, 0.75)]
        """
        return (
            (i, j, a, p)
            for i, a in enumerate(self.a_values)
            for j, p in enumerate(self.p_xy_values)
        )

    def every(self, step: int) -> AtlasGrid:
        """The grid of every ``step``-th row and column (0, step, 2·step, …).

        Examples
        --------
        >>> grid = AtlasGrid.of([0.5, 0.75], [0.0, 0.3, 0.6], samples=41, tubes=2)
        >>> grid.every(2).a_values, grid.every(1) == grid
        ((0.0, 0.6), True)
        >>> grid.every(0)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: step must be an integer ≥ 1, got 0
        """
        _check_step(step)
        return replace(self, p_xy_values=self.p_xy_values[::step], a_values=self.a_values[::step])

    @property
    def shared(self) -> dict:
        """The keyword arguments every design shares (of :func:`evaluate_design`)."""
        return {
            "width": self.width,
            "fold_angle": self.fold_angle,
            "tubes": self.tubes,
            "samples": self.samples,
        }

    def to_dict(self) -> dict:
        """The grid's values and parameters, JSON-ready.

        Examples
        --------
        >>> AtlasGrid.of([0.75], [0.3], samples=41).to_dict()
        {'p_xy_values': [0.75], 'a_values': [0.3], 'width': 0.08, 'fold_angle': 90.0, 'tubes': None,
        'samples': 41}
        """
        return {
            "p_xy_values": list(self.p_xy_values),
            "a_values": list(self.a_values),
            **self.shared,
        }


def _axis(values: Sequence[float], name: str) -> tuple[float, ...]:
    """A grid axis as a tuple of floats; each value is checked later, per design."""
    try:
        arr = (
            np.asarray(values, dtype=float)
            if not isinstance(values, (str, bytes))
            else np.array([])
        )
    except (TypeError, ValueError):
        arr = np.array([])
    if arr.ndim != 1 or arr.size == 0:
        raise InputError(f"{name} must be a non-empty 1-D sequence of numbers, got {values!r}")
    return tuple(float(x) for x in arr)


def _check_step(step: int) -> None:
    check_integer(step, "step", "[1, inf)")


@dataclass(frozen=True, eq=False)
class Atlas:
    """A grid of vault designs with their metrics.

    Build it with :func:`run_atlas`, or with :meth:`from_results` from :func:`sweep`.

    Attributes
    ----------
    grid : AtlasGrid
        The designs: the two axes and the shared parameters.
    records : tuple of dict
        One record per design, row-major (``records[row * len(grid.p_xy_values) + col]``).
    sketches : tuple of Sketch or None
        Geometry for drawing, parallel to ``records`` (None for an invalid design).

    Examples
    --------
    >>> atlas = run_atlas([0.75], [0.0, 0.3], samples=41, tubes=2, workers=1)
    >>> atlas.shape, len(atlas.records), len(atlas.sketches)
    ((2, 1), 2, 2)
    """

    grid: AtlasGrid
    records: tuple[dict, ...]
    sketches: tuple[Sketch | None, ...] = field(repr=False)

    @classmethod
    def from_results(cls, grid: AtlasGrid, results: Iterable[tuple[dict, Sketch | None]]) -> Atlas:
        """The atlas of ``grid`` from its (record, sketch) pairs in grid order.

        ``row`` and ``col`` of the records are set to their place in ``grid`` (a thinned
        grid numbers its rows and columns afresh).

        Examples
        --------
        >>> grid = AtlasGrid.of([0.75], [0.0, 0.3], samples=41, tubes=2)
        >>> Atlas.from_results(grid, sweep(grid, workers=1)).shape
        (2, 1)
        >>> Atlas.from_results(grid, [])
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: results must hold one (record, sketch) pair per design
        of the 2 × 1 grid, got 0
        """
        pairs = list(results)
        if len(pairs) != grid.size:
            raise InputError(
                "results must hold one (record, sketch) pair per design of the "
                f"{grid.shape[0]} × {grid.shape[1]} grid, got {len(pairs)}"
            )
        cols = len(grid.p_xy_values)
        records = tuple(
            {k: r[k] for k in FIELDS} | {"row": n // cols, "col": n % cols}
            for n, (r, _) in enumerate(pairs)
        )
        return cls(grid, records, tuple(s for _, s in pairs))

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, columns) of the grid."""
        return self.grid.shape

    def record(self, row: int, col: int) -> dict:
        """The record of grid.a_values[row], grid.p_xy_values[col].

        Examples
        --------
        >>> atlas = run_atlas([0.75], [0.0, 0.3], samples=41, tubes=2, workers=1)
        >>> round(atlas.record(1, 0)["kappa0_s0"], 6)
        3.165717
        >>> atlas.record(2, 0)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: (row, col) must be in [0, 2) × [0, 1), got (2, 0)
        """
        rows, cols = self.shape
        if not (0 <= row < rows and 0 <= col < cols):
            raise InputError(f"(row, col) must be in [0, {rows}) × [0, {cols}), got ({row}, {col})")
        return self.records[row * cols + col]

    def values(self, key: str) -> np.ndarray:
        """One numeric field over the grid, shape (rows, cols); NaN for invalid designs.

        Examples
        --------
        >>> atlas = run_atlas(
        ...     [0.75], [0.3, 1.5], samples=41, tubes=2, workers=1
        ... )  # a = 1.5 has no standing arch
        >>> atlas.values("kappa0_s0").round(6).tolist()
        [[3.165717], [nan]]
        """
        if key not in FIELDS or key in ("error", "reason"):
            raise InputError(
                "key must be a numeric field of the atlas "
                f"({', '.join(k for k in FIELDS if k not in ('error', 'reason'))}), got {key!r}"
            )
        values = [np.nan if r[key] is None else float(r[key]) for r in self.records]
        return np.array(values, float).reshape(self.shape)

    def every(self, step: int) -> Atlas:
        """The atlas of every ``step``-th row and column (0, step, 2·step, …), rows and columns
        renumbered.

        Examples
        --------
        >>> atlas = run_atlas([0.75], [0.0, 0.3], samples=41, tubes=2, workers=1)
        >>> atlas.every(2).shape, atlas.every(2).records[0]["a"]
        ((1, 1), 0.0)
        """
        return Atlas.from_results(
            self.grid.every(step), thin(zip(self.records, self.sketches), step)
        )


def thin(
    results: Iterable[tuple[dict, Sketch | None]], step: int
) -> Iterator[tuple[dict, Sketch | None]]:
    """The (record, sketch) pairs on every ``step``-th row and column, as they come.

    Examples
    --------
    >>> atlas = run_atlas([0.75], [0.0, 0.3], samples=41, tubes=2, workers=1)
    >>> [(r["row"], r["col"]) for r, _ in thin(zip(atlas.records, atlas.sketches), 2)]
    [(0, 0)]
    """
    _check_step(step)
    return ((r, s) for r, s in results if r["row"] % step == 0 and r["col"] % step == 0)


# -- running a sweep --------------------------------------------------------------------------


def sweep(
    grid: AtlasGrid,
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: Callable[[int, int], Any] | None = None,
    sketch_step: int = 1,
) -> Generator[tuple[dict, Sketch | None], None, None]:
    """The record and sketch of every design of ``grid``, in grid order, as the designs finish.

    Parameters
    ----------
    grid : AtlasGrid
    workers : int, optional, keyword-only
        Processes of a local Dask cluster, 1 to the CPUs here; 1 runs in this process.
        Default: ``min(2, CPUs)`` for grids of at least :data:`LOCAL_CLUSTER_FROM` designs
        when Dask is installed, this process otherwise. Worker processes are spawned: call
        this under ``if __name__ == "__main__":`` in a script.
    scheduler : str, optional, keyword-only
        Address of a running Dask scheduler (``"tcp://host:8786"``): its workers run the
        designs. They need the same version of curvefold as this process (checked). Not
        with ``workers``.
    progress : callable, optional, keyword-only
        ``progress(done, total)``, called with 0 first and after every design.
    sketch_step : int, keyword-only
        Sketch the designs of every k-th row and column only (those a figure of
        :meth:`Atlas.every` ``(k)`` draws); the others' sketch is None. Default 1: every design.

    Yields
    ------
    record : dict
        Keys :data:`FIELDS`.
    sketch : Sketch or None
        None for an invalid design.

    Notes
    -----
    Designs go to the cluster in tasks of :func:`task_sizes`, which shrink from
    :data:`CHUNK` designs as the grid runs out, at most :data:`IN_FLIGHT` tasks per
    worker thread at a time; a finished task waits until the ones before it
    are handed out, so memory stays bounded whatever the grid's size. A cluster started
    here is closed when the iterator ends, is closed, or raises (close it with
    :func:`contextlib.closing` when stopping early). Connection errors and a version
    mismatch raise :class:`InputError` at the first ``next()``.

    Examples
    --------
    >>> results = list(sweep(AtlasGrid.of([0.75], [0.0, 0.3], samples=41, tubes=2), workers=1))
    >>> [(record["row"], record["valid"]) for record, _ in results]
    [(0, True), (1, True)]
    >>> sweep([0.75, 0.3])
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: grid must be an AtlasGrid (AtlasGrid.of(p_xy_values,
    a_values, ...)), got list
    """
    if not isinstance(grid, AtlasGrid):
        raise InputError(
            "grid must be an AtlasGrid (AtlasGrid.of(p_xy_values, a_values, ...)), "
            f"got {type(grid).__name__}"
        )
    if progress is not None and not callable(progress):
        raise InputError(
            f"progress must be a callable progress(done, total) or None, got {progress!r}"
        )
    _check_step(sketch_step)
    return _sweep(grid, *cluster_plan(grid.size, workers, scheduler), progress, sketch_step)


def _sweep(
    grid: AtlasGrid,
    workers: int,
    scheduler: str | None,
    progress: Callable[[int, int], Any] | None,
    step: int,
) -> Generator[tuple[dict, Sketch | None], None, None]:
    design = grid.shared
    total, done = grid.size, 0
    if progress is not None:
        progress(0, total)
    with cluster_client(workers, scheduler) as client:
        if client is None:
            arches: dict = {}  # one row's arch, shared by the designs handed out one by one
            chunks: Generator[list, None, None] = (
                _evaluate_chunk([point], design, step, arches) for point in grid.points()
            )
        else:
            threads = max(1, sum(client.nthreads().values()))
            sizes = task_sizes(total, grid.shape[1], threads)
            submit = lambda points: client.submit(
                _evaluate_packed, points, design, step, pure=False
            )  # noqa: E731
            chunks = _unpacked(in_order(submit, batched(grid.points(), sizes), IN_FLIGHT * threads))
        with closing(chunks):  # closed before the client, when the sweep stops early
            for results in chunks:
                for result in results:
                    done += 1
                    if progress is not None:
                        progress(done, total)
                    yield result


def _evaluate_chunk(
    points: Sequence[tuple[int, int, float, float]],
    design: dict,
    step: int = 1,
    arches: dict | None = None,
) -> list[tuple[dict, Sketch | None]]:
    """(record, sketch) of several grid points, in order (sketches on every ``step``-th row and
    column). ``arches`` keeps the last row's arch across calls."""
    out, arches = [], {} if arches is None else arches
    for row, col, a, p in points:
        if row not in arches:  # the row's arch, once: its designs differ in p_xy alone
            arches.clear()
            arches[row] = _row_arch(a, design)
        record, sketch = evaluate_design(
            a, p, **design, sketch=row % step == 0 and col % step == 0, arch=arches[row]
        )
        out.append(({"row": row, "col": col} | record, sketch))
    return out


def _evaluate_packed(
    points: Sequence[tuple[int, int, float, float]], design: dict, step: int
) -> bytes:
    """:func:`_evaluate_chunk` as one pickle, the task a worker runs. Dask would serialize each
    pair of a list apart: 11 ms of the worker's CPU for 400 designs and 4.7 ms of the
    client's, against 2.3 and 1.8."""
    return pickle.dumps(_evaluate_chunk(points, design, step), protocol=pickle.HIGHEST_PROTOCOL)


def _unpacked(
    packed: Generator[bytes, None, None],
) -> Generator[list[tuple[dict, Sketch | None]], None, None]:
    """The results of :func:`_evaluate_packed` tasks, as they come; closing it closes ``packed``."""
    with closing(packed):
        for blob in packed:
            yield pickle.loads(blob)


def _row_arch(a: float, design: dict) -> tuple | None:
    """The arch and crease of the designs of one ``a`` (None where there is none: each design
    records why)."""
    from ._assembly import VaultDesign, arch_crease

    shape = VaultDesign()  # the grid's vaults take its panels and radius
    try:
        return arch_crease(
            check_standing(GRID_A.check(a)),
            shape.panels,
            shape.radius,
            design["fold_angle"],
            design["samples"],
        )
    except CurvefoldError:
        return None


def run_atlas(
    p_xy_values: Sequence[float],
    a_values: Sequence[float],
    *,
    width: float = 0.08,
    fold_angle: float = 90.0,
    tubes: int | None = None,
    samples: int = 201,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: Callable[[int, int], Any] | None = None,
) -> Atlas:
    """Build the vault of every (p_xy, a) of a grid and record its metrics, in memory.

    For grids too large to hold, iterate :func:`sweep` instead (the command line does).

    Parameters
    ----------
    p_xy_values : (C,) array_like
        Section proportions w_R(0)/w_L(0): the columns.
    a_values : (R,) array_like
        Torsion amplitudes: the rows. a ≥ :data:`curvefold.vault.A_MAX` has no standing arch
        and is recorded as invalid.
    width, fold_angle, tubes, samples : keyword-only
        Shared :class:`~curvefold.vault.VaultDesign` parameters (checked once, by
        :meth:`AtlasGrid.of`).
    workers, scheduler, progress : keyword-only
        Where the designs run and a progress callback, as for :func:`sweep`.

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
    grid = AtlasGrid.of(
        p_xy_values, a_values, width=width, fold_angle=fold_angle, tubes=tubes, samples=samples
    )
    return Atlas.from_results(
        grid, sweep(grid, workers=workers, scheduler=scheduler, progress=progress)
    )
