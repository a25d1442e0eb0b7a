"""3D model files of a structure: the folded state (OBJ, STL, PLY, 3DM) and its motion (GLB).

:func:`write_3d` prepares a :class:`FoldedModel` once and writes each format asked with the
writer the registry (:data:`curvefold.io._formats.FORMATS`) names for it: :func:`model_glb`,
:func:`model_obj`, :func:`model_stl`, :func:`model_ply` or :func:`model_3dm`
(:mod:`curvefold.io._model_files`).
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from ..geometry._crease import check_fold_angle, check_fold_angles
from ..geometry._fold_arrays import structure_metadata
from ..geometry._structure import Structure, check_structure
from ..kernel._arrays import readonly
from . import _mesh3d as mesh3d
from ._formats import FORMATS, check_formats, formats_of
from ._layout import Layout
from ._model_files import FoldedModel, model_3dm, model_glb, model_obj, model_ply, model_stl

__all__ = ["MODEL_FORMATS", "FoldedModel", "write_3d", "model_glb", "model_obj", "model_stl", "model_ply", "model_3dm"]

#: 3D formats :func:`write_3d` writes.
MODEL_FORMATS = formats_of("model")

# --------------------------------------------------------------------------------------
# 3D


def write_3d(
    path_stem: str | os.PathLike,
    structure: Structure,
    fold_angles=None,
    *,
    fold_angle: float | None = None,
    degrees: bool = True,
    formats: Sequence[str] = MODEL_FORMATS,
    unit: str = "unit",
    metadata: Mapping | None = None,
    anchor: str = "start",
    seconds_per_state: float = 1.0,
    keep: Sequence[np.ndarray] | None = None,
    print_unit: str | None = None,
    morph_targets: Mapping[str, np.ndarray] | None = None,
    pattern: Layout | None = None,
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
    fold_angle : float, optional, keyword-only
        The state written to OBJ, STL, PLY and 3dm; default the design angle.
    degrees : bool, keyword-only
    formats : sequence of {"glb", "obj", "stl", "ply", "3dm"}, keyword-only
    unit : str, keyword-only
        Model unit (``"unit"``, ``"m"``, ``"mm"``…); GLB converts it to metres.
    metadata : mapping, optional, keyword-only
        Extra design parameters, merged over the defaults of :func:`to_fold`.
    anchor : {"start", "middle"}, keyword-only
    seconds_per_state : float, keyword-only
        GLB animation time between consecutive states.
    keep : sequence of (m_k,) array_like of int, optional, keyword-only
        The samples each tube's mesh keeps (:func:`curvefold.geometry.choose_sampling`);
        default every sample.
    print_unit : str, optional, keyword-only
        Length unit of the STL, which slicers read as millimetres (``"mm"``); default the
        model unit. The model unit counts as one metre (:data:`curvefold.io._tables.UNITS`).
    morph_targets : mapping of str to (V, 3) array_like, optional, keyword-only
        Further named morph targets of the GLB (a deformed shape, mode shapes): displacements,
        in model units, of the vertices of ``structure.state(fold_angle).mesh(keep=keep)``
        from that state (see :func:`curvefold.io.write_glb`).
    pattern : Layout, optional, keyword-only
        The crease pattern the 3dm lays beside the model on its ``crease pattern`` layer
        (:func:`curvefold.io.layout_pattern`).

    Returns
    -------
    tuple of Path
        The files written, in the order of ``formats``.
    """
    check_structure(structure)
    formats = check_formats(formats, "model")
    design = structure.lattice.crease.fold_angle
    static = design if fold_angle is None else check_fold_angle(fold_angle, degrees=degrees, allow_flat=True)
    motion = np.linspace(0.0, design, 7) if fold_angles is None else check_fold_angles(fold_angles, degrees=degrees)
    meta = mesh3d.check_metadata({**structure_metadata(structure), **mesh3d.check_metadata(metadata)})
    curves = structure.state(static, anchor=anchor).vertices
    triangles, quads = structure.topology(keep=keep), structure.topology("quads", keep=keep)  # State.mesh's, made once
    model = FoldedModel(structure, triangles.mesh(curves), quads.mesh(curves), static, readonly(motion), unit,
                        meta, anchor, seconds_per_state, keep, print_unit, dict(morph_targets or {}), pattern, triangles, quads)
    return tuple(FORMATS[name].load_writer()(FORMATS[name].path(path_stem), model) for name in formats)  # each format's writer
