"""curvefold: rigid-foldable curved-crease tubes, cellular blocks and deployable vaults.

Data flows one way: a :class:`SpaceCurve` (from curvature and torsion) → a :class:`Crease`
(fold angle and rulings) → a :class:`Lattice` (curve 1 at one fold angle with its
:class:`Pattern`: widths, regression domain and all else folding keeps) → a
:class:`Structure` (which cells) → a :class:`State` at a fold angle → meshes, files and
pictures. :mod:`curvefold.analysis._measure` certifies each stage with numbers.

The names below are imported when first used (``from curvefold import Crease`` imports
the geometry, not the file writers or SciPy), so the command line starts quickly.
"""

from .kernel._exports import lazy_exports as _lazy_exports

# the one place it is set (pyproject.toml reads it)
from .kernel._version import VERSION

__version__ = VERSION  # the one place it is set (pyproject.toml reads it)

# The public names by package, imported when first asked for (kernel.exports); type
# checkers and editors read them from __init__.pyi.
__all__, _getattr, _dir = _lazy_exports(
    __name__,
    {
        "kernel": [
            "CurvefoldError",
            "InputError",
            "RegressionError",
            "ConvergenceError",
            "InternalError",
        ],
        "geometry": [
            "SpaceCurve",
            "Crease",
            "Lattice",
            "Pattern",
            "RegressionDomain",
            "Structure",
            "State",
            "Mesh",
        ],
    },
)
__all__ = [*__all__, "measure"]


def __dir__() -> list[str]:
    return sorted({*_dir(), "measure", "__version__"})


def __getattr__(name: str):
    if name == "measure":  # a module
        from .analysis import _measure as measure

        return measure
    return _getattr(name)
