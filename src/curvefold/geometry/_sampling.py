"""How finely the files sample a structure: as accurate as asked, without sliver triangles.

The geometry is computed at every sample of curve 1 (the design's ``samples``: dense, so
that the certificate's finite differences are accurate to ~(κh)⁴). Meshes written to files
need far fewer. Near the curve of regression a lattice curve moves slowly in t, so at the
dense samples its steps are tiny beside the rulings: triangles with corners of a fraction
of a degree, which make simulators blow up and planar-graph tools mistake faces. Each
tube's mesh therefore keeps its own subset of the samples (:func:`choose_sampling`),
walking from each end to the middle sample (a vault's apex, kept) in steps as long as
they stay accurate, measured on the tube's four creases folded (at the design angle)
and flat (the crease pattern):

* every computed sample lies within ``tolerance`` × the structure's size of the polyline
  through the kept ones;
* no edge of the mesh changes its length by more than ``tolerance`` (relative) between
  the folded and the flat state, and no ruling quad folds across its diagonal by more
  than ``max_bend`` (``curvefold check`` holds FOLD files to both);
* the triangles keep corners of at least ``min_angle`` where a shorter step allows it.

The longest accurate steps have the best-shaped triangles, except where a step is long
beside the rulings; where the accurate steps are short beside them (right next to the
curve of regression) accuracy wins, and the smallest corner is reported as measured.

A structure whose lattice is not :attr:`~curvefold.geometry.StructureLattice.thinnable`
keeps every vertex: the polylines of rigid panels (:mod:`curvefold.geometry._panels`) are
the creases themselves, a few per panel, and two panels joined into one quad would not be
planar (:meth:`PanelLattice.topology <curvefold.geometry.PanelLattice.topology>`
refuses it). Its resolution is measured and reported the same way.
"""

from __future__ import annotations

from collections.abc import Generator
from dataclasses import dataclass

import numpy as np

from ..kernel._arrays import FrozenArrays
from ..kernel._errors import InputError
from ..kernel._lie import cross, cross3
from ._mesh import edges_faces
from ._structure import Structure
from ._topology import Topology

__all__ = [
    "Sampling",
    "choose_sampling",
    "corner_angles",
    "polyline_deviation",
    "DEFAULT_TOLERANCE",
    "DEFAULT_MIN_ANGLE",
    "DEFAULT_MAX_BEND",
]

#: Largest distance of the exact creases from the written polylines, relative to the structure's
#: size.
DEFAULT_TOLERANCE = 1e-4
#: Samples inside candidate steps measured at once (:func:`_chord_deviations`): 20 MB of arrays.
_CHORD_CHUNK = 1 << 14
#: Smallest triangle corner, degrees.
DEFAULT_MIN_ANGLE = 5.0
#: Largest fold across the diagonal of a ruling quad, degrees (``curvefold check`` accepts 0.5°).
DEFAULT_MAX_BEND = 0.5


