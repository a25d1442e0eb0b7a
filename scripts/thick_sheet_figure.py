"""Draw docs/thick-sheet.png: the end of a tube's sheet A in 4 mm plywood drawn 1:1, the outline of
zero thickness dashed and the one drawn for the sheet solid (creases inset by their bend, seams
lapped out by t).

Run: ``python scripts/thick_sheet_figure.py docs/thick-sheet.png`` (needs matplotlib).
"""

from __future__ import annotations

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from curvefold import Crease, Lattice, SpaceCurve, Structure
from curvefold.geometry._sheets import sheets
from curvefold.io._sheet_bend import sheet_bend
from curvefold.io._thick_sheet import thick_sheets

T = 0.004


def _outline(sheet) -> np.ndarray:
    """The sheet's outline loop (mm), from its triangles' edges used once."""
    mesh = sheet.mesh
    kinds = np.isin(mesh.edges_kind, ("seam", "boundary"))
    ev = mesh.edges_vertices[kinds].tolist()
    nxt: dict[int, list[int]] = {}
    for a, b in ev:
        nxt.setdefault(a, []).append(b)
        nxt.setdefault(b, []).append(a)
    loop, prev = [ev[0][0]], -1
    while True:
        cur = loop[-1]
        step = next(v for v in nxt[cur] if v != prev)
        if step == loop[0]:
            break
        prev = cur
        loop.append(step)
    xy = mesh.vertices_coords[loop + loop[:1], :2] * 1e3
    return xy


def main(path: str) -> None:
    curve = SpaceCurve.from_curvature(2.0 / 0.3, 0.5 / 0.3, 0.3, samples=21)
    tube = Structure.tube(Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.03, 0.03))
    plain = sheets(tube)[0]
    drawn = thick_sheets(sheets(tube), sheet_bend("plywood", T).bend)[0]
    fig, ax = plt.subplots(figsize=(5.6, 3.6), dpi=150)
    ax.plot(*_outline(plain).T, color="#888888", lw=0.8, ls=(0, (4, 3)), label="zero thickness")
    ax.plot(*_outline(drawn).T, color="black", lw=1.0, label="drawn for 4 mm plywood")
    fold = plain.mesh.edges_kind == "fold"
    crease = np.unique(plain.mesh.edges_vertices[fold])
    ax.plot(
        *(plain.mesh.vertices_coords[crease, :2] * 1e3).T,
        color="#c0392b",
        lw=0.9,
        ls="-.",
        label="crease: the bend's centre line",
    )
    c = plain.mesh.vertices_coords[crease[0], :2] * 1e3  # the crease's first end
    ax.set(xlim=(c[0] - 3, c[0] + 40), ylim=(c[1] - 38, c[1] + 36), aspect="equal")
    ax.set(xlabel="mm", ylabel="mm")
    ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.02, 0.5))
    ax.set_title(
        "inset δ = 1.29 mm each side of the crease; seams out t = 4 mm (2α = 90°)", fontsize=8
    )
    fig.tight_layout()
    fig.savefig(path)


if __name__ == "__main__":
    main(sys.argv[1])
