"""Soft modes: the inextensional motions of a model, counted by the null space of its bars.

What "soft" must mean where the sheet bends along rulings: rigid folding of a smooth
curved fold bends its strips (κ = κ_2D / cos α changes), so no motion of a smooth
structure costs only crease energy. What separates the soft motions from the rest is
stretching: a thin sheet bends at a cost ∝ E t³ and stretches at one ∝ E t, so the
motions that stretch no bar at first order (inextensional: ``C u = 0``) are those whose
stiffness stays of the order of bending and creases however thin the sheet, and every
other motion stiffens by (L / t)². Their number, rigid motions excluded, is
``dim null(C) − 6``.

Constraints can be added to ask what holds them: hinges of some kinds held (the panel
diagonals held: rigid panels, rulings that cannot drift), and quadruples of nodes held
planar (a tube's end sections: what the paper calls straight boundary quads), or node
pairs held at their distance (the end sections' diagonals).

The count is the number of singular values of the stacked, dimensionless constraint rows
(a bar's elongation, a held hinge's turn times its edge's length, a quadruple's
planarity) at or below ``rtol`` times the largest (:data:`RTOL`). The null motions of an
exact mechanism (a panel structure's folding) come out below 1e-8 (the floor of the
eigenvalues of AᵀA that find them); a smooth structure's folding, which stretches its
chords at O(h⁴), as well from 9 samples on; the smallest true deformation stays above
5e-6 up to 64 panels or 163 samples along the creases (all measured in the tests) and
falls as the structure is sampled finer. The count is found sparse: the smallest
eigenvalues of ``AᵀA`` (shift-invert just below zero), taken in growing blocks until one
lies above the tolerance.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..kernel._arrays import FrozenArrays
from ..kernel._errors import InputError
from ._linear import Factorized, eigsh
from ._model import BarHingeModel
from ._structures import StructureModel

__all__ = [
    "SoftModes",
    "soft_modes",
    "conjecture_counts",
    "RTOL",
    "planarity_rows",
    "distance_rows",
]

#: Rank tolerance relative to the largest singular value (module notes).
RTOL = 1e-6


@dataclass(frozen=True, eq=False)
class SoftModes(FrozenArrays):
    """The inextensional motions of a model under some constraints.

    Attributes
    ----------
    count : int
        Internal inextensional motions: null space dimension − 6.
    singular_values : (k,) ndarray
        The smallest singular values of the constraints, ascending, relative to the
        largest (rigid motions included).
    tolerance : float
        The relative rank tolerance.
    shapes : (count + 6, P, 3) ndarray
        A basis of the null motions (rigid ones included), orthonormal.

    Examples
    --------
    >>> import numpy as np
    >>> from curvefold.vault import Vault
    >>> tube = StructureModel.from_state(
    ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
    ...     MATERIALS["aluminium"],
    ...     1e-3,
    ... )
    >>> soft = soft_modes(tube.model)
    >>> soft.count, soft.shapes.shape, soft.gap > 1e3
    (2, (8, 20, 3), True)
    """

    count: int
    singular_values: np.ndarray
    tolerance: float
    shapes: np.ndarray

    @property
    def gap(self) -> float:
        """Smallest singular value above the tolerance over the largest at or below it."""
        s = self.singular_values
        above, below = s[s > self.tolerance], s[s <= self.tolerance]
        if not above.size or not below.size:
            return float("nan")
        return float(above[0] / below[-1]) if below[-1] > 0 else float("inf")


def planarity_rows(nodes: np.ndarray, quads: np.ndarray) -> sp.csr_matrix:
    """First-order change of ``det[c − a, d − b, b − a] / (|c − a| |d − b|)`` of quadruples (Q, 4),
    shape (Q, 3P).

    Zero when the quadruple stays planar (its diagonals' lines keep meeting): the
    condition of :mod:`curvefold.analysis._mechanism`, with dimensionless rows.
    """
    x = np.asarray(nodes, float)
    q = np.asarray(quads, np.int64).reshape(-1, 4)
    a, b, c, d = (x[q[:, i]] for i in range(4))
    u, v, w = c - a, d - b, b - a
    uv, vw, wu = np.cross(u, v), np.cross(v, w), np.cross(w, u)
    scale = (np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1))[:, None]
    grads = np.stack([-(vw + uv), uv - wu, vw, wu], axis=1) / scale[:, None]
    return _rows(grads, q, x.size)


def distance_rows(nodes: np.ndarray, pairs: np.ndarray) -> sp.csr_matrix:
    """First-order change of the distance of node pairs (Q, 2), shape (Q, 3P)."""
    x = np.asarray(nodes, float)
    p = np.asarray(pairs, np.int64).reshape(-1, 2)
    e = x[p[:, 1]] - x[p[:, 0]]
    e /= np.linalg.norm(e, axis=1, keepdims=True)
    return _rows(np.stack([-e, e], axis=1), p, x.size)


def _rows(grads: np.ndarray, elements: np.ndarray, dofs: int) -> sp.csr_matrix:
    N, m = elements.shape
    cols = (3 * elements[:, :, None] + np.arange(3)).reshape(N, 3 * m)
    return sp.csr_matrix(
        (grads.reshape(N, -1).ravel(), (np.repeat(np.arange(N), 3 * m), cols.ravel())),
        shape=(N, dofs),
    )


def soft_modes(
    model: BarHingeModel,
    *,
    held_hinges: Sequence[str] = (),
    planar: np.ndarray | None = None,
    held_pairs: np.ndarray | None = None,
    rtol: float = RTOL,
) -> SoftModes:
    """The inextensional motions of a model (module notes).

    Parameters
    ----------
    model : BarHingeModel
    held_hinges : sequence of str, keyword-only
        Hinge kinds that may not turn (``("diagonal",)``: rigid panels).
    planar : (Q, 4) array_like of int, optional, keyword-only
        Node quadruples held planar.
    held_pairs : (Q, 2) array_like of int, optional, keyword-only
        Node pairs held at their distance.
    rtol : float, keyword-only
        Rank tolerance relative to the largest singular value, in (0, 1).

    Examples
    --------
    A square of four bars has one shear mode and one out-of-plane fold; a diagonal holds
    the shear (its hinge is free), and with the diagonal's hinge held nothing moves:

    >>> import numpy as np
    >>> square = BarHingeModel(
    ...     np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]),
    ...     [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
    ...     np.ones(5),
    ...     [[0, 2, 1, 3]],
    ...     [1.0],
    ...     np.ones(4),
    ... )
    >>> soft_modes(square).count, soft_modes(square, held_hinges=("hinge",)).count
    (1, 0)
    """
    if not 0 < rtol < 1:
        raise InputError(f"rtol must be in (0, 1), got {rtol!r}")
    blocks = [model.compatibility()]
    held = np.flatnonzero(np.isin(np.asarray(model.hinge_kind), list(held_hinges)))
    if held.size:  # a hinge's turn times its edge's length: a displacement, like a bar's elongation
        edge = np.linalg.norm(np.diff(model.nodes[model.hinges[held, :2]], axis=1)[:, 0], axis=1)
        blocks.append(sp.diags(edge) @ model.hinge_matrix()[held])
    if planar is not None and len(planar):
        blocks.append(planarity_rows(model.nodes, planar))
    if held_pairs is not None and len(held_pairs):
        blocks.append(distance_rows(model.nodes, held_pairs))
    A = sp.vstack(blocks).tocsr()
    Q = (A.T @ A).tocsr()
    top = float(abs(Q).sum(axis=1).max())  # ≥ σ_max² (Gershgorin)
    n = Q.shape[0]
    shift = 1e-3 * (rtol * rtol * top)
    factor = Factorized(Q + shift * sp.identity(n, format="csr"))
    k = 12
    while True:
        k = min(k, n - 2)
        values, vectors = eigsh(
            Q,
            what="the soft modes",
            k=k,
            sigma=-shift,
            OPinv=factor.operator(),
            which="LM",
            tol=1e-12,
        )
        order = np.argsort(values)
        values, vectors = np.maximum(values[order], 0.0), vectors[:, order]
        sigma = np.sqrt(values / top)
        null = int(np.count_nonzero(sigma <= rtol))
        if null < k or k == n - 2:
            break
        k *= 2
    return SoftModes(null - 6, sigma, rtol, vectors[:, :null].T.reshape(null, -1, 3))


def conjecture_counts(structure: StructureModel, *, rtol: float = RTOL) -> dict[str, SoftModes]:
    """The paper's conjecture measured on a structure: its inextensional motions, free and held.

    Keys:

    ``"free"``
        every hinge may turn: the sheet bends at rulings and across the panels' diagonals,
        the discrete form of rulings that drift;
    ``"end planar"``
        every tube's end section at t = 0 held planar: the paper's straight boundary quads
        (whole tubes only);
    ``"end diagonals"``
        both end sections' diagonals held at their lengths (whole tubes only): the
        sections may no longer shear, which is what folding does to them;
    ``"rulings fixed"``
        the diagonal hinges held: rigid panels, rulings that cannot drift (the rigid
        folding of the paper's "folding without a change in the rulings position").

    Examples
    --------
    >>> from curvefold.vault import Vault
    >>> from curvefold.mechanics import MATERIALS
    >>> tube = StructureModel.from_state(
    ...     Vault.from_design(tubes=1, panels=8).structure.state(), MATERIALS["aluminium"], 1e-3
    ... )
    >>> {name: soft.count for name, soft in conjecture_counts(tube).items()}
    {'free': 2, 'end planar': 1, 'end diagonals': 0, 'rulings fixed': 1}
    """
    model = structure.model
    counts = {"free": soft_modes(model, rtol=rtol)}
    try:
        ends = structure.end_sections()
    except InputError:  # single sheets: a sheet's end is two rulings, not a section
        ends = None
    if ends is not None:
        counts["end planar"] = soft_modes(model, planar=ends[0::2], rtol=rtol)
        counts["end diagonals"] = soft_modes(
            model, held_pairs=np.concatenate([ends[:, [0, 2]], ends[:, [1, 3]]]), rtol=rtol
        )
    counts["rulings fixed"] = soft_modes(model, held_hinges=("diagonal",), rtol=rtol)
    return counts
