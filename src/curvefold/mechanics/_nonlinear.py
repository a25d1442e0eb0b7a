"""Large displacements of the bar-and-hinge model: its energy, internal forces and tangent.

Total Lagrangian, about the model's reference state (stress free, :class:`BarHingeModel`):
the unknowns are the displacements u (3P,) from it, of any size, and the elastic energy is

    U(u) = ½ δ̃ᵀ S δ̃ + ½ Σ k_h (θ_h(x) − θ_h(X))²,    x = X + u,

**Bars and membranes.** Every bar's elongation δ is replaced by its Green–Lagrange
elongation δ̃ = (ℓ² − L²) / 2L = L E, with L and ℓ its reference and current lengths and
E = (ℓ² − L²) / 2L² its Green–Lagrange strain along it; S is the model's stiffness on the
bars (:meth:`BarHingeModel.bar_stiffness_matrix`). Why this law: for a triangle, the
Green–Lagrange strain tensor is uniform and its normal component along side m is exactly
E_m, so the membrane written on its bars (``ε = G δ``, :mod:`._elements`) becomes
``E = G δ̃`` and the energy ½ t A Eᵀ D E: the St Venant–Kirchhoff constant-strain
triangle, exact, at no cost beyond the linear model's. A bar of its own is the
St Venant–Kirchhoff bar (second Piola–Kirchhoff stress E·E). A quad keeps its five bars'
stiffness with δ̃ in place of δ. At the strains of a sheet that stays elastic (below 1 %)
the law differs from Liu and Paulino's (2017) Ogden-type bars by less than 1 % of the stress;
it softens in compression only past a shortening of 42 % (ℓ < L/√3).

Its derivatives: ∂δ̃/∂x = (x_b − x_a)/L on the bar's second node, its opposite on the
first (the rows of C at u = 0), and ∂²δ̃/∂x² = (1/L) [[I, −I], [−I, I]]; so the bars' forces
are ``C̃ᵀ S δ̃`` and their tangent ``C̃ᵀ S C̃ + Σ_b (S δ̃)_b ∂²δ̃_b/∂x²``.

**Hinges.** θ is the exact dihedral angle (:func:`._elements.dihedral_angle`) and
θ − θ(X) is taken in (−π, π] (a hinge turns by less than a half turn from its rest
angle). Its gradient is :func:`._elements.dihedral_gradient` (Liu and Paulino's formulas in
the module's notation), its Hessian :func:`._elements.dihedral_hessian` (analytic, vectorised
over the hinges; equal to a complex step of the gradient to rounding); a hinge's moment is
M = k Δθ, its forces M ∇θ and its tangent ``k ∇θ ∇θᵀ + M ∇²θ``. The tangent's sparse pattern
is found once per model and each assembly sums the blocks into it, the hinges' a chunk of
:data:`CHUNK` at a time (the Hessian of 71,712 hinges at once took 0.80 CPU-s, in chunks
0.18: its temporaries stay in cache and need no fresh pages).

At u = 0 every stress and moment vanishes and C̃ = C, J̃ = J: the tangent is the linear
model's stiffness Cᵀ S C + Jᵀ diag(k) J (equal to 2e-16 relative, measured in the tests).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from . import _elements
from ._model import BarHingeModel
from ._sparse import dof_index, rows_matrix

__all__ = ["elongations", "rotations", "energy", "internal_forces", "tangent"]


def _positions(model: BarHingeModel, u: np.ndarray) -> np.ndarray:
    return model.nodes + np.asarray(u, float).reshape(-1, 3)


def _lengths(model: BarHingeModel) -> np.ndarray:
    d = model.nodes[model.bars[:, 1]] - model.nodes[model.bars[:, 0]]
    return np.sqrt((d * d).sum(axis=1))


def elongations(model: BarHingeModel, u: np.ndarray) -> np.ndarray:
    """The bars' Green–Lagrange elongations δ̃ = (ℓ² − L²) / 2L for displacements u (3P,), m,
    shape (B,).

    Examples
    --------
    >>> import numpy as np
    >>> bar = BarHingeModel(
    ...     np.array([[0.0, 0, 0], [1, 0, 0]]), [[0, 1]], [1.0], np.zeros((0, 4), int), [], [1, 1]
    ... )
    >>> elongations(bar, np.array([0, 0, 0, 0.1, 0, 0])).round(12).tolist()  # (1.21 − 1) / 2
    [0.105]
    >>> elongations(bar, np.array([0, 0, 0, -1.0, 1, 0])).round(12).tolist()  # turned: no strain
    [0.0]
    """
    u = np.asarray(u, float).reshape(-1, 3)
    D = model.nodes[model.bars[:, 1]] - model.nodes[model.bars[:, 0]]
    du = u[model.bars[:, 1]] - u[model.bars[:, 0]]
    return (du * (2 * D + du)).sum(axis=1) / (2 * _lengths(model))  # ℓ² − L², no cancellation


def rotations(model: BarHingeModel, u: np.ndarray) -> np.ndarray:
    """The hinges' rotations θ(x) − θ(X) from their rest angles, in (−π, π], rad, shape (H,).

    Examples
    --------
    >>> import numpy as np
    >>> hinge = BarHingeModel(
    ...     np.array([[0.0, 0, 0], [0, 1, 0], [1, 0, 0], [-1, 0, 0]]),
    ...     [[0, 1], [0, 2], [1, 2], [0, 3], [1, 3]],
    ...     np.ones(5),
    ...     [[0, 1, 2, 3]],
    ...     [1.0],
    ...     np.ones(4),
    ... )
    >>> u = np.zeros(12)
    >>> u[9:] = [1, 0, 1]  # wing l turned by 90° about the edge
    >>> round(abs(float(rotations(hinge, u)[0])) * 2 / np.pi, 12)
    1.0
    """
    x = _positions(model, u)
    rest = model.__dict__.get("_rest_angles")  # cached like a cached_property
    if rest is None:
        rest = model.__dict__["_rest_angles"] = _elements.dihedral_angle(model.nodes[model.hinges])
    turn = _elements.dihedral_angle(x[model.hinges]) - rest
    return np.pi - np.mod(np.pi - turn, 2 * np.pi)


def energy(model: BarHingeModel, u: np.ndarray) -> float:
    """The elastic energy U(u) (module notes), J.

    Examples
    --------
    >>> import numpy as np
    >>> bar = BarHingeModel(
    ...     np.array([[0.0, 0, 0], [2, 0, 0]]), [[0, 1]], [3.0], np.zeros((0, 4), int), [], [1, 1]
    ... )
    >>> energy(bar, np.array([0, 0, 0, 1.0, 0, 0]))  # δ̃ = (9 − 4) / 4, ½ · 3 · δ̃²
    2.34375
    """
    d = elongations(model, u)
    turn = rotations(model, u)
    return float(0.5 * d @ (_stiffness(model) @ d) + 0.5 * turn @ (model.hinge_stiffness * turn))


def _bar_rows(model: BarHingeModel, x: np.ndarray) -> np.ndarray:
    """∂δ̃/∂x of every bar, shape (B, 2, 3)."""
    d = (x[model.bars[:, 1]] - x[model.bars[:, 0]]) / _lengths(model)[:, None]
    return np.stack([-d, d], axis=1)


def internal_forces(model: BarHingeModel, u: np.ndarray) -> np.ndarray:
    """∂U/∂u, the nodal forces the deformed model exerts against the loads, N, shape (3P,).

    Equilibrium under nodal loads f is ``internal_forces(model, u) = f`` on the free DOFs.

    Examples
    --------
    >>> import numpy as np
    >>> bar = BarHingeModel(
    ...     np.array([[0.0, 0, 0], [2, 0, 0]]), [[0, 1]], [3.0], np.zeros((0, 4), int), [], [1, 1]
    ... )
    >>> internal_forces(bar, np.array([0, 0, 0, 1.0, 0, 0])).tolist()  # 3 · 1.25 · 3 / 2
    [-5.625, 0.0, 0.0, 5.625, 0.0, 0.0]
    """
    x = _positions(model, u)
    S = _stiffness(model)
    f = rows_matrix(_bar_rows(model, x), model.bars, model.dofs).T @ (S @ elongations(model, u))
    if len(model.hinges):
        moments = model.hinge_stiffness * rotations(model, u)
        f = (
            f
            + rows_matrix(_elements.dihedral_gradient(x[model.hinges]), model.hinges, model.dofs).T
            @ moments
        )
    return np.asarray(f)


def tangent(model: BarHingeModel, u: np.ndarray) -> sp.csr_matrix:
    """∂²U/∂u², the tangent stiffness at displacements u, N/m, shape (3P, 3P), symmetric.

    The material part C̃ᵀ S C̃ + J̃ᵀ diag(k) J̃ on the current rows, plus the stresses' and
    moments' geometric part (module notes). At u = 0 it is :attr:`BarHingeModel.stiffness`.

    Examples
    --------
    >>> import numpy as np
    >>> bar = BarHingeModel(
    ...     np.array([[0.0, 0, 0], [2, 0, 0]]), [[0, 1]], [3.0], np.zeros((0, 4), int), [], [1, 1]
    ... )
    >>> # stretched to 3 m: axial 3 · (3/2)² + 3 · 1.25 / 2, transverse the force over L
    >>> tangent(bar, np.array([0, 0, 0, 1.0, 0, 0])).toarray()[3, 3:5].tolist()
    [8.625, 0.0]
    >>> float(tangent(bar, np.array([0, 0, 0, 1.0, 0, 0])).toarray()[4, 4])
    1.875
    """
    x = _positions(model, u)
    dofs = model.dofs
    L = _lengths(model)
    rows = _bar_rows(model, x).reshape(-1, 6)
    d = elongations(model, u)
    # bars of their own, and every bar's geometric part, as 6 × 6 blocks
    N = model.bar_stiffness * d
    membranes = model.membrane_stiffness.any()
    if membranes:
        S = _stiffness(model) - sp.diags(model.bar_stiffness)
        N = N + S @ d
    w = (N / L)[:, None, None] * _SPREAD
    bars = model.bar_stiffness[:, None, None] * rows[:, :, None] * rows[:, None, :] + w
    elements = [model.bars, model.hinges] if len(model.hinges) else [model.bars]
    place, indptr, indices = _pattern_of(elements, dofs, model)
    data = np.bincount(place[: bars.size], weights=bars.ravel(), minlength=len(indices))
    if len(model.hinges):
        moments = model.hinge_stiffness * rotations(model, u)
        _add_hinges(data, place[bars.size :], model, x[model.hinges], moments)
    K = sp.csr_matrix((data, indices, indptr), shape=(dofs, dofs))
    if membranes:  # the membranes couple their bars: C̃ᵀ S C̃ on the sparse rows
        Ct = rows_matrix(rows.reshape(-1, 2, 3), model.bars, dofs)
        K = (K + Ct.T @ S @ Ct).tocsr()
    K.sort_indices()
    return K


#: Hinges whose tangent blocks are made at a time (4.7 MB of blocks).
CHUNK = 4096


def _add_hinges(
    data: np.ndarray, place: np.ndarray, model: BarHingeModel, xh: np.ndarray, moments: np.ndarray
) -> None:
    """Add the hinges' tangent blocks ``k ∇θ ∇θᵀ + M ∇²θ`` at positions xh (H, 4, 3) under
    moments M (H,) to the CSR data, at their places ``place`` (H · 144,), :data:`CHUNK` hinges
    at a time: temporaries of a few MB, not of 144 floats per hinge (whose fresh pages made a
    third of the time system time)."""
    g = _elements.dihedral_gradient(xh).reshape(-1, 12)
    k = model.hinge_stiffness
    for s in range(0, len(g), CHUNK):
        part = slice(s, s + CHUNK)
        hinge = k[part, None, None] * g[part, :, None] * g[part, None, :]
        moving = np.flatnonzero(moments[part])
        if moving.size:
            hinge[moving] += moments[part][moving, None, None] * _elements.dihedral_hessian(
                xh[part][moving]
            )
        at = place[144 * s : 144 * s + hinge.size]
        low = int(at.min())  # neighbouring hinges land in a narrow range of the data
        summed = np.bincount(at - low, weights=hinge.ravel())
        data[low : low + len(summed)] += summed


def _stiffness(model: BarHingeModel) -> sp.csr_matrix:
    """The model's :meth:`BarHingeModel.bar_stiffness_matrix`, built once per model."""
    S = model.__dict__.get("_bar_stiffness")  # cached like a cached_property
    if S is None:
        S = model.__dict__["_bar_stiffness"] = model.bar_stiffness_matrix()
    return S


