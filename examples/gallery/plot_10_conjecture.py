"""
The paper's conjecture, measured
================================

A single curved fold can move in more ways than by rigid folding: its rulings may drift
(the paper's Fig. 08). The paper conjectures that a tube whose boundary curves are
straight quads, with no cone apex, has rigid folding as its only motion. Counted here:
the motions that stretch no bar to first order, the sheet free to bend at its rulings and
across its panels' diagonals (the discrete form of drifting rulings), as the panels
along each crease double (:func:`curvefold.mechanics.conjecture_counts`).
"""

# %%
import numpy as np
from matplotlib.figure import Figure

from curvefold import Crease, Lattice, SpaceCurve, Structure
from curvefold.geometry import PanelLattice
from curvefold.mechanics import MATERIALS, StructureModel, conjecture_counts
from curvefold.vault import Vault

curve = SpaceCurve.from_curvature(
    lambda s: 1 + 0.3 * np.sin(s), lambda s: 0.2 + 0.3 * np.cos(s), 3.0, samples=161
)
smooth = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.08)


def structures(panels):
    lattice = PanelLattice.from_lattice(smooth, panels)
    return {
        "single fold": (Structure.tube(lattice), (0,)),
        "tube": (Structure.tube(lattice), None),
        "cellular block (2 × 2)": (
            Structure.from_cells(lattice, [(0, 0), (0, 1), (1, 0), (1, 1)]),
            None,
        ),
        "the paper's vault (9 tubes)": (Vault.from_design(panels=panels).structure, None),
    }


keys = ("free", "end planar", "end diagonals", "rulings fixed")
print(f"{'structure':30s} {'N':>3s}  " + "  ".join(f"{k:>13s}" for k in keys))
found = {}
for panels in (8, 16, 32):
    for name, (structure, sheets) in structures(panels).items():
        model = StructureModel.from_state(
            structure.state(), MATERIALS["polypropylene"], 1e-3, sheets=sheets
        )
        counts = conjecture_counts(model)
        found[name, panels] = counts
        print(
            f"{name:30s} {panels:3d}  "
            + "  ".join(f"{counts[k].count:13d}" if k in counts else f"{'—':>13s}" for k in keys)
        )

# %% A single fold drifts in 2N + 1 ways: the more panels, the more ways (in the limit, a function's
# worth). A tube has one motion besides folding at every N, and it warps the end sections out of
# their planes: held planar (straight boundary quads), the tube keeps rigid folding alone. Bonded
# tubes hold each other's end sections: a block and the vault fold and do nothing else. Holding the
# end sections' diagonals as well stops everything: a tube's section shears as it folds. Below, the
# smallest singular values of the bars' compatibility at N = 16 (the rigid motions' six among them),
# relative to the largest, and the rank tolerance.
fig = Figure(figsize=(7.5, 4))
ax = fig.add_subplot()
for name, _ in structures(16).items():
    s = found[name, 16]["free"].singular_values
    ax.semilogy(
        np.arange(1, len(s) + 1),
        np.maximum(s, 1e-17),
        "o-",
        ms=4,
        label=f"{name}: {found[name, 16]['free'].count}",
    )
ax.axhline(found["tube", 16]["free"].tolerance, color="0.4", ls="--", lw=1, label="rank tolerance")
ax.set(
    xlabel="index (ascending)",
    ylabel="σ / σ_max",
    title="Inextensional motions (6 rigid + the count), 16 panels",
    ylim=(1e-17, 1),
)
ax.legend(fontsize=8, loc="lower right")
