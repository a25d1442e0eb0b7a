"""The convergence tables of the docs: the bar-and-hinge model as k elements across each strip
grow, against OpenSees shells refined across and along each ruling quad, on the same geometry:
a tube, the paper's vault and a cellular block.

The structures (aluminium 2 mm, default creases, under their own weight, every sample kept):

- the tube: one tube of the paper's vault (a = 0.3, p_xy = 0.75), smooth, on 41 samples
  (81 with ``--only tube-81``), its feet pinned;
- the paper's vault (``examples/paper-vault.toml``: a = 0.3, p_xy = 0.75, 9 tubes) on 21
  samples instead of 801, its feet pinned; its shells stop at 8 across (5760 elements): OpenSees's
  banded ARPACK takes 20 CPU-s a solve at 4 across and about m³ times more;
- the cellular block (``examples/cellular-block.toml``: three cells around a twisting curve)
  on 21 samples instead of 401, held at both end sections (pinned), as a bridge; its shells
  too stop at 8 across.

Figures: the largest deflection, the two lowest free eigenvalues ω², the lowest supported ω²
and, for the bar-and-hinge model, the buckling factor of the self-weight. Ours on k = 1, 2,
4, 8 across, with the observed order of k = 2, 4, 8 and Richardson's estimate of the limit
and of the error of k = 8 from k = 4 and 8; OpenSees (``tests/_opensees.py``: ASDShellQ4
on every ruling quad, m across × n along, the creases as springs) on m = 1 … 16 across at
one element along (the bar-and-hinge model's own discretisation along the strips), with
Richardson's estimate from the two finest (8 and 16; the vault 4 and 8), and on n = 2 (and
4) along, the move of which is the shells' uncertainty along (module notes of
``tests/_opensees.py``). The largest deflection is taken over every node of
either model (ours: the curves' and those inside the strips; the shells': every node).

Run from the repository root; ``--write`` puts the tables into ``docs/guide/mechanics.md``
between its markers, and every case's figures into ``docs/guide/mechanics-convergence.json``
(about half an hour on one core; ``--only tube`` runs one structure, keeping the others'
figures, and ``--write --only`` rewrites the tables from the JSON)::

    .venv/bin/python benchmarks/convergence.py --write
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

import _opensees  # noqa: E402
from curvefold.mechanics import MATERIALS, StructureModel, Supports, analyse_load  # noqa: E402
from curvefold.mechanics._convergence import observed_order, richardson  # noqa: E402

DOC = ROOT / "docs" / "guide" / "mechanics.md"
BEGIN = "<!-- convergence table: written by benchmarks/convergence.py -->"
END = "<!-- end of the convergence table -->"
#: Every case's figures, so that the cases can be run apart (``--only``) and written together.
FIGURES_JSON = DOC.with_name("mechanics-convergence.json")
AL = MATERIALS["aluminium"]
THICKNESS = 2e-3
ACROSS = (1, 2, 4, 8)
#: The figures' names, in the order of a row.
FIGURES = ("deflection", "ω₁²", "ω₂²", "supported ω₁²", "buckling")


@dataclass(frozen=True)
class Case:
    """A structure of the tables: its name, how to build its state, samples, supports and the
    OpenSees meshes (m across, n along) of every ruling quad."""

    name: str
    state: Callable[[int], object]
    samples: int
    at: str
    shells: tuple[tuple[int, int], ...]


def tube_state(samples: int):
    from curvefold.vault import Vault

    return Vault.from_design(a=0.3, p_xy=0.75, tubes=1, samples=samples).structure.state()


def vault_state(samples: int):
    """The paper's vault (examples/paper-vault.toml) on ``samples`` samples."""
    from curvefold.app import load_design
    from curvefold.vault import Vault, VaultDesign

    v = load_design(ROOT / "examples" / "paper-vault.toml").vault
    design = VaultDesign(
        a=v.a, p_xy=v.p_xy, width=v.width, fold_angle=v.fold_angle, radius=v.radius
    )
    return Vault.from_design(design, samples=samples).structure.state()


def block_state(samples: int):
    """The cellular block (examples/cellular-block.toml) on ``samples`` samples."""
    from curvefold.app import parse_design
    from curvefold.app._build import build_block

    text = (ROOT / "examples" / "cellular-block.toml").read_text()
    design = parse_design(text).overrides(samples=samples)
    return build_block(design).structure.state()


