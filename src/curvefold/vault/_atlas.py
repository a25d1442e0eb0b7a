"""The design atlas of composite vaults: a grid over (p_xy, a) (the paper's Fig. 10, extended).

For every pair of section proportion p_xy = w_R(0)/w_L(0) and torsion amplitude a, the
vault is built with :meth:`curvefold.vault.Vault.from_design` and its
:meth:`~curvefold.vault.Vault.summary` metrics are recorded (:func:`evaluate_design`). A
design that cannot be built (no standing arch, regression, a parameter out of range: any
:class:`~curvefold.kernel.CurvefoldError` raised while building it) is recorded as
invalid with the reason, and the sweep goes on. Any error past that point (measuring or
drawing a built vault) is a bug and propagates. Each valid design also keeps a small
:class:`Sketch` of its geometry so the atlas figure needs no vault rebuilt.

A grid may carry a :class:`Measure` (``AtlasGrid.of(..., load=...)``): an object of a layer
above, such as :class:`curvefold.mechanics.AtlasLoad`, whose ``measure(vault)`` adds its
``fields`` to every valid design's record (an invalid design gets them empty). It travels to
the workers with the grid's shared parameters, so this layer needs no mechanics.

Records are flat dicts with the keys of :data:`FIELDS`; the :class:`AtlasGrid` is
row-major, rows = a, columns = p_xy, and an :class:`Atlas` holds its records in that
order. The sweep that runs a grid, here or on a Dask cluster, is
:mod:`curvefold.vault._sweep`.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from ..kernel._arrays import FrozenArrays
from ..kernel._errors import CurvefoldError, InputError
from ..kernel._validate import Interval, Spec, check_integer
from ._arch import A_MAX, check_standing

if TYPE_CHECKING:  # pragma: no cover
    from ._assembly import Vault

__all__ = [
    "Atlas",
    "AtlasGrid",
    "Sketch",
    "Measure",
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
#: Fields that hold text, not numbers (of FIELDS and of the mechanics' columns).
_TEXT = ("error", "reason", "governing", "load_error")


class Measure(Protocol):
    """More columns of every valid design of an atlas, measured on its built vault (picklable:
    it is sent to the workers)."""

    fields: tuple[str, ...]

    def measure(self, vault: Vault) -> dict:
        """The values of :attr:`fields` of one built vault."""
        ...  # pragma: no cover

    def empty(self) -> dict:
        """The values of :attr:`fields` of a design that is not built (every one None)."""
        ...  # pragma: no cover

    def to_dict(self) -> dict:
        """What the atlas's JSON header says of it."""
        ...  # pragma: no cover

    def notes(self) -> list[str]:
        """What a reader of its columns must know, a sentence each."""
        ...  # pragma: no cover


