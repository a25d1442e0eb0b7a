"""
A tube from a CSV curve
=======================

A tube whose curve is given by measured samples: curvature and torsion read from the
columns of a CSV file (``examples/tube-kappa-tau.csv``) by the design file
``examples/tube-csv.toml``, exactly as ``curvefold tube examples/tube-csv.toml`` reads it.
"""

# %%
from pathlib import Path

from curvefold.app import load_design
from curvefold.app._build import build
from curvefold.figures import plot_sections, plot_structure

examples = Path("..")  # the repository's examples/ folder: this script runs in examples/gallery/
print((examples / "tube-csv.toml").read_text())

# %%
built = build(load_design(examples / "tube-csv.toml"))
tube = built.structure
curve = tube.lattice.crease.curve
kappa = curve.kappa(curve.s)
print(
    f"{curve.s.size} samples over s ∈ [0, {curve.s[-1]:g}]; κ from {kappa.min():.3f} to "
    f"{kappa.max():.3f}"
)

# %%
# The tube at its design angle: folds red, seams blue.
fig = plot_structure(tube)

# %%
# Its sections normal to curve 1's tangent at three places along it, at several fold
# angles: the four creases form a parallelogram whose sides keep their lengths, so
# rigid folding shears it like a pantograph (flat at 2α = 0).
fig = plot_sections(tube, (0.0, 0.5, 1.0))
