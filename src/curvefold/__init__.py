"""curvefold: rigid-foldable curved-crease tubes, cellular blocks and deployable vaults."""

from .errors import ConvergenceError, CurvefoldError, InputError, RegressionError
from .curve import SpaceCurve
from .mesh import Mesh

__version__ = "0.1.0"

__all__ = [
    "CurvefoldError",
    "InputError",
    "RegressionError",
    "ConvergenceError",
    "SpaceCurve",
    "Mesh",
]
