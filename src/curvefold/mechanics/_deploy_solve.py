"""Newton's method along a prescribed motion, for :mod:`._deploy`: the energy of a model whose
hinges rest at given angles, the states reached from the kinematic ones, a line search."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np
import scipy.sparse as sp

from . import _elements
from ._model import BarHingeModel
from ._nonlinear import _add_hinges, _pattern_of, internal_forces, tangent
from ._path import _factor

__all__ = ["RATE", "Energy", "wrap", "first_state", "next_state"]

#: Newton's method makes a new tangent where an iteration leaves more than this share of the
#: residual.
RATE = 0.25


def wrap(turn: np.ndarray) -> np.ndarray:
    return np.pi - np.mod(np.pi - turn, 2 * np.pi)


class Energy:
    """The model's energy with hinges at given rest angles: forces, tangent and stresses."""

    def __init__(self, model: BarHingeModel, rest: np.ndarray) -> None:
        self.model = model
        self.rest = np.asarray(rest, float)
        empty = np.zeros(0)
        self.bars = replace(
            model,
            hinges=np.zeros((0, 4), np.int64),
            hinge_stiffness=empty,
            hinge_kind=np.zeros(0, str),
            hinge_length=empty,
            hinge_faces=np.zeros((0, 2), np.int64),
        )
        self.solver: Any = None  # the factor of the last tangent on the free DOFs
        d = model.nodes[model.bars[:, 1]] - model.nodes[model.bars[:, 0]]
        self.lengths = np.sqrt((d * d).sum(axis=1))

    def moments(self, x: np.ndarray) -> np.ndarray:
        m = self.model
        return m.hinge_stiffness * wrap(_elements.dihedral_angle(x[m.hinges]) - self.rest)

    def forces(self, u: np.ndarray) -> np.ndarray:
        m = self.model
        f = internal_forces(self.bars, u)
        if len(m.hinges):
            x = m.nodes + u.reshape(-1, 3)
            g = _elements.dihedral_gradient(x[m.hinges]).reshape(-1, 12)
            summed = np.bincount(  # a sum by index, 4 times faster than np.add.at
                _dofs(m.hinges).ravel(), (g * self.moments(x)[:, None]).ravel(), len(f)
            )
            f = f + summed
        return f

    def tangent(self, u: np.ndarray):
        m = self.model
        K = tangent(self.bars, u)
        if not len(m.hinges):
            return K
        x = m.nodes + u.reshape(-1, 3)
        place, indptr, indices = _pattern_of([m.hinges], m.dofs, m)
        data = np.zeros(len(indices))
        _add_hinges(data, place, m, x[m.hinges], self.moments(x))
        return (K + sp.csr_matrix((data, indices, indptr), shape=K.shape)).tocsr()

    def energy(self, u: np.ndarray) -> float:
        m = self.model
        x = m.nodes + u.reshape(-1, 3)
        D = x[m.bars[:, 1]] - x[m.bars[:, 0]]
        L = self.lengths
        d = ((D * D).sum(axis=1) - L * L) / (2 * L)
        turn = wrap(_elements.dihedral_angle(x[m.hinges]) - self.rest) if len(m.hinges) else d[:0]
        return float(
            0.5 * d @ (m.bar_stiffness_matrix() @ d) + 0.5 * turn @ (m.hinge_stiffness * turn)
        )

    def max_stress(self, u: np.ndarray) -> tuple[float, int]:
        """The largest surface stress (Pa) and the node nearest it (module notes of _response)."""
        m = self.model
        x = m.nodes + u.reshape(-1, 3)
        D = x[m.bars[:, 1]] - x[m.bars[:, 0]]
        L = self.lengths
        d = ((D * D).sum(axis=1) - L * L) / (2 * L)
        mb = m.membrane_bars
        s = np.einsum("tij,tj->ti", m.membrane_strain, np.where(mb >= 0, d[mb], 0.0))
        sx, sy, txy = (s @ m.elasticity.T).T
        vm = np.sqrt(np.maximum(sx * sx - sx * sy + sy * sy + 3 * txy * txy, 0.0))
        t = m.thickness
        bend = np.zeros(len(m.hinges))
        if len(m.hinges) and t > 0:
            bend = 6 * np.abs(self.moments(x)) / (np.asarray(m.hinge_length) * t * t)
        worst = np.zeros(len(m.membranes))
        for side in (0, 1):
            faces = np.asarray(m.hinge_faces)[:, side] if len(m.hinges) else np.zeros(0, int)
            ok = faces >= 0
            np.maximum.at(worst, faces[ok], bend[ok])
        surface = vm + worst
        if surface.size and surface.max() >= bend.max(initial=0.0):
            i = int(np.argmax(surface))
            return float(surface[i]), int(m.membranes[i, 0])
        if bend.size:
            i = int(np.argmax(bend))
            return float(bend[i]), int(m.hinges[i, 0])
        return 0.0, 0


