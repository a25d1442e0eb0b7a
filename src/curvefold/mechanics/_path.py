"""Path following: the equilibrium of the model under a load growing from zero, past limit points.

The loads are λ f, a reference load f (N) times a load factor λ; the path is the set of
(u, λ) with ``internal_forces(model, u) = λ f`` on the free DOFs (:mod:`._nonlinear`).
Newton's method at a fixed λ (load control) stops at the first limit point, where the
tangent is singular and the load cannot grow. The generalized displacement control method
(Yang and Shieh 1990; modified by Leon, Paulino, Pereira, Menezes and Lages 2011, the
method of Liu and Paulino's MERLIN) makes λ an unknown:

* predictor of step i: ``K u_P = f`` on the current tangent, Δλ = ± Δλ₁ √|GSP| with the
  generalized stiffness parameter GSP = (u_P¹ · u_P¹) / (u_Pⁱ⁻¹ · u_Pⁱ): the step's
  displacement stays near the first step's, and the sign of Δλ flips where GSP < 0 (the
  tangent displacement reversed: a limit point was passed);
* corrector: ``K u_P = f``, ``K u_R = r`` (the residual), δλ = −(Δu₁ · u_R)/(Δu₁ · u_P),
  δu = u_R + δλ u_P, so that every correction stays orthogonal to the step's predictor
  Δu₁ (the displacement, not the load, is held: λ can pass a maximum).

The steps adapt: after a step that converged in few iterations the next grows (by 1.5, at
most :data:`GROWTH_LIMIT` times the first), after a slow one it shrinks; a step that does
not converge, or whose corrections take it farther than its predictor went (a jump to
another branch, not a step along this one), is halved and tried again, down to
2^-:data:`HALVINGS` of the first, below which :class:`PathError` says where (load factor,
step) and keeps the points computed. A try also ends after more than :data:`STALLS` iterations
in a row that did not halve the residual (each followed by a fresh tangent): on the paper's
vault, where Newton's method stalls at λ = 30.75, the command took 141 CPU-s, not 269 (side
by side), the same states bit for bit. Tangents are factorised by Cholesky
(:class:`._linear.Factorized`) where they are positive definite (the path is stable there)
and by a sparse LU past a limit point.

Measured (``tests/test_nonlinear.py``): the von Mises truss's states lie on its exact curve
to 2.4e-14 N through the limit point (2.9033 N), the inversion and back, in 48 states of one
iteration each; load control stops at 2.90327 with :class:`PathError`. A strip of 8 and 16
rigid panels follows the elastica to 5.6e-3 and 1.4e-3 m (second order). MERLIN's
Miura-ori folding, pop-through and bending (``benchmarks/bench_merlin.py``): the same load
factors to 4e-10, 1.7e-4 (beside a snap-back) and, where the bars' laws part at 7 %
strain, 2.1e-3, 10 to 14 times faster than MERLIN under Octave.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.sparse.linalg as spl

from ..kernel._arrays import FrozenArrays
from ..kernel._errors import ConvergenceError, InputError
from ..kernel._validate import Spec, check_integer
from ._linear import Factorized
from ._model import BarHingeModel
from ._nonlinear import internal_forces, tangent

__all__ = [
    "LoadPath",
    "PathError",
    "follow_load",
    "METHODS",
    "HALVINGS",
    "GROWTH_LIMIT",
    "STALLS",
]

#: The methods of :func:`follow_load`: generalized displacement control, or plain load control
#: (Newton at fixed load factors: stops at the first limit point).
METHODS = ("displacement", "load")
#: The path stops when a step that does not converge has been halved to 2^-HALVINGS of the
#: first.
HALVINGS = 12
#: The largest step, as a multiple of the first.
GROWTH_LIMIT = 8.0
#: A try of a step gives up after more than this many iterations in a row that did not halve the
#: residual, each followed by a fresh tangent (a factorisation: most of a stalled path's cost).
STALLS = 3
#: The iterations a step aims at: fewer and the next step grows, more and it shrinks.
AIM = 4

MAX_FACTOR = Spec("max_factor", "real", range="(0, inf)", help="the largest load factor")
FIRST = Spec("first", "real", range="(0, inf)", help="the first step's load factor")
TOLERANCE = Spec("tolerance", "real", range="[1e-14, 1e-2]", why="rounding to rough")
GROWTH = Spec("growth", "real", range="[1, 1e6]", help="the largest step over the first")
MAX_DISPLACEMENT = Spec("max_displacement", "real", range="(0, inf)", unit="m")


@dataclass(frozen=True, eq=False)
class LoadPath(FrozenArrays):
    """The equilibrium states along a load path, from the unloaded state. Arrays read-only.

    Attributes
    ----------
    factors : (n,) ndarray
        Load factors λ of the states, the first 0.
    displacements : (n, P, 3) ndarray
        Nodal displacements of the states, m.
    control : int
        The DOF (3 node + axis) whose displacement :attr:`control_displacement` follows.
    stable : (n,) ndarray of bool
        Whether the tangent on the free DOFs is positive definite at each state (stable
        equilibrium); it turns false past a limit point or a bifurcation.
    iterations : (n,) ndarray of int
        Newton iterations of each state's step (0 for the unloaded state).

    Examples
    --------
    The von Mises truss (half span 1 m, rise 0.2 m, EA = 1000 N) pressed at its apex: λ
    rises to the limit point (2.9033 N exactly), falls and turns negative (the truss pulled
    back as it inverts):

    >>> import numpy as np
    >>> truss = BarHingeModel(
    ...     np.array([[-1.0, 0, 0], [1, 0, 0], [0, 0, 0.2]]),
    ...     [[0, 2], [1, 2]],
    ...     [1000 / np.hypot(1, 0.2)] * 2,
    ...     np.zeros((0, 4), int),
    ...     [],
    ...     [1, 1, 1],
    ... )
    >>> fixed = np.ones((3, 3), bool)
    >>> fixed[2, 2] = False
    >>> path = follow_load(
    ...     truss,
    ...     [[0, 0, 0], [0, 0, 0], [0, 0, -1.0]],
    ...     fixed,
    ...     steps=300,
    ...     max_factor=10.0,
    ...     first=0.1,
    ...     max_displacement=0.3,
    ... )
    >>> round(path.limit, 2), bool(path.factors.min() < 0), bool(path.stable.all())
    (2.89, True, False)
    """

    factors: np.ndarray
    displacements: np.ndarray
    control: int
    stable: np.ndarray
    iterations: np.ndarray

    @property
    def control_displacement(self) -> np.ndarray:
        """The control DOF's displacement at every state, m, shape (n,)."""
        return self.displacements.reshape(len(self.factors), -1)[:, self.control]

    @property
    def limit(self) -> float | None:
        """The load factor of the first limit point (the largest λ before the path turns back),
        or None if λ only grew."""
        down = np.flatnonzero(np.diff(self.factors) < 0)
        return float(self.factors[: down[0] + 1].max()) if down.size else None