#: A bar's geometric block per unit N/L: [[I, −I], [−I, I]].
_SPREAD = np.kron(np.array([[1.0, -1.0], [-1.0, 1.0]]), np.eye(3))


def _assemble_blocks(
    blocks: list[np.ndarray], elements: list[np.ndarray], dofs: int, model: BarHingeModel
):
    """Σ of element blocks (N, 3m, 3m) on their nodes (N, m), of several kinds, in one build: the
    sum of each block entry into its place of the matrix's pattern, found once per model."""
    place, indptr, indices = _pattern_of(elements, dofs, model)
    vals = np.concatenate([b.ravel() for b in blocks])
    data = np.bincount(place, weights=vals, minlength=len(indices))
    return sp.csr_matrix((data, indices, indptr), shape=(dofs, dofs))


def _pattern_of(
    elements: list[np.ndarray], dofs: int, model: BarHingeModel
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`_pattern` of a model's elements, found once per model."""
    pattern = model.__dict__.get("_tangent_pattern")  # cached like a cached_property
    if pattern is None or pattern[0] != [len(e) for e in elements]:
        pattern = model.__dict__["_tangent_pattern"] = ([len(e) for e in elements],) + _pattern(
            elements, dofs
        )
    return pattern[1], pattern[2], pattern[3]


def _pattern(elements: list[np.ndarray], dofs: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Where every entry of the element blocks lands in the CSR data of their sum (its place),
    and the sum's indptr and (sorted) column indices."""
    index = [dof_index(e) for e in elements]
    rows = np.concatenate([np.repeat(i, i.shape[1], axis=1).ravel() for i in index])
    cols = np.concatenate([np.tile(i, (1, i.shape[1])).ravel() for i in index])
    flat = rows.astype(np.int64) * dofs + cols
    order = np.argsort(flat, kind="stable")
    ordered = flat[order]
    new = np.concatenate([[True], ordered[1:] != ordered[:-1]])
    place = np.empty(len(flat), np.int64)
    place[order] = np.cumsum(new) - 1
    first = ordered[new]
    indptr = np.searchsorted(first // dofs, np.arange(dofs + 1))
    return place, indptr, (first % dofs).astype(np.int32)
