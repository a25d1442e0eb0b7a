"""Collapse: the load of a structure followed from zero to its first limit point, on the
model of its verdict, with an initial imperfection in the shape of its first buckling mode.

The linear buckling factor λ_cr is where the stiffness about the state as built turns
singular; a real shell, never quite the shape drawn, deflects more and more as the load
grows and carries its largest load, the collapse load, at a limit point of its
equilibrium path, often below λ_cr (the knock-down). :func:`collapse` measures it:

* the load is the ULS combination of smallest linear buckling factor (the verdict's
  governing stability check), λ times it, on the same model, materials, supports and
  units (:func:`._verdict.assess`);
* the imperfection: the structure's stress-free shape moved by the first buckling mode of
  that combination, scaled so that its largest nodal displacement is ``imperfection`` ×
  the span (:func:`._verdict.span_length`), signed to add to the linear deflection (the
  mode's dot product with it positive). Default span / 300: EN 1993-1-1 §5.3.2(11) lets
  the shape of the elastic critical buckling mode stand for the global and local
  imperfections, and Table 5.1 gives bow imperfections e₀/L of 1/350 to 1/150 by
  buckling curve for an elastic analysis, 1/300 for curve a; span / 300 is also the
  amplitude commonly taken for the in-plane imperfection of arches (EN 1993-2 Annex D).
  The bars and hinges keep the stiffness of the shape as built (their rest lengths and
  angles are the imperfect shape's): the difference is of the order of the imperfection
  over the span, 3e-3;
* the path: :func:`._path.follow_load` (generalized displacement control, which passes a
  limit point; modified Newton, the first step :data:`FIRST` λ_cr, growing up to
  :data:`GROWTH` times), stopped one state past the first whose tangent is not positive
  definite: a limit point (the load factor falls) or a bifurcation (it still rises). The
  collapse factor is where the tangent's eigenvalue nearest zero crosses it, interpolated
  between the last stable state and the first unstable one, and never below the last stable
  state's. A path that ends otherwise says why: the load factor reached :data:`MAX_RATIO`
  λ_cr, the control displacement a quarter of the span, the steps ran out, or Newton's
  method found no equilibrium (then the states computed are kept); its factor is then the
  largest reached, a lower bound of the collapse load.

Measured (``tests/test_collapse.py``): Koiter's strut (a rigid bar pinned at its foot, its
head held sideways by a spring; ``_strut``), tilted by 1e-2, 1e-3 and 1e-4 of its length,
collapses 1.6e-4, 4.5e-5 and 3.9e-5 below its exact load, and its knock-down shrinks by 4.59
and 4.67 per decade of the tilt (Koiter's law for an unstable symmetric bifurcation:
10^(2/3) = 4.64); perfect, its path finds the bifurcation at the linear factor to 1e-3.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from ..kernel._errors import InputError
from ..kernel._validate import Spec

if TYPE_CHECKING:  # pragma: no cover
    from ._analysis import LoadResult
    from ._model import BarHingeModel
    from ._path import LoadPath
    from ._verdict import Verdict

__all__ = [
    "Collapse",
    "collapse",
    "follow_collapse",
    "judged",
    "IMPERFECTION",
    "NONLINEAR",
    "MAX_RATIO",
    "STEPS",
]

#: The imperfection's amplitude as a fraction of the span (module notes: span / 300).
IMPERFECTION = Spec(
    "imperfection",
    "real",
    1 / 300,
    "[0, 0.1]",
    help="the initial imperfection of --nonlinear, the first buckling mode's largest "
    "displacement as a fraction of the span (default 1/300: EN 1993-1-1 §5.3.2(11) and "
    "Table 5.1, curve a)",
    why="a tenth of the span is a different structure, not an imperfect one",
    label="imperfection",
)
#: Whether a design's verdict follows its governing combination to collapse (``--nonlinear``).
NONLINEAR = Spec(
    "nonlinear",
    "flag",
    False,
    help="follow the ULS combination of smallest buckling factor from zero to collapse "
    "(large displacements, an imperfection in the shape of the first buckling mode): "
    "the collapse factor beside the linear one, the verdict on the smaller",
    label="collapse analysis",
)
#: The path stops once the load factor reaches this multiple of the linear buckling factor.
MAX_RATIO = 3.0
#: The most steps of a path.
STEPS = 80
#: The path's first step, as a fraction of the linear buckling factor.
FIRST = 0.1
#: The largest step over the first: the path's displacement at collapse may be hundreds of times
#: its first step's, where an imperfection-sensitive structure bends away from its first path.
GROWTH = 1000.0
#: The control displacement that ends a path without a limit point, as a fraction of the span.
MAX_SPAN_DISPLACEMENT = 0.25


@dataclass(frozen=True, eq=False)
class Collapse:
    """The load path of a structure to collapse (module notes).

    Attributes
    ----------
    path : LoadPath
        The states of the imperfect structure, λ on the combination's load.
    linear_factor : float
        The linear buckling factor λ_cr of the combination (the perfect structure's).
    imperfection : float
        The imperfection's largest nodal displacement, m.
    span : float
        The span it is a fraction of, m.
    combination : str
        The combination followed (:attr:`Combination.name`).
    limit_reached : bool
        Whether the path passed its first limit point.
    reason : str
        Why the path ended, in words.
    shape : (P, 3) ndarray
        The imperfection: the buckling mode as added to the shape, m.
    critical : float or None
        Where the tangent's eigenvalue nearest zero crosses it between the last stable state
        and the first unstable one, λ interpolated linearly between them; None when the path
        stayed stable.

    Examples
    --------
    Koiter's strut (``_strut``: λ_cr = 100 N), tilted by a thousandth of its length,
    collapses at its exact 98.504 N (its steps resolve 98.499):

    >>> from curvefold.mechanics._collapse import _strut
    >>> c = _strut(1e-3)
    >>> round(c.factor, 3), round(c.knock_down, 4), c.limit_reached
    (98.499, 0.985, True)
    """

    path: LoadPath
    linear_factor: float
    imperfection: float
    span: float
    combination: str
    limit_reached: bool
    reason: str
    shape: np.ndarray
    critical: float | None = None

    @property
    def factor(self) -> float:
        """The collapse load factor: where the path first loses stability (a limit point or a
        bifurcation, :attr:`limit_reached`), the larger of the last stable state's λ and
        :attr:`critical`; else the path's largest λ (a lower bound of the collapse load)."""
        lam = self.path.factors
        if not self.limit_reached:
            return float(lam.max())
        first = self.first_unstable
        top = float(lam[:first].max())
        return top if self.critical is None else max(top, min(self.critical, float(lam.max())))

    @property
    def first_unstable(self) -> int:
        """The index of the first state whose tangent is not positive definite (the number of
        states when every one is stable)."""
        unstable = np.flatnonzero(~np.asarray(self.path.stable, bool))
        return int(unstable[0]) if unstable.size else len(self.path.factors)

    @property
    def knock_down(self) -> float:
        """The collapse factor over the linear buckling factor."""
        return self.factor / self.linear_factor

    @property
    def at_collapse(self) -> int:
        """The index of the state of largest λ among those before the first unstable one (the
        last state of the path if none is)."""
        first = self.first_unstable
        if first == len(self.path.factors):
            return int(np.argmax(self.path.factors))
        return int(np.argmax(self.path.factors[:first]))

    def csv(self) -> str:
        """The load–displacement curve as CSV: a header row naming the columns and their units
        (the load factor on the combination, the control DOF's displacement in mm, signed
        along its axis, and whether the state is stable), then one row per state.

        Examples
        --------
        >>> from curvefold.mechanics._collapse import _strut
        >>> _strut(1e-3).csv().splitlines()[:2]
        ['state,load_factor,control_displacement_mm_node_1_x,stable', '0,0,0,1']
        """
        node, axis = divmod(self.path.control, 3)
        rows = [
            f"state,load_factor,control_displacement_mm_node_{node}_{'xyz'[axis]},stable",
            *(
                f"{k},{lam:.10g},{1e3 * w:.10g},{int(s)}"
                for k, (lam, w, s) in enumerate(
                    zip(
                        self.path.factors,
                        self.path.control_displacement,
                        self.path.stable,
                        strict=True,
                    )
                )
            ),
        ]
        return "\n".join(rows) + "\n"

    def to_dict(self) -> dict[str, Any]:
        """JSON: ``factor``, ``linear_factor``, ``knock_down``, ``imperfection`` (m),
        ``imperfection_ratio`` (of the span), ``span`` (m), ``combination``, ``steps``,
        ``limit_reached``, ``reason``, ``control`` (node and axis) and
        ``control_displacement`` at collapse (m).

        Examples
        --------
        >>> from curvefold.mechanics._collapse import _strut
        >>> d = _strut(1e-3).to_dict()
        >>> d["imperfection"], d["control"], d["limit_reached"]
        (0.001, {'node': 1, 'axis': 'x'}, True)
        """
        node, axis = divmod(self.path.control, 3)
        return {
            "factor": self.factor,
            "linear_factor": self.linear_factor,
            "knock_down": self.knock_down,
            "imperfection": self.imperfection,
            "imperfection_ratio": self.imperfection / self.span if self.span else 0.0,
            "span": self.span,
            "combination": self.combination,
            "steps": len(self.path.factors) - 1,
            "limit_reached": self.limit_reached,
            "reason": self.reason,
            "control": {"node": node, "axis": "xyz"[axis]},
            "control_displacement": float(self.path.control_displacement[self.at_collapse]),
        }

    def text(self) -> str:
        """The result in one phrase for the terminal.

        Examples
        --------
        >>> from curvefold.mechanics._collapse import _strut
        >>> _strut(1e-3).text()[:60]
        '98.5 on the load, 0.985 × the linear factor 100 (imperfectio'
        """
        ratio = self.imperfection / self.span if self.span else 0.0
        shown = f"span / {1 / ratio:.0f}" if ratio else "none"
        return (
            f"{self.factor:.4g} on {self.combination}, {self.knock_down:.3g} × the linear "
            f"factor {self.linear_factor:.4g} (imperfection {1e3 * self.imperfection:.3g} mm = "
            f"{shown}; {len(self.path.factors) - 1} steps; {self.reason})"
        )


def governing_combination(result: LoadResult, verdict: Verdict) -> tuple[str, np.ndarray]:
    """The ULS combination of smallest linear buckling factor and its nodal forces (P, 3), N."""
    stability = [c for c in verdict.checks if c.name == "stability"]
    if not stability:
        raise InputError("collapse needs a ULS combination, and the loads make none")
    check = min(stability, key=lambda c: c.value)
    combo = next(c for c in verdict.combinations if c.name == check.combination)
    return combo.name, combo.forces(result.structure)


def collapse(
    result: LoadResult,
    verdict: Verdict,
    *,
    imperfection: float = IMPERFECTION.default,
    steps: int = STEPS,
    stop: Callable[[LoadPath], None] | None = None,
) -> Collapse:
    """The structure of ``result`` followed to collapse under the governing ULS combination of
    ``verdict`` (module notes).

    Parameters
    ----------
    result : LoadResult
    verdict : Verdict
        Its verdict (:func:`assess`): the combination of smallest linear buckling factor is
        followed.
    imperfection : float, keyword-only
        The imperfection's amplitude as a fraction of the span, in :data:`IMPERFECTION`'s range.
    steps : int, keyword-only
        The most steps of the path.
    stop : callable, keyword-only
        Called with the path after every state (a progress bar).

    Returns
    -------
    Collapse
        A path that does not converge is not an error: its states are kept and the reason
        says where it stopped.

    Raises
    ------
    InputError
        For an imperfection out of range, or a load that cannot buckle the structure.

    Examples
    --------
    >>> from curvefold.vault import Vault
    >>> from curvefold.mechanics import analyse_load, assess
    >>> result = analyse_load(Vault.from_design(tubes=1, panels=4, samples=21), "aluminium", 1e-3)
    >>> c = collapse(result, assess(result), imperfection=0.001)
    >>> c.limit_reached, bool(0.2 < c.knock_down < 1.0)
    (True, True)
    """
    from ._response import buckling, static_response
    from ._verdict import _multiple, span_length

    IMPERFECTION.check(imperfection)  # before any work
    sm, model = result.structure, result.structure.model
    name, forces = governing_combination(result, verdict)
    fixed = result.supports.fixed(sm)
    c = _multiple(forces, result.static.load)
    if c is not None:
        linear, mode, static = result.buckling.factor / c, result.buckling.shape, result.static
    else:
        static, factor = static_response(model, forces, fixed)
        buckled = buckling(model, static, factor)
        linear, mode = buckled.factor, buckled.shape
    if not math.isfinite(linear):
        raise InputError(f"collapse: {name} only stiffens the structure: it has no buckling")
    return follow_collapse(
        model,
        forces,
        fixed,
        linear_factor=linear,
        mode=mode,
        span=span_length(sm, result.supports),
        imperfection=imperfection,
        deflection=static.displacements,
        combination=name,
        steps=steps,
        stop=stop,
    )


def follow_collapse(
    model: BarHingeModel,
    forces: np.ndarray,
    fixed: np.ndarray,
    *,
    linear_factor: float,
    mode: np.ndarray,
    span: float,
    imperfection: float = IMPERFECTION.default,
    deflection: np.ndarray | None = None,
    combination: str = "the load",
    steps: int = STEPS,
    first: float = FIRST,
    stop: Callable[[LoadPath], None] | None = None,
) -> Collapse:
    """Any model followed to collapse under λ ``forces`` (P, 3) on ``fixed`` (P, 3), imperfect
    by ``mode`` (P, 3) scaled to ``imperfection`` × ``span`` (m) and signed to add to
    ``deflection`` (P, 3) if given; ``linear_factor`` λ_cr sets the first step (``first``
    λ_cr) and the largest load factor (:data:`MAX_RATIO` λ_cr). :func:`collapse` on a
    :class:`BarHingeModel` of the user's."""
    from ._path import PathError, follow_load

    imperfection = float(IMPERFECTION.check(imperfection))
    mode = np.asarray(mode, float).reshape(-1, 3)
    if deflection is not None and float(np.sum(mode * deflection)) < 0:
        mode = -mode  # the imperfection adds to the deflection
    shape = imperfection * span * mode / max(float(np.linalg.norm(mode, axis=1).max()), 1e-300)
    imperfect = replace(model, nodes=model.nodes + shape)

    def ending(path: LoadPath) -> bool:
        if stop is not None:
            stop(path)
        # the last state's stability is known at the next step: one state past the first loss
        return path.limit is not None or not np.all(path.stable[:-1])

    reason = ""
    try:
        path = follow_load(
            imperfect,
            forces,
            fixed,
            steps=steps,
            max_factor=MAX_RATIO * linear_factor,
            first=first * linear_factor,
            max_displacement=MAX_SPAN_DISPLACEMENT * span,
            stop=ending,
            growth=GROWTH,
            modified=True,
        )
    except PathError as error:
        path, reason = error.path, str(error)
    unstable = np.flatnonzero(~np.asarray(path.stable, bool))
    lost = bool(unstable.size and unstable[0] > 0)
    critical = None
    if lost:
        j = int(unstable[0])
        lam = path.factors
        before = _nearest_eigenvalue(imperfect, path, fixed, j - 1)
        after = _nearest_eigenvalue(imperfect, path, fixed, j, shift=abs(before))
        t = before / (before - after) if before > 0 > after else 1.0
        critical = float(lam[j - 1] + t * (lam[j] - lam[j - 1]))
        kind = "a limit point" if path.limit is not None else "a bifurcation"
        reason = (
            f"{kind}: the tangent loses positive definiteness between load factors "
            f"{lam[j - 1]:.6g} and {lam[j]:.6g}"
        )
    elif not reason:
        reason = _reason(path, linear_factor, span, steps)
    return Collapse(
        path,
        float(linear_factor),
        float(imperfection * span),
        float(span),
        combination,
        lost,
        reason,
        shape,
        critical,
    )


def _nearest_eigenvalue(
    model: BarHingeModel, path: LoadPath, fixed: np.ndarray, k: int, shift: float = 0.0
) -> float:
    """The eigenvalue of the tangent on the free DOFs at state k nearest ``-shift`` (≤ 0), N/m:
    shift-inverted on a Cholesky factor of K + shift I, the shift doubled until it is positive
    definite (from the state's own smallest eigenvalue's size when 0 is not)."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spl

    from ._linear import Factorized
    from ._nonlinear import tangent

    free = np.flatnonzero(~np.asarray(fixed, bool).reshape(-1))
    K = tangent(model, path.displacements[k].reshape(-1))[free][:, free]
    eye = sp.identity(len(free), format="csr")
    shift = max(shift, 0.0)
    for _ in range(60):
        try:
            factor = Factorized(K + shift * eye)
            if factor.definite:
                break
        except InputError:
            pass
        shift = 2 * shift if shift > 0 else 1e-9 * abs(K.diagonal()).max()
    else:  # pragma: no cover - a shift of 2^60 its diagonal's 1e-9 is definite
        raise InputError("the tangent has no definite shift")
    op = spl.LinearOperator(K.shape, matvec=factor.solve, dtype=float)
    start = np.random.default_rng(0).standard_normal(len(free))  # deterministic
    mu = spl.eigsh(K, k=1, sigma=-shift, which="LM", OPinv=op, v0=start)[0][0]
    return float(mu)


def _reason(path: LoadPath, linear: float, span: float, steps: int) -> str:
    """Why a path that converged and stayed stable ended."""
    if path.factors[-1] >= MAX_RATIO * linear:
        return f"the load factor reached {MAX_RATIO:g} × the linear factor without a limit point"
    if abs(path.control_displacement[-1]) >= MAX_SPAN_DISPLACEMENT * span:
        return (
            f"the control displacement reached span / {1 / MAX_SPAN_DISPLACEMENT:g} without a "
            "limit point"
        )
    return f"the path took its {steps} steps without a limit point"


def judged(verdict: Verdict, collapsed: Collapse) -> Verdict:
    """The verdict with the stability check of the followed combination on the smaller of its
    linear and collapse factors (the collapse factor's error is not estimated: none is shown)."""
    checks = []
    for check in verdict.checks:
        if (
            check.name == "stability"
            and check.combination == collapsed.combination
            and collapsed.factor < check.value
        ):
            ratio = collapsed.imperfection / collapsed.span if collapsed.span else 0.0
            check = replace(
                check,
                value=collapsed.factor,
                error=None,
                basis=f"{check.basis}; the collapse factor of the nonlinear path (imperfection "
                f"span / {1 / ratio:.0f}), {collapsed.knock_down:.3g} × the linear factor"
                if ratio
                else f"{check.basis}; the collapse factor of the nonlinear path, "
                f"{collapsed.knock_down:.3g} × the linear factor",
            )
        checks.append(check)
    return replace(verdict, checks=tuple(checks))


def _strut(imperfection: float) -> Collapse:
    """Koiter's strut, the examples' model: a rigid bar 1 m long pinned at its foot, its head held
    sideways by a spring of 100 N/m that stays horizontal (a bar 10 km long), pressed down; it
    buckles at λ_cr = 100 N and its load falls past it (``tests/test_collapse.py``)."""
    from ._model import BarHingeModel

    nodes = np.array([[0.0, 0, 0], [0, 0, 1], [1e4, 0, 1]])
    model = BarHingeModel(
        nodes,
        np.array([[0, 1], [1, 2]]),
        np.array([1e9, 100.0]),
        np.zeros((0, 4), int),
        np.zeros(0),
        np.ones(3),
    )
    fixed = np.ones((3, 3), bool)
    fixed[1, [0, 2]] = False
    forces, mode = np.zeros((3, 3)), np.zeros((3, 3))
    forces[1, 2], mode[1, 0] = -1.0, 1.0
    return follow_collapse(
        model, forces, fixed, linear_factor=100.0, mode=mode, span=1.0, imperfection=imperfection
    )
