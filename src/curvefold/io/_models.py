"""3D model files of a structure: the folded state (OBJ, STL, PLY, 3DM) and its motion (GLB).

:func:`write_3d` prepares a :class:`FoldedModel` once and writes each format asked with the
writer the registry (:data:`curvefold.io._formats.FORMATS`) names for it: :func:`model_glb`,
:func:`model_obj`, :func:`model_stl`, :func:`model_ply` or :func:`model_3dm`.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..geometry._crease import check_fold_angle, check_fold_angles
from ..geometry._fold_arrays import structure_metadata
from ..geometry._mesh import Mesh
from ..geometry._sheets import folding_motion
from ..geometry._structure import Structure, check_structure
from ..geometry._topology import Topology
from ..kernel._arrays import readonly
from . import _gltf as gltf
from . import _mesh3d as mesh3d
from . import _rhino as rhino
from ._formats import FORMATS, check_formats, formats_of
from ._layout import Layout

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


@dataclass(frozen=True, eq=False)
class FoldedModel:
    """A structure prepared once for all its 3D files (see :func:`write_3d`).

    Attributes
    ----------
    structure : Structure
    mesh : Mesh
        The state written to OBJ, STL, PLY and 3dm, two triangles per ruling quad (per panel).
    quads : Mesh
        The same state, one quad per ruling quad (per panel).
    fold_angle : float
        2α of that state, degrees.
    motion : (A,) ndarray
        2α of the states of the GLB animation, degrees.
    unit : str
        Model unit.
    metadata : dict
        Design parameters of the files.
    anchor : str
        Which frame of curve 1 stays fixed along the motion.
    seconds_per_state : float
        GLB animation time between consecutive states.
    keep : sequence of (m_k,) ndarray of int, or None
        The samples each tube's mesh keeps.
    print_unit : str or None
        Length unit of the STL; None for the model unit.
    morph_targets : dict of str to (V, 3) ndarray
        Further named morph targets of the GLB, displacements from :attr:`mesh`.
    pattern : Layout or None
        The crease pattern of the 3dm's ``crease pattern`` layer.
    topology, quad_topology : Topology or None
        The topologies of :attr:`mesh` and :attr:`quads` (``structure.topology(faces, keep=keep)``);
        None: made when asked.
    """

    structure: Structure
    mesh: Mesh
    quads: Mesh
    fold_angle: float
    motion: np.ndarray
    unit: str
    metadata: dict
    anchor: str
    seconds_per_state: float
    keep: Sequence[np.ndarray] | None
    print_unit: str | None = None
    morph_targets: Mapping[str, np.ndarray] = field(default_factory=dict)
    pattern: Layout | None = None
    topology: Topology | None = None
    quad_topology: Topology | None = None

    @property
    def static_metadata(self) -> dict:
        """:attr:`metadata` with the fold angle of the state the static files hold."""
        return {**self.metadata, "fold_angle_deg": self.fold_angle}


def model_glb(path: str | os.PathLike, model: FoldedModel) -> Path:
    """The GLB of a model: a node per sheet, its state as the base pose, the folding motion as morph
    targets and an animation that starts at that state; the model's further morph targets after them."""
    topology = model.structure.topology(keep=model.keep) if model.topology is None else model.topology
    coords = folding_motion(model.structure, model.motion, anchor=model.anchor, topology=topology)
    base = int(np.argmin(np.abs(model.motion - model.fold_angle)))
    sheets = topology.sheets
    # the base pose is the motion's state nearest the model's: the further targets move from it
    shift = coords[base] - model.mesh.vertices_coords
    morphs = {name: np.asarray(d, float) - shift for name, d in model.morph_targets.items()}
    return gltf.write_glb(path, model.mesh, coords=coords, angles_deg=model.motion, base_state=base, unit=model.unit,
                          metadata=model.metadata, seconds_per_state=model.seconds_per_state,
                          parts=[(s.label, s.faces, s.edges) for s in sheets], morph_targets=morphs)


def model_obj(path: str | os.PathLike, model: FoldedModel) -> Path:
    """The OBJ of a model: one quad per ruling quad, with the creases as polylines."""
    return mesh3d.write_obj(path, model.quads, unit=model.unit, metadata=model.static_metadata)


def model_stl(path: str | os.PathLike, model: FoldedModel) -> Path:
    """The STL of a model (triangles), in its print unit."""
    return mesh3d.write_stl(path, model.mesh, unit=model.unit, to_unit=model.print_unit)


def model_ply(path: str | os.PathLike, model: FoldedModel) -> Path:
    """The PLY of a model (triangles, each with its strip)."""
    return mesh3d.write_ply(path, model.mesh)


def model_3dm(path: str | os.PathLike, model: FoldedModel) -> Path:
    """The Rhino model of a model: a mesh per sheet, ruled NURBS strips and NURBS creases (of the lattice's crease degree),
    grouped by tube and sheet, and the model's crease pattern laid beside it when it has one."""
    structure = model.structure
    topology = structure.topology("quads", keep=model.keep) if model.quad_topology is None else model.quad_topology
    return rhino.write_3dm(path, model.quads, topology, unit=model.unit,
                           metadata=model.static_metadata, degree=structure.lattice.crease_degree, fold_angle=model.fold_angle,
                           pattern=model.pattern)
