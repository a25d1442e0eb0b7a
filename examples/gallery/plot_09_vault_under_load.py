"""
The paper's vault under its own weight
======================================

Will the deployed vault stand? The bar-and-hinge model of the vault at its design angle
(:mod:`curvefold.mechanics`): polypropylene 1 mm thick on a vault of radius 1 m, its feet
(the end sections on the ground) pinned, under its own weight, on the 801 samples
``curvefold load`` builds. The first free mode is its folding motion; how much stiffer the
next one is, the fold-mode gap, is what the tubes' virtual thickness buys.
"""

# %%
import numpy as np

from curvefold.figures._mechanics import plot_deflection, plot_modes
from curvefold.mechanics import analyse_load
from curvefold.vault import Vault

vault = Vault.from_design(a=0.3, p_xy=0.75, samples=801)
result = analyse_load(vault, "polypropylene", 1e-3)
summary = result.to_dict()
# rounding shown as 0
reactions = np.where(
    np.abs(summary["reactions"]) < 1e-9 * summary["total_weight"], 0.0, summary["reactions"]
)
print(
    f"weight {summary['total_weight']:.1f} N, carried by the feet: reactions "
    f"{reactions.round(4).tolist()} N"
)
print(
    f"largest deflection {summary['max_displacement'] * 1e6:.1f} µm, largest stress "
    f"{summary['max_stress'] / 1e3:.1f} kPa ({summary['utilisation']:.2%} of the strength)"
)
print(
    f"buckling factor {summary['buckling_factor']:.0f}; fold-mode gap "
    f"{summary['fold_mode_gap']:.2f}; first mode against the rigid folding: correlation "
    f"{summary['fold_mode_correlation']:.3f}; soft modes {summary['soft_modes']}"
)

# %%
# The deflected vault, its displacement magnified 1,000 times and coloured by its size: the
# picture of the report's section *Under load*.
deflection = plot_deflection(result, magnification=1000)

# %%
# The three lowest free modes, each at a largest displacement of 0.1 m: the folding motion
# first, then how the vault bends.
modes = plot_modes(result, amplitude=0.1)
