"""A design under load: its ``[material]`` and ``[loads]`` sections, and what the mechanics says of
the built design.

A vault, tube or block design may say what it is made of and what loads it::

    [material]
    material = "aluminium"  # a named material, or your own values:
    thickness = 0.002  # youngs_modulus, poisson, density (and strength)
    [loads]
    snow = 0.5  # kPa on the roof seen from above
    snow_half = 0.3  # kPa more on half the span (snow_half_side = "end")
    wind = 0.6  # kPa, the wind's velocity pressure q_p, times
    wind_cp = -0.8  # its pressure coefficient on every face
    point_load = 100.0  # N at the apex
    supports = "pinned"

    [[loads.case]]  # any number of cases more, each of a type of
    type = "point"  # curvefold.mechanics.LOAD_CASES, in the units above
    force = 50.0
    at = [0.0, 1.0, 1.1]

The sections are optional: a design that has either is analysed under load wherever it is
built into an output folder (``curvefold vault``, ``tube``, ``block``, the designer's
folder), and ``curvefold load`` analyses any design, filling them with their defaults
(polypropylene 1 mm, self-weight, pinned). Their keys are checked by the specs of
:mod:`curvefold.mechanics`: a load key is a parameter of a load case
(:data:`LOADS_KEYS`), its spec that parameter's in the user's unit (pressures in kPa
here, in Pa there: :class:`curvefold.mechanics.Parameter` converts). A vault stands on its feet
(the end sections on the ground); a tube or block is held at both end sections, t = 0 and
t = 1, wherever they are.

:func:`analyse` runs :func:`curvefold.mechanics.analyse_load` on a built structure
(:attr:`Built.mechanics <curvefold.app.Built.mechanics>`) and returns a
:class:`Loaded`: the result with what the report, the 3D model and the command line show
of it. The mechanics and SciPy are imported only then.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from contextvars import ContextVar
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from ..kernel._errors import InputError
from ..kernel._validate import Spec, describe
from ..mechanics import (
    ACROSS,
    CREASE_STIFFNESS,
    CRITERIA_SPECS,
    ERROR_TOLERANCE,
    IMPERFECTION,
    LOAD_CASES,
    MATERIAL,
    MATERIAL_SPECS,
    MATERIALS,
    NONLINEAR,
    SUPPORTS,
    THICKNESS,
    LoadCase,
    Loads,
    SelfWeight,
    error_text,
)
from ._loaded_text import _check_words, _finite, _rounded, _vector

if TYPE_CHECKING:  # pragma: no cover
    from ..geometry._structure import Structure
    from ..mechanics import AtlasLoad, Collapse, Criteria, LoadResult, Verdict

__all__ = [
    "MATERIAL_SECTION",
    "LOADS_SECTION",
    "LOADS_KEYS",
    "MaterialParams",
    "LoadParams",
    "check_material",
    "check_cases",
    "material_alternatives",
    "Loaded",
    "analyse",
    "atlas_load",
    "magnification",
    "DEFAULT_MATERIAL",
    "MAX_CASES",
    "PROGRESS",
]

#: The material of a design that names none and gives no values of its own.
DEFAULT_MATERIAL = "polypropylene"
#: What :func:`analyse` calls with the collapse path after every state (a progress bar), if set.
PROGRESS: ContextVar[Callable[[Any], None] | None] = ContextVar("PROGRESS", default=None)
#: Most ``[[loads.case]]`` entries a design may list.
MAX_CASES = 1000
_OWN = tuple(s.name for s in MATERIAL_SPECS)  # youngs_modulus, poisson, density, strength
_NEEDED = _OWN[:3]
_CRITERIA = {s.name: s for s in CRITERIA_SPECS}

#: ``[material]``: a named material or the user's own values, the thickness and the creases'
#: stiffness.
MATERIAL_SECTION: tuple[Spec, ...] = (
    Spec(
        MATERIAL.name,
        "choice",
        None,
        choices=MATERIAL.choices,
        label=MATERIAL.label,
        help=f"{MATERIAL.help}; default {DEFAULT_MATERIAL} unless your own values are given",
    ),
    *MATERIAL_SPECS,
    THICKNESS,
    CREASE_STIFFNESS,
)


def _key(name: str, case: str, parameter: str, **words: Any) -> Spec:
    """The ``[loads]`` key ``name``: the spec of a case's parameter in the user's unit, renamed
    (and reworded)."""
    spec = next(p for p in LOAD_CASES[case].parameters if p.name == parameter).user_spec
    return replace(spec, name=name, **words)


#: The ``[loads]`` keys that set a load case: key -> (case, parameter). A case's first key
#: adds it when non-zero; its others set its other parameters.
LOADS_KEYS: Mapping[str, tuple[str, str]] = {
    "snow": ("snow", "load"),
    "snow_half": ("snow_half", "load"),
    "snow_half_side": ("snow_half", "side"),
    "wind": ("wind", "velocity_pressure"),
    "wind_cp": ("wind", "cp"),
    "point_load": ("point", "force"),
}
#: ``[loads]``: what loads the structure and how it is held, the keys' specs those of the
#: load cases' parameters in the user's units (:data:`LOADS_KEYS`); the ``[[loads.case]]``
#: entries are checked apart (:func:`check_cases`).
LOADS_SECTION: tuple[Spec, ...] = (
    Spec("self_weight", "flag", True, help="the sheet's own weight loads it", label="self-weight"),
    _key("snow", "snow", "load", label="snow load"),
    _key("snow_half", "snow_half", "load", label="snow on half the span"),
    _key("snow_half_side", "snow_half", "side", label="half of the span under snow"),
    _key(
        "wind",
        "wind",
        "velocity_pressure",
        label="wind velocity pressure",
        help="wind: its peak velocity pressure q_p (EN 1991-1-4 §4.5), times wind_cp, presses "
        "normal to every face",
    ),
    _key("wind_cp", "wind", "cp", label="wind pressure coefficient"),
    _key(
        "point_load",
        "point",
        "force",
        help="a vertical point load, downward, at the apex (the highest point); "
        "elsewhere: a [[loads.case]] of type point",
        label="point load",
    ),
    Spec(
        SUPPORTS.name,
        "choice",
        SUPPORTS.default,
        choices=SUPPORTS.choices,
        label=SUPPORTS.label,
        help=f"{SUPPORTS.help}; a vault stands on its feet, a tube or block is held at both end "
        "sections (t = 0 and t = 1)",
    ),
    *CRITERIA_SPECS,
    ACROSS,
    NONLINEAR,
    IMPERFECTION,
)


def check_cases(entries: Any, where: str) -> tuple[LoadCase, ...] | None:
    """The ``[[loads.case]]`` entries of a design as load cases (SI), or None when it lists none.

    Each entry is a table with a ``type`` of :data:`curvefold.mechanics.LOAD_CASES` and
    that case's parameters in the user's units (:meth:`curvefold.mechanics.LoadCase.from_dict`).

    Raises
    ------
    InputError
        One line starting with ``where`` (``"design.toml: [[loads.case]] "``) and the entry's
        number.

    Examples
    --------
    >>> check_cases([{"type": "wind", "velocity_pressure": 0.5, "cp": -0.8}], "[[loads.case]] ")
    (Wind(velocity_pressure=500.0, cp=-0.8),)
    >>> check_cases({"type": "wind"}, "[[loads.case]] ")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: [[loads.case]] must be an array of tables (...), got ...
    """
    if entries is None:
        return None
    if not isinstance(entries, (list, tuple)) or not 1 <= len(entries) <= MAX_CASES:
        raise InputError(
            f"{where}must be an array of tables ([[loads.case]] entries with a type), "
            f"got {describe(entries)}",
            parameter="case",
        )
    return tuple(LoadCase.from_dict(entry, f"{where}{n + 1}: ") for n, entry in enumerate(entries))


@dataclass(frozen=True)
class MaterialParams:
    """``[material]``: a named material or the user's own values (SI), the thickness (m) and the
    crease stiffness (N·m/rad/m)."""

    material: str | None
    youngs_modulus: float | None
    poisson: float | None
    density: float | None
    strength: float | None
    thickness: float
    crease_stiffness: float | None


@dataclass(frozen=True)
class LoadParams:
    """``[loads]``: self-weight or not, the keys of :data:`LOADS_KEYS` in the user's units (snow
    and wind in kPa, a point load in N), the supports, the model's elements across each strip,
    the ``[[loads.case]]`` entries (SI; None: none listed), and what the verdict asks
    (:class:`curvefold.mechanics.Criteria`: the partial factors, the required buckling factor,
    the deflection limit in m)."""

    self_weight: bool
    snow: float
    snow_half: float
    snow_half_side: str
    wind: float
    wind_cp: float
    point_load: float
    supports: str
    gamma_g: float = _CRITERIA["gamma_g"].default
    gamma_q: float = _CRITERIA["gamma_q"].default
    gamma_m: float | None = _CRITERIA["gamma_m"].default
    buckling_safety: float = _CRITERIA["buckling_safety"].default
    deflection_limit: float | None = _CRITERIA["deflection_limit"].default
    across: int = ACROSS.default
    nonlinear: bool = False
    imperfection: float = IMPERFECTION.default
    case: tuple[LoadCase, ...] | None = None

    def criteria(self) -> Criteria:
        """What the verdict asks, from these keys (:class:`curvefold.mechanics.Criteria`)."""
        from ..mechanics import Criteria

        return Criteria(
            self.gamma_g, self.gamma_q, self.gamma_m, self.buckling_safety, self.deflection_limit
        )

    def cases(self) -> Loads:
        """The load cases these keys and entries make, SI: the self-weight, each case whose first
        key is not zero, then the listed ones.

        Examples
        --------
        >>> params = LoadParams(True, 0.5, 0.0, "end", 0.0, 1.0, 10.0, "pinned")
        >>> params.cases().describe()
        'self-weight + snow 0.5 kPa + 10 N at the apex'
        """
        given: dict[str, dict[str, Any]] = {}
        absent: set[str] = set()
        for key, (case, parameter) in LOADS_KEYS.items():
            spec = next(p for p in LOAD_CASES[case].parameters if p.name == parameter)
            value = getattr(self, key)
            if case not in given and not value:  # a case's first key, zero: no such case
                absent.add(case)
            if case not in absent:
                given.setdefault(case, {})[parameter] = (
                    value * spec.scale if isinstance(value, float) else value
                )
        made = tuple(LOAD_CASES[case](**values) for case, values in given.items())
        return Loads(((SelfWeight(),) if self.self_weight else ()) + made + (self.case or ()))


def check_material(values: dict, where: str) -> None:
    """Check a ``[material]`` section's values together, naming the default material when none is
    given.

    Either a named material or the user's own E, ν and density (and, optionally, a
    strength), never both; ``values`` is completed in place.

    Raises
    ------
    InputError
        One line starting with ``where`` (``"design.toml: [material] "``).
    """
    own = [k for k in _OWN if values.get(k) is not None]
    if values.get("material") is not None and own:
        raise InputError(
            f"{where}give material or your own values ({', '.join(own)}), not both",
            parameter=own[0],
        )
    if own:
        missing = [k for k in _NEEDED if values.get(k) is None]
        if missing:
            raise InputError(
                f"{where}your own material needs youngs_modulus, poisson and "
                f"density (missing: {', '.join(missing)}), or name one with material",
                parameter=missing[0],
            )
    elif values.get("material") is None:
        values["material"] = DEFAULT_MATERIAL


def material_alternatives(data: dict, given: set[str]) -> None:
    """A named material and the user's own values are alternatives: the one given by flags drops
    the other from the design's data."""
    section = data.get("material")
    if section is None:
        return
    if "material" in given:
        for key in _OWN:
            if key not in given:
                section.pop(key, None)
    elif given & set(_OWN):
        section.pop("material", None)