#: Samples along t and tubes kept in a sketch (the apex and both feet are always samples);
#: SKETCH_TUBES matches the vault's default cap, so default stacks are drawn whole.
SKETCH_SAMPLES = 17
SKETCH_TUBES = 24


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
    load: Measure | None = None,
) -> tuple[dict, Sketch | None]:
    """Build one vault and return its flat record and sketch; an invalid design is a record too.

    ``sketch=False`` leaves the sketch out (the record is the same); ``arch`` is the
    design's :func:`~curvefold.vault._assembly.arch_crease` when the caller has it; ``load``
    adds its columns (:class:`Measure`).

    Returns
    -------
    record : dict
        Keys of :data:`FIELDS` except ``row`` and ``col``, and ``load.fields``.
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
        return record | ({} if load is None else load.empty()), None
    # A built vault that cannot be measured or drawn is a bug: it propagates.
    record.update(valid=True, error=None, reason=None)
    record.update(metrics_of(vault.summary()))
    if load is not None:
        record.update(load.measure(vault))
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
    load : Measure or None
        More columns of every design (:class:`Measure`), None for none.

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
    load: Measure | None = None

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
        load: Measure | None = None,
    ) -> AtlasGrid:
        """The grid of ``p_xy_values`` (columns) × ``a_values`` (rows); the shared parameters fail
        once, here.

        Each grid value is checked later, per design: a value out of range is an invalid record.

        Examples
        --------
        >>> grid = AtlasGrid.of([0.5, 0.75], [0.0, 0.3, 0.6], samples=41, tubes=2)
        >>> grid.a_values, grid.tubes
        ((0.0, 0.3, 0.6), 2)
        >>> AtlasGrid.of([0.5], [0.3], load="self-weight")
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: load must measure every design
        (curvefold.mechanics.AtlasLoad(material, thickness, ...)) or be None, got str
        >>> AtlasGrid.of([0.5], [0.3], samples=2)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: samples must be odd and ≥ 21 (the apex is the middle
        sample), got 2
        """
        from ._assembly import VaultDesign

        VaultDesign(width=width, fold_angle=fold_angle, tubes=tubes, samples=samples)
        if load is not None and not all(
            callable(getattr(load, name, None)) for name in ("measure", "empty", "to_dict", "notes")
        ):
            raise InputError(
                "load must measure every design (curvefold.mechanics.AtlasLoad(material, "
                f"thickness, ...)) or be None, got {type(load).__name__}"
            )
        return cls(
            _axis(p_xy_values, "p_xy_values"),
            _axis(a_values, "a_values"),
            float(width),
            float(fold_angle),
            tubes,
            int(samples),
            load,
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
        check_step(step)
        return replace(self, p_xy_values=self.p_xy_values[::step], a_values=self.a_values[::step])

    @property
    def fields(self) -> tuple[str, ...]:
        """Keys of every record: :data:`FIELDS`, then the load's (:class:`Measure`)."""
        return FIELDS + (() if self.load is None else tuple(self.load.fields))

    @property
    def shared(self) -> dict:
        """The keyword arguments every design shares (of :func:`evaluate_design`)."""
        return {
            "width": self.width,
            "fold_angle": self.fold_angle,
            "tubes": self.tubes,
            "samples": self.samples,
            "load": self.load,
        }

    def to_dict(self) -> dict:
        """The grid's values and parameters, JSON-ready.

        Examples
        --------
        >>> AtlasGrid.of([0.75], [0.3], samples=41).to_dict()
        {'p_xy_values': [0.75], 'a_values': [0.3], 'width': 0.08, 'fold_angle': 90.0, 'tubes': None,
        'samples': 41}
        """
        shared = {k: v for k, v in self.shared.items() if k != "load"}
        return {
            "p_xy_values": list(self.p_xy_values),
            "a_values": list(self.a_values),
            **shared,
        } | ({} if self.load is None else {"load": self.load.to_dict()})


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


def check_step(step: int) -> None:
    check_integer(step, "step", "[1, inf)")


@dataclass(frozen=True, eq=False)
class Atlas:
    """A grid of vault designs with their metrics.

    Build it with :func:`~curvefold.vault.run_atlas`, or with :meth:`from_results` from
    :func:`~curvefold.vault.sweep`.

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
    >>> from curvefold.vault import run_atlas
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
        >>> from curvefold.vault import sweep
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
            {k: r[k] for k in grid.fields} | {"row": n // cols, "col": n % cols}
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
        >>> from curvefold.vault import run_atlas
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
        >>> from curvefold.vault import run_atlas
        >>> atlas = run_atlas(
        ...     [0.75], [0.3, 1.5], samples=41, tubes=2, workers=1
        ... )  # a = 1.5 has no standing arch
        >>> atlas.values("kappa0_s0").round(6).tolist()
        [[3.165717], [nan]]
        """
        numeric = [k for k in self.grid.fields if k not in _TEXT]
        if key not in numeric:
            raise InputError(
                f"key must be a numeric field of the atlas ({', '.join(numeric)}), got {key!r}"
            )
        values = [np.nan if r[key] is None else float(r[key]) for r in self.records]
        return np.array(values, float).reshape(self.shape)

    def every(self, step: int) -> Atlas:
        """The atlas of every ``step``-th row and column (0, step, 2·step, …), rows and columns
        renumbered.

        Examples
        --------
        >>> from curvefold.vault import run_atlas
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
    >>> from curvefold.vault import run_atlas
    >>> atlas = run_atlas([0.75], [0.0, 0.3], samples=41, tubes=2, workers=1)
    >>> [(r["row"], r["col"]) for r, _ in thin(zip(atlas.records, atlas.sketches), 2)]
    [(0, 0)]
    """
    check_step(step)
    return ((r, s) for r, s in results if r["row"] % step == 0 and r["col"] % step == 0)
