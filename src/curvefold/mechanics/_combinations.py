"""Load combinations with partial factors: what the verdict checks a structure under.

EN 1990 §6.4.3.2, expression (6.10), is the reference for the ultimate limit states (ULS):

    Σ γ_G G  +  γ_Q Q_1  +  Σ_{i>1} γ_Q ψ0,i Q_i

the permanent load (the self-weight, :attr:`LoadCase.permanent`) times γ_G = 1.35, the
leading variable action Q_1 times γ_Q = 1.5 and every accompanying one times γ_Q ψ0 (ψ0
of its case, :attr:`LoadCase.psi0`: EN 1990 Table A1.1, 0.5 for snow, 0.6 for wind, 0.7
for imposed point loads). γ_G and γ_Q are EN 1990 Table A1.2(B)'s recommended values; the
user sets others. The permanent load is taken unfavourable throughout (γ_G,inf = 1.0 is not
used: the self-weight of a thin sheet stabilises none of these structures), and so is every
variable case: one that relieves another (a wind suction lifting a snow load) is not
dropped from a combination as EN 1990 would (γ_Q = 0 where favourable); check the
combination without it by leaving it out. Each variable case leads in turn, so there are
as many ULS combinations as variable cases (one, the permanent load alone, when there is
none).

The serviceability limit state (SLS) takes every case with factor 1.0: one combination.

A :class:`Combination` is a value made of load cases and their factors; its forces are the
cases' forces times their factors, summed. This module needs no SciPy.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from ..kernel._errors import InputError
from ..kernel._validate import Spec, describe
from ._loadcase import LoadCase, Target, _model

__all__ = ["Combination", "combinations", "GAMMA_G", "GAMMA_Q", "LIMIT_STATES"]

#: The limit states a combination is made for.
LIMIT_STATES = ("ULS", "SLS")

_FACTOR_WHY = "a factor below 1 would make the load favourable, which no check here takes"

#: The partial factor γ_G on the permanent load (the self-weight).
GAMMA_G = Spec(
    "gamma_g",
    "real",
    1.35,
    "[1, 10]",
    help="partial factor γ_G on the self-weight in the ULS combinations (default 1.35: EN 1990 "
    "Table A1.2(B), expression 6.10)",
    why=_FACTOR_WHY,
    label="partial factor γ_G",
)
#: The partial factor γ_Q on the variable loads.
GAMMA_Q = Spec(
    "gamma_q",
    "real",
    1.5,
    "[1, 10]",
    help="partial factor γ_Q on the variable loads (snow, wind, point loads) in the ULS "
    "combinations; accompanying ones also × ψ0 (default 1.5: EN 1990 Table A1.2(B))",
    why=_FACTOR_WHY,
    label="partial factor γ_Q",
)


@dataclass(frozen=True)
class Combination:
    """Load cases with their factors, for one limit state. Checked on construction.

    Attributes
    ----------
    cases : tuple of LoadCase
    factors : tuple of float
        One factor per case, each finite and positive.
    limit_state : {"ULS", "SLS"}

    Examples
    --------
    >>> from curvefold.mechanics import SelfWeight, Snow
    >>> uls = Combination((SelfWeight(), Snow(500.0)), (1.35, 1.5))
    >>> uls.describe(), uls.name
    ('1.35 G + 1.5 S', 'ULS 1.35 G + 1.5 S')
    >>> Combination((SelfWeight(),), (0.0,))
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: a combination's factors must be finite and > 0, one per
    case, got (0.0,) for 1 case
    """

    cases: tuple[LoadCase, ...]
    factors: tuple[float, ...]
    limit_state: Literal["ULS", "SLS"] = "ULS"

    def __post_init__(self) -> None:
        cases, factors = tuple(self.cases), tuple(float(f) for f in self.factors)
        if not cases or not all(isinstance(c, LoadCase) for c in cases):
            raise InputError(
                f"a combination needs load cases (Snow(500.0), …), got {describe(self.cases)}"
            )
        if len(factors) != len(cases) or not all(np.isfinite(f) and f > 0 for f in factors):
            raise InputError(
                "a combination's factors must be finite and > 0, one per case, got "
                f"{factors} for {len(cases)} case{'s' * (len(cases) != 1)}"
            )
        Spec("limit_state", "choice", choices=LIMIT_STATES).check(self.limit_state)
        object.__setattr__(self, "cases", cases)
        object.__setattr__(self, "factors", factors)

    def forces(self, model: Target) -> np.ndarray:
        """The nodal forces of the cases times their factors, summed, N, shape (P, 3).

        Examples
        --------
        >>> import numpy as np
        >>> from curvefold.mechanics import SelfWeight
        >>> from curvefold.vault import Vault
        >>> state = Vault.from_design(tubes=1, panels=4, samples=21).structure.state()
        >>> tube = StructureModel.from_state(state, MATERIALS["aluminium"], 1e-3)
        >>> uls = Combination((SelfWeight(),), (1.35,))
        >>> bool(np.allclose(uls.forces(tube), 1.35 * SelfWeight().forces(tube), rtol=0, atol=0))
        True
        """
        total = np.zeros((len(_model(model).nodes), 3))
        for case, factor in zip(self.cases, self.factors, strict=True):
            total += factor * case.forces(model)
        return total

    def describe(self) -> str:
        """The combination in symbols: ``1.35 G + 1.5 S + 0.9 W`` (a factor 1 is not written).

        Examples
        --------
        >>> from curvefold.mechanics import SelfWeight, Wind
        >>> Combination((SelfWeight(), Wind(600.0)), (1.0, 1.0), "SLS").describe()
        'G + W'
        """
        return " + ".join(
            case.symbol if f == 1.0 else f"{f:.4g} {case.symbol}"
            for case, f in zip(self.cases, self.factors, strict=True)
        )

    @property
    def name(self) -> str:
        """The limit state and the combination: ``ULS 1.35 G + 1.5 S``."""
        return f"{self.limit_state} {self.describe()}"

    def to_dict(self) -> dict[str, Any]:
        """The combination as JSON: its name, limit state, and each case with its factor.

        Examples
        --------
        >>> from curvefold.mechanics import PointLoad
        >>> Combination((PointLoad(10.0),), (1.5,)).to_dict()
        {'name': 'ULS 1.5 P', 'limit_state': 'ULS', 'cases': [{'type': 'point', 'force': 10.0,
        'factor': 1.5}]}
        """
        return {
            "name": self.name,
            "limit_state": self.limit_state,
            "cases": [
                case.to_dict() | {"factor": f}
                for case, f in zip(self.cases, self.factors, strict=True)
            ],
        }


def combinations(
    cases: Sequence[LoadCase],
    *,
    gamma_g: float = GAMMA_G.default,
    gamma_q: float = GAMMA_Q.default,
) -> tuple[Combination, ...]:
    """The ULS combinations of EN 1990 (6.10), each variable case leading in turn, then the SLS one.

    Parameters
    ----------
    cases : sequence of LoadCase
        The characteristic loads (as :class:`Loads` holds them).
    gamma_g, gamma_q : float, keyword-only
        γ_G on the permanent cases, γ_Q on the variable ones (``GAMMA_G``,
        ``GAMMA_Q``); an accompanying case is also multiplied by its ψ0.

    Raises
    ------
    InputError
        No case, or a factor out of its range (one line naming it).

    Examples
    --------
    >>> from curvefold.mechanics import SelfWeight, Snow, Wind
    >>> for c in combinations((SelfWeight(), Snow(500.0), Wind(600.0, -0.8))):
    ...     print(c.name)
    ULS 1.35 G + 1.5 S + 0.9 W
    ULS 1.35 G + 0.75 S + 1.5 W
    SLS G + S + W
    >>> [c.name for c in combinations((SelfWeight(),), gamma_g=1.2)]
    ['ULS 1.2 G', 'SLS G']
    >>> combinations((SelfWeight(),), gamma_q=0.9)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: gamma_q must be in [1, 10] (...), got 0.9
    """
    g, q = GAMMA_G.check(gamma_g), GAMMA_Q.check(gamma_q)
    cases = tuple(cases)
    if not cases:
        raise InputError("no load: give self-weight, snow or a point load")
    variable = [k for k, case in enumerate(cases) if not case.permanent]
    leaders: list[int | None] = [*variable] or [None]
    uls = tuple(
        Combination(
            cases,
            tuple(
                g if case.permanent else q if k == lead else q * case.psi0
                for k, case in enumerate(cases)
            ),
        )
        for lead in leaders
    )
    return uls + (Combination(cases, (1.0,) * len(cases), "SLS"),)
