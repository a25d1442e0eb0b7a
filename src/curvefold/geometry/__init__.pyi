"""The names :mod:`curvefold.geometry` loads on first use, for type checkers and editors."""

from ._contact import first_contact as first_contact
from ._crease import Crease as Crease
from ._curve import FramedCurve as FramedCurve
from ._curve import SpaceCurve as SpaceCurve
from ._curve import integrate_frenet as integrate_frenet
from ._fold_angle import check_fold_angle as check_fold_angle
from ._fold_angle import half_angle as half_angle
from ._fold_arrays import FoldArrays as FoldArrays
from ._fold_arrays import structure_metadata as structure_metadata
from ._kinds import FoldedCrease as FoldedCrease
from ._kinds import StructureLattice as StructureLattice
from ._lattice import Lattice as Lattice
from ._lattice_pattern import Pattern as Pattern
from ._lattice_pattern import RegressionDomain as RegressionDomain
from ._mesh import Mesh as Mesh
from ._mesh import fold_angles as fold_angles
from ._panel_pattern import PanelPattern as PanelPattern
from ._panels import PanelCrease as PanelCrease
from ._panels import PanelCurve as PanelCurve
from ._panels import PanelLattice as PanelLattice
from ._sampling import Sampling as Sampling
from ._sampling import choose_sampling as choose_sampling
from ._sheets import Bond as Bond
from ._sheets import FlatPlane as FlatPlane
from ._sheets import PatternSheet as PatternSheet
from ._sheets import bonds as bonds
from ._sheets import flat_plane as flat_plane
from ._sheets import folding_motion as folding_motion
from ._single_fold import SingleFold as SingleFold
from ._structure import State as State
from ._structure import Structure as Structure
from ._thick import ThickPanels as ThickPanels
from ._thick import ThickRange as ThickRange
from ._topology import SheetTopology as SheetTopology
from ._topology import Topology as Topology

__all__ = [
    "SpaceCurve",
    "FramedCurve",
    "integrate_frenet",
    "Crease",
    "half_angle",
    "check_fold_angle",
    "Lattice",
    "Pattern",
    "RegressionDomain",
    "StructureLattice",
    "FoldedCrease",
    "PanelLattice",
    "PanelCrease",
    "PanelCurve",
    "PanelPattern",
    "Structure",
    "State",
    "Mesh",
    "fold_angles",
    "Topology",
    "SheetTopology",
    "PatternSheet",
    "Bond",
    "FlatPlane",
    "bonds",
    "flat_plane",
    "folding_motion",
    "FoldArrays",
    "structure_metadata",
    "Sampling",
    "choose_sampling",
    "first_contact",
    "ThickPanels",
    "ThickRange",
    "SingleFold",
]
