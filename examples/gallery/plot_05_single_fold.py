"""
A single curved fold from its crease pattern
============================================

A crease pattern gives a planar crease of curvature κ_2D and the angles β_L, β_R of the
rulings on its two sides. Folding it integrates the corrected Eqs. (3)–(4): the fold
angle α(s) and the torsion follow, and κ = κ_2D / cos α. This is the design of
``examples/single-fold.toml`` (``curvefold crease examples/single-fold.toml``).
"""

# %%
import numpy as np

from curvefold import Crease, measure
from curvefold.figures import plot_crease

crease = Crease.from_pattern(
    0.5,  # κ_2D, per model unit
    lambda s: 80 + 10 * np.sin(np.pi * s / 3),  # β_L(s), degrees
    lambda s: 100 - 5 * np.sin(np.pi * s / 3),  # β_R(s), degrees
    3.0,  # length
    fold_angle=60.0,  # 2α at s = 0, degrees
    samples=301,
)
two_alpha = 2 * np.degrees(crease.alpha(crease.s))
print(f"2α runs from {two_alpha[0]:.1f}° to {two_alpha[-1]:.1f}° along the crease")
print(
    "developability: the tangent planes turn along the rulings by at most "
    f"{measure.developability_residual(crease):.1e} per unit length"
)

# %%
# Left, the folded crease and the developable surfaces on both sides along its rulings;
# right, its curvature and torsion, the fold angle and the ruling angles along it.
fig = plot_crease(crease)
