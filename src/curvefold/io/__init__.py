"""File exporters: FOLD (with a reader), OBJ/STL/PLY, animated GLB, Rhino 3dm and crease patterns.

Every writer goes through :mod:`curvefold.io.atomic` (temporary file, then rename), so a
failure never leaves a partial file. Heavy libraries (``pygltflib``, ``rhino3dm``,
``ezdxf``) are optional and imported only by the writer that needs them; OBJ, STL and PLY
(:mod:`curvefold.io.mesh3d`) and the PDF pages (:mod:`curvefold.io.pdf`) need none.

:mod:`curvefold.io.formats` is the registry of every file format (name, extension,
contents, kinds of design, writer, optional package); :mod:`curvefold.io.tables` is the
one table of pages, length units and line colours the writers share. Files a user names
are read through :mod:`curvefold.io.reading` (regular files only, within a size limit).

The writers take meshes and laid-out sheets; the structure-level entry points
(:func:`write_structure_fold`, :func:`write_pattern`, :func:`write_3d`) take a structure and
the conversions geometry makes of it (:mod:`curvefold.geometry.fold_arrays`,
:mod:`curvefold.geometry.sheets`), and only serialise them. FOLD files are read back by
:mod:`curvefold.io.fold_reading`.

The names are imported from their modules when first used (:mod:`curvefold.kernel.lazy`):
importing one writer, or :mod:`curvefold.io.formats`, does not import the others.
"""

from typing import TYPE_CHECKING

from ..kernel.lazy import lazy_exports

#: Each public name -> the module that defines it.
_EXPORTS = {
    "CUTTERS": ".cutters",
    "FoldFile": ".fold_reading",
    "Layout": ".layout",
    "MODEL_FORMATS": ".models",
    "PATTERN_FORMATS": ".pattern",
    "check_metadata": ".mesh3d",
    "crease_polylines": ".mesh3d",
    "fold_assignments": ".fold",
    "layout_pattern": ".pattern",
    "layout_sheets": ".layout",
    "page_size": ".layout",
    "read_fold": ".fold_reading",
    "to_fold": ".fold",
    "write_3d": ".models",
    "write_3dm": ".rhino",
    "write_dxf": ".pattern",
    "write_fold": ".fold",
    "write_glb": ".gltf",
    "write_layout": ".pattern",
    "write_obj": ".mesh3d",
    "write_pattern": ".pattern",
    "write_pdf": ".pattern",
    "write_ply": ".mesh3d",
    "write_sheet_fold": ".fold",
    "write_stl": ".mesh3d",
    "write_structure_fold": ".fold",
    "write_svg": ".pattern",
}
__all__ = sorted(_EXPORTS)
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)

if TYPE_CHECKING:  # the same names, for type checkers and editors
    from .fold import fold_assignments, to_fold, write_fold, write_sheet_fold, write_structure_fold
    from .fold_reading import FoldFile, read_fold
    from .gltf import write_glb
    from .layout import Layout, layout_sheets, page_size
    from .mesh3d import check_metadata, crease_polylines, write_obj, write_ply, write_stl
    from .models import MODEL_FORMATS, write_3d
    from .cutters import CUTTERS
    from .pattern import PATTERN_FORMATS, layout_pattern, write_dxf, write_layout, write_pattern, write_pdf, write_svg
    from .rhino import write_3dm
