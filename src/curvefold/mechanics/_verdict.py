"""Will it stand: the checks of a structure under its load combinations, and the verdict.

Three checks, each a :class:`Check` (its value, limit, unit, utilisation and the
combination it was found under):

* **stability**: the linear buckling factor λ of every ULS combination
  (:mod:`._combinations`) must reach the required factor (default 10: EN 1993-1-1
  §5.2.1(3), expression 5.1, asks α_cr ≥ 10 before a first-order, linear analysis is
  enough; below it second-order effects and imperfections count, which this linear model
  does not hold). Utilisation: required / λ;
* **strength**: the largest surface stress (:attr:`StaticResult.max_stress`) of every ULS
  combination against the design strength f / γ_M (γ_M the material's,
  :attr:`Material.partial_factor`, with its source, or the user's). Utilisation: stress /
  design strength. A material without a strength has no strength check;
* **deflection**: the largest displacement under the SLS combination (every case × 1.0)
  against span / 250 (the span: the distance between the end sections' supported nodes,
  the feet of a vault or the ends of a tube; or the user's limit, m). Utilisation:
  deflection / limit.

The verdict (:class:`Verdict`): the structure stands when every utilisation is at most 1;
the governing check is the one of largest utilisation. The figures are the model's with the
elements across each ruling strip it was given (``across``): how far they are from the
structure's is answered by refining it (:func:`mesh_note` says so in every verdict).

The checks and their specs load without SciPy; :func:`assess` loads the solvers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..kernel._arrays import readonly
from ..kernel._errors import InputError
from ..kernel._validate import Spec
from ._combinations import GAMMA_G, GAMMA_Q, Combination, combinations

if TYPE_CHECKING:  # pragma: no cover
    from ._analysis import LoadResult
    from ._structures import StructureModel
    from ._supports import Supports

__all__ = [
    "Check",
    "Criteria",
    "Verdict",
    "assess",
    "span_length",
    "BUCKLING_SAFETY",
    "DEFLECTION_LIMIT",
    "GAMMA_M",
    "SPAN_RATIO",
    "mesh_note",
    "error_text",
    "CRITERIA_SPECS",
]

#: The span over the deflection limit by default (span / 250).
SPAN_RATIO = 250.0


def mesh_note(across: int, compared: int | None = None) -> str:
    """What every figure of the verdict is computed on: the model with ``across`` elements
    across each ruling strip or panel, and the one of ``compared`` its errors were estimated
    against, if any (docs: Mechanics, Convergence).

    Examples
    --------
    >>> mesh_note(1).split(";")[0]
    "the checks are the model's with one element across each ruling strip"
    >>> mesh_note(4, 2)
    "every figure is the model's with 4 elements across each ruling strip, ± its error estimated
    against 2 across (Richardson)"
    """
    if compared is not None:
        return (
            f"every figure is the model's with {across} elements across each ruling strip, ± its "
            f"error estimated against {compared} across (Richardson)"
        )
    if across == 1:
        return (
            "the checks are the model's with one element across each ruling strip; a strip "
            "cannot bend across its width there (the paper's vault: deflection 24 % low, buckling "
            "factor 29 times too high against --across 4): raise --across until they stop moving"
        )
    return (
        f"the checks are the model's with {across} elements across each ruling strip; compare "
        f"with --across {2 * across} to see how far they still move"
    )


def error_text(error: float | None) -> str:
    """`` ± x %`` for an estimated relative error, nothing for None.

    Examples
    --------
    >>> error_text(0.0123), error_text(None), error_text(2e-6), error_text(24.4)
    (' ± 1.2 %', '', ' ± 0.01 %', ' ± 2440 %')
    >>> error_text(float("inf"))
    ' ± ? (one mesh finds no buckling)'
    """
    if error is None:
        return ""
    if math.isinf(error):
        return " ± ? (one mesh finds no buckling)"
    percent = max(100 * error, 0.01)
    return f" ± {percent:.0f} %" if percent >= 10 else f" ± {percent:.2g} %"


#: The linear buckling factor each ULS combination must reach.
BUCKLING_SAFETY = Spec(
    "buckling_safety",
    "real",
    10.0,
    "[1, 1000]",
    help="the linear buckling factor each ULS combination must reach (default 10: EN 1993-1-1 "
    "§5.2.1(3), where α_cr ≥ 10 lets a linear analysis stand without second-order effects)",
    why="below 1 the structure buckles under its design load",
    label="required buckling factor",
)
#: The user's deflection limit under the SLS combination.
DEFLECTION_LIMIT = Spec(
    "deflection_limit",
    "real",
    None,
    "(0, 1000]",
    "m",
    help="the largest deflection allowed under the SLS combination (default the span / 250)",
    why="a limit of 0 no structure meets",
    label="deflection limit",
)
#: The user's partial factor on the material's strength.
GAMMA_M = Spec(
    "gamma_m",
    "real",
    None,
    "[1, 10]",
    help="partial factor γ_M on the material's strength (default the material's own, with its "
    "source: EN 1999-1-1's 1.10 for aluminium, 1.3 for board, 1.5 where no code covers it)",
    why="a factor below 1 would raise the strength above its characteristic value",
    label="material factor γ_M",
)


#: The checks of :class:`Criteria`'s fields, in its order (design-file keys and flags alike).
CRITERIA_SPECS: tuple[Spec, ...] = (GAMMA_G, GAMMA_Q, GAMMA_M, BUCKLING_SAFETY, DEFLECTION_LIMIT)


@dataclass(frozen=True)
class Criteria:
    """What the verdict asks: the partial factors, the required buckling factor and the deflection
    limit. Checked on construction (``GAMMA_G``, ``GAMMA_Q``, ``GAMMA_M``,
    ``BUCKLING_SAFETY``, ``DEFLECTION_LIMIT``).

    Attributes
    ----------
    gamma_g, gamma_q : float
        γ_G on the self-weight, γ_Q on the variable loads.
    gamma_m : float or None
        γ_M on the strength; None: the material's (:attr:`Material.partial_factor`).
    buckling_safety : float
        The linear buckling factor each ULS combination must reach, ≥ 1.
    deflection_limit : float or None
        m; None: the span / 250.

    Examples
    --------
    >>> Criteria().buckling_safety, Criteria(gamma_m=1.2).gamma_m
    (10.0, 1.2)
    >>> Criteria(deflection_limit=0.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: deflection_limit must be in (0, 1000] m (...), got 0.0
    """

    gamma_g: float = GAMMA_G.default
    gamma_q: float = GAMMA_Q.default
    gamma_m: float | None = None
    buckling_safety: float = BUCKLING_SAFETY.default
    deflection_limit: float | None = None

    def __post_init__(self) -> None:
        for spec in CRITERIA_SPECS:
            value = getattr(self, spec.name)
            if value is not None or spec.default is not None:
                object.__setattr__(self, spec.name, spec.check(value))


@dataclass(frozen=True)
class Check:
    """One check of the verdict: a value against its limit under one combination.

    Attributes
    ----------
    name : {"stability", "strength", "deflection"}
    value : float
        The buckling factor (``inf`` when the load only stiffens the structure), the largest
        stress (Pa) or deflection (m).
    limit : float
        What the value must reach (stability) or stay within (the others).
    unit : str
    combination : str
        The combination's name (:attr:`Combination.name`).
    at_least : bool
        Whether the value must reach the limit rather than stay within it.
    basis : str
        Where the limit comes from, in words.
    error : float or None
        The value's estimated relative error, from the same check on a coarser mesh
        (:func:`check_errors`); None when not estimated. The utilisation's is the same to
        first order.

    Examples
    --------
    >>> c = Check("stability", 0.61, 1.5, "", "ULS 1.35 G", at_least=True)
    >>> round(c.utilisation, 4), c.passed
    (2.459, False)
    >>> c.text()
    'stability under ULS 1.35 G (buckling factor 0.61 < 1.5 required; utilisation 2.46)'
    """

    name: str
    value: float
    limit: float
    unit: str
    combination: str
    at_least: bool = False
    basis: str = ""
    error: float | None = None

    @property
    def utilisation(self) -> float:
        """How much of the limit is used: value / limit, or limit / value for a value that must
        reach its limit; above 1 the check fails."""
        if self.at_least:
            return 0.0 if math.isinf(self.value) else self.limit / self.value
        return self.value / self.limit

    @property
    def passed(self) -> bool:
        """Whether the utilisation is at most 1."""
        return self.utilisation <= 1.0

    def text(self) -> str:
        """The check in one phrase: what, under which combination, the value against its limit.

        Examples
        --------
        >>> Check("deflection", 0.02, 0.0135, "m", "SLS G").text()
        'deflection under SLS G (deflection 20 mm > limit 13.5 mm; utilisation 1.48)'
        """
        if self.name == "stability":
            shown = (
                "buckling factor: none, the load only stiffens it"
                if math.isinf(self.value)
                else f"buckling factor {self.value:.3g} {'≥' if self.passed else '<'} "
                f"{self.limit:.3g} required"
            )
        else:
            scale, unit = (1e-6, "MPa") if self.unit == "Pa" else (1e3, "mm")
            words = "stress" if self.name == "strength" else "deflection"
            bound = "design strength" if self.name == "strength" else "limit"
            shown = (
                f"{words} {self.value * scale:.3g} {unit} {'≤' if self.passed else '>'} "
                f"{bound} {self.limit * scale:.3g} {unit}"
            )
        return (
            f"{self.name} under {self.combination} ({shown}; utilisation "
            f"{self.utilisation:.3g}{error_text(self.error)})"
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON: name, value (None for an infinite buckling factor), limit, unit, utilisation,
        combination, passed and basis.

        Examples
        --------
        >>> Check("stability", float("inf"), 10.0, "", "ULS 1.5 W", at_least=True).to_dict()
        {'name': 'stability', 'value': None, 'limit': 10.0, 'unit': '', 'utilisation': 0.0,
        'combination': 'ULS 1.5 W', 'passed': True, 'basis': '', 'error': None}
        """
        return {
            "name": self.name,
            "value": None if math.isinf(self.value) else self.value,
            "limit": self.limit,
            "unit": self.unit,
            "utilisation": self.utilisation,
            "combination": self.combination,
            "passed": self.passed,
            "basis": self.basis,
            "error": None if self.error is None or math.isinf(self.error) else self.error,
        }


@dataclass(frozen=True, eq=False)
class Verdict:
    """Whether a structure stands: its checks, the combinations they were found under, and what
    each combination puts on the supports.

    Attributes
    ----------
    checks : tuple of Check
    combinations : tuple of Combination
    totals : tuple of (3,) ndarray
        The applied load of each combination summed, [x, y, z] N.
    reactions : tuple of (3,) ndarray
        The support reactions of each combination summed, [x, y, z] N.
    notes : tuple of str

    Examples
    --------
    >>> ok = Check("deflection", 0.001, 0.01, "m", "SLS G")
    >>> bad = Check("stability", 5.0, 10.0, "", "ULS 1.35 G", at_least=True)
    >>> Verdict((ok, bad), ()).headline()
    'fails: stability under ULS 1.35 G (buckling factor 5 < 10 required; utilisation 2)'
    """

    checks: tuple[Check, ...]
    combinations: tuple[Combination, ...]
    totals: tuple[np.ndarray, ...] = ()
    reactions: tuple[np.ndarray, ...] = ()
    notes: tuple[str, ...] = ()

    @property
    def stands(self) -> bool:
        """Whether every check passed."""
        return all(c.passed for c in self.checks)

    @property
    def governing(self) -> Check:
        """The check of largest utilisation (the first of them on a tie)."""
        if not self.checks:
            raise InputError("a verdict needs at least one check")
        return max(self.checks, key=lambda c: c.utilisation)

    def headline(self) -> str:
        """``stands: …`` or ``fails: …`` and the governing check (:meth:`Check.text`).

        Examples
        --------
        >>> Verdict((Check("strength", 1e6, 2e7, "Pa", "ULS 1.35 G"),), ()).headline()
        'stands: strength under ULS 1.35 G (stress 1 MPa ≤ design strength 20 MPa; utilisation
        0.05)'
        """
        return f"{'stands' if self.stands else 'fails'}: {self.governing.text()}"

    def to_dict(self) -> dict[str, Any]:
        """JSON: ``verdict`` ("stands" or "fails"), ``verdict_text`` (:meth:`headline`),
        ``governing`` and ``checks`` (each
        :meth:`Check.to_dict`), ``combinations`` (each with its applied load and reactions,
        [x, y, z] N) and ``verdict_notes``.

        Examples
        --------
        >>> check = Check("strength", 1e6, 2e7, "Pa", "ULS 1.35 G")
        >>> d = Verdict((check,), ()).to_dict()
        >>> d["verdict"], d["governing"]["utilisation"], d["combinations"]
        ('stands', 0.05, [])
        """
        return {
            "verdict": "stands" if self.stands else "fails",
            "verdict_text": self.headline(),
            "governing": self.governing.to_dict(),
            "checks": [c.to_dict() for c in self.checks],
            "combinations": [
                c.to_dict() | {"applied_load": t.tolist(), "reactions": r.tolist()}
                for c, t, r in zip(self.combinations, self.totals, self.reactions, strict=True)
            ],
            "verdict_notes": list(self.notes),
        }


def span_length(structure: StructureModel, supports: Supports) -> float:
    """The span, m: the distance between the centroids of the supported nodes at the end sections
    t = 0 and t = 1 (the feet of a vault, the ends of a tube); the model's size when the
    supports are given nodes or one end holds none.

    Examples
    --------
    >>> import numpy as np
    >>> from curvefold.mechanics import MATERIALS, StructureModel, Supports
    >>> from curvefold.vault import Vault
    >>> state = Vault.from_design(tubes=1, panels=4, samples=21).structure.state()
    >>> tube = StructureModel.from_state(state, MATERIALS["aluminium"], 1e-3)
    >>> feet = tube.model.nodes[tube.feet]  # four at t = 0 and four at t = 1
    >>> middle = feet[4:].mean(axis=0) - feet[:4].mean(axis=0)
    >>> span_length(tube, Supports()) == float(np.linalg.norm(middle)), round(float(middle[1]), 4)
    (True, 2.0604)
    """
    if supports.nodes is not None:
        return structure.model.size
    held = structure.feet if supports.at == "feet" else structure.ends
    last = structure.state.vertices.shape[1] - 1
    sample = structure.node_sample[held]
    if not (np.any(sample == 0) and np.any(sample == last)):
        return structure.model.size
    x = structure.model.nodes[held]
    return float(np.linalg.norm(x[sample == last].mean(axis=0) - x[sample == 0].mean(axis=0)))


def assess(result: LoadResult, criteria: Criteria | None = None) -> Verdict:
    """The checks of a structure under load (module notes) and the verdict.

    Each ULS combination of the result's load cases (:func:`combinations`) is solved
    (its static response and linear buckling) on one factorisation of the stiffness; a
    combination that is the result's own load times c (self-weight alone: 1.35 G) takes
    the result's response times c and its buckling factor over c, which the linear model
    makes exact. The SLS combination is the result's own load (every case × 1.0).

    Parameters
    ----------
    result : LoadResult
        The structure, its characteristic loads and supports (:func:`analyse_load`).
    criteria : Criteria, optional
        Default :class:`Criteria()`.

    Examples
    --------
    >>> from curvefold.vault import Vault
    >>> vault = Vault.from_design(tubes=1, panels=4, samples=21)
    >>> verdict = assess(analyse_load(vault, "aluminium", 1e-3))
    >>> verdict.stands, [c.name for c in verdict.checks]
    (True, ['stability', 'strength', 'deflection'])
    """
    from ._response import buckling, static_response

    criteria = Criteria() if criteria is None else criteria
    sm, model, material = result.structure, result.structure.model, result.structure.material
    fixed = result.supports.fixed(sm)
    combos = combinations(result.loads.cases, gamma_g=criteria.gamma_g, gamma_q=criteria.gamma_q)
    gamma_m = material.partial_factor if criteria.gamma_m is None else criteria.gamma_m
    basis_m = (
        material.partial_factor_source if criteria.gamma_m is None else "γ_M given by the user"
    )
    checks: list[Check] = []
    totals, reactions = [], []
    shared = None  # the stiffness on the free DOFs, factorised once for every combination
    for combo in combos:
        if combo.limit_state == "SLS":
            static = result.static
            span = span_length(sm, result.supports)
            limit = criteria.deflection_limit or span / SPAN_RATIO
            basis = (
                "given by the user"
                if criteria.deflection_limit
                else f"span / {SPAN_RATIO:g} = {span:.4g} m / {SPAN_RATIO:g}"
            )
            checks.append(
                Check("deflection", static.max_displacement, limit, "m", combo.name, basis=basis)
            )
        else:
            forces = combo.forces(sm)
            c = _multiple(forces, result.static.load)
            if c is not None:
                static, factor_value = result.static.scaled(c), result.buckling.factor / c
            else:
                static, shared = static_response(model, forces, fixed, factor=shared)
                factor_value = buckling(model, static, shared).factor
            checks.append(
                Check(
                    "stability",
                    factor_value,
                    criteria.buckling_safety,
                    "",
                    combo.name,
                    at_least=True,
                    basis="EN 1993-1-1 §5.2.1(3): α_cr ≥ 10"
                    if criteria.buckling_safety == BUCKLING_SAFETY.default
                    else "given by the user",
                )
            )
            if material.strength is not None:
                checks.append(
                    Check(
                        "strength",
                        static.max_stress,
                        material.strength / gamma_m,
                        "Pa",
                        combo.name,
                        basis=f"f / γ_M = {material.strength * 1e-6:.4g} MPa / {gamma_m:g}",
                    )
                )
        totals.append(readonly(static.total_load))
        reactions.append(readonly(static.total_reaction))
    order = {"stability": 0, "strength": 1, "deflection": 2}
    checks.sort(key=lambda c: order[c.name])  # stable: combinations in order within a check
    notes = (mesh_note(result.structure.across),) + (
        (f"γ_M = {gamma_m:g}: {basis_m}",)
        if material.strength is not None
        else (
            "no strength given: the stresses are not measured against one (no strength check, "
            "utilisation unknown)",
        )
    )
    return Verdict(tuple(checks), combos, tuple(totals), tuple(reactions), notes)


def _multiple(forces: np.ndarray, load: np.ndarray) -> float | None:
    """c > 0 with ``forces`` = c ``load`` to rounding (1e-12 of their size), or None.

    Examples
    --------
    >>> g = np.array([[0.0, 0.0, -2.0], [0.0, 0.0, -1.0]])
    >>> _multiple(1.35 * g, g), _multiple(g + [[0.0, 0.0, -1.0], [0.0, 0.0, 0.0]], g)
    (1.35, None)
    """
    f, g = np.asarray(forces, float).ravel(), np.asarray(load, float).ravel()
    gg = float(g @ g)
    if gg == 0:
        return None
    c = float(f @ g) / gg
    if not c > 0 or np.linalg.norm(f - c * g) > 1e-12 * np.linalg.norm(f):
        return None
    return c
