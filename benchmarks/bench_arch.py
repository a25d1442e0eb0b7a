"""The symmetric arch (Eq. 20) at a = 0.3: solve_symmetric_arch against solve_ivp + brentq.

Problem: κ = 1, τ = a sin(2π s / s₀); find s₀ (= κ₀ s₀) with T(s₀/2)·T(0) = 0 on the
root next to π. The exact value at a = 0.3 is 3.16571746805…

- ours: ``solve_symmetric_arch(0.3, xtol=1e-12)`` (it also finds its own bracket by a
  batched scan of 61 lengths); also at its default ``xtol = 1e-14``;
- what a user would write: the frame ODE (9 unknowns) by solve_ivp (DOP853,
  rtol = atol = 1e-12) over [0, s₀/2] inside ``brentq`` on the given bracket [3.0, 3.3],
  ``xtol = 1e-12``.

Targets: ≥ 10× faster; the two roots differ by ≤ 1e-10.
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
from scipy.optimize import brentq

from curvefold.vault import solve_symmetric_arch

A = 0.3
EXACT = 3.16571746805  # the digits known independently (the brief); 12 significant figures
BRACKET = (3.0, 3.3)
XTOL = 1e-12
SPEEDUP_TARGET = 10.0
AGREEMENT_TARGET = 1e-10
BUDGET = 20.0  # seconds of timing rounds


def condition_ivp(x: float, a: float = A) -> float:
    """T(x/2)·T(0) for κ = 1, τ = a sin(2π s / x), frame (T, N, B) from the identity."""

    def rhs(s: float, y: np.ndarray) -> np.ndarray:
        t = a * math.sin(2.0 * math.pi * s / x)
        T, N, B = y[0:3], y[3:6], y[6:9]
        return np.concatenate([N, -T + t * B, -t * N])

    sol = solve_ivp(rhs, (0.0, 0.5 * x), np.eye(3).ravel(), method="DOP853", rtol=1e-12, atol=1e-12)
    return float(sol.y[0, -1])


def user_root() -> float:
    return brentq(condition_ivp, *BRACKET, xtol=XTOL)


def run() -> list[SummaryRow]:
    contenders = {
        "ours (xtol 1e-12)": lambda: solve_symmetric_arch(A, xtol=XTOL).kappa0_s0,
        "ours (default xtol 1e-13)": lambda: solve_symmetric_arch(A).kappa0_s0,
        "solve_ivp + brentq": user_root,
    }
    warm, _ = best_of_interleaved(contenders, 1)
    k = choose_repeats(sum(warm.values()), BUDGET, high=30)
    best, roots = best_of_interleaved(contenders, k)
    user = roots["solve_ivp + brentq"]
    print(
        f"symmetric arch, a = {A}: root of T(s0/2)·T(0) = 0 near π; best of k = {k} "
        "interleaved rounds"
    )
    rows = []
    for name in contenders:
        ratio = best["solve_ivp + brentq"] / best[name]
        rows.append(
            (
                name,
                ms(best[name]),
                f"{ratio:.2f}",
                f"{roots[name]:.15f}",
                f"{roots[name] - EXACT:+.1e}",
                f"{roots[name] - user:+.1e}",
            )
        )
    print(
        markdown_table(
            [
                "solver",
                "time [ms]",
                "speed-up vs ivp",
                "κ0·s0",
                f"− {EXACT} (12 s.f.)",
                "− ivp root",
            ],
            rows,
        )
    )
    ratio = best["solve_ivp + brentq"] / best["ours (xtol 1e-12)"]
    diff = abs(roots["ours (xtol 1e-12)"] - user)
    print(
        f"speed-up {ratio:.2f}× (target ≥ {SPEEDUP_TARGET:g}×): {verdict(ratio >= SPEEDUP_TARGET)}"
    )
    print(
        f"ours − ivp (absolute) = {diff:.1e} (target ≤ {AGREEMENT_TARGET:g}): "
        f"{verdict(diff <= AGREEMENT_TARGET)}"
    )
    return [
        SummaryRow(
            "arch",
            "solve_symmetric_arch(0.3) vs solve_ivp + brentq",
            f"{ms(best['ours (xtol 1e-12)'])} "
            f"ms vs {ms(best['solve_ivp + brentq'])} ms ({ratio:.2f}×)",
            f"≥ {SPEEDUP_TARGET:g}×",
            verdict(ratio >= SPEEDUP_TARGET),
        ),
        SummaryRow(
            "arch",
            "root agreement, ours − ivp (absolute)",
            f"{diff:.1e} (κ0·s0 = {roots['ours (xtol 1e-12)']:.12f})",
            f"≤ {AGREEMENT_TARGET:g}",
            verdict(diff <= AGREEMENT_TARGET),
        ),
    ]


def main() -> None:
    print("\n" + summary_table(run()))


if __name__ == "__main__":
    main()
