"""The names of :mod:`curvefold.mechanics`, most loaded on first use, for type checkers and
editors."""

from ._across import ACROSS as ACROSS
from ._analysis import LoadResult as LoadResult
from ._analysis import analyse_load as analyse_load
from ._loads import LOAD_CASES as LOAD_CASES
from ._loads import SUPPORTS as SUPPORTS
from ._loads import G as G
from ._loads import HalfSnow as HalfSnow
from ._loads import LoadCase as LoadCase
from ._loads import Loads as Loads
from ._loads import Parameter as Parameter
from ._loads import PointLoad as PointLoad
from ._loads import SelfWeight as SelfWeight
from ._loads import Snow as Snow
from ._loads import Supports as Supports
from ._loads import Wind as Wind
from ._loads import ZonedWind as ZonedWind
from ._materials import CREASE_STIFFNESS as CREASE_STIFFNESS
from ._materials import MATERIAL as MATERIAL
from ._materials import MATERIAL_SPECS as MATERIAL_SPECS
from ._materials import MATERIALS as MATERIALS
from ._materials import THICKNESS as THICKNESS
from ._materials import Material as Material
from ._materials import material as material
from ._model import BarHingeModel as BarHingeModel
from ._modes import Modes as Modes
from ._modes import correlation as correlation
from ._modes import free_modes as free_modes
from ._modes import span_correlation as span_correlation
from ._response import Buckling as Buckling
from ._response import StaticResult as StaticResult
from ._response import buckling as buckling
from ._response import static_response as static_response
from ._softmodes import SoftModes as SoftModes
from ._softmodes import conjecture_counts as conjecture_counts
from ._softmodes import soft_modes as soft_modes
from ._structures import StructureModel as StructureModel
from ._structures import model_samples as model_samples

__all__ = [
    "analyse_load",
    "LoadResult",
    "Material",
    "MATERIALS",
    "MATERIAL",
    "MATERIAL_SPECS",
    "THICKNESS",
    "CREASE_STIFFNESS",
    "ACROSS",
    "LOAD_CASES",
    "LoadCase",
    "Parameter",
    "SelfWeight",
    "Snow",
    "HalfSnow",
    "Wind",
    "ZonedWind",
    "PointLoad",
    "SUPPORTS",
    "material",
    "BarHingeModel",
    "StructureModel",
    "model_samples",
    "Loads",
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
]
