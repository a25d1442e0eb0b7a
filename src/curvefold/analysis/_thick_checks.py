"""The checks of thick panels: every hinge axis on its crease, and the degrees of freedom of the
thick linkage.

A thick structure (:class:`~curvefold.geometry.ThickPanels`) is a linkage of rigid solids
joined by hinges. Two measurements say whether it moves as the zero-thickness structure does:

* :func:`hinge_offsets`: every hinge axis, carried by its panel's placement in a state of
  the zero-thickness motion, lies on that state's crease line (its distance, model units).
  A panel that does not keep its shape, or a hinge built off its crease, shows here.
* :func:`thick_mechanism`: the first-order degrees of freedom of the linkage, with the
  project's rigidity analysis (:func:`~curvefold.analysis.mechanism`). Each solid is a rigid
  body: its hinge-axis ends and one point of its top face, every pair of them a bar (the
  point off the panel's plane makes the body rigid in space); a hinge is two axis ends shared
  by the solids it joins (points that coincide in the design state are one). The constraints
  are thus the hinge axes and nothing else: no planarity of the zero-thickness panels is
  assumed.

With the hinges on their creases the thick linkage is the zero-thickness one, and it moves
with one degree of freedom away from flat (measured on tubes, blocks and vaults in the tests).
A hinge moved off its crease turns a spherical vertex (four axes through one point) into a
spatial four-bar loop, which is generically rigid: the count drops to 0.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..geometry._thick import ThickPanels, ThickRange
from ..geometry._topology import lattice_corners
from ..kernel._arrays import distinct
from ..kernel._lie import cross
from ._mechanism import CERTIFY_UNKNOWNS, RTOL, Framework, Mechanism, mechanism

__all__ = [
    "HINGE_TOL",
    "RANGE_STATES",
    "hinge_offsets",
    "thick_framework",
    "thick_mechanism",
    "thickness_checks",
]


def _world(thick: ThickPanels, local: np.ndarray, fold_angles: np.ndarray) -> np.ndarray:
    """Points (F, m, 3) given in their panels' frames, placed at fold angles (A,): (A, F, m, 3)."""
    origin, axes = thick.placements(fold_angles)
    return origin[:, :, None] + np.einsum("fmj,afjd->afmd", local, axes)


def hinge_offsets(thick: ThickPanels, fold_angles: Sequence[float] | np.ndarray) -> np.ndarray:
    """The largest distance of a hinge axis end from its crease line at each fold angle, (A,)
    model units.

    Every panel's hinge ends (:attr:`~curvefold.geometry.ThickPanels.hinges`) are placed by
    the panel's frame in the state and measured against the line through the corners of the
    zero-thickness state on that edge.

    Examples
    --------
    >>> from curvefold import Structure
    >>> from curvefold.geometry import PanelLattice, ThickPanels
    >>> from curvefold.geometry._lattice import _example_lattice
    >>> thick = ThickPanels.offset(
    ...     Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4)), 0.01
    ... )
    >>> bool(hinge_offsets(thick, [0, 45, 90]).max() < 1e-15)
    True
    """
    angles = np.asarray(fold_angles, float)
    F, k = thick.hinges.shape[:2]
    ends = _world(thick, thick.hinges.reshape(F, 2 * k, 3), angles).reshape(-1, F, k, 2, 3)
    corners = thick.corners(angles)  # (A, F, k, 3)
    start, stop = corners, np.roll(corners, -1, axis=2)
    direction = (stop - start) / np.linalg.norm(stop - start, axis=-1, keepdims=True)
    off = cross(ends - start[..., None, :], np.broadcast_to(direction[..., None, :], ends.shape))
    return np.linalg.norm(off, axis=-1).reshape(len(angles), -1).max(axis=1)


