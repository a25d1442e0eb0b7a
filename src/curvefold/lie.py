"""Rigid motions for the Frenet–Serret integrator: the Lie group SE(3) and its algebra.

A rigid motion is a pair ``(R, p)`` of a rotation (..., 3, 3) and a translation (..., 3)
acting as ``x ↦ R x + p``. A twist is a pair ``(ω, v)`` of (..., 3) arrays, the body
angular and linear velocity.

The Frenet frame ``F = [T N B]`` (columns) and the position ``x`` of a curve obey
``(F, x)' = (F, x) · ξ`` with the body twist ``ξ = (σ (τ, 0, κ), σ (1, 0, 0))``, where σ is
the speed ds/dq of the parameter q. :func:`magnus6` integrates one step of that equation
with the sixth-order Magnus expansion on three Gauss–Legendre nodes (Blanes, Casas & Ros,
2000), :func:`exp_twist` maps the result onto the group in closed form (rotation as a quaternion),
and :func:`prefix_compose` chains the steps.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "GAUSS3_NODES",
    "GAUSS3_WEIGHTS",
    "frenet_twists",
    "magnus6",
    "exp_twist",
    "compose",
    "prefix_compose",
    "quaternion_matrix",
    "matrix_quaternion",
    "quaternion_rotate",
    "cross",
]

#: Gauss–Legendre nodes on [0, 1] (three points, order 6) and their weights.
GAUSS3_NODES = np.array([0.5 - np.sqrt(15.0) / 10.0, 0.5, 0.5 + np.sqrt(15.0) / 10.0])
GAUSS3_WEIGHTS = np.array([5.0, 8.0, 5.0]) / 18.0


def frenet_twists(kappa: np.ndarray, tau: np.ndarray, speed: np.ndarray | float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """Body twists of the Frenet–Serret equations.

    Parameters
    ----------
    kappa, tau : (...,) ndarray
        Curvature and torsion.
    speed : (...,) ndarray or float
        ds/dq for the integration parameter q (1 for arc length).

    Returns
    -------
    omega, v : (..., 3) ndarray
    """
    kappa, tau, speed = np.broadcast_arrays(np.asarray(kappa, float), np.asarray(tau, float), np.asarray(speed, float))
    zero = np.zeros_like(kappa)
    omega = np.stack([tau * speed, zero, kappa * speed], axis=-1)
    v = np.stack([speed, zero, zero], axis=-1)
    return omega, v


def _cross3(a: tuple, b: tuple) -> tuple:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _bracket(x: tuple, y: tuple) -> tuple:
    """Lie bracket for the form ``g' = g ξ`` (body twists): the negated se(3) commutator.

    Twists are 6-tuples of component arrays (ω₀, ω₁, ω₂, v₀, v₁, v₂).
    """
    w = _cross3(y[:3], x[:3])
    a, b = _cross3(y[:3], x[3:]), _cross3(x[:3], y[3:])
    return w + (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _lin(*terms: tuple) -> tuple:
    """Linear combination Σ c·x of 6-tuples, given as (c, x) pairs."""
    return tuple(sum(c * x[i] for c, x in terms) for i in range(6))


def magnus6(h: np.ndarray, omega: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """One sixth-order Magnus step per interval.

    Parameters
    ----------
    h : (M,) ndarray
        Step lengths in the integration parameter.
    omega, v : (M, 3, 3) ndarray
        Twists at the three Gauss nodes of each step (axis 1 is the node, axis 2 the coordinate).

    Returns
    -------
    omega, v : (M, 3) ndarray
        The step's twist Ω with ``g(q + h) = g(q) exp(Ω)``; exact when the twist is constant.
    """
    h = np.asarray(h, float)
    A = [tuple(h * omega[:, i, j] for j in range(3)) + tuple(h * v[:, i, j] for j in range(3)) for i in range(3)]
    c = np.sqrt(15.0) / 3.0
    a1 = A[1]
    a2 = _lin((c, A[2]), (-c, A[0]))
    a3 = _lin((10.0 / 3.0, A[2]), (-20.0 / 3.0, A[1]), (10.0 / 3.0, A[0]))
    c1 = _bracket(a1, a2)
    c2 = _lin((-1.0 / 60.0, _bracket(a1, _lin((2.0, a3), (1.0, c1)))))
    last = _bracket(_lin((-20.0, a1), (-1.0, a3), (1.0, c1)), _lin((1.0, a2), (1.0, c2)))
    out = _lin((1.0, a1), (1.0 / 12.0, a3), (1.0 / 240.0, last))
    return np.stack(out[:3], axis=-1), np.stack(out[3:], axis=-1)


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product over the last axis (several times faster than ``np.cross`` on small vectors)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a1 * b2 - a2 * b1
    out[..., 1] = a2 * b0 - a0 * b2
    out[..., 2] = a0 * b1 - a1 * b0
    return out


def exp_twist(omega: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Exponential map se(3) → SE(3) in closed form, the rotation as a unit quaternion.

    ``q = (cos θ/2, sin(θ/2)/θ · ω)`` and ``p = v + B ω×v + C ω×(ω×v)`` with θ = |ω|,
    ``B = (1 − cos θ)/θ²``, ``C = (θ − sin θ)/θ³``; below θ = 0.1 the coefficients come from
    their Taylor series (truncation < 1e-17).

    Quaternions, not matrices, carry the rotations through long products: the rounding
    error of a near-identity matrix sits in its diagonal and is the same at every equal
    step, so a product of n equal steps loses orthonormality like n·ε; in a quaternion
    that error only changes the norm, which :func:`quaternion_matrix` divides out.

    Parameters
    ----------
    omega, v : (..., 3) ndarray

    Returns
    -------
    q : (..., 4) ndarray
        Scalar-first unit quaternion.
    p : (..., 3) ndarray
    """
    t2 = np.einsum("...i,...i->...", omega, omega)
    t = np.sqrt(t2)
    small = t < 0.1
    ts = np.where(small, 1.0, t)
    # sin(θ/2)/θ, (1 − cos θ)/θ², (θ − sin θ)/θ³
    a = np.where(small, 0.5 * (1 - t2 / 24 * (1 - t2 / 80 * (1 - t2 / 168 * (1 - t2 / 288)))), np.sin(ts / 2) / ts)
    b = np.where(small, 0.5 * (1 - t2 / 12 * (1 - t2 / 30 * (1 - t2 / 56 * (1 - t2 / 90)))), (1 - np.cos(ts)) / ts**2)
    c = np.where(small, (1 - t2 / 20 * (1 - t2 / 42 * (1 - t2 / 72 * (1 - t2 / 110)))) / 6, (ts - np.sin(ts)) / ts**3)
    q = np.concatenate([np.cos(t / 2)[..., None], a[..., None] * omega], axis=-1)
    wv = cross(omega, v)
    p = v + b[..., None] * wv + c[..., None] * cross(omega, wv)
    return q, p


