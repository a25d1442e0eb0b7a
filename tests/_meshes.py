"""Small synthetic structures with known geometry for the exporter tests.

A strip of ``n`` unit-wide panels (``rows`` rows of cells, each cell two triangles) is
folded along its ``n - 1`` vertical fold lines, all by the same angle (valley positive).
With ``n = 4`` and 90° it closes into a square tube whose two end edges are a seam.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.testing import assert_allclose

from curvefold.geometry import Mesh, fold_angles
from curvefold.io._fold import COORDINATE_RTOL


@dataclass(frozen=True)
class Motion:
    crease_pattern: Mesh
    angles_deg: np.ndarray  # (K,)
    coords: np.ndarray  # (K, V, 3)
    seam_partners: np.ndarray  # (P, 2)

    def state(self, k: int) -> Mesh:
        return self.crease_pattern.with_coords(self.coords[k])

    @property
    def folded(self) -> list[tuple[str, Mesh]]:
        return [(f"{a:g} deg", self.state(k)) for k, a in enumerate(self.angles_deg)]


def _grid(n: int, rows: int, width: float, height: float) -> tuple[np.ndarray, np.ndarray]:
    """Crease-pattern vertices (V, 3) and counter-clockwise triangles (F, 3) of the strip."""
    i, j = np.meshgrid(np.arange(n + 1), np.arange(rows + 1), indexing="ij")
    xy = (
        np.stack([i * width, j * height / rows, np.zeros_like(i, float)], axis=-1)
        .reshape(-1, 3)
        .astype(float)
    )
    vid = lambda a, b: a * (rows + 1) + b  # noqa: E731
    faces = []
    for a in range(n):
        for b in range(rows):
            p, q, r, s = vid(a, b), vid(a + 1, b), vid(a, b + 1), vid(a + 1, b + 1)
            faces += [[p, q, s], [p, s, r]]
    return xy, np.array(faces)


def fold_strip(xy: np.ndarray, n: int, width: float, angle_deg: float) -> np.ndarray:
    """Positions (V, 3) of the strip folded by ``angle_deg`` at every fold line."""
    phi = np.radians(angle_deg) * np.arange(n)
    direction = np.stack([np.cos(phi), np.zeros(n), np.sin(phi)], axis=-1)
    start = np.concatenate([[np.zeros(3)], np.cumsum(width * direction, axis=0)[:-1]])
    panel = np.clip(np.floor(xy[:, 0] / width + 1e-9).astype(int), 0, n - 1)
    u = xy[:, 0] - panel * width
    return start[panel] + u[:, None] * direction[panel] + np.outer(xy[:, 1], [0.0, 1.0, 0.0])


def strip_motion(
    n: int = 2,
    rows: int = 2,
    angles_deg=(0.0, 30.0, 60.0, 90.0),
    *,
    design_index: int = -1,
    seam: bool = False,
    width: float = 1.0,
    height: float = 1.0,
    offset=(0.0, 0.0, 0.0),
) -> Motion:
    """A folding strip: crease pattern at ``angles_deg[design_index]`` plus all states."""
    xy, faces = _grid(n, rows, width, height)
    edges, kinds = [], []
    seen = {}
    for f in faces:
        for a, b in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0])):
            key = (min(a, b), max(a, b))
            if key in seen:
                continue
            seen[key] = len(edges)
            edges.append([a, b])
            (xa, ya), (xb, yb) = xy[a, :2], xy[b, :2]
            if xa != xb and ya != yb:
                kinds.append("diagonal")
            elif xa == xb and 0 < xa < n * width:
                kinds.append("fold")
            elif xa == xb:
                kinds.append("seam" if seam else "boundary")
            elif ya in (0.0, height):
                kinds.append("boundary")
            else:
                kinds.append("ruling")
    edges = np.array(edges)
    kinds = np.array(kinds)
    angles = np.asarray(angles_deg, float)
    coords = np.stack([fold_strip(xy, n, width, a) for a in angles]) + np.asarray(offset, float)
    design = angles[design_index]
    fold_angle = np.where(kinds == "fold", design, 0.0)
    assignment = np.where(
        kinds == "fold",
        "V" if design >= 0 else "M",
        np.where(np.isin(kinds, ("boundary", "seam")), "B", "F"),
    )
    cp = Mesh(
        vertices_coords=xy,
        edges_vertices=edges,
        edges_assignment=assignment,
        edges_foldAngle=fold_angle,
        faces_vertices=faces,
        edges_kind=kinds,
        faces_group=np.arange(len(faces)) // (2 * rows),
    )
    seam_ids = np.flatnonzero(kinds == "seam")
    partners = np.zeros((0, 2), int)
    if seam:  # pair the seam edges at x = 0 with those at x = n, row by row
        left = sorted(
            (e for e in seam_ids if xy[edges[e, 0], 0] == 0),
            key=lambda e: xy[edges[e]].min(axis=0)[1],
        )
        right = sorted(
            (e for e in seam_ids if xy[edges[e, 0], 0] != 0),
            key=lambda e: xy[edges[e]].min(axis=0)[1],
        )
        partners = np.array(list(zip(left, right)))
    return Motion(cp, angles, coords, partners)


def measured_fold_angles(mesh: Mesh) -> np.ndarray:
    """Fold angles (E,) measured from the mesh's own coordinates."""
    return fold_angles(mesh.vertices_coords, mesh.faces_vertices, mesh.edges_vertices)


