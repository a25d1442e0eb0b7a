"""What a load falls on: the sheet seen from above, the halves of its span, its outward faces.

Pure functions of a model's nodes and membranes (:meth:`BarHingeModel.triangles`), shared
by the load cases of :mod:`._cases`:

* :func:`snow_areas`: the projected area of every triangle seen from above (0 where hidden);
* :func:`span_axis`: the horizontal direction of the span and the middle of it;
* :func:`projected_forces`: a vertical load per projected area on the seen triangles, on
  all of them or on the part beyond the middle of the span (each triangle cut exactly
  there, its share given to its corners by the linear shape functions);
* :func:`face_vectors`: every triangle's area times its unit normal, pointing out of the
  structure;
* :func:`beyond_shares`: the share of every triangle beyond a line, and how its corners
  carry it (the zones of a wind along the span).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    from ._model import BarHingeModel

__all__ = [
    "apex",
    "snow_areas",
    "span_axis",
    "span",
    "projected_forces",
    "face_vectors",
    "beyond_shares",
]


def apex(model: BarHingeModel) -> int:
    """The highest node (the first of equals).

    Examples
    --------
    >>> from curvefold.mechanics import BarHingeModel
    >>> x = np.array([[0.0, 0, 0], [1, 0, 2], [2, 0, 2]])
    >>> apex(BarHingeModel(x, [[0, 1], [1, 2]], [1.0, 1.0], [], [], np.ones(3)))  # first of two
    1
    """
    return int(np.argmax(model.nodes[:, 2]))


def _projected(model: BarHingeModel) -> tuple[np.ndarray, np.ndarray]:
    """The triangles' corners (n, 3) and their horizontal projections (n, 3, 2)."""
    triangles = model.triangles()[0]
    return triangles, model.nodes[triangles][..., :2]


def _signed_area(xy: np.ndarray) -> np.ndarray:
    """Signed area of triangles (..., 3, 2), counter-clockwise positive."""
    u, v = xy[..., 1, :] - xy[..., 0, :], xy[..., 2, :] - xy[..., 0, :]
    return 0.5 * (u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0])


def snow_areas(model: BarHingeModel) -> np.ndarray:
    """Projected area of every triangle of the sheet (:meth:`BarHingeModel.triangles`) seen
    from above, m², shape (n,): 0 where hidden.

    A triangle is seen when no other triangle passes above its centroid (higher by more
    than 1e-9 of the model's size); its horizontal projected area then carries the snow.

    Examples
    --------
    >>> from curvefold.mechanics import BarHingeModel
    >>> x = np.array([[0.0, 0, 0], [2, 0, 0], [0, 1, 0]])
    >>> flat = BarHingeModel(
    ...     x,
    ...     [[0, 1], [1, 2], [2, 0]],
    ...     np.ones(3),
    ...     [],
    ...     [],
    ...     np.ones(3),
    ...     membranes=np.array([[0, 1, 2, -1]]),
    ... )
    >>> snow_areas(flat).tolist()
    [1.0]
    """
    x = model.nodes[model.triangles()[0]]  # (n, 3, 3)
    xy = x[..., :2]
    area = np.abs(_signed_area(xy))
    centroid = x.mean(axis=1)
    covered = _covered(xy, x[..., 2], centroid, 1e-9 * max(model.size, 1e-300))
    return np.where(covered, 0.0, area)


