"""File exporters: FOLD (with a reader), OBJ/STL/PLY, animated GLB, Rhino 3dm and crease patterns.

Every writer goes through :mod:`curvefold.io._atomic` (temporary file, then rename), so a
failure never leaves a partial file. Heavy libraries (``rhino3dm``, ``ezdxf``) are optional
and imported only by the writer that needs them; GLB (:mod:`curvefold.io._gltf`), OBJ, STL
and PLY (:mod:`curvefold.io._mesh3d`) and the PDF pages (:mod:`curvefold.io._pdf`) need none.

:mod:`curvefold.io._formats` is the registry of every file format (name, extension,
contents, kinds of design, writer, optional package); :mod:`curvefold.io._tables` is the
one table of pages, length units and line colours the writers share. Files a user names
are read through :mod:`curvefold.io._reading` (regular files only, within a size limit).

The writers take meshes and laid-out sheets; the structure-level entry points
(:func:`write_structure_fold`, :func:`write_pattern`, :func:`write_3d`) take a structure and
the conversions geometry makes of it (:mod:`curvefold.geometry._fold_arrays`,
:mod:`curvefold.geometry._sheets`), and only serialise them. FOLD files are read back by
:mod:`curvefold.io._fold_reading`.

The names are imported from their modules when first used (:mod:`curvefold.kernel._exports`):
importing one writer, or :mod:`curvefold.io._formats`, does not import the others.
"""

from ..kernel._exports import lazy_exports as _lazy_exports

# The public names by module, imported when first asked for (kernel.exports).
__all__, __getattr__, __dir__ = _lazy_exports(
    __name__,
    {
        "_fold": [
            "fold_assignments",
            "to_fold",
            "write_fold",
            "write_sheet_fold",
            "write_structure_fold",
        ],
        "_fold_reading": ["FoldFile", "read_fold"],
        "_gltf": ["GlbOptions", "write_glb"],
        "_layout": ["Layout", "layout_sheets", "page_size"],
        "_mesh3d": ["check_metadata", "crease_polylines", "write_obj", "write_ply", "write_stl"],
        "_solids": [
            "write_thick_stl",
            "write_cut_list",
            "write_cut_list_csv",
            "write_cut_list_pdf",
            "write_thick_3dm",
        ],
        "_step": ["write_thick_step"],
        "_models": ["MODEL_FORMATS", "write_3d"],
        "_cutters": ["CUTTERS"],
        "_output": ["FoldOutput", "ModelOutput", "PatternOutput"],
        "_pattern": [
            "PATTERN_FORMATS",
            "layout_pattern",
            "write_dxf",
            "write_layout",
            "write_pattern",
            "write_pdf",
            "write_svg",
        ],
        "_rhino": ["RhinoOptions", "write_3dm"],
    },
)
