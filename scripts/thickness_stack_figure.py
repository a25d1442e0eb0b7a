"""Draw docs/thickness-stack.png: the paper's vault of 16 panels in 2 mm sheets (radius 1 m) at four
fold angles of its range with thickness, and sections of the stacks: the vault's bundle of
tubes where it stops, and one of its tubes folded flat (two plies, 2t).

Run: ``python scripts/thickness_stack_figure.py docs/thickness-stack.png`` (needs matplotlib).
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from curvefold import Structure
from curvefold.geometry import ThickPanels
from curvefold.vault import Vault, VaultDesign

sys.path.insert(0, str(Path(__file__).parent))
from thickness_figure import section  # noqa: E402

T = 0.002
WOOD, EDGE = "#c8a26b", "#5a4326"


def _solids(ax, thick: ThickPanels, angle: float, title: str) -> None:
    x, tri = thick.triangles(angle)
    ax.add_collection3d(Poly3DCollection(x[tri], facecolor=WOOD, edgecolor=EDGE, linewidths=0.1))
    lo, hi = x.min(0), x.max(0)
    c, r = 0.5 * (lo + hi), 0.5 * (hi - lo).max()
    ax.set(xlim=(c[0] - r, c[0] + r), ylim=(c[1] - r, c[1] + r), zlim=(c[2] - r, c[2] + r))
    ax.set_box_aspect((1, 1, 1), zoom=1.4)
    ax.view_init(elev=22, azim=-60)
    ax.set_axis_off()
    ax.set_title(title, fontsize=9)


def _section(ax, thick: ThickPanels, angle: float, up: np.ndarray, box, title: str) -> None:
    """The solids cut across the crease at the middle of the structure's middle panel, in mm:
    ``up`` the section's vertical, ``box`` its (xlim, ylim)."""
    vertices = thick.solids([angle])[0][0]
    corners = thick.corners([angle])[0]
    f = len(corners) // 2
    point = 0.5 * (corners[f, 0] + corners[f, 1])
    normal = corners[f, 1] - corners[f, 0]
    normal /= np.linalg.norm(normal)
    v = up - (up @ normal) * normal
    v /= np.linalg.norm(v)
    u = np.cross(v, normal)
    for p in section(vertices, point, normal):
        q = np.c_[(p - point) @ u, (p - point) @ v] * 1e3
        ax.fill(q[:, 0], q[:, 1], facecolor=WOOD, edgecolor=EDGE, lw=0.6)
    ax.set_aspect("equal")
    ax.set(xlim=box[0], ylim=box[1], xlabel="mm", ylabel="mm")
    ax.set_title(title, fontsize=9)
    ax.tick_params(labelsize=7)


def main(path: str) -> None:
    vault = Vault.from_design(VaultDesign(panels=16))
    thick = ThickPanels.offset(vault.structure, T)
    low = thick.motion_range().low
    s = vault.structure
    tube = ThickPanels.offset(Structure.from_cells(s.lattice, s.cells[:1]), T)
    assert tube.motion_range().low == 0.0  # one tube alone folds flat
    fig = plt.figure(figsize=(13, 6.4))
    grid = fig.add_gridspec(2, 4, height_ratios=(1.4, 1))
    angles = (90.0, 90.0 - (90.0 - low) / 3, 90.0 - 2 * (90.0 - low) / 3, low)
    for n, angle in enumerate(angles):
        title = f"2α = {angle:.1f}°" + (" (first contact)" if n == 3 else "")
        _solids(fig.add_subplot(grid[0, n], projection="3d"), thick, angle, title)
    _section(
        fig.add_subplot(grid[1, 0]),
        thick,
        low,
        np.array([0.0, 0.0, 1.0]),
        ((-40, 40), (-40, 40)),
        f"across the vault's tubes at 2α = {low:.1f}°:\nthe walls' bevels meet",
    )
    flat = tube.corners([0.0])[0].reshape(-1, 3)
    normal = np.linalg.svd(flat - flat.mean(0))[2][-1]
    _section(
        fig.add_subplot(grid[1, 1:]),
        tube,
        0.0,
        normal,
        ((-70, 90), (-8, 8)),
        f"across one of its tubes folded flat (2α = 0°): the stack of two plies, "
        f"{1e3 * tube.stack_height():.3g} mm",
    )
    fig.suptitle(
        f"The paper's vault, 16 panels, panels {T * 1000:g} mm thick at radius 1 m: folding to "
        "its first contact, and sections of the stacks",
        fontsize=11,
    )
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1])