class PathError(ConvergenceError):
    """A load path that stopped before its end: the message says where, :attr:`path` holds the
    states computed up to there.

    Examples
    --------
    Load control stops at the von Mises truss's limit point (2.9033 N):

    >>> import numpy as np
    >>> truss = BarHingeModel(
    ...     np.array([[-1.0, 0, 0], [1, 0, 0], [0, 0, 0.2]]),
    ...     [[0, 2], [1, 2]],
    ...     [1000 / np.hypot(1, 0.2)] * 2,
    ...     np.zeros((0, 4), int),
    ...     [],
    ...     [1, 1, 1],
    ... )
    >>> fixed = np.ones((3, 3), bool)
    >>> fixed[2, 2] = False
    >>> try:
    ...     follow_load(
    ...         truss,
    ...         [[0, 0, 0], [0, 0, 0], [0, 0, -1.0]],
    ...         fixed,
    ...         steps=100,
    ...         max_factor=10.0,
    ...         method="load",
    ...     )
    ... except PathError as error:
    ...     print(round(float(error.path.factors.max()), 4))
    2.9033
    """

    def __init__(self, message: str, path: LoadPath) -> None:
        super().__init__(message)
        self.path = path


def _factor(K) -> tuple[Factorized | spl.SuperLU | None, bool]:
    """A solver of K (Cholesky if positive definite, else LU) and whether K is positive
    definite."""
    try:  # an indefinite K too wide for a band keeps its symmetric factor (pivots' signs)
        factor = Factorized(K)
        return factor, factor.definite
    except InputError:
        pass
    try:
        return spl.splu(K.tocsc(), permc_spec="COLAMD"), False
    except RuntimeError:  # exactly singular
        return None, False


