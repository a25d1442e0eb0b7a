"""
Design variations (the paper's Fig. 10)
=======================================

The family of vaults over the torsion amplitude a (rows) and the section proportion
p_xy (columns). Each view shows a vault at its design angle with its section lines at
the feet (red, xy plane) and at the apex (blue, zx plane) and their slopes; the number
at the top left is its count of tubes. ``curvefold atlas`` sweeps larger grids, on a
Dask cluster if you have one.
"""

# %%
import numpy as np

from curvefold.figures import atlas_figure
from curvefold.vault import run_atlas

atlas = run_atlas(np.linspace(0.5, 1.25, 4), np.linspace(0.0, 0.9, 4), samples=201, workers=1)
valid = sum(record["valid"] for record in atlas.records)
print(f"{valid} of {len(atlas.records)} designs are valid")

# %%
fig = atlas_figure(atlas)