FULL = (1, 1), (2, 1), (4, 1), (8, 1), (16, 1), (8, 2), (8, 4)
#: The vault's and the block's shells stop at 8 across: their ARPACK solves take 20 and 13
#: CPU-s at 4 × 1, growing about as m³.
COARSE = (1, 1), (2, 1), (4, 1), (8, 1), (4, 2)
CASES = {
    "tube": (Case("tube", tube_state, 41, "feet", FULL),),
    "tube-81": (Case("tube", tube_state, 81, "feet", FULL),),
    "vault": (Case("paper's vault", vault_state, 21, "feet", COARSE),),
    "block": (Case("block", block_state, 21, "ends", COARSE),),
}


def model(case: Case) -> StructureModel:
    return StructureModel.from_state(case.state(case.samples), AL, THICKNESS, samples="all")


def ours(one: StructureModel, at: str, ks=ACROSS) -> list[tuple[str, list[float], float]]:
    rows = []
    for k in ks:
        start = time.process_time()
        r = analyse_load(one.with_across(k), AL, THICKNESS, supports=Supports(at=at))
        figures = [
            r.static.max_displacement,
            *r.modes.eigenvalues[:2],
            r.supported_eigenvalues[0],
            r.buckling.factor,
        ]
        rows.append((f"k = {k}", figures, time.process_time() - start))
    return rows