def follow_load(
    model: BarHingeModel,
    forces: np.ndarray,
    fixed: np.ndarray,
    *,
    steps: int = 100,
    max_factor: float = 1.0,
    first: float | None = None,
    control: int | None = None,
    max_displacement: float | None = None,
    method: str = "displacement",
    tolerance: float = 1e-10,
    max_iterations: int = 20,
    stop: Callable[[LoadPath], bool] | None = None,
    growth: float = GROWTH_LIMIT,
    modified: bool = False,
) -> LoadPath:
    """Follow the equilibrium of a model under the loads λ · ``forces`` from λ = 0 (module notes).

    Parameters
    ----------
    model : BarHingeModel
    forces : (P, 3) or (3P,) array_like
        The reference load f, N (dead: fixed in size and direction).
    fixed : (P, 3) or (3P,) array_like of bool
        The held DOFs.
    steps : int, keyword-only
        The most steps to take, in [1, 100000].
    max_factor : float, keyword-only
        The path stops once λ reaches it.
    first : float, keyword-only
        The first step's load factor; default ``max_factor / steps``.
    control : int, keyword-only
        The DOF whose displacement the path reports (and ``max_displacement`` bounds);
        default the one the first step moves most.
    max_displacement : float, keyword-only
        The path stops once the control DOF has moved this far, m (default: no bound).
    method : {"displacement", "load"}, keyword-only
        Generalized displacement control, or load control (stops at a limit point).
    tolerance : float, keyword-only
        Converged when the residual's norm is below ``tolerance`` times the load's,
        ‖f‖ max(abs(λ), first), or a correction below ``tolerance`` times the step's
        displacement (where stiff bars round the residual above the first).
    max_iterations : int, keyword-only
        Newton iterations per try of a step.
    stop : callable, keyword-only
        Called with the path after every state (a progress bar's hook); the path ends
        there when it returns true.
    growth : float, keyword-only
        The largest step, as a multiple of the first (≥ 1).
    modified : bool, keyword-only
        Modified Newton: a step's corrections solve with the factor of its predictor's
        tangent, factorised again only where the residual falls by less than half in an
        iteration (each iteration then costs a residual and two solves, not an assembly
        and a factorisation); the states are the same equilibria, to the tolerance.

    Returns
    -------
    LoadPath

    Raises
    ------
    InputError
        For an argument out of its range, or a model free to move under the supports.
    PathError
        If a step does not converge even at 2^-``HALVINGS`` of the first: the message gives
        the load factor and the step, the error's ``path`` the states found.

    Examples
    --------
    A bar along x, held at its first node and across at its second, pulled by 1 N:

    >>> import numpy as np
    >>> bar = BarHingeModel(
    ...     np.array([[0.0, 0, 0], [1, 0, 0]]),
    ...     [[0, 1]],
    ...     [100.0],
    ...     np.zeros((0, 4), int),
    ...     [],
    ...     [1, 1],
    ... )
    >>> fixed = np.array([[True] * 3, [False, True, True]])
    >>> path = follow_load(
    ...     bar, [[0, 0, 0], [1.0, 0, 0]], fixed, steps=4, max_factor=1.0, method="load"
    ... )
    >>> path.factors.round(12).tolist()
    [0.0, 0.25, 0.625, 1.0]
    >>> # St Venant–Kirchhoff: N = EA E ℓ/L, 1 = 100 (ℓ² − 1)/2 · ℓ at ℓ = 1.009853873
    >>> round(float(path.control_displacement[-1]), 9)
    0.009853873
    """
    P = len(model.nodes)
    f = np.asarray(forces, float).reshape(-1)
    held = np.asarray(fixed, bool).reshape(-1)
    if f.shape != (3 * P,) or held.shape != (3 * P,):
        raise InputError(
            f"forces and fixed must have shape ({P}, 3), got {np.shape(forces)} and "
            f"{np.shape(fixed)}"
        )
    steps = check_integer(steps, "steps", "[1, 100000]")
    max_iterations = check_integer(max_iterations, "max_iterations", "[1, 1000]")
    max_factor = MAX_FACTOR.check(max_factor)
    first = max_factor / steps if first is None else FIRST.check(first)
    tolerance = TOLERANCE.check(tolerance)
    growth = GROWTH.check(growth)
    if max_displacement is not None:
        max_displacement = MAX_DISPLACEMENT.check(max_displacement)
    if method not in METHODS:
        raise InputError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    free = np.flatnonzero(~held)
    if control is not None:
        control = check_integer(control, "control", f"[0, {3 * P - 1}]")
    F = f[free]
    scale = float(np.linalg.norm(F))
    if scale == 0:
        raise InputError("forces must load a free DOF, got none")
    K0 = model.stiffness[free][:, free]
    Factorized.checked(K0, model, free, where="under these supports")

    u = np.zeros(3 * P)
    lam = 0.0
    states, factors, stable, iterations = [u.copy()], [0.0], [True], [0]
    ref = prev = None  # first step's and previous step's tangent displacements
    step_size, direction = first, 1.0

    def path() -> LoadPath:
        c = control if control is not None else 0
        return LoadPath(
            np.array(factors),
            np.array(states).reshape(len(states), P, 3),
            int(c),
            np.array(stable),
            np.array(iterations),
        )

    def fail(reason: str) -> PathError:
        return PathError(
            f"the load path did not converge at load factor {lam:.6g} (step {len(factors)}, "
            f"{len(factors) - 1} states kept): {reason}",
            path(),
        )

    for _ in range(steps):
        solver, definite = _factor(tangent(model, u)[free][:, free])
        if solver is None:
            raise fail("the tangent is singular")
        up = solver.solve(F)
        if ref is None:
            ref = up @ up
            if control is None:
                control = int(free[np.argmax(np.abs(up))])
        sign = direction
        if method == "displacement" and prev is not None:
            gsp = ref / (prev @ up)
            direction *= np.sign(gsp)  # the tangent displacement reversed: a limit point
            sign = direction * np.sqrt(abs(gsp))
        stable[-1] = definite
        while True:
            dlam = step_size * sign
            if method == "load":
                dlam = min(dlam, max_factor - lam)  # land on max_factor
            trial = _step(
                model,
                free,
                u,
                lam,
                F,
                up * dlam,
                dlam,
                method,
                tolerance,
                scale,
                max(first, abs(lam) + abs(dlam)),
                max_iterations,
                (solver, up) if modified else None,
            )
            if trial is not None:
                break
            step_size *= 0.5
            if step_size < first * 0.5**HALVINGS:
                raise fail(
                    f"Newton's method found no equilibrium within {max_iterations} "
                    f"iterations (nor while its own tangent halved the residual), even on a "
                    f"step of 2^-{HALVINGS} of the first"
                    + (" (load control cannot pass a limit point)" if method == "load" else "")
                )
        u, lam, its, fresh = trial
        prev = up
        states.append(u.copy())
        factors.append(lam)
        stable.append(True)
        iterations.append(its)
        effort = fresh + 1 if modified else its  # modified: the factorisations count
        step_size = min(
            step_size * (1.5 if effort <= AIM else 0.7 if effort > 2 * AIM else 1.0),
            growth * first,
        )
        if lam >= max_factor or (
            max_displacement is not None and abs(u[control]) >= max_displacement
        ):
            break
        if stop is not None and stop(path()):
            break
    stable[-1] = _factor(tangent(model, u)[free][:, free])[1]
    return path()


