"""Space curves from curvature and torsion (the paper's Eq. 1).

The frame convention is the paper's: ``T' = κN``, ``N' = −κT + τB``, ``B' = −τN`` in arc
length s. The frame and the position are integrated together on SE(3) with the
sixth-order Magnus method (:mod:`curvefold.kernel._lie`), so a helix is exact to rounding and a
varying κ, τ converges at order 6 in both the frame and the position. Samples much denser
than that accuracy needs are filled between coarser Magnus steps by sixth-order Hermite
interpolation (:mod:`curvefold.kernel._dense`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._dense import coarse_indices, dense_stride, frenet_rates, hermite_fill
from ..kernel._errors import InputError
from ..kernel._functions import FunctionLike, ScalarFunction, as_function, check_finite
from ..kernel._lie import (
    CHUNK,
    GAUSS3_NODES,
    dual_to_motion,
    exp_dual,
    magnus6,
    matrix_quaternion,
    motion_to_dual,
    prefix_dual,
)
from ..kernel._validate import check_integer

__all__ = ["FramedCurve", "SpaceCurve", "integrate_frenet", "MAX_SAMPLES"]

#: Largest sample count accepted: a curve of this many samples holds ~1 GB of arrays.
MAX_SAMPLES = 10_000_000


def integrate_frenet(
    grid: np.ndarray,
    kappa_nodes: np.ndarray,
    tau_nodes: np.ndarray,
    *,
    speed_nodes: np.ndarray | float = 1.0,
    origin: np.ndarray | None = None,
    frame: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Integrate the Frenet–Serret frame and the position over a grid.

    Parameters
    ----------
    grid : (n,) ndarray
        Increasing values of the integration parameter q (arc length when speed is 1).
    kappa_nodes, tau_nodes : (..., n - 1, 3) ndarray
        Curvature and torsion at the three Gauss nodes of every interval
        (``grid[i] + GAUSS3_NODES * (grid[i+1] - grid[i])``); leading axes are a batch of
        curves integrated together.
    speed_nodes : (..., n - 1, 3) ndarray or float
        ds/dq at the same nodes.
    origin : (3,) ndarray, optional
        Position at ``grid[0]``; default the origin.
    frame : (3, 3) ndarray, optional
        Rotation whose columns are T, N, B at ``grid[0]``; default the identity.

    Returns
    -------
    points : (..., n, 3) ndarray
    frames : (..., n, 3, 3) ndarray
        Columns T, N, B at every grid value.

    Examples
    --------
    Half a unit circle in two steps of π/2, and a straight line (κ = τ = 0):

    >>> points, frames = integrate_frenet(
    ...     np.linspace(0, np.pi, 3), np.ones((2, 3)), np.zeros((2, 3))
    ... )
    >>> (points.round(6) + 0.0).tolist(), frames.shape
    ([[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 2.0, 0.0]], (3, 3, 3))
    >>> integrate_frenet(np.linspace(0, 1, 3), np.zeros((2, 3)), np.zeros((2, 3)))[0].tolist()
    [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [1.0, 0.0, 0.0]]
    """
    motions = integrate_motions(
        grid, kappa_nodes, tau_nodes, speed_nodes=speed_nodes, origin=origin, frame=frame
    )
    points = np.empty(motions.shape[1:] + (3,))
    frames = np.empty(motions.shape[1:] + (3, 3))
    for sl in _slices(motions.shape[-1], CHUNK):
        frames[..., sl, :, :], points[..., sl, :] = dual_to_motion(motions[..., sl])
    return points, frames


def integrate_motions(
    grid: np.ndarray,
    kappa_nodes: np.ndarray,
    tau_nodes: np.ndarray,
    *,
    speed_nodes: np.ndarray | float = 1.0,
    origin: np.ndarray | None = None,
    frame: np.ndarray | None = None,
) -> np.ndarray:
    """As :func:`integrate_frenet`, returning the rigid motions as dual quaternions (8, ..., n)."""
    kappa_nodes, tau_nodes, speed_nodes = np.broadcast_arrays(
        np.asarray(kappa_nodes, float), np.asarray(tau_nodes, float), np.asarray(speed_nodes, float)
    )
    h = np.diff(grid)
    steps = np.empty((8,) + kappa_nodes.shape[:-1])  # (8, ..., n-1)
    # Work in slices that stay in cache: each step is independent of the others.
    for sl in _slices(len(h), CHUNK):
        steps[..., sl] = exp_dual(
            magnus6(h[sl], kappa_nodes[..., sl, :], tau_nodes[..., sl, :], speed_nodes[..., sl, :])
        )
    # The start frame is the first factor of the prefix product.
    q0 = np.array([1.0, 0.0, 0.0, 0.0]) if frame is None else matrix_quaternion(frame)
    x0 = np.zeros(3) if origin is None else np.asarray(origin, float)
    start = np.broadcast_to(
        motion_to_dual(q0, x0)[(...,) + (None,) * (steps.ndim - 1)], steps.shape[:-1] + (1,)
    )
    return prefix_dual(np.concatenate([start, steps], axis=-1))