def ground(one: StructureModel) -> np.ndarray:
    """Six DOFs (node, axis) that hold the rigid motions, by a pivoted QR."""
    from scipy.linalg import qr

    from curvefold.mechanics._linear import rigid_motions

    R = rigid_motions(one.model.nodes, one.model.masses)
    held = qr(R.T, mode="r", pivoting=True)[1][:6]
    return np.stack([held // 3, held % 3], axis=1)


def theirs(
    one: StructureModel, at: str, lam: float, meshes
) -> list[tuple[str, list[float], float]]:
    """OpenSees's figures on every mesh; ``lam`` our ω₁², to scale the soft springs."""
    held, spring = ground(one), 1e-6 * one.model.masses.sum() * lam
    rows = []
    for m, n in meshes:
        start = time.process_time()
        u = _opensees.static_deflection(one, (m, n), at, every=True)
        mu = _opensees.free_eigenvalues(one, (m, n), 2, held, spring)
        held_mu = _opensees.supported_eigenvalues(one, (m, n), 1, at)
        figures = [float(np.linalg.norm(u, axis=1).max()), *mu[:2], held_mu[0], float("nan")]
        rows.append((f"{m} × {n}", figures, time.process_time() - start))
    return rows


def limits(rows: np.ndarray) -> tuple[list[float], list[tuple[float, float]]]:
    """Observed orders of the last three rows (refined by 2) and Richardson's limit ± error
    from the last two, every column (order at least 0.5)."""
    p = [observed_order(*rows[-3:, c]) for c in range(rows.shape[1])]
    est = [richardson(rows[-2, c], rows[-1, c], order=max(p[c], 0.5)) for c in range(len(p))]
    return p, est


def compare(case: Case) -> dict:
    """Every figure of both models on one case, their limits and the ratios of the limits."""
    one = model(case)
    mine = ours(one, case.at)
    shells = theirs(one, case.at, mine[0][1][1], case.shells)
    F = np.array([f for _, f, _ in mine])
    p, est = limits(F[1:])
    figures = {(m, n): f for (m, n), (_, f, _) in zip(case.shells, shells)}
    ms = sorted(m for m, n in figures if n == 1)[-3:]
    q, shell = limits(np.array([figures[(m, 1)] for m in ms])[:, :4])
    along = np.max(
        [
            np.abs(np.array(f[:4]) / np.array(figures[(m, 1)][:4]) - 1)
            for (m, n), f in figures.items()
            if n > 1
        ],
        axis=0,
    )
    return {
        "name": case.name,
        "samples": case.samples,
        "at": case.at,
        "ours": mine,
        "shells": shells,
        "orders": p,
        "limits": est,
        "shell_meshes": ms,
        "shell_orders": q,
        "shell_limits": shell,
        "ratios": [float(est[c][0] / shell[c][0]) for c in range(4)],
        "along": along.tolist(),
    }


def plain(value):
    """JSON's values: floats, NaN as None, tuples as lists."""
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [plain(v) for v in value]
    if isinstance(value, float | np.floating):
        return None if np.isnan(value) else float(value)
    return value


def store(result: dict, path: Path = FIGURES_JSON) -> dict:
    """Add one case's figures to the JSON beside the docs (others' kept); return them all."""
    import fcntl
    import json

    with open(path.with_suffix(".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        stored = json.loads(path.read_text()) if path.exists() else {}
        stored[f"{result['name']}, {result['samples']}"] = plain(result)
        path.write_text(json.dumps(stored, indent=1, ensure_ascii=False) + "\n")
    path.with_suffix(".lock").unlink(missing_ok=True)
    return stored


def ordered(stored: dict) -> list[dict]:
    """The stored cases in the order of :data:`CASES`."""
    keys = [f"{c.name}, {c.samples}" for cases in CASES.values() for c in cases]
    return [stored[k] for k in keys if k in stored]


def rows_of(result: dict) -> list[str]:
    label = f"{result['name']}, {result['samples']}"
    lines = []
    for name, rows in (("bar-and-hinge", result["ours"]), ("OpenSees shells", result["shells"])):
        for mesh, f, cpu in rows:
            factor = "" if f[4] is None or np.isnan(f[4]) else f"{f[4]:.2f}"
            lines.append(
                f"| {label} | {name} | {mesh} | {f[0] * 1e6:.3f} | {f[1]:.2f} | {f[2]:.1f} "
                f"| {f[3]:.1f} | {factor} | {cpu:.1f} |"
            )
    e = result["limits"]
    lines.append(
        f"| {label} | bar-and-hinge | k → ∞ (k = 4, 8) "
        f"| {e[0][0] * 1e6:.3f} ± {e[0][1] * 1e6:.3f} | {e[1][0]:.2f} ± {e[1][1]:.2f} "
        f"| {e[2][0]:.1f} ± {e[2][1]:.1f} | {e[3][0]:.1f} ± {e[3][1]:.1f} "
        f"| {e[4][0]:.2f} ± {e[4][1]:.2f} | |"
    )
    s, ms = result["shell_limits"], result["shell_meshes"]
    lines.append(
        f"| {label} | OpenSees shells | m → ∞ × 1 (m = {ms[1]}, {ms[2]}) "
        f"| {s[0][0] * 1e6:.3f} ± {s[0][1] * 1e6:.3f} | {s[1][0]:.2f} ± {s[1][1]:.2f} "
        f"| {s[2][0]:.1f} ± {s[2][1]:.1f} | {s[3][0]:.1f} ± {s[3][1]:.1f} | | |"
    )
    return lines


def note_of(result: dict) -> str:
    fmt = ", ".join
    return (
        f"{result['name']}, {result['samples']} samples ({result['at']} pinned): "
        "observed orders in k (2, 4, 8) "
        + fmt(f"{x:.2f}" for x in result["orders"])
        + " (deflection, ω₁², ω₂², supported ω₁², buckling); the shells' in m ("
        + fmt(str(m) for m in result["shell_meshes"])
        + ") "
        + fmt(f"{x:.2f}" for x in result["shell_orders"])
        + "; our limits over the shells': "
        + fmt(f"{name} {r:.4f}" for name, r in zip(FIGURES, result["ratios"]))
        + "; refining the shells along moves them by "
        + fmt(f"{100 * x:.1f} %" for x in result["along"])
        + "."
    )


def table(results: list[dict]) -> str:
    lines = [
        "| structure, samples | model | mesh | deflection (µm) | ω₁² (rad²/s²) | ω₂² (rad²/s²) "
        "| supported ω₁² (rad²/s²) | buckling factor | CPU-s |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for result in results:
        lines += rows_of(result)
    notes = [note_of(r) for r in results]
    return "\n".join(lines) + "\n\n" + "\n".join(f"- {n}" for n in notes) + "\n"


def write(text: str, doc: Path = DOC) -> None:
    page = doc.read_text()
    if BEGIN not in page or END not in page:
        raise SystemExit(f"{doc} has no convergence markers ({BEGIN!r} … {END!r})")
    head, rest = page.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    doc.write_text(head + BEGIN + "\n" + text + END + tail)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument(
        "--write",
        action="store_true",
        help="store the figures in the JSON beside the docs and write the tables of every "
        "stored case into the docs",
    )
    parser.add_argument(
        "--only",
        nargs="*",
        choices=sorted(CASES),
        default=["tube", "vault", "block"],
        help="these structures (tube-81: the tube on 81 samples, an hour on one core)",
    )
    args = parser.parse_args(argv)
    results = []
    for name in args.only:
        for case in CASES[name]:
            results.append(plain(compare(case)))
            print("\n".join(rows_of(results[-1])), "\n" + note_of(results[-1]), flush=True)
            if args.write:
                store(results[-1])
    if args.write:
        import json

        results = ordered(json.loads(FIGURES_JSON.read_text()))
    text = table(results)
    print(text)
    if args.write:
        write(text)


if __name__ == "__main__":
    main()
