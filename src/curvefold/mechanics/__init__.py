"""Mechanics: the bar-and-hinge model of a structure at a fold angle, under load, its modes and soft
modes.

Will a deployed vault stand? The model (Filipov, Liu, Tachi, Schenk and Paulino 2017; Liu
and Paulino 2017; Woodruff and Filipov 2020 for curved creases) puts on every state
curvefold builds

* **bars** on the mesh's edges and triangle diagonals: each membrane triangle's exact
  plane-stress stiffness (E, ν, t) written in its three bars' elongations;
* **hinges** on the edges between two triangles: creases (fold and seam edges, a
  rotational stiffness per length k_c), the sheet bending about a ruling and the twist of
  a ruling quad or panel (from D = E t³ / 12(1 − ν²));

with welded seams and bonded tubes sharing their nodes. SI units throughout: metres,
newtons, pascals, kilograms; z up, the ground z = 0; g = 9.80665 m/s².

From a structure to a result in one call: :func:`analyse_load`. The parts:
:class:`StructureModel` (the model of a state), :class:`BarHingeModel` (any triangulated
sheet, a Miura-ori cell or a single bar), :class:`Loads` and :class:`Supports`,
:func:`static_response`, :func:`free_modes` (the fold-mode gap), :func:`buckling`,
:func:`soft_modes` (the inextensional motions: the paper's conjecture measured). The
load cases are classes registered in :data:`LOAD_CASES` (:class:`SelfWeight`,
:class:`Snow`, :class:`HalfSnow`, :class:`Wind`, :class:`ZonedWind`, :class:`PointLoad`),
summed by
:class:`Loads`; will it stand: :func:`assess` checks a result under the load combinations
of EN 1990 (:class:`Combination`, :func:`combinations`) against :class:`Criteria` and
gives a :class:`Verdict` of :class:`Check` values; :class:`AtlasLoad` does both for every vault
of a design atlas, on a coarse model. The
materials are :data:`MATERIALS` with their sources, or :meth:`Material.from_values`.

The materials, loads and supports and their checks load at once (they need no SciPy:
design files and flags are checked with them); the model and its solvers load when one
of their names is first used.
"""

import importlib

from . import _across, _collapse, _convergence, _loadcase, _materials, _supports, _verdict
from ._cases import HalfSnow, PointLoad, SelfWeight, Snow, Wind, ZonedWind
from ._combinations import Combination, combinations
from ._convergence import check_errors, figure_errors
from ._loadcase import LoadCase, Parameter
from ._loads import Loads
from ._materials import Material, material
from ._supports import Supports
from ._verdict import Check, Criteria, Verdict, assess, error_text

#: The check of --nonlinear's imperfection, a fraction of the span (:func:`collapse`).
IMPERFECTION = _collapse.IMPERFECTION
#: The check of --nonlinear, whether the verdict follows its combination to collapse.
NONLINEAR = _collapse.NONLINEAR

#: Standard gravity, m/s².
G = _loadcase.G
#: Named sheet materials (:class:`Material`), each with its source.
MATERIALS = _materials.MATERIALS
#: The name of a material of :data:`MATERIALS`, checked.
MATERIAL = _materials.MATERIAL
#: The checks of a user's material: Young's modulus, Poisson's ratio, density, strength.
MATERIAL_SPECS = _materials.MATERIAL_SPECS
#: The check of a sheet's thickness (m).
THICKNESS = _materials.THICKNESS
#: The check of a crease stiffness per length (N·m/rad/m).
CREASE_STIFFNESS = _materials.CREASE_STIFFNESS
#: The check of the elements across each ruling strip or panel of a model.
ACROSS = _across.ACROSS
#: The estimated relative error of a printed figure above which its mesh is called too coarse.
ERROR_TOLERANCE = _convergence.TOLERANCE
#: Every load case class by name (:class:`LoadCase`): a new case is one class registered there.
LOAD_CASES = _loadcase.LOAD_CASES
#: The check of how the supported nodes are held ("pinned" or "roller").
SUPPORTS = _supports.SUPPORTS
#: The checks of :class:`Criteria`'s fields: γ_G, γ_Q, γ_M, the required buckling factor and the
#: deflection limit.
CRITERIA_SPECS = _verdict.CRITERIA_SPECS