def _slices(n: int, size: int) -> list[slice]:
    return [slice(i, min(i + size, n)) for i in range(0, n, size)]


def gauss_nodes(grid: np.ndarray) -> np.ndarray:
    """The three Gauss–Legendre nodes of every interval of ``grid``, shape (n - 1, 3)."""
    return grid[:-1, None] + GAUSS3_NODES[None, :] * np.diff(grid)[:, None]


class FramedCurve:
    """A curve with a frame at every sample: its length and the columns of its frames.

    For classes holding ``s`` (n,), the curve parameter of the samples, ``points`` (n, 3)
    and ``frames`` (n, 3, 3), rotations whose columns are the tangent, normal and binormal.

    Examples
    --------
    >>> arc = SpaceCurve.from_curvature(1.0, 0.0, 2.0, samples=3)  # a SpaceCurve is a FramedCurve
    >>> arc.length, arc.tangent[0].tolist(), arc.normal[0].tolist(), arc.binormal[0].tolist()
    (2.0, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0])
    """

    # What the subclasses hold (their fields).
    s: np.ndarray
    points: np.ndarray
    frames: np.ndarray

    @property
    def length(self) -> float:
        """Parameter length s[-1] − s[0]: the arc length L."""
        return float(self.s[-1] - self.s[0])

    @property
    def tangent(self) -> np.ndarray:
        """Unit tangents, shape (n, 3)."""
        return self.frames[:, :, 0]

    @property
    def normal(self) -> np.ndarray:
        """Unit normals, shape (n, 3)."""
        return self.frames[:, :, 1]

    @property
    def binormal(self) -> np.ndarray:
        """Unit binormals, shape (n, 3)."""
        return self.frames[:, :, 2]


@dataclass(frozen=True, eq=False)
class SpaceCurve(FramedCurve, FrozenArrays):
    """A space curve sampled at uniform arc length with its Frenet frame.

    Build it with :meth:`from_curvature`. All arrays are read-only.

    Attributes
    ----------
    s : (n,) ndarray
        Arc length of the samples, ``linspace(0, length, n)``.
    points : (n, 3) ndarray
        Positions x(s).
    frames : (n, 3, 3) ndarray
        Rotation matrices whose columns are T, N, B.
    kappa, tau : ScalarFunction
        Curvature and torsion as functions of s.

    Examples
    --------
    >>> helix = SpaceCurve.from_curvature(1.0, 1.0, np.pi, samples=3)
    >>> helix.s.round(6).tolist(), helix.points.shape, helix.points.flags.writeable
    ([0.0, 1.570796, 3.141593], (3, 3), False)
    >>> SpaceCurve.from_curvature(0.0, 0.0, 1.0)  # a straight line has no Frenet frame
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: kappa must be > 0 everywhere (the Frenet frame needs it);
    at s = 0 it is 0
    """

    s: np.ndarray
    points: np.ndarray
    frames: np.ndarray
    kappa: ScalarFunction = field(repr=False)
    tau: ScalarFunction = field(repr=False)

    @classmethod
    def from_curvature(
        cls,
        kappa: FunctionLike,
        tau: FunctionLike,
        length: float,
        *,
        samples: int = 1001,
        origin: np.ndarray | None = None,
        frame: np.ndarray | None = None,
    ) -> SpaceCurve:
        """Integrate a curve from its curvature and torsion.

        Parameters
        ----------
        kappa, tau : float, callable or (m,) array_like
            κ(s) > 0 and τ(s) on ``[0, length]``: a constant, a vectorised callable, or m
            samples at ``linspace(0, length, m)`` (interpolated by a cubic spline).
        length : float
            Arc length L > 0.
        samples : int, keyword-only
            Number of output samples n ≥ 2. The integration step is L / (n - 1), or a
            multiple of it when that is still below ``0.015 / max(|ω|, √|ω'|)``; the samples
            in between then come from quintic Hermite interpolation
            (:mod:`curvefold.kernel._dense`).
        origin : (3,) array_like, optional
            x(0); default the origin.
        frame : (3, 3) array_like, optional
            Rotation with columns T(0), N(0), B(0); default the identity.

        Raises
        ------
        InputError
            If κ ≤ 0 or a value is not finite (the message names the arc length), or if
            a parameter is out of range.

        Examples
        --------
        A circle of radius 2 closes after one turn:

        >>> import numpy as np
        >>> c = SpaceCurve.from_curvature(0.5, 0.0, 4 * np.pi, samples=65)
        >>> bool(np.allclose(c.points[-1], c.points[0], atol=1e-13))
        True
        """
        length = check_length(length)
        samples = check_samples(samples)
        origin_arr = _check_vector(origin, "origin")
        frame_arr = _check_frame(frame)
        kf = as_function(kappa, name="kappa", length=length)
        tf = as_function(tau, name="tau", length=length)
        s = np.linspace(0.0, length, samples)
        stride, grid, rates = _coarse_grid(kf, tf, s)
        nodes = gauss_nodes(grid)
        k_nodes, t_nodes = kf(nodes), tf(nodes)
        ends = np.array([0.0, length])
        k_ends, t_ends = kf(ends), tf(ends)
        ok = (
            all(np.isfinite(v).all() for v in (k_nodes, t_nodes, k_ends, t_ends))
            and (k_nodes > 0).all()
            and (k_ends > 0).all()
        )
        if not ok:  # find and report the first offending arc length, samples included
            where = np.concatenate([s, nodes.ravel()])
            _check_curvature(np.concatenate([kf(s), k_nodes.ravel()]), where)
            check_finite(np.concatenate([tf(s), t_nodes.ravel()]), name="tau", s=where)
        if stride == 1:
            points, frames = integrate_frenet(
                s, k_nodes, t_nodes, origin=origin_arr, frame=frame_arr
            )
        else:
            motions = integrate_motions(grid, k_nodes, t_nodes, origin=origin_arr, frame=frame_arr)
            assert rates is not None  # a coarse grid (stride > 1) comes with its rates
            points, frames = hermite_fill(s, stride, motions, rates)
        return cls(readonly(s), readonly(points), readonly(frames), kf, tf)


