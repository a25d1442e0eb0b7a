"""
The vault and its folding motion (the paper's Fig. 09)
======================================================

The composite vault of the paper: torsion ``τ = a κ0 sin(2π s / s0)`` with a = 0.3,
section proportion p_xy = 0.75 at the feet, designed at 2α = 90°, with as many tubes as
the regression domain allows. Solving the arch condition (Eq. 20) exactly gives
κ0·s0 = 3.16571746805, not the paper's 3.305 (see the errata).
"""

# %%
from curvefold.figures import plot_motion_strip, plot_vault
from curvefold.vault import Vault

vault = Vault.from_design(a=0.3, p_xy=0.75)
print(f"κ0·s0 = {vault.kappa0_s0:.11f}")
print(
    f"proportion change = {vault.proportion_change:.3f}, p_xz = {vault.p_xz:.3f}, tubes = "
    f"{vault.max_tubes}"
)
print(
    f"largest |z| of the feet at the design angle: {vault.ground_error():.1e} (model units, "
    "radius 1)"
)

# %%
# At its design angle every end section stands on the ground plane z = 0.
fig = plot_vault(vault)

# %%
# One parameter, the fold angle 2α, drives the whole structure: from the flat two-ply
# state (0°) to the design angle. Away from 90° the feet lift off the ground; each panel
# gives that lift.
fig = plot_motion_strip(vault, angles=(0.0, 30.0, 60.0, 90.0))