def _dofs(elements: np.ndarray) -> np.ndarray:
    return (3 * elements[:, :, None] + np.arange(3)).reshape(len(elements), -1)


def first_state(
    energy: Energy,
    kin: np.ndarray,
    free: np.ndarray,
    f: np.ndarray,
    parts: int,
    tolerance: float,
    max_iterations: int,
    limit: float,
) -> tuple[np.ndarray, int] | None:
    """The first state: the kinematic state, in equilibrium with no load and its own hinge
    angles at rest, then the load and the rest angles brought to theirs in ``parts`` steps."""
    rest = energy.rest
    x = energy.model.nodes + kin.reshape(-1, 3)
    own = _elements.dihedral_angle(x[energy.model.hinges]) if len(rest) else rest
    gap = wrap(rest - own)
    u, total = kin.copy(), 0
    try:
        for p in range(1, parts + 1):
            energy.rest = own + gap * (p / parts)
            done = _newton(energy, u, free, f * (p / parts), tolerance, max_iterations, limit)
            if done is None:
                return None
            u, its = done
            total += its
    finally:
        energy.rest = rest
    return u, total


def next_state(
    energy: Energy,
    kin: np.ndarray,
    i: int,
    departure: np.ndarray,
    free: np.ndarray,
    f: np.ndarray,
    parts: int,
    tolerance: float,
    max_iterations: int,
    limit: float,
    trend: np.ndarray | None = None,
) -> tuple[np.ndarray, int] | None:
    """The state at angle i from the previous one, in ``parts`` sub-steps (the prescribed
    DOFs moved linearly between the two kinematic states), or None. ``trend``: the departure's
    expected change over the step (the last step's, extrapolated), added as the DOFs move."""
    start = kin[i - 1]
    total = 0
    u, prior = start + departure, start
    for p in range(1, parts + 1):
        target = start + (kin[i] - start) * (p / parts)
        if trend is not None:
            target = target + trend * (p / parts)
        u, prior = u + (target - prior), target
        done = _newton(energy, u, free, f, tolerance, max_iterations, limit)
        if done is None:
            return None
        u, its = done
        total += its
    return u, total


def _newton(
    energy: Energy,
    u: np.ndarray,
    free: np.ndarray,
    f: np.ndarray,
    tolerance: float,
    max_iterations: int,
    limit: float,
) -> tuple[np.ndarray, int] | None:
    """Newton's method on the free DOFs, every correction cut to ``limit`` (m) at most.

    The tangent's factor is kept from step to step (``energy.solver``) and made again only
    where the residual falls by less than :data:`RATE` in an iteration: along a motion at
    small steps most states need no new tangent (measured: the paper's vault, 1° steps).
    """
    u = u.copy()
    last, potential = np.inf, None
    for k in range(max_iterations + 1):
        g = energy.forces(u)
        r = f[free] - g[free]
        norm = float(np.linalg.norm(r))
        scale = float(np.abs(f).sum() + np.abs(g).sum())
        if not np.isfinite(norm):
            energy.solver = None
            return None
        if norm <= tolerance * max(scale, 1e-300):
            return u, k
        if k == max_iterations:
            energy.solver = None
            return None
        if energy.solver is None or norm > RATE * last:
            energy.solver, _ = _factor(energy.tangent(u)[free][:, free])
            if energy.solver is None:
                return None
        last = norm
        d = energy.solver.solve(r)
        big = float(np.abs(d).max(initial=0.0))
        if big <= 2e-9 * limit:  # 1e-10 of the span: stiff bars round the residual above
            u[free] += d
            return u, k + 1
        u, potential = _search(energy, u, free, f, d * min(1.0, limit / big), potential)
    return None


def _search(
    energy: Energy,
    u: np.ndarray,
    free: np.ndarray,
    f: np.ndarray,
    d: np.ndarray,
    before: float | None = None,
) -> tuple[np.ndarray, float | None]:
    """u moved along the Newton correction d by the first of 1, ½, ¼, … that lowers the total
    potential Π = U − f·u (or d itself where Π cannot tell, at rounding): a full Newton step
    from a strained warm start can overshoot into the stiff membranes. ``before``: Π(u) if
    known (the last search's); returns the point and its Π (None if not computed)."""
    if before is None:
        before = energy.energy(u) - float(f @ u)
    step = 1.0
    for _ in range(8):
        trial = u.copy()
        trial[free] += step * d
        after = energy.energy(trial) - float(f @ trial)
        if after <= before + 1e-12 * abs(before):
            return trial, after
        step *= 0.5
    trial = u.copy()
    trial[free] += d
    return trial, None
