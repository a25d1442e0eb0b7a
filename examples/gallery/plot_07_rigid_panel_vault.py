"""
A vault of rigid planar panels and its singular values
======================================================

For plywood, aluminium or thick boards: each crease becomes a polyline of N segments and
every strip a row of exactly planar trapezoids. The panel vault stands on the ground by
a discrete arch condition. Its motion is a mechanism with one internal degree of
freedom; the singular values of its constraint Jacobian show it (Rigid panels in the
user guide).
"""

# %%
from curvefold.analysis import analyse
from curvefold.figures import plot_singular_values, plot_vault
from curvefold.vault import Vault

vault = Vault.from_design(a=0.3, p_xy=0.75, tubes=3, panels=16)
print(f"κ0·s0 = {vault.kappa0_s0:.5f} for 16 panels (smooth: 3.16572)")
print(f"largest |z| of the feet at the design angle: {vault.ground_error():.1e}")

# %%
fig = plot_vault(vault)

# %%
# Flat, half-way and at the design angle: the values below the rank tolerance are the
# first-order motions, six of them rigid motions in space. Folded, one more is left: the
# single internal degree of freedom, with a gap of many orders of magnitude above it.
mechanisms = analyse(vault.structure)
for m in mechanisms:
    print(f"{m.label}: {m.dof} internal degree(s) of freedom, gap {m.gap:.1e}")
fig = plot_singular_values(mechanisms)
