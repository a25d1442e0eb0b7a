"""curvefold: rigid-foldable curved-crease tubes, cellular blocks and deployable vaults.

Data flows one way: a :class:`SpaceCurve` (from curvature and torsion) → a :class:`Crease`
(fold angle and rulings) → a :class:`Lattice` (curve 1 at one fold angle with its
:class:`Pattern`: widths, regression domain and all else folding keeps) → a
:class:`Structure` (which cells) → a :class:`State` at a fold angle → meshes, files and
pictures. :mod:`curvefold.analysis.measure` certifies each stage with numbers.
"""

from importlib.metadata import version

from .analysis import measure
from .geometry.crease import Crease
from .geometry.curve import SpaceCurve
from .geometry.lattice import Lattice, Pattern, RegressionDomain
from .geometry.mesh import Mesh
from .geometry.structure import State, Structure
from .kernel.errors import ConvergenceError, CurvefoldError, InputError, InternalError, RegressionError

__version__ = version("curvefold")  # one source: the version in pyproject.toml

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
