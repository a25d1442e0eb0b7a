"""Deployment: a structure folded from near flat to its design angle under its own weight.

The sheet is cut flat, so the model's reference (stress-free) state is the flat crease
pattern (2α = 0): every bar at its flat length, every hinge of the sheet's own bending
(rulings, diagonals, lines within a strip) at rest flat. A crease (fold or seam) rests at
the angle it was creased at, 2α = ``rest_angle`` (default the design angle: the creases
were folded to the shape they are built for); its moment is k (θ − θ_rest). The energy is
that of :mod:`._nonlinear` with these rest angles, and the self-weight is a dead load.

**Motion.** The folding motion is the kinematics' own (:meth:`Lattice.fold_points`), the
frame of curve 1 at its first end held: the first end section stays on the ground z = 0 at
every angle (it opens there as the fold angle grows), the flat sheet stands on it in a
vertical plane, and the far end section comes down to the ground at the design angle.

**Supports** (:data:`DEPLOY_SUPPORTS`): ``feet`` carries every node of both end sections
along its kinematic path (each foot in a jig that folds with it), ``foot`` those of the
first end section alone (the far end free). Both feet cannot stay on the ground while the
structure folds (the second end section tilts and lifts off it, :meth:`Vault.lift_off`), and
near flat a sheet held at a few points is a mechanism under its own weight (measured: one
tube of the paper's vault in 4 panels, aluminium 1 mm, held at three foot points at
2α = 5°: a lowest stiffness of 0.5 N/m against 22 N of weight), so neither a pinned nor a
roller point support is offered.
The actuation is the generalized force along the motion, Q = Σ R · dx/d(2α) over the held
DOFs, N·m per radian of 2α: the moment that drives the fold angle; by virtual work
``∫ Q d(2α) = ΔU + ΔV`` (elastic and gravity energy). Q < 0 where the creases, resting at
a larger angle, fold the structure themselves and the supports hold it back.

**Solution.** At every angle the held DOFs are set to their kinematic positions and the
others found by Newton's method on the exact tangent (:func:`._nonlinear.tangent`), from
the kinematic state plus the previous state's departure from its own and that departure's
last change, extrapolated (a warm start of second order: at 1° steps on the paper's vault it
halved the tangents made, 255 to 133, and the CPU time, 126 to 74 s). A step
that does not converge is split in halves, down to 2^-:data:`HALVINGS` of the step; past
that :class:`DeployError` says at which angle and why, and keeps the states found.

**Start.** At 2α = 0 the two plies of a tube lie on each other and the seams' dihedral
angle is degenerate (0 or 2π); near flat, a vault is a flat wall standing on its feet that
the creases, resting at 90°, push to fold while the feet hold it: it buckles off the path
(measured on the paper's vault in polypropylene 1 mm: 119 mm, 6 % of the span, from the
kinematic state at 2α = 1°, and no equilibrium near it at 8°). The motion starts at
2α = ``start``, 10° by default, where the first state is found near the path (the paper's vault
from 10° at 10° steps reaches its design angle).

Measured (``tests/test_deploy.py``): a hinge lifting a panel against gravity gives
Q = k (θ − θ₀) + m g ℓ cos φ to 1e-9 relative; the energy balance holds to the step's
second order; the path distance falls as the sheet stiffens.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..kernel._arrays import FrozenArrays
from ..kernel._errors import ConvergenceError, InputError
from ..kernel._validate import Spec, check_integer
from . import _elements
from ._deploy_solve import Energy, first_state, next_state
from ._deploy_specs import DEPLOY_SUPPORTS, REST_ANGLE, START, STEP
from ._materials import Material
from ._model import CREASES, BarHingeModel
from ._structures import StructureModel

__all__ = [
    "Deployment",
    "DeployError",
    "deploy",
    "follow_motion",
    "DEPLOY_SUPPORTS",
    "STEP",
    "REST_ANGLE",
    "HALVINGS",
]

#: g, m/s² (as the loads).
GRAVITY = 9.80665
#: A step that does not converge is halved at most this many times.
HALVINGS = 6
TOLERANCE = Spec("tolerance", "real", 1e-9, "[1e-14, 1e-3]", why="rounding to rough")


@dataclass(frozen=True, eq=False)
class Deployment(FrozenArrays):
    """The equilibrium states of a deployment, one per fold angle. SI; arrays read-only.

    Attributes
    ----------
    angles : (n,) ndarray
        Fold angles 2α of the states, degrees.
    actuation : (n,) ndarray
        Q, the generalized force along the folding motion (module notes), N·m per radian of 2α.
    max_stress : (n,) ndarray
        The largest surface stress (membrane von Mises plus bending), Pa.
    distance : (n,) ndarray
        The largest distance of a node from its kinematic position at the same angle, m.
    span : float
        The distance of the feet a and c at the design angle, m.
    displacements : (n, P, 3) ndarray
        The equilibrium positions minus the flat reference positions, m.
    kinematic : (n, P, 3) ndarray
        The placed kinematic positions, m.
    iterations : (n,) ndarray of int
        Newton iterations of each state.
    energy : (n,) ndarray
        Elastic energy plus the self-weight's potential, J (up to a constant).
    supports : str

    Examples
    --------
    >>> import numpy as np
    >>> rows = np.array([[10.0, 20], [1, -3], [2e6, 1e6], [1e-3, 2e-3]])  # 2α, Q, σ, distance
    >>> d = Deployment(*rows, 2.0, *np.zeros((2, 2, 1, 3)), np.array([3, 2]), np.zeros(2))
    >>> d.relative_distance.tolist()
    [0.0005, 0.001]
    """

    angles: np.ndarray
    actuation: np.ndarray
    max_stress: np.ndarray
    distance: np.ndarray
    span: float
    displacements: np.ndarray
    kinematic: np.ndarray
    iterations: np.ndarray
    energy: np.ndarray
    supports: str = "feet"

    @property
    def relative_distance(self) -> np.ndarray:
        """:attr:`distance` over the span, shape (n,)."""
        return self.distance / self.span

    def summary(self) -> dict[str, Any]:
        """The peaks: actuation (by size) and where, stress and where, distance and where.

        Examples
        --------
        >>> import numpy as np
        >>> rows = np.array([[10.0, 20], [1, -3], [2e6, 1e6], [1e-3, 2e-3]])  # 2α, Q, σ, distance
        >>> d = Deployment(*rows, 2.0, *np.zeros((2, 2, 1, 3)), np.array([3, 2]), np.zeros(2))
        >>> s = d.summary()
        >>> s["peak_actuation_Nm"], s["peak_actuation_at_deg"], s["max_stress_MPa"]
        (-3.0, 20.0, 2.0)
        """
        out: dict[str, Any] = {"supports": self.supports, "states": len(self.angles)}
        if not len(self.angles):
            return out
        i = int(np.argmax(np.abs(self.actuation)))
        j = int(np.argmax(self.max_stress))
        k = int(np.argmax(self.distance))
        out |= {
            "start_deg": float(self.angles[0]),
            "end_deg": float(self.angles[-1]),
            "peak_actuation_Nm": float(self.actuation[i]),
            "peak_actuation_at_deg": float(self.angles[i]),
            "max_stress_MPa": float(self.max_stress[j] / 1e6),
            "max_stress_at_deg": float(self.angles[j]),
            "max_distance_mm": float(self.distance[k] * 1e3),
            "max_distance_span": float(self.distance[k] / self.span),
            "max_distance_at_deg": float(self.angles[k]),
        }
        return out


class DeployError(ConvergenceError):
    """A deployment that stopped before its end: the message says at which angle and why;
    :attr:`deployment` holds the states found.

    Examples
    --------
    >>> import numpy as np
    >>> none = Deployment(*[np.zeros(0)] * 4, 1.0, *[np.zeros((0, 1, 3))] * 2, *[np.zeros(0)] * 2)
    >>> DeployError("stopped at 2α = 40°", none).deployment.summary()
    {'supports': 'feet', 'states': 0}
    """

    def __init__(self, message: str, deployment: Deployment) -> None:
        super().__init__(message)
        self.deployment = deployment


def follow_motion(
    model: BarHingeModel,
    rest: np.ndarray,
    frames: np.ndarray,
    held: np.ndarray,
    forces: np.ndarray,
    angles: Sequence[float] | np.ndarray,
    *,
    velocities: np.ndarray | None = None,
    span: float = 1.0,
    tolerance: float = 1e-9,
    max_iterations: int = 40,
    progress: Callable[[int, int], None] | None = None,
    supports: str = "given",
) -> Deployment:
    """The equilibrium along a prescribed motion of some DOFs (module notes), from the model's
    reference state.

    Parameters
    ----------
    model : BarHingeModel
        Its nodes are the stress-free reference.
    rest : (H,) array_like
        The hinges' rest angles (:func:`._elements.dihedral_angle`), rad.
    frames : (n, P, 3) array_like
        The kinematic positions of every node at every angle, m.
    held : (P, 3) array_like of bool
        The DOFs set to their kinematic positions.
    forces : (P, 3) array_like
        Dead loads, N.
    angles : sequence of float
        The fold angles 2α of the frames, degrees, increasing or decreasing.
    velocities : (n, P, 3) array_like, optional, keyword-only
        d x / d(2α) of the frames, m/rad (default central differences of the frames).
    span : float, keyword-only
        m, for :attr:`Deployment.relative_distance`.
    tolerance : float, keyword-only
        Converged when the free residual is below ``tolerance`` times the loads' and
        reactions' scale.
    max_iterations : int, keyword-only
        Newton iterations per try of a state, in [1, 1000].
    progress : callable, optional, keyword-only
        ``progress(done, total)`` after every angle.

    Returns
    -------
    Deployment

    Raises
    ------
    DeployError
        If an angle is not reached even in 2^-HALVINGS of a step (the states found kept).

    Examples
    --------
    A panel on a hinge, lifted against gravity (tests/test_deploy.py has the closed form):

    >>> import numpy as np
    >>> hinge = BarHingeModel(
    ...     np.array([[0.0, 0, 0], [0, 1, 0], [-1, 0.5, 0], [1, 0.5, 0]]),
    ...     [[0, 1], [0, 2], [1, 2], [0, 3], [1, 3]],
    ...     np.full(5, 1e6),
    ...     [[0, 1, 2, 3]],
    ...     [2.0],
    ...     np.ones(4),
    ... )
    >>> phi = np.radians([10.0, 20.0])
    >>> frames = np.repeat(hinge.nodes[None], 2, axis=0)
    >>> frames[:, 3] = np.column_stack([np.cos(phi), [0.5, 0.5], np.sin(phi)])
    >>> weight = np.zeros((4, 3))
    >>> weight[3, 2] = -GRAVITY
    >>> speed = np.zeros_like(frames)
    >>> speed[:, 3] = np.column_stack([-np.sin(phi), [0, 0], np.cos(phi)])
    >>> d = follow_motion(
    ...     hinge, [0.0], frames, np.ones((4, 3), bool), weight, [10, 20], velocities=speed
    ... )
    >>> # Q = k φ + m g cos φ per radian of φ (the wing turns by φ = 2α here)
    >>> bool(np.allclose(d.actuation, 2.0 * phi + GRAVITY * np.cos(phi), rtol=1e-9))
    True
    """
    rest = np.asarray(rest, float)
    frames = np.asarray(frames, float)
    P = len(model.nodes)
    held = np.asarray(held, bool).reshape(-1)
    f = np.asarray(forces, float).reshape(-1)
    grid = np.asarray(angles, float)
    n = len(grid)
    if frames.shape != (n, P, 3) or held.shape != (3 * P,) or f.shape != (3 * P,):
        raise InputError(
            f"frames, held and forces must have shapes ({n}, {P}, 3), ({P}, 3), ({P}, 3); got "
            f"{frames.shape}, {np.shape(held)}, {np.shape(forces)}"
        )
    if rest.shape != (len(model.hinges),):
        raise InputError(f"rest must have one angle per hinge ({len(model.hinges)})")
    max_iterations = check_integer(max_iterations, "max_iterations", "[1, 1000]")
    energy = Energy(model, rest)
    free = np.flatnonzero(~held)
    X = model.nodes.reshape(-1)
    kin = frames.reshape(n, -1) - X  # kinematic displacements from the reference
    if velocities is not None:
        velocity = np.asarray(velocities, float).reshape(n, -1)
    elif n > 1:  # central differences in the angle, second order
        velocity = np.gradient(kin, np.radians(grid), axis=0)
    else:
        velocity = np.zeros_like(kin)
    out: dict[str, list] = {k: [] for k in ("u", "Q", "s", "d", "it", "E")}
    departure = trend = np.zeros(3 * P)

    def deployment() -> Deployment:
        m = len(out["u"])
        return Deployment(
            grid[:m].copy(),
            np.array(out["Q"]),
            np.array(out["s"]),
            np.array(out["d"]),
            float(span),
            np.array(out["u"]).reshape(m, P, 3),
            frames[:m].copy(),
            np.array(out["it"], dtype=np.int64),
            np.array(out["E"]),
            supports,
        )

    limit = 0.05 * span  # Newton's corrections are cut to this length, m
    for i in range(n):
        found, parts = None, 4 if i == 0 else 1
        while found is None:
            if i == 0:
                found = first_state(
                    energy, kin[0], free, f, parts, tolerance, max_iterations, limit
                )
            else:
                found = next_state(energy, kin, i, departure, free, f, parts, tolerance,
                               max_iterations, limit, trend)  # fmt: skip
            if found is None:
                parts *= 2
                if parts > 2**HALVINGS:
                    raise DeployError(
                        f"the deployment did not converge at 2α = {grid[i]:.6g}° "
                        f"({i} of {n} states kept): Newton's method found no equilibrium within "
                        f"{max_iterations} iterations, even on 2^-{HALVINGS} of the step "
                        "(the sheet leaves the rigid-folding path: a snap or a collapse)",
                        deployment(),
                    )
        u, its = found
        r = energy.forces(u) - f  # the supports' reactions, on the held DOFs
        r[free] = 0.0
        out["u"].append(u.reshape(P, 3))
        out["Q"].append(float(r @ velocity[i]))
        out["s"].append(energy.max_stress(u)[0])
        out["d"].append(float(np.linalg.norm((u - kin[i]).reshape(P, 3), axis=1).max()))
        out["it"].append(its)
        out["E"].append(energy.energy(u) - float(f @ u))
        if i:  # the departure's change, extrapolated over the next step (second order)
            ratio = (grid[i + 1] - grid[i]) / (grid[i] - grid[i - 1]) if i + 1 < n else 0.0
            trend = (u - kin[i] - departure) * ratio
        departure = u - kin[i]
        if progress is not None:
            progress(i + 1, n)
    return deployment()


def deploy(
    structure: Any,
    material: Material,
    thickness: float,
    *,
    crease_stiffness: float | None = None,
    rest_angle: float | None = None,
    supports: str = "feet",
    step: float = 1.0,
    start: float = 10.0,
    samples: str | Sequence[int] = "graded",
    across: int = 1,
    tolerance: float = 1e-9,
    max_iterations: int = 40,
    progress: Callable[[int, int], None] | None = None,
) -> Deployment:
    """Fold a structure from 2α = ``start`` to its design angle under its own weight
    (module notes).

    Parameters
    ----------
    structure : Structure
        A structure with feet: end sections at t = 0 and t = 1 (a vault, a tube).
    material : Material
    thickness : float
        t, m.
    crease_stiffness : float, optional, keyword-only
        k_c, N·m/rad/m (default the material's).
    rest_angle : float, optional, keyword-only
        2α at which the creases rest, degrees, in (0, 180) (default the design angle).
    supports : {"feet", "foot"}, keyword-only
    step : float, keyword-only
        Degrees of 2α between states, in [0.05, 10]; the last step lands on the design angle.
    start : float, keyword-only
        2α of the first state, degrees, in (0, 180), below the design angle (module notes).
    samples, across : keyword-only
        As :meth:`StructureModel.from_state`.
    tolerance, max_iterations : keyword-only
        As ``follow_motion``.
    progress : callable, optional, keyword-only
        ``progress(done, total)`` after every angle.

    Returns
    -------
    Deployment

    Raises
    ------
    InputError
        For an argument out of its range (one line naming it).
    DeployError
        If an angle is not reached (the states found kept).

    Examples
    --------
    >>> from curvefold.vault import Vault
    >>> from curvefold.mechanics import MATERIALS
    >>> vault = Vault.from_design(tubes=1, panels=4, samples=21)
    >>> d = deploy(vault.structure, MATERIALS["aluminium"], 1e-3, step=10.0)
    >>> d.angles.tolist()
    [10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 90.0]
    >>> # near flat the sheet sags 1 % of the span between its feet; at 90° it is on the path
    >>> bool(d.relative_distance[0] < 0.01), bool(d.relative_distance[-1] < 1e-5)
    (True, True)
    >>> deploy(vault.structure, MATERIALS["aluminium"], 1e-3, step=0.0)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: step must be in [0.05, 10] degrees (finer steps resolve
    nothing more; coarser ones lose the warm start), got 0.0
    """
    step = STEP.check(step)
    supports = DEPLOY_SUPPORTS.check(supports)
    tolerance = TOLERANCE.check(tolerance)
    design = float(structure.state().fold_angle)
    rest_at = design if rest_angle is None else REST_ANGLE.check(rest_angle)
    start = START.check(start)
    if design <= start:
        raise InputError(
            f"start must be below the design angle {design:g}°, got {start:g} (no motion to follow)"
        )
    count = int(np.floor((design - start) / step + 1e-9))
    angles = start + step * np.arange(0, count + 1)
    if design - angles[-1] > 1e-9 * design:
        angles = np.append(angles, design)
    angles[-1] = design
    sm = StructureModel.from_state(
        structure.state(0.0),
        material,
        thickness,
        crease_stiffness=crease_stiffness,
        samples=samples,
        across=across,
    )
    model = sm.model
    n = structure.state().vertices.shape[1]
    feet = _feet(sm, n)
    a, c = feet["a"], feet["c"]
    h = 1e-3  # degrees: the central difference of the velocities (error ~1e-9 relative)
    placed = _placed(sm, structure, np.concatenate([angles, angles - h, angles + h, [rest_at]]))
    m = len(angles)
    frames, lo, hi = placed[:m], placed[m : 2 * m], placed[2 * m : 3 * m]
    velocities = (hi - lo) / np.radians(2 * h)
    rest = _elements.dihedral_angle(model.nodes[model.hinges])
    crease = np.isin(np.asarray(model.hinge_kind), CREASES)
    rest[crease] = _elements.dihedral_angle(placed[-1][model.hinges])[crease]
    P = len(model.nodes)
    held = np.zeros((P, 3), bool)
    held[np.isin(sm.node_sample, (0,) if supports == "foot" else (0, n - 1))] = True
    weight = np.zeros((P, 3))
    weight[:, 2] = -GRAVITY * model.masses
    return follow_motion(
        model,
        rest,
        frames,
        held,
        weight,
        angles,
        velocities=velocities,
        span=float(np.linalg.norm(frames[-1][c] - frames[-1][a])),
        tolerance=tolerance,
        max_iterations=max_iterations,
        progress=progress,
        supports=supports,
    )


def _feet(sm: StructureModel, n: int) -> dict[str, int]:
    """Nodes a (curve 1, t = 0) and c (curve 1, t = 1): the span is their distance."""
    curve, sample = np.asarray(sm.node_curve), np.asarray(sm.node_sample)
    first = np.flatnonzero((sample == 0) & (curve >= 0))
    last = np.flatnonzero((sample == n - 1) & (curve >= 0))
    if not len(first) or not len(last):
        raise InputError("a deployment needs both end sections of the structure in its model")
    a = int(first[np.argmin(curve[first])])
    c = int(last[np.argmin(curve[last])])
    return {"a": a, "c": c}


def _placed(sm: StructureModel, structure: Any, angles: np.ndarray) -> np.ndarray:
    """The model's nodes along the kinematic motion (start frame held), (A, P, 3)."""
    X = structure.lattice.fold_points(structure.curves_uv, angles)
    ends = np.asarray(sm.node_ends)
    w = np.asarray(sm.node_weight)[None, :, None]
    curve, sample = np.asarray(sm.node_curve), np.asarray(sm.node_sample)
    pa = X[:, curve[ends[:, 0]], sample[ends[:, 0]]]
    pb = X[:, curve[ends[:, 1]], sample[ends[:, 1]]]
    return (1 - w) * pa + w * pb