def _rotation(
    axis_point: np.ndarray, axis_dir: np.ndarray, child_point: np.ndarray, angle_deg: float
) -> np.ndarray:
    """4x4 rotation about a crease line in the plane z = 0, valley positive for the child side."""
    a = axis_dir / np.linalg.norm(axis_dir)
    r = child_point - axis_point
    if np.cross(a, r)[2] < 0:  # orient the axis so that a positive angle lifts the child toward +z
        a = -a
    t = np.radians(angle_deg)
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    R = np.eye(3) + np.sin(t) * K + (1 - np.cos(t)) * K @ K
    M = np.eye(4)
    M[:3, :3] = R
    M[:3, 3] = axis_point - R @ axis_point
    return M


def oblique_motion(angles_deg=(0.0, 20.0, 45.0, 70.0), ratio: float = -0.7) -> Motion:
    """Three panels hinged on two non-parallel creases; chiral when folded.

    Crease 1 (x = 1) folds by ``a`` and crease 2 (from (2, 0) to (2.4, 1)) by ``ratio * a``
    for each ``a`` in ``angles_deg``; the crease pattern carries the last state's angles.
    """
    xy = np.array([[0, 0], [1, 0], [2, 0], [3, 0], [0, 1], [1, 1], [2.4, 1], [3, 1]], float)
    xyz = np.column_stack([xy, np.zeros(len(xy))])
    faces = np.array([[0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6]])
    # vertices on a crease belong to the parent panel
    panel_of_vertex = np.array([0, 0, 1, 2, 0, 0, 1, 2])
    edges, kinds = [], []
    for f in faces:
        for a, b in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0])):
            if any({a, b} == set(e) for e in edges):
                continue
            edges.append([a, b])
            pair = {int(a), int(b)}
            kinds.append(
                "fold"
                if pair in ({1, 5}, {2, 6})
                else "diagonal"
                if pair in ({0, 5}, {1, 6}, {2, 7})
                else "boundary"
            )
    edges, kinds = np.array(edges), np.array(kinds)
    coords = []
    for a in angles_deg:
        T1 = _rotation(xyz[1], xyz[5] - xyz[1], xyz[2], a)
        T2 = T1 @ _rotation(xyz[2], xyz[6] - xyz[2], xyz[3], ratio * a)
        T = np.stack([np.eye(4), T1, T2])[panel_of_vertex]
        coords.append(np.einsum("vij,vj->vi", T, np.column_stack([xyz, np.ones(len(xyz))]))[:, :3])
    coords = np.array(coords)
    last = angles_deg[-1]
    fold_angle = np.zeros(len(edges))
    for e, (a, b) in enumerate(edges):
        if {int(a), int(b)} == {1, 5}:
            fold_angle[e] = last
        elif {int(a), int(b)} == {2, 6}:
            fold_angle[e] = ratio * last
    assignment = np.where(
        fold_angle > 0, "V", np.where(fold_angle < 0, "M", np.where(kinds == "boundary", "B", "F"))
    )
    cp = Mesh(
        vertices_coords=xyz,
        edges_vertices=edges,
        edges_assignment=assignment,
        edges_foldAngle=fold_angle,
        faces_vertices=faces,
        edges_kind=kinds,
        faces_group=np.array([0, 0, 1, 1, 2, 2]),
    )
    return Motion(cp, np.asarray(angles_deg, float), coords, np.zeros((0, 2), int))


def two_sheet_tube(angles_deg=(0.0, 45.0, 90.0)) -> Motion:
    """A square tube from two L-shaped sheets (2 panels each) glued by two seams.

    Sheet B is sheet A turned half a turn about the tube axis (through x = z = 0.5); in the
    crease pattern it lies beside A, shifted by 3 in x. At 90 degrees both seams close.
    """
    a = strip_motion(2, 2, angles_deg, seam=True)
    cp = a.crease_pattern
    V, E = len(cp.vertices_coords), len(cp.edges_vertices)
    b_coords = a.coords * [-1, 1, -1] + [1, 0, 1]  # (x, y, z) -> (1 - x, y, 1 - z)
    seam_a = np.flatnonzero(cp.edges_kind == "seam")
    at_x0 = seam_a[cp.vertices_coords[cp.edges_vertices[seam_a, 0], 0] == 0]
    at_x2 = seam_a[cp.vertices_coords[cp.edges_vertices[seam_a, 0], 0] != 0]
    order = lambda ids: ids[
        np.argsort(cp.vertices_coords[cp.edges_vertices[ids]].min(axis=1)[:, 1])
    ]  # noqa: E731
    at_x0, at_x2 = order(at_x0), order(at_x2)
    partners = np.concatenate(
        [np.column_stack([at_x0, at_x2 + E]), np.column_stack([at_x2, at_x0 + E])]
    )
    both = Mesh(
        vertices_coords=np.concatenate([cp.vertices_coords, cp.vertices_coords + [3.0, 0, 0]]),
        edges_vertices=np.concatenate([cp.edges_vertices, cp.edges_vertices + V]),
        edges_assignment=np.concatenate([cp.edges_assignment] * 2),
        edges_foldAngle=np.concatenate([cp.edges_foldAngle] * 2),
        faces_vertices=np.concatenate([cp.faces_vertices, cp.faces_vertices + V]),
        edges_kind=np.concatenate([cp.edges_kind] * 2),
        faces_group=np.concatenate([cp.faces_group, cp.faces_group + cp.faces_group.max() + 1]),
    )
    return Motion(both, a.angles_deg, np.concatenate([a.coords, b_coords], axis=1), partners)


def assert_written(got, want) -> None:
    """Coordinates as a FOLD file holds them: within ``COORDINATE_RTOL`` of the sheet's size."""
    got, want = np.asarray(got, float), np.asarray(want, float)
    assert got.shape == want.shape
    assert_allclose(got, want, rtol=0, atol=COORDINATE_RTOL * np.ptp(want, axis=0).max())