def magnification(displacement: float, size: float, *, share: float = 0.05) -> float:
    """A round factor (1, 2 or 5 × 10^k) that shows a displacement at about ``share`` of the
    structure's size.

    Examples
    --------
    >>> magnification(9.88e-5, 3.3), magnification(0.0, 3.3), magnification(1.0, 1.0)
    (1000.0, 1.0, 0.05)
    """
    if not displacement > 0:
        return 1.0
    target = share * size / displacement
    k = math.floor(math.log10(target))
    return max(m * 10.0**k for m in (1.0, 2.0, 5.0) if m * 10.0**k <= target * (1 + 1e-12))


@dataclass(frozen=True, eq=False)
class Loaded:
    """A built design under load: the mechanics' result and what is shown of it.

    Attributes
    ----------
    result : LoadResult
    material : MaterialParams
    loads : LoadParams
    supported : {"feet", "ends"}
        The feet of a vault, or both end sections of a tube or block.
    verdict : Verdict
        Whether it stands under the load combinations (:func:`curvefold.mechanics.assess`),
        each check with its estimated error.
    errors : dict
        The estimated relative error of every figure that depends on the mesh, from the
        model on half the elements across (:func:`curvefold.mechanics.figure_errors`);
        empty with one element across.
    collapse : Collapse or None
        The governing combination followed to collapse (``nonlinear``,
        :func:`curvefold.mechanics.collapse`); the verdict's stability check then takes the
        smaller of its collapse and linear factors.
    """

    result: LoadResult
    material: MaterialParams
    loads: LoadParams
    supported: str
    verdict: Verdict
    errors: Mapping[str, float | list[float]] = field(default_factory=dict)
    collapse: Collapse | None = None

    @property
    def size(self) -> float:
        """The structure's largest extent, m."""
        return self.result.structure.model.size

    @property
    def deflection_scale(self) -> float:
        """How much the pictures and the 3D model magnify the deflection (:func:`magnification`)."""
        return magnification(self.result.static.max_displacement, self.size)

    @property
    def mode_amplitude(self) -> float:
        """Largest displacement of a mode as the pictures and the 3D model show it, m: a round 5
        % of the size."""
        return magnification(1.0, self.size)

    def notes(self) -> list[str]:
        """What a reader must know to read the numbers (the supports, a buckling mode the samples
        do not resolve, and the verdict's notes: today's mesh, γ_M or no strength)."""
        r = self.result
        held = (
            "the feet (the end sections on the ground)"
            if self.supported == "feet"
            else "both end sections of every tube (t = 0 and t = 1)"
        )
        notes = [
            f"held at {held}, {r.supports.kind}; the model keeps {len(r.structure.samples)} "
            f"of the {r.structure.state.vertices.shape[1]} samples along each crease (the "
            "closest near the end sections)"
        ]
        if self._peak_on_supports():
            notes.append(
                "the largest stress is in an element on the supports, where a linear model's "
                "stress is singular at the supports' corners (it grows as the mesh is refined): "
                "it is the load the supports' detail must spread, not the sheet's own stress"
            )
        if not r.buckling_resolved:
            notes.append(
                "the buckling mode alternates from one sample to the next: the samples "
                "do not resolve it, and its factor is lower than the structure's; more samples "
                "find the structure's"
            )
        notes += list(self.verdict.notes)  # the mesh, γ_M or no strength
        error, figure = max(
            ((float(np.max(e, initial=0.0)), key) for key, e in self.errors.items()),
            default=(0.0, ""),
        )
        if error > ERROR_TOLERANCE:
            notes.append(
                f"the estimated error of {figure} is{error_text(error)[2:]}, above "
                f"{100 * ERROR_TOLERANCE:g} %: raise --across (now {self.loads.across})"
            )
        return notes

    def _peak_on_supports(self) -> bool:
        """Whether the largest surface stress is in a membrane with a supported corner."""
        static = self.result.static
        if not len(static.surface_stress):
            return False
        corners = np.asarray(self.result.structure.model.membranes)[
            int(np.argmax(static.surface_stress))
        ]
        return bool(static.fixed[corners[corners >= 0]].any())

    def to_dict(self) -> dict:
        """The result's stable keys (:meth:`curvefold.mechanics.LoadResult.to_dict`) and what
        loads and holds it."""
        r = self.result
        mat = r.structure.material
        return (
            r.to_dict()
            | self.verdict.to_dict()
            | {
                "material": mat.name,
                "sheet": {
                    "youngs_modulus": mat.youngs_modulus,
                    "poisson": mat.poisson,
                    "density": mat.density,
                    "strength": mat.strength,
                    "source": mat.source,
                    "partial_factor": mat.partial_factor,
                    "partial_factor_source": mat.partial_factor_source,
                },
                "loads": {
                    "self_weight": self.loads.self_weight,
                    "snow_kpa": self.loads.snow,
                    "point_load": self.loads.point_load,
                    "cases": [case.to_dict() for case in r.loads.cases],
                    "described": [case.describe() for case in r.loads.cases],
                },
                "supported": self.supported,
                "reactions_by_end": self.reactions_by_end(),
                "errors": {
                    key: [_finite(e) for e in value] if isinstance(value, list) else _finite(value)
                    for key, value in self.errors.items()
                },
                "deflection_scale": self.deflection_scale,
                "mode_amplitude": self.mode_amplitude,
                "notes": self.notes(),
            }
            | ({} if self.collapse is None else {"collapse": self.collapse.to_dict()})
        )

    def reactions_by_end(self) -> dict[str, list[float]]:
        """The support reactions summed over each end, t = 0 and t = 1, [x, y, z] N: an arch's
        horizontal thrust, equal and opposite at its two ends."""
        sm, reactions = self.result.structure, self.result.static.reactions
        n = sm.state.vertices.shape[1]
        return {
            end: reactions[sm.node_sample == s].sum(axis=0).tolist()
            for end, s in (("t = 0", 0), ("t = 1", n - 1))
        }

    def lines(self) -> list[str]:
        """The result in a few lines for the terminal: what loads it, the load and reactions of
        each combination, the checks, then the characteristic load's figures (the weight among
        them). The verdict's own line (:meth:`curvefold.mechanics.Verdict.headline`) comes
        before them."""
        d = self.to_dict()
        use = d["utilisation"]
        factor = d["buckling_factor"]
        v = self.verdict

        def pm(key: str, *, frequency: bool = False) -> str:
            """`` ± x %``: the figure's estimated error (a list's largest; a frequency's is half
            its eigenvalue's)."""
            if key not in self.errors:
                return ""
            error = float(np.max(self.errors[key], initial=0.0))
            return error_text(error / 2 if frequency else error)

        combined = [
            (
                c.name,
                f"load {_vector(t, t)} N, reactions {_vector(r, t)} N",
            )
            for c, t, r in zip(v.combinations, v.totals, v.reactions, strict=True)
        ]
        checks = [(f"{c.name}", _check_words(c)) for c in v.checks]
        rows = [
            *combined,
            *checks,
            ("total_weight", f"{d['total_weight']:.6g} N"),
            (
                "reactions",
                "["
                + ", ".join(
                    f"{v:.6g}" for v in _rounded(d["reactions"], max(map(abs, d["applied_load"])))
                )
                + "] N (x, y, z)",
            ),
            ("max_displacement", f"{d['max_displacement']:.4g} m{pm('max_displacement')}"),
            (
                "max_stress",
                f"{d['max_stress']:.4g} Pa{pm('max_stress')}"
                + ("" if use is None else f" ({use:.3g} of the strength)"),
            ),
            (
                "buckling_factor",
                "none: the load only stiffens it"
                if factor is None
                else f"{factor:.4g}{pm('buckling_factor')}"
                + ("" if d["buckling_resolved"] else " (not resolved at these samples)"),
            ),
            *([] if self.collapse is None else [("collapse_factor", self.collapse.text())]),
            ("fold_mode_gap", f"{d['fold_mode_gap']:.4g}{pm('fold_mode_gap')}"),
            ("soft_modes", str(d["soft_modes"])),
            (
                "modes",
                ", ".join(f"{v:.4g}" for v in d["modes"])
                + " rad²/s² ("
                + ", ".join(f"{f:.3g}" for f in d["frequencies"])
                + f" Hz){pm('modes')}",
            ),
            (
                "supported_modes",
                ", ".join(f"{f:.3g}" for f in d["supported_frequencies"])
                + f" Hz (on its supports){pm('supported_modes', frequency=True)}",
            ),
        ]
        head = (
            f"  under load         {d['material']} {d['thickness'] * 1e3:g} mm, "
            f"{self._load_words()}"
        )
        return (
            [head]
            + [f"  {k:<18} {text}" for k, text in rows]
            + [f"  note: {n}" for n in d["notes"]]
        )

    def _load_words(self) -> str:
        return f"{self.result.loads.describe()}, {self.loads.supports} at the {self.supported}"

    def morph_targets(
        self, structure: Structure, keep: Sequence[np.ndarray] | None = None, *, modes: int = 3
    ) -> dict[str, np.ndarray]:
        """The deflected shape and the first modes as named morph targets of the GLB.

        Displacements (V, 3) in metres of the vertices of ``structure.state().mesh(keep=keep)``
        (:func:`curvefold.io.write_3d`): the deflection magnified by
        :attr:`deflection_scale`, each mode at :attr:`mode_amplitude`.
        """
        r, sm = self.result, self.result.structure
        topology = structure.topology(keep=keep)
        at = lambda values: topology.coords(sm.interpolate(values))  # noqa: E731
        out = {
            f"deflection × {self.deflection_scale:g}": self.deflection_scale
            * at(r.static.displacements)
        }
        c = self.collapse
        if c is not None:  # the imperfect shape at collapse, moved from the shape as built
            moved = c.shape + c.path.displacements[c.at_collapse]
            scale = magnification(float(np.linalg.norm(moved, axis=1).max()), self.size)
            out[f"collapse at {c.factor:.4g} × {c.combination} × {scale:g}"] = scale * at(moved)
        for k in range(min(modes, len(r.modes.eigenvalues))):
            out[f"mode {k + 1} ({r.modes.frequencies[k]:.3g} Hz)"] = self.mode_amplitude * at(
                r.modes.shapes[k]
            )
        return out


