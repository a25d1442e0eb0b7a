"""SpaceCurve.from_curvature against scipy's solve_ivp (DOP853) on the Frenet–Serret ODE.

Curve: κ = 1 + 0.5 sin s, τ = 0.3 cos 2s, L = 20, start frame the identity at the origin.
The contenders produce the same thing, the position and the frame T, N, B (12 unknowns)
at N + 1 uniform samples, N = 1e3 … 1e6 (N + 1 so that the grids nest and one reference
serves them all):

- ours: ``SpaceCurve.from_curvature(kappa, tau, L, samples=N + 1)``;
- solve_ivp: DOP853, rtol = atol = 1e-12, ``t_eval`` = the same samples.

Errors are measured against two references that share no code:

- fine: our integrator at 8× finer sampling than the largest N (every grid is a subset);
- DOP853: solve_ivp at rtol = atol = 1e-14 (scipy raises rtol to 100 ε ≈ 2.2e-14) at the
  1001 samples every grid contains.

Their mutual agreement is printed; a contender's error is the larger of its errors against
the two (the fine one at every sample, the DOP853 one at the common samples).

Targets: error ≤ 1e-12 at every N; ≥ 3× faster than solve_ivp at N ≤ 1e4; not slower
at N = 1e6.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
from scipy.integrate import solve_ivp

from curvefold import SpaceCurve

from _bench import SummaryRow, best_of_interleaved, choose_repeats, markdown_table, ms, summary_table, timed, verdict

LENGTH = 20.0
N_VALUES = (10**3, 10**4, 10**5, 10**6)
REFINE = 8
COMMON = 1000  # intervals of the grid every N contains
ERROR_TARGET = 1e-12
SPEEDUP_SMALL = 3.0  # ivp / ours at N ≤ 1e4
BUDGET_PER_N = 12.0  # seconds of timing rounds per N


def kappa(s: np.ndarray) -> np.ndarray:
    return 1.0 + 0.5 * np.sin(s)


def tau(s: np.ndarray) -> np.ndarray:
    return 0.3 * np.cos(2.0 * s)


def frenet_rhs(s: float, y: np.ndarray) -> np.ndarray:
    """y = (x, T, N, B): x' = T, T' = κN, N' = −κT + τB, B' = −τN."""
    k, t = 1.0 + 0.5 * math.sin(s), 0.3 * math.cos(2.0 * s)
    T, N, B = y[3:6], y[6:9], y[9:12]
    return np.concatenate([T, k * N, -k * T + t * B, -t * N])


Y0 = np.concatenate([np.zeros(3), np.eye(3).ravel()])  # x = 0, T = e1, N = e2, B = e3


def ours(samples: int) -> tuple[np.ndarray, np.ndarray]:
    c = SpaceCurve.from_curvature(kappa, tau, LENGTH, samples=samples)
    return c.points, c.frames


def ivp(s: np.ndarray, tol: float = 1e-12) -> tuple[np.ndarray, np.ndarray]:
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*rtol.*too small.*")
        sol = solve_ivp(frenet_rhs, (0.0, LENGTH), Y0, method="DOP853", rtol=tol, atol=tol, t_eval=s)
    if not sol.success:
        raise RuntimeError(f"solve_ivp failed: {sol.message}")
    return ivp_arrays(sol.y)


def ivp_arrays(y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """solve_ivp's (12, n) output as points (n, 3) and frames (n, 3, 3) with columns T, N, B."""
    return y[:3].T, np.swapaxes(y[3:].T.reshape(-1, 3, 3), -1, -2)


def max_errors(result: tuple[np.ndarray, np.ndarray], reference: tuple[np.ndarray, np.ndarray]) -> tuple[float, float]:
    """Largest absolute error in the positions and in the frame entries."""
    return float(np.abs(result[0] - reference[0]).max()), float(np.abs(result[1] - reference[1]).max())


def orthonormality_error(frames: np.ndarray) -> float:
    """max |FᵀF − I| over all frames."""
    return float(np.abs(np.swapaxes(frames, -1, -2) @ frames - np.eye(3)).max())


