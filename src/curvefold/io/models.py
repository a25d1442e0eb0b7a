"""3D model files of a structure: the folded state (OBJ, STL, PLY, 3DM) and its motion (GLB)."""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from ..geometry.crease import check_fold_angle, check_fold_angles
from ..geometry.fold_arrays import structure_metadata
from ..geometry.sheets import folding_motion
from ..geometry.structure import Structure, check_structure
from . import gltf, mesh3d, rhino
from .formats import FORMATS, check_formats, formats_of

__all__ = ["MODEL_FORMATS", "write_3d"]

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
        The samples each tube's mesh keeps (:func:`curvefold.geometry.sampling.choose_sampling`);
        default every sample.

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
    state = structure.state(static, anchor=anchor)
    mesh, quads = state.mesh(keep=keep), state.mesh(faces="quads", keep=keep)
    static_meta = {**meta, "fold_angle_deg": static}
    out: list[Path] = []
    for fmt in formats:
        target = FORMATS[fmt].path(path_stem)
        if fmt == "glb":
            coords = folding_motion(structure, motion, anchor=anchor, keep=keep)
            out.append(gltf.write_glb(target, mesh, coords=coords, angles_deg=motion, base_state=int(np.argmin(np.abs(motion - static))), unit=unit, metadata=meta,
                                      seconds_per_state=seconds_per_state))
        elif fmt == "obj":
            out.append(mesh3d.write_obj(target, quads, unit=unit, metadata=static_meta))
        elif fmt == "stl":
            out.append(mesh3d.write_stl(target, mesh))
        elif fmt == "ply":
            out.append(mesh3d.write_ply(target, mesh))
        else:
            out.append(rhino.write_3dm(target, quads, structure.topology("quads", keep=keep), unit=unit, metadata=static_meta,
                                       degree=structure.lattice.crease_degree))
    return tuple(out)
