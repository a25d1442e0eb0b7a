"""Geometry: curves, creases, lattices, structures, their folded states, meshes and sheets.

Pure NumPy on top of :mod:`curvefold.kernel`. The names below are its public surface, in
the order data flows: curve → crease → lattice (smooth, or rigid panels) → structure →
state → mesh, sheets and FOLD arrays.
"""

from ..kernel._exports import lazy_exports as _lazy_exports

# The public names by module, imported when first asked for (kernel.exports).
__all__, __getattr__, __dir__ = _lazy_exports(
    __name__,
    {
        "_curve": ["SpaceCurve", "FramedCurve", "integrate_frenet"],
        "_crease": ["Crease"],
        "_fold_angle": ["half_angle", "check_fold_angle"],
        "_lattice": ["Lattice"],
        "_lattice_pattern": ["Pattern", "RegressionDomain"],
        "_kinds": ["StructureLattice", "FoldedCrease"],
        "_panels": ["PanelLattice", "PanelCrease", "PanelCurve"],
        "_panel_pattern": ["PanelPattern"],
        "_structure": ["Structure", "State"],
        "_mesh": ["Mesh", "fold_angles"],
        "_topology": ["Topology", "SheetTopology"],
        "_sheets": ["PatternSheet", "Bond", "FlatPlane", "bonds", "flat_plane", "folding_motion"],
        "_fold_arrays": ["FoldArrays", "structure_metadata"],
        "_sampling": ["Sampling", "choose_sampling"],
        "_contact": ["first_contact"],
        "_thick": ["ThickPanels", "ThickRange"],
        "_single_fold": ["SingleFold"],
    },
)
