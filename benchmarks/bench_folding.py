"""Fold-state throughput: a 20-curve structure with 2000 samples per curve.

Lattice: curve 1 with κ = 1 + 0.3 sin s, τ = 0.3 cos s, L = 4, folded at 90°, widths
0.05; structure: the 4 × 3 cellular block of cells (i, j), i < 4, j < 3, whose corners
are 5 × 4 = 20 lattice curves. A "state" is the vertices of all 20 curves, shape
(20, 2000, 3), at one fold angle; the angles sweep 10° … 170°.

Contenders, all in the same interleaved rounds:

- state: ``structure.state(angle).vertices``, one state at a time;
- fold_points/c: ``lattice.fold_points(structure.curves_uv, chunk)`` for chunks of
  c = 8, 16, 32 angles;
- solve_ivp: what a user would otherwise write per state: rebuild curve 1 at the new
  κ = κ_2D / cos α, τ = τ₀ tan α / tan α₀ with solve_ivp (DOP853, rtol = atol = 1e-12,
  t_eval = the 2000 samples). Only the integration is timed (Eq. 11 on top of it would
  cost more), so this baseline is a lower bound on the user's cost.

Target: ≥ 500 states/s (on the best path).
"""

from __future__ import annotations

import math

import numpy as np
from _bench import (
    SummaryRow,
    best_of_interleaved,
    choose_repeats,
    markdown_table,
    ms,
    summary_table,
    verdict,
)
from scipy.integrate import solve_ivp

from curvefold import Crease, Lattice, SpaceCurve, Structure

SAMPLES = 2000
LENGTH = 4.0
DESIGN_ANGLE = 90.0  # degrees
WIDTH = 0.05
BLOCK = (4, 3)  # cells along u and v: (4 + 1) × (3 + 1) = 20 curves
STATES = 64  # fold angles per round
CHUNKS = (8, 16, 32)
IVP_STATES = 16  # the solve_ivp baseline is slow: a subset of the angles per round
TARGET = 500.0  # states per second
BUDGET = 30.0  # seconds of timing rounds


def kappa(s: np.ndarray) -> np.ndarray:
    return 1.0 + 0.3 * np.sin(s)


def tau(s: np.ndarray) -> np.ndarray:
    return 0.3 * np.cos(s)


def build() -> Structure:
    curve = SpaceCurve.from_curvature(kappa, tau, LENGTH, samples=SAMPLES)
    lattice = Lattice.from_crease(Crease.from_curve(curve, fold_angle=DESIGN_ANGLE), WIDTH, WIDTH)
    cells = [(i, j) for i in range(BLOCK[0]) for j in range(BLOCK[1])]
    return Structure.from_cells(lattice, cells)


def one_at_a_time(structure: Structure, angles: np.ndarray) -> list[np.ndarray]:
    """Vertices (20, n, 3) of every state, one ``state()`` call each."""
    return [structure.state(a).vertices for a in angles]


def batched(structure: Structure, angles: np.ndarray, chunk: int) -> list[np.ndarray]:
    """Vertices (chunk, 20, n, 3) of every chunk of states, one ``fold_points`` call each."""
    lattice, uv = structure.lattice, structure.curves_uv
    return [lattice.fold_points(uv, angles[i : i + chunk]) for i in range(0, len(angles), chunk)]


def ivp_curve1(structure: Structure, angles: np.ndarray) -> list:
    """Curve 1 (points and frames) at every angle by solve_ivp, as a user would rebuild it."""
    curve = structure.lattice.crease.curve
    a0 = math.radians(DESIGN_ANGLE) / 2
    y0 = np.concatenate([curve.points[0], curve.frames[0].T.ravel()])
    out = []
    for angle in angles:
        a = math.radians(angle) / 2
        k_scale, t_scale = math.cos(a0) / math.cos(a), math.tan(a) / math.tan(a0)

        def rhs(s: float, y: np.ndarray, k_scale=k_scale, t_scale=t_scale) -> np.ndarray:
            k, t = k_scale * (1.0 + 0.3 * math.sin(s)), t_scale * 0.3 * math.cos(s)
            T, N, B = y[3:6], y[6:9], y[9:12]
            return np.concatenate([T, k * N, -k * T + t * B, -t * N])

        out.append(
            solve_ivp(
                rhs, (0.0, LENGTH), y0, method="DOP853", rtol=1e-12, atol=1e-12, t_eval=curve.s
            ).y
        )
    return out


def run() -> list[SummaryRow]:
    structure = build()
    curves = len(structure.curves_uv)
    angles = np.linspace(10.0, 170.0, STATES)
    ivp_angles = angles[:: STATES // IVP_STATES]
    print(
        f"fold-state throughput: {curves} curves × {SAMPLES} samples ({len(structure.cells)} "
        f"cells), {STATES} states per round"
    )
    contenders = {"state": lambda: one_at_a_time(structure, angles)}
    for c in CHUNKS:
        contenders[f"fold_points/{c}"] = lambda c=c: batched(structure, angles, c)
    contenders["solve_ivp"] = lambda: ivp_curve1(structure, ivp_angles)
    counts = {name: (IVP_STATES if name == "solve_ivp" else STATES) for name in contenders}
    warm, results = best_of_interleaved(contenders, 1)
    k = choose_repeats(sum(warm.values()), BUDGET, high=10)
    best, results = best_of_interleaved(contenders, k)
    reference = np.stack(results["state"])
    agree = max(
        float(np.abs(np.concatenate(results[name]) - reference).max())
        for name in contenders
        if name.startswith("fold_points")
    )
    rate = {name: counts[name] / t for name, t in best.items()}
    best_chunk = max((n for n in contenders if n.startswith("fold_points")), key=rate.get)
    rows = []
    for name in contenders:
        target = name in ("state", best_chunk)
        rows.append(
            (
                name,
                counts[name],
                ms(best[name]),
                ms(best[name] / counts[name]),
                f"{rate[name]:.0f}",
                f"{rate[name] / rate['solve_ivp']:.1f}",
                verdict(rate[name] >= TARGET) if target else "—",
            )
        )
    print(f"best of k = {k} interleaved rounds")
    print(
        markdown_table(
            [
                "path",
                "states",
                "round [ms]",
                "per state [ms]",
                "states/s",
                "vs solve_ivp",
                f"≥ {TARGET:g}/s",
            ],
            rows,
        )
    )
    print(f"fold_points vs state(): max |Δ vertex| = {agree:.1e}")
    return [
        SummaryRow(
            "folding",
            f"batched {best_chunk} ({curves} curves × {SAMPLES})",
            f"{rate[best_chunk]:.0f} "
            f"states/s ({rate[best_chunk] / rate['solve_ivp']:.0f}× solve_ivp)",
            f"≥ {TARGET:g}/s",
            verdict(rate[best_chunk] >= TARGET),
        ),
        SummaryRow(
            "folding",
            "one at a time, structure.state()",
            f"{rate['state']:.0f} states/s",
            f"≥ {TARGET:g}/s",
            verdict(rate["state"] >= TARGET),
        ),
        SummaryRow(
            "folding",
            "solve_ivp curve 1 only (baseline)",
            f"{rate['solve_ivp']:.0f} states/s",
            "—",
            "—",
        ),
    ]


def main() -> None:
    print("\n" + summary_table(run()))


if __name__ == "__main__":
    main()
