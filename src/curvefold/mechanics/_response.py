"""The linear static response and the linear buckling of a supported model.

Static: ``K_ff u_f = f_f`` on the free DOFs (the supported ones held at zero); the
reactions are ``K u − f`` on the supported DOFs, so that they carry exactly the applied
load (:attr:`StaticResult.equilibrium_error` measures it). Bar forces ``S C u``, hinge
moments ``k J u``, membrane stresses ``D G δ`` in every triangle's own frame.

Stresses for the utilisation: at the sheet's faces a triangle carries its membrane stress
and the bending stress ``6 m / t²`` of the moment per length ``m = M / ℓ`` of its hinges.
The surface stress of a triangle is its membrane von Mises stress plus the largest
bending stress of its hinges: an upper bound of the von Mises stress at either face
(the von Mises norm is a norm, and a bending stress across a hinge is uniaxial).
Creases count too: a crease's moment bends the sheet along it.

Buckling: the load factor λ at which ``K + λ K_G`` becomes singular on the free DOFs,
``K_G`` the geometric stiffness of the static internal forces (the membranes' stresses,
the bars' forces, the hinges' moments: :meth:`BarHingeModel.geometric_stiffness`); the smallest
positive one (ARPACK on ``−K_G φ = (1/λ) K φ`` with the static factorisation). A load
that only stiffens the structure has no positive λ: the factor is infinite. The hinge
moments' part of K_G is small beside the bar forces' in a sheet that carries its load as a
shell (it moves the paper's vault's factor by 3e-4, measured) and costs most of the
assembly (a 12 × 12 Hessian per hinge): it enters through the Rayleigh quotient of the
mode found without it, one directional second derivative per hinge, exact to second order
in it; the whole K_G is solved when that correction passes :data:`RAYLEIGH_RTOL`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import scipy.sparse.linalg as spl

from ..kernel._arrays import FrozenArrays, readonly
from ..kernel._errors import InputError
from ._elements import dihedral_hessian_action
from ._linear import Factorized, eigsh, unit_displacement
from ._model import BarHingeModel

__all__ = ["StaticResult", "Buckling", "static_response", "buckling", "RAYLEIGH_RTOL"]

#: Largest relative change of 1/λ by the hinges' part of K_G taken from the Rayleigh
#: quotient of the bars' mode (exact to second order); beyond it the whole K_G is solved.
RAYLEIGH_RTOL = 1e-3


@dataclass(frozen=True, eq=False)
class StaticResult(FrozenArrays):
    """The linear static response of a supported model to a load. SI units; arrays read-only.

    Attributes
    ----------
    load : (P, 3) ndarray
        Applied nodal forces, N.
    fixed : (P, 3) ndarray of bool
        The supported DOFs.
    displacements : (P, 3) ndarray
        u, m.
    reactions : (P, 3) ndarray
        Support reactions, N (0 where nothing is supported).
    bar_forces : (B,) ndarray
        Axial force of every bar, N, tension positive.
    hinge_moments : (H,) ndarray
        Moment of every hinge, N·m.
    membrane_stress : (T, 3) ndarray
        (σ_xx, σ_yy, τ_xy) at the centre of every membrane, in its own frame, Pa.
    von_mises : (T,) ndarray
        Von Mises stress of the membrane stress, Pa.
    bending_stress : (H,) ndarray
        ``6 |M| / (ℓ t²)`` of every hinge, Pa (0 without a sheet thickness).
    surface_stress : (T,) ndarray
        Membrane von Mises stress plus the largest bending stress of the triangle's
        hinges: an upper bound of the von Mises stress at the sheet's faces, Pa.
    force_scale : float
        ``Σ |f| + Σ |K| |u|``, N: the sizes of the forces that K u − f adds up, to which its
        rounding is proportional.

    Examples
    --------
    >>> import numpy as np
    >>> from curvefold.vault import Vault
    >>> tube = StructureModel.from_state(
    ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
    ...     MATERIALS["aluminium"],
    ...     1e-3,
    ... )
    >>> result, factor = static_response(
    ...     tube.model, Loads().forces(tube.model), Supports().fixed(tube)
    ... )
    >>> (
    ...     (result.total_reaction.round(6) + 0.0).tolist(),
    ...     result.equilibrium_error < 1e-12,
    ... )  # the feet carry the weight (+ 0.0: no -0.0)
    ([0.0, 0.0, 22.737584], True)
    """

    load: np.ndarray
    fixed: np.ndarray
    displacements: np.ndarray
    reactions: np.ndarray
    bar_forces: np.ndarray
    hinge_moments: np.ndarray
    membrane_stress: np.ndarray
    von_mises: np.ndarray
    bending_stress: np.ndarray
    surface_stress: np.ndarray
    force_scale: float

    @property
    def total_load(self) -> np.ndarray:
        """Sum of the applied forces, [x, y, z] N, shape (3,)."""
        return self.load.sum(axis=0)

    @property
    def total_reaction(self) -> np.ndarray:
        """Sum of the support reactions, [x, y, z] N, shape (3,)."""
        return self.reactions.sum(axis=0)

    @property
    def equilibrium_error(self) -> float:
        """``|Σ reactions + Σ loads|`` over :attr:`force_scale`: rounding (~1e-16) when the
        reactions carry the load."""
        return (
            float(np.linalg.norm(self.total_reaction + self.total_load) / self.force_scale)
            if self.force_scale
            else 0.0
        )

    @property
    def max_displacement(self) -> float:
        """The largest nodal displacement (its length), m."""
        return float(np.linalg.norm(self.displacements, axis=1).max(initial=0.0))

    @property
    def max_stress(self) -> float:
        """The largest surface stress, or of the bending stresses without membranes, Pa."""
        return float(
            max(self.surface_stress.max(initial=0.0), self.bending_stress.max(initial=0.0))
        )

    def scaled(self, c: float) -> StaticResult:
        """The response to the load times ``c`` > 0: every field times c (the response is linear
        in the load; the stresses are norms, positively homogeneous).

        Examples
        --------
        >>> import numpy as np
        >>> from curvefold.vault import Vault
        >>> tube = StructureModel.from_state(
        ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
        ...     MATERIALS["aluminium"],
        ...     1e-3,
        ... )
        >>> forces, feet = Loads().forces(tube.model), Supports().fixed(tube)
        >>> once, factor = static_response(tube.model, forces, feet)
        >>> again, _ = static_response(tube.model, 1.35 * forces, feet, factor=factor)
        >>> bool(np.allclose(once.scaled(1.35).surface_stress, again.surface_stress, rtol=1e-12))
        True
        """
        if not c > 0:
            raise InputError(f"a response scales by a factor > 0, got {c!r}")
        return StaticResult(
            load=self.load * c,
            fixed=self.fixed,
            displacements=self.displacements * c,
            reactions=self.reactions * c,
            bar_forces=self.bar_forces * c,
            hinge_moments=self.hinge_moments * c,
            membrane_stress=self.membrane_stress * c,
            von_mises=self.von_mises * c,
            bending_stress=self.bending_stress * c,
            surface_stress=self.surface_stress * c,
            force_scale=self.force_scale * c,
        )


@dataclass(frozen=True, eq=False)
class Buckling(FrozenArrays):
    """The linear buckling of a supported model under a load.

    Attributes
    ----------
    factor : float
        The smallest positive load factor λ at which ``K + λ K_G`` is singular (``inf`` if
        the load only stiffens the structure).
    shape : (P, 3) ndarray
        The buckling mode, largest displacement 1 (zero if there is none).

    Examples
    --------
    >>> import numpy as np
    >>> from curvefold.vault import Vault
    >>> tube = StructureModel.from_state(
    ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
    ...     MATERIALS["aluminium"],
    ...     1e-3,
    ... )
    >>> result, factor = static_response(
    ...     tube.model, Loads().forces(tube.model), Supports().fixed(tube)
    ... )
    >>> b = buckling(tube.model, result, factor)
    >>> round(b.factor, -2), round(float(np.linalg.norm(b.shape, axis=1).max()), 12)
    (16600.0, 1.0)
    """

    factor: float
    shape: np.ndarray


def static_response(
    model: BarHingeModel,
    load: np.ndarray,
    fixed: np.ndarray,
    *,
    motions: Mapping[str, np.ndarray] | None = None,
    factor: Factorized | None = None,
) -> tuple[StaticResult, Factorized]:
    """The static response to nodal forces (P, 3) with the DOFs ``fixed`` (P, 3) held, and its
    factorisation.

    ``factor``, the factorisation an earlier call returned for the same model and supports,
    is used instead of a new one (another load on the same structure).

    Raises
    ------
    InputError
        If nothing is supported, or the model is still a mechanism under the supports (the
        message names the free motion).

    Examples
    --------
    >>> import numpy as np
    >>> from curvefold.vault import Vault
    >>> tube = StructureModel.from_state(
    ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
    ...     MATERIALS["aluminium"],
    ...     1e-3,
    ... )
    >>> forces, feet = Loads().forces(tube.model), Supports().fixed(tube)
    >>> result, factor = static_response(tube.model, forces, feet)
    >>> (
    ...     result.displacements.shape,
    ...     result.max_displacement < 1e-5,
    ... )  # 1 mm of aluminium under its own weight
    ((20, 3), True)
    >>> static_response(tube.model, forces, np.zeros_like(feet))
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: no support: at least one node must be held (the structure
    would fly away)
    """
    P = len(model.nodes)
    f = np.asarray(load, float).reshape(P, 3)
    fixed = np.asarray(fixed, bool).reshape(P, 3)
    if not fixed.any():
        raise InputError(
            "no support: at least one node must be held (the structure would fly away)"
        )
    free = np.flatnonzero(~fixed.ravel())
    K = model.stiffness
    if factor is None:
        factor = Factorized.checked(
            K[free][:, free], model, free, where="under these supports", motions=motions
        )
    elif factor.shape != (len(free), len(free)):
        raise InputError(
            f"the factorisation given is of {factor.shape[0]} DOFs, these supports leave "
            f"{len(free)} free"
        )
    u = np.zeros(model.dofs)
    u[free] = factor.solve(f.ravel()[free])
    reactions = (K @ u - f.ravel()).reshape(P, 3)
    reactions[~fixed] = 0.0
    scale = float(np.abs(f).sum() + (abs(K) @ np.abs(u)).sum())
    return _result(model, f, fixed, u, reactions, scale), factor


def _result(
    model: BarHingeModel,
    f: np.ndarray,
    fixed: np.ndarray,
    u: np.ndarray,
    reactions: np.ndarray,
    scale: float,
) -> StaticResult:
    delta = model.compatibility() @ u
    forces = model.bar_stiffness_matrix() @ delta
    moments = model.hinge_stiffness * (model.hinge_matrix() @ u)
    stress = model.membrane_stress(u)
    sx, sy, txy = stress.T
    von_mises = np.sqrt(np.maximum(sx * sx - sx * sy + sy * sy + 3 * txy * txy, 0.0))
    t = model.thickness
    length = np.asarray(model.hinge_length)  # set on construction
    bending = 6 * np.abs(moments) / (length * t * t) if t > 0 else np.zeros(len(moments))
    worst = np.zeros(len(model.membranes))
    for side in (0, 1):
        faces = np.asarray(model.hinge_faces)[:, side]
        ok = faces >= 0
        np.maximum.at(worst, faces[ok], bending[ok])
    return StaticResult(
        load=f,
        fixed=fixed,
        displacements=readonly(u.reshape(-1, 3)),
        reactions=reactions,
        bar_forces=forces,
        hinge_moments=moments,
        membrane_stress=stress,
        von_mises=von_mises,
        bending_stress=bending,
        surface_stress=von_mises + worst,
        force_scale=scale,
    )


def buckling(model: BarHingeModel, result: StaticResult, factor: Factorized) -> Buckling:
    """The linear buckling factor of the static load of ``result`` and its mode (module notes).

    ``factor`` is the factorisation :func:`static_response` returned with it.

    Examples
    --------
    >>> import numpy as np
    >>> from curvefold.vault import Vault
    >>> tube = StructureModel.from_state(
    ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
    ...     MATERIALS["aluminium"],
    ...     1e-3,
    ... )
    >>> result, factor = static_response(
    ...     tube.model, Loads().forces(tube.model), Supports().fixed(tube)
    ... )
    >>> round(buckling(tube.model, result, factor).factor, -2)  # its own weight × 16600 buckles it
    16600.0
    """
    free = np.flatnonzero(~result.fixed.ravel())
    n = len(free)
    if n < 3:
        raise InputError(f"buckling needs at least 3 free DOFs, this model has {n}")
    K = factor.matrix
    u = result.displacements.ravel()
    mu, phi = _largest(model.geometric_stiffness(u, hinges=False)[free][:, free], factor)
    if mu is None:
        return Buckling(np.inf, np.zeros_like(model.nodes))
    moving = np.flatnonzero(result.hinge_moments)
    if moving.size:  # the hinges' part of K_G by the Rayleigh quotient of the mode without it
        v = np.zeros(model.dofs)
        v[free] = phi
        corners = model.hinges[moving]
        action = dihedral_hessian_action(model.nodes[corners], v.reshape(-1, 3)[corners])
        q = float(
            np.einsum(
                "h,hij,hij->", result.hinge_moments[moving], action, v.reshape(-1, 3)[corners]
            )
        )
        corrected = mu - q / float(phi @ (K @ phi))
        if abs(corrected - mu) <= RAYLEIGH_RTOL * abs(mu):
            mu = corrected
        else:
            mu, phi = _largest(model.geometric_stiffness(u)[free][:, free], factor)
            if mu is None:
                return Buckling(np.inf, np.zeros_like(model.nodes))
    shape = np.zeros(model.dofs)
    shape[free] = phi
    return Buckling(float(1.0 / mu), unit_displacement(shape))


def _largest(KG, factor: Factorized) -> tuple[float | None, np.ndarray]:
    """The largest μ of −K_G φ = μ K φ and its φ, or None when no μ is positive (ARPACK, regular
    mode).

    The eigenvalue of largest magnitude first (to 1e-6, then the Rayleigh quotient of its
    vector): if positive it is the largest. Otherwise the largest is sought on the pencil
    shifted by a thousandth of that magnitude (ARPACK's
    tolerance is relative to the eigenvalue, which would never be met at the zeros that
    every DOF without geometric stiffness puts at μ = 0), to 1e-5 of the shifted value,
    its eigenvalue the Rayleigh quotient of its vector (in error by the square of that):
    none is positive if it stays below a millionth of that magnitude (a load factor a
    million times that of the load's tension), or if ARPACK stays in the cluster of zeros.
    """
    if KG.nnz == 0 or not np.abs(KG.data).max(initial=0.0) > 0:
        return None, np.zeros(KG.shape[0])
    n = KG.shape[0]
    K, Kinv = factor.matrix, factor.operator()
    options = {"k": 1, "M": K, "Minv": Kinv, "ncv": min(n - 1, 20), "tol": 1e-6}
    mu, vec = eigsh(-KG, what="the buckling factor", which="LM", **options)
    # its Rayleigh quotient, in error by the square of ARPACK's 1e-6 (measured: 3e-8 of it)
    if mu[0] > 0:
        phi = vec[:, 0]
        return float(phi @ (-KG @ phi)) / float(phi @ (K @ phi)), phi
    shift = 1e-3 * abs(float(mu[0]))
    try:
        mu, vec = spl.eigsh(
            -KG + shift * K,
            which="LA",
            maxiter=300,
            **{**options, "tol": 1e-5, "v0": np.random.default_rng(0).standard_normal(n)},
        )
    except spl.ArpackNoConvergence:  # stuck in the cluster at the shift: nothing above it
        return None, np.zeros(n)
    phi = vec[:, 0]
    # its Rayleigh quotient: the error is the residual's square
    top = float(phi @ (-KG @ phi)) / float(phi @ (K @ phi))
    return (top, phi) if top > 1e-3 * shift else (None, phi)  # a millionth of the largest magnitude
