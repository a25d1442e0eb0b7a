"""Rhino ``.3dm`` of one structure state, written with ``rhino3dm`` (imported when called).

Layers: ``Surface`` (the mesh, triangulated, double-precision vertices), ``Fold``, ``Seam``,
``Boundary`` and ``Rulings`` (the crease edges of each kind chained into polylines; rulings
are split wherever they turn, so each straight ruling is one polyline). Triangulating
diagonals are not drawn. The design parameters are stored as document user text
(``File3dm.Strings``, key → str(value)), prefixed ``curvefold:``; the unit is the model unit
system.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from ..geometry.mesh import Mesh
from ..kernel.errors import InputError
from .atomic import atomic_path
from .mesh3d import check_metadata, crease_polylines
from .tables import UNITS, rgba8

__all__ = ["LAYERS", "write_3dm"]

#: Layer name, edge kind (``None`` for the surface) and RGBA colour (from
#: :data:`curvefold.io.tables.COLOURS`), in layer order.
LAYERS = (
    ("Surface", None, rgba8("surface")),
    ("Fold", "fold", rgba8("fold")),
    ("Seam", "seam", rgba8("seam")),
    ("Boundary", "boundary", rgba8("boundary")),
    ("Rulings", "ruling", rgba8("ruling")),
)
#: Turn (degrees) above which a ruling polyline is split.
_RULING_SPLIT_DEG = 1e-3


def write_3dm(
    path: str | os.PathLike,
    mesh: Mesh,
    *,
    unit: str = "unit",
    metadata: Mapping | None = None,
    name: str = "curvefold",
    version: int = 0,
) -> Path:
    """Write one state to a Rhino 3dm file.

    Parameters
    ----------
    path : path-like
    mesh : Mesh
        The state to write.
    unit : str
        Model unit, a name in :data:`curvefold.io.tables.UNITS` (``"unit"``: no unit system).
    metadata : mapping, optional
        Design parameters, written as document user text ``curvefold:<key>``.
    name : str
        Name of the surface mesh object; polylines are named ``<kind> <i>``.
    version : int
        3dm archive version (0 = the newest rhino3dm writes).

    Returns
    -------
    Path
    """
    try:
        import rhino3dm
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("writing 3dm needs rhino3dm: pip install 'curvefold[rhino]'") from exc
    if unit not in UNITS:
        raise InputError(f"unit must be one of {sorted(UNITS)} for a 3dm file, got {unit!r}")
    meta = check_metadata(metadata)
    x = np.asarray(mesh.vertices_coords, float)
    if not np.isfinite(x).all():
        raise InputError("mesh.vertices_coords must be finite")

    model = rhino3dm.File3dm()
    model.Settings.ModelUnitSystem = getattr(rhino3dm.UnitSystem, UNITS[unit].rhino)
    model.ApplicationName = "curvefold"
    layer_index = {layer: model.Layers.AddLayer(layer, colour) for layer, _, colour in LAYERS}

    def attributes(layer: str, object_name: str):
        attr = rhino3dm.ObjectAttributes()
        attr.LayerIndex = layer_index[layer]
        attr.Name = object_name
        return attr

    surface = rhino3dm.Mesh()
    surface.Vertices.UseDoublePrecisionVertices = True
    for p in x.tolist():
        surface.Vertices.AddPoint3d(*p)  # double precision (Add stores single)
    for a, b, c in mesh.triangulated().faces_vertices.tolist():
        surface.Faces.AddFace(a, b, c)
    surface.Normals.ComputeNormals()
    surface.Compact()
    model.Objects.AddMesh(surface, attributes("Surface", name))

    for layer, kind, _ in LAYERS:
        if kind is None:
            continue
        split = _RULING_SPLIT_DEG if kind == "ruling" else None
        for i, chain in enumerate(crease_polylines(mesh, kind, split_angle_deg=split)):
            points = [rhino3dm.Point3d(*p) for p in x[chain].tolist()]
            model.Objects.AddPolyline(points, attributes(layer, f"{kind} {i}"))

    for key, value in meta.items():
        model.Strings[f"curvefold:{key}"] = str(value)
    model.Strings["curvefold:unit"] = unit

    with atomic_path(path) as tmp:
        if not model.Write(str(tmp), version):
            raise OSError(f"rhino3dm could not write {path}")
    return Path(path)
