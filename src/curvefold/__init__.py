"""curvefold: rigid-foldable curved-crease tubes, cellular blocks and deployable vaults.

Data flows one way: a :class:`SpaceCurve` (from curvature and torsion) → a :class:`Crease`
(fold angle and rulings) → a :class:`Lattice` (curve 1 at one fold angle with its
:class:`Pattern`: widths, regression domain and all else folding keeps) → a
:class:`Structure` (which cells) → a :class:`State` at a fold angle → meshes, files and
pictures. :mod:`curvefold.analysis.measure` certifies each stage with numbers.

The names below are imported when first used (``from curvefold import Crease`` imports
the geometry, not the file writers or SciPy), so the command line starts quickly.
"""

from typing import TYPE_CHECKING

from .kernel.lazy import lazy_exports

#: Each public name -> the module that defines it.
_EXPORTS = {
    "CurvefoldError": ".kernel.errors",
    "InputError": ".kernel.errors",
    "RegressionError": ".kernel.errors",
    "ConvergenceError": ".kernel.errors",
    "InternalError": ".kernel.errors",
    "SpaceCurve": ".geometry.curve",
    "Crease": ".geometry.crease",
    "Lattice": ".geometry.lattice",
    "Pattern": ".geometry.lattice",
    "RegressionDomain": ".geometry.lattice",
    "Structure": ".geometry.structure",
    "State": ".geometry.structure",
    "Mesh": ".geometry.mesh",
    "measure": ".analysis.measure",
}
__all__ = list(_EXPORTS)

_getattr, __dir__ = lazy_exports(__name__, _EXPORTS)


def __getattr__(name: str):
    if name == "__version__":  # one source: the version in pyproject.toml, read when asked
        from importlib.metadata import version

        globals()["__version__"] = version("curvefold")
        return globals()["__version__"]
    return _getattr(name)


if TYPE_CHECKING:  # the same names, for type checkers and editors
    from .analysis import measure
    from .geometry.crease import Crease
    from .geometry.curve import SpaceCurve
    from .geometry.lattice import Lattice, Pattern, RegressionDomain
    from .geometry.mesh import Mesh
    from .geometry.structure import State, Structure
    from .kernel.errors import ConvergenceError, CurvefoldError, InputError, InternalError, RegressionError