def quaternion_multiply(q1: np.ndarray, q2: np.ndarray) -> np.ndarray:
    """Hamilton product of scalar-first quaternions, shape (..., 4)."""
    w1, v1 = q1[..., :1], q1[..., 1:]
    w2, v2 = q2[..., :1], q2[..., 1:]
    return np.concatenate([w1 * w2 - np.einsum("...i,...i->...", v1, v2)[..., None], w1 * v2 + w2 * v1 + cross(v1, v2)], axis=-1)


def quaternion_rotate(q: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Rotate vectors x (..., 3) by quaternions q (..., 4) of any non-zero norm."""
    w, u = q[..., :1], q[..., 1:]
    n2 = np.einsum("...i,...i->...", q, q)[..., None]
    ux = cross(u, x)
    return x + (2.0 / n2) * (w * ux + cross(u, ux))


def matrix_quaternion(R: np.ndarray) -> np.ndarray:
    """Scalar-first unit quaternion of one rotation matrix (3, 3) (Shepperd's method)."""
    R = np.asarray(R, float)
    tr = np.trace(R)
    k = int(np.argmax([tr, R[0, 0], R[1, 1], R[2, 2]]))
    if k == 0:
        w = 0.5 * np.sqrt(1.0 + tr)
        q = [w, (R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w), (R[1, 0] - R[0, 1]) / (4 * w)]
    else:
        i, j, m = k - 1, k % 3, (k + 1) % 3
        r = 0.5 * np.sqrt(1.0 + R[i, i] - R[j, j] - R[m, m])
        q = [0.0] * 4
        q[0] = (R[m, j] - R[j, m]) / (4 * r)
        q[1 + i], q[1 + j], q[1 + m] = r, (R[j, i] + R[i, j]) / (4 * r), (R[m, i] + R[i, m]) / (4 * r)
    return np.array(q)


def quaternion_matrix(q: np.ndarray) -> np.ndarray:
    """Rotation matrices (..., 3, 3) of quaternions (..., 4) of any non-zero norm."""
    n2 = np.einsum("...i,...i->...", q, q)
    s = 2.0 / n2
    w, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    rows = [
        [1 - s * (y * y + z * z), s * (x * y - w * z), s * (x * z + w * y)],
        [s * (x * y + w * z), 1 - s * (x * x + z * z), s * (y * z - w * x)],
        [s * (x * z - w * y), s * (y * z + w * x), 1 - s * (x * x + y * y)],
    ]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def compose(q1: np.ndarray, p1: np.ndarray, q2: np.ndarray, p2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(q1, p1) ∘ (q2, p2) = (q1 q2, q1 p2 q1⁻¹ + p1)``, broadcasting over leading axes."""
    return quaternion_multiply(q1, q2), quaternion_rotate(q1, p2) + p1


def prefix_compose(q: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Inclusive prefix products ``G_k = S_0 ∘ S_1 ∘ … ∘ S_k``.

    The n steps are cut into about √n blocks of about √n steps; products run sequentially
    inside the blocks (vectorised across blocks), the block totals are prefixed by the same
    method recursively, and each block is then moved by the product of the blocks before it.
    Every result is thus a product of O(√n) factors instead of O(n), and the Python loop
    runs only O(√n) times.

    Parameters
    ----------
    q : (n, 4) ndarray
        Rotations as quaternions.
    p : (n, 3) ndarray
        Translations.

    Returns
    -------
    q, p : (n, 4) and (n, 3) ndarray
    """
    n = len(q)
    if n <= 16:
        qs, ps = q.copy(), p.copy()
        for k in range(1, n):
            qs[k], ps[k] = compose(qs[k - 1], ps[k - 1], q[k], p[k])
        return qs, ps
    b = int(np.ceil(np.sqrt(n)))
    nb = -(-n // b)
    pad = nb * b - n
    qb = np.concatenate([q, np.tile([1.0, 0.0, 0.0, 0.0], (pad, 1))]).reshape(nb, b, 4)
    pb = np.concatenate([p, np.zeros((pad, 3))]).reshape(nb, b, 3)
    for k in range(1, b):
        qb[:, k], pb[:, k] = compose(qb[:, k - 1], pb[:, k - 1], qb[:, k], pb[:, k])
    # Block k > 0 is moved by the product of blocks 0 … k−1.
    before_q, before_p = prefix_compose(qb[:-1, -1].copy(), pb[:-1, -1].copy())
    qb[1:], pb[1:] = compose(before_q[:, None], before_p[:, None], qb[1:], pb[1:])
    return qb.reshape(-1, 4)[:n], pb.reshape(-1, 3)[:n]
