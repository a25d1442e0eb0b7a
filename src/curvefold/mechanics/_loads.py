"""Loads and supports of a structure's model, in SI units with z up.

A load is a list of **load cases** (:class:`LoadCase`), each a frozen value that gives the
nodal forces (P, 3), N, it puts on a model, its parameters (:class:`Parameter`: the
spec of each, in SI, and the unit users write it in) and a phrase for the report. The
cases are registered by name (:data:`LOAD_CASES`): a new case is one new class. The cases:

* ``self_weight`` (:class:`SelfWeight`): every node's lumped mass times g = 9.80665 m/s²,
  downward;
* ``snow`` (:class:`Snow`): a uniform vertical load per projected area (Pa; users write
  kPa) on the surface seen from above: each triangle of the sheet whose centroid no other
  triangle covers from above carries the load times its horizontal projected area, shared
  equally by its corners (the triangles hidden under another part of the structure, the
  lower sheet of every tube among them, carry none);
* ``snow_half`` (:class:`HalfSnow`): the same load on the half of the span before or
  beyond its middle only. EN 1991-1-3 (§5.3.5, Fig. 5.6) loads a cylindrical roof's
  drifted case with μ₃ s_k on one half and 0.5 μ₃ s_k on the other; what governs an arch
  is the difference, the antisymmetric part. The case is that simplification: one half
  loaded uniformly, the other not (the user's load is the difference; a uniform
  :class:`Snow` adds the symmetric part);
* ``wind`` (:class:`Wind`): a pressure c_p q_p normal to every face of the sheets, positive
  towards the surface (:func:`._surface.face_vectors`: out of every tube, where faces two
  tubes share cancel), a third of each triangle's force on each corner. One uniform
  coefficient: EN 1991-1-4's zones of a vaulted roof (§7.2.8) and the internal pressure
  are not modelled; on a closed surface a uniform pressure is in equilibrium by itself;
* ``wind_zones`` (:class:`ZonedWind`): the same with EN 1991-1-4's zones of a vaulted roof
  (§7.2.8, Fig. 7.11: the windward quarter of the span A, the middle half B, the leeward
  quarter C), a coefficient each, the user's (read off the figure for the roof's f/d, h/d);
* ``point`` (:class:`PointLoad`): a vertical force (N, downward) at the apex, the highest
  node, or at the node nearest a given point, refused when that node is farther than
  :data:`POINT_REACH` of the structure's size from the point.

:class:`Loads` holds the cases of one analysis and sums their forces.

Supports (:class:`Supports`): the feet, the end sections on the ground z = 0 (a vault
stands on them), or the end sections t = 0 and t = 1 wherever they are (a tube or block
held at both ends, as a bridge), or given nodes; ``"pinned"`` (every translation held) or
``"roller"`` (the vertical held on every supported node; three horizontal restraints,
chosen among them by a pivoted QR to hold the horizontal rigid motions, keep the
structure in place and, being statically determinate, carry no vertical load's reaction).

This module needs no SciPy at import (the roller's QR imports it when used): the cases
and their checks, and the supports' (:data:`SUPPORTS`), serve design files and flags that
are read before any solver is loaded.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, ClassVar, Literal, TypeVar, Union, cast

import numpy as np

from ..kernel._errors import InputError
from ..kernel._validate import Interval, Spec, describe
from ._surface import apex, beyond_shares, face_vectors, projected_forces, snow_areas, span

if TYPE_CHECKING:  # pragma: no cover
    from ._model import BarHingeModel
    from ._structures import StructureModel

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
    "POINT_REACH",
    "Loads",
    "Supports",
    "SUPPORTS",
    "SUPPORTED",
    "snow_areas",
    "apex",
]

#: Standard gravity, m/s².
G = 9.80665
#: How far from its nearest node a point load may be placed, as a share of the structure's size.
POINT_REACH = 0.05
#: How the supported nodes are held.
SUPPORTS = Spec(
    "supports",
    "choice",
    "pinned",
    choices=("pinned", "roller"),
    help="how the supported end sections are held: pinned (every translation) or roller "
    "(the vertical, and three horizontal restraints that only keep the structure "
    "in place)",
    label="supports",
)
#: Which nodes are supported: the feet (end sections on the ground) or both end sections
#: wherever they are.
SUPPORTED = ("feet", "ends")

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
        kind = CASE_TYPE.check(entry.get("type"), f"{where}type")
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


def _register(case: _Case) -> _Case:
    """Add a case class to :data:`LOAD_CASES` under its name."""
    _REGISTRY[case.name] = case
    return case


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


_PRESSURE_WHY = "a roof's snow is below 10 kPa; 1000 kPa is a press"


@_register
@dataclass(frozen=True)
class SelfWeight(LoadCase):
    """The sheet's weight: every node's lumped mass (density × thickness × area) times g,
    downward.

    Examples
    --------
    >>> SelfWeight().describe()
    'self-weight'
    """

    name: ClassVar[str] = "self_weight"
    title: ClassVar[str] = "the sheet's own weight"

    def forces(self, model: Target) -> np.ndarray:
        m = _model(model)
        f = np.zeros((len(m.nodes), 3))
        f[:, 2] -= G * m.masses
        return f

    def describe(self) -> str:
        return "self-weight"


@_register
@dataclass(frozen=True)
class Snow(LoadCase):
    """Snow: a uniform vertical load per projected area (Pa) on the surface seen from above
    (module notes).

    Examples
    --------
    >>> Snow(500.0).describe()
    'snow 0.5 kPa'
    """

    load: float = 0.0

    name: ClassVar[str] = "snow"
    title: ClassVar[str] = "snow, uniform on the roof seen from above"
    parameters: ClassVar[tuple[Parameter, ...]] = (
        Parameter(
            Spec(
                "load",
                "real",
                0.0,
                Interval.parse("[0, 1e6]"),
                "Pa",
                help="a uniform vertical load per projected area on the roof",
                why=_PRESSURE_WHY,
            ),
            "kPa",
            1000.0,
        ),
    )

    def forces(self, model: Target) -> np.ndarray:
        m = _model(model)
        _needs_sheet(m, "snow")
        return projected_forces(m, self.load)

    def describe(self) -> str:
        return f"snow {self.parameters[0].text(self.load)}"


@_register
@dataclass(frozen=True)
class HalfSnow(LoadCase):
    """Snow on half the span: :class:`Snow`'s load on the part of the seen surface before
    (``"start"``) or beyond (``"end"``) the middle of the span (module notes; the span:
    :func:`._surface.span_axis`, from end section t = 0 to t = 1 on a structure's model).

    Examples
    --------
    >>> HalfSnow(500.0, "start").describe()
    'snow 0.5 kPa on the start half of the span'
    """

    load: float = 0.0
    side: str = "end"

    name: ClassVar[str] = "snow_half"
    title: ClassVar[str] = "snow on half the span (EN 1991-1-3's drifted case, simplified)"
    parameters: ClassVar[tuple[Parameter, ...]] = (
        Parameter(
            Spec(
                "load",
                "real",
                0.0,
                Interval.parse("[0, 1e6]"),
                "Pa",
                help="snow on half the span: a vertical load per projected "
                "area on one half of the roof, none on the other",
                why=_PRESSURE_WHY,
            ),
            "kPa",
            1000.0,
        ),
        Parameter(
            Spec(
                "side",
                "choice",
                "end",
                choices=("start", "end"),
                help="which half carries it: from the start of the span (t = 0) to its middle, "
                "or from there to its end (t = 1)",
            )
        ),
    )

    def forces(self, model: Target) -> np.ndarray:
        m = _model(model)
        _needs_sheet(m, "snow")
        return projected_forces(m, self.load, half=self.side, ends=_ends(model))

    def describe(self) -> str:
        return f"snow {self.parameters[0].text(self.load)} on the {self.side} half of the span"


@_register
@dataclass(frozen=True)
class Wind(LoadCase):
    """Wind: a pressure c_p q_p normal to the sheets, positive towards the surface (module notes).

    Examples
    --------
    >>> Wind(500.0, -0.8).pressure, Wind(500.0).cp
    (-400.0, 1.0)
    """

    velocity_pressure: float = 0.0
    cp: float = 1.0

    name: ClassVar[str] = "wind"
    title: ClassVar[str] = "wind, a uniform pressure normal to the sheets"
    parameters: ClassVar[tuple[Parameter, ...]] = (
        Parameter(
            Spec(
                "velocity_pressure",
                "real",
                0.0,
                Interval.parse("[0, 1e5]"),
                "Pa",
                help="the peak velocity pressure q_p of the wind (EN 1991-1-4 §4.5)",
                why="a hurricane's is below 5 kPa",
            ),
            "kPa",
            1000.0,
        ),
        Parameter(
            Spec(
                "cp",
                "real",
                1.0,
                Interval.parse("[-3, 3]"),
                help="the pressure coefficient c_p on every face: positive presses "
                "on the surface, negative pulls (suction)",
                why="EN 1991-1-4's coefficients lie within ±3",
            )
        ),
    )

    @property
    def pressure(self) -> float:
        """c_p q_p, Pa: positive towards the surface."""
        return self.cp * self.velocity_pressure

    def forces(self, model: Target) -> np.ndarray:
        m = _model(model)
        _needs_sheet(m, "wind")
        triangles, vectors = face_vectors(m)
        f = np.zeros((len(m.nodes), 3))
        share = np.repeat(
            -self.pressure * vectors / 3, 3, axis=0
        )  # towards the surface: against its outward normal
        for k in range(3):
            f[:, k] = np.bincount(triangles.ravel(), share[:, k], minlength=len(f))
        return f

    def describe(self) -> str:
        pressure = self.parameters[0].text(self.velocity_pressure)
        return f"wind {pressure} × c_p {self.cp:g} normal to the sheets"


def _coefficient(name: str, zone: str) -> Parameter:
    return Parameter(
        Spec(
            name,
            "real",
            0.0,
            Interval.parse("[-3, 3]"),
            help=f"c_pe,10 of zone {zone} (EN 1991-1-4 Fig. 7.11, read for the roof's rise f/d "
            "and height h/d)",
            why="EN 1991-1-4's coefficients lie within ±3",
        )
    )


@_register
@dataclass(frozen=True)
class ZonedWind(LoadCase):
    """Wind across a vaulted roof in EN 1991-1-4's zones (§7.2.8, Fig. 7.11): the span, from
    the windward edge, in a quarter A, a half B and a quarter C, each with its own coefficient.

    The pressure c_p q_p of each zone acts normal to the sheets as :class:`Wind`'s; every
    triangle is cut exactly at the zones' borders (:func:`._surface.beyond_shares`). The
    coefficients are the user's, read off the standard's figure for the roof's f/d and h/d
    (its values depend on them and on the national annex); they default to 0.

    Examples
    --------
    >>> ZonedWind(500.0, -0.5, -1.0, -0.4, "end").describe()
    'wind 0.5 kPa from the end of the span, c_p -0.5, -1, -0.4 on its zones A, B, C'
    """

    velocity_pressure: float = 0.0
    cp_a: float = 0.0
    cp_b: float = 0.0
    cp_c: float = 0.0
    windward: str = "start"

    name: ClassVar[str] = "wind_zones"
    title: ClassVar[str] = "wind on a vaulted roof in EN 1991-1-4's zones A, B and C"
    parameters: ClassVar[tuple[Parameter, ...]] = (
        Wind.parameters[0],
        _coefficient("cp_a", "A, the windward quarter of the span"),
        _coefficient("cp_b", "B, the middle half"),
        _coefficient("cp_c", "C, the leeward quarter"),
        Parameter(
            Spec(
                "windward",
                "choice",
                "start",
                choices=("start", "end"),
                help="where the wind comes from: the start of the span (t = 0) or its end (t = 1)",
            )
        ),
    )

    def forces(self, model: Target) -> np.ndarray:
        m = _model(model)
        _needs_sheet(m, "wind")
        triangles, vectors = face_vectors(m)
        axis, lo, hi = span(m, _ends(model))
        along = m.nodes[triangles][..., :2] @ axis  # (n, 3)
        if self.windward == "end":
            along, lo, hi = -along, -hi, -lo
        quarter = 0.25 * (hi - lo)
        past_a, past_b = beyond_shares(along - lo - quarter), beyond_shares(along - hi + quarter)
        shares = self.cp_a * (1 / 3 - past_a) + self.cp_b * (past_a - past_b) + self.cp_c * past_b
        # (n, 3 corners, 3): towards the surface, against its outward normal
        load = -self.velocity_pressure * shares[..., None] * vectors[:, None, :]
        f = np.zeros((len(m.nodes), 3))
        for k in range(3):
            f[:, k] = np.bincount(triangles.ravel(), load[..., k].ravel(), minlength=len(f))
        return f

    def describe(self) -> str:
        pressure = self.parameters[0].text(self.velocity_pressure)
        return (
            f"wind {pressure} from the {self.windward} of the span, c_p {self.cp_a:g}, "
            f"{self.cp_b:g}, {self.cp_c:g} on its zones A, B, C"
        )


@_register
@dataclass(frozen=True)
class PointLoad(LoadCase):
    """A vertical point load (N, downward) at the apex, or at the node nearest ``at`` (m).

    Examples
    --------
    >>> PointLoad(10.0, (0.0, 1.0, 1.2)).describe()
    '10 N at [0, 1, 1.2] m'
    """

    force: float = 0.0
    at: tuple[float, float, float] | None = None

    name: ClassVar[str] = "point"
    title: ClassVar[str] = "a point load"
    parameters: ClassVar[tuple[Parameter, ...]] = (
        Parameter(
            Spec(
                "force",
                "real",
                0.0,
                Interval.parse("[0, 1e9]"),
                "N",
                help="a vertical point load, downward",
                why="numerical range",
            )
        ),
        Parameter(
            Spec(
                "at",
                "real",
                None,
                Interval.parse("(-inf, inf)"),
                "m",
                help="where it is, [x, y, z]: the nearest node carries "
                f"it, within {POINT_REACH:.0%} of the structure's size; default the apex",
            ),
            size=3,
        ),
    )

    def node(self, model: Target) -> int:
        """The node that carries the load: the apex, or the node nearest :attr:`at`.

        Raises
        ------
        InputError
            If that node is farther from ``at`` than :data:`POINT_REACH` of the model's size.

        Examples
        --------
        >>> import numpy as np
        >>> from curvefold.vault import Vault
        >>> state = Vault.from_design(tubes=1, panels=4, samples=21).structure.state()
        >>> tube = StructureModel.from_state(state, MATERIALS["aluminium"], 1e-3)
        >>> PointLoad(1.0).node(tube) == int(np.argmax(tube.model.nodes[:, 2]))
        True
        >>> PointLoad(1.0, (0.0, 1.0, 3.0)).node(tube)  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: point load at [0, 1, 3] m is 1.89 m ... allowed (...)
        """
        m = _model(model)
        if self.at is None:
            return apex(m)
        distance = np.linalg.norm(m.nodes - np.asarray(self.at), axis=1)
        node = int(np.argmin(distance))
        reach = POINT_REACH * m.size
        if not distance[node] <= reach:
            raise InputError(
                f"point load at {self.parameters[1].text(self.at)} is {distance[node]:.3g} m from "
                "the "
                f"structure's nearest node, farther than the {reach:.3g} m allowed "
                f"({POINT_REACH:.0%} of its size, {m.size:.3g} m)",
                parameter="at",
            )
        return node

    def forces(self, model: Target) -> np.ndarray:
        f = np.zeros((len(_model(model).nodes), 3))
        f[self.node(model), 2] -= self.force
        return f

    def describe(self) -> str:
        where = "the apex" if self.at is None else self.parameters[1].text(self.at)
        return f"{self.parameters[0].text(self.force)} at {where}"


#: The check of a ``[[loads.case]]`` entry's ``type``.
CASE_TYPE = Spec("type", "choice", choices=tuple(LOAD_CASES), help="the kind of load case")


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


@dataclass(frozen=True)
class Supports:
    """How the structure is held (module notes).

    Attributes
    ----------
    kind : {"pinned", "roller"}
    nodes : tuple of int or None
        The supported nodes; None: those ``at`` names, of a structure's model.
    at : {"feet", "ends"}
        Without ``nodes``: the feet (the end sections on z = 0, where a vault stands) or
        the ends (every tube's end sections t = 0 and t = 1, wherever they are: a tube or
        block held at both ends).

    Examples
    --------
    >>> Supports("clamped")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: supports must be one of "pinned", "roller", got string
    'clamped'
    """

    kind: Literal["pinned", "roller"] = "pinned"
    nodes: tuple[int, ...] | None = None
    at: Literal["feet", "ends"] = "feet"

    def __post_init__(self) -> None:
        SUPPORTS.check(self.kind)
        Spec("at", "choice", choices=SUPPORTED).check(self.at)
        if self.nodes is not None:
            nodes = np.asarray(self.nodes)
            if nodes.ndim != 1 or not len(nodes) or not np.issubdtype(nodes.dtype, np.integer):
                raise InputError(
                    f"support nodes must be a non-empty list of node indices, got {self.nodes!r}"
                )
            object.__setattr__(self, "nodes", tuple(int(v) for v in nodes))

    def fixed(self, target: StructureModel | BarHingeModel) -> np.ndarray:
        """The held DOFs, shape (P, 3) of bool.

        Raises
        ------
        InputError
            If the structure has no feet (no end section on z = 0) and no nodes are given,
            or a node is out of range.

        Examples
        --------
        >>> import numpy as np
        >>> from curvefold.vault import Vault
        >>> state = Vault.from_design(tubes=1, panels=4, samples=21).structure.state()
        >>> tube = StructureModel.from_state(state, MATERIALS["aluminium"], 1e-3)
        >>> (
        ...     int(Supports().fixed(tube).sum()),
        ...     int(Supports("roller").fixed(tube).sum()),
        ... )  # 8 feet pinned; on rollers, z and 3 more
        (24, 11)
        >>> Supports(nodes=(99,)).fixed(tube)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: support nodes must be in [0, 20), got 99 … 99
        """
        sm = _structure(target)  # a StructureModel, which knows its end sections
        model = _model(target)
        P = len(model.nodes)
        if self.nodes is not None:
            nodes = np.asarray(self.nodes)
            if nodes.min() < 0 or nodes.max() >= P:
                raise InputError(
                    f"support nodes must be in [0, {P}), got {nodes.min()} … {nodes.max()}"
                )
        elif sm is not None:
            nodes = sm.feet if self.at == "feet" else sm.ends
            if not len(nodes):
                low = float(model.nodes[sm.ends, 2].min())
                raise InputError(
                    "no foot: no end section of this structure lies on the ground "
                    f"z = 0 (the lowest end point is at z = {low:.6g} m); place it on the "
                    "ground or give the supported nodes"
                )
        else:
            raise InputError("a model without a structure needs its supported nodes")
        fixed = np.zeros((P, 3), bool)
        if self.kind == "pinned":
            fixed[nodes] = True
            return fixed
        fixed[nodes, 2] = True
        # the horizontal rigid motions (x, y, rotation about z) at the feet's x, y DOFs
        c = model.nodes[nodes, :2] - model.nodes[nodes, :2].mean(axis=0)
        rows = np.zeros((len(nodes), 2, 3))
        rows[:, 0, 0] = rows[:, 1, 1] = 1.0
        rows[:, 0, 2], rows[:, 1, 2] = -c[:, 1], c[:, 0]
        from scipy.linalg import qr

        held = qr(rows.reshape(-1, 3).T, mode="r", pivoting=True)[1][:3]
        fixed[nodes[held // 2], held % 2] = True
        return fixed
