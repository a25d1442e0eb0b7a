"""curvefold: rigid-foldable curved-crease tubes, cellular blocks and deployable vaults.

Data flows one way: a :class:`SpaceCurve` (from curvature and torsion) → a :class:`Crease`
(fold angle and rulings) → a :class:`Lattice` (widths and the (u, v) family of creases) →
a :class:`Structure` (which cells) → a :class:`State` at a fold angle → meshes, files and
pictures. :mod:`curvefold.measure` certifies each stage with numbers.
"""

from .errors import ConvergenceError, CurvefoldError, InputError, RegressionError
from .curve import SpaceCurve
from .crease import Crease
from .lattice import Lattice, RegressionDomain
from .structure import State, Structure
from .mesh import Mesh

__version__ = "0.1.0"

__all__ = [
    "CurvefoldError",
    "InputError",
    "RegressionError",
    "ConvergenceError",
    "SpaceCurve",
    "Crease",
    "Lattice",
    "RegressionDomain",
    "Structure",
    "State",
    "Mesh",
]
