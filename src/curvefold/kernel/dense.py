"""Dense output: a curve sampled far more finely than its accuracy needs.

When the requested samples are much denser than the Magnus steps need, the curve is
integrated on every m-th sample and the samples in between are filled by quintic Hermite
interpolation of the position and of the frame's quaternion, from their values and first
two derivatives at both ends of each coarse step — all known in closed form:

    x' = T,  x'' = κ N,  q' = ½ q ω,  q'' = ½ q' ω + ½ q ω'     with ω = (0, τ, 0, κ)

(the quaternion's body angular velocity). The interpolation error is bounded by
``max|f⁽⁶⁾| H⁶ / (720 · 64)`` on a step of length H; the stride is chosen so that
``H · r ≤`` :data:`STEP_RATE` with r the largest of ``|ω|`` and ``√|ω'|`` on the curve, which puts
it below rounding. The frames stay orthonormal: every interpolated quaternion is
normalised by :func:`curvefold.kernel.lie.quaternion_matrix`.
"""

from __future__ import annotations

import numpy as np

from .functions import ScalarFunction
from .lie import _qmul, quaternion_matrix

__all__ = ["dense_stride", "hermite_fill", "STEP_RATE", "MIN_STRIDE"]

#: Largest coarse step, as a multiple of the curve's rate scale 1/r.
STEP_RATE = 0.015
#: Below this stride the direct integration at every sample is used.
MIN_STRIDE = 4


def dense_stride(kappa: ScalarFunction, tau: ScalarFunction, length: float, samples: int, *, probes: int = 4001) -> int:
    """How many samples one coarse Magnus step may span (1: integrate every sample).

    The rate scale ``r = max(|ω|, √|ω'|)`` with ``|ω| = √(κ² + τ²)`` is read on ``probes``
    points along the curve. Where κ or τ is not finite, or κ ≤ 0, on those points the
    answer is 1, so that the full integration validates every node and names the place.
    """
    h = length / (samples - 1)
    s = np.linspace(0.0, length, min(samples, probes))
    with np.errstate(all="ignore"):
        k, t = kappa(s), tau(s)
        dk, dt = kappa.derivative(s), tau.derivative(s)
    if not (np.isfinite([k, t, dk, dt]).all() and (k > 0).all()):
        return 1  # let the sample-by-sample integration find and report the bad input
    rate = max(float(np.max(np.hypot(k, t))), float(np.sqrt(np.max(np.hypot(dk, dt)))), 1e-12)
    m = int(STEP_RATE / (rate * h))
    return m if m >= MIN_STRIDE else 1


# Quintic Hermite basis on [0, 1] for (p0, H v0, H² a0, H² a1, H v1, p1).
def _basis(t: np.ndarray) -> np.ndarray:
    t2, t3 = t * t, t * t * t
    t4, t5 = t3 * t, t3 * t2
    return np.stack(
        [
            1 - 10 * t3 + 15 * t4 - 6 * t5,
            t - 6 * t3 + 8 * t4 - 3 * t5,
            0.5 * t2 - 1.5 * t3 + 1.5 * t4 - 0.5 * t5,
            0.5 * t3 - t4 + 0.5 * t5,
            -4 * t3 + 7 * t4 - 3 * t5,
            10 * t3 - 15 * t4 + 6 * t5,
        ],
        axis=-1,
    )


def hermite_fill(
    s: np.ndarray,
    stride: int,
    coarse_q: np.ndarray,
    coarse_x: np.ndarray,
    kappa: ScalarFunction,
    tau: ScalarFunction,
) -> tuple[np.ndarray, np.ndarray]:
    """Fill every sample from the coarse solution at ``s[::stride]`` (and ``s[-1]``).

    Parameters
    ----------
    s : (n,) ndarray
        Arc length of all samples (uniform).
    stride : int
        Samples per coarse step.
    coarse_q : (4, M) ndarray
        Frame quaternions at the coarse samples.
    coarse_x : (M, 3) ndarray
        Positions at the coarse samples.
    kappa, tau : ScalarFunction

    Returns
    -------
    points : (n, 3) ndarray
    frames : (n, 3, 3) ndarray
    """
    n = len(s)
    idx = coarse_indices(n, stride)
    S = s[idx]
    q = coarse_q / np.sqrt(np.sum(coarse_q**2, axis=0))
    k, t, dk, dt = kappa(S), tau(S), kappa.derivative(S), tau.derivative(S)
    zero = np.zeros_like(k)
    w, dw = (zero, t, zero, k), (zero, dt, zero, dk)
    q1 = tuple(0.5 * c for c in _qmul(tuple(q), w))
    q2 = tuple(0.5 * (a + b) for a, b in zip(_qmul(q1, w), _qmul(tuple(q), dw)))
    R = quaternion_matrix(q.T)
    # values and derivatives at the coarse samples: (M, C) with C = 4 quaternion + 3 position
    f0 = np.concatenate([q.T, coarse_x], axis=1)
    f1 = np.concatenate([np.stack(q1, axis=1), R[:, :, 0]], axis=1)
    f2 = np.concatenate([np.stack(q2, axis=1), k[:, None] * R[:, :, 1]], axis=1)
    H = np.diff(S)[:, None]
    coef = np.stack([f0[:-1], H * f1[:-1], H**2 * f2[:-1], H**2 * f2[1:], H * f1[1:], f0[1:]], axis=1)  # (M-1, 6, C)
    out = np.empty((n, 7))
    full = (n - 1) // stride  # coarse steps that span exactly ``stride`` samples
    if full:
        basis = _basis(np.arange(stride) / stride)  # (stride, 6), the same for every full step
        out[: full * stride] = (basis @ coef[:full]).reshape(-1, 7)
    tail = np.arange(full * stride, n)
    j = np.minimum(tail // stride, len(coef) - 1)
    local = (s[tail] - S[j]) / H[j, 0]
    out[tail] = np.einsum("ib,ibc->ic", _basis(local), coef[j])
    out[idx] = f0  # the coarse samples themselves, exactly
    return out[:, 4:], quaternion_matrix(out[:, :4])


def coarse_indices(n: int, stride: int) -> np.ndarray:
    """Indices of the coarse samples: every ``stride``-th, and the last."""
    idx = np.arange(0, n, stride)
    return idx if idx[-1] == n - 1 else np.append(idx, n - 1)
