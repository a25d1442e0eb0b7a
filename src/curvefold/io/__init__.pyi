"""The names :mod:`curvefold.io` loads on first use, for type checkers and editors."""

from ._cutters import CUTTERS as CUTTERS
from ._fold import fold_assignments as fold_assignments
from ._fold import to_fold as to_fold
from ._fold import write_fold as write_fold
from ._fold import write_sheet_fold as write_sheet_fold
from ._fold import write_structure_fold as write_structure_fold
from ._fold_reading import FoldFile as FoldFile
from ._fold_reading import read_fold as read_fold
from ._gltf import GlbOptions as GlbOptions
from ._gltf import write_glb as write_glb
from ._layout import Layout as Layout
from ._layout import layout_sheets as layout_sheets
from ._layout import page_size as page_size
from ._mesh3d import check_metadata as check_metadata
from ._mesh3d import crease_polylines as crease_polylines
from ._mesh3d import write_obj as write_obj
from ._mesh3d import write_ply as write_ply
from ._mesh3d import write_stl as write_stl
from ._models import MODEL_FORMATS as MODEL_FORMATS
from ._models import write_3d as write_3d
from ._output import FoldOutput as FoldOutput
from ._output import ModelOutput as ModelOutput
from ._output import PatternOutput as PatternOutput
from ._pattern import PATTERN_FORMATS as PATTERN_FORMATS
from ._pattern import layout_pattern as layout_pattern
from ._pattern import write_dxf as write_dxf
from ._pattern import write_layout as write_layout
from ._pattern import write_pattern as write_pattern
from ._pattern import write_pdf as write_pdf
from ._pattern import write_svg as write_svg
from ._rhino import RhinoOptions as RhinoOptions
from ._rhino import write_3dm as write_3dm
from ._solids import write_cut_list as write_cut_list
from ._solids import write_cut_list_csv as write_cut_list_csv
from ._solids import write_cut_list_pdf as write_cut_list_pdf
from ._solids import write_thick_3dm as write_thick_3dm
from ._solids import write_thick_stl as write_thick_stl
from ._step import write_thick_step as write_thick_step

__all__ = [
    "fold_assignments",
    "to_fold",
    "write_fold",
    "write_sheet_fold",
    "write_structure_fold",
    "FoldFile",
    "read_fold",
    "GlbOptions",
    "write_glb",
    "Layout",
    "layout_sheets",
    "page_size",
    "check_metadata",
    "crease_polylines",
    "write_obj",
    "write_ply",
    "write_stl",
    "write_thick_stl",
    "write_cut_list",
    "write_cut_list_csv",
    "write_cut_list_pdf",
    "write_thick_3dm",
    "write_thick_step",
    "MODEL_FORMATS",
    "write_3d",
    "CUTTERS",
    "FoldOutput",
    "ModelOutput",
    "PatternOutput",
    "PATTERN_FORMATS",
    "layout_pattern",
    "write_dxf",
    "write_layout",
    "write_pattern",
    "write_pdf",
    "write_svg",
    "RhinoOptions",
    "write_3dm",
]
