"""
A cellular block
================

Cells of the tube lattice around one curve share their creases: an L-shaped block of
three cells, (0, 0), (0, 1) and (1, 1), around a gently twisting curve. It folds rigidly
and flat with one parameter, like a single tube. This is ``examples/cellular-block.toml``.
"""

# %%
import numpy as np

from curvefold import Crease, Lattice, SpaceCurve, Structure
from curvefold.figures import plot_regression_domain, plot_structure

curve = SpaceCurve.from_curvature(0.8, lambda s: 0.15 * np.sin(np.pi * s / 4), 4.0, samples=401)
lattice = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.2, 0.2)
block = Structure.from_cells(lattice, [(0, 0), (0, 1), (1, 1)])
print(f"{len(block.cells)} cells on {len(block.curves_uv)} lattice curves")

# %%
# Every corner of every cell lies inside the regression domain.
fig = plot_regression_domain(lattice, block.cells)

# %%
# The block at its design angle, and half-way through its motion.
fig = plot_structure(block)
half_way = plot_structure(block, fold_angle=45.0)
