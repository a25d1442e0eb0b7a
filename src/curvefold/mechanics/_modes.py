"""The lowest vibration modes of the free (unsupported) model, its six rigid motions removed.

``K φ = λ M φ`` with the lumped mass matrix M: λ = ω² (rad²/s²) does not depend on how
finely the structure is sampled, as an eigenvalue of K alone would (its Rayleigh quotient
over ``φᵀ φ`` falls as nodes are added). K of a free structure is singular on the rigid
motions R. Holding six DOFs chosen so that they fix every rigid motion (a pivoted QR of
R's rows: a statically determinate support) gives a factorisable K_c whose solve, padded
with zeros, is a generalised inverse G of K; then with the projector ``P = I − R Rᵀ M``
(R M-orthonormal) the operator ``P G Pᵀ`` is ``(K − 0·M)⁻¹`` on the elastic modes and
zero on the rigid ones, so shift-invert ARPACK at σ = 0 returns the lowest elastic modes
and never a rigid one.

The first mode of a foldable structure is its folding motion; the ratio of the second
eigenvalue to the first is the **fold-mode gap**: how much stiffer every other motion is.
Each mode also reports the share of its energy in stretching (the bars), which tells a
soft mode (bending and creases) from a stiff one.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import scipy.linalg as la
import scipy.sparse.linalg as spl

from ..kernel._arrays import FrozenArrays
from ..kernel._errors import InputError
from ._linear import Factorized, eigsh, rigid_motions, unit_displacement
from ._model import BarHingeModel

__all__ = ["Modes", "free_modes", "supported_modes", "correlation", "span_correlation"]


@dataclass(frozen=True, eq=False)
class Modes(FrozenArrays):
    """The lowest elastic modes of a free model.

    Attributes
    ----------
    eigenvalues : (k,) ndarray
        λ = ω², ascending, rad²/s².
    shapes : (k, P, 3) ndarray
        The mode shapes, each with largest nodal displacement 1 and orthogonal to the
        rigid motions in the mass metric.
    stretching : (k,) ndarray
        Share of each mode's strain energy in the bars (stretching and shear), in [0, 1].

    Examples
    --------
    >>> import numpy as np
    >>> from curvefold.vault import Vault
    >>> tube = StructureModel.from_state(
    ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
    ...     MATERIALS["aluminium"],
    ...     1e-3,
    ... )
    >>> modes = free_modes(tube.model, 4)
    >>> (
    ...     modes.shapes.shape,
    ...     bool((np.diff(modes.eigenvalues) >= 0).all()),
    ...     round(modes.fold_mode_gap, 1),
    ... )
    ((4, 20, 3), True, 11.1)
    """

    eigenvalues: np.ndarray
    shapes: np.ndarray
    stretching: np.ndarray

    @property
    def frequencies(self) -> np.ndarray:
        """Natural frequencies ω / 2π, Hz, shape (k,)."""
        return np.sqrt(np.maximum(self.eigenvalues, 0.0)) / (2 * np.pi)

    @property
    def fold_mode_gap(self) -> float:
        """λ₂ / λ₁: how much stiffer the next mode is than the first (the folding motion)."""
        return (
            float(self.eigenvalues[1] / self.eigenvalues[0])
            if len(self.eigenvalues) > 1
            else float("nan")
        )


def free_modes(
    model: BarHingeModel,
    count: int = 6,
    *,
    motions: Mapping[str, np.ndarray] | None = None,
    tol: float = 1e-8,
) -> Modes:
    """The ``count`` lowest elastic modes of the free model (module notes).

    Parameters
    ----------
    model : BarHingeModel
        Every node must have mass.
    count : int
        How many modes, ≥ 1 (fewer than the elastic DOFs).
    motions : mapping of str to (3P,) ndarray, optional, keyword-only
        Known motions, to name a free one if the model is a mechanism.
    tol : float, keyword-only
        ARPACK's relative accuracy of the eigenvalues.

    Raises
    ------
    InputError
        For a node without mass, a count out of range, or a model that has a motion of
        zero stiffness besides the rigid ones (the message names it).

    Examples
    --------
    >>> import numpy as np
    >>> from curvefold.vault import Vault
    >>> tube = StructureModel.from_state(
    ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
    ...     MATERIALS["aluminium"],
    ...     1e-3,
    ... )
    >>> free_modes(tube.model, 2).eigenvalues.shape
    (2,)
    >>> free_modes(tube.model, 0)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: count must be an integer in [1, 52] for this model (60
    DOFs), got 0
    """
    n = model.dofs
    if not (model.masses > 0).all():
        raise InputError(
            f"the modes need every node to have mass; node {int(np.argmin(model.masses))} has none"
        )
    if (
        isinstance(count, bool)
        or not isinstance(count, (int, np.integer))
        or not 1 <= count <= n - 8
    ):
        raise InputError(
            f"count must be an integer in [1, {n - 8}] for this model ({n} DOFs), got {count!r}"
        )
    w = np.repeat(model.masses, 3)
    R = rigid_motions(model.nodes, model.masses)  # M-orthonormal, (3P, 6)
    held = la.qr(R.T, mode="r", pivoting=True)[1][:6]
    rest = np.setdiff1d(np.arange(n), held)
    K = model.stiffness
    G = Factorized.checked(
        K[rest][:, rest], model, rest, where="once its rigid motions are held", motions=motions
    )

    def project(b: np.ndarray) -> np.ndarray:  # P G Pᵀ b
        b = b - w * (R @ (R.T @ b))
        u = np.zeros(n)
        u[rest] = G.solve(b[rest])
        return u - R @ (R.T @ (w * u))

    operator = spl.LinearOperator((n, n), matvec=project, dtype=float)
    values, vectors = eigsh(
        K,
        what="the free modes",
        k=count,
        M=model.mass,
        sigma=0.0,
        OPinv=operator,
        which="LM",
        ncv=min(n - 7, max(2 * count + 8, 24)),
        tol=tol,
    )
    order = np.argsort(values)
    values, vectors = values[order], vectors[:, order]
    C, S = model.compatibility(), model.bar_stiffness_matrix()
    delta = C @ vectors
    stretch = np.einsum("bk,bk->k", delta, S @ delta)
    total = np.einsum("ik,ik->k", vectors, K @ vectors)
    shapes = np.stack([unit_displacement(v) for v in vectors.T])
    return Modes(values, shapes, np.clip(stretch / total, 0.0, 1.0))


def supported_modes(
    model: BarHingeModel,
    fixed: np.ndarray,
    factor: Factorized,
    count: int = 3,
    *,
    tol: float = 1e-8,
) -> np.ndarray:
    """The ``count`` lowest eigenvalues ω² (rad²/s²) of the model on its supports.

    ``K_ff φ = ω² M_ff φ`` on the free DOFs (the supported ones held at zero), by
    shift-invert about 0 with ``factor``, the factorisation of ``K_ff`` that
    :func:`static_response` returned. A supported structure has no rigid motion: its
    first mode is the first way it vibrates where it stands.

    Parameters
    ----------
    model : BarHingeModel
    fixed : (P, 3) ndarray of bool
        The supported DOFs.
    factor : Factorized
        ``K_ff`` factorised.
    count : int
        How many, at least 1 and fewer than the free DOFs less one.
    tol : float, keyword-only
        ARPACK's relative accuracy.

    Examples
    --------
    >>> from curvefold.mechanics import MATERIALS, Loads, StructureModel, Supports
    >>> from curvefold.mechanics import static_response
    >>> from curvefold.vault import Vault
    >>> tube = StructureModel.from_state(
    ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
    ...     MATERIALS["aluminium"],
    ...     1e-3,
    ... )
    >>> feet = Supports().fixed(tube)
    >>> result, factor = static_response(tube.model, Loads().forces(tube.model), feet)
    >>> held = supported_modes(tube.model, feet, factor, 2)
    >>> bool(held[0] > free_modes(tube.model, 1).eigenvalues[0])  # held, it is stiffer
    True
    """
    free = np.flatnonzero(~np.asarray(fixed, bool).ravel())
    n = len(free)
    if (
        isinstance(count, bool)
        or not isinstance(count, (int, np.integer))
        or not 1 <= count < n - 1
    ):
        raise InputError(
            f"count must be an integer in [1, {n - 2}] for this model ({n} free DOFs), got "
            f"{count!r}"
        )
    K = model.stiffness[free][:, free]
    M = model.mass.tocsr()[free][:, free]
    operator = spl.LinearOperator((n, n), matvec=factor.solve, dtype=float)
    values = eigsh(
        K,
        what="the supported modes",
        k=count,
        M=M,
        sigma=0.0,
        OPinv=operator,
        which="LM",
        ncv=min(n - 1, max(2 * count + 8, 24)),
        tol=tol,
        return_eigenvectors=False,
    )
    return np.sort(np.asarray(values, float))


def correlation(model: BarHingeModel, shape: np.ndarray, motion: np.ndarray) -> float:
    """The absolute cosine of the angle between a mode shape and a motion (P, 3), in the mass
    metric, rigid parts removed.

    1 when the mode is the motion (up to a rigid motion and scale).

    Examples
    --------
    >>> import numpy as np
    >>> from curvefold.vault import Vault
    >>> tube = StructureModel.from_state(
    ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
    ...     MATERIALS["aluminium"],
    ...     1e-3,
    ... )
    >>> fold = tube.fold_velocity()
    >>> (
    ...     round(correlation(tube.model, fold, 2 * fold), 12),
    ...     round(correlation(tube.model, free_modes(tube.model, 2).shapes[0], fold), 3),
    ... )
    (1.0, 0.999)
    """
    return span_correlation(model, np.asarray(shape, float)[None], motion)


def span_correlation(model: BarHingeModel, shapes: np.ndarray, motion: np.ndarray) -> float:
    """The cosine of the angle between a motion (P, 3) and the span of mode shapes (k, P, 3), in the
    mass metric, rigid parts removed.

    1 when the motion is a combination of the shapes (up to a rigid motion); for one
    shape, :func:`correlation`.

    Examples
    --------
    A motion in the span of two shapes, and one in the span of none but rigid motions:

    >>> import numpy as np
    >>> from curvefold.vault import Vault
    >>> tube = StructureModel.from_state(
    ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
    ...     MATERIALS["aluminium"],
    ...     1e-3,
    ... )
    >>> shapes = free_modes(tube.model, 2).shapes
    >>> round(span_correlation(tube.model, shapes, shapes[0] - 3 * shapes[1]), 12)
    1.0
    >>> round(
    ...     span_correlation(
    ...         tube.model,
    ...         shapes,
    ...         np.tile([0.0, 0.0, 1.0], (len(tube.model.nodes), 1)) + 1e-9 * shapes[0],
    ...     ),
    ...     6,
    ... )
    1.0
    """
    w = np.repeat(model.masses, 3)
    R = rigid_motions(model.nodes, model.masses)
    A = np.asarray(shapes, float).reshape(len(shapes), -1).T
    b = np.asarray(motion, float).ravel()
    A, b = A - R @ (R.T @ (w[:, None] * A)), b - R @ (R.T @ (w * b))
    # an orthonormal basis of the span in the mass metric
    Q, _ = np.linalg.qr(np.sqrt(w)[:, None] * A)
    wb = np.sqrt(w) * b
    return min(1.0, float(np.linalg.norm(Q.T @ wb) / np.linalg.norm(wb)))