def run() -> list[SummaryRow]:
    n_max = max(N_VALUES)
    print(f"Frenet integrator: κ = 1 + 0.5 sin s, τ = 0.3 cos 2s, L = {LENGTH:g}; samples = N + 1")
    t_fine, fine = timed(lambda: ours(REFINE * n_max + 1))
    s_common = np.linspace(0.0, LENGTH, COMMON + 1)
    t_ref, ref_ivp = timed(lambda: ivp(s_common, tol=1e-14))
    stride = REFINE * n_max // COMMON
    agreement = max_errors((fine[0][::stride], fine[1][::stride]), ref_ivp)
    print(
        f"references: fine = ours at {REFINE * n_max + 1:,} samples ({t_fine:.1f} s); DOP853 at rtol = atol = 1e-14 "
        f"(SciPy raises rtol to 2.2e-14) at {COMMON + 1} samples ({t_ref:.2f} s)"
    )
    print(f"mutual agreement of the references: positions {agreement[0]:.2e}, frames {agreement[1]:.2e}\n")

    rows, error_rows, summary, frames_1e6 = [], [], [], None
    worst = (0.0, 0.0)
    for n in N_VALUES:
        label = f"1e{round(math.log10(n))}"
        s = np.linspace(0.0, LENGTH, n + 1)
        contenders = {"ours": lambda: ours(n + 1), "ivp": lambda: ivp(s)}
        warm, _ = best_of_interleaved(contenders, 1)
        k = choose_repeats(sum(warm.values()), BUDGET_PER_N)
        best, results = best_of_interleaved(contenders, k)
        step = REFINE * n_max // n
        ref_fine = (fine[0][::step], fine[1][::step])
        common = n // COMMON
        err, split = {}, {}
        for name, res in results.items():
            e_fine = max_errors(res, ref_fine)
            e_ivp = max_errors((res[0][::common], res[1][::common]), ref_ivp)
            err[name] = (max(e_fine[0], e_ivp[0]), max(e_fine[1], e_ivp[1]))
            split[name] = (e_fine, e_ivp)
        error_rows.append((label,) + tuple(f"{a:.1e} / {b:.1e}" for name in ("ours", "ivp") for a, b in split[name]))
        ratio = best["ivp"] / best["ours"]
        err_ok = max(err["ours"]) <= ERROR_TARGET
        speed_target = SPEEDUP_SMALL if n <= 10**4 else 1.0 if n == n_max else None
        speed_ok = None if speed_target is None else ratio >= speed_target
        rows.append(
            (
                label,
                k,
                ms(best["ours"]),
                ms(best["ivp"]),
                f"{ratio:.2f}" + ("" if speed_ok is None else f" {verdict(speed_ok)} (≥ {speed_target:g})"),
                f"{err['ours'][0]:.1e}",
                f"{err['ours'][1]:.1e}",
                f"{err['ivp'][0]:.1e}",
                f"{err['ivp'][1]:.1e}",
                verdict(err_ok),
            )
        )
        summary.append(
            SummaryRow(
                "integrator",
                f"N = {label}: from_curvature vs solve_ivp",
                f"{ms(best['ours'])} ms vs {ms(best['ivp'])} ms ({ratio:.2f}×)",
                "—" if speed_target is None else f"≥ {speed_target:g}×",
                "—" if speed_ok is None else verdict(speed_ok),
            )
        )
        worst = (max(worst[0], err["ours"][0]), max(worst[1], err["ours"][1]))
        if n == n_max:
            frames_1e6 = {name: res[1] for name, res in results.items()}
        del results
    headers = ["N", "k", "ours [ms]", "solve_ivp [ms]", "ivp/ours", "ours pos err", "ours frame err", "ivp pos err", "ivp frame err", f"ours err ≤ {ERROR_TARGET:g}"]
    print(markdown_table(headers, rows))
    print("\nerrors split by reference, position / frame (the table above shows the larger of the two):")
    print(markdown_table(["N", "ours vs fine", "ours vs DOP853", "ivp vs fine", "ivp vs DOP853"], error_rows))
    orth = {name: orthonormality_error(f) for name, f in frames_1e6.items()}
    print(f"\nframe orthonormality max|FᵀF − I| at N = 1e{round(math.log10(n_max))}: ours {orth['ours']:.1e}, solve_ivp {orth['ivp']:.1e}")
    ok = max(worst) <= ERROR_TARGET
    summary.append(SummaryRow("integrator", "max error over all N (pos, frame)", f"{worst[0]:.1e}, {worst[1]:.1e}", f"≤ {ERROR_TARGET:g}", verdict(ok)))
    summary.append(SummaryRow("integrator", "orthonormality at N = 1e6", f"{orth['ours']:.1e} (solve_ivp {orth['ivp']:.1e})", "—", "—"))
    summary.append(SummaryRow("integrator", "reference agreement (pos, frame)", f"{agreement[0]:.1e}, {agreement[1]:.1e}", "—", "—"))
    return summary


def main() -> None:
    print("\n" + summary_table(run()))


if __name__ == "__main__":
    main()
