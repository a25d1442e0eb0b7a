"""Rhino ``.3dm`` of one structure state, written with ``rhino3dm`` (imported when called).

What a Rhino user works with, each kind on its own layer:

* ``Sheets``: one mesh object per developed sheet (``"tube 1 · sheet A"``), one quad per
  ruling quad (per panel, for rigid panels), double-precision vertices;
* ``Strips``: each developable strip as a ruled NURBS surface between its two crease
  curves (``"tube 1 · strip 1"``): the two curves share their parameter, so the lines of
  equal parameter, the surface's isocurves across the strip, are the rulings at the kept
  samples (and close to them between);
* ``Fold``, ``Seam``: every crease of every tube as a cubic NURBS curve through its
  samples (interpolating, parameter t in [0, 1] shared by all creases);
  with ``degree=1`` (rigid panels) the creases are their polylines, and each strip,
  ruled between two of them, is its planar panels exactly;
* ``Boundary``: the end sections of every tube, closed polylines as degree-1 NURBS curves.

The unit system is the model's (``"unit"``, the model unit, is written as metres, the
convention of :data:`curvefold.io.tables.UNITS`). The design parameters are stored as
document user text (``File3dm.Strings``, key → str(value)), prefixed ``curvefold:``.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import replace
from pathlib import Path

import numpy as np

from ..geometry.mesh import Mesh
from ..geometry.topology import Topology
from ..kernel.errors import InputError
from .atomic import atomic_path
from .mesh3d import check_metadata, crease_polylines
from .tables import CREATOR, UNITS, rgba8

__all__ = ["LAYERS", "write_3dm"]

#: Layer name and RGBA colour (from :data:`curvefold.io.tables.COLOURS`), in layer order.
LAYERS = (
    ("Sheets", rgba8("surface")),
    ("Strips", rgba8("surface")),
    ("Fold", rgba8("fold")),
    ("Seam", rgba8("seam")),
    ("Boundary", rgba8("boundary")),
)


def _nurbs_curve(rhino3dm, points: np.ndarray, t: np.ndarray, degree: int):
    """The NURBS curve of ``degree`` (fewer points: lower) through ``points`` (m, 3) at parameters t (m,)."""
    from scipy.interpolate import make_interp_spline

    spline = make_interp_spline(t, points, k=min(degree, len(t) - 1))
    curve = rhino3dm.NurbsCurve(3, False, spline.k + 1, len(spline.c))
    for i, knot in enumerate(spline.t[1:-1].tolist()):  # Rhino leaves out the end knots
        curve.Knots[i] = knot
    for i, p in enumerate(spline.c.tolist()):
        curve.Points[i] = rhino3dm.Point4d(*p, 1.0)
    return curve


def write_3dm(
    path: str | os.PathLike,
    mesh: Mesh,
    topology: Topology,
    *,
    unit: str = "unit",
    metadata: Mapping | None = None,
    version: int = 0,
    degree: int = 3,
) -> Path:
    """Write one state to a Rhino 3dm file (see the module notes).

    Parameters
    ----------
    path : path-like
    mesh : Mesh
        The state to write, on the quads of ``topology`` (``state.mesh(faces="quads")``).
    topology : Topology
        The mesh's topology (:meth:`Structure.topology` with ``faces="quads"``): its
        sheets, and the samples of its vertices.
    unit : str
        Model unit, a name in :data:`curvefold.io.tables.UNITS`.
    metadata : mapping, optional
        Design parameters, written as document user text ``curvefold:<key>``.
    version : int
        3dm archive version (0 = the newest rhino3dm writes).
    degree : {3, 1}
        Of the crease curves: cubic through the samples of smooth creases, 1 for the
        polylines of rigid panels.

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
    faces = np.asarray(mesh.faces_vertices)
    if faces.shape[1] != 4 or (faces < 0).any() or not np.array_equal(faces, topology.faces_vertices):
        raise InputError("write_3dm needs a mesh of ruling quads on the given topology (state.mesh(faces='quads'))")
    if degree not in (1, 3):
        raise InputError(f"degree must be 1 or 3, got {degree!r}")
    meta = check_metadata(metadata)
    x = np.asarray(mesh.vertices_coords, float)
    if not np.isfinite(x).all():
        raise InputError("mesh.vertices_coords must be finite")
    t = topology.vertex_sample / max(int(topology.vertex_sample.max()), 1)

    model = rhino3dm.File3dm()
    model.Settings.ModelUnitSystem = getattr(rhino3dm.UnitSystem, UNITS[unit].rhino)
    model.ApplicationName = CREATOR
    layer_index = {layer: model.Layers.AddLayer(layer, colour) for layer, colour in LAYERS}

    def attributes(layer: str, object_name: str):
        attr = rhino3dm.ObjectAttributes()
        attr.LayerIndex = layer_index[layer]
        attr.Name = object_name
        return attr

    for sheet in topology.sheets:
        part = rhino3dm.Mesh()
        part.Vertices.UseDoublePrecisionVertices = True
        for p in x[sheet.vertices].tolist():
            part.Vertices.AddPoint3d(*p)  # double precision (Add stores single)
        for a, b, c, d in sheet.faces_vertices.tolist():
            part.Faces.AddFace(a, b, c, d)
        part.Normals.ComputeNormals()
        part.Compact()
        model.Objects.AddMesh(part, attributes("Sheets", sheet.label))

    # Strips: quads (a_j, a_{j+1}, b_{j+1}, b_j) along each strip (Topology.tubes).
    for g in np.unique(topology.faces_group).tolist():
        rows = faces[topology.faces_group == g]
        sides = [np.append(rows[:, 0], rows[-1, 1]), np.append(rows[:, 3], rows[-1, 2])]
        a, b = (_nurbs_curve(rhino3dm, x[v], t[v], degree) for v in sides)
        model.Objects.AddSurface(rhino3dm.NurbsSurface.CreateRuledSurface(a, b),
                                 attributes("Strips", f"tube {g // 4 + 1} · strip {g % 4 + 1}"))

    # creases run along one lattice curve (a panel's fold lines, kind "fold" too, run across)
    ends = topology.vertex_curve[mesh.edges_vertices]
    along = replace(mesh, edges_kind=np.where((ends[:, 0] == ends[:, 1]) | (mesh.edges_kind == "boundary"), mesh.edges_kind, "ruling"))
    for layer, kind in (("Fold", "fold"), ("Seam", "seam"), ("Boundary", "boundary")):
        for i, chain in enumerate(crease_polylines(along, kind)):
            if kind == "boundary":
                points = [rhino3dm.Point3d(*p) for p in x[chain].tolist()]
                curve = rhino3dm.PolylineCurve(points)
            else:
                chain = chain if t[chain[0]] < t[chain[-1]] else chain[::-1]
                curve = _nurbs_curve(rhino3dm, x[chain], t[chain], degree)
            model.Objects.AddCurve(curve, attributes(layer, f"{kind} {i + 1}"))

    for key, value in meta.items():
        model.Strings[f"curvefold:{key}"] = str(value)
    model.Strings["curvefold:unit"] = unit

    with atomic_path(path) as tmp:
        if not model.Write(str(tmp), version):
            raise OSError(f"rhino3dm could not write {path}")
    return Path(path)