#: The module of every name loaded on first use.
_LAZY = {
    "analyse_load": "_analysis",
    "AtlasLoad": "_atlas_load",
    "LoadResult": "_analysis",
    "BarHingeModel": "_model",
    "StructureModel": "_structures",
    "model_samples": "_structures",
    "StaticResult": "_response",
    "static_response": "_response",
    "Buckling": "_response",
    "buckling": "_response",
    "Modes": "_modes",
    "free_modes": "_modes",
    "correlation": "_modes",
    "span_correlation": "_modes",
    "SoftModes": "_softmodes",
    "soft_modes": "_softmodes",
    "conjecture_counts": "_softmodes",
    "follow_load": "_path",
    "LoadPath": "_path",
    "PathError": "_path",
    "deploy": "_deploy",
    "Deployment": "_deploy",
    "DeployError": "_deploy",
    "Collapse": "_collapse",
    "collapse": "_collapse",
}

__all__ = [
    "analyse_load",
    "AtlasLoad",
    "LoadResult",
    "Material",
    "MATERIALS",
    "MATERIAL",
    "MATERIAL_SPECS",
    "THICKNESS",
    "CREASE_STIFFNESS",
    "ACROSS",
    "LOAD_CASES",
    "SUPPORTS",
    "material",
    "BarHingeModel",
    "StructureModel",
    "model_samples",
    "Loads",
    "LoadCase",
    "Parameter",
    "SelfWeight",
    "Snow",
    "HalfSnow",
    "Wind",
    "ZonedWind",
    "PointLoad",
    "Supports",
    "G",
    "StaticResult",
    "static_response",
    "Modes",
    "free_modes",
    "correlation",
    "span_correlation",
    "Buckling",
    "buckling",
    "SoftModes",
    "soft_modes",
    "conjecture_counts",
    "Combination",
    "combinations",
    "Criteria",
    "CRITERIA_SPECS",
    "Check",
    "Verdict",
    "assess",
    "error_text",
    "figure_errors",
    "check_errors",
    "ERROR_TOLERANCE",
    "follow_load",
    "LoadPath",
    "PathError",
    "deploy",
    "Deployment",
    "DeployError",
    "Collapse",
    "collapse",
    "IMPERFECTION",
    "NONLINEAR",
]


def _public(value):
    """A public name is documented, and pickled, as this package's: its module is private."""
    if getattr(value, "__module__", "").startswith(__name__ + "._"):
        value.__module__ = __name__
    return value


def __getattr__(name: str):
    if name == "__test__":  # asked for by the doctest finder only
        return _examples()
    if name not in _LAZY:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = globals()[name] = _public(
        getattr(importlib.import_module(f"{__name__}.{_LAZY[name]}"), name)
    )
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))


for _name in (
    "Loads",
    "LoadCase",
    "Parameter",
    "SelfWeight",
    "Snow",
    "HalfSnow",
    "Wind",
    "ZonedWind",
    "PointLoad",
    "Supports",
    "Material",
    "material",
    "Combination",
    "combinations",
    "Criteria",
    "Check",
    "Verdict",
    "assess",
    "error_text",
    "figure_errors",
    "check_errors",
):
    _public(globals()[_name])


def _examples() -> dict:
    """The examples of the public names and of the public classes' methods, for the doctests.

    The doctest finder takes a function or method for its module only, which is this one
    (:func:`_public`) while its globals are its private module's, and finds this module's
    names in its namespace only once they have been imported: they are listed here to run.
    """
    names = {name: __getattr__(name) if name in _LAZY else globals()[name] for name in __all__}
    methods = {
        f"{name}.{attr}": getattr(value, "__func__", value)
        for name, cls in names.items()
        if isinstance(cls, type)
        for attr, value in vars(cls).items()
        if not attr.startswith("_")
        and callable(getattr(value, "__func__", value))
        and getattr(value, "__doc__", None)
    }
    return {name: value for name, value in names.items() if callable(value)} | methods
