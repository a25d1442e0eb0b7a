"""
The paper's vault under its own weight
======================================

Will the deployed vault stand? The bar-and-hinge model of the vault at its design angle
(:mod:`curvefold.mechanics`): polypropylene 1 mm thick on a vault of radius 1 m, its feet
(the end sections on the ground) pinned, under its own weight. The first free mode is its
folding motion; how much stiffer the next one is, the fold-mode gap, is what the tubes'
virtual thickness buys.
"""

# %%
import numpy as np
from matplotlib import colormaps
from matplotlib.cm import ScalarMappable
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from curvefold.mechanics import analyse_load
from curvefold.vault import Vault

vault = Vault.from_design(a=0.3, p_xy=0.75)
result = analyse_load(vault, "polypropylene", 1e-3)
summary = result.to_dict()
print(f"weight {summary['total_weight']:.1f} N, carried by the feet: reactions {np.round(summary['reactions'], 9).tolist()} N")
print(f"largest deflection {summary['max_displacement'] * 1e6:.1f} µm, largest stress {summary['max_stress'] / 1e3:.1f} kPa "
      f"(utilisation {summary['utilisation']:.2%})")
print(f"buckling factor {summary['buckling_factor']:.0f}; fold-mode gap {summary['fold_mode_gap']:.2f}; "
      f"first mode against the rigid folding: correlation {summary['fold_mode_correlation']:.3f}; soft modes {summary['soft_modes']}")

# %%
# The deflected vault, its displacement magnified 2,000 times and coloured by its size.
sm = result.structure
topology = vault.structure.topology("quads")
displacement = sm.field(result.static.displacements)  # (M, n, 3): every lattice curve's points
size = np.linalg.norm(topology.coords(displacement), axis=1)


def draw(ax, curves, values, title, cmap):
    """The vault's quads at the points ``curves`` (M, n, 3), coloured by ``values`` at their vertices."""
    faces = topology.coords(curves)[topology.faces_vertices]
    colour = values[topology.faces_vertices].mean(axis=1)
    ax.add_collection3d(Poly3DCollection(faces, facecolors=colormaps[cmap](colour / colour.max()), edgecolor="none"))
    return ScalarMappable(Normalize(0, colour.max()), cmap)
    lo, hi = faces.reshape(-1, 3).min(axis=0), faces.reshape(-1, 3).max(axis=0)
    ax.set_box_aspect(hi - lo)
    ax.set(xlim=(lo[0], hi[0]), ylim=(lo[1], hi[1]), zlim=(lo[2], hi[2]), title=title)
    ax.view_init(elev=20, azim=-50)
    ax.set_axis_off()


fig = Figure(figsize=(7.5, 5.5))
ax = fig.add_subplot(projection="3d")
scale = draw(ax, vault.vertices + 2000 * displacement, 1e6 * size, "the paper's vault under its weight (deflection × 2000)", "viridis")
fig.colorbar(scale, ax=ax, shrink=0.6, label="deflection (µm)")

# %%
# The three lowest free modes: the folding motion first, then how the vault bends.
modes = Figure(figsize=(10, 3.6))
for k in range(3):
    shape = sm.field(result.modes.shapes[k])
    draw(modes.add_subplot(1, 3, k + 1, projection="3d"), vault.vertices + 0.15 * shape, np.linalg.norm(topology.coords(shape), axis=1),
         f"mode {k + 1}: {result.modes.frequencies[k]:.2f} Hz", "magma")
