"""The names of :mod:`curvefold.mechanics`, most loaded on first use, for type checkers and
editors."""

from ._across import ACROSS as ACROSS
from ._analysis import LoadResult as LoadResult
from ._analysis import analyse_load as analyse_load
from ._atlas_load import AtlasLoad as AtlasLoad
from ._cases import HalfSnow as HalfSnow
from ._cases import PointLoad as PointLoad
from ._cases import SelfWeight as SelfWeight
from ._cases import Snow as Snow
from ._cases import Wind as Wind
from ._cases import ZonedWind as ZonedWind
from ._collapse import IMPERFECTION as IMPERFECTION
from ._collapse import NONLINEAR as NONLINEAR
from ._collapse import Collapse as Collapse
from ._collapse import collapse as collapse
from ._combinations import Combination as Combination
from ._combinations import combinations as combinations
from ._convergence import TOLERANCE as ERROR_TOLERANCE
from ._convergence import check_errors as check_errors
from ._convergence import figure_errors as figure_errors
from ._deploy import DeployError as DeployError
from ._deploy import Deployment as Deployment
from ._deploy import deploy as deploy
from ._loadcase import LOAD_CASES as LOAD_CASES
from ._loadcase import G as G
from ._loadcase import LoadCase as LoadCase
from ._loadcase import Parameter as Parameter
from ._loads import Loads as Loads
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
from ._path import LoadPath as LoadPath
from ._path import PathError as PathError
from ._path import follow_load as follow_load
from ._response import Buckling as Buckling
from ._response import StaticResult as StaticResult
from ._response import buckling as buckling
from ._response import static_response as static_response
from ._softmodes import SoftModes as SoftModes
from ._softmodes import conjecture_counts as conjecture_counts
from ._softmodes import soft_modes as soft_modes
from ._structures import StructureModel as StructureModel
from ._structures import model_samples as model_samples
from ._supports import SUPPORTS as SUPPORTS
from ._supports import Supports as Supports
from ._verdict import CRITERIA_SPECS as CRITERIA_SPECS
from ._verdict import Check as Check
from ._verdict import Criteria as Criteria
from ._verdict import Verdict as Verdict
from ._verdict import assess as assess
from ._verdict import error_text as error_text

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
