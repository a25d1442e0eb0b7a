"""Draw docs/thickness.png: the paper's vault of 16 panels with 4 mm panels (radius 1 m) at three
fold angles of its range, and a section across two tubes at the range's lower end.

Run: ``python scripts/thickness_figure.py docs/thickness.png`` (needs matplotlib).
"""

from __future__ import annotations

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from curvefold.geometry import ThickPanels
from curvefold.vault import Vault, VaultDesign

T = 0.004


def section(vertices: np.ndarray, point: np.ndarray, normal: np.ndarray) -> list[np.ndarray]:
    """The polygons where a plane cuts convex prisms (F, 8, 3)."""
    k = vertices.shape[1] // 2
    i = np.arange(k)
    edges = np.concatenate(
        [np.stack([i, (i + 1) % k], 1), np.stack([i, (i + 1) % k], 1) + k, np.stack([i, i + k], 1)]
    )
    out = []
    for solid in vertices:
        d = (solid - point) @ normal
        a, b = solid[edges[:, 0]], solid[edges[:, 1]]
        da, db = d[edges[:, 0]], d[edges[:, 1]]
        cross = da * db < 0
        if cross.sum() < 3:
            continue
        s = da[cross] / (da[cross] - db[cross])
        p = a[cross] + s[:, None] * (b[cross] - a[cross])
        c = p.mean(0)
        u = p[0] - c
        u /= np.linalg.norm(u)
        v = np.cross(normal, u)
        order = np.argsort(np.arctan2((p - c) @ v, (p - c) @ u))
        out.append(p[order])
    return out


def main(path: str) -> None:
    vault = Vault.from_design(VaultDesign(panels=16))
    thick = ThickPanels.offset(vault.structure, T)
    low = thick.motion_range().low
    angles = (90.0, 0.5 * (90.0 + low), low)
    fig = plt.figure(figsize=(13, 4.0))
    for n, angle in enumerate(angles):
        ax = fig.add_subplot(1, 4, n + 1, projection="3d")
        x, tri = thick.triangles(angle)
        ax.add_collection3d(
            Poly3DCollection(x[tri], facecolor="#c8a26b", edgecolor="#5a4326", linewidths=0.1)
        )
        lo, hi = x.min(0), x.max(0)
        c, r = 0.5 * (lo + hi), 0.5 * (hi - lo).max()
        ax.set(xlim=(c[0] - r, c[0] + r), ylim=(c[1] - r, c[1] + r), zlim=(c[2] - r, c[2] + r))
        ax.set_box_aspect((1, 1, 1), zoom=1.5)
        ax.view_init(elev=22, azim=-60)
        ax.set_axis_off()
        ax.set_title(f"2α = {angle:.1f}°" + (" (first contact)" if n == 2 else ""), fontsize=10)
    # a section across the crease two tubes share, at the middle of the vault, at the contact
    ax = fig.add_subplot(1, 4, 4)
    vertices = thick.solids([low])[0][0]
    corners = thick.corners([low])[0]
    f = len(corners) // 2
    point = corners[f].mean(0)
    tangent = corners[f, 1] - corners[f, 0]
    normal = tangent / np.linalg.norm(tangent)
    polys = section(vertices, point, normal)
    u = np.cross(normal, [0, 0, 1.0])
    u /= np.linalg.norm(u)
    v = np.cross(normal, u)
    for p in polys:
        q = np.c_[(p - point) @ u, (p - point) @ v]
        if np.abs(q).max() < 0.12:
            ax.fill(
                q[:, 0] * 1000, q[:, 1] * 1000, facecolor="#c8a26b", edgecolor="#5a4326", lw=0.6
            )
    ax.set_aspect("equal")
    ax.set(
        xlim=(-60, 60),
        ylim=(-60, 60),
        xlabel="mm",
        title=f"section across the tubes, 2α = {low:.1f}°",
    )
    ax.tick_params(labelsize=7)
    fig.suptitle(
        f"The paper's vault, 16 panels, panels {T * 1000:g} mm thick at radius 1 m", fontsize=11
    )
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1])
