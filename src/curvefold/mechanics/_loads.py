"""The loads of one analysis: its load cases, their forces summed (:class:`Loads`).

The vocabulary of loads lives in three modules, each one concept: the interface and
registry of load cases (:mod:`._loadcase`: :class:`LoadCase`, :class:`Parameter`,
:data:`LOAD_CASES`, g), the cases themselves (:mod:`._cases`) and the supports
(:mod:`._supports`). Their names are re-exported here, where the package and its
callers have always found them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import cast

import numpy as np

from ..kernel._errors import InputError
from ..kernel._validate import describe
from ._cases import POINT_REACH, HalfSnow, PointLoad, SelfWeight, Snow, Wind, ZonedWind
from ._loadcase import LOAD_CASES, G, LoadCase, Parameter, Target, _model, case_type
from ._supports import SUPPORTED, SUPPORTS, Supports
from ._surface import apex, snow_areas

__all__ = [
    "G",
    "Parameter",
    "LoadCase",
    "SelfWeight",
    "Snow",
    "HalfSnow",
    "Wind",
    "ZonedWind",
    "PointLoad",
    "LOAD_CASES",
    "CASE_TYPE",
    "POINT_REACH",
    "Loads",
    "Supports",
    "SUPPORTS",
    "SUPPORTED",
    "snow_areas",
    "apex",
]

#: The check of a ``[[loads.case]]`` entry's ``type``.
CASE_TYPE = case_type()


@dataclass(frozen=True)
class Loads:
    """What loads the structure: load cases (module notes), their forces summed. Checked on
    construction.

    Attributes
    ----------
    cases : tuple of LoadCase
        Default: the self-weight alone.

    Examples
    --------
    >>> Loads((SelfWeight(), Snow(500.0))).describe()
    'self-weight + snow 0.5 kPa'
    >>> Loads(("snow",))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: loads must be load cases (...), got string 'snow'
    """

    cases: tuple[LoadCase, ...] = (SelfWeight(),)

    def __post_init__(self) -> None:
        if not isinstance(self.cases, (tuple, list)):
            raise InputError(f"loads must be a sequence of load cases, got {describe(self.cases)}")
        for case in self.cases:
            if not isinstance(case, LoadCase):
                raise InputError(f"loads must be load cases (Snow(500.0), …), got {describe(case)}")
        object.__setattr__(self, "cases", tuple(self.cases))

    @classmethod
    def from_values(
        cls,
        *,
        self_weight: bool = True,
        snow: float = 0.0,
        point: float = 0.0,
        point_at: Sequence[float] | None = None,
    ) -> Loads:
        """The loads of the usual keywords: the self-weight or not, snow (Pa), a point load (N) at
        the apex or ``point_at`` (m).

        A zero snow or point load is no case.

        Examples
        --------
        >>> Loads.from_values(snow=100.0, point=5.0).cases
        (SelfWeight(), Snow(load=100.0), PointLoad(force=5.0, at=None))
        >>> Loads.from_values(snow=-1.0)  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: snow load must be in [0, 1000000] Pa (...), got -1.0
        """
        if not isinstance(self_weight, (bool, np.bool_)):
            raise InputError(f"self_weight must be true or false, got {self_weight!r}")
        cases: list[LoadCase] = [SelfWeight()] if self_weight else []
        at = None if point_at is None else cast("tuple[float, float, float]", tuple(point_at))
        snowed, pointed = Snow(snow), PointLoad(point, at)
        cases += [snowed] if snowed.load else []
        cases += [pointed] if pointed.force else []
        return cls(tuple(cases))

    def forces(self, model: Target) -> np.ndarray:
        """The nodal forces of every case on a model (or a structure's model), summed, N, shape
        (P, 3).

        Raises
        ------
        InputError
            If there is no case, or a case refuses the model (:meth:`LoadCase.forces`).

        Examples
        --------
        >>> import numpy as np
        >>> from curvefold.vault import Vault
        >>> state = Vault.from_design(tubes=1, panels=4, samples=21).structure.state()
        >>> tube = StructureModel.from_state(state, MATERIALS["aluminium"], 1e-3)
        >>> forces = Loads().forces(tube.model)  # self-weight
        >>> round(float(forces[:, 2].sum()), 6), round(float(-G * tube.model.masses.sum()), 6)
        (-22.737584, -22.737584)
        >>> Loads(()).forces(tube.model)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: no load: give self-weight, snow or a point load
        """
        if not self.cases:
            raise InputError("no load: give self-weight, snow or a point load")
        return sum(
            (case.forces(model) for case in self.cases), np.zeros((len(_model(model).nodes), 3))
        )

    def describe(self) -> str:
        """Every case in words, joined by " + " (:meth:`LoadCase.describe`).

        Examples
        --------
        >>> Loads.from_values(self_weight=False, point=10.0).describe()
        '10 N at the apex'
        """
        return " + ".join(case.describe() for case in self.cases)