@dataclass(frozen=True, eq=False)
class Sampling(FrozenArrays):
    """The samples each tube's mesh keeps, with what they were measured to give.

    Attributes
    ----------
    keep : tuple of (m_k,) ndarray of int
        Per tube, the kept sample indices (ascending; the first and last sample included).
        Pass it to :meth:`Structure.topology` or to the writers.
    samples : int
        Samples the geometry was computed at.
    tolerance : float
        The accuracy asked (relative, see :func:`choose_sampling`).
    min_angle_bound : float
        The smallest triangle corner asked, degrees.
    max_bend : float
        The largest fold across a ruling quad's diagonal asked, degrees.
    deviation : float
        Largest distance of a computed crease sample from the written polylines, model units.
    stretch : float
        Largest relative change of an edge's length between the folded and the flat mesh.
    bend : float
        Largest fold across a ruling quad's diagonal, degrees.
    min_angle : float
        Smallest triangle corner of the meshes, folded and flat, degrees.
    size : float
        Largest extent of the structure at the design angle, model units.

    Examples
    --------
    >>> from curvefold import SpaceCurve, Crease, Lattice, Structure
    >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
    >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
    >>> tube = Structure.tube(lat)
    >>> s = choose_sampling(tube)  # 5 samples: none to spare
    >>> s.vertices_per_crease, s.samples, s.deviation
    ((5,), 5, 0.0)
    """

    keep: tuple[np.ndarray, ...]
    samples: int
    tolerance: float
    min_angle_bound: float
    max_bend: float
    deviation: float
    stretch: float
    bend: float
    min_angle: float
    size: float

    @property
    def vertices_per_crease(self) -> tuple[int, ...]:
        """Vertices along each crease of every tube."""
        return tuple(len(k) for k in self.keep)

    def summary(self) -> dict:
        """The resolution as a JSON-ready dict (for reports and file metadata).

        Examples
        --------
        >>> from curvefold import SpaceCurve, Crease, Lattice, Structure
        >>> curve = SpaceCurve.from_curvature(1.0, 0.0, 1.0, samples=5)
        >>> lat = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.1)
        >>> tube = Structure.tube(lat)
        >>> summary = choose_sampling(tube).summary()
        >>> (
        ...     summary["samples_computed"],
        ...     summary["mesh_samples_per_crease"],
        ...     summary["mesh_deviation"],
        ... )
        (5, '5', 0.0)
        """
        counts = self.vertices_per_crease
        return {
            "samples_computed": int(self.samples),
            "mesh_samples_per_crease": f"{min(counts)}–{max(counts)}"
            if min(counts) != max(counts)
            else str(counts[0]),
            "mesh_tolerance": float(self.tolerance),
            "mesh_deviation": float(self.deviation),
            "mesh_deviation_relative": float(self.deviation / self.size),
            "mesh_stretch": float(self.stretch),
            "mesh_bend_deg": float(self.bend),
            "mesh_bend_bound_deg": float(self.max_bend),
            "mesh_smallest_angle_deg": float(self.min_angle),
            "mesh_angle_bound_deg": float(self.min_angle_bound),
        }


def polyline_deviation(curves: np.ndarray, keep: np.ndarray) -> float:
    """Largest distance of the samples of curves from the polylines through the kept samples.

    Parameters
    ----------
    curves : (..., n, 3) ndarray
    keep : (m,) ndarray of int
        Ascending sample indices, the first 0 and the last n − 1.

    Examples
    --------
    A quarter circle of radius 1 through 3 of its points deviates by 1 − cos(π/8):

    >>> t = np.linspace(0, np.pi / 2, 9)
    >>> arc = np.stack([np.cos(t), np.sin(t), 0 * t], axis=-1)
    >>> bool(abs(polyline_deviation(arc, np.array([0, 4, 8])) - (1 - np.cos(np.pi / 8))) < 1e-12)
    True
    """
    x = np.asarray(curves, float)
    n = x.shape[-2]
    j = np.clip(np.searchsorted(keep, np.arange(n), side="right") - 1, 0, len(keep) - 2)
    a, b = x[..., keep[j], :], x[..., keep[j + 1], :]
    d = b - a
    t = np.clip(np.sum((x - a) * d, axis=-1) / np.maximum(np.sum(d * d, axis=-1), 1e-300), 0.0, 1.0)
    return float(np.linalg.norm(x - a - t[..., None] * d, axis=-1).max())


def corner_angles(vertices_coords: np.ndarray, faces_vertices: np.ndarray) -> np.ndarray:
    """The smallest corner of every triangle, degrees, shape (..., F) for vertices (..., V, 3).

    Examples
    --------
    >>> corner_angles(
    ...     np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float), np.array([[0, 1, 2]])
    ... ).round(6).tolist()
    [45.0]
    """
    p = np.asarray(vertices_coords, float)[..., np.asarray(faces_vertices), :]  # (..., F, 3, 3)
    u = np.roll(p, -1, axis=-2) - p
    v = np.roll(p, 1, axis=-2) - p
    angle = np.arctan2(np.linalg.norm(cross(u, v), axis=-1), np.sum(u * v, axis=-1))
    return np.degrees(angle.min(axis=-1))


#: One step of a tube's mesh: its triangles on the four corners at two samples (0, 1).
_STEP = Topology.tubes(np.arange(4)[None], 2)
#: The two triangles on each of its diagonals.
_DIAGONAL_FACES = edges_faces(
    _STEP.faces_vertices, _STEP.edges_vertices[_STEP.edges_kind == "diagonal"]
)


