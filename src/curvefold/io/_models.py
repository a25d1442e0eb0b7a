"""3D model files of a structure: the folded state (OBJ, STL, PLY, 3DM) and its motion (GLB).

:func:`write_3d` prepares a :class:`FoldedModel` once and writes each format asked with the
writer the registry (:data:`curvefold.io._formats.FORMATS`) names for it: :func:`model_glb`,
:func:`model_obj`, :func:`model_stl`, :func:`model_ply` or :func:`model_3dm`
(:mod:`curvefold.io._model_files`).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from ..geometry._fold_angle import check_fold_angle, check_fold_angles
from ..geometry._fold_arrays import structure_metadata
from ..geometry._structure import Structure, check_structure
from ..kernel._arrays import readonly
from ..kernel._errors import InputError
from . import _mesh3d as mesh3d
from ._formats import FORMATS, check_formats, formats_of
from ._model_files import FoldedModel, model_3dm, model_glb, model_obj, model_ply, model_stl
from ._output import ModelOutput

__all__ = [
    "MODEL_FORMATS",
    "FoldedModel",
    "ModelOutput",
    "write_3d",
    "model_glb",
    "model_obj",
    "model_stl",
    "model_ply",
    "model_3dm",
]

#: 3D formats :func:`write_3d` writes.
MODEL_FORMATS = formats_of("model")

# --------------------------------------------------------------------------------------
# 3D


def write_3d(
    path_stem: str | os.PathLike,
    structure: Structure,
    fold_angles: ArrayLike | None = None,
    output: ModelOutput = ModelOutput(),
    *,
    formats: Sequence[str] = MODEL_FORMATS,
    fold_angle: float | None = None,
    degrees: bool = True,
) -> tuple[Path, ...]:
    """Write the folded structure as 3D files; the GLB holds the folding motion.

    OBJ and 3dm hold one quad per ruling quad (per panel), GLB, STL and PLY two triangles (their
    formats know triangles only). The GLB's base pose is the state of OBJ, STL, PLY and
    3dm; the other states of the motion are its morph targets.

    Parameters
    ----------
    path_stem : path-like
        Files are ``<stem>.glb``, ``<stem>.obj``… one per format.
    structure : Structure
    fold_angles : (A,) array_like, optional
        2α of the states of the GLB animation (morph targets), in [0°, 180°); default
        seven steps from 0° (flat) to the design angle.
    output : ModelOutput
        Units, metadata, anchor, sampling, animation timing, further morph targets and the
        crease pattern of the 3dm.
    formats : sequence of {"glb", "obj", "stl", "ply", "3dm"}, keyword-only
    fold_angle : float, optional, keyword-only
        The state written to OBJ, STL, PLY and 3dm; default the design angle.
    degrees : bool, keyword-only

    Returns
    -------
    tuple of Path
        The files written, in the order of ``formats``.
    """
    check_structure(structure)
    if not isinstance(output, ModelOutput):
        raise InputError(
            f"output must be a ModelOutput (unit, metadata…), got {type(output).__name__}",
            parameter="output",
        )
    formats = check_formats(formats, "model")
    design = structure.lattice.crease.fold_angle
    static = (
        design
        if fold_angle is None
        else check_fold_angle(fold_angle, degrees=degrees, allow_flat=True)
    )
    motion = (
        np.linspace(0.0, design, 7)
        if fold_angles is None
        else check_fold_angles(fold_angles, degrees=degrees)
    )
    meta = mesh3d.check_metadata(
        {**structure_metadata(structure), **mesh3d.check_metadata(output.metadata)}
    )
    o = output
    curves = structure.state(static, anchor=o.anchor).vertices
    # State.mesh's, made once
    triangles, quads = structure.topology(keep=o.keep), structure.topology("quads", keep=o.keep)
    model = FoldedModel(
        structure,
        triangles.mesh(curves),
        quads.mesh(curves),
        static,
        readonly(motion),
        o.unit,
        meta,
        o.anchor,
        o.seconds_per_state,
        o.keep,
        o.print_unit,
        dict(o.morph_targets or {}),
        o.pattern,
        triangles,
        quads,
        o.print_scale,
    )
    # each format's writer
    return tuple(
        FORMATS[name].load_writer()(FORMATS[name].path(path_stem), model) for name in formats
    )
