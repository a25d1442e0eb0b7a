"""The 3D files of a prepared model: the folded state (OBJ, STL, PLY, 3DM) and its motion (GLB).

A :class:`FoldedModel` is a structure prepared once for all its 3D files
(:func:`curvefold.io.write_3d` makes it); each function here writes one format of it, as
the registry (:data:`curvefold.io._formats.FORMATS`) names them: :func:`model_glb`,
:func:`model_obj`, :func:`model_stl`, :func:`model_ply` and :func:`model_3dm`.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal

import numpy as np

from ..geometry._mesh import Mesh
from ..geometry._sheets import folding_motion
from ..geometry._structure import Structure
from ..geometry._topology import Topology
from . import _gltf as gltf
from . import _mesh3d as mesh3d
from . import _rhino as rhino
from ._layout import Layout

__all__ = ["FoldedModel", "model_glb", "model_obj", "model_stl", "model_ply", "model_3dm"]


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
    anchor : {"start", "middle"}
        Which frame of curve 1 stays fixed along the motion.
    seconds_per_state : float
        GLB animation time between consecutive states.
    keep : sequence of (m_k,) ndarray of int, or None
        The samples each tube's mesh keeps.
    print_unit : str or None
        Length unit of the STL; None for the model unit.
    print_scale : float or None
        Millimetres of the STL per model unit (the crease pattern's scale); None: true size.
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
    anchor: Literal["start", "middle"]
    seconds_per_state: float
    keep: Sequence[np.ndarray] | None
    print_unit: str | None = None
    morph_targets: Mapping[str, np.ndarray] = field(default_factory=dict)
    pattern: Layout | None = None
    topology: Topology | None = None
    quad_topology: Topology | None = None
    print_scale: float | None = None

    @property
    def static_metadata(self) -> dict:
        """:attr:`metadata` with the fold angle of the state the static files hold."""
        return {**self.metadata, "fold_angle_deg": self.fold_angle}


def model_glb(path: str | os.PathLike, model: FoldedModel) -> Path:
    """The GLB of a model: a node per sheet, its state as the base pose, the folding motion as morph
    targets and an animation that starts at that state; the model's further morph targets after
    them."""
    topology = model.topology
    if topology is None:
        topology = model.structure.topology(keep=model.keep)
    coords = folding_motion(model.structure, model.motion, anchor=model.anchor, topology=topology)
    base = int(np.argmin(np.abs(model.motion - model.fold_angle)))
    sheets = topology.sheets
    # the base pose is the motion's state nearest the model's: the further targets move from it
    shift = coords[base] - model.mesh.vertices_coords
    morphs = {name: np.asarray(d, float) - shift for name, d in model.morph_targets.items()}
    options = gltf.GlbOptions(
        unit=model.unit,
        metadata=model.metadata,
        seconds_per_state=model.seconds_per_state,
        parts=[(s.label, s.faces, s.edges) for s in sheets],
    )
    return gltf.write_glb(
        path,
        model.mesh,
        coords=coords,
        angles_deg=model.motion,
        base_state=base,
        morph_targets=morphs,
        options=options,
    )


def model_obj(path: str | os.PathLike, model: FoldedModel) -> Path:
    """The OBJ of a model: one quad per ruling quad, with the creases as polylines."""
    return mesh3d.write_obj(path, model.quads, unit=model.unit, metadata=model.static_metadata)


def model_stl(path: str | os.PathLike, model: FoldedModel) -> Path:
    """The STL of a model (triangles), in its print unit at its print scale: a surface, open."""
    return mesh3d.write_stl(
        path, model.mesh, unit=model.unit, to_unit=model.print_unit, scale=model.print_scale
    )


def model_ply(path: str | os.PathLike, model: FoldedModel) -> Path:
    """The PLY of a model (triangles, each with its strip)."""
    return mesh3d.write_ply(path, model.mesh)


def model_3dm(path: str | os.PathLike, model: FoldedModel) -> Path:
    """The Rhino model of a model: a mesh per sheet, ruled NURBS strips and NURBS creases (of the
    lattice's crease degree), grouped by tube and sheet, and the model's crease pattern laid beside
    it when it has one."""
    structure = model.structure
    topology = model.quad_topology
    if topology is None:
        topology = structure.topology("quads", keep=model.keep)
    options = rhino.RhinoOptions(
        unit=model.unit, metadata=model.static_metadata, pattern=model.pattern
    )
    return rhino.write_3dm(
        path,
        model.quads,
        topology,
        degree=structure.lattice.crease_degree,
        fold_angle=model.fold_angle,
        options=options,
    )
