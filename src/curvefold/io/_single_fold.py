"""The files of a single curved fold: its FOLD file with the folding motion, its 3D models and its
crease pattern.

A single fold (:class:`curvefold.geometry.SingleFold`) is no structure of tubes, so
it has its own preparation, and then the writers every kind shares: the FOLD document of
:func:`curvefold.io._fold.fold_document`, the meshes of :mod:`curvefold.io._mesh3d`, the GLB of
:mod:`curvefold.io._gltf`, the Rhino model of :mod:`curvefold.io._rhino`, and the crease
pattern's pages laid out by :func:`curvefold.io.layout_sheets` for the registry's
SVG, DXF and PDF writers.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import replace
from pathlib import Path

import numpy as np

from ..geometry._single_fold import SingleFold
from ..kernel._errors import InputError
from . import _gltf as gltf
from . import _mesh3d as mesh3d
from . import _rhino as rhino
from ._cutters import cutter as check_cutter
from ._cutting import prepare_layout
from ._fold_reading import FoldFile
from ._formats import FORMATS, check_formats
from ._layout import FOOTER, Layout, layout_sheets, page_size
from ._mesh3d import check_metadata
from ._output import ModelOutput, PatternOutput, check_output
from ._tables import mm_per_unit

__all__ = ["single_fold_model", "write_single_fold_3d", "layout_single_fold"]


def _glb(path: Path, fold: SingleFold, motion: np.ndarray, o: ModelOutput, meta: dict) -> Path:
    coords = np.stack([fold.topology().coords(fold.curves(a)) for a in motion])
    return gltf.write_glb(
        path,
        fold.mesh(fold.fold_angle),
        coords=coords,
        angles_deg=motion,
        base_state=int(np.argmin(np.abs(motion - fold.fold_angle))),
        options=gltf.GlbOptions(unit=o.unit, metadata=meta),
    )


def _obj(path: Path, fold: SingleFold, motion: np.ndarray, o: ModelOutput, meta: dict) -> Path:
    return mesh3d.write_obj(path, fold.mesh(fold.fold_angle, "quads"), unit=o.unit, metadata=meta)


def _stl(path: Path, fold: SingleFold, motion: np.ndarray, o: ModelOutput, meta: dict) -> Path:
    return mesh3d.write_stl(
        path, fold.mesh(fold.fold_angle), unit=o.unit, to_unit=o.print_unit, scale=o.print_scale
    )


def _ply(path: Path, fold: SingleFold, motion: np.ndarray, o: ModelOutput, meta: dict) -> Path:
    return mesh3d.write_ply(path, fold.mesh(fold.fold_angle))


#: The names of a single fold's two strips in its 3dm, by group (:meth:`SingleFold.topology`).
STRIP_NAMES = ("left strip", "right strip")


def _3dm(path: Path, fold: SingleFold, motion: np.ndarray, o: ModelOutput, meta: dict) -> Path:
    return rhino.write_3dm(
        path,
        fold.mesh(fold.fold_angle, "quads"),
        fold.topology("quads"),
        degree=3,
        fold_angle=fold.fold_angle,
        options=rhino.RhinoOptions(
            unit=o.unit, metadata=meta, pattern=o.pattern, strip_names=STRIP_NAMES
        ),
    )


#: How a single fold writes each 3D format of the registry: its meshes to the format's serialiser.
_MODELS = {"glb": _glb, "obj": _obj, "stl": _stl, "ply": _ply, "3dm": _3dm}


def single_fold_model(
    fold: SingleFold,
    fold_angles,
    *,
    unit: str = "unit",
    metadata: Mapping | None = None,
    design: Mapping | None = None,
) -> FoldFile:
    """A single fold as a FOLD model: its crease pattern and its folded frames at ``fold_angles``
    (degrees).

    ``design`` (the design as a design file holds it) is recorded with the frames' fold
    angles, so that the file can be built again and compared (``curvefold check --rebuild``).
    """
    angles = np.asarray(fold_angles, float)
    pattern, folded = fold.arrays(angles)
    meta = check_metadata(
        {
            "kind": "crease",
            "samples": fold.samples,
            "curve_length": float(fold.crease.curve.length),
            "width_left": fold.width_left,
            "width_right": fold.width_right,
            "design_fold_angle_deg": fold.fold_angle,
            **check_metadata(metadata),
        }
    )
    record = None if design is None else {"design": dict(design), "fold_angles": angles.tolist()}
    return FoldFile(crease_pattern=pattern, folded=folded, metadata=meta, unit=unit, design=record)


def write_single_fold_3d(
    path_stem: str | os.PathLike,
    fold: SingleFold,
    fold_angles,
    *,
    formats: Sequence[str],
    output: ModelOutput = ModelOutput(),
) -> tuple[Path, ...]:
    """The 3D files of a single fold at its design angle; the GLB holds the folding motion at
    ``fold_angles``.

    OBJ and 3dm hold one quad per ruling quad, GLB, STL and PLY two triangles, as for the other
    kinds. Of ``output``, the model unit and metadata are used by every file, the print unit
    and scale by the STL, the crease pattern by the 3dm (on its ``crease pattern`` layers).
    """
    formats = check_formats(formats, "model")
    motion = np.asarray(fold_angles, float)
    meta = check_metadata(
        {"kind": "crease", "fold_angle_deg": fold.fold_angle, **check_metadata(output.metadata)}
    )
    return tuple(
        _MODELS[name](FORMATS[name].path(path_stem), fold, motion, output, meta) for name in formats
    )


def layout_single_fold(fold: SingleFold, output: PatternOutput = PatternOutput()) -> Layout:
    """The crease pattern of a single fold on its page: at the output's scale, or as large as the
    page takes it.

    The output's page, units, scale, cutter, perforation, kerf and name are used; a single
    sheet has no seam, so no glue tab.

    Raises
    ------
    InputError
        A scale at which the pattern does not fit the page (the message gives both sizes).
    """
    check_output(output)
    fitted = _fitted(fold.pattern_sheet(output.name), output.page, output.units, output.scale)
    check_cutter(output.cutter)
    return prepare_layout(
        replace(fitted, cutter=output.cutter), perforation=output.perforation, kerf=output.kerf
    )


def _fitted(sheet, page, units: str, scale: float | None) -> Layout:
    """The sheet on its page at ``scale``, or as large as the page takes it."""
    if scale is not None:
        return layout_sheets([sheet], page=page, units=units, scale=scale, glue_tabs=False)
    width, height = page_size(page, units=units)
    target = max(width, height) - 20.0 / mm_per_unit(units)  # the margins' 10 mm either side
    # the pattern turned to its narrowest rectangle may be too wide: shrink until it fits
    for _ in range(40):
        try:
            return layout_sheets(
                [sheet], page=page, units=units, target_size=target, glue_tabs=False
            )
        except InputError:
            target *= 0.9
    raise InputError(
        f"page {page!r} leaves no room for the single fold's pattern inside its "
        f"margins and footer ({FOOTER:g} mm)"
    )
