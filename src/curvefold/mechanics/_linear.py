"""Sparse factorisation, rigid motions, and mechanisms named rather than solved into nonsense.

Every solve of the model goes through :class:`Factorized`, a Cholesky factorisation (the
matrices are symmetric positive definite once the model is supported): banded (LAPACK)
when the nodes can be ordered in a narrow band, as a structure's are sample by sample,
else SuperLU with a symmetric minimum-degree ordering and diagonal pivots. A matrix that is
singular, or so nearly that a pivot falls below :data:`PIVOT_RTOL` of the largest
diagonal, is examined: inverse iteration finds the motion that costs (nearly) nothing,
and if it deforms no bar and no hinge to first order (:data:`MECHANISM_RTOL`) the model is
a mechanism there and :class:`~curvefold.kernel.InputError` says which motion is
free (a rigid motion by its axes, the folding motion, or another one) instead of
returning a solution of a singular system.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from scipy.sparse.csgraph import reverse_cuthill_mckee

from ..kernel._errors import ConvergenceError, InputError
from ._model import BarHingeModel

__all__ = [
    "Factorized",
    "eigsh",
    "unit",
    "rigid_motions",
    "PIVOT_RTOL",
    "MECHANISM_RTOL",
    "MAX_BAND",
    "describe_motion",
    "kinematic_residual",
]

#: A pivot below this fraction of the largest diagonal entry makes the factorisation suspect.
PIVOT_RTOL = 1e-10
#: A motion whose bars stretch and hinges turn by less than this (relative to the motion,
#: hinge angles times the model's size) is a mechanism: rounding makes ~1e-13 of a true one.
MECHANISM_RTOL = 1e-7
#: Widest band factorised as a band (its memory is 8 (band + 1) bytes per DOF, its work
#: about band² per DOF); wider matrices (large cellular blocks) go to SuperLU.
MAX_BAND = 600


def eigsh(A, *, what: str, **options) -> tuple[np.ndarray, np.ndarray]:
    """:func:`scipy.sparse.linalg.eigsh` from a fixed start vector, its failure to converge one
    line.

    ``what`` names the eigenproblem for the message; the start vector is seeded, so that a
    run gives the same result every time.

    Raises
    ------
    ConvergenceError
        If ARPACK does not converge, or fails (its internal errors, as for a matrix with
        entries that are not finite: stiffnesses too far apart to compute with).
    """
    options.setdefault("v0", np.random.default_rng(0).standard_normal(A.shape[0]))
    try:
        return spl.eigsh(A, **options)
    except spl.ArpackNoConvergence as error:
        raise ConvergenceError(
            f"the eigenvalue solver did not converge for {what} ({error}); a "
            "report of the design helps"
        ) from None
    except spl.ArpackError as error:
        data = getattr(A, "data", None)
        finite = data is None or bool(np.isfinite(data).all())
        reason = (
            "the model's stiffnesses are too far apart for it"
            if finite
            else "the model's stiffness holds numbers that are not finite"
        )
        raise ConvergenceError(
            f"the eigenvalue solver failed for {what}: {reason} (material, thickness or "
            "crease values near the ends of their ranges); bring them closer to a real "
            f"sheet's ({' '.join(str(error).split()[:3]).rstrip(':')})"
        ) from None


def unit(v: np.ndarray) -> np.ndarray:
    """v scaled to largest |component| 1, that component positive (zero stays zero).

    Examples
    --------
    >>> unit(np.array([0.5, -2.0])).tolist(), unit(np.zeros(2)).tolist()
    ([-0.25, 1.0], [0.0, 0.0])
    """
    i = int(np.argmax(np.abs(v)))
    return v / v[i] if v[i] != 0 else v


def unit_displacement(v: np.ndarray) -> np.ndarray:
    """Nodal displacements (3P,) as (P, 3) scaled to largest nodal displacement 1, their largest
    |component| positive (zero stays zero).

    Examples
    --------
    >>> (
    ...     unit_displacement(np.array([0.0, 3.0, -4.0, 1.0, 2.0, 2.0])).tolist(),
    ...     unit_displacement(np.zeros(3)).tolist(),
    ... )
    ([[-0.0, -0.6, 0.8], [-0.2, -0.4, -0.4]], [[0.0, 0.0, 0.0]])
    """
    u = unit(v).reshape(-1, 3)
    top = np.linalg.norm(u, axis=1).max()
    return u / top if top > 0 else u


def _rigid_basis(nodes: np.ndarray) -> np.ndarray:
    """Translations along x, y, z, then rotations about x, y, z through the centroid, of nodes
    (P, 3), shape (3P, 6)."""
    c = nodes - nodes.mean(axis=0)
    return np.stack(
        [np.tile(e, len(c)) for e in np.eye(3)] + [np.cross(e, c).ravel() for e in np.eye(3)],
        axis=1,
    )


def rigid_motions(nodes: np.ndarray, masses: np.ndarray | None = None) -> np.ndarray:
    """The six rigid motions of nodes (P, 3), orthonormal in the mass metric, shape (3P, 6).

    Translations along x, y, z, then rotations about x, y, z through the centroid; with
    ``masses`` (P,) they are made M-orthonormal (Gram–Schmidt in that order), else
    orthonormal.
    """
    R = _rigid_basis(np.asarray(nodes, float))
    w = np.ones(R.shape[0]) if masses is None else np.repeat(np.asarray(masses, float), 3)
    L = np.linalg.cholesky(R.T @ (w[:, None] * R))
    return np.linalg.solve(L, R.T).T  # R L⁻ᵀ: orthonormal in the w metric, same span in order


def kinematic_residual(model: BarHingeModel, u: np.ndarray) -> float:
    """How much a motion u (3P,) deforms the model to first order, relative to the motion.

    ``max(|C u|, |J u| · size) / max|u|``: 0 for a mechanism, O(1) for a deformation.
    """
    scale = np.abs(u).max()
    if scale == 0:
        return 0.0
    stretch = np.abs(model.compatibility() @ u).max(initial=0.0)
    turn = np.abs(model.hinge_matrix() @ u).max(initial=0.0) * model.size
    return float(max(stretch, turn) / scale)


def describe_motion(
    model: BarHingeModel, u: np.ndarray, motions: Mapping[str, np.ndarray] | None = None
) -> str:
    """A motion u (3P,) in words: a known motion by name, a rigid motion by its axis, or where it is
    largest.

    A rigid part with rotation ω and velocity v at the centroid c is a rotation about the
    axis along ω through ``c + ω × v / |ω|²`` (its screw axis), or a translation if ω is
    negligible.
    """
    x = model.nodes
    c = x.mean(axis=0)
    R = _rigid_basis(x)
    known = {name: np.asarray(v, float).ravel() for name, v in (motions or {}).items()}
    basis = np.concatenate([R] + [v[:, None] for v in known.values()], axis=1)
    coef, *_ = np.linalg.lstsq(basis, u, rcond=None)
    scale = np.linalg.norm(u)
    if np.linalg.norm(basis @ coef - u) > 1e-3 * scale:
        node = int(np.argmax(np.linalg.norm(u.reshape(-1, 3), axis=1)))
        return f"a motion of its own, largest at node {node} (x = {_point(x[node])} m)"
    parts = [
        name
        for (name, v), a in zip(known.items(), coef[6:])
        if np.linalg.norm(a * v) > 0.05 * scale
    ]
    v, w = coef[:3], coef[3:6]
    if np.linalg.norm(R @ coef[:6]) > 0.05 * scale:
        if np.linalg.norm(w) * model.size < 1e-3 * np.linalg.norm(v):
            parts.append(f"a rigid motion (translation along {_point(v / np.linalg.norm(v))})")
        else:
            axis = w / np.linalg.norm(w)
            parts.append(
                f"a rigid motion (rotation about the axis along {_point(axis)} through "
                f"{_point(c + np.cross(w, v) / (w @ w))} m)"
            )
    return " with ".join(parts) or "a motion too small to name"


def _point(p: np.ndarray) -> str:
    """A point or direction for a message: three rounded numbers, no negative zeros."""
    return "[" + ", ".join(f"{v:.4g}" for v in np.round(np.asarray(p, float), 6) + 0.0) + "]"


class Factorized:
    """A symmetric positive definite sparse matrix, factorised once, with its solve.

    A banded Cholesky (LAPACK) in the ordering of smaller bandwidth, the matrix's own or
    reverse Cuthill–McKee, when the band is at most :data:`MAX_BAND` wide (a structure's
    nodes numbered sample by sample make a band as wide as two samples); SuperLU with a
    symmetric minimum-degree ordering otherwise. Build it with :meth:`checked` for a
    stiffness matrix (a mechanism is named), or directly for any definite matrix.

    Parameters
    ----------
    matrix : (N, N) sparse matrix
        Symmetric positive definite.

    Raises
    ------
    InputError
        If the matrix is not positive definite.
    """

    def __init__(self, matrix: sp.spmatrix) -> None:
        if self._setup(matrix) is None:
            raise InputError("the matrix to factorise is not positive definite")

    def _setup(self, matrix: sp.spmatrix) -> np.ndarray | None:
        A = sp.csr_matrix(matrix)
        self.matrix, self.shape = A, A.shape
        self._order = _band_order(A)
        self.pivots = self._factor(A, 0.0)
        return self.pivots

    @classmethod
    def checked(
        cls,
        matrix: sp.spmatrix,
        model: BarHingeModel,
        dofs: np.ndarray,
        *,
        where: str,
        motions: Mapping[str, np.ndarray] | None = None,
    ) -> Factorized:
        """The factorisation of a model's stiffness on some DOFs, refused if the model is a
        mechanism there.

        Parameters
        ----------
        matrix : (N, N) sparse matrix
            The stiffness on the DOFs ``dofs``.
        model : BarHingeModel
        dofs : (N,) ndarray of int
            The model DOFs of the matrix's rows.
        where : str
            Where the model is a mechanism, for the message ("under these supports").
        motions : mapping of str to (3P,) ndarray, optional
            Known motions to name a free motion by (the folding motion).

        Raises
        ------
        InputError
            If the matrix is singular because the model is a mechanism there: the message
            names the free motion (module notes).
        """
        self = cls.__new__(cls)
        self._setup(matrix)
        A = self.matrix
        scale = float(A.diagonal().max(initial=0.0))
        if self.pivots is None or not self.pivots.min(initial=np.inf) > PIVOT_RTOL * scale:
            # not positive definite: shift by a rounding-sized amount to find the null motion
            if self.pivots is None:
                self._factor(A, 1e-12 * max(scale, 1e-300))
            x = np.random.default_rng(0).standard_normal(A.shape[0])
            for _ in range(3):
                x = self.solve(x)
                x /= np.abs(x).max()
            u = np.zeros(model.dofs)
            u[np.asarray(dofs)] = x
            if kinematic_residual(model, u) < MECHANISM_RTOL:
                raise InputError(
                    f"the structure is still a mechanism {where}: "
                    f"{describe_motion(model, u, motions)} is free (it stretches no bar and "
                    "turns no hinge); support or connect it so that no motion is free"
                )
        return self

    def _factor(self, A: sp.csr_matrix, shift: float) -> np.ndarray | None:
        """Factorise A + shift·I; the pivots (the factor's diagonal, squared for Cholesky), or
        None if not definite."""
        if shift:
            A = A + shift * sp.identity(A.shape[0], format="csr")
        if self._order is not None:
            order, band = self._order
            B = A[order][:, order].tocoo()
            low = B.row >= B.col
            ab = np.zeros((band + 1, B.shape[0]))
            ab[B.row[low] - B.col[low], B.col[low]] = B.data[low]
            try:
                self._banded = la.cholesky_banded(ab, lower=True, check_finite=False)
            except la.LinAlgError:
                return None
            return self._banded[0] ** 2
        try:
            self._lu = spl.splu(
                A.tocsc(),
                permc_spec="MMD_AT_PLUS_A",
                diag_pivot_thresh=0.0,
                options={"SymmetricMode": True},
            )
        except RuntimeError:  # "Factor is exactly singular"
            return None
        # diagonal pivots only: U's diagonal is D of A = L D Lᵀ, its signs A's inertia; U is
        # copied out of SuperLU at each access (a second of the vault's collapse): once
        pivots = self._lu.U.diagonal()
        self._definite = bool((pivots > 0).all())
        return np.abs(pivots)

    @property
    def definite(self) -> bool:
        """Whether the matrix is positive definite: its banded Cholesky factor exists, or every
        pivot of its symmetric factor L D Lᵀ (SuperLU with diagonal pivots) is positive
        (Sylvester's law of inertia).

        Examples
        --------
        A random sparse matrix: no ordering makes its band narrower than MAX_BAND (SuperLU);
        diagonally dominant, then with one negative diagonal entry:

        >>> R = sp.random(2000, 2000, density=0.003, random_state=np.random.default_rng(0))
        >>> A = (R + R.T + 20 * sp.identity(2000)).tolil()
        >>> Factorized(A.tocsr()).definite
        True
        >>> A[5, 5] = -1.0
        >>> Factorized(A.tocsr()).definite
        False
        """
        return self._order is not None or self._definite

    def solve(self, b: np.ndarray) -> np.ndarray:
        """x with A x = b, for b (N,) or (N, k)."""
        b = np.asarray(b, float)
        if self._order is None:
            return self._lu.solve(b)
        order = self._order[0]
        x = np.empty_like(b)
        x[order] = la.cho_solve_banded((self._banded, True), b[order], check_finite=False)
        return x

    def operator(self) -> spl.LinearOperator:
        """The inverse as a :class:`scipy.sparse.linalg.LinearOperator`."""
        return spl.LinearOperator(self.shape, matvec=self.solve, dtype=float)


def _bandwidth(A: sp.coo_matrix) -> int:
    return int(np.abs(A.row - A.col).max(initial=0))


def _band_order(A: sp.csr_matrix) -> tuple[np.ndarray, int] | None:
    """The ordering of smaller bandwidth (as numbered, or reverse Cuthill–McKee) and the band, or
    None past MAX_BAND."""
    natural = np.arange(A.shape[0])
    best = (natural, _bandwidth(A.tocoo()))
    if best[1] > MAX_BAND // 2:
        rcm = reverse_cuthill_mckee(A, symmetric_mode=True)
        band = _bandwidth(A[rcm][:, rcm].tocoo())
        if band < best[1]:
            best = (rcm, band)
    return best if best[1] <= MAX_BAND else None
