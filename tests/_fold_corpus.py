"""A corpus of small FOLD files in the forms other tools write, each with its known degrees of
freedom.

The geometry is built here (nothing is copied from another tool): a Miura-ori folded in
closed form, a rigidly folded square twist and a folded waterbomb base found by
least squares on their panels' constraints, a flat-folded diagonal. Each is then written the
way a tool writes it:

* ``miura-mathematica.fold``: quads, a folded form only, 6 decimals (as the FOLD repository's
  examples by Mathematica are);
* ``miura-origami-simulator.fold``: as Origami Simulator's "Save FOLD" writes a simulated
  sheet: triangles (``F`` facet edges), a folded form only, Y up, single-precision
  coordinates, ``edges_foldAngle`` the target angles with ``null`` on boundary edges;
* ``square-twist.fold``: a rigidly folded square twist, quads, a folded form only, 6 decimals;
* ``waterbomb.fold``: a waterbomb base folded in space, by hand: triangles, no fold angles;
* ``diagonal-flat-folded.fold``: a square folded flat along its diagonal, as ``fold-convert
  --flat-fold`` writes it (2D coordinates, ``faces_flatFoldTransform``,
  ``vertices_flatUnfoldCoords``, ``edges_faces`` with ``null``);
* ``miura-cp-frames.fold``: a crease pattern and two folded frames inheriting it, with a
  byte-order mark, FOLD 1.2's ``U``, ``J`` and ``C`` assignments and keys of another tool.

Known degrees of freedom (internal, rigid panels): a Miura-ori of quads has one (Schenk and
Guest 2013); a rigidly foldable square twist has one (Evans, Lang, Magleby and Howell 2015);
a single vertex of degree n with rigid sectors is a spherical linkage of n − 3 (5 for the
waterbomb base's 8 creases). A simulated Miura-ori's facet (F) edges lie between coplanar
triangles and are no hinges: it has the Miura-ori's one (were they hinges, a triangulated
disk whose constraints are independent has 3V − E − 6 = B − 3, B its boundary edges).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from curvefold.analysis import Framework
from curvefold.geometry import fold_angles

#: The corpus: file name -> internal degrees of freedom of its folded frames.
KNOWN_DOF = {
    "miura-mathematica.fold": 1,
    "miura-origami-simulator.fold": 1,  # its facet (F) edges flat: the Miura-ori's one
    "square-twist.fold": 1,
    "waterbomb.fold": 5,
    "miura-cp-frames.fold": 1,
}


def miura(
    rows: int = 3,
    cols: int = 4,
    a: float = 1.0,
    b: float = 1.0,
    gamma: float = np.radians(60),
    height: float = 0.0,
) -> np.ndarray:
    """A Miura-ori of ``rows`` × ``cols`` parallelograms (sides a, b, angle γ) folded to zigzag
    height H, vertices (rows + 1, cols + 1, 3).

    Row lines are zigzags P_i = (i L, 0, H (i mod 2)) with L² + H² = a², translated by steps
    (±δ, w, 0) that alternate in sign, δ = a b cos γ / L: every panel is a parallelogram with
    the angle γ or π − γ of the flat pattern (H = 0), so the state is isometric to it and
    every vertex is flat-foldable.
    """
    L = np.sqrt(a * a - height * height)
    delta = a * b * np.cos(gamma) / L
    w = np.sqrt(b * b - delta * delta)
    i = np.arange(cols + 1)
    P = np.stack([i * L, np.zeros_like(i, float), height * (i % 2)], axis=1)
    steps = np.array([[delta * (-1) ** j, w, 0.0] for j in range(rows)])
    origins = np.concatenate([np.zeros((1, 3)), np.cumsum(steps, axis=0)])
    return origins[:, None, :] + P[None, :, :]


def grid_faces(rows: int, cols: int) -> list[list[int]]:
    """Counter-clockwise quads of a (rows + 1) × (cols + 1) vertex grid, vertex (j, i) = j (cols
    + 1) + i."""
    n = cols + 1
    return [
        [j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i]
        for j in range(rows)
        for i in range(cols)
    ]


def edges_of(faces: list[list[int]]) -> list[list[int]]:
    """Every face side once, sorted."""
    return sorted(
        {tuple(sorted((f[k], f[(k + 1) % len(f)]))) for f in faces for k in range(len(f))}
    )


def assignment_of(
    x: np.ndarray, faces: list[list[int]], edges: list[list[int]]
) -> tuple[list[str], np.ndarray]:
    """M/V/B from the measured dihedral angles (B on one face), and the angles."""
    fv = _padded(faces)
    angle = fold_angles(x, fv, np.array(edges))
    counts = {}
    for f in faces:
        for k in range(len(f)):
            key = tuple(sorted((f[k], f[(k + 1) % len(f)])))
            counts[key] = counts.get(key, 0) + 1
    out = [
        "B" if counts[tuple(e)] == 1 else "V" if angle[i] > 0 else "M" if angle[i] < 0 else "F"
        for i, e in enumerate(edges)
    ]
    return out, np.where(np.array(out) == "B", 0.0, angle)


def _padded(faces: list[list[int]]) -> np.ndarray:
    k = max(map(len, faces))
    return np.array([f + [-1] * (k - len(f)) for f in faces])


def square_twist(
    psi: float = np.radians(30), side: float = 0.5, pleat: float = 0.4
) -> tuple[np.ndarray, list[list[int]]]:
    """The crease pattern of a square twist: a central square turned by ψ/3, a pleat of two parallel
    creases on each side, their directions the side's outward normal turned by ψ, and a square in
    every corner (16 vertices, 9 quads). Every vertex is flat-foldable (its pleat lines are 90°
    apart)."""
    turn = psi / 3
    C = (
        np.array([[np.cos(t), np.sin(t)] for t in np.radians([45, 135, 225, 315]) + turn])
        * side
        / np.sqrt(2)
    )
    d = []
    for k in range(4):
        e = (C[(k + 1) % 4] - C[k]) / np.linalg.norm(C[(k + 1) % 4] - C[k])
        d.append(np.cos(psi) * np.array([e[1], -e[0]]) + np.sin(psi) * e)
    pts, ends = list(C), {}
    for k in range(4):
        ends[k] = (len(pts), len(pts) + 1)
        pts += [C[k] + pleat * d[k], C[(k + 1) % 4] + pleat * d[k]]
    corners = []
    for k in range(4):
        corners.append(len(pts))
        pts.append(C[k] + pleat * (d[k - 1] + d[k]))
    faces = [[0, 1, 2, 3]]
    for k in range(4):
        faces.append([k, ends[k][0], ends[k][1], (k + 1) % 4])
        faces.append([k, ends[(k - 1) % 4][1], corners[k], ends[k][0]])
    return np.column_stack([np.array(pts), np.zeros(len(pts))]), faces


def fold_rigidly(
    flat: np.ndarray,
    faces: list[list[int]],
    *,
    drive: tuple[int, int],
    angle: float,
    fixed: list[int],
    seed: int,
) -> np.ndarray:
    """A state of rigid panels isometric to ``flat`` with the crease ``drive`` folded to
    ``angle`` degrees, found by least squares from a seeded random lift (panels' lengths,
    diagonals and planarity, the ``fixed`` vertices held, the driving crease's dihedral
    angle)."""
    from scipy.optimize import least_squares

    fv, ev = _padded(faces), np.array(edges_of(faces))
    framework = Framework.from_mesh(flat, ev, fv, np.arange(len(flat)))
    e = next(i for i, edge in enumerate(ev.tolist()) if edge == sorted(drive))

    def residual(v):
        y = v.reshape(-1, 3)
        return np.concatenate(
            [
                framework.residual(y) / framework.scales,
                (y[fixed] - flat[fixed]).ravel(),
                [np.radians(fold_angles(y, fv, ev)[e] - angle)],
            ]
        )

    start = flat.copy()
    start[:, 2] = np.random.default_rng(seed).normal(scale=0.1, size=len(flat))
    start[fixed, 2] = 0.0
    solution = least_squares(
        residual, start.ravel(), xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=2000
    )
    if np.abs(residual(solution.x)).max() > 1e-12:
        raise AssertionError("no rigid folded state found")
    return solution.x.reshape(-1, 3)


def waterbomb(angle: float = -60.0) -> tuple[np.ndarray, np.ndarray, list[list[int]]]:
    """A waterbomb base (a square with its diagonals and midlines, 8 triangles about the centre),
    flat and folded."""
    rays = [
        np.array([np.cos(t), np.sin(t)]) * (np.sqrt(2) if k % 2 else 1.0)
        for k, t in enumerate(np.radians(np.arange(0, 360, 45)))
    ]
    flat = np.column_stack([np.array([[0.0, 0.0]] + rays), np.zeros(9)])
    faces = [[0, 1 + k, 1 + (k + 1) % 8] for k in range(8)]
    return (
        flat,
        fold_rigidly(flat, faces, drive=(0, 1), angle=angle, fixed=[0, 1, 2], seed=3),
        faces,
    )


def _rounded(x: np.ndarray, decimals: int) -> list:
    return [[round(float(v), decimals) + 0.0 for v in p] for p in x]


def _doc(creator: str, title: str, **frame) -> dict:
    return {
        "file_spec": 1,
        "file_creator": creator,
        "file_author": "curvefold tests",
        "file_classes": ["singleModel"],
        "frame_title": title,
        **frame,
    }


def corpus() -> dict[str, bytes]:
    """Every file of the corpus, by name, as the bytes a tool writes."""
    files = {}
    rows, cols = 3, 4
    faces = grid_faces(rows, cols)
    edges = edges_of(faces)
    folded = miura(rows, cols, height=0.6).reshape(-1, 3)
    assignment, _ = assignment_of(folded, faces, edges)
    files["miura-mathematica.fold"] = json.dumps(
        _doc(
            "Mathematica",
            "Rigidly folded Miura-ori",
            frame_classes=["foldedForm"],
            frame_attributes=["3D"],
            vertices_coords=_rounded(folded, 6),
            faces_vertices=faces,
            edges_vertices=edges,
            edges_assignment=assignment,
        ),
        indent=4,
    ).encode()

    # Origami Simulator: triangulated along the shorter diagonal, Y up, float32 coordinates, target
    # angles
    triangles, tri_edges = [], list(edges)
    assignment_os = list(assignment)
    for f in faces:
        a, b, c, d = f
        triangles += [[a, b, d], [b, c, d]]
        tri_edges.append(sorted((b, d)))
        assignment_os.append("F")
    y_up = folded[:, [0, 2, 1]] * [1, 1, -1]  # a rotation: z up becomes y up
    # a converged simulation's angles
    reached = fold_angles(folded, np.array(triangles), np.array(tri_edges))
    angles_os = [None if s == "B" else round(float(v), 4) for s, v in zip(assignment_os, reached)]
    simulated = {
        "file_spec": 1.1,
        "file_creator": "Origami Simulator: http://git.amandaghassaei.com/OrigamiSimulator/",
        "file_author": "",
        "file_classes": ["singleModel"],
        "frame_title": "miura",
        "frame_classes": ["foldedForm"],
        "frame_attributes": ["3D"],
        "frame_unit": "unit",
        "vertices_coords": [[float(np.float32(v)) for v in p] for p in y_up],
        "edges_vertices": tri_edges,
        "edges_assignment": assignment_os,
        "faces_vertices": triangles,
        "edges_foldAngle": angles_os,
    }
    files["miura-origami-simulator.fold"] = json.dumps(simulated, indent=4).encode()

    flat, twist_faces = square_twist()
    twisted = fold_rigidly(flat, twist_faces, drive=(0, 1), angle=-40.0, fixed=[0, 1, 2, 3], seed=0)
    twist_edges = edges_of(twist_faces)
    twist_assignment, _ = assignment_of(twisted, twist_faces, twist_edges)
    files["square-twist.fold"] = json.dumps(
        _doc(
            "Mathematica",
            "Rigidly folded square twist",
            frame_classes=["foldedForm"],
            frame_attributes=["3D"],
            vertices_coords=_rounded(twisted, 6),
            faces_vertices=twist_faces,
            edges_vertices=twist_edges,
            edges_assignment=twist_assignment,
        ),
        indent=4,
    ).encode()

    _, bomb, bomb_faces = waterbomb()
    bomb_edges = edges_of(bomb_faces)
    bomb_assignment, _ = assignment_of(bomb, bomb_faces, bomb_edges)
    files["waterbomb.fold"] = json.dumps(
        _doc(
            "A text editor",
            "Waterbomb base, folded",
            frame_classes=["foldedForm"],
            frame_attributes=["3D"],
            vertices_coords=[list(map(float, p)) for p in bomb],
            faces_vertices=bomb_faces,
            edges_vertices=bomb_edges,
            edges_assignment=bomb_assignment,
        )
    ).encode()

    files["diagonal-flat-folded.fold"] = json.dumps(
        {
            "file_spec": 1.1,
            "file_creator": "fold-convert --flat-fold",
            "file_classes": ["singleModel"],
            "frame_classes": ["foldedForm"],
            "vertices_coords": [[0, 0], [1, 0], [0, 0], [0, 1]],
            "edges_vertices": [[0, 1], [1, 2], [2, 3], [3, 0], [3, 1]],
            "edges_assignment": ["B", "B", "B", "B", "V"],
            "edges_foldAngle": [0, 0, 0, 0, 180],
            "cpedit:page": {"xMin": 0, "xMax": 1},
            "vertices_edges": [[0, 3], [1, 4, 0], [1, 2], [3, 4, 2]],
            "faces_vertices": [[0, 1, 3], [1, 2, 3]],
            "faces_edges": [[0, 4, 3], [1, 2, 4]],
            "edges_faces": [[0, None], [1, None], [1, None], [0, None], [1, 0]],
            "faces_flatFoldTransform": [[[1, 0, 0], [0, 1, 0]], [[0, -1, 1], [-1, 0, 1]]],
            "faces_flatFoldOrientation": [1, -1],
            "vertices_flatUnfoldCoords": [[0, 0], [1, 0], [1, 1], [0, 1]],
        }
    ).encode()

    # a crease pattern with two folded frames; FOLD 1.2 assignments: a cut on the outline, a join
    # splitting a panel, an unassigned crease
    pattern = miura(rows, cols).reshape(-1, 3)
    cp_assignment = list(assignment)
    cp_faces = [list(f) for f in faces]
    cp_edges = [list(e) for e in edges]
    u = next(i for i, s in enumerate(cp_assignment) if s in "MV")
    cp_assignment[u] = "U"
    cp_assignment[cp_assignment.index("B")] = "C"  # a cut on the outline: one face, read as B
    a, b, c, d = cp_faces[0]  # the first panel split by a join along a diagonal
    cp_faces[0:1] = [[a, b, c], [a, c, d]]
    cp_edges.append(sorted((a, c)))
    cp_assignment.append("J")
    frames = [
        {
            "frame_title": f"folded to H = {h}",
            "frame_classes": ["foldedForm"],
            "frame_parent": 0,
            "frame_inherit": True,
            "vertices_coords": [
                list(map(float, p)) for p in miura(rows, cols, height=h).reshape(-1, 3)
            ],
            "edges_foldAngle": [
                float(v)
                for v in _angles(miura(rows, cols, height=h).reshape(-1, 3), cp_faces, cp_edges)
            ],
        }
        for h in (0.3, 0.6)
    ]
    doc = {
        "file_spec": 1.2,
        "file_creator": "a crease pattern editor",
        "file_classes": ["singleModel"],
        "frame_classes": ["creasePattern"],
        "vertices_coords": [[float(p[0]), float(p[1])] for p in pattern],
        "edges_vertices": cp_edges,
        "edges_assignment": cp_assignment,
        "faces_vertices": cp_faces,
        "frame_attributes": ["2D", "joins"],
        "editor:selection": [3, 4],
        "faceOrders": [],
        "file_frames": frames,
    }
    files["miura-cp-frames.fold"] = b"\xef\xbb\xbf" + json.dumps(doc).encode()
    return files


def _angles(x: np.ndarray, faces: list[list[int]], edges: list[list[int]]) -> np.ndarray:
    return np.where(
        [sum(set(e) <= set(f) for f in faces) == 2 for e in edges],
        fold_angles(x, _padded(faces), np.array(edges)),
        0.0,
    )


def write_corpus(folder: Path) -> dict[str, Path]:
    """Write every file of the corpus into ``folder``; their paths by name."""
    out = {}
    for name, content in corpus().items():
        out[name] = folder / name
        out[name].write_bytes(content)
    return out


def triangulated_dof(doc: dict) -> int:
    """B − 3 of a triangulated disk: its boundary edges minus 3 (Euler's formula, independent
    constraints)."""
    return sum(a == "B" for a in doc["edges_assignment"]) - 3
