"""File exporters: FOLD (with a reader), OBJ/STL/PLY, animated GLB and Rhino 3dm.

Every writer goes through :mod:`curvefold.fileio` (temporary file, then rename), so a
failure never leaves a partial file. Heavy libraries (``trimesh``, ``pygltflib``,
``rhino3dm``) are optional and imported only by the writer that needs them.
"""

from .fold import FoldFile, fold_assignments, read_fold, write_fold, write_sheet_fold
from .gltf import write_glb
from .mesh3d import check_metadata, crease_polylines, write_obj, write_ply, write_stl
from .rhino import write_3dm

__all__ = [
    "FoldFile",
    "check_metadata",
    "crease_polylines",
    "fold_assignments",
    "read_fold",
    "write_3dm",
    "write_fold",
    "write_glb",
    "write_obj",
    "write_ply",
    "write_sheet_fold",
    "write_stl",
]
