"""The load cases, each one class registered in :data:`._loadcase.LOAD_CASES`:

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
  ``POINT_REACH`` of the structure's size from the point.

"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..kernel._errors import InputError
from ..kernel._validate import Interval, Spec
from ._loadcase import G, LoadCase, Parameter, Target, _ends, _model, _needs_sheet, register
from ._surface import apex, beyond_shares, face_vectors, projected_forces, span

__all__ = ["SelfWeight", "Snow", "HalfSnow", "Wind", "ZonedWind", "PointLoad", "POINT_REACH"]

#: How far from its nearest node a point load may be placed, as a share of the structure's size.
POINT_REACH = 0.05

_PRESSURE_WHY = "a roof's snow is below 10 kPa; 1000 kPa is a press"


def _snow_load(help: str) -> Parameter:
    """A snow load's parameter: Pa inside, kPa where users write it."""
    spec = Spec("load", "real", 0.0, Interval.parse("[0, 1e6]"), "Pa", help=help, why=_PRESSURE_WHY)
    return Parameter(spec, "kPa", 1000.0)


@register
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
    symbol: ClassVar[str] = "G"
    permanent: ClassVar[bool] = True
    title: ClassVar[str] = "the sheet's own weight"

    def forces(self, model: Target) -> np.ndarray:
        m = _model(model)
        f = np.zeros((len(m.nodes), 3))
        f[:, 2] -= G * m.masses
        return f

    def describe(self) -> str:
        return "self-weight"


@register
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
    symbol: ClassVar[str] = "S"
    psi0: ClassVar[float] = 0.5  # EN 1990 Table A1.1
    title: ClassVar[str] = "snow, uniform on the roof seen from above"
    parameters: ClassVar[tuple[Parameter, ...]] = (
        _snow_load("a uniform vertical load per projected area on the roof"),
    )

    def forces(self, model: Target) -> np.ndarray:
        m = _model(model)
        _needs_sheet(m, "snow")
        return projected_forces(m, self.load)

    def describe(self) -> str:
        return f"snow {self.parameters[0].text(self.load)}"


@register
@dataclass(frozen=True)
class HalfSnow(LoadCase):
    """Snow on half the span: :class:`Snow`'s load on the part of the seen surface before
    (``"start"``) or beyond (``"end"``) the middle of the span (module notes; the span:
    ``_surface.span_axis``, from end section t = 0 to t = 1 on a structure's model).

    Examples
    --------
    >>> HalfSnow(500.0, "start").describe()
    'snow 0.5 kPa on the start half of the span'
    """

    load: float = 0.0
    side: str = "end"

    name: ClassVar[str] = "snow_half"
    symbol: ClassVar[str] = "S_half"
    psi0: ClassVar[float] = 0.5  # EN 1990 Table A1.1
    title: ClassVar[str] = "snow on half the span (EN 1991-1-3's drifted case, simplified)"
    parameters: ClassVar[tuple[Parameter, ...]] = (
        _snow_load(
            "snow on half the span: a vertical load per projected "
            "area on one half of the roof, none on the other"
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


@register
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
    symbol: ClassVar[str] = "W"
    psi0: ClassVar[float] = 0.6  # EN 1990 Table A1.1
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


@register
@dataclass(frozen=True)
class ZonedWind(LoadCase):
    """Wind across a vaulted roof in EN 1991-1-4's zones (§7.2.8, Fig. 7.11): the span, from
    the windward edge, in a quarter A, a half B and a quarter C, each with its own coefficient.

    The pressure c_p q_p of each zone acts normal to the sheets as :class:`Wind`'s; every
    triangle is cut exactly at the zones' borders (``_surface.beyond_shares``). The
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
    symbol: ClassVar[str] = "W_zones"
    psi0: ClassVar[float] = 0.6  # EN 1990 Table A1.1
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


@register
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
    symbol: ClassVar[str] = "P"
    psi0: ClassVar[float] = 0.7  # EN 1990 Table A1.1
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
            If that node is farther from ``at`` than ``POINT_REACH`` of the model's size.

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