def _tube_points(states: np.ndarray, cell_curves: np.ndarray) -> np.ndarray:
    """The tubes' four curves in every state, component-major: (3, states, K·4·n) from states
    (states, M, n, 3); column (4·k + c)·n + s holds corner c + 1 of tube k at sample s
    (:func:`_rows`)."""
    return np.ascontiguousarray(
        np.moveaxis(states[:, cell_curves].reshape(len(states), -1, 3), -1, 0)
    )


def _rows(n: int, tube: np.ndarray, curve: np.ndarray, sample: np.ndarray) -> np.ndarray:
    """The columns of :func:`_tube_points` (n samples) of curves ``curve`` of tubes ``tube`` at
    ``sample`` (broadcast)."""
    return (tube * 4 + curve) * n + sample


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The dot products of component-major vectors (3, ...), summed as ``np.sum(a * b, axis=-1)``
    sums the vectors' components (the same floats)."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _step_shape(
    points: np.ndarray, n: int, tube: np.ndarray, i: np.ndarray, ends: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The steps of tubes ``tube`` from samples i to ``ends``, each (J,), measured over the states.

    ``points`` are the tubes' curves (:func:`_tube_points`, n samples). Returns each step's
    smallest triangle corner (degrees), the largest relative change of an edge length
    between the two states, and the largest fold across a diagonal in a folded state
    (degrees), each (J,): the floats :func:`corner_angles`,
    :func:`~curvefold.geometry._mesh.vector_areas` and ``np.linalg.norm`` give on the steps' meshes,
    computed component by component.
    """
    lo, hi = np.minimum(i, ends), np.maximum(i, ends)
    samples = np.where(_STEP.vertex_sample == 0, lo[:, None], hi[:, None])  # (J, 8)
    rows = _rows(n, tube[:, None], _STEP.vertex_curve, samples)
    # (3, states, J, F, 3): the triangles' corners
    corner = np.take(points, rows[:, _STEP.faces_vertices], axis=2)
    u = np.roll(corner, -1, axis=-1) - corner
    v = np.roll(corner, 1, axis=-1) - corner
    area = cross3(u, v)
    angle = np.arctan2(np.sqrt(_dot(area, area)), _dot(u, v))
    edges = np.take(points, rows[:, _STEP.edges_vertices[:, 1]], axis=2) - np.take(
        points, rows[:, _STEP.edges_vertices[:, 0]], axis=2
    )
    length = np.sqrt(_dot(edges, edges))  # (states, J, E)
    stretch = np.abs(length / length[-1:] - 1).max(axis=(0, 2))
    # vector areas, (3, states, J, F)
    normal = cross3(corner[..., 1] - corner[..., 0], corner[..., 2] - corner[..., 0])
    normal /= np.sqrt(_dot(normal, normal))
    cos = _dot(normal[..., _DIAGONAL_FACES[:, 0]], normal[..., _DIAGONAL_FACES[:, 1]])
    bend = np.arccos(np.clip(cos, -1.0, 1.0)).max(axis=(0, 2))
    return np.degrees(angle.min(axis=(0, 2, 3))), stretch, np.degrees(bend)


def _chord_deviations(
    points: np.ndarray, n: int, tube: np.ndarray, i: np.ndarray, ends: np.ndarray
) -> np.ndarray:
    """For the steps of tubes ``tube`` from samples i to ``ends``, each (J,), the largest distance
    of the samples between them from the chords of the four curves, over the states, (J,).

    Only the samples strictly inside a step are measured: its ends lie on its chords. The
    candidate steps of a walk hold about k²/2 samples for steps of k, so they are measured
    :data:`_CHORD_CHUNK` samples at a time: memory stays linear in the samples (a tube of
    100 000 samples written as SVG peaked at 2.97 GB, 244 MB since).
    """
    inside = np.maximum(np.abs(ends - i) - 1, 0)  # samples strictly inside each step
    deviation = np.zeros(len(i))
    total = int(inside.sum())
    first = np.cumsum(inside) - inside  # each step's first sample in the list
    direction = np.sign(ends - i)
    for lo in range(0, total, _CHORD_CHUNK):
        at = np.arange(lo, min(lo + _CHORD_CHUNK, total))
        step = np.searchsorted(first, at, side="right") - 1  # an empty step owns none
        j = at - first[step] + 1  # 1 … inside[step]
        rows = (
            _rows(n, tube[step, None], np.arange(4), x[:, None])
            for x in (i[step], ends[step], i[step] + direction[step] * j)
        )
        # chord start, chord end, sample inside: (3, states, P, 4)
        p, q, m = (np.take(points, r, axis=2) for r in rows)
        chord, off = q - p, m - p
        t = np.clip(_dot(off, chord) / np.maximum(_dot(chord, chord), 1e-300), 0.0, 1.0)
        away = off - t * chord
        np.maximum.at(deviation, step, np.sqrt(_dot(away, away)).max(axis=(0, 2)))
    return deviation


def _accurate(
    points: np.ndarray,
    n: int,
    steps: list[tuple[int, int, np.ndarray]],
    limits: tuple[float, float, float],
) -> list[tuple[np.ndarray, np.ndarray]]:
    """For each (tube, a, ends (J,)): whether each step of the tube from sample a to ``ends`` is
    accurate, and its smallest triangle corner, each (J,), all measured together.

    A step is accurate when the samples it skips lie within ``limits[0]`` of its chords,
    no edge of its triangles changes length by more than ``limits[1]`` (relative) between
    the states and no diagonal folds by more than ``limits[2]`` degrees.
    """
    allowed, stretch_limit, bend_limit = limits
    sizes = [len(ends) for _, _, ends in steps]
    tube, start = (np.repeat([step[k] for step in steps], sizes) for k in (0, 1))
    ends = np.concatenate([ends for _, _, ends in steps])
    angle, stretch, bend = _step_shape(points, n, tube, start, ends)
    ok = (
        (_chord_deviations(points, n, tube, start, ends) <= allowed)
        & (stretch <= stretch_limit)
        & (bend <= bend_limit)
    )
    split = np.cumsum(sizes)[:-1]
    return list(zip(np.split(ok, split), np.split(angle, split)))


def _walk(
    start: int, stop: int, min_angle: float
) -> Generator[tuple[tuple[int, np.ndarray], ...], list, list[int]]:
    """Kept samples from ``start`` to ``stop`` (either way), each step as long as it stays accurate.

    A generator: it yields the steps it asks about, a tuple of (a, ends (J,)), and is sent
    back, for each, whether each step from a to ``ends`` is accurate and its smallest
    triangle corner (:func:`_accurate`), so that the walks of all tubes are measured
    together; it returns the kept samples. The longest accurate step has the best-shaped
    triangles unless it is long beside the rulings: if its triangles are thinner than
    ``min_angle``, the longest shorter step that is not is taken instead, if any. The last
    one or two steps are chosen together, so that no short step is left at the end.
    """
    d = 1 if stop >= start else -1
    picks, reach = [start], 8
    while picks[-1] != stop:
        i = picks[-1]
        room = abs(stop - i)
        lengths = np.arange(1, room + 1)
        ok, angle = np.zeros(0, bool), np.zeros(0)
        # the accurate steps are those before the first one that is not
        while len(ok) < room and ok.all():
            # about as long as the last step and one more, then twice as many
            span = min(max(reach, 2 * len(ok)), room)
            ((more_ok, more_angle),) = yield ((i, i + d * lengths[len(ok) : span]),)
            ok, angle = np.concatenate([ok, more_ok]), np.concatenate([angle, more_angle])
        k = max(1, int(np.argmin(ok)) if not ok.all() else room)
        reach = k + 2
        if angle[k - 1] < min_angle:  # too long for the rulings?
            shorter = np.flatnonzero(angle[:k] >= min_angle)
            k = int(lengths[shorter[-1]]) if shorter.size else k
        if room - k >= k:
            picks.append(i + d * k)
            continue
        # At most two steps are left: one step, or two split at i + d·m, whichever is best.
        ends = i + d * lengths
        last = lengths == room
        second, second_ok = np.full(room, np.inf), np.ones(room, bool)
        (second_ok[:-1], second[:-1]), (first_ok, first) = yield ((stop, ends[:-1]), (i, ends))
        shape = np.minimum(first, second)
        both = first_ok & second_ok
        good = (shape >= min_angle) & both
        score = np.stack([good, both, last & good, shape], axis=-1)
        m = int(lengths[np.lexsort(score.T[::-1])[-1]])
        picks += [i + d * m] + ([stop] if m < room else [])
    return picks


def _walks(
    points: np.ndarray,
    n: int,
    walks: list[tuple[int, int, int]],
    limits: tuple[float, float, float],
    min_angle: float,
) -> list[list[int]]:
    """The kept samples of each walk (tube, start, stop) on the tubes' curves
    (:func:`_tube_points`, n samples) (:func:`_walk`), the walks measured in lockstep: each
    round, every step they ask about at once."""
    picks: list = [None] * len(walks)
    asking: dict[int, tuple[tuple[int, np.ndarray], ...]] = {}

    def advance(w: int, answer: list | None) -> None:
        try:
            asking[w] = next(running[w]) if answer is None else running[w].send(answer)
        except StopIteration as done:
            picks[w] = done.value
            asking.pop(w, None)

    running = [_walk(start, stop, min_angle) for _, start, stop in walks]
    for w in range(len(walks)):
        advance(w, None)
    while asking:
        order = list(asking)
        steps = [(walks[w][0], a, ends) for w in order for a, ends in asking[w]]
        answers = iter(_accurate(points, n, steps, limits))
        for w in order:
            advance(w, [next(answers) for _ in asking[w]])
    return picks


def choose_sampling(
    structure: Structure,
    *,
    tolerance: float = DEFAULT_TOLERANCE,
    min_angle: float = DEFAULT_MIN_ANGLE,
    max_bend: float = DEFAULT_MAX_BEND,
    fold_angle: float | None = None,
) -> Sampling:
    """The samples each tube's mesh keeps (see the module notes).

    Parameters
    ----------
    structure : Structure
    tolerance : float, keyword-only
        In (0, 1): the largest distance of the exact creases from the written polylines,
        relative to the structure's largest extent, and the largest relative change of an
        edge's length between the folded and the flat mesh.
    min_angle : float, keyword-only
        Smallest triangle corner wanted, degrees, in [0, 30].
    max_bend : float, keyword-only
        Largest fold across the diagonal of a ruling quad (whose triangles are then
        coplanar to this angle), degrees, > 0.
    fold_angle : float, optional, keyword-only
        The folded state measured besides the flat one; default the design angle.

    Returns
    -------
    Sampling

    Examples
    --------
    >>> from curvefold.vault import Vault
    >>> s = choose_sampling(Vault.from_design(samples=401).structure)
    >>> s.deviation <= 1e-4 * s.size, s.stretch <= 1e-4, s.bend <= 0.5, len(s.keep) == 9
    (True, True, True, True)
    """
    if not (isinstance(tolerance, (int, float)) and 0 < tolerance < 1):
        raise InputError(f"tolerance must be a number in (0, 1), got {tolerance!r}")
    if not (isinstance(min_angle, (int, float)) and 0 <= min_angle <= 30):
        raise InputError(f"min_angle must be in [0, 30] degrees, got {min_angle!r}")
    if not (isinstance(max_bend, (int, float)) and 0 < max_bend <= 90):
        raise InputError(f"max_bend must be in (0, 90] degrees, got {max_bend!r}")
    n = len(structure.lattice.s)
    # (2, M, n, 3): folded, flat
    states = np.stack([structure.state(fold_angle).vertices, structure.state(0.0).vertices])
    size = float(np.ptp(states[0].reshape(-1, 3), axis=0).max())
    limits = (tolerance * size, float(tolerance), float(max_bend))
    middle = (n - 1) // 2
    thinnable = structure.lattice.thinnable
    points = _tube_points(states, structure.cell_curves)
    tubes = range(len(structure.cell_curves))
    if thinnable:
        walks = _walks(
            points, n, [(t, end, middle) for t in tubes for end in (0, n - 1)], limits, min_angle
        )
        keep = [
            np.array(first + second[-2::-1], dtype=np.int64)
            for first, second in zip(walks[::2], walks[1::2])
        ]
    else:  # every vertex
        keep = [np.arange(n) for _ in tubes]
    tube = np.concatenate([np.full(len(picks) - 1, t) for t, picks in zip(tubes, keep)])
    angles, stretches, bends = _step_shape(
        points,
        n,
        tube,
        np.concatenate([k[:-1] for k in keep]),
        np.concatenate([k[1:] for k in keep]),
    )
    deviation = max(
        polyline_deviation(states[:, rows], picks)
        for rows, picks in zip(structure.cell_curves, keep)
    )
    return Sampling(
        tuple(keep),
        n,
        float(tolerance),
        float(min_angle),
        float(max_bend),
        deviation,
        float(stretches.max()),
        float(bends.max()),
        float(angles.min()),
        size,
    )
