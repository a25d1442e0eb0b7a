"""Loads and supports of a structure's model, in SI units with z up.

Loads (:class:`Loads`), summed into nodal forces (P, 3), N:

* self-weight: every node's lumped mass times g = 9.80665 m/s², downward;
* snow: a uniform vertical load per projected area (Pa; 1 kPa = 1000 Pa) on the surface
  seen from above: each triangle of the sheet whose centroid no other triangle covers from
  above carries the pressure times its horizontal projected area, shared equally by its
  corners (the triangles hidden under another part of the structure, the lower sheet of
  every tube among them, carry none);
* a point load (N, downward) at the apex, the highest node, or at the node nearest a
  given point.

Supports (:class:`Supports`): the feet, the end sections on the ground z = 0 (a vault
stands on them), or the end sections t = 0 and t = 1 wherever they are (a tube or block
held at both ends, as a bridge), or given nodes; ``"pinned"`` (every translation held) or
``"roller"`` (the vertical held on every supported node; three horizontal restraints,
chosen among them by a pivoted QR to hold the horizontal rigid motions, keep the
structure in place and, being statically determinate, carry no vertical load's reaction).

This module needs no SciPy at import (the roller's QR imports it when used): the checks
of the loads and supports (:data:`LOAD_SPECS`, :data:`SUPPORTS`) serve design files and
flags that are read before any solver is loaded.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np

from ..kernel._errors import InputError
from ..kernel._validate import Spec

if TYPE_CHECKING:  # pragma: no cover
    from ._model import BarHingeModel
    from ._structures import StructureModel

__all__ = ["G", "Loads", "Supports", "LOAD_SPECS", "SUPPORTS", "SUPPORTED", "snow_areas", "apex"]

#: Standard gravity, m/s².
G = 9.80665
#: The checks of the loads (keyword arguments and, later, flags and design-file keys).
LOAD_SPECS: tuple[Spec, ...] = (
    Spec("snow", "real", 0.0, "[0, 1e6]", "Pa", help="uniform vertical load per projected area on the roof (1 kPa = 1000 Pa)",
         why="a roof's snow is below 1e4 Pa; 1e6 Pa is a press"),
    Spec("point", "real", 0.0, "[0, 1e9]", "N", help="vertical point load, downward, at the apex unless placed", why="numerical range"),
)
_SPEC = {s.name: s for s in LOAD_SPECS}
#: How the supported nodes are held.
SUPPORTS = Spec("supports", "choice", "pinned", choices=("pinned", "roller"),
                help="how the supported end sections are held: pinned (every translation) or roller (the vertical, and three "
                     "horizontal restraints that only keep the structure in place)", label="supports")
#: Which nodes are supported: the feet (end sections on the ground) or both end sections wherever they are.
SUPPORTED = ("feet", "ends")


@dataclass(frozen=True)
class Loads:
    """What loads the structure (module notes). Checked on construction.

    Attributes
    ----------
    self_weight : bool
        The sheet's weight (density × thickness × area × g).
    snow : float
        Pa on the projected area of the surface seen from above.
    point : float
        N, downward.
    point_at : (3,) tuple of float or None
        Where the point load is (the nearest node carries it), m; None: the apex.

    Examples
    --------
    >>> Loads(snow=-1.0)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: snow must be in [0, 1000000] Pa (a roof's snow is below 1e4 Pa; 1e6 Pa is a press), got -1.0
    """

    self_weight: bool = True
    snow: float = 0.0
    point: float = 0.0
    point_at: tuple[float, float, float] | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.self_weight, (bool, np.bool_)):
            raise InputError(f"self_weight must be true or false, got {self.self_weight!r}")
        for name in ("snow", "point"):
            object.__setattr__(self, name, _SPEC[name].check(getattr(self, name)))
        if self.point_at is not None:
            at = np.asarray(self.point_at, float)
            if at.shape != (3,) or not np.isfinite(at).all():
                raise InputError(f"point_at must be a finite point [x, y, z] in m, got {self.point_at!r}")
            object.__setattr__(self, "point_at", tuple(float(v) for v in at))

    def forces(self, model: BarHingeModel) -> np.ndarray:
        """The nodal forces of these loads on a model, N, shape (P, 3).

        Raises
        ------
        InputError
            If no load is asked for, or snow falls on a model without membranes.

        Examples
        --------
        >>> import numpy as np
        >>> from curvefold.vault import Vault
        >>> tube = StructureModel.from_state(Vault.from_design(tubes=1, panels=4, samples=21).structure.state(), MATERIALS["aluminium"], 1e-3)
        >>> forces = Loads().forces(tube.model)   # self-weight
        >>> round(float(forces[:, 2].sum()), 6), round(float(-G * tube.model.masses.sum()), 6)
        (-22.737584, -22.737584)
        >>> Loads(self_weight=False).forces(tube.model)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: no load: give self-weight, snow or a point load
        """
        if not (self.self_weight or self.snow or self.point):
            raise InputError("no load: give self-weight, snow or a point load")
        f = np.zeros((len(model.nodes), 3))
        if self.self_weight:
            f[:, 2] -= G * model.masses
        if self.snow:
            if not len(model.membranes):
                raise InputError("snow needs a sheet (membrane triangles) to fall on")
            triangles, _ = model.triangles()
            f[:, 2] -= np.bincount(triangles.ravel(), np.repeat(self.snow * snow_areas(model) / 3, 3), minlength=len(f))
        if self.point:
            node = apex(model) if self.point_at is None else int(np.argmin(np.linalg.norm(model.nodes - self.point_at, axis=1)))
            f[node, 2] -= self.point
        return f


def apex(model: BarHingeModel) -> int:
    """The highest node (the first of equals)."""
    return int(np.argmax(model.nodes[:, 2]))


def snow_areas(model: BarHingeModel) -> np.ndarray:
    """Projected area of every triangle of the sheet (:meth:`BarHingeModel.triangles`) seen from above, m², shape (n,): 0 where hidden.

    A triangle is seen when no other triangle passes above its centroid (higher by more
    than 1e-9 of the model's size); its horizontal projected area then carries the snow.
    """
    x = model.nodes[model.triangles()[0]]  # (n, 3, 3)
    xy = x[..., :2]
    area = 0.5 * np.abs((xy[:, 1, 0] - xy[:, 0, 0]) * (xy[:, 2, 1] - xy[:, 0, 1]) - (xy[:, 2, 0] - xy[:, 0, 0]) * (xy[:, 1, 1] - xy[:, 0, 1]))
    centroid = x.mean(axis=1)
    covered = _covered(xy, x[..., 2], centroid, 1e-9 * max(model.size, 1e-300))
    return np.where(covered, 0.0, area)


def _covered(xy: np.ndarray, z: np.ndarray, points: np.ndarray, tol: float) -> np.ndarray:
    """For points (T, 3), the centroids of triangles (T, 3, 2) at heights z (T, 3): is another triangle above it?

    Triangles are binned on a uniform grid by their bounding boxes; each point is tested
    against the triangles of its cell (barycentric coordinates, then the height there).
    """
    T = len(xy)
    lo, hi = xy.min(axis=1), xy.max(axis=1)
    cell = float(np.median((hi - lo).max(axis=1))) / 3  # a third of a triangle's extent: fewest pairs tested (measured)
    if not cell > 0:
        return np.zeros(T, bool)
    origin = lo.min(axis=0)
    i0, i1 = np.floor((lo - origin) / cell).astype(np.int64), np.floor((hi - origin) / cell).astype(np.int64)
    width = int(i1[:, 0].max()) + 1
    spans = i1 - i0 + 1
    counts = spans[:, 0] * spans[:, 1]
    tri = np.repeat(np.arange(T), counts)
    k = np.arange(len(tri)) - np.repeat(np.cumsum(counts) - counts, counts)
    cx = i0[tri, 0] + k % spans[tri, 0]
    cy = i0[tri, 1] + k // spans[tri, 0]
    key = cy * width + cx
    order = np.argsort(key, kind="stable")
    key, tri = key[order], tri[order]
    p = points[:, :2]
    q = np.floor((p - origin) / cell).astype(np.int64)
    qkey = q[:, 1] * width + q[:, 0]
    start, stop = np.searchsorted(key, qkey, "left"), np.searchsorted(key, qkey, "right")
    n = stop - start
    query = np.repeat(np.arange(T), n)
    cand = tri[np.repeat(start, n) + np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)]
    a, b, c = xy[cand, 0], xy[cand, 1], xy[cand, 2]
    v0, v1, v2 = b - a, c - a, p[query] - a
    det = v0[:, 0] * v1[:, 1] - v0[:, 1] * v1[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (v2[:, 0] * v1[:, 1] - v2[:, 1] * v1[:, 0]) / det
        t = (v0[:, 0] * v2[:, 1] - v0[:, 1] * v2[:, 0]) / det
    inside = (det != 0) & (s >= 0) & (t >= 0) & (s + t <= 1) & (cand != query)
    height = (1 - s - t) * z[cand, 0] + s * z[cand, 1] + t * z[cand, 2]
    above = inside & (height > points[query, 2] + tol)
    out = np.zeros(T, bool)
    out[query[above]] = True
    return out


@dataclass(frozen=True)
class Supports:
    """How the structure is held (module notes).

    Attributes
    ----------
    kind : {"pinned", "roller"}
    nodes : tuple of int or None
        The supported nodes; None: those ``at`` names, of a structure's model.
    at : {"feet", "ends"}
        Without ``nodes``: the feet (the end sections on z = 0, where a vault stands) or
        the ends (every tube's end sections t = 0 and t = 1, wherever they are: a tube or
        block held at both ends).

    Examples
    --------
    >>> Supports("clamped")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: supports must be one of "pinned", "roller", got string 'clamped'
    """

    kind: Literal["pinned", "roller"] = "pinned"
    nodes: tuple[int, ...] | None = None
    at: Literal["feet", "ends"] = "feet"

    def __post_init__(self) -> None:
        SUPPORTS.check(self.kind)
        Spec("at", "choice", choices=SUPPORTED).check(self.at)
        if self.nodes is not None:
            nodes = np.asarray(self.nodes)
            if nodes.ndim != 1 or not len(nodes) or not np.issubdtype(nodes.dtype, np.integer):
                raise InputError(f"support nodes must be a non-empty list of node indices, got {self.nodes!r}")
            object.__setattr__(self, "nodes", tuple(int(v) for v in nodes))

    def fixed(self, target: StructureModel | BarHingeModel) -> np.ndarray:
        """The held DOFs, shape (P, 3) of bool.

        Raises
        ------
        InputError
            If the structure has no feet (no end section on z = 0) and no nodes are given,
            or a node is out of range.

        Examples
        --------
        >>> import numpy as np
        >>> from curvefold.vault import Vault
        >>> tube = StructureModel.from_state(Vault.from_design(tubes=1, panels=4, samples=21).structure.state(), MATERIALS["aluminium"], 1e-3)
        >>> int(Supports().fixed(tube).sum()), int(Supports("roller").fixed(tube).sum())   # 8 feet pinned; on rollers, z and 3 more
        (24, 11)
        >>> Supports(nodes=(99,)).fixed(tube)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: support nodes must be in [0, 20), got 99 … 99
        """
        structure = hasattr(target, "feet")  # a StructureModel, which knows its end sections
        model = target.model if structure else target
        P = len(model.nodes)
        if self.nodes is not None:
            nodes = np.asarray(self.nodes)
            if nodes.min() < 0 or nodes.max() >= P:
                raise InputError(f"support nodes must be in [0, {P}), got {nodes.min()} … {nodes.max()}")
        elif structure:
            nodes = target.feet if self.at == "feet" else target.ends
            if not len(nodes):
                low = float(model.nodes[target.ends, 2].min())
                raise InputError(f"no foot: no end section of this structure lies on the ground z = 0 (the lowest end point is at "
                                 f"z = {low:.6g} m); place it on the ground or give the supported nodes")
        else:
            raise InputError("a model without a structure needs its supported nodes")
        fixed = np.zeros((P, 3), bool)
        if self.kind == "pinned":
            fixed[nodes] = True
            return fixed
        fixed[nodes, 2] = True
        # the horizontal rigid motions (x, y, rotation about z) at the feet's x, y DOFs
        c = model.nodes[nodes, :2] - model.nodes[nodes, :2].mean(axis=0)
        rows = np.zeros((len(nodes), 2, 3))
        rows[:, 0, 0] = rows[:, 1, 1] = 1.0
        rows[:, 0, 2], rows[:, 1, 2] = -c[:, 1], c[:, 0]
        from scipy.linalg import qr

        held = qr(rows.reshape(-1, 3).T, mode="r", pivoting=True)[1][:3]
        fixed[nodes[held // 2], held % 2] = True
        return fixed
