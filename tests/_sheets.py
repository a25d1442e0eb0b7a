"""Test sheets for the crease-pattern exporters: the two developed sheets of tubes.

Each sheet is an annular sector: vertices on three concentric arcs, the middle arc a fold
crease, the two outer arcs seams (ids shared with the partner sheet), the two radial ends
boundary edges, the other radial edges rulings and the quads split by diagonals.
"""

from __future__ import annotations

import numpy as np

from curvefold.geometry import Mesh, PatternSheet


def annular_sheet(
    label: str,
    *,
    radii=(40.0, 52.0, 64.0),
    span_deg=(0.0, 100.0),
    n=24,
    fold="M",
    seams=(0, 1),
    clockwise=False,
    origin=(0.0, 0.0),
) -> PatternSheet:
    """An annular-sector sheet, shape (3 arcs × (n + 1)) vertices, z = 0.

    ``seams`` gives the seam ids of the inner and outer arcs (None: a boundary instead).
    ``clockwise`` lists the triangles clockwise (the sheet seen from its back).
    """
    r = np.asarray(radii, float)
    theta = np.radians(np.linspace(*span_deg, n + 1))
    x = origin[0] + r[:, None] * np.cos(theta)[None]
    y = origin[1] + r[:, None] * np.sin(theta)[None]
    coords = np.stack([x.ravel(), y.ravel(), np.zeros(x.size)], axis=1)

    def vid(k, j):
        return k * (n + 1) + j

    faces, edges, kinds, seam_ids = [], [], [], []
    for k in range(2):
        for j in range(n):
            a, b, c, d = vid(k, j), vid(k + 1, j), vid(k + 1, j + 1), vid(k, j + 1)
            faces += [(a, b, c), (a, c, d)]
            edges.append((a, c))
            kinds.append("diagonal")
            seam_ids.append(-1)
    arc_kind = {
        0: "seam" if seams[0] is not None else "boundary",
        1: "fold",
        2: "seam" if seams[1] is not None else "boundary",
    }
    arc_seam = {0: seams[0], 1: None, 2: seams[1]}
    for k in range(3):
        for j in range(n):
            edges.append((vid(k, j), vid(k, j + 1)))
            kinds.append(arc_kind[k])
            seam_ids.append(-1 if arc_seam[k] is None else arc_seam[k])
    for k in range(2):
        for j in range(n + 1):
            edges.append((vid(k, j), vid(k + 1, j)))
            kinds.append("boundary" if j in (0, n) else "ruling")
            seam_ids.append(-1)
    kinds = np.array(kinds)
    assign = np.where(
        kinds == "fold", fold, np.where(np.isin(kinds, ("seam", "boundary")), "B", "F")
    )
    angle = np.where(kinds == "fold", 60.0 if fold == "V" else -60.0, 0.0)
    faces = np.array(faces)
    if clockwise:
        faces = faces[:, ::-1]
    mesh = Mesh(
        vertices_coords=coords,
        edges_vertices=np.array(edges),
        edges_assignment=assign,
        edges_foldAngle=angle,
        faces_vertices=faces,
        edges_kind=kinds,
        faces_group=np.zeros(len(faces), int),
    )
    return PatternSheet(label, mesh, np.array(seam_ids))


def tube_sheets(
    tube: int = 1, *, seams=(0, 1), n=24, scale=1.0
) -> tuple[PatternSheet, PatternSheet]:
    """The two sheets of one tube: A (mountain crease) and B (valley crease), seams shared.

    Both seams have equal lengths on A and B (same radii and span), as in a real tube.
    """
    a = annular_sheet(
        f"tube {tube} · sheet A",
        radii=(40 * scale, 52 * scale, 64 * scale),
        n=n,
        fold="M",
        seams=seams,
    )
    b = annular_sheet(
        f"tube {tube} · sheet B",
        radii=(40 * scale, 50 * scale, 64 * scale),
        span_deg=(30.0, 130.0),
        n=n,
        fold="V",
        seams=seams,
        origin=(300.0 * scale, 0.0),
    )
    return a, b


def vault_sheets(tubes: int = 3, *, n=24) -> list[PatternSheet]:
    """``2 × tubes`` sheets; tube i uses seam ids 2i and 2i + 1."""
    out: list[PatternSheet] = []
    for i in range(tubes):
        a, b = tube_sheets(i + 1, seams=(2 * i, 2 * i + 1), n=n)
        out += [a, b]
    return out
