"""Soft modes at finite amplitude: does a first-order inextensional motion go on?

A soft mode φ stretches no bar at first order (``C φ = 0``, :mod:`._softmodes`); whether it is
a motion is a question about the stretching energy at finite amplitude ε (the energy ∝ E t
that a thin sheet cannot pay; its bending and crease energy, ∝ k ε² along every motion the
rigid folding included, is left out):

    U_s(u) = ½ δ̃ᵀ S δ̃,    δ̃ = (ℓ² − L²) / 2L,

with the Green–Lagrange elongations of :mod:`._nonlinear`. Two measures:

**Along the mode**, u = ε φ: δ̃ = ε C φ + ε² |Δφ|² / 2L, so U_s grows as ε² for a direction
that stretches at first order and as ε⁴ exactly for every soft mode, a motion or not: the
straight line leaves a curved path at second order.

**Relaxed**, U_s minimised over every displacement whose projection on φ is ε and on the
held directions (by default the rigid motions and the other soft modes) is zero, over the
stiff directions: Newton's method with Levenberg's damping on the exact Hessian, dense. A
soft mode that is rigid at second order (its second-order stretching not compensated by any
correction) still grows as ε⁴; one that starts a finite motion (the rigid folding) relaxes to
rounding (U_s at 1e-15 of its value along the line, measured in the tests); a stiff
direction grows as ε².

The exponent is the slope of log U_s against log ε, fitted by least squares over the
amplitudes given. The amplitude is the largest nodal displacement of ε φ, m.
"""

from __future__ import annotations

import numpy as np

from ..kernel._errors import InputError
from ._model import BarHingeModel
from ._nonlinear import _bar_rows, _lengths, elongations
from ._softmodes import soft_modes
from ._sparse import assemble, rows_matrix

__all__ = ["mode_energy_exponent", "stretching_energy", "rigid_motions"]

#: Relaxed over along below which the mode is a finite motion (reached: 1e-14, the stop).
FINITE = 1e-12

#: Newton steps at most per amplitude (the tests' cases take 2 to 7).
MAX_ITERATIONS = 50

_BAR_BLOCK = np.kron(np.array([[1.0, -1.0], [-1.0, 1.0]]), np.eye(3))


def stretching_energy(model: BarHingeModel, u: np.ndarray) -> float:
    """½ δ̃ᵀ S δ̃ of displacements u (3P,), J: the bars' part of :func:`._nonlinear.energy`.

    Examples
    --------
    >>> import numpy as np
    >>> bar = BarHingeModel(
    ...     np.array([[0.0, 0, 0], [2, 0, 0]]), [[0, 1]], [3.0], np.zeros((0, 4), int), [], [1, 1]
    ... )
    >>> stretching_energy(bar, np.array([0, 0, 0, 1.0, 0, 0]))  # δ̃ = (9 − 4) / 4, ½ · 3 · δ̃²
    2.34375
    """
    d = elongations(model, u)
    return float(0.5 * d @ (model.bar_stiffness_matrix() @ d))


