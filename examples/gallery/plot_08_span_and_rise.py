"""
A vault from span and rise targets
==================================

Instead of a, p_xy and the radius, give what the building needs: the span, the rise and
the section proportion p_xz at the apex. For a given width and number of tubes, rise/span
and p_xz fix a and p_xy, and the span then fixes the radius
(``curvefold vault --span 4 --rise 2.5 --p-xz 1.2 --tubes 9``).
"""

# %%
from curvefold.figures import plot_vault
from curvefold.vault import Vault, VaultDesign, fit_targets

fit = fit_targets(VaultDesign(tubes=9), span=4.0, rise=2.5, p_xz=1.2)
design = fit.require()
print(f"a = {design.a:.4f}, p_xy = {design.p_xy:.4f}, radius = {design.radius:.4f}")
print(f"measured: span = {fit.span:.6f}, rise = {fit.rise:.6f}, p_xz = {fit.p_xz:.6f}")

# %%
vault = Vault.from_design(design)
fig = plot_vault(vault)

# %%
# A target the family cannot reach is answered with the nearest design it can build.
far = fit_targets(VaultDesign(tubes=9), span=4.0, rise=9.0)
print(far.reached, far.message)