def _sheet(params: MaterialParams):
    from ..mechanics import Material

    if params.material is not None:
        return MATERIALS[params.material]
    own = params.youngs_modulus, params.poisson, params.density
    if None in own:  # check_material asks for all three
        raise InputError("your own material needs youngs_modulus, poisson and density")
    E, nu, rho = cast("tuple[float, float, float]", own)
    return Material.from_values(E, nu, rho, params.strength)


def analyse(
    structure: Structure,
    material: MaterialParams | None,
    loads: LoadParams | None,
    *,
    supported: str,
) -> Loaded:
    """The mechanics of a vault, tube or block at its design angle under a design's material and
    loads (their defaults where it gives none), held at its ``supported`` ("feet" or "ends").

    Raises
    ------
    InputError
        What the mechanics refuses (no load, a structure still a mechanism under its
        supports), in one line.
    """
    from ..mechanics import Supports, analyse_load, assess, check_errors, figure_errors

    material = material or MaterialParams(**_defaults(MATERIAL_SECTION, material=DEFAULT_MATERIAL))
    loads = loads or LoadParams(**_defaults(LOADS_SECTION))
    cases, criteria = loads.cases(), loads.criteria()

    def at(across: int) -> tuple[LoadResult, Verdict]:
        result = analyse_load(
            structure,
            _sheet(material),
            material.thickness,
            cases,
            Supports(loads.supports, at=supported),  # type: ignore[arg-type]
            crease_stiffness=material.crease_stiffness,
            across=across,
        )
        return result, assess(result, criteria)

    fine, coarse = loads.across, loads.across // 2
    result, verdict = at(fine)
    errors: dict = {}
    if coarse:
        before, before_verdict = at(coarse)
        verdict = check_errors(before_verdict, verdict, (coarse, fine))
        errors = figure_errors(before, result)
    if not loads.nonlinear:
        return Loaded(result, material, loads, supported, verdict, errors)
    from ..mechanics import collapse
    from ..mechanics._collapse import judged

    path = collapse(result, verdict, imperfection=loads.imperfection, stop=PROGRESS.get())
    return Loaded(result, material, loads, supported, judged(verdict, path), errors, path)


def atlas_load(
    material: MaterialParams, loads: LoadParams, *, samples: int, across: int | None = None
) -> AtlasLoad:
    """The mechanics of every design of an atlas (:class:`curvefold.mechanics.AtlasLoad`) under a
    design's ``[material]`` and ``[loads]``, as :func:`analyse` reads them, on a model of
    ``samples`` samples along each crease and ``across`` elements across each strip (default
    the ``[loads]``'s).

    Examples
    --------
    >>> material = MaterialParams(**_defaults(MATERIAL_SECTION, material="aluminium"))
    >>> loads = LoadParams(**_defaults(LOADS_SECTION) | {"snow": 0.5})
    >>> load = atlas_load(material, loads, samples=40)
    >>> load.material.name, load.loads.describe(), load.samples
    ('aluminium', 'self-weight + snow 0.5 kPa', 41)
    """
    from ..mechanics import AtlasLoad

    return AtlasLoad(
        _sheet(material),
        material.thickness,
        loads.cases(),
        loads.supports,
        loads.criteria(),
        material.crease_stiffness,
        loads.across if across is None else across,
        samples,
    )


def _defaults(specs: Sequence[Spec], **given: Any) -> dict:
    return {spec.name: spec.default for spec in specs} | given