def _gradient_hessian(model: BarHingeModel, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    x = model.nodes + u.reshape(-1, 3)
    C = rows_matrix(_bar_rows(model, x), model.bars, model.dofs)
    S = model.bar_stiffness_matrix()
    n = S @ elongations(model, u)
    blocks = (n / _lengths(model))[:, None, None] * _BAR_BLOCK[None]
    H = C.T @ S @ C + assemble(blocks, model.bars, model.dofs)
    return np.asarray(C.T @ n), H.toarray()


def rigid_motions(nodes: np.ndarray) -> np.ndarray:
    """The six infinitesimal rigid motions of nodes (P, 3), orthonormal, shape (6, 3P)."""
    x = np.asarray(nodes, float)
    x = x - x.mean(axis=0)
    e = np.eye(3)
    motions = [np.tile(e[i], len(x)) for i in range(3)]
    motions += [np.cross(e[i], x).ravel() for i in range(3)]
    q, _ = np.linalg.qr(np.array(motions).T)
    return np.asarray(q.T)


def mode_energy_exponent(
    model: BarHingeModel,
    mode: np.ndarray,
    amplitudes: np.ndarray,
    *,
    held: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The stretching energy of a mode at finite amplitude, along it and relaxed (module notes).

    Parameters
    ----------
    model : BarHingeModel
    mode : (P, 3) or (3P,) array_like
        The direction, free of rigid motions; scaled to a largest nodal displacement of 1.
    amplitudes : (n,) array_like
        ε, the largest nodal displacement, m, at least two, positive.
    held : (k, P, 3) or (k, 3P) array_like, optional, keyword-only
        Directions whose projections stay zero, taken orthogonal to the mode (supports: unit
        vectors on their DOFs); by default the null space of the bars
        (:func:`._softmodes.soft_modes`: the rigid motions and the other soft modes), so that
        the relaxation runs over the stiff directions only.

    Returns
    -------
    exponents : (2,) ndarray
        The slopes of log U_s against log ε (least squares): along the mode, relaxed; the
        relaxed one NaN where U_s relaxes to :data:`FINITE` of its value along the mode or
        less at every amplitude (a finite motion).
    energies : (2, n) ndarray
        U_s along the mode and relaxed at each amplitude, J.

    Examples
    --------
    A bar of two, pinned at both ends, its midpoint pushed sideways: ℓ² − L² = ε² in each
    half, U_s = 2 · ½ (EA / L) (ε² / 2L)² = EA ε⁴ / 4 L³, the same relaxed (the midpoint,
    free to move along the bar, stays by symmetry):

    >>> import numpy as np
    >>> bar = BarHingeModel(
    ...     np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0]]),
    ...     [[0, 1], [1, 2]],
    ...     [5.0, 5.0],
    ...     np.zeros((0, 4), int),
    ...     [],
    ...     np.ones(3),
    ... )
    >>> pins = np.eye(9)[[0, 1, 2, 6, 7, 8]]
    >>> exponents, energies = mode_energy_exponent(
    ...     bar, np.eye(9)[4], [1e-3, 1e-2], held=np.concatenate([pins, np.eye(9)[[5]]])
    ... )
    >>> exponents.round(9).tolist(), (energies / (5 / 4 * np.array([1e-12, 1e-8]))).round(12)
    ([4.0, 4.0], array([[1., 1.],
           [1., 1.]]))
    """
    dofs = model.dofs
    eps = np.asarray(amplitudes, float).ravel()
    if eps.size < 2 or not np.all(np.isfinite(eps)) or eps.min() <= 0:
        raise InputError(f"amplitudes must be at least two positive numbers, got {eps.tolist()!r}")
    m = np.asarray(mode, float).ravel()
    if m.size != dofs:
        raise InputError(f"mode must have {dofs} entries (3 per node), got {m.size}")
    size = float(np.abs(m).max())
    if not np.isfinite(size) or size == 0:
        raise InputError("mode must be finite and not zero")
    m = m / size
    if held is None:
        null = soft_modes(model).shapes
        H = null.reshape(len(null), dofs)
    else:
        H = np.asarray(held, float).reshape(-1, dofs)
    unit = m / np.linalg.norm(m)
    H = H - np.outer(H @ unit, unit)  # the mode keeps its own amplitude
    q = np.zeros((dofs, 0))
    if H.size:
        U, s, _ = np.linalg.svd(H.T, full_matrices=False)
        q = U[:, s > 1e-9 * max(float(s[0]), 1e-300)]
    full, _ = np.linalg.qr(np.column_stack([q, m]), mode="complete")
    N = full[:, q.shape[1] + 1 :]  # the relaxed directions
    along = np.array([stretching_energy(model, e * m) for e in eps])
    relaxed = np.array([_relax(model, e * m, N, a) for e, a in zip(eps, along)])
    exponents = [_slope(eps, along), _slope(eps, relaxed)]
    if np.all(relaxed <= FINITE * along):
        exponents[1] = np.nan  # a finite motion: rounding, no power law
    return np.array(exponents), np.array([along, relaxed])


def _slope(eps: np.ndarray, energies: np.ndarray) -> float:
    return float(np.polyfit(np.log(eps), np.log(np.maximum(energies, 1e-300)), 1)[0])


def _relax(model: BarHingeModel, u0: np.ndarray, N: np.ndarray, scale: float) -> float:
    """min over v of U_s(u0 + N v): Newton with Levenberg's damping on the exact Hessian, until
    U_s falls to 1e-14 of its start (a finite motion) or stops falling (a minimum)."""
    if scale <= 0 or not N.shape[1]:
        return scale
    v = np.zeros(N.shape[1])
    value, mu = scale, 1e-12
    for _ in range(MAX_ITERATIONS):
        g, H = _gradient_hessian(model, u0 + N @ v)
        g, H = N.T @ g / scale, N.T @ H @ N / scale
        for _ in range(30):  # damping grows until a step lowers the energy
            step = np.linalg.solve(H + mu * np.abs(H).max() * np.eye(len(v)), -g)
            trial = stretching_energy(model, u0 + N @ (v + step))
            if trial < value:
                break
            mu *= 10
        else:
            return value
        v, decrease, value = v + step, value - trial, trial
        mu = max(mu / 10, 1e-15)
        if value < 1e-14 * scale or decrease < 1e-10 * value:
            break
    return value