def _covered(xy: np.ndarray, z: np.ndarray, points: np.ndarray, tol: float) -> np.ndarray:
    """For points (T, 3), the centroids of triangles (T, 3, 2) at heights z (T, 3): is another
    triangle above it?

    Triangles are binned on a uniform grid by their bounding boxes; each point is tested
    against the triangles of its cell (barycentric coordinates, then the height there).
    """
    T = len(xy)
    lo, hi = xy.min(axis=1), xy.max(axis=1)
    # a third of a triangle's extent: fewest pairs tested (measured)
    cell = float(np.median((hi - lo).max(axis=1))) / 3 if T else 0.0
    if not cell > 0:
        return np.zeros(T, bool)
    origin = lo.min(axis=0)
    i0 = np.floor((lo - origin) / cell).astype(np.int64)
    i1 = np.floor((hi - origin) / cell).astype(np.int64)
    width = int(i1[:, 0].max()) + 1
    spans = i1 - i0 + 1
    counts = spans[:, 0] * spans[:, 1]
    tri = np.repeat(np.arange(T), counts)
    k = np.arange(len(tri)) - np.repeat(np.cumsum(counts) - counts, counts)
    cx = i0[tri, 0] + k % spans[tri, 0]
    cy = i0[tri, 1] + k // spans[tri, 0]
    key = cy * width + cx
    order = np.argsort(key, kind="stable")
    key, tri = key[order], tri[order]
    p = points[:, :2]
    q = np.floor((p - origin) / cell).astype(np.int64)
    qkey = q[:, 1] * width + q[:, 0]
    start, stop = np.searchsorted(key, qkey, "left"), np.searchsorted(key, qkey, "right")
    n = stop - start
    query = np.repeat(np.arange(T), n)
    cand = tri[np.repeat(start, n) + np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)]
    a, b, c = xy[cand, 0], xy[cand, 1], xy[cand, 2]
    v0, v1, v2 = b - a, c - a, p[query] - a
    det = v0[:, 0] * v1[:, 1] - v0[:, 1] * v1[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (v2[:, 0] * v1[:, 1] - v2[:, 1] * v1[:, 0]) / det
        t = (v0[:, 0] * v2[:, 1] - v0[:, 1] * v2[:, 0]) / det
    inside = (det != 0) & (s >= 0) & (t >= 0) & (s + t <= 1) & (cand != query)
    height = (1 - s - t) * z[cand, 0] + s * z[cand, 1] + t * z[cand, 2]
    above = inside & (height > points[query, 2] + tol)
    out = np.zeros(T, bool)
    out[query[above]] = True
    return out


def span_axis(
    model: BarHingeModel, ends: tuple[np.ndarray, np.ndarray] | None = None
) -> tuple[np.ndarray, float]:
    """The horizontal unit direction of the span (2,) and the coordinate of its middle along it, m.

    With ``ends`` (the nodes of the end sections t = 0 and t = 1, where an arch is held),
    the span runs from the first's centroid to the second's, seen from above. Without, it
    is the principal direction of the seen area (its longest horizontal extent), pointing
    where its larger component is positive. The middle is half-way between the seen
    surface's extremes along it.

    Examples
    --------
    >>> from curvefold.mechanics import BarHingeModel
    >>> x = np.array([[0.0, 0, 0], [4, 0, 0], [4, 1, 0], [0, 1, 0]])  # a 4 m × 1 m plate
    >>> flat = BarHingeModel(
    ...     x,
    ...     [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
    ...     np.ones(5),
    ...     [],
    ...     [],
    ...     np.ones(4),
    ...     membranes=np.array([[0, 1, 2, 3]]),
    ... )
    >>> axis, middle = span_axis(flat)
    >>> axis.tolist(), middle
    ([1.0, 0.0], 2.0)
    """
    axis, lo, hi = span(model, ends)
    return axis, 0.5 * (lo + hi)


def span(
    model: BarHingeModel, ends: tuple[np.ndarray, np.ndarray] | None = None
) -> tuple[np.ndarray, float, float]:
    """The span's horizontal unit direction (2,) (:func:`span_axis`) and where the seen surface
    starts and ends along it, m.

    Examples
    --------
    >>> from curvefold.mechanics import BarHingeModel
    >>> x = np.array([[0.0, 0, 0], [4, 0, 0], [4, 1, 0], [0, 1, 0]])  # a 4 m × 1 m plate
    >>> flat = BarHingeModel(
    ...     x,
    ...     [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
    ...     np.ones(5),
    ...     [],
    ...     [],
    ...     np.ones(4),
    ...     membranes=np.array([[0, 1, 2, 3]]),
    ... )
    >>> span(flat)[1:]
    (0.0, 4.0)
    """
    triangles, xy = _projected(model)
    seen = snow_areas(model) > 0
    if ends is not None:
        axis = model.nodes[ends[1], :2].mean(axis=0) - model.nodes[ends[0], :2].mean(axis=0)
    else:
        # the seen area's second moment; on a triangle
        # ∫ x xᵀ dA = A/12 (Σ_k v_k v_kᵀ + (Σ_k v_k)(Σ_k v_k)ᵀ)
        area = snow_areas(model)
        total = max(area.sum(), 1e-300)
        corners, sums = (
            np.einsum("nki,nkj->nij", xy, xy),
            np.einsum("ni,nj->nij", xy.sum(1), xy.sum(1)),
        )
        centre = (area @ xy.mean(axis=1)) / total
        spread = np.einsum("n,nij->ij", area / 12, corners + sums) - total * np.outer(
            centre, centre
        )
        axis = np.linalg.eigh(spread)[1][:, -1]
        axis = axis if axis[np.argmax(np.abs(axis))] > 0 else -axis
    axis = axis / np.linalg.norm(axis)
    along = xy[seen] @ axis
    if not along.size:
        return axis, 0.0, 0.0
    return axis, float(along.min()), float(along.max())


def projected_forces(
    model: BarHingeModel,
    pressure: float,
    *,
    half: str | None = None,
    ends: tuple[np.ndarray, np.ndarray] | None = None,
) -> np.ndarray:
    """Nodal forces (P, 3), N, of a downward load ``pressure`` (Pa) per projected area on the seen
    triangles.

    ``half``: None, the whole seen surface (each triangle's corners carry a third of its
    load); ``"start"`` or ``"end"``, only the part before or beyond the middle of the span
    (:func:`span_axis`, ``ends`` passed on): every triangle is cut exactly at the middle
    and the part kept, of area A and centroid c, gives corner i the load p A N_i(c), N_i
    the triangle's linear shape functions in plan (exact for a uniform load).

    Examples
    --------
    >>> from curvefold.mechanics import BarHingeModel
    >>> x = np.array([[0.0, 0, 0], [4, 0, 0], [4, 1, 0], [0, 1, 0]])  # a 4 m × 1 m plate
    >>> flat = BarHingeModel(
    ...     x,
    ...     [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
    ...     np.ones(5),
    ...     [],
    ...     [],
    ...     np.ones(4),
    ...     membranes=np.array([[0, 1, 2, 3]]),
    ... )
    >>> whole, half = projected_forces(flat, 10.0), projected_forces(flat, 10.0, half="end")
    >>> round(float(whole[:, 2].sum()), 12), round(float(half[:, 2].sum()), 12)
    (-40.0, -20.0)
    """
    triangles, xy = _projected(model)
    areas = snow_areas(model)
    f = np.zeros((len(model.nodes), 3))
    if half is None:
        f[:, 2] -= np.bincount(
            triangles.ravel(), np.repeat(pressure * areas / 3, 3), minlength=len(f)
        )
        return f
    axis, middle = span_axis(model, ends)
    beyond = (xy @ axis - middle) * (
        1.0 if half == "end" else -1.0
    )  # (n, 3): ≥ 0 on the loaded side
    area, centroid = _clipped(xy, beyond)
    seen = areas > 0
    area = np.where(seen, area, 0.0)
    shape = _barycentric(xy, centroid)  # (n, 3)
    f[:, 2] -= np.bincount(
        triangles.ravel(), (pressure * area[:, None] * shape).ravel(), minlength=len(f)
    )
    return f


def _clipped(xy: np.ndarray, d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Area (n,) and centroid (n, 2) of the part of every triangle (n, 3, 2) where the
    linear function with corner values d (n, 3) is ≥ 0 (Sutherland–Hodgman on one line)."""
    n = len(xy)
    nxt = [1, 2, 0]
    p, q, dp, dq = xy, xy[:, nxt], d, d[:, nxt]
    cross = (dp >= 0) != (dq >= 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        w = np.where(cross, dp / (dp - dq), 0.0)
    cut = p + w[..., None] * (q - p)
    points = np.stack([p, cut], axis=2).reshape(
        n, 6, 2
    )  # corner 0, cut 0-1, corner 1, cut 1-2, ...
    keep = np.stack([dp >= 0, cross], axis=2).reshape(n, 6)
    order = np.argsort(~keep, axis=1, kind="stable")
    points = np.take_along_axis(points, order[..., None], axis=1)
    count = keep.sum(axis=1)
    last = points[np.arange(n), np.maximum(count - 1, 0)]
    points = np.where(
        (np.arange(6) < count[:, None])[..., None], points, last[:, None]
    )  # padded by the last
    a, b = points, np.roll(points, -1, axis=1)
    c = a[..., 0] * b[..., 1] - b[..., 0] * a[..., 1]
    signed = 0.5 * c.sum(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        centroid = ((a + b) * c[..., None]).sum(axis=1) / (6 * signed[:, None])
    empty = count < 3
    centroid = np.where((empty | (signed == 0))[:, None], xy.mean(axis=1), centroid)
    return np.where(empty, 0.0, np.abs(signed)), centroid


def beyond_shares(d: np.ndarray) -> np.ndarray:
    """∫ N_i dA / A over the part of every triangle where a linear function with corner values
    d (n, 3) is ≥ 0, shape (n, 3): N_i the triangle's shape functions. Exact: the part is cut
    where the function crosses 0, and N_i, linear, integrates to its value at the part's
    centroid times its area (the whole triangle: a third each).

    Examples
    --------
    >>> beyond_shares(np.array([[1.0, 1.0, 1.0], [-1.0, -1.0, -1.0]])).round(12).tolist()
    [[0.333333333333, 0.333333333333, 0.333333333333], [0.0, 0.0, 0.0]]
    >>> round(float(beyond_shares(np.array([[-1.0, 1.0, 1.0]])).sum()), 12)  # 1 − (1/2)²
    0.75
    """
    unit = np.broadcast_to(np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]), (len(d), 3, 2))
    area, centroid = _clipped(unit, d)
    return 2 * area[:, None] * _barycentric(unit, centroid)


def _barycentric(xy: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Barycentric coordinates (n, 3) of points (n, 2) in triangles (n, 3, 2); thirds for a
    degenerate triangle."""
    v0, v1, v2 = xy[:, 1] - xy[:, 0], xy[:, 2] - xy[:, 0], points - xy[:, 0]
    det = v0[:, 0] * v1[:, 1] - v0[:, 1] * v1[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (v2[:, 0] * v1[:, 1] - v2[:, 1] * v1[:, 0]) / det
        t = (v0[:, 0] * v2[:, 1] - v0[:, 1] * v2[:, 0]) / det
    out = np.stack([1 - s - t, s, t], axis=1)
    return np.where((det != 0)[:, None], out, 1.0 / 3)


def face_vectors(model: BarHingeModel) -> tuple[np.ndarray, np.ndarray]:
    """Every triangle's corners (n, 3) and its area times its unit normal (n, 3), m², pointing out
    of the structure.

    The faces keep the orientation of the mesh, all turned if need be so that the volume
    they enclose seen from the nodes' centroid is positive (the normals of a closed tube
    then point out of it, an arch's away from its centre); a sheet that encloses no
    volume (flat, to 1e-9) has its normals pointing up.

    Examples
    --------
    >>> from curvefold.mechanics import BarHingeModel
    >>> x = np.array([[0.0, 0, 0], [0, 1, 0], [2, 0, 0]])
    >>> flat = BarHingeModel(
    ...     x,
    ...     [[0, 1], [1, 2], [2, 0]],
    ...     np.ones(3),
    ...     [],
    ...     [],
    ...     np.ones(3),
    ...     membranes=np.array([[0, 1, 2, -1]]),
    ... )
    >>> (face_vectors(flat)[1] + 0.0).tolist()  # listed clockwise from above, turned up
    [[0.0, 0.0, 1.0]]
    """
    triangles = model.triangles()[0]
    x = model.nodes[triangles]
    vectors = 0.5 * np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0])
    volume = float(((x.mean(axis=1) - model.nodes.mean(axis=0)) * vectors).sum()) / 3
    scale = max(model.size, 1e-300) ** 3
    if abs(volume) > 1e-9 * scale:
        sign = np.sign(volume)
    else:
        sign = -1.0 if vectors[:, 2].sum() < 0 else 1.0
    return triangles, sign * vectors
