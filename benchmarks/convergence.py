"""The convergence table of the docs: the bar-and-hinge model as k elements across each strip
grow, against OpenSees shells refined across and along each ruling quad, on the same tube.

The tube: one tube of the paper's vault (a = 0.3, p_xy = 0.75), smooth, on 41 and 81
samples (every one kept), aluminium 2 mm, default creases, the feet pinned, under its own
weight. Figures: the largest deflection, the two lowest free eigenvalues ω² and, for the
bar-and-hinge model, the buckling factor of the self-weight. Ours on k = 1, 2, 4, 8 across,
with the observed order of k = 2, 4, 8 and Richardson's estimate of the limit and of the
error of k = 8 from k = 4 and 8; OpenSees (``tests/_opensees.py``: ASDShellQ4 on every
ruling quad, m across × n along, the creases as springs) on m = 1 … 16 across and n = 1, 2,
4 along, with Richardson's estimate across from m = 8 and 16 at one element along (the
bar-and-hinge model's own discretisation along the strips).

Run from the repository root; ``--write`` puts the table into ``docs/guide/mechanics.md``
between its markers (about four minutes on two cores)::

    .venv/bin/python benchmarks/convergence.py --write
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

import _opensees  # noqa: E402
from curvefold.mechanics import MATERIALS, StructureModel, analyse_load  # noqa: E402
from curvefold.mechanics._convergence import observed_order, richardson  # noqa: E402
from curvefold.vault import Vault  # noqa: E402

DOC = ROOT / "docs" / "guide" / "mechanics.md"
BEGIN = "<!-- convergence table: written by benchmarks/convergence.py -->"
END = "<!-- end of the convergence table -->"
AL = MATERIALS["aluminium"]
THICKNESS = 2e-3
ACROSS = (1, 2, 4, 8)
#: OpenSees meshes of every ruling quad: (m across, n along).
SHELLS = ((1, 1), (2, 1), (4, 1), (8, 1), (16, 1), (8, 2), (8, 4))


def tube(samples: int) -> StructureModel:
    state = Vault.from_design(a=0.3, p_xy=0.75, tubes=1, samples=samples).structure.state()
    return StructureModel.from_state(state, AL, THICKNESS, samples="all")


def ours(one: StructureModel) -> list[tuple[str, list[float], float]]:
    rows = []
    for k in ACROSS:
        start = time.process_time()
        r = analyse_load(one.with_across(k), AL, THICKNESS)
        figures = [r.static.max_displacement, *r.modes.eigenvalues[:2], r.buckling.factor]
        rows.append((f"k = {k}", figures, time.process_time() - start))
    return rows


def theirs(one: StructureModel, lam: np.ndarray) -> list[tuple[str, list[float], float]]:
    from scipy.linalg import qr

    from curvefold.mechanics._linear import rigid_motions

    R = rigid_motions(one.model.nodes, one.model.masses)
    held = qr(R.T, mode="r", pivoting=True)[1][:6]
    ground = np.stack([held // 3, held % 3], axis=1)
    spring = 1e-6 * one.model.masses.sum() * lam[0]
    rows = []
    for m, n in SHELLS:
        start = time.process_time()
        u = _opensees.static_deflection(one, (m, n))
        mu = _opensees.free_eigenvalues(one, (m, n), 2, ground, spring)
        figures = [float(np.linalg.norm(u, axis=1).max()), *mu[:2], float("nan")]
        rows.append((f"{m} × {n}", figures, time.process_time() - start))
    return rows


def table(samples_list=(41, 81)) -> str:
    lines = [
        "| tube, samples | model | mesh | deflection (µm) | ω₁² (rad²/s²) | ω₂² (rad²/s²) "
        "| buckling factor | CPU-s |",
        "|---|---|---|---|---|---|---|---|",
    ]
    notes = []
    for samples in samples_list:
        one = tube(samples)
        mine = ours(one)
        shells = theirs(one, np.array(mine[0][1][1:3]))
        for name, rows in (("bar-and-hinge", mine), ("OpenSees shells", shells)):
            for mesh, f, cpu in rows:
                factor = "" if np.isnan(f[3]) else f"{f[3]:.2f}"
                lines.append(
                    f"| {samples} | {name} | {mesh} | {f[0] * 1e6:.3f} | {f[1]:.3f} | {f[2]:.2f} "
                    f"| {factor} | {cpu:.1f} |"
                )
        F = np.array([f for _, f, _ in mine])
        p = [observed_order(*F[1:, c]) for c in range(4)]
        est = [richardson(F[2, c], F[3, c], order=max(p[c], 0.5)) for c in range(4)]
        lines.append(
            f"| {samples} | bar-and-hinge | k → ∞ (Richardson, k = 4, 8) "
            f"| {est[0][0] * 1e6:.3f} ± {est[0][1] * 1e6:.3f} | {est[1][0]:.3f} ± {est[1][1]:.3f} "
            f"| {est[2][0]:.2f} ± {est[2][1]:.2f} | {est[3][0]:.2f} ± {est[3][1]:.2f} | |"
        )
        S = np.array([f for mesh, f, _ in shells if mesh in ("4 × 1", "8 × 1", "16 × 1")])
        q = [observed_order(*S[:, c]) for c in range(3)]
        shell = [richardson(S[1, c], S[2, c], order=max(q[c], 0.5)) for c in range(3)]
        limit = shell[0][0]
        lines.append(
            f"| {samples} | OpenSees shells | m → ∞ × 1 (Richardson, m = 8, 16) "
            f"| {limit * 1e6:.3f} ± {shell[0][1] * 1e6:.3f} "
            f"| {shell[1][0]:.3f} ± {shell[1][1]:.3f} | {shell[2][0]:.2f} ± {shell[2][1]:.2f} "
            "| | |"
        )
        notes.append(
            f"{samples} samples: observed orders in k (2, 4, 8) "
            + ", ".join(f"{x:.2f}" for x in p)
            + " (deflection, ω₁², ω₂², buckling); the shells' in m (4, 8, 16) "
            + ", ".join(f"{x:.2f}" for x in q)
            + f"; the bar-and-hinge limits (k → ∞) over the shells' (m → ∞): deflection "
            f"{est[0][0] / limit:.4f}, ω₁² {est[1][0] / shell[1][0]:.4f}, "
            f"ω₂² {est[2][0] / shell[2][0]:.4f}."
        )
    return "\n".join(lines) + "\n\n" + "\n".join(f"- {n}" for n in notes) + "\n"


def write(text: str, doc: Path = DOC) -> None:
    page = doc.read_text()
    if BEGIN not in page or END not in page:
        raise SystemExit(f"{doc} has no convergence markers ({BEGIN!r} … {END!r})")
    head, rest = page.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    doc.write_text(head + BEGIN + "\n" + text + END + tail)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help="write the table into the docs")
    parser.add_argument("--samples", type=int, nargs="+", default=[41, 81])
    args = parser.parse_args(argv)
    text = table(tuple(args.samples))
    print(text)
    if args.write:
        write(text)


if __name__ == "__main__":
    main()
