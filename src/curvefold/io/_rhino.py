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
* ``Boundary``: the end sections of every tube, closed polylines as degree-1 NURBS curves;
* ``crease pattern``, when a :class:`~curvefold.io.Layout` is given: the sheets laid
  flat beside the model at their printed size (millimetres on the page, in the document's
  unit), as on a cutting table, one sub-layer per operation in the layout's colour
  convention (``crease pattern::cut``, ``crease pattern::score - mountain``…), labels as
  text dots, the page frames on ``crease pattern::pages``.

Every sheet is a group (``"tube 1 · sheet A"``: its mesh, its two strips, its fold crease)
and every tube a group of all its objects (``"tube 1"``). Each object carries user text:
``curvefold:tube`` (1-based), ``curvefold:sheet`` (A or B; none for seams and end
sections, which belong to both sheets), ``curvefold:kind`` (sheet, strip, fold, seam,
boundary) and ``curvefold:fold_angle_deg`` (the state's 2α; for a crease, the mean of its
edges' measured fold angles). The file has three named views: ``perspective``, ``plan``
(from above) and ``section`` (level, along the horizontal direction in which the model is
thinnest: across a vault's arch, so it shows the arch).

A model of one sheet (a single fold) has no tube: its objects make one group named after the
sheet (``"single fold"``), carry no ``curvefold:tube`` or ``curvefold:sheet``, and its strips
take the names given (``RhinoOptions.strip_names``: ``"left strip"``, ``"right strip"``).

The unit system is the model's (``"unit"``, the model unit, is written as metres, the
convention of :data:`curvefold.io._tables.UNITS`). The design parameters are stored as
document user text (``File3dm.Strings``, key → str(value)), prefixed ``curvefold:``.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np

from ..geometry._mesh import Mesh
from ..geometry._topology import Topology
from ..kernel._arrays import distinct
from ..kernel._errors import InputError
from ._atomic import atomic_path
from ._layout import Layout
from ._mesh3d import check_metadata, crease_polylines
from ._tables import CREATOR, UNITS, rgb8, rgba8

__all__ = [
    "LAYERS",
    "PATTERN_LAYER",
    "SHEET_LETTERS",
    "RhinoOptions",
    "interpolating_spline",
    "write_3dm",
]

#: Layer name and RGBA colour (from :data:`curvefold.io._tables.COLOURS`), in layer order.
LAYERS = (
    ("Sheets", rgba8("surface")),
    ("Strips", rgba8("surface")),
    ("Fold", rgba8("fold")),
    ("Seam", rgba8("seam")),
    ("Boundary", rgba8("boundary")),
)


def interpolating_spline(
    t: np.ndarray, points: np.ndarray, degree: int
) -> tuple[np.ndarray, np.ndarray]:
    """The B-spline of degree k = min(``degree``, m − 1) through ``points`` (m, d) at increasing
    parameters ``t`` (m,): its knots (m + k + 1,) and control points (m, d).

    The spline of :func:`scipy.interpolate.make_interp_spline` (its default ends, "not-a-knot"):
    knots at the inner parameters but the first and last (k + 1) // 2 of them (for odd k; for
    k = 2 at the midpoints between parameters but the first and last), each end knot k + 1
    times; the control points solve the collocation equations. Row i of that system holds the
    k + 1 basis functions that do not vanish at t_i (Cox–de Boor, in its knot span, the last
    in the last span), so it is banded and, past :data:`DENSE_POINTS`, solved in O(m k²) time and
    memory; the matrix of a B-spline collocation is totally positive, so elimination needs no
    pivoting (de Boor, *A Practical Guide to Splines*, 2001, ch. XIII).

    Examples
    --------
    >>> knots, control = interpolating_spline(
    ...     np.array([0.0, 1.0]), np.array([[0.0, 0.0], [2.0, 1.0]]), 3
    ... )
    >>> knots.tolist(), control.tolist()  # two points: the segment between them
    ([0.0, 0.0, 1.0, 1.0], [[0.0, 0.0], [2.0, 1.0]])
    """
    m = len(t)
    k = min(degree, m - 1)
    inner = t if k % 2 else 0.5 * (t[1:] + t[:-1])
    drop = (k + 1) // 2 if k % 2 else k // 2
    knots = np.concatenate(
        [np.full(k + 1, t[0]), inner[drop : len(inner) - drop], np.full(k + 1, t[-1])]
    )
    span = np.clip(np.searchsorted(knots, t, side="right") - 1, k, m - 1)
    basis = np.ones((m, 1))  # the bases of degree d at t_i: functions span_i − d … span_i
    for d in range(1, k + 1):
        # t − knot of each function's start
        left = t[:, None] - knots[span[:, None] + np.arange(1 - d, 1)]
        right = knots[span[:, None] + np.arange(1, d + 1)] - t[:, None]  # its end − t
        ratio = _ratio(basis, right + left)
        # each function's part from the lower one on its left and on its right
        higher = np.zeros((m, d + 1))
        higher[:, :-1] += right * ratio
        higher[:, 1:] += left * ratio
        basis = higher
    return knots, _solve_banded(basis, span - k, np.asarray(points, float))


#: Up to this many points, the collocation system is solved dense (LAPACK: faster than the band's
#: Python loop, and its m² numbers at most 2 MB); beyond, on its band.
DENSE_POINTS = 512


def _ratio(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a / b, 0 where b is 0 (Cox–de Boor's convention for empty knot spans)."""
    return np.divide(a, b, out=np.zeros(np.broadcast_shapes(a.shape, b.shape)), where=b != 0)


def _solve_banded(rows: np.ndarray, first: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """x with A x = ``rhs`` (m, d), row i of A (m, m) holding ``rows[i]`` (m, w) in columns
    ``first[i]`` … ``first[i] + w − 1`` (nondecreasing, A totally positive): Gaussian elimination
    without pivoting on the band, O(m w²)."""
    m, w = rows.shape
    if m <= DENSE_POINTS:
        dense = np.zeros((m, m))
        dense[np.arange(m)[:, None], first[:, None] + np.arange(w)] = rows
        return np.linalg.solve(dense, rhs)
    band = np.zeros((m, 2 * w - 1))  # row i, columns i − w + 1 … i + w − 1
    band[np.arange(m)[:, None], first[:, None] - np.arange(m)[:, None] + w - 1 + np.arange(w)] = (
        rows
    )
    b = rhs.copy()
    for j in range(m - 1):  # rows below j reach column j only within w − 1 rows
        # row j + 1 + a holds A[r, j] at w − 2 − a, A[r, j + c] at w − 2 − a + c
        below = np.arange(j + 1, min(j + w, m))
        shift = w - 2 - np.arange(len(below))
        factor = band[below, shift] / band[j, w - 1]  # A[r, j] / A[j, j]
        band[below[:, None], shift[:, None] + np.arange(w)] -= factor[:, None] * band[j, w - 1 :]
        b[below] -= factor[:, None] * b[j]
    x = np.empty_like(b)
    for j in range(m - 1, -1, -1):
        right = min(w - 1, m - 1 - j)
        x[j] = (b[j] - band[j, w : w + right] @ x[j + 1 : j + 1 + right]) / band[j, w - 1]
    return x


def _nurbs_curve(rhino3dm, points: np.ndarray, t: np.ndarray, degree: int):
    """The NURBS curve of ``degree`` (fewer points: lower) through ``points`` (m, 3) at
    parameters t (m,)."""
    knots, control = interpolating_spline(t, points, degree)
    curve = rhino3dm.NurbsCurve(3, False, len(knots) - len(control), len(control))
    curve_knots, curve_points, point = curve.Knots, curve.Points, rhino3dm.Point4d
    for i, knot in enumerate(knots[1:-1].tolist()):  # Rhino leaves out the end knots
        curve_knots[i] = knot
    for i, (u, v, w) in enumerate(control.tolist()):
        curve_points[i] = point(u, v, w, 1.0)
    return curve


@dataclass(frozen=True, eq=False)
class RhinoOptions:
    """How :func:`write_3dm` writes a state: unit, user text, archive version and the crease
    pattern beside it.

    Attributes
    ----------
    unit : str
        Model unit, a name in :data:`curvefold.io._tables.UNITS`.
    metadata : mapping or None
        Design parameters, written as document user text ``curvefold:<key>``.
    version : int
        3dm archive version (0 = the newest rhino3dm writes).
    pattern : Layout or None
        The crease pattern to lay beside the model on the ``crease pattern`` layer.
    strip_names : sequence of str or None
        The strips' names, by strip (group of faces); None: ``"tube 1 · strip 1"``…
    """

    unit: str = "unit"
    metadata: Mapping[str, object] | None = None
    version: int = 0
    pattern: Layout | None = None
    strip_names: Sequence[str] | None = None


def write_3dm(
    path: str | os.PathLike,
    mesh: Mesh,
    topology: Topology,
    *,
    degree: int = 3,
    fold_angle: float | None = None,
    options: RhinoOptions = RhinoOptions(),
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
    degree : {3, 1}, keyword-only
        Of the crease curves: cubic through the samples of smooth creases, 1 for the
        polylines of rigid panels.
    fold_angle : float, optional, keyword-only
        2α of the state in degrees, recorded as the objects' user text.
    options : RhinoOptions, keyword-only
        Unit, metadata, archive version and the crease pattern laid beside the model.

    Returns
    -------
    Path
    """
    if not isinstance(options, RhinoOptions):
        raise InputError(
            f"options must be a RhinoOptions, got {type(options).__name__}", parameter="options"
        )
    unit, metadata, pattern = options.unit, options.metadata, options.pattern
    try:
        import rhino3dm as module
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("writing 3dm needs rhino3dm: pip install 'curvefold[rhino]'") from exc
    # its stubs call settable properties read-only and lack tables (Groups): untyped here
    rhino3dm: Any = module
    if unit not in UNITS:
        raise InputError(f"unit must be one of {sorted(UNITS)} for a 3dm file, got {unit!r}")
    faces = np.asarray(mesh.faces_vertices)
    if (
        faces.shape[1] != 4
        or (faces < 0).any()
        or not np.array_equal(faces, topology.faces_vertices)
    ):
        raise InputError(
            "write_3dm needs a mesh of ruling quads on the given topology "
            "(state.mesh(faces='quads'))"
        )
    if degree not in (1, 3):
        raise InputError(f"degree must be 1 or 3, got {degree!r}")
    meta = check_metadata(metadata)
    x = np.asarray(mesh.vertices_coords, float)
    if not np.isfinite(x).all():
        raise InputError("mesh.vertices_coords must be finite")
    t = topology.vertex_sample / max(int(topology.vertex_sample.max()), 1)
    curves: dict[tuple, object] = {}

    def crease_curve(chain: np.ndarray):  # a strip's side is a crease: its curve is made once
        key = tuple(chain.tolist())
        if key not in curves:
            curves[key] = _nurbs_curve(rhino3dm, x[chain], t[chain], degree)
        return curves[key]

    model = rhino3dm.File3dm()
    model.Settings.ModelUnitSystem = getattr(rhino3dm.UnitSystem, UNITS[unit].rhino)
    model.ApplicationName = CREATOR
    layer_index = {layer: model.Layers.AddLayer(layer, colour) for layer, colour in LAYERS}
    group_index: dict[str, int] = {}
    single = topology.sheets[0].label if len(topology.sheets) == 1 else None
    names = options.strip_names

    def group(name: str) -> int:
        if name not in group_index:
            g = rhino3dm.Group()
            g.Name = name
            model.Groups.Add(g)
            group_index[name] = model.Groups.FindName(name).Index
        return group_index[name]

    def attributes(
        layer: str,
        object_name: str,
        *,
        tube: int,
        kind: str,
        sheet: str | None = None,
        angle: float | None = fold_angle,
    ):
        attr = rhino3dm.ObjectAttributes()
        attr.LayerIndex = layer_index[layer]
        attr.Name = object_name
        attr.SetUserString("curvefold:kind", kind)
        if single is not None:  # one sheet, no tube: one group
            attr.AddToGroup(group(single))
            sheet = None
        else:
            attr.AddToGroup(group(f"tube {tube + 1}"))
            attr.SetUserString("curvefold:tube", str(tube + 1))
        if sheet is not None:
            attr.AddToGroup(group(f"tube {tube + 1} · sheet {sheet}"))
            attr.SetUserString("curvefold:sheet", sheet)
        if angle is not None:
            attr.SetUserString("curvefold:fold_angle_deg", f"{angle:.6g}")
        return attr

    for k, sheet in enumerate(topology.sheets):
        part = rhino3dm.Mesh()
        vertices, add_face = part.Vertices, part.Faces.AddFace
        vertices.UseDoublePrecisionVertices = True
        add_vertex = vertices.AddPoint3d  # double precision (Add stores single)
        for u, v, w in x[sheet.vertices].tolist():
            add_vertex(u, v, w)
        for a, b, c, d in sheet.faces_vertices.tolist():
            add_face(a, b, c, d)
        part.Normals.ComputeNormals()
        part.Compact()
        model.Objects.AddMesh(
            part,
            attributes(
                "Sheets", sheet.label, tube=k // 2, kind="sheet", sheet=SHEET_LETTERS[k % 2]
            ),
        )

    # Strips: quads (a_j, a_{j+1}, b_{j+1}, b_j) along each strip (Topology.tubes); strips 4 and 1
    # make sheet A.
    for g in distinct(topology.faces_group).tolist():
        rows = faces[topology.faces_group == g]
        sides = [np.append(rows[:, 0], rows[-1, 1]), np.append(rows[:, 3], rows[-1, 2])]
        a, b = (crease_curve(v) for v in sides)
        model.Objects.AddSurface(
            rhino3dm.NurbsSurface.CreateRuledSurface(a, b),
            attributes(
                "Strips",
                f"tube {g // 4 + 1} · strip {g % 4 + 1}" if names is None else names[g],
                tube=g // 4,
                kind="strip",
                sheet="A" if g % 4 in (0, 3) else "B",
            ),
        )

    # creases run along one lattice curve (a panel's fold lines, kind "fold" too, run across)
    ends = topology.vertex_curve[mesh.edges_vertices]
    along = replace(
        mesh,
        edges_kind=np.where(
            (ends[:, 0] == ends[:, 1]) | (mesh.edges_kind == "boundary"), mesh.edges_kind, "ruling"
        ),
    )
    edge_key = np.sort(mesh.edges_vertices, axis=1) @ np.array([len(x), 1])
    edge_order = np.argsort(edge_key, kind="stable")
    sheet_of = np.zeros(len(x), np.int64)  # the letter of a vertex's (last) sheet
    for k, s in enumerate(topology.sheets):
        sheet_of[s.vertices] = k % 2
    # the first strip (faces_group) on each vertex
    first_strip = np.full(len(x), np.iinfo(np.int64).max)
    np.minimum.at(first_strip, faces.reshape(-1), np.repeat(topology.faces_group, faces.shape[1]))
    for layer, kind in (("Fold", "fold"), ("Seam", "seam"), ("Boundary", "boundary")):
        for i, chain in enumerate(crease_polylines(along, kind)):
            tube = int(first_strip[chain[0]]) // 4
            steps = np.sort(np.stack([chain[:-1], chain[1:]], axis=1), axis=1) @ np.array(
                [len(x), 1]
            )
            angles = np.abs(
                mesh.edges_foldAngle[
                    edge_order[np.searchsorted(edge_key[edge_order], steps, side="right") - 1]
                ]
            )
            if kind == "boundary":
                curve = _polyline(rhino3dm, x[chain])
            else:
                chain = chain if t[chain[0]] < t[chain[-1]] else chain[::-1]
                curve = crease_curve(chain)
            model.Objects.AddCurve(
                curve,
                attributes(
                    layer,
                    f"{kind} {i + 1}",
                    tube=tube,
                    kind=kind,
                    sheet=SHEET_LETTERS[sheet_of[chain[0]]] if kind == "fold" else None,
                    angle=float(angles.mean()) if kind != "boundary" else fold_angle,
                ),
            )

    if pattern is not None:
        _add_pattern(rhino3dm, model, pattern, unit, x)
    for _, vi in _views(rhino3dm, x):
        model.NamedViews.Add(vi)

    for key, value in meta.items():
        model.Strings[f"curvefold:{key}"] = str(value)
    model.Strings["curvefold:unit"] = unit

    with atomic_path(path) as tmp:
        if not model.Write(str(tmp), options.version):
            raise OSError(f"rhino3dm could not write {path}")
    return Path(path)


#: The letters of a tube's two sheets, in sheet order.
SHEET_LETTERS = ("A", "B")
#: The parent layer of the laid-out crease pattern.
PATTERN_LAYER = "crease pattern"


def _polyline(rhino3dm, points: np.ndarray):
    """The polyline curve through points (n, 3), or (n, 2) on z = 0."""
    line = rhino3dm.Polyline(len(points))
    add = line.Add
    if points.shape[1] == 2:
        for u, v in points.tolist():
            add(u, v, 0.0)
    else:
        for u, v, w in points.tolist():
            add(u, v, w)
    return line.ToPolylineCurve()


def _add_pattern(rhino3dm, model, layout: Layout, unit: str, x: np.ndarray) -> None:
    """The layout's pages beside the model (to its right, on z = 0), at their printed size."""
    from ._dxf import page_grid
    from ._legend import check_layers, layer_look

    to_unit = UNITS["mm"].metres / UNITS[unit].metres  # page mm in the document's unit
    parent = rhino3dm.Layer()
    parent.Name = PATTERN_LAYER
    parent_index = model.Layers.Add(parent)
    parent_id = model.Layers.FindIndex(parent_index).Id

    def child(name: str, colour: str) -> int:
        layer = rhino3dm.Layer()
        layer.Name, layer.ParentLayerId, layer.Color = name, parent_id, (*rgb8(colour), 255)
        return model.Layers.Add(layer)

    keys = check_layers(None)
    looks = {key: layer_look(layout, key) for key in keys}
    index = {key: child(name, colour) for key, (name, colour, _) in looks.items()}
    frames = child("pages", "#808080")
    W, H = layout.page_size
    size = float(np.ptp(x, axis=0).max()) if len(x) else 0.0
    origin = (
        np.array([x[:, 0].max() + 0.25 * size if len(x) else 0.0, x[:, 1].min() if len(x) else 0.0])
        / to_unit
    )
    corners = page_grid(len(layout.pages), (W, H), 20.0)
    corners = corners - corners.min(axis=0) + origin

    def attr(layer: int, name: str):
        a = rhino3dm.ObjectAttributes()
        a.LayerIndex, a.Name = layer, name
        return a

    def polyline(points: np.ndarray, closed: bool) -> object:
        q = np.concatenate([points, points[:1]]) if closed else points
        return _polyline(rhino3dm, q * to_unit)

    for number, (page, corner) in enumerate(zip(layout.pages, corners), start=1):
        frame = np.array([corner, corner + (W, 0), corner + (W, H), corner + (0, H)])
        model.Objects.AddCurve(polyline(frame, True), attr(frames, f"page {number}"))
        for key in keys:
            if key == "labels":
                for t in page.labels():
                    u, v = np.asarray(t.position) + corner
                    model.Objects.AddTextDot(
                        t.text,
                        rhino3dm.Point3d(float(u) * to_unit, float(v) * to_unit, 0.0),
                        attr(index[key], t.text),
                    )
                continue
            for p in page.on_layer(key):
                model.Objects.AddCurve(
                    polyline(p.points + corner, p.closed),
                    attr(index[key], f"page {number} · {looks[key][0]}"),
                )


def _views(rhino3dm, x: np.ndarray) -> list[tuple[str, object]]:
    """The named views ``perspective``, ``plan`` and ``section`` of points (n, 3), each framing
    them."""
    lo, hi = (x.min(axis=0), x.max(axis=0)) if len(x) else (np.zeros(3), np.ones(3))
    centre, size = 0.5 * (lo + hi), max(float(np.linalg.norm(hi - lo)), 1e-9)
    flat = x[:, :2] - x[:, :2].mean(axis=0) if len(x) > 1 else np.eye(2)
    _, vectors = np.linalg.eigh(flat.T @ flat)
    thin = vectors[:, 0]  # the horizontal direction of least extent
    az, el = np.radians(-50.0), np.radians(22.0)  # the figures' view
    toward = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
    out = []
    for name, direction, up, parallel in (
        ("perspective", -toward, (0.0, 0.0, 1.0), False),
        ("plan", (0.0, 0.0, -1.0), (0.0, 1.0, 0.0), True),
        ("section", (thin[0], thin[1], 0.0), (0.0, 0.0, 1.0), True),
    ):
        vp = rhino3dm.ViewportInfo()
        if parallel:
            vp.ChangeToParallelProjection(True)
        else:
            vp.ChangeToPerspectiveProjection(2.0 * size, True, 50.0)
        d = np.asarray(direction, float)
        vp.SetCameraLocation(rhino3dm.Point3d(*(centre - 2.0 * size * d).tolist()))
        vp.SetCameraDirection(rhino3dm.Vector3d(*d.tolist()))
        vp.SetCameraUp(rhino3dm.Vector3d(*up))
        half = 0.6 * size if parallel else 0.3 * size
        vp.SetFrustum(-half, half, -half, half, 0.5 * size if parallel else 0.05 * size, 4.0 * size)
        vi = rhino3dm.ViewInfo()
        vi.Name, vi.Viewport = name, vp
        out.append((name, vi))
    return out
