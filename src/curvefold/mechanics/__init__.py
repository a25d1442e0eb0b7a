"""Mechanics: the bar-and-hinge model of a structure at a fold angle, under load, its modes and soft modes.

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
materials are :data:`MATERIALS` with their sources, or :meth:`Material.from_values`.
"""

from . import _loads, _materials
from ._analysis import LoadResult, analyse_load
from ._loads import Loads, Supports
from ._materials import Material, material
from ._model import BarHingeModel
from ._modes import Modes, correlation, free_modes
from ._response import Buckling, StaticResult, buckling, static_response
from ._softmodes import SoftModes, conjecture_counts, soft_modes
from ._structures import StructureModel

#: Standard gravity, m/s².
G = _loads.G
#: Named sheet materials (:class:`Material`), each with its source.
MATERIALS = _materials.MATERIALS
#: The checks of a user's material: Young's modulus, Poisson's ratio, density, strength.
MATERIAL_SPECS = _materials.MATERIAL_SPECS
#: The check of a sheet's thickness (m).
THICKNESS = _materials.THICKNESS
#: The check of a crease stiffness per length (N·m/rad/m).
CREASE_STIFFNESS = _materials.CREASE_STIFFNESS
#: The checks of the loads: snow (Pa on the projected area), point load (N).
LOAD_SPECS = _loads.LOAD_SPECS

__all__ = [
    "analyse_load",
    "LoadResult",
    "Material",
    "MATERIALS",
    "MATERIAL_SPECS",
    "THICKNESS",
    "CREASE_STIFFNESS",
    "LOAD_SPECS",
    "material",
    "BarHingeModel",
    "StructureModel",
    "Loads",
    "Supports",
    "G",
    "StaticResult",
    "static_response",
    "Modes",
    "free_modes",
    "correlation",
    "Buckling",
    "buckling",
    "SoftModes",
    "soft_modes",
    "conjecture_counts",
]

# The public names are documented, and pickled, as this package's: their modules are private.
for _name in __all__:
    if getattr(globals()[_name], "__module__", "").startswith(__name__ + "._"):
        globals()[_name].__module__ = __name__

# The doctest finder takes a method for its class's module only, which is now this one while
# the method's globals are its private module's: the methods' examples are listed here to run.
__test__ = {
    f"{_name}.{_attr}": getattr(_value, "__func__", _value)
    for _name in __all__ if isinstance(globals()[_name], type)
    for _attr, _value in vars(globals()[_name]).items()
    if not _attr.startswith("_") and callable(getattr(_value, "__func__", _value)) and getattr(_value, "__doc__", None)
}
