"""
The regression domain (the paper's Fig. 07)
===========================================

Every lattice curve of a tube or vault is ``x(t; u, v) = x1(t) + u ℓ_L r_L + v ℓ_R r_R``
(Eq. 11). It runs forward only while ``1 − u w_L/w_lim_L − v w_R/w_lim_R > 0`` for every
t (Eq. 17), so the valid (u, v) form an intersection of half-planes (Eq. 18). Here is that
domain for the paper's vault (a = 0.3, p_xy = 0.75), with the cells of its tubes: every
corner of every cell must lie inside it.
"""

# %%
from curvefold.figures import plot_regression_domain
from curvefold.vault import Vault

vault = Vault.from_design(a=0.3, p_xy=0.75)
print(f"κ0·s0 = {vault.kappa0_s0:.11f}, tubes = {vault.max_tubes}")
margin = vault.lattice.domain.margin(vault.structure.curves_uv.astype(float)).min()
print(f"smallest speed factor of Eq. 17 over every crease: {margin:.3f} (> 0: free of regression)")

# %%
# The shaded set is valid; each coloured line is one t's limit ``u a(t) + v b(t) = 1``.
# The tubes stack along the diagonal until the next cell would cross a line.
fig = plot_regression_domain(vault.lattice, vault.structure.cells)