def _coarse_grid(
    kappa: ScalarFunction, tau: ScalarFunction, s: np.ndarray
) -> tuple[int, np.ndarray, np.ndarray | None]:
    """The stride of the Magnus steps over the samples s, their grid and the rates the Hermite fill
    reads there.

    Where a derivative is not finite although the values are, every sample is a step (the
    integration needs no derivative).
    """
    stride = dense_stride(kappa, tau, float(s[-1]), len(s))
    if stride > 1:
        grid = s[coarse_indices(len(s), stride)]
        with np.errstate(all="ignore"):
            rates = frenet_rates(kappa, tau, grid)
        if np.isfinite(rates).all():
            return stride, grid, rates
    return 1, s, None


def check_length(length: float) -> float:
    """Validate an arc length: a finite number > 0."""
    L = float(length)
    if not np.isfinite(L) or L <= 0:
        raise InputError(f"length must be a finite number > 0, got {length!r}")
    return L


def check_samples(samples: int, *, name: str = "samples") -> int:
    """Validate a sample count: an integer in [2, MAX_SAMPLES]."""
    return check_integer(samples, name, f"[2, {MAX_SAMPLES}]", why="memory bound, about 1 GB")


def _check_vector(x: np.ndarray | None, name: str) -> np.ndarray | None:
    if x is None:
        return None
    arr = np.asarray(x, float)
    if arr.shape != (3,) or not np.isfinite(arr).all():
        raise InputError(f"{name} must be 3 finite numbers, got {x!r}")
    return arr


def _check_frame(frame: np.ndarray | None, *, tol: float = 1e-9) -> np.ndarray | None:
    if frame is None:
        return None
    R = np.asarray(frame, float)
    if R.shape != (3, 3) or not np.isfinite(R).all():
        raise InputError(
            f"frame must be a 3×3 rotation matrix (columns T, N, B), got shape {R.shape}"
        )
    err = np.abs(R.T @ R - np.eye(3)).max()
    if err > tol or np.linalg.det(R) < 0:
        raise InputError(
            f"frame must be a rotation (orthonormal, det +1) to within {tol:g}; "
            f"orthonormality error {err:.3g}, det {np.linalg.det(R):.6g}"
        )
    return R


def _check_curvature(k: np.ndarray, s: np.ndarray) -> None:
    check_finite(k, name="kappa", s=s)
    bad = np.flatnonzero(~(k > 0))
    if bad.size:
        i = bad[np.argmin(s[bad])]
        raise InputError(
            "kappa must be > 0 everywhere (the Frenet frame needs it); at s = "
            f"{s[i]:.6g} it is {k[i]:.6g}"
        )
