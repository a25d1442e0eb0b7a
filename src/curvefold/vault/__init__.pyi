"""The names :mod:`curvefold.vault` loads on first use, for type checkers and editors."""

from ._arch import A_MAX as A_MAX
from ._arch import ArchRoot as ArchRoot
from ._arch import GeneralArch as GeneralArch
from ._arch import HarmonicTorsion as HarmonicTorsion
from ._arch import proportion_change as proportion_change
from ._arch import solve_general_arch as solve_general_arch
from ._arch import solve_panel_arch as solve_panel_arch
from ._arch import solve_symmetric_arch as solve_symmetric_arch
from ._assembly import Vault as Vault
from ._assembly import VaultDesign as VaultDesign
from ._atlas import Atlas as Atlas
from ._atlas import AtlasGrid as AtlasGrid
from ._atlas import Sketch as Sketch
from ._atlas import evaluate_design as evaluate_design
from ._paper import paper_comparison as paper_comparison
from ._sweep import run_atlas as run_atlas
from ._sweep import sweep as sweep
from ._targets import TargetFit as TargetFit
from ._targets import fit_targets as fit_targets
from ._tubes import DEFAULT_TUBES_CAP as DEFAULT_TUBES_CAP
from ._tubes import MAX_TUBES_SEARCH as MAX_TUBES_SEARCH
from ._tubes import max_tubes as max_tubes

__all__ = [
    "A_MAX",
    "ArchRoot",
    "GeneralArch",
    "HarmonicTorsion",
    "proportion_change",
    "solve_general_arch",
    "solve_panel_arch",
    "solve_symmetric_arch",
    "DEFAULT_TUBES_CAP",
    "MAX_TUBES_SEARCH",
    "Vault",
    "VaultDesign",
    "max_tubes",
    "Atlas",
    "AtlasGrid",
    "Sketch",
    "evaluate_design",
    "run_atlas",
    "sweep",
    "TargetFit",
    "fit_targets",
    "paper_comparison",
]
