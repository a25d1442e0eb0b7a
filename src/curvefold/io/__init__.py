"""File exporters: FOLD (with a reader), OBJ/STL/PLY, animated GLB, Rhino 3dm and crease patterns.

Every writer goes through :mod:`curvefold.io.atomic` (temporary file, then rename), so a
failure never leaves a partial file. Heavy libraries (``trimesh``, ``pygltflib``,
``rhino3dm``, ``ezdxf``, ``matplotlib``) are optional and imported only by the writer that
needs them.

:mod:`curvefold.io.formats` is the registry of every file format (name, extension,
contents, kinds of design, writer, optional package); :mod:`curvefold.io.tables` is the
one table of pages, length units and line colours the writers share. Files a user names
are read through :mod:`curvefold.io.reading` (regular files only, within a size limit).

The writers take meshes and laid-out sheets; the structure-level entry points
(:func:`write_structure_fold`, :func:`write_pattern`, :func:`write_3d`) take a structure and
the conversions geometry makes of it (:mod:`curvefold.geometry.fold_arrays`,
:mod:`curvefold.geometry.sheets`), and only serialise them. FOLD files are read back by
:mod:`curvefold.io.fold_reading`.
"""

from .fold import fold_assignments, to_fold, write_fold, write_sheet_fold, write_structure_fold
from .fold_reading import FoldFile, read_fold
from .gltf import write_glb
from .layout import Layout, layout_sheets, page_size
from .mesh3d import check_metadata, crease_polylines, write_obj, write_ply, write_stl
from .models import MODEL_FORMATS, write_3d
from .pattern import PATTERN_FORMATS, layout_pattern, write_dxf, write_pattern, write_pdf, write_svg
from .rhino import write_3dm

__all__ = [
    "FoldFile",
    "Layout",
    "MODEL_FORMATS",
    "PATTERN_FORMATS",
    "check_metadata",
    "crease_polylines",
    "fold_assignments",
    "layout_pattern",
    "layout_sheets",
    "page_size",
    "read_fold",
    "to_fold",
    "write_3d",
    "write_3dm",
    "write_dxf",
    "write_fold",
    "write_glb",
    "write_obj",
    "write_pattern",
    "write_pdf",
    "write_ply",
    "write_sheet_fold",
    "write_stl",
    "write_structure_fold",
    "write_svg",
]