def thick_framework(thick: ThickPanels, *, tol: float = 1e-9) -> tuple[Framework, np.ndarray]:
    """The linkage of the solids as a :class:`~curvefold.analysis.Framework`, and which point of
    which panel every point is.

    Per panel: its 2k hinge ends and the centroid of its top face; points within ``tol`` ×
    the structure's size of each other in the design state are one. Bars join every pair of a
    panel's points; lengths are the design state's.

    Returns
    -------
    Framework
    members : (F, 2k + 1) ndarray of int
        The point of every panel's hinge ends and top point.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    F, k = thick.hinges.shape[:2]
    top = thick.local[:, k:].mean(axis=1, keepdims=True)
    local = np.concatenate([thick.hinges.reshape(F, 2 * k, 3), top], axis=1)
    design = float(thick.structure.lattice.crease.fold_angle)
    x = _world(thick, local, np.array([design]))[0].reshape(-1, 3)
    size = float(np.ptp(x, axis=0).max())
    pairs = cKDTree(x).query_pairs(tol * size, output_type="ndarray").reshape(-1, 2)
    n = len(x)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    count, weld = connected_components(graph, directed=False)
    members = weld.reshape(F, 2 * k + 1)
    i, j = np.triu_indices(2 * k + 1, 1)
    bars = np.sort(np.stack([members[:, i], members[:, j]], -1).reshape(-1, 2), axis=1)
    keys = distinct((bars[:, 0] * count + bars[:, 1])[bars[:, 0] != bars[:, 1]])
    bars = np.stack([keys // count, keys % count], axis=1)
    position = np.zeros((count, 3))
    position[weld] = x
    lengths = np.linalg.norm(position[bars[:, 0]] - position[bars[:, 1]], axis=1)
    empty = np.zeros(0)
    framework = Framework(count, bars, lengths, np.zeros((0, 4), np.int64), empty, empty)
    return framework, members


def thick_mechanism(
    thick: ThickPanels, fold_angles: Sequence[float] | np.ndarray, *, rtol: float = RTOL
) -> tuple[Mechanism, ...]:
    """The degrees of freedom of the thick linkage (:func:`thick_framework`) at fold angles
    (degrees).

    Each state places every panel's points by the panel's frame in the zero-thickness motion;
    a point shared by several panels takes the first one's place (the residual shows whether
    they agree).

    Examples
    --------
    >>> from curvefold import Structure
    >>> from curvefold.geometry import PanelLattice, ThickPanels
    >>> from curvefold.geometry._lattice import _example_lattice
    >>> thick = ThickPanels.offset(
    ...     Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4)), 0.01
    ... )
    >>> [m.dof for m in thick_mechanism(thick, [45, 90])]
    [1, 1]
    """
    framework, members = thick_framework(thick)
    F, k = thick.hinges.shape[:2]
    top = thick.local[:, k:].mean(axis=1, keepdims=True)
    local = np.concatenate([thick.hinges.reshape(F, 2 * k, 3), top], axis=1)
    angles = np.asarray(fold_angles, float)
    placed = _world(thick, local, angles).reshape(len(angles), -1, 3)
    flat = members.ravel()
    first = np.full(framework.points, -1)
    first[flat[::-1]] = np.arange(len(flat))[::-1]
    return tuple(
        mechanism(
            framework,
            x[first],
            rtol=rtol,
            label=f"2α = {a:g}°" + (" (flat)" if a == 0 else ""),
        )
        for a, x in zip(angles, placed)
    )


#: Largest distance of a hinge axis end from its crease, relative to the structure's size: the
#: placements are exact to rounding (measured at most 1.3e-15 of a size about 1, 6 ε).
HINGE_TOL = 1e-12
#: States tested for interpenetration inside the range, ends included.
RANGE_STATES = 9


def thickness_checks(
    thick: ThickPanels,
    motion: ThickRange | None = None,
    *,
    budget: int = CERTIFY_UNKNOWNS,
) -> dict:
    """The checks of thick panels, JSON-ready: the range with thickness and three verdicts.

    * ``hinges on creases``: :func:`hinge_offsets` at the range's ends, its middle and the
      design angle, at most :data:`HINGE_TOL` × the structure's size;
    * ``no interpenetration``: no two solids deeper than ``PENETRATION_TOL`` × t at
      :data:`RANGE_STATES` states across the stated range (``motion``, default
      :meth:`~curvefold.geometry.ThickPanels.motion_range`);
    * ``one degree of freedom``: :func:`thick_mechanism` at the same states but flat, of the
      first tubes within ``budget`` unknowns.

    Examples
    --------
    >>> from curvefold import Structure
    >>> from curvefold.geometry import PanelLattice, ThickPanels
    >>> from curvefold.geometry._lattice import _example_lattice
    >>> thick = ThickPanels.offset(
    ...     Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4)), 0.01
    ... )
    >>> report = thickness_checks(thick)
    >>> [(c["name"], c["passed"]) for c in report["checks"]]
    [('hinges on creases', True), ('no interpenetration', True), ('one degree of freedom', True)]
    >>> report["range"]["low"], round(report["stack_height"], 12)
    (0.0, 0.02)
    """
    from ..geometry._thick import PENETRATION_TOL

    motion = thick.motion_range() if motion is None else motion
    design = motion.design
    states = distinct(np.append(np.linspace(motion.low, motion.high, RANGE_STATES), design))
    size = float(np.ptp(thick.corners([design])[0].reshape(-1, 3), axis=0).max())
    offsets = hinge_offsets(thick, states)
    depths = [thick.deepest(a)[0] for a in states]
    part = _first_tubes(thick, budget)
    moving = [a for a in states if a > 0]
    counts = thick_mechanism(part, moving)
    checks = [
        {
            "name": "hinges on creases",
            "value": float(offsets.max()),
            "limit": HINGE_TOL * size,
            "passed": bool(offsets.max() <= HINGE_TOL * size),
        },
        {
            "name": "no interpenetration",
            "value": float(max(depths)),
            "limit": PENETRATION_TOL * thick.thickness,
            "passed": bool(max(depths) <= PENETRATION_TOL * thick.thickness),
        },
        {
            "name": "one degree of freedom",
            "value": [m.dof for m in counts],
            "limit": 1,
            "passed": all(m.dof == 1 and m.consistent for m in counts),
        },
    ]
    return {
        "thickness": thick.thickness,
        "technique": "offset panels",
        "reach": list(thick.reach),
        "range": {
            "design": design,
            "low": motion.low,
            "high": motion.high,
            "low_pair": motion.low_pair,
            "high_pair": motion.high_pair,
        },
        "stack_height": thick.stack_height(),
        "states": states.tolist(),
        "mechanism_scope": ""
        if part is thick
        else f"the first {len(part.structure.cells)} of the {len(thick.structure.cells)} tubes",
        "mechanism": [m.to_dict() for m in counts],
        "checks": checks,
    }


def _first_tubes(thick: ThickPanels, budget: int) -> ThickPanels:
    """The thick panels of the longest run of the structure's first tubes whose linkage has at
    most ``budget`` unknowns (at least one tube), bevelled as in the whole."""
    from dataclasses import replace

    from ..geometry._structure import Structure

    s = thick.structure
    panels_per_tube = len(thick.side) // len(s.cells)
    # a lattice point per hinge end and a top point per panel, 3 unknowns each
    fit = next(
        (
            k
            for k in range(len(s.cells), 0, -1)
            if 3 * (len(lattice_corners(s.cells[:k])[0]) * len(s.lattice.s) + k * panels_per_tube)
            <= budget
        ),
        1,
    )
    if fit == len(s.cells):
        return thick
    n = fit * panels_per_tube  # the first tubes' panels are the first faces
    part = Structure.from_cells(s.lattice, s.cells[:fit])
    return replace(
        thick,
        structure=part,
        side=thick.side[:n],
        bevels=thick.bevels[:n],
        local=thick.local[:n],
        hinges=thick.hinges[:n],
    )
