"""The load-case interface: a case's parameters, its registry, and what a case acts on.

A load is a list of **load cases** (:class:`LoadCase`), each a frozen value that gives the
nodal forces (P, 3), N, it puts on a model, its parameters (:class:`Parameter`: the
spec of each, in SI, and the unit users write it in) and a phrase for the report. The
cases are registered by name (:data:`LOAD_CASES`): a new case is one new class
(:mod:`._cases` holds them). SI units with z up.

This module needs no SciPy at import: the cases and their checks serve design files and
flags that are read before any solver is loaded.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, ClassVar, TypeVar, Union, cast

import numpy as np

from ..kernel._errors import InputError
from ..kernel._validate import Interval, Spec, describe

if TYPE_CHECKING:  # pragma: no cover
    from ._model import BarHingeModel
    from ._structures import StructureModel

__all__ = ["G", "Target", "Parameter", "LoadCase", "LOAD_CASES", "register", "case_type"]

#: Standard gravity, m/s².
G = 9.80665

#: What a load case acts on: a model, or a structure's model (which knows its end sections).
Target = Union["BarHingeModel", "StructureModel"]


@dataclass(frozen=True)
class Parameter:
    """One parameter of a load case: its check in SI units, and the unit users write it in.

    Parameters
    ----------
    spec : Spec
        Name, kind, default, range, SI unit, help and why (the library's values).
    unit : str
        The unit users write (a design file, a flag), when it is not the SI one:
        ``"kPa"`` for a pressure. Empty: the SI unit.
    scale : float
        How many SI units one user unit is (1000 Pa per kPa). The one conversion: every
        user-facing spec and value comes from it (:attr:`user_spec`, :meth:`from_user`,
        :meth:`to_user`).
    size : int
        1 for a number; 3 for a point [x, y, z], each coordinate checked by ``spec``.

    Examples
    --------
    >>> from curvefold.kernel import Spec
    >>> snow = Parameter(Spec("load", "real", 0.0, "[0, 1e6]", "Pa"), "kPa", 1000.0)
    >>> snow.from_user(0.5, "snow"), snow.user_spec.requirement, snow.text(500.0)
    (500.0, 'in [0, 1000] kPa', '0.5 kPa')
    """

    spec: Spec
    unit: str = ""
    scale: float = 1.0
    size: int = 1

    @property
    def name(self) -> str:
        """The parameter's name (a keyword of its case, a key of a ``[[loads.case]]`` entry)."""
        return self.spec.name

    @property
    def user_spec(self) -> Spec:
        """The spec in the user's unit: range and default divided by :attr:`scale`.

        Examples
        --------
        >>> from curvefold.kernel import Spec
        >>> snow = Parameter(Spec("load", "real", 0.0, "[0, 1e6]", "Pa"), "kPa", 1000.0)
        >>> snow.user_spec.describe()
        'in [0, 1000] kPa; default 0'
        """
        spec = self.spec
        if not self.unit:
            return spec
        r = spec.range
        range_ = (
            None
            if r is None
            else Interval(r.lo / self.scale, r.hi / self.scale, r.lo_closed, r.hi_closed)
        )
        default = spec.default / self.scale if isinstance(spec.default, float) else spec.default
        return replace(spec, range=range_, default=default, unit=self.unit)

    def check(self, value: Any, where: str | None = None, *, spec: Spec | None = None) -> Any:
        """The value checked by the spec (SI, or ``spec``'s unit): a number, a point as a tuple,
        or None where it may be none.

        Examples
        --------
        >>> from curvefold.kernel import Spec
        >>> at = Parameter(Spec("at", "real", None, "(-inf, inf)", "m"), size=3)
        >>> at.check([0, 1, 2.5])
        (0.0, 1.0, 2.5)
        >>> at.check([0, 1])
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: at must be a point [x, y, z] in m, got array [0, 1]
        """
        spec = spec or self.spec
        where = where or spec.name
        if value is None and spec.default is None:
            return None
        if self.size == 1:
            return spec.check(value, where)
        if not isinstance(value, (list, tuple, np.ndarray)) or len(value) != self.size:
            raise InputError(
                f"{where} must be a point [x, y, z] in {spec.unit}, got {describe(value)}",
                parameter=spec.name,
            )
        return tuple(spec.check(v, f"{where}[{i}]") for i, v in enumerate(value))

    def from_user(self, value: Any, where: str) -> Any:
        """A value in the user's unit, checked by :attr:`user_spec` (its message in that unit),
        in SI.

        Examples
        --------
        >>> from curvefold.kernel import Spec
        >>> snow = Parameter(Spec("load", "real", 0.0, "[0, 1e6]", "Pa"), "kPa", 1000.0)
        >>> snow.from_user(0.25, "snow")
        250.0
        >>> snow.from_user(2000, "snow")
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: snow must be in [0, 1000] kPa, got 2000.0
        """
        value = self.check(value, where, spec=self.user_spec)
        if value is None or self.scale == 1.0:
            return value
        return tuple(v * self.scale for v in value) if self.size > 1 else value * self.scale

    def to_user(self, value: Any) -> Any:
        """An SI value in the user's unit (a point as a list), as a design file holds it.

        Examples
        --------
        >>> from curvefold.kernel import Spec
        >>> Parameter(Spec("load", "real", 0.0, "[0, 1e6]", "Pa"), "kPa", 1000.0).to_user(250.0)
        0.25
        """
        if value is None:
            return None
        if self.size > 1:
            return [v / self.scale for v in value]
        return value / self.scale if isinstance(value, float) else value

    def text(self, value: Any) -> str:
        """An SI value in words, in the user's unit: ``0.5 kPa``, ``[0, 1, 2] m``.

        Examples
        --------
        >>> from curvefold.kernel import Spec
        >>> Parameter(Spec("at", "real", None, "(-inf, inf)", "m"), size=3).text((0.0, 1.0, 2.5))
        '[0, 1, 2.5] m'
        """
        shown = self.to_user(value)
        unit = self.unit or self.spec.unit
        if self.size > 1:
            return "[" + ", ".join(f"{v:g}" for v in shown) + f"] {unit}"
        text = f"{shown:g}" if isinstance(shown, float) else str(shown)
        return f"{text} {unit}" if unit else text


class LoadCase:
    """A load case: what it puts on a structure's nodes, its parameters and how it is told.

    A case is a frozen dataclass subclass registered in :data:`LOAD_CASES`, whose fields
    are its :attr:`parameters`, checked on construction (SI units).

    Attributes
    ----------
    name : str
        Its key in :data:`LOAD_CASES` and a design file's ``type``.
    title : str
        What it is, in a few words.
    parameters : tuple of Parameter
    symbol : str
        Its symbol in a load combination (``G``, ``S``, ``W``, ``P``).
    permanent : bool
        A permanent action (EN 1990 §1.5.3.3: the self-weight), or a variable one.
    psi0 : float
        The combination factor ψ0 of a variable action accompanying a leading one (EN 1990
        Table A1.1: 0.5 for snow at sites up to 1000 m, 0.6 for wind, 0.7 for imposed loads
        of categories A to D); 1 for a permanent action.

    Examples
    --------
    >>> list(LOAD_CASES)
    ['self_weight', 'snow', 'snow_half', 'wind', 'wind_zones', 'point']
    >>> Snow(-1.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: snow load must be in [0, 1000000] Pa (...), got -1.0
    """

    name: ClassVar[str]
    title: ClassVar[str]
    parameters: ClassVar[tuple[Parameter, ...]] = ()
    symbol: ClassVar[str] = "Q"
    permanent: ClassVar[bool] = False
    psi0: ClassVar[float] = 1.0

    def __post_init__(self) -> None:
        for p in self.parameters:
            object.__setattr__(
                self, p.name, p.check(getattr(self, p.name), f"{self.name} {p.name}")
            )

    def forces(self, model: Target) -> np.ndarray:
        """The nodal forces of this case on a model (or a structure's model), N, shape (P, 3).

        Raises
        ------
        InputError
            If the case needs what the model lacks (a sheet to fall on), or a point load
            lies too far from the structure.

        Examples
        --------
        >>> from curvefold.vault import Vault
        >>> state = Vault.from_design(tubes=1, panels=4, samples=21).structure.state()
        >>> tube = StructureModel.from_state(state, MATERIALS["aluminium"], 1e-3)
        >>> weight = SelfWeight().forces(tube)
        >>> round(float(weight[:, 2].sum()), 6), round(float(-G * tube.model.masses.sum()), 6)
        (-22.737584, -22.737584)
        >>> [round(float(c.forces(tube)[:, 2].sum()), 6) for c in (Snow(100.0), HalfSnow(100.0))]
        [-19.6211, -9.81055]
        """
        raise NotImplementedError

    def describe(self) -> str:
        """The case in words, its values in the user's units, for the report and the terminal.

        Examples
        --------
        >>> for case in (
        ...     SelfWeight(),
        ...     Snow(500.0),
        ...     HalfSnow(500.0, "end"),
        ...     Wind(600.0, -0.8),
        ...     PointLoad(10.0),
        ... ):
        ...     print(case.describe())
        self-weight
        snow 0.5 kPa
        snow 0.5 kPa on the end half of the span
        wind 0.6 kPa × c_p -0.8 normal to the sheets
        10 N at the apex
        """
        raise NotImplementedError

    def to_dict(self) -> dict[str, Any]:
        """The case as a design file's ``[[loads.case]]`` entry: its ``type`` and its values in
        the user's units.

        Examples
        --------
        >>> PointLoad(10.0, (0.0, 1.0, 1.5)).to_dict()
        {'type': 'point', 'force': 10.0, 'at': [0.0, 1.0, 1.5]}
        """
        values = {p.name: p.to_user(getattr(self, p.name)) for p in self.parameters}
        return {"type": self.name} | {k: v for k, v in values.items() if v is not None}

    @classmethod
    def from_dict(cls, entry: Mapping[str, Any], where: str) -> LoadCase:
        """The case of a ``[[loads.case]]`` entry (``type`` and values in the user's units),
        checked.

        Raises
        ------
        InputError
            One line starting with ``where``: an unknown type or key, a value out of range.

        Examples
        --------
        >>> LoadCase.from_dict({"type": "snow", "load": 0.5}, "design.toml: [[loads.case]] 1: ")
        Snow(load=500.0)
        >>> LoadCase.from_dict({"type": "hail"}, "case 1: ")  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: case 1: type must be one of ..., got string 'hail'
        """
        if not isinstance(entry, Mapping):
            raise InputError(f"{where}must be a table with a type, got {describe(entry)}")
        kind = case_type().check(entry.get("type"), f"{where}type")
        case = LOAD_CASES[kind]
        names = [p.name for p in case.parameters]
        for key in entry:
            if key != "type" and key not in names:
                allowed = ", ".join(names) or "none"
                raise InputError(
                    f"{where}unknown key {key!r} for type {kind!r} (allowed: {allowed})"
                )
        values = {
            p.name: p.from_user(entry.get(p.name, p.user_spec.default), f"{where}{kind} {p.name}")
            for p in case.parameters
        }
        return case(**values)


_Case = TypeVar("_Case", bound=type[LoadCase])
_REGISTRY: dict[str, type[LoadCase]] = {}
#: Every load case class by name, in the order they are listed.
LOAD_CASES: Mapping[str, type[LoadCase]] = MappingProxyType(_REGISTRY)


def register(case: _Case) -> _Case:
    """Add a case class to :data:`LOAD_CASES` under its name."""
    _REGISTRY[case.name] = case
    return case


def case_type() -> Spec:
    """The check of a ``[[loads.case]]`` entry's ``type``: one of the registered cases."""
    return Spec("type", "choice", choices=tuple(LOAD_CASES), help="the kind of load case")


def _structure(target: Target) -> StructureModel | None:
    """The structure's model, when the target is one (it knows its end sections)."""
    return cast("StructureModel", target) if hasattr(target, "feet") else None


def _model(target: Target) -> BarHingeModel:
    structure = _structure(target)
    return cast("BarHingeModel", target) if structure is None else structure.model


def _ends(target: Target) -> tuple[np.ndarray, np.ndarray] | None:
    """The nodes of the end sections t = 0 and t = 1 of a structure's model (None for a model)."""
    sm = _structure(target)
    if sm is None:
        return None
    n = sm.state.vertices.shape[1]
    return np.flatnonzero(sm.node_sample == 0), np.flatnonzero(sm.node_sample == n - 1)


def _needs_sheet(model: BarHingeModel, what: str) -> None:
    if not len(model.membranes):
        raise InputError(f"{what} needs a sheet (membrane triangles) to fall on")
