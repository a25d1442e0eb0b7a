"""Geometry: curves, creases, lattices, structures, their folded states, meshes and sheets.

Pure NumPy on top of :mod:`curvefold.kernel`. The names below are its public surface, in
the order data flows: curve → crease → lattice (smooth, or rigid panels) → structure →
state → mesh, sheets and FOLD arrays.
"""

from ..kernel.exports import lazy_exports as _lazy_exports

# The public names by module, imported when first asked for (kernel.exports).
__all__, __getattr__, __dir__ = _lazy_exports(
    __name__,
    {
        "curve": ["SpaceCurve", "FramedCurve", "integrate_frenet"],
        "crease": ["Crease", "half_angle", "check_fold_angle"],
        "lattice": ["Lattice", "Pattern", "RegressionDomain"],
        "kinds": ["StructureLattice", "FoldedCrease"],
        "panels": ["PanelLattice", "PanelCrease", "PanelCurve"],
        "panel_pattern": ["PanelPattern"],
        "structure": ["Structure", "State"],
        "mesh": ["Mesh", "fold_angles"],
        "topology": ["Topology", "SheetTopology"],
        "sheets": ["PatternSheet", "Bond", "FlatPlane", "bonds", "flat_plane", "folding_motion"],
        "fold_arrays": ["FoldArrays", "structure_metadata"],
        "sampling": ["Sampling", "choose_sampling"],
        "contact": ["first_contact"],
        "single_fold": ["SingleFold"],
    },
)
