"""The names :mod:`curvefold` loads on first use, for type checkers and editors."""

from .analysis import _measure as measure
from .geometry import Crease as Crease
from .geometry import Lattice as Lattice
from .geometry import Mesh as Mesh
from .geometry import Pattern as Pattern
from .geometry import RegressionDomain as RegressionDomain
from .geometry import SpaceCurve as SpaceCurve
from .geometry import State as State
from .geometry import Structure as Structure
from .kernel import ConvergenceError as ConvergenceError
from .kernel import CurvefoldError as CurvefoldError
from .kernel import InputError as InputError
from .kernel import InternalError as InternalError
from .kernel import RegressionError as RegressionError

__version__: str

__all__ = [
    "CurvefoldError",
    "InputError",
    "RegressionError",
    "ConvergenceError",
    "InternalError",
    "SpaceCurve",
    "Crease",
    "Lattice",
    "Pattern",
    "RegressionDomain",
    "Structure",
    "State",
    "Mesh",
    "measure",
]
