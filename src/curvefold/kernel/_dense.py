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
normalised by :func:`curvefold.kernel._lie.quaternion_matrix`.
"""

from __future__ import annotations

import numpy as np

from ._functions import ScalarFunction
from ._lie import CHUNK, dual_to_motion, quaternion_matrix

__all__ = [
    "dense_stride",
    "frenet_rates",
    "hermite_fill",
    "coarse_indices",
    "STEP_RATE",
    "MIN_STRIDE",
]

#: Largest coarse step, as a multiple of the curve's rate scale 1/r.
STEP_RATE = 0.015
#: Below this stride the direct integration at every sample is used.
MIN_STRIDE = 4


def dense_stride(
    kappa: ScalarFunction, tau: ScalarFunction, length: float, samples: int, *, probes: int = 4001
) -> int:
    """How many samples one coarse Magnus step may span (1: integrate every sample).

    The rate scale ``r = max(|ω|, √|ω'|)`` with ``|ω| = √(κ² + τ²)`` is read on ``probes``
    points along the curve, ω' by differences of those values (:func:`numpy.gradient`). Where κ or τ
    is not finite, or κ ≤ 0, on those points the answer is 1, so that the full integration
    validates every node and names the place.

    Examples
    --------
    >>> from curvefold.kernel import Constant
    >>> dense_stride(Constant(1.0), Constant(0.0), 1.0, 100001)  # a circle sampled every 10 µm
    1499
    >>> dense_stride(
    ...     Constant(0.0), Constant(0.0), 1.0, 100001
    ... )  # zero curvature: every sample integrated
    1
    """
    h = length / (samples - 1)
    s = np.linspace(0.0, length, min(samples, probes))
    with np.errstate(all="ignore"):
        k, t = kappa(s), tau(s)
    if not (np.isfinite([k, t]).all() and (k > 0).all()):
        return 1  # let the sample-by-sample integration find and report the bad input
    rate = max(float(np.max(np.hypot(k, t))), 1e-12)
    if STEP_RATE / (rate * h) >= MIN_STRIDE:  # |ω| alone leaves room for a stride: ω' too
        rate = max(rate, float(np.sqrt(np.max(np.hypot(np.gradient(k, s), np.gradient(t, s))))))
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


def frenet_rates(kappa: ScalarFunction, tau: ScalarFunction, s: np.ndarray) -> np.ndarray:
    """κ, τ, κ' and τ' at arc lengths s (M,): the (4, M) data :func:`hermite_fill` reads.

    Examples
    --------
    >>> from curvefold.kernel import Constant
    >>> frenet_rates(Constant(1.0), Constant(0.0), np.array([0.0, 1.0])).tolist()
    [[1.0, 1.0], [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]]
    >>> frenet_rates(Constant(1.0), Constant(0.0), np.array([])).shape  # no samples
    (4, 0)
    """
    return np.stack([kappa(s), tau(s), kappa.derivative(s), tau.derivative(s)])


def hermite_fill(
    s: np.ndarray, stride: int, motions: np.ndarray, rates: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Fill every sample from the coarse solution at ``s[::stride]`` (and ``s[-1]``).

    Parameters
    ----------
    s : (n,) ndarray
        Arc length of all samples (uniform).
    stride : int
        Samples per coarse step.
    motions : (8, M) ndarray
        The frames and positions at the coarse samples, as dual quaternions.
    rates : (4, M) ndarray
        κ, τ, κ', τ' at the coarse samples (:func:`frenet_rates`).

    Returns
    -------
    points : (n, 3) ndarray
    frames : (n, 3, 3) ndarray

    Examples
    --------
    A unit circle from the coarse frames at s = 0 and 0.5 and 1, filled at 9 samples:

    >>> from curvefold.kernel import Constant
    >>> from curvefold.kernel._lie import motion_to_dual
    >>> s = np.linspace(0.0, 1.0, 9)
    >>> S = s[coarse_indices(9, 4)]
    >>> circle = lambda s: np.stack([np.sin(s), 1 - np.cos(s), 0 * s], axis=-1)
    >>> motions = np.stack(
    ...     [motion_to_dual([np.cos(a / 2), 0, 0, np.sin(a / 2)], x) for a, x in zip(S, circle(S))],
    ...     axis=1,
    ... )
    >>> points, frames = hermite_fill(s, 4, motions, frenet_rates(Constant(1.0), Constant(0.0), S))
    >>> float(np.abs(points - circle(s)).max()) < 1e-6, frames.shape
    (True, (9, 3, 3))
    """
    n = len(s)
    idx = coarse_indices(n, stride)
    S = s[idx]
    R, x = dual_to_motion(motions)
    q = motions[:4] / np.sqrt(np.einsum("im,im->m", motions[:4], motions[:4]))
    k, t, dk, dt = rates
    q1 = _times_twist(q, t, k) / 2  # q' = ½ q ω with ω = (0, τ, 0, κ)
    q2 = (_times_twist(q1, t, k) + _times_twist(q, dt, dk)) / 2
    # Hermite data of every coarse step: quaternions (4, M - 1, 6), positions (M - 1, 6, 3)
    H = np.diff(S)
    quaternions = np.moveaxis(_step_data(q.T, q1.T, q2.T, H), -1, 0)
    positions = _step_data(x, R[:, :, 0], k[:, None] * R[:, :, 1], H)
    points, frames = np.empty((n, 3)), np.empty((n, 3, 3))
    full = (n - 1) // stride  # coarse steps that span exactly ``stride`` samples
    basis = _basis(np.arange(stride) / stride)  # (stride, 6), the same for every full step
    per = max(1, CHUNK // stride)  # full steps per slice, to stay in cache
    for a in range(0, full, per):
        b = min(a + per, full)
        rows = slice(a * stride, b * stride)
        np.matmul(basis, positions[a:b], out=points[rows].reshape(b - a, stride, 3))
        quaternion_matrix((quaternions[:, a:b] @ basis.T).reshape(4, -1), out=frames[rows])
    if full < len(H):  # the samples inside the last, shorter step
        rows = slice(full * stride, n - 1)
        local = _basis((s[rows] - S[-2]) / H[-1])  # (r, 6)
        points[rows] = local @ positions[-1]
        quaternion_matrix(quaternions[:, -1] @ local.T, out=frames[rows])
    points[-1], frames[-1] = x[-1], R[-1]  # the last coarse sample, which no full step starts
    return points, frames


def _step_data(f0: np.ndarray, f1: np.ndarray, f2: np.ndarray, H: np.ndarray) -> np.ndarray:
    """Hermite data (p0, H v0, H² a0, H² a1, H v1, p1) of every step, shape (M - 1, 6, C), from
    the values and first two derivatives (M, C) at the coarse samples and the step lengths H (M -
    1,)."""
    H = H[:, None]
    H2 = H * H
    return np.stack([f0[:-1], H * f1[:-1], H2 * f2[:-1], H2 * f2[1:], H * f1[1:], f0[1:]], axis=1)


def _times_twist(q: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The Hamilton products q (0, a, 0, b) of quaternions q (4, M) by pure ones in the x–z
    plane, (4, M)."""
    w, x, y, z = q
    return np.stack([-(x * a + z * b), w * a + y * b, z * a - x * b, w * b - y * a])


def coarse_indices(n: int, stride: int) -> np.ndarray:
    """Indices of the coarse samples: every ``stride``-th, and the last.

    Examples
    --------
    >>> coarse_indices(10, 4).tolist(), coarse_indices(9, 4).tolist()
    ([0, 4, 8, 9], [0, 4, 8])
    >>> coarse_indices(1, 4).tolist()  # a single sample is its own last
    [0]
    """
    idx = np.arange(0, n, stride)
    return idx if idx[-1] == n - 1 else np.append(idx, n - 1)