def _step(
    model: BarHingeModel,
    free: np.ndarray,
    u0: np.ndarray,
    lam0: float,
    F: np.ndarray,
    predictor: np.ndarray,
    dlam: float,
    method: str,
    tolerance: float,
    scale: float,
    level: float,
    max_iterations: int,
    held: tuple | None = None,
) -> tuple[np.ndarray, float, int, int] | None:
    """One step from (u0, λ0) along a predictor; the converged (u, λ, iterations, tangents
    factorised), or None. ``held``: the predictor's solver and its solve of F, for modified
    Newton."""
    u = u0.copy()
    u[free] += predictor
    lam = lam0 + dlam
    before, fresh, stalled = np.inf, 0, 0
    for k in range(1, max_iterations + 1):
        r = lam * F - internal_forces(model, u)[free]
        if not np.isfinite(r).all():
            return None
        size = float(np.linalg.norm(r))
        if size <= tolerance * scale * max(level, abs(lam)):
            return u, lam, k - 1, fresh
        if held is None or size > 0.5 * before:
            stalled = stalled + 1 if size > 0.5 * before else 0
            if stalled > STALLS:
                return None  # Newton's own tangent no longer halves the residual: halve the step
            fresh += 1
            solver, _ = _factor(tangent(model, u)[free][:, free])
            if solver is None:
                return None
            held = None if held is None else (solver, solver.solve(F))
        else:
            solver = held[0]
        before = size
        ur = solver.solve(r)
        if method == "load":
            d, dl = ur, 0.0
        else:
            uf = solver.solve(F) if held is None else held[1]
            dl = -(predictor @ ur) / (predictor @ uf)
            d = ur + dl * uf
        u[free] += d
        lam += dl
        step = np.linalg.norm(u[free] - u0[free])
        if np.linalg.norm(u[free] - u0[free] - predictor) > np.linalg.norm(predictor):
            return None  # corrected farther than the step went: a jump off the path
        if np.linalg.norm(d) <= tolerance * step:
            return u, lam, k, fresh  # the correction is at rounding: stiff bars cannot do better
    return None
